"""Times Mitsuba 3 on the scenes `rt bench compare` translated, as rt is timed: after
the same warm-up, each render of `spp` samples per pixel timed by the wall clock (the
render and a sync) and by the device (Dr.Jit's kernel history: the kernels' own time),
and camera and diffuse-bounce rays through its acceleration structure. The first two
renders' images are written where the case says, for the comparison of the images.

Reads one JSON job on stdin, writes one JSON line per case on stdout. Exit status 3:
Mitsuba (or a variant asked for) is not importable; the message says why.
"""

import json
import os
import sys
import time


def fail_import(message):
    print(message, file=sys.stderr)
    sys.exit(3)


try:
    import drjit as dr
    import mitsuba as mi
except Exception as e:  # ImportError, or a broken native library
    fail_import(f"cannot import mitsuba: {e}")

from mitsuba_scene import scene_dict  # noqa: E402

# As rt's warm-up: back-to-back work for a second before anything is timed, so that the
# device runs at its sustained clock.
WARM_UP_S = 1.0


def pick_variant(asked):
    wanted = [asked] if asked else ["cuda_ad_rgb", "llvm_ad_rgb"]
    errors = []
    for v in wanted:
        try:
            mi.set_variant(v)
            return v
        except Exception as e:
            errors.append(f"{v}: {e}")
    fail_import("no Mitsuba variant works: " + "; ".join(errors))


def timed(work):
    """(wall seconds, device seconds) of one call of `work`, synchronised."""
    dr.kernel_history()
    t0 = time.perf_counter()
    work()
    dr.sync_thread()
    wall = time.perf_counter() - t0
    device = sum(k.get("execution_time", 0.0) for k in dr.kernel_history()) / 1000.0
    return wall, device


def warm_up(work):
    start = time.perf_counter()
    work()
    dr.sync_thread()
    while time.perf_counter() - start < WARM_UP_S:
        work()
        dr.sync_thread()


def camera_rays(scene, w, h):
    sensor = scene.sensors()[0]
    idx = dr.arange(mi.UInt32, w * h)
    pos = (mi.Vector2f(mi.Float(idx % w), mi.Float(idx // w)) + 0.5) / mi.ScalarVector2f(w, h)
    rays, _ = sensor.sample_ray(time=0.0, sample1=0.0, sample2=pos, sample3=mi.Vector2f(0.5))
    dr.eval(rays)
    return rays


def diffuse_rays(scene, rays):
    """Cosine-distributed bounce rays from the camera rays' hits, as rt's trace bench makes them."""
    si = scene.ray_intersect(rays)
    valid = si.is_valid()
    n = dr.width(valid)
    sampler = mi.load_dict({"type": "independent"})
    sampler.seed(7, n)
    local = mi.warp.square_to_cosine_hemisphere(sampler.next_2d())
    bounce = si.spawn_ray(si.to_world(local))
    keep = dr.compress(valid)
    bounce = dr.gather(mi.Ray3f, bounce, keep)
    dr.eval(bounce)
    return bounce, dr.width(keep)


def rays(scene, w, h, runs):
    def trace(r):
        pi = scene.ray_intersect_preliminary(r)
        dr.eval(pi.t, pi.prim_index, pi.shape_index)

    camera = camera_rays(scene, w, h)
    warm_up(lambda: trace(camera))
    out = {"camera": {"count": w * h, "times": [timed(lambda: trace(camera)) for _ in range(runs)]}}
    bounce, count = diffuse_rays(scene, camera)
    warm_up(lambda: trace(bounce))
    out["diffuse"] = {"count": count, "times": [timed(lambda: trace(bounce)) for _ in range(runs)]}
    return out


def measure(case, sampler):
    scene = mi.load_dict(scene_dict(case["scene"], sampler, case["spp"]))
    film = case["scene"]["sensor"]["film"]
    w, h, spp = film["width"], film["height"], case["spp"]
    out = {"name": case["name"]}
    if case["rays"]:
        out["rays"] = rays(scene, w, h, case["runs"])
    images = {}

    def render(seed):
        images[seed] = mi.render(scene, spp=spp, seed=seed)
        dr.eval(images[seed])

    warm_up(lambda: render(1000))
    out["paths"] = {"count": w * h * spp, "times": [timed(lambda: render(seed)) for seed in range(1, case["runs"] + 1)]}
    for seed, path in zip((1, 2), case["images"]):
        mi.util.write_bitmap(path, images[seed], write_async=False)
    return out


def main():
    job = json.load(sys.stdin)
    variant = pick_variant(job.get("variant"))
    dr.set_flag(dr.JitFlag.KernelHistory, True)
    print(json.dumps({"variant": variant, "version": mi.__version__}), flush=True)
    for case in job["cases"]:
        print(json.dumps(measure(case, job["sampler"])), flush=True)


main()
sys.stdout.flush()
# Dr.Jit's threads can keep the interpreter from ending (seen with llvm_ad_rgb after
# kernel history was read): everything is written, so leave at once.
os._exit(0)
