"""A farm job: frames × sample ranges as Ray tasks, parts kept as they arrive, each frame
merged by `rt merge` once its parts are in. Losing a worker loses no finished part: Ray
runs its unfinished task again elsewhere, and the parts already written stay."""

import os
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

import ray

from . import bundle, worker


@dataclass(frozen=True)
class Task:
    frame: int | None
    first: int
    end: int


@dataclass
class Job:
    rt: str
    scene: str
    output: str
    spp: int
    parts: int
    parts_dir: Path
    frames: range | None = None
    flags: list[str] = field(default_factory=list)
    gpus_per_task: float = 1.0
    ship_rt: bool = True
    # Called with (task, result) as each part arrives (tests kill a worker from here).
    on_part: object = None


def frame_path(pattern: str, frame: int | None) -> str:
    """`pattern` with its run of `#` replaced by the zero-padded frame number."""
    if frame is None:
        return pattern
    start = pattern.find("#")
    if start < 0:
        raise ValueError(f"{pattern}: with --frames, the path needs #### where the frame number goes")
    end = start
    while end < len(pattern) and pattern[end] == "#":
        end += 1
    return f"{pattern[:start]}{frame:0{end - start}d}{pattern[end:]}"


def plan(job: Job) -> list[Task]:
    """Each frame's samples 0..spp cut into `parts` ranges as even as they go."""
    cuts = [job.spp * i // job.parts for i in range(job.parts + 1)]
    frames = list(job.frames) if job.frames is not None else [None]
    return [Task(f, a, b) for f in frames for a, b in zip(cuts, cuts[1:]) if a < b]


def part_file(job: Job, task: Task) -> Path:
    frame = "" if task.frame is None else f"frame{task.frame:06d}-"
    return job.parts_dir / f"{frame}samples{task.first:09d}-{task.end:09d}.exr"


def write_atomically(path: Path, data: bytes) -> None:
    partial = path.with_name(f".{path.name}.{os.getpid()}.partial")
    partial.write_bytes(data)
    os.replace(partial, path)


def run(job: Job) -> dict:
    """Renders the job on the Ray cluster `ray.init` connected to; returns a summary."""
    gpus = ray.cluster_resources().get("GPU", 0)
    if job.gpus_per_task > gpus:
        raise RuntimeError(f"each task asks for {job.gpus_per_task:g} GPU and the cluster offers {gpus:g}: "
                           "add GPU workers, or give --gpus-per-task 0 to render on CPUs (lavapipe)")
    job.parts_dir.mkdir(parents=True, exist_ok=True)
    tasks = plan(job)
    # Parts an earlier run finished are kept: only the others are rendered.
    todo = [t for t in tasks if not part_file(job, t).exists()]
    shipped = {}
    remote = ray.remote(worker.render_part).options(num_gpus=job.gpus_per_task, max_retries=5)
    rt_ship = (None, [None])
    if job.ship_rt:
        data = Path(job.rt).read_bytes()
        rt_ship = (bundle.digest(data), [ray.put(data)])
    pending = {}
    for task in todo:
        if task.frame not in shipped:
            scene = bundle.bundle_scene(job.rt, Path(frame_path(job.scene, task.frame)))
            shipped[task.frame] = (scene.scene, (scene.digest, [ray.put(scene.data)]))
        scene_path, scene_ship = shipped[task.frame]
        ref = remote.remote(rt_ship, scene_ship, scene_path, task.first, task.end, job.flags)
        pending[ref] = task
    progress = Progress(job, len(tasks), len(tasks) - len(todo))
    nodes = set()
    while pending:
        done, _ = ray.wait(list(pending), num_returns=1)
        task = pending.pop(done[0])
        result = ray.get(done[0])
        write_atomically(part_file(job, task), result["data"])
        nodes.add(result["node"])
        progress.part_done(task)
        if job.on_part is not None:
            job.on_part(task, result)
    outputs = [merge(job, frame, [t for t in tasks if t.frame == frame]) for frame in sorted_frames(tasks)]
    progress.finish()
    return {"tasks": len(tasks), "rendered": len(todo), "nodes": len(nodes), "outputs": outputs,
            "seconds": progress.elapsed()}


def sorted_frames(tasks: list[Task]) -> list:
    frames = []
    for t in tasks:
        if t.frame not in frames:
            frames.append(t.frame)
    return frames


def merge(job: Job, frame: int | None, tasks: list[Task]) -> str:
    output = frame_path(job.output, frame)
    parts = [str(part_file(job, t)) for t in tasks]
    run = subprocess.run([job.rt, "merge", *parts, "-o", output], capture_output=True, text=True)
    if run.returncode != 0:
        raise RuntimeError(f"rt merge of {output} failed:\n{run.stderr.strip()}")
    return output


class Progress:
    """Parts done, samples per second across the cluster, and the time left, on stderr."""

    def __init__(self, job: Job, total: int, already: int):
        self.job, self.total, self.done, self.samples = job, total, already, 0
        self.start = time.monotonic()

    def elapsed(self) -> float:
        return time.monotonic() - self.start

    def part_done(self, task: Task) -> None:
        self.done += 1
        self.samples += task.end - task.first
        elapsed = self.elapsed()
        rate = self.samples / elapsed if elapsed > 0 else 0.0
        left = (self.total - self.done) * elapsed / max(self.done, 1)
        frame = "" if task.frame is None else f"frame {task.frame}, "
        print(f"rt-farm: {self.done}/{self.total} parts ({frame}samples {task.first}..{task.end}), "
              f"{rate:.1f} spp/s across the cluster, ~{left:.0f} s left", file=sys.stderr, flush=True)

    def finish(self) -> None:
        print(f"rt-farm: {self.total} parts in {self.elapsed():.1f} s", file=sys.stderr, flush=True)
