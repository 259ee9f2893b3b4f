"""A farm job on a local Ray cluster of a head and two GPU workers (lavapipe stands in for
the GPUs), one worker killed as the first part arrives, while the other renders: Ray runs
the lost task again on the survivor, and the job ends with every part. Writes a JSON
summary to OUT/summary.json; tests/farm.rs compares the merged image with `rt render`'s.

usage: kill_a_worker.py OUT RT SCENE SPP PARTS [RT RENDER FLAGS...]"""

import json
import sys
from pathlib import Path

import ray
from ray.cluster_utils import Cluster

farm = Path(__file__).resolve().parents[2] / "farm"
sys.path.insert(0, str(farm))
from rt_farm import job  # noqa: E402


def main() -> None:
    out, rt, scene, spp, parts, flags = Path(sys.argv[1]), sys.argv[2], sys.argv[3], int(sys.argv[4]), int(sys.argv[5]), sys.argv[6:]
    cluster = Cluster(initialize_head=True, head_node_args={"num_cpus": 1, "num_gpus": 0})
    workers = [cluster.add_node(num_cpus=1, num_gpus=1) for _ in range(2)]
    cluster.wait_for_nodes()
    ray.init(address=cluster.address, logging_level="warning", log_to_driver=False,
             runtime_env={"py_modules": [str(farm / "rt_farm")]})
    events = {"killed": None, "parts": []}

    def on_part(task, result):
        events["parts"].append({"first": task.first, "end": task.end, "node": result["node"],
                                "after_kill": events["killed"] is not None})
        if events["killed"] is None:
            # The other worker is rendering a part of its own: kill it mid-task.
            victim = next(w for w in workers if w.node_id != result["node"])
            cluster.remove_node(victim, allow_graceful=False)
            events["killed"] = victim.node_id

    spec = job.Job(rt=rt, scene=scene, output=str(out / "farm.exr"), spp=spp, parts=parts,
                   parts_dir=out / "parts", flags=flags, gpus_per_task=1, on_part=on_part)
    try:
        summary = job.run(spec)
    finally:
        ray.shutdown()
        cluster.shutdown()
    summary = {**summary, **events, "workers": [w.node_id for w in workers]}
    (out / "summary.json").write_text(json.dumps(summary))


if __name__ == "__main__":
    main()
