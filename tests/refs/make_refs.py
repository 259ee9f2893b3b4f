#!/usr/bin/env python3
"""Renders rt's validation scenes with Mitsuba 3 into linear EXR references.

    python3 -m venv /tmp/mi && /tmp/mi/bin/pip install mitsuba==3.9.1
    apt-get install libllvm19          # for the llvm_ad_rgb variant
    cargo build --release
    /tmp/mi/bin/python tests/refs/make_refs.py [--spp 8192] [--rt target/release/rt] [NAME...]

Each `tests/refs/scenes/NAME.toml` (an rt scene) is translated by rt itself
(`rt bench mitsuba-scene`: the one translation, which `rt bench compare` renders too;
crates/rt-bench/src/mitsuba_scene.rs says how each part maps) and rendered to
`tests/refs/NAME.exr`, in PARTS renders of other seeds whose spread gives each pixel's
standard error per channel, `tests/refs/NAME.error.exr`: Mitsuba's noise is not rt's
(its volumetric path tracer samples an absorbing medium by one channel at a time).
`tests/mitsuba_validation.rs` renders the same TOML with rt and compares.
"""

import argparse
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "crates", "rt-bench", "src"))

import drjit as dr  # noqa: E402
import mitsuba as mi  # noqa: E402
from mitsuba_scene import load  # noqa: E402

PARTS = 8


def translate(rt, scene_path, folder):
    """The path of rt's Mitsuba translation of `scene_path`, written into `folder`."""
    result = subprocess.run([rt, "bench", "mitsuba-scene", scene_path, "-o", folder], capture_output=True, text=True)
    if result.returncode != 0:
        raise SystemExit(f"translating {scene_path}: {result.stderr.strip()}")
    return os.path.join(folder, "scene.json")


def render_in_parts(scene, spp):
    """The mean of PARTS renders of spp / PARTS samples (seeds 1 to PARTS), and each
    pixel's standard error of that mean per channel from the renders' spread."""
    parts = [mi.render(scene, spp=spp // PARTS, seed=seed) for seed in range(1, PARTS + 1)]
    mean = sum(parts[1:], parts[0]) / PARTS
    spread = sum(dr.square(p - mean) for p in parts)
    return mean, dr.sqrt(spread / (PARTS * (PARTS - 1)))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--spp", type=int, default=8192)
    ap.add_argument("--variant", default="llvm_ad_rgb")
    ap.add_argument("--rt", default=os.path.join(ROOT, "target", "release", "rt"))
    ap.add_argument("--out", default=HERE, help="folder for the EXR files")
    ap.add_argument("names", nargs="*")
    args = ap.parse_args()
    mi.set_variant(args.variant)
    scenes = os.path.join(HERE, "scenes")
    names = args.names or sorted(n[:-5] for n in os.listdir(scenes) if n.endswith(".toml"))
    for name in names:
        folder = tempfile.mkdtemp(prefix=f"rt-refs-{name}-")
        scene = load(translate(args.rt, os.path.join(scenes, f"{name}.toml"), folder), spp=args.spp)
        mean, error = render_in_parts(scene, args.spp)
        out = os.path.join(args.out, f"{name}.exr")
        mi.util.write_bitmap(out, mean, write_async=False)
        mi.util.write_bitmap(os.path.join(args.out, f"{name}.error.exr"), error, write_async=False)
        print(f"{name}: {out}", file=sys.stderr, flush=True)
    # Dr.Jit's threads can keep the interpreter from ending: everything is written.
    os._exit(0)


if __name__ == "__main__":
    main()
