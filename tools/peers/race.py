#!/usr/bin/python3
"""Race Kiln against Blender Cycles (and pbrt-v4) on the same scene: error against render time, side by side, in
one run.

Needs: Debian's `blender` (Cycles 3.4), `python3-openimageio`, `python3-numpy`; a built Kiln; for --pbrt a pbrt-v4
binary (../shared/tools/peers/pbrt-v4.md).

    /usr/bin/python3 race.py --kiln build/release/kiln [--scene cb.json] [--spp 256] [--runs 3]
        [--ref-spp 4096] [--threads 2] [--max-bounces 8] [--work DIR] [--kiln-args "..."]
        [--filter gaussian:0.01] [--adaptive THRESHOLD [--adaptive-min-spp N]]
        [--pbrt PATH [--pbrt-light-sampler bvh]] [--kiln-alt "..."] [--no-cycles]

Kiln's copy of ../shared/tools/peers/race.py, extended with matched pixel filters, a pixel-by-pixel comparison and
adaptive sampling (tools/peers/README.md).

What it does:
  1. Takes a scene JSON (the schema of cycles_render.py; default: its built-in Cornell box, dumped once) and
     writes it as CENG795 XML with scene_to_ceng795.py (Kiln's own rules: no <Renderer>, depth = bounces + 1);
     Kiln renders it with `--strategy mis` unless --kiln-args says otherwise.
  2. Renders one reference per renderer at --ref-spp with seed 1000 (cached in --work; delete to redo). The two
     references must agree (16-px block means, median relative difference printed): if they do not, the
     renderers are not rendering the same image and the race means nothing.
  3. Renders --runs rounds at --spp, alternating Kiln and Cycles (seeds 11, 12, ...), so both see the same machine
     load, and measures each image's MSE against ITS OWN renderer's reference and the render time (Kiln:
     render_seconds of --stats; Cycles: the render call, CYCLES_RENDER_WALL_S; start-up excluded for both).
  4. Prints per round and the medians: time, MSE, efficiency 1/(MSE*time), and Kiln's efficiency / Cycles'.
     Efficiency ratio 2.0 means Kiln reaches Cycles' error in half its time.
  5. Pixel by pixel (both renderers use the same --filter, so they converge to the same image, not only to the
     same block means): the references' relative difference per pixel (median, p95 over pixels brighter than 1%
     of the mean) and a noise-aware ratio, MSE(Kiln ref - Cycles ref) / the MSE their own noise explains
     (each reference's noise is its renderer's round MSE scaled by q / (1 + q), q = spp / ref-spp; medians;
     fixed-spp races only). About 1 when the images
     agree pixel by pixel; well above 1 means a systematic difference. Also each round's MSE against the OTHER
     renderer's reference ("cross").

--filter NAME[:WIDTH] (default gaussian:0.01, i.e. pixel centres, Cycles' smallest filter): Kiln gets --filter,
Cycles --filter/--filter-width; Cycles 3.4 offers gaussian and blackman-harris (its box ignores the width).
Kiln's gaussian subtracts its value at the radius (pbrt-v4) and Cycles' does not: at 0.01 px irrelevant, at 1.5 px
a ~1% difference at the tails; blackman-harris is the same function in both.

--pbrt PATH: pbrt-v4 races too, the same way: the scene written by scene_to_pbrt.py (pixel centres, maxdepth =
bounces + 1, its light sampler --pbrt-light-sampler), its own reference at --ref-spp with seed 1000, the rounds'
seeds, its render time the one its progress bar reports at the end of "Rendering" (parsing and building excluded).
Fixed-spp races with the default filter only. Its reference is compared with Kiln's by 16-px blocks (pbrt-v4 is
spectral, so a few percent apart where colours are saturated).

--kiln-alt "ARGS": a second Kiln entrant with these arguments instead of --kiln-args (e.g. "--strategy mis
--light-sampler power"), raced in the same rounds against Kiln's reference (both converge to the same image), so
the efficiency ratio of the two Kiln variants is taken in one run. --no-cycles leaves Cycles out.

--adaptive T: both renderers sample adaptively with noise threshold T (Kiln --adaptive T, Cycles
use_adaptive_sampling with adaptive_threshold T), --spp the maximum, the same minimum (--adaptive-min-spp, 0 =
Cycles' automatic rule, which Kiln follows); the references stay non-adaptive. Kiln's mean spp is printed; Cycles'
is not exposed (its Debug Sample Count pass reads 1.0 in every pixel under adaptive sampling).
"""
import argparse, glob, json, os, re, shlex, subprocess, sys
import numpy as np
import OpenImageIO as oiio

HERE = os.path.dirname(os.path.abspath(__file__))


def load(path):
    px = np.asarray(oiio.ImageBuf(path).get_pixels(oiio.FLOAT), dtype=np.float64)
    return px[:, :, :3]


def blocks(a, b=16):
    h, w = a.shape[0] // b * b, a.shape[1] // b * b
    return a[:h, :w].reshape(h // b, b, w // b, b, 3).mean(axis=(1, 3))


def run(cmd, log=None):
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if log:
        open(log, "w").write(r.stdout)
    if r.returncode != 0:
        sys.exit("failed (%d): %s\n%s" % (r.returncode, " ".join(cmd), r.stdout[-2000:]))
    return r.stdout


def block_agreement(ref, other):
    """16-px block means of two references: median and p95 relative difference, mean ratio ref/other."""
    b1, b2 = blocks(ref).mean(axis=2), blocks(other).mean(axis=2)
    m = b2 > 1e-3 * b2.mean()
    rel = np.abs(b1 - b2)[m] / b2[m]
    return np.median(rel), np.percentile(rel, 95), ref.mean() / other.mean()


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--kiln", required=True)
    ap.add_argument("--scene", help="scene JSON (default: Cycles' built-in Cornell box)")
    ap.add_argument("--spp", type=int, default=256)
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--ref-spp", type=int, default=4096)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--max-bounces", type=int, default=8, help="Cycles' count; Kiln gets depth = this + 1")
    ap.add_argument("--work", default="race-work")
    ap.add_argument("--kiln-args", default="--strategy mis")
    ap.add_argument("--kiln-alt", help="a second Kiln entrant with these arguments instead of --kiln-args")
    ap.add_argument("--no-cycles", action="store_true", help="leave Cycles out of the race")
    ap.add_argument("--pbrt", help="pbrt-v4 binary: pbrt-v4 races too")
    ap.add_argument("--pbrt-light-sampler", default="bvh", choices=["bvh", "power", "uniform"])
    ap.add_argument("--filter", default="gaussian:0.01", help="pixel filter of both renderers, NAME[:WIDTH]")
    ap.add_argument("--adaptive", type=float, default=0.0, help="adaptive sampling threshold of both (0: off)")
    ap.add_argument("--adaptive-min-spp", type=int, default=0, help="adaptive minimum spp of both (0: automatic)")
    a = ap.parse_args()
    fname, _, fwidth = a.filter.partition(":")
    if fname not in ("gaussian", "blackman-harris"):
        sys.exit("--filter: Cycles 3.4 has gaussian and blackman-harris with a width (its box ignores it)")
    fwidth = float(fwidth) if fwidth else (3.0 if fname == "gaussian" else 1.5)
    ftag = "%s-%g" % (fname, fwidth)
    if a.pbrt and (a.adaptive > 0 or a.filter != "gaussian:0.01"):
        sys.exit("--pbrt: fixed-spp races with the default filter (pixel centres) only")
    os.makedirs(a.work, exist_ok=True)
    kiln = os.path.abspath(a.kiln)
    cyc = ["blender", "-b", "--factory-startup", "-t", str(a.threads), "--python",
           os.path.join(HERE, "cycles_render.py"), "--"]
    scene = a.scene or os.path.join(a.work, "cornell.json")
    src = [] if a.scene else ["--cornell"]
    if not a.scene and not os.path.exists(scene):
        run(cyc + ["--cornell", "--dump-scene", scene, "--dump-only"])
    if a.scene:
        src = ["--scene", os.path.abspath(a.scene)]
    xml = os.path.join(a.work, "scene.xml")
    run([sys.executable, os.path.join(HERE, "scene_to_ceng795.py"), scene, xml, "--mode", "kiln",
         "--max-bounces", str(a.max_bounces)])
    cam = json.load(open(scene))["camera"]
    res = ["--width", str(cam["width"]), "--height", str(cam["height"])]
    pbrt_scene = os.path.join(a.work, "scene_%s.pbrt" % a.pbrt_light_sampler)
    if a.pbrt:
        run([sys.executable, os.path.join(HERE, "scene_to_pbrt.py"), scene, pbrt_scene, "--max-bounces",
             str(a.max_bounces), "--light-sampler", a.pbrt_light_sampler])

    def kiln_renderer(kiln_args):
        def render(spp, seed, tag, adaptive=0.0):
            out = os.path.join(a.work, tag)
            stats = out + ".json"
            extra = ["--adaptive", str(adaptive), "--adaptive-min-spp", str(a.adaptive_min_spp)] if adaptive > 0 else []
            run([kiln, "render", xml, "-o", out, "--spp", str(spp), "--threads", str(a.threads), "--seed", str(seed),
                 "-q", "--stats", stats, "--filter", "%s:%g" % (fname, fwidth)] + extra + shlex.split(kiln_args))
            cam = json.load(open(stats))["cameras"][0]
            return glob.glob(os.path.join(out, "*.exr"))[0], cam["render_seconds"], cam.get("mean_spp", spp)
        return render

    def cycles_render(spp, seed, tag, adaptive=0.0):
        out = os.path.join(a.work, tag + ".exr")
        extra = ["--adaptive-threshold", str(adaptive), "--adaptive-min-samples", str(a.adaptive_min_spp)] \
            if adaptive > 0 else []
        log = run(cyc + src + res + ["--spp", str(spp), "--max-bounces", str(a.max_bounces), "--seed", str(seed),
                                     "--threads", str(a.threads), "--out", out, "--filter", fname,
                                     "--filter-width", str(fwidth)] + extra)
        # Cycles does not expose its per-pixel sample counts (its Debug Sample Count pass is normalised by each
        # pixel's own count under adaptive sampling: 1.0 everywhere).
        return out, float(re.search(r"CYCLES_RENDER_WALL_S \d+ ([\d.]+)", log).group(1)), float("nan")

    def pbrt_render(spp, seed, tag, adaptive=0.0):
        out = os.path.join(a.work, tag + ".exr")
        log = run([a.pbrt, "--nthreads", str(a.threads), "--seed", str(seed), "--spp", str(spp), "--outfile", out,
                   pbrt_scene])
        # The progress bar ends with the render's elapsed time: "Rendering: [+++...] (19.9s)".
        times = re.findall(r"Rendering: \[[+ ]*\]\s+\(([\d.]+)s\)", log)
        if not times:
            sys.exit("pbrt-v4 printed no render time:\n" + log[-2000:])
        return out, float(times[-1]), spp

    # name, render(), the tag of its reference, whose reference it is measured against
    kiln_ref_tag = "ref_kiln_%d_%s" % (a.ref_spp, ftag)
    entrants = [("Kiln", kiln_renderer(a.kiln_args), kiln_ref_tag)]
    if a.kiln_alt:
        entrants.append(("Kiln[%s]" % a.kiln_alt, kiln_renderer(a.kiln_alt), kiln_ref_tag))
    if not a.no_cycles:
        entrants.append(("Cycles", cycles_render, "ref_cycles_%d_%s" % (a.ref_spp, ftag)))
    if a.pbrt:
        entrants.append(("pbrt-v4", pbrt_render, "ref_pbrt_%s_%d" % (a.pbrt_light_sampler, a.ref_spp)))

    refs = {}
    for name, render, tag in entrants:
        if tag in refs:
            continue
        found = glob.glob(os.path.join(a.work, tag, "*.exr")) + glob.glob(os.path.join(a.work, tag + ".exr"))
        if not found:
            print("rendering %s's reference at %d spp ..." % (name, a.ref_spp), flush=True)
            found = [render(a.ref_spp, 1000, tag)[0]]
        refs[tag] = load(found[0])
    kref = refs[kiln_ref_tag]
    for name, _, tag in entrants:
        if tag != kiln_ref_tag:
            med_rel, p95_rel, ratio = block_agreement(kref, refs[tag])
            print("references agree, Kiln against %s: 16-px blocks median %.4f, p95 %.4f, mean ratio Kiln/%s %.4f"
                  % (name, med_rel, p95_rel, name, ratio))

    rows = []
    mode = "adaptive %g" % a.adaptive if a.adaptive > 0 else "fixed"
    print("racing at %d spp (%s), filter %s, %d threads: %s" % (a.spp, mode, a.filter, a.threads,
                                                               ", ".join(e[0] for e in entrants)), flush=True)
    for i in range(a.runs):
        seed = 11 + i
        tag = "%d_%s_%s_%d" % (a.spp, ftag, "a%g" % a.adaptive if a.adaptive > 0 else "f", seed)
        row = []
        for k, (name, render, ref_tag) in enumerate(entrants):
            path, t, n = render(a.spp, seed, "%s%d_%s" % (name.split("[")[0].lower(), k, tag), a.adaptive)
            row.append((t, float(((load(path) - refs[ref_tag]) ** 2).mean()), n, path))
        rows.append(row)
        print("round %d: " % (i + 1) + " | ".join("%s %.2f s MSE %.3e" % (e[0], r[0], r[1])
                                                   for e, r in zip(entrants, row)), flush=True)
        if not a.no_cycles:
            ci = [k for k, e in enumerate(entrants) if e[0] == "Cycles"][0]
            kx = float(((load(row[0][3]) - refs[entrants[ci][2]]) ** 2).mean())
            cx = float(((load(row[ci][3]) - kref) ** 2).mean())
            print("         cross MSE Kiln vs Cycles' ref %.3e, Cycles vs Kiln's ref %.3e" % (kx, cx), flush=True)
    med = [(float(np.median([r[k][0] for r in rows])), float(np.median([r[k][1] for r in rows])),
            float(np.median([r[k][2] for r in rows]))) for k in range(len(entrants))]
    kt, km = med[0][0], med[0][1]
    print("median of %d rounds:" % a.runs)
    for (name, _, _), (t, m, _) in zip(entrants, med):
        line = "  %-40s %7.2f s  MSE %.3e  efficiency %.3g" % (name, t, m, 1.0 / (m * t))
        if name != "Kiln":
            line += "  | Kiln's efficiency / %s's %.2f (time ratio %.2f)" % (name, (m * t) / (km * kt), kt / t)
        print(line)
    if a.adaptive > 0:
        print("adaptive: Kiln's mean spp %.1f (max %d)" % (med[0][2], a.spp))
    if not a.no_cycles:
        ci = [k for k, e in enumerate(entrants) if e[0] == "Cycles"][0]
        pixel_comparison(kref, refs[entrants[ci][2]],
                         None if a.adaptive > 0 else (km, med[ci][1], a.spp / a.ref_spp))


def pixel_comparison(kref, cref, noise_from):
    """Both references rendered with the same pixel filter: compare them pixel by pixel."""
    lum = lambda im: im @ np.array([0.2126, 0.7152, 0.0722])
    lk, lc = lum(kref), lum(cref)
    m = lc > 0.01 * lc.mean()
    rel = np.abs(lk - lc)[m] / lc[m]
    diff_mse = float(((kref - cref) ** 2).mean())
    print("pixel by pixel (same filter): |Kiln - Cycles| / Cycles over %d pixels: median %.4f, p95 %.4f, "
          "mean ratio %.4f; MSE(Kiln ref - Cycles ref) %.3e"
          % (m.sum(), np.median(rel), np.percentile(rel, 95), kref.mean() / cref.mean(), diff_mse), end="")
    if noise_from:
        # A round's MSE against its own reference is the round's noise v plus the reference's, v * q with
        # q = spp / ref-spp (independent samples), so the reference's own noise is MSE * q / (1 + q).
        km, cm, q = noise_from
        noise = (km + cm) * q / (1.0 + q)
        print(" vs %.3e from the references' noise: ratio %.2f" % (noise, diff_mse / noise), end="")
    print()


if __name__ == "__main__":
    main()
