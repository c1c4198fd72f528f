#!/usr/bin/env python3
"""What Kiln would still not render in the pbrt-v4 scene collection (mmp/pbrt-v4-scenes), scene by scene.

Usage: tools/pbrt_survey.py COLLECTION [--kiln build/release/kiln] [--keep DIR]

COLLECTION is a checkout of mmp/pbrt-v4-scenes or its bare git directory (files are read from HEAD). For each
scene file in SCENES the tool copies the scene and the text files it Includes/Imports into a temporary tree, puts a
stand-in beside every data file the text names that the collection does not hold (large PLY meshes and images are
often absent from a snapshot: a one-triangle PLY, a 4x4 black image made by oiiotool, a flat .spd spectrum, an empty
file otherwise), and runs `kiln info` on it. What the loader reports as "not rendered yet" is what Kiln would still
not render; a scene renders as intended when it loads and nothing is reported. An Included text file the collection
does not hold is left absent (`kiln info --allow-missing` leaves it out, with the parameters that go on after the
Include, which belong to its last directive) and named in the table, and so is a stand-in kiln cannot read (a volume
grid): such a scene is "incomplete" unless something is reported. Prints a Markdown table and, below it, how many scenes each
feature keeps from rendering as intended.
"""
import argparse
import collections
import gzip
import os
import re
import shutil
import subprocess
import sys
import tempfile

# The scene files a user renders: every lighting, material or camera set-up of the collection once. Views, frames
# and parameter sweeps of one set-up (kroken camera-2..7, landscape view-1..4, watercolor camera-2..18, the other
# bistro, sanmiguel, transparent-machines and zero-day views, dambreak1, sssdragon dragon_50/250, the other hair
# variants) use the same directives and are represented by one file.
SCENES = [
    "barcelona-pavilion/pavilion-day.pbrt", "barcelona-pavilion/pavilion-night.pbrt", "bistro/bistro_cafe.pbrt",
    "bmw-m6/bmw-m6.pbrt", "bunny-cloud/bunny-cloud.pbrt", "bunny-fur/bunny-fur.pbrt", "clouds/clouds.pbrt",
    "contemporary-bathroom/contemporary-bathroom.pbrt", "crown/crown.pbrt", "dambreak/dambreak0.pbrt",
    "disney-cloud/disney-cloud.pbrt", "explosion/explosion.pbrt", "ganesha/ganesha.pbrt",
    "hair/hair-blonde-3-bounces.pbrt", "head/head.pbrt", "killeroos/killeroo-simple.pbrt",
    "killeroos/killeroo-gold.pbrt", "killeroos/killeroo-coated-gold.pbrt", "killeroos/killeroo-moving.pbrt",
    "kroken/camera-1.pbrt", "landscape/view-0.pbrt", "lte-orb/lte-orb-silver.pbrt", "lte-orb/lte-orb-rough-glass.pbrt",
    "lte-orb/lte-orb-blue-agat-spec.pbrt", "lte-orb/lte-orb-simple-ball.pbrt", "pbrt-book/book.pbrt",
    "sanmiguel/sanmiguel-courtyard.pbrt", "sanmiguel/sanmiguel-realistic-courtyard.pbrt", "smoke-plume/plume.pbrt",
    "sportscar/sportscar-sky.pbrt", "sportscar/sportscar-area-lights.pbrt", "sssdragon/dragon_10.pbrt",
    "transparent-machines/frame812.pbrt", "villa/villa-daylight.pbrt", "villa/villa-lights-on.pbrt",
    "watercolor/camera-1.pbrt", "zero-day/frame120.pbrt",
]

TOKEN = re.compile(r'"[^"]*"|#[^\n]*|[^\s"#\[\]]+')
# kiln info's features that --allow-missing makes of absent files (the files themselves, and the named materials and
# media they define): the table names the absent files itself.
ALLOW_MISSING_MARK = "(left out: --allow-missing)"

# Extensions of the data files a scene names (after a trailing .gz): stand-ins are made for the absent ones.
IMAGE_EXTS = {"exr", "png", "jpg", "jpeg", "tga", "pfm", "hdr", "tif", "tiff", "bmp"}
DATA_EXTS = IMAGE_EXTS | {"ply", "nvdb", "vdb", "spd", "dat", "bsdf", "ptx", "txt", "csv"}
SPD_STANDIN = b"300 1\n800 1\n"
PLY_STANDIN = (b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
               b"element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")


class Collection:
    """Reads files of the collection from a checkout or from a bare git directory's HEAD."""

    def __init__(self, path):
        self.path = path
        self.git = os.path.isfile(os.path.join(path, "HEAD")) and os.path.isdir(os.path.join(path, "objects"))

    def read(self, rel):
        """The file's bytes, or None when the collection does not hold it."""
        if not self.git:
            full = os.path.join(self.path, rel)
            return open(full, "rb").read() if os.path.isfile(full) else None
        r = subprocess.run(["git", "--git-dir", self.path, "cat-file", "blob", "HEAD:" + rel],
                           stdout=subprocess.PIPE, stderr=subprocess.DEVNULL)
        return r.stdout if r.returncode == 0 else None


def text_of(data, name):
    return (gzip.decompress(data) if name.endswith(".gz") else data).decode("utf-8", "replace")


def references(text):
    """(Include/Import targets, data file names) named in a pbrt file's text."""
    tokens = [t for t in TOKEN.findall(text) if not t.startswith("#")]
    includes, data = [], []
    for prev, tok in zip([""] + tokens, tokens):
        if not tok.startswith('"'):
            continue
        name = tok[1:-1]
        if prev in ("Include", "Import"):
            includes.append(name)
        elif "." in name and name.rsplit(".gz", 1)[0].rsplit(".", 1)[-1].lower() in DATA_EXTS:
            data.append(name)
    return includes, data


class StandIns:
    """One stand-in per data file extension, made once."""

    def __init__(self, folder):
        self.folder = folder
        self.made = {}

    def bytes_for(self, name):
        base = name[:-3] if name.endswith(".gz") else name
        ext = base.rsplit(".", 1)[-1].lower()
        if ext not in self.made:
            self.made[ext] = self.make(ext)
        return gzip.compress(self.made[ext]) if name.endswith(".gz") else self.made[ext]

    def make(self, ext):
        if ext == "ply":
            return PLY_STANDIN
        if ext == "spd":
            return SPD_STANDIN
        if ext in IMAGE_EXTS:
            out = os.path.join(self.folder, "standin." + ext)
            subprocess.run(["oiiotool", "--create", "4x4", "3", "-o", out], stdout=subprocess.DEVNULL,
                           stderr=subprocess.DEVNULL)
            if os.path.isfile(out):
                return open(out, "rb").read()
        return b""


def extract(collection, scene, tree, standins):
    """Writes the scene, its Included text files and its data files (or stand-ins) under tree. Returns the Included
    text files the collection does not hold (written empty) and the data files given a stand-in."""
    root = os.path.dirname(scene)
    absent, standin_files, seen, todo = [], [], set(), [scene]
    while todo:
        rel = todo.pop()
        if rel in seen:
            continue
        seen.add(rel)
        data = collection.read(rel)
        if data is None:  # left absent: `kiln info --allow-missing` leaves it out with its trailing parameters
            absent.append(rel)
            continue
        write(tree, rel, data)
        includes, files = references(text_of(data, rel))
        todo += [os.path.normpath(os.path.join(root, name)) for name in includes]
        for name in files:
            target = os.path.normpath(os.path.join(root, name))
            if target in seen:
                continue
            seen.add(target)
            content = collection.read(target)
            if content is None:
                content = standins.bytes_for(name)
                standin_files.append(target)
            write(tree, target, content)
    return absent, standin_files


def write(tree, rel, data):
    path = os.path.join(tree, rel)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb") as f:
        f.write(data)


def survey(kiln, path):
    """(loaded, first error line, features not rendered) from `kiln info`."""
    try:
        r = subprocess.run([kiln, "info", "--allow-missing", path], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                           timeout=900)
    except subprocess.TimeoutExpired:
        return False, "kiln info took more than 15 minutes", []
    if r.returncode != 0:
        lines = (r.stderr or r.stdout).strip().splitlines()
        return False, (lines[0] if lines else "exit %d" % r.returncode).replace("kiln: error: ", ""), []
    features = [re.sub(r" \(\d+ directives?\)$", "", line[len("not rendered yet: "):])
                for line in r.stdout.splitlines() if line.startswith("not rendered yet: ")]
    features = [f for f in features if ALLOW_MISSING_MARK not in f]  # counted as absent files
    return True, "", features


def cell(text):
    return text.replace("|", "\\|")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("collection", help="checkout or bare git directory of mmp/pbrt-v4-scenes")
    ap.add_argument("--kiln", default="build/release/kiln")
    ap.add_argument("--keep", help="extract into this folder (kept) instead of a temporary one")
    args = ap.parse_args()
    collection = Collection(args.collection)
    work = args.keep or tempfile.mkdtemp(prefix="pbrt_survey.")
    standins = StandIns(work)
    counts, verdicts = collections.Counter(), collections.Counter()
    print("| scene file | loads | what Kiln would still not render | verdict |")
    print("|---|---|---|---|")
    for scene in SCENES:
        if collection.read(scene) is None:
            verdicts["not surveyed"] += 1
            print("| %s | the collection at hand does not hold it | — | not surveyed |" % scene)
            continue
        tree = os.path.join(work, "tree")
        shutil.rmtree(tree, ignore_errors=True)
        absent, standin_files = extract(collection, scene, tree, standins)
        loaded, error, features = survey(args.kiln, os.path.join(tree, scene))
        if not loaded and any(f in error for f in standin_files):
            absent.append(next(f for f in standin_files if f in error))  # kiln cannot read the stand-in
        loads = ("yes" if loaded else "no") + (": " + error.replace(tree + "/", "") if error else "")
        if absent:
            names = [os.path.relpath(a, os.path.dirname(scene)) for a in absent]
            loads += " (%d file%s absent, left out: %s)" % (
                len(names), "" if len(names) == 1 else "s", ", ".join(names[:3]) + (", ..." if len(names) > 3 else ""))
        unreadable_standin = not loaded and absent and absent[-1] in standin_files
        if features or not (loaded or unreadable_standin):
            verdict = "not as intended"
        else:
            verdict = "incomplete (absent files)" if absent else "renders as intended"
        verdicts[verdict] += 1
        counts.update(features)
        print("| %s | %s | %s | %s |" % (scene, cell(loads), cell(", ".join(features)) or "—", verdict))
        sys.stdout.flush()
    print("\nOf %d scene files: %s. Scenes kept from rendering as intended, by feature:\n" % (
        len(SCENES), ", ".join("%d %s" % (n, v) for v, n in verdicts.most_common())))
    for feature, n in counts.most_common():
        print("- %s: %d" % (feature, n))
    if not args.keep:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
