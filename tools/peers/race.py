#!/usr/bin/python3
"""Race Kiln against Blender Cycles on the same scene: error against render time, side by side, in one run.

Needs: Debian's `blender` (Cycles 3.4), `python3-openimageio`, `python3-numpy`; a built Kiln.

    /usr/bin/python3 race.py --kiln build/release/kiln [--scene cb.json] [--spp 256] [--runs 3]
        [--ref-spp 4096] [--threads 2] [--max-bounces 8] [--work DIR] [--kiln-args "..."]
        [--filter gaussian:0.01] [--adaptive THRESHOLD [--adaptive-min-spp N]]

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
    ap.add_argument("--filter", default="gaussian:0.01", help="pixel filter of both renderers, NAME[:WIDTH]")
    ap.add_argument("--adaptive", type=float, default=0.0, help="adaptive sampling threshold of both (0: off)")
    ap.add_argument("--adaptive-min-spp", type=int, default=0, help="adaptive minimum spp of both (0: automatic)")
    a = ap.parse_args()
    fname, _, fwidth = a.filter.partition(":")
    if fname not in ("gaussian", "blackman-harris"):
        sys.exit("--filter: Cycles 3.4 has gaussian and blackman-harris with a width (its box ignores it)")
    fwidth = float(fwidth) if fwidth else (3.0 if fname == "gaussian" else 1.5)
    ftag = "%s-%g" % (fname, fwidth)
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

    def kiln_render(spp, seed, tag, adaptive=0.0):
        out = os.path.join(a.work, tag)
        stats = out + ".json"
        extra = ["--adaptive", str(adaptive), "--adaptive-min-spp", str(a.adaptive_min_spp)] if adaptive > 0 else []
        run([kiln, "render", xml, "-o", out, "--spp", str(spp), "--threads", str(a.threads), "--seed", str(seed),
             "-q", "--stats", stats, "--filter", "%s:%g" % (fname, fwidth)] + extra + shlex.split(a.kiln_args))
        cam = json.load(open(stats))["cameras"][0]
        return glob.glob(os.path.join(out, "*.exr"))[0], cam["render_seconds"], cam.get("mean_spp", spp)

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

    kref_path = os.path.join(a.work, "ref_kiln_%d_%s" % (a.ref_spp, ftag))
    cref_path = os.path.join(a.work, "ref_cycles_%d_%s.exr" % (a.ref_spp, ftag))
    if not glob.glob(os.path.join(kref_path, "*.exr")):
        print("rendering Kiln's reference at %d spp ..." % a.ref_spp, flush=True)
        kiln_render(a.ref_spp, 1000, os.path.basename(kref_path))
    if not os.path.exists(cref_path):
        print("rendering Cycles' reference at %d spp ..." % a.ref_spp, flush=True)
        cycles_render(a.ref_spp, 1000, os.path.basename(cref_path)[:-4])
    kref, cref = load(glob.glob(os.path.join(kref_path, "*.exr"))[0]), load(cref_path)
    bk, bc = blocks(kref), blocks(cref)
    m = bc.mean(axis=2) > 1e-3 * bc.mean()
    rel = np.abs(bk.mean(axis=2) - bc.mean(axis=2))[m] / bc.mean(axis=2)[m]
    print("references agree: 16-px blocks median %.4f, p95 %.4f, mean ratio Kiln/Cycles %.4f"
          % (np.median(rel), np.percentile(rel, 95), kref.mean() / cref.mean()))
    rows = []
    mode = "adaptive %g" % a.adaptive if a.adaptive > 0 else "fixed"
    print("racing at %d spp (%s), filter %s, %d threads" % (a.spp, mode, a.filter, a.threads), flush=True)
    for i in range(a.runs):
        seed = 11 + i
        tag = "%d_%s_%s_%d" % (a.spp, ftag, "a%g" % a.adaptive if a.adaptive > 0 else "f", seed)
        kp, kt, kn = kiln_render(a.spp, seed, "kiln_" + tag, a.adaptive)
        cp, ct, cn = cycles_render(a.spp, seed, "cycles_" + tag, a.adaptive)
        ki, ci = load(kp), load(cp)
        km, cm = float(((ki - kref) ** 2).mean()), float(((ci - cref) ** 2).mean())
        kx, cx = float(((ki - cref) ** 2).mean()), float(((ci - kref) ** 2).mean())
        rows.append((kt, km, ct, cm, kn, cn, kx, cx))
        print("round %d: Kiln %.2f s MSE %.3e (%.1f spp) | Cycles %.2f s MSE %.3e | efficiency "
              "Kiln/Cycles %.2f | cross MSE Kiln vs Cycles' ref %.3e, Cycles vs Kiln's ref %.3e"
              % (i + 1, kt, km, kn, ct, cm, (cm * ct) / (km * kt), kx, cx), flush=True)
    kt, km, ct, cm, kn, cn, kx, cx = (float(np.median([r[j] for r in rows])) for j in range(8))
    print("median of %d: Kiln %.2f s MSE %.3e, Cycles %.2f s MSE %.3e; time ratio Kiln/Cycles %.2f, "
          "efficiency ratio Kiln/Cycles %.2f" % (a.runs, kt, km, ct, cm, kt / ct, (cm * ct) / (km * kt)))
    if a.adaptive > 0:
        print("adaptive: Kiln's mean spp %.1f (max %d)" % (kn, a.spp))
    pixel_comparison(kref, cref, None if a.adaptive > 0 else (km, cm, a.spp / a.ref_spp))


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
