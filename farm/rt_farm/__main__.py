"""`python -m rt_farm SCENE --spp N --parts K -o OUT [--frames A..B] [-- RT RENDER FLAGS]`:
renders on the Ray cluster at --address (by default a local one, as `ray start --head`
would make), then merges. See docs/farm.md."""

import argparse
import shutil
import sys
from pathlib import Path

import ray

from . import job


def frame_range(text: str) -> range:
    first, _, last = text.partition("..")
    try:
        a, b = int(first), int(last)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected FIRST..LAST (frames, both included), not {text!r}")
    if b < a:
        raise argparse.ArgumentTypeError(f"{text!r}: the last frame comes before the first")
    return range(a, b + 1)


def parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="rt-farm", description=__doc__.splitlines()[0])
    p.add_argument("scene", help="scene file; with --frames, #### in its name is the frame number")
    p.add_argument("-o", "--output", required=True, help=".exr or .png; with --frames, #### is the frame number")
    p.add_argument("--spp", type=int, required=True, help="samples per pixel of each frame")
    p.add_argument("--parts", type=int, default=8, help="sample ranges per frame, each one task (default 8)")
    p.add_argument("--frames", type=frame_range, help="FIRST..LAST, both included")
    p.add_argument("--address", help="a Ray cluster (ray://… or host:port, or auto); default: a local one")
    p.add_argument("--rt", default=shutil.which("rt") or "rt", help="the rt to ship to the workers (default: rt on PATH)")
    p.add_argument("--workers-own-rt", action="store_true", help="workers run their own rt (on their PATH) instead")
    p.add_argument("--gpus-per-task", type=float, default=1.0, help="Ray GPU resource each task takes (default 1)")
    p.add_argument("--parts-dir", type=Path, help="where parts are kept (default: OUTPUT's folder/.rt-farm-parts)")
    p.epilog = "After --, flags for each rt render (--size, --seed, --noise-threshold 0, …)."
    return p


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    ours, flags = (argv[: argv.index("--")], argv[argv.index("--") + 1 :]) if "--" in argv else (argv, [])
    args = parser().parse_args(ours)
    if args.spp < 1 or args.parts < 1:
        print("rt-farm: --spp and --parts must be at least 1", file=sys.stderr)
        return 2
    if not Path(args.rt).is_file():
        print(f"rt-farm: {args.rt}: no rt there to run and ship: put rt on PATH or give --rt PATH", file=sys.stderr)
        return 2
    parts_dir = args.parts_dir or Path(args.output).resolve().parent / ".rt-farm-parts"
    spec = job.Job(rt=args.rt, scene=args.scene, output=args.output, spp=args.spp, parts=min(args.parts, args.spp),
                   parts_dir=parts_dir, frames=args.frames, flags=flags, gpus_per_task=args.gpus_per_task,
                   ship_rt=not args.workers_own_rt)
    # The workers import this package from the job's own copy, wherever they run.
    package = str(Path(__file__).resolve().parent)
    ray.init(address=args.address, logging_level="warning", log_to_driver=False,
             runtime_env={"py_modules": [package]})
    try:
        summary = job.run(spec)
    except (RuntimeError, ValueError) as e:
        print(f"rt-farm: {e}", file=sys.stderr)
        return 1
    finally:
        ray.shutdown()
    print(f"rt-farm: wrote {', '.join(summary['outputs'])} ({summary['tasks']} parts on {summary['nodes']} nodes)",
          file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
