"""Blender side of tests/blender_live.rs, live export on every edit (run with the bpy
venv's python): an artist's session with "Live export on every edit" on and no save.

    live_edits.py OUT

Builds a small scene, exports it once and writes OUT/done-0. For each step i it waits
for OUT/go-i, makes the step's edit, lets the depsgraph update (which exports) and
writes OUT/done-i:
    1. the cube moves                 (the scene file is rewritten)
    2. the cube's material turns red  (its .gltf is rewritten)
    3. the cube grows taller          (its .rtmesh is rewritten)
    4. the camera moves               (the scene file is rewritten)
    5. the cube is dragged: six moves in quick succession; the first is exported at
       once, the others are held back, and the timer exports the last of them.
Background bpy runs no timers, so step 5 calls the timer's function itself once its
interval has passed, as Blender's event loop would. What each step's depsgraph updates
were classified as, and what the drag did, go to OUT/live_edits.json.
"""

import json
import os
import sys
import time

import bpy

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(REPO, "blender"))
import rt_export  # noqa: E402
import live_watch  # noqa: E402  (its scene, edits and wait_for)
from live_watch import edits, wait_for  # noqa: E402


def build():
    """live_watch.py's scene, its camera named as the viewport's export names it."""
    scene, cube, paint = live_watch.build()
    scene.camera.name = "Camera"
    return scene, cube, paint


def main(out):
    scene, cube, paint = build()
    settings = live_watch.exporter(scene, out)
    rt_export.live_export(scene)
    settings.live_edits = True

    classified = []

    def record(_scene, depsgraph):
        changes = rt_export.classify_updates(depsgraph.updates)
        classified[-1].append({k: sorted(v) if isinstance(v, set) else v for k, v in changes.items()})

    bpy.app.handlers.depsgraph_update_post.append(record)
    open(os.path.join(out, "done-0"), "w").close()

    report = {}
    scene_file = settings.scene_file

    def drag():
        before = open(scene_file).read()
        for _ in range(6):
            cube.location.y += 0.1
            bpy.context.view_layer.update()
        held = open(scene_file).read()
        report["first_move_exported"] = held != before
        report["timer_scheduled"] = bpy.app.timers.is_registered(rt_export.flush_live_edits)
        time.sleep(rt_export.LIVE_EDIT_INTERVAL_S)
        rt_export.flush_live_edits()
        landed = open(scene_file).read()
        report["last_state_held_back"] = landed != held
        # Exporting again now writes nothing: what the flush wrote is the scene as it is.
        report["last_state_landed"] = not rt_export.export_scene(scene, settings.out_dir, scene_file).written

    # The edits in their order (move, material, mesh, camera), then a drag.
    for step, step_edit in enumerate((*edits(scene, cube, paint).values(), drag), start=1):
        wait_for(os.path.join(out, f"go-{step}"))
        classified.append([])
        # More than the interval since the last export: the edit goes out at once.
        time.sleep(rt_export.LIVE_EDIT_INTERVAL_S)
        step_edit()
        bpy.context.view_layer.update()
        open(os.path.join(out, f"done-{step}"), "w").close()
    report["classified"] = classified
    with open(os.path.join(out, "live_edits.json"), "w") as f:
        json.dump(report, f, indent=1)
    bpy.app.handlers.depsgraph_update_post.remove(record)
    rt_export.unregister()


if __name__ == "__main__":
    main(sys.argv[1])
