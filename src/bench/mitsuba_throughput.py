"""Times Mitsuba 3 on scenes `rt bench compare` translated: paths/s of its path
integrator, and camera and diffuse-bounce rays/s through its acceleration structure.

Reads one JSON job on stdin, writes one JSON line per case on stdout. Exit status 3:
Mitsuba (or a variant asked for) is not importable; the message says why.
"""

import json
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


def rgb(v):
    return {"type": "rgb", "value": [float(c) for c in v]}


def scene_dict(case):
    cam = case["camera"]
    d = {
        "type": "scene",
        "integrator": {"type": "path", "max_depth": case["max_depth"]},
        "sensor": {
            "type": "perspective",
            "fov_axis": "y",
            "fov": cam["fov_y_deg"],
            "to_world": mi.ScalarTransform4f().look_at(origin=cam["position"], target=cam["look_at"], up=cam["up"]),
            "film": {"type": "hdrfilm", "width": case["width"], "height": case["height"],
                     "rfilter": {"type": "box"}, "pixel_format": "rgb"},
            "sampler": {"type": "independent", "sample_count": case["spp"]},
        },
    }
    if case["sky"] is not None:
        d["sky"] = {"type": "constant", "radiance": rgb(case["sky"])}
    for i, shape in enumerate(case["shapes"]):
        s = {"type": "ply", "filename": shape["ply"], "face_normals": True,
             "bsdf": {"type": "twosided", "bsdf": {"type": "diffuse", "reflectance": rgb(shape["reflectance"])}}}
        if max(shape["emission"]) > 0:
            s["emitter"] = {"type": "area", "radiance": rgb(shape["emission"])}
        d[f"shape{i}"] = s
    for i, sp in enumerate(case["spheres"]):
        s = {"type": "sphere", "center": sp["center"], "radius": sp["radius"],
             "bsdf": {"type": "diffuse", "reflectance": rgb(sp["reflectance"])}}
        if max(sp["emission"]) > 0:
            s["emitter"] = {"type": "area", "radiance": rgb(sp["emission"])}
        d[f"sphere{i}"] = s
    return d


def timed(runs, work):
    """Median seconds of `runs` calls of `work` after one warm-up (which compiles kernels)."""
    work()
    dr.sync_thread()
    times = []
    for _ in range(runs):
        t0 = time.perf_counter()
        work()
        dr.sync_thread()
        times.append(time.perf_counter() - t0)
    return sorted(times)[len(times) // 2]


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


def measure(case):
    scene = mi.load_dict(scene_dict(case))
    w, h, spp, runs = case["width"], case["height"], case["spp"], case["runs"]
    out = {"name": case["name"]}
    if case["rays"]:
        rays = camera_rays(scene, w, h)

        def trace(r):
            pi = scene.ray_intersect_preliminary(r)
            dr.eval(pi.t, pi.prim_index, pi.shape_index)

        out["camera_rays_per_s"] = w * h / timed(runs, lambda: trace(rays))
        bounce, count = diffuse_rays(scene, rays)
        out["diffuse_rays_per_s"] = count / timed(runs, lambda: trace(bounce))
    seeds = iter(range(1, 10_000))

    def render():
        dr.eval(mi.render(scene, spp=spp, seed=next(seeds)))

    out["paths_per_s"] = w * h * spp / timed(runs, render)
    return out


def main():
    job = json.load(sys.stdin)
    variant = pick_variant(job.get("variant"))
    print(json.dumps({"variant": variant, "version": mi.__version__}), flush=True)
    for case in job["cases"]:
        print(json.dumps(measure(case)), flush=True)


main()
