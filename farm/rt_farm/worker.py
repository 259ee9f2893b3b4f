"""One task: samples FIRST..END of one frame, rendered by `rt render --sample-range` on
whichever worker Ray placed it on. Returns the part's bytes and where it ran."""

import os
import socket
import subprocess
import tempfile
from pathlib import Path

import ray

from . import bundle


def render_part(rt_ship, bundle_ship, scene: str, first: int, end: int, flags: list[str]) -> dict:
    """`rt_ship`, `bundle_ship`: (digest, [object ref]) pairs; the refs sit in a list so
    that Ray does not fetch the bytes before the cache is asked."""
    rt_digest, rt_ref = rt_ship
    rt = materialised_rt(rt_digest, rt_ref)
    bundle_digest, bundle_ref = bundle_ship
    root = bundle.materialise(f"scene-{bundle_digest}", lambda: ray.get(bundle_ref[0]), bundle.unpack_archive)
    with tempfile.TemporaryDirectory(dir=bundle.cache_dir()) as scratch:
        part = Path(scratch) / "part.exr"
        command = [rt, "render", str(root / scene), "--sample-range", f"{first}..{end}", "-o", str(part)]
        run = subprocess.run(command + ["--progress", "none", *flags], capture_output=True, text=True)
        if run.returncode != 0:
            raise RuntimeError(f"rt render of samples {first}..{end} failed:\n{run.stderr.strip()}")
        data = part.read_bytes()
    node = ray.get_runtime_context().get_node_id()
    return {"data": data, "node": node, "host": socket.gethostname(), "pid": os.getpid()}


def materialised_rt(digest: str | None, ref) -> str:
    """The shipped rt, or with no digest the worker's own (`rt` on its PATH)."""
    if digest is None:
        return "rt"
    folder = bundle.materialise(f"rt-{digest}", lambda: ray.get(ref[0]), bundle.unpack_executable)
    return str(folder / "rt")
