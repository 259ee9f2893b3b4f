#!/usr/bin/env python3
"""Time to a clean image: how long rt and Mitsuba 3 each take to reach a relative RMSE of
2 %, 1 % and 0.5 % (and SSIM 0.99) on the same scene, rendered alike.

    python3 scripts/equal_error.py --rt rt=target/release/rt [--rt old=OLD_RT] \\
        [--variant cuda_ad_rgb] [--size 128] [--max-spp 4096] SCENE.toml...

Each SCENE is an rt scene that Mitsuba can render alike (tests/refs/scenes/*.toml, say);
Mitsuba sees it through rt's own translation (`rt bench mitsuba-scene`, the first --rt
binary's), the one `rt bench compare` and the tests' references use: the same path length
(`max_depth` = rt's bounces + 1), Russian roulette from the same vertex and by the same
rule, the same box pixel filter, emitters that emit from both faces as rt's do (see
crates/rt-bench/src/mitsuba_scene.rs).

For each renderer (each rt binary given, and Mitsuba with each of its samplers) the scene
is rendered at 1, 2, 4, ... samples per pixel, twice with other seeds, after a warm-up;
the error of each image is its relative RMSE (RMSE over the mean) against that renderer's
own converged image, with that image's own noise (measured from its two halves) taken
off, and the time is what the render took (rt: its render loop, as `--progress json`
reports it; Mitsuba: `mi.render` and a sync, warm). SSIM is against the converged image
as it is. The time to each
error is interpolated in log-log between the sample counts around it. Before any ratio is
printed, rt's converged image and Mitsuba's are compared: their difference, as a relative
RMSE with both references' own noise taken off (measured from each one's two halves), is
the bias between the renderers. A target gets a ratio only where that bias, at two standard
errors of its estimate, is at most a third of it: errors add in quadrature, so against the other renderer's image the time to
that target would change by at most 10 %. The worst 8×8 block, in standard errors of the
noise, is printed beside it to say where a disagreement lies.

Writes a markdown table on stdout and the raw points as JSON (--json).
"""

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "crates", "rt-bench", "src"))

import drjit as dr  # noqa: E402
import mitsuba as mi  # noqa: E402
from mitsuba_scene import scene_dict  # noqa: E402

SAMPLERS = ("independent", "stratified", "multijitter", "orthogonal", "ldsampler")
TARGETS = (0.02, 0.01, 0.005)
BLOCK = 8
# A target is compared only where the bias between the converged images is at most this
# fraction of it (at a third, the time to the target would change by at most 10 %).
BIAS_FRACTION = 1.0 / 3.0


def read_exr(path):
    return np.array(mi.Bitmap(path).convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.Float32), dtype=np.float64)


def rmse(image, reference, reference_noise):
    """Relative RMSE against a converged image, its own noise taken off: each renderer's
    reference is as noisy as its sampler leaves it, and that must not count against it."""
    excess = float(np.mean((image - reference) ** 2)) - float(np.mean(reference_noise**2))
    return math.sqrt(max(excess, 1e-30)) / float(np.mean(reference))


def ssim(a, b):
    """Mean SSIM of luminance over 8x8 windows (display-independent, on linear values
    normalised by the reference's mean)."""
    la, lb = (x @ np.array([0.2126, 0.7152, 0.0722]) for x in (a, b))
    scale = float(np.mean(lb)) or 1.0
    la, lb = la / scale, lb / scale
    c1, c2 = 0.01**2, 0.03**2
    h, w = la.shape
    values = []
    for y in range(0, h - BLOCK + 1, BLOCK // 2):
        for x in range(0, w - BLOCK + 1, BLOCK // 2):
            pa, pb = la[y : y + BLOCK, x : x + BLOCK], lb[y : y + BLOCK, x : x + BLOCK]
            ma, mb = pa.mean(), pb.mean()
            va, vb, cov = pa.var(), pb.var(), ((pa - ma) * (pb - mb)).mean()
            values.append(((2 * ma * mb + c1) * (2 * cov + c2)) / ((ma * ma + mb * mb + c1) * (va + vb + c2)))
    return float(np.mean(values))


def spp_series(max_spp):
    spp, out = 1, []
    while spp <= max_spp:
        out.append(spp)
        spp *= 2
    return out


class Rt:
    def __init__(self, label, binary, scene, size, folder):
        self.label, self.binary, self.scene, self.size, self.folder = label, binary, scene, size, folder

    def render(self, spp, seed):
        out = os.path.join(self.folder, f"{self.label}-{spp}-{seed}.exr")
        command = [self.binary, "render", self.scene, "-o", out, "--spp", str(spp), "--seed", str(seed),
                   "--size", f"{self.size}x{self.size}", "--progress", "json"]
        result = subprocess.run(command, capture_output=True, text=True)
        if result.returncode != 0:
            raise SystemExit(f"{self.label}: {result.stderr[-2000:]}")
        done = [json.loads(l) for l in result.stderr.splitlines() if '"done"' in l][-1]
        return read_exr(out), done["seconds"]


class Mitsuba:
    def __init__(self, sampler, scene_dict):
        self.label = f"mitsuba/{sampler}"
        self.sampler = sampler
        self.scene_dict = scene_dict
        self.loaded = {}

    def scene(self, spp):
        if spp not in self.loaded:
            d = dict(self.scene_dict)
            sensor = dict(d["sensor"])
            sampler = {"type": self.sampler, "sample_count": spp}
            if self.sampler in ("stratified", "multijitter", "orthogonal"):
                sampler["jitter"] = True
            sensor["sampler"] = sampler
            d["sensor"] = sensor
            self.loaded[spp] = mi.load_dict(d)
        return self.loaded[spp]

    def render(self, spp, seed):
        scene = self.scene(spp)
        dr.eval(mi.render(scene, spp=spp, seed=1000 + seed))  # warm: kernels compiled for this size
        dr.sync_thread()
        start = time.perf_counter()
        image = mi.render(scene, spp=spp, seed=seed)
        dr.eval(image)
        dr.sync_thread()
        return np.array(image, dtype=np.float64)[:, :, :3], time.perf_counter() - start


def mitsuba_scene(binary, scene_path, size, folder):
    """rt's translation of the scene (`rt bench mitsuba-scene`, the one `rt bench compare`
    and the tests' references render) at `size` × `size`."""
    out = os.path.join(folder, "mitsuba-" + os.path.splitext(os.path.basename(scene_path))[0])
    command = [binary, "bench", "mitsuba-scene", scene_path, "-o", out, "--size", f"{size}x{size}"]
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        raise SystemExit(f"translating {scene_path}: {result.stderr[-2000:]}")
    with open(os.path.join(out, "scene.json")) as f:
        return scene_dict(json.load(f))


def bias(a, b, noise_a, noise_b):
    """The relative RMSE between two converged images with their own noise taken off, and
    its bound at two standard errors of that estimate (the noise is itself measured)."""
    excess = (a - b) ** 2 - noise_a**2 - noise_b**2
    mean, error = float(np.mean(excess)), float(np.std(excess)) / math.sqrt(excess.size)
    scale = float(np.mean(b))
    return math.sqrt(max(mean, 0.0)) / scale, math.sqrt(max(mean + 2.0 * error, 0.0)) / scale


def worst_block(a, b, noise_a, noise_b):
    """The worst 8x8 block and colour channel: (|mean difference| in standard errors, y, x)."""
    h, w, _ = a.shape
    worst = (0.0, 0, 0)
    for y in range(0, h - BLOCK + 1, BLOCK):
        for x in range(0, w - BLOCK + 1, BLOCK):
            sl = (slice(y, y + BLOCK), slice(x, x + BLOCK))
            diff = a[sl].mean(axis=(0, 1)) - b[sl].mean(axis=(0, 1))
            sigma = np.sqrt((noise_a[sl] ** 2).mean(axis=(0, 1)) + (noise_b[sl] ** 2).mean(axis=(0, 1))) / BLOCK
            worst = max(worst, (float(np.max(np.abs(diff) / np.maximum(sigma, 1e-9))), y, x))
    return worst


def curve(renderer, reference, noise, series, seeds):
    points = []
    for spp in series:
        for seed in seeds:
            image, seconds = renderer.render(spp, seed)
            points.append({"spp": spp, "seconds": seconds, "rmse": rmse(image, reference, noise), "ssim": ssim(image, reference)})
    return points


def time_to(points, target, key="rmse", better=lambda v, t: v <= t):
    """Seconds to reach `target`, interpolated in log-log between the mean points around it."""
    by_spp = {}
    for p in points:
        by_spp.setdefault(p["spp"], []).append(p)
    means = [(np.mean([p["seconds"] for p in ps]), np.mean([p[key] for p in ps])) for _, ps in sorted(by_spp.items())]
    for (t0, e0), (t1, e1) in zip(means, means[1:]):
        if not better(e0, target) and better(e1, target):
            if key == "ssim":
                f = (target - e0) / (e1 - e0)
            else:
                f = (math.log(e0) - math.log(target)) / (math.log(e0) - math.log(e1))
            return math.exp(math.log(t0) + f * (math.log(t1) - math.log(t0)))
    return 0.0 if means and better(means[0][1], target) else None


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("scenes", nargs="+")
    ap.add_argument("--rt", action="append", default=[], help="LABEL=BINARY, repeatable")
    ap.add_argument("--variant", default="cuda_ad_rgb")
    ap.add_argument("--samplers", default=",".join(SAMPLERS))
    ap.add_argument("--size", type=int, default=128)
    ap.add_argument("--max-spp", type=int, default=4096)
    ap.add_argument("--reference-spp", type=int, default=65536)
    ap.add_argument("--json")
    args = ap.parse_args()
    mi.set_variant(args.variant)
    folder = tempfile.mkdtemp(prefix="rt-equal-error-")
    results = []
    for scene_path in args.scenes:
        name = os.path.splitext(os.path.basename(scene_path))[0]
        rts = [Rt(*spec.split("=", 1), scene_path, args.size, folder) for spec in args.rt]
        md = mitsuba_scene(rts[0].binary, scene_path, args.size, folder)
        refs = {}
        # rt's reference: its first binary, two halves for its noise.
        halves = [rts[0].render(args.reference_spp // 2, 900 + s)[0] for s in (1, 2)]
        refs["rt"] = (halves[0] + halves[1]) / 2
        rt_noise = np.abs(halves[0] - halves[1]) / 2
        mref = Mitsuba("independent", md)
        mhalves = [mref.render(args.reference_spp // 2, 900 + s)[0] for s in (1, 2)]
        refs["mitsuba"] = (mhalves[0] + mhalves[1]) / 2
        mi_noise = np.abs(mhalves[0] - mhalves[1]) / 2
        between, bound = bias(refs["rt"], refs["mitsuba"], rt_noise, mi_noise)
        z, y, x = worst_block(refs["rt"], refs["mitsuba"], rt_noise, mi_noise)
        ratio = refs["rt"].mean(axis=(0, 1)) / refs["mitsuba"].mean(axis=(0, 1))
        print(f"{name}: bias between the converged images {100 * between:.3f} % (at most {100 * bound:.3f} % "
              f"at 2 sigma; worst block {z:.1f} sigma "
              f"at ({x}, {y}); rt/Mitsuba mean per channel {ratio.round(4).tolist()})", file=sys.stderr, flush=True)
        series = spp_series(args.max_spp)
        entry = {"scene": name, "bias": between, "bias_bound": bound, "worst_block_sigma": z, "worst_block_at": [x, y],
                 "mean_ratio": ratio.tolist(), "renderers": {}}
        for r in rts:
            entry["renderers"][r.label] = curve(r, refs["rt"], rt_noise, series, (1, 2))
        for sampler in args.samplers.split(","):
            entry["renderers"][f"mitsuba/{sampler}"] = curve(Mitsuba(sampler, md), refs["mitsuba"], mi_noise, series, (1, 2))
        results.append(entry)
    report(results)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(results, f, indent=1)


def comparable(entry, target):
    """Whether the converged images agree well enough to compare times to `target`."""
    return entry["bias_bound"] <= BIAS_FRACTION * target


def report(results):
    for entry in results:
        print(f"\n### {entry['scene']} (bias between the converged images {100 * entry['bias']:.3f} %, "
              f"at most {100 * entry['bias_bound']:.3f} %; worst block {entry['worst_block_sigma']:.1f} σ)\n")
        print("| renderer | to 2 % | to 1 % | to 0.5 % | to SSIM 0.99 | s per spp |")
        print("|---|---:|---:|---:|---:|---:|")
        fmt = lambda t: "—" if t is None else f"{t * 1e3:.1f} ms"
        ssim_at = lambda p: time_to(p, 0.99, key="ssim", better=lambda v, t: v >= t)
        for label, points in entry["renderers"].items():
            row = [time_to(points, t) for t in TARGETS]
            per = np.mean([p["seconds"] / p["spp"] for p in points if p["spp"] >= 64] or [0.0])
            print(f"| {label} | {' | '.join(fmt(t) for t in row)} | {fmt(ssim_at(points))} | {per * 1e3:.3f} ms |")
        rts = {k: v for k, v in entry["renderers"].items() if not k.startswith("mitsuba/")}
        mits = {k: v for k, v in entry["renderers"].items() if k.startswith("mitsuba/")}
        # SSIM 0.99 is compared under the 1 % target's rule.
        goals = [(f"{100 * t:g} % relative RMSE", t, lambda p, t=t: time_to(p, t)) for t in TARGETS]
        goals.append(("SSIM 0.99", 0.01, ssim_at))
        for label, points in rts.items():
            for what, target, at in goals:
                ours = at(points)
                best = min((t for t in (at(p) for p in mits.values()) if t), default=None)
                if not comparable(entry, target):
                    print(f"\n{label}: {what}: no ratio, the images differ by more than a third of it")
                elif ours and best:
                    print(f"\n{label}: {what} {best / ours:.2f}x sooner than Mitsuba's best sampler")


if __name__ == "__main__":
    main()
