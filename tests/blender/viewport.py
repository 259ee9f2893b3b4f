"""Blender side of tests/blender_live.rs, the viewport's Rendered mode without a display
(run with the bpy venv's python, RT_BINARY naming rt): what view_update and view_draw do
besides drawing, driven as Blender drives them.

    viewport.py OUT

1. The first update exports the scene and starts `rt watch --stream`; its first converged
   frame (the exported camera) is kept.
2. The viewport's camera is sent as view_draw sends it, from Blender's own matrices of the
   scene camera (view = inverse of its world matrix, projection = calc_matrix_camera) and,
   as when the viewport looks through the camera, its depth of field (a wide aperture
   focused far behind the cube): the converged frame must be the same image. A camera
   with a 10% longer lens must not be, nor the same view without its depth of field.
   The exported camera's frames, from before the viewport's first view, are not drawn.
3. Edits reach the viewport through a depsgraph handler calling the viewport's update,
   as view_update is called: the cube moves, its material changes, its mesh changes.
   Which files each rewrote and rt's reload line for each go to OUT/viewport.json.
4. The scene camera moves while the viewport looks through its own view: rt reloads the
   scene file (its camera changed) and must go on showing the viewport's view, the same
   image as before the move.
"""

import json
import os
import sys
import time

import bpy
import numpy as np

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(REPO, "blender"))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import rt_blender  # noqa: E402
from rt_blender import rt_engine  # noqa: E402
from rt_blender import rt_viewport  # noqa: E402
from live_edits import build  # noqa: E402
from live_watch import edits  # noqa: E402

SPP = 16
TIMEOUT_S = 300


def converged_frame(client, after_line):
    """The first frame at SPP samples that shows every command up to `after_line`."""
    deadline = time.monotonic() + TIMEOUT_S
    while time.monotonic() < deadline:
        frame, _ = client.latest()
        if frame is not None and frame.line >= after_line and frame.spp >= SPP:
            return frame
        if client.closed:
            sys.exit(f"rt stopped: {list(client.stderr)}")
        time.sleep(0.02)
    sys.exit(f"no converged frame after line {after_line}")


def reload_line(client, line):
    """rt's reload (or error) line for command line `line`."""
    deadline = time.monotonic() + TIMEOUT_S
    seen = []
    while time.monotonic() < deadline:
        seen += client.take_messages()
        for message in seen:
            if f" line={line} " in message + " ":
                return message
        time.sleep(0.02)
    sys.exit(f"no reload line for line {line}; messages {seen}")


def block_difference(a, b, block=8):
    """The largest difference of 8x8-block mean luminance between two frames, over the mean."""
    def blocks(frame):
        lum = frame.pixels[..., :3].mean(axis=2)
        h, w = (lum.shape[0] // block) * block, (lum.shape[1] // block) * block
        return lum[:h, :w].reshape(h // block, block, w // block, block).mean(axis=(1, 3))

    ba, bb = blocks(a), blocks(b)
    return float(np.abs(ba - bb).max() / max(ba.mean(), 1e-6))


def main(out):
    scene, cube, paint = build()
    dof = scene.camera.data.dof
    dof.use_dof, dof.aperture_fstop, dof.focus_distance = True, 0.025, 20.0
    rt_blender.register()
    scene.rt_render.viewport_spp = SPP
    viewport = rt_viewport.Viewport(os.environ["RT_BINARY"], os.path.join(out, "viewport"))
    depsgraph = bpy.context.evaluated_depsgraph_get()
    viewport.update(depsgraph)
    client = viewport.client
    exported = converged_frame(client, 0)

    width, height = exported.width, exported.height
    camera = scene.camera
    view = camera.matrix_world.inverted()
    projection = camera.calc_matrix_camera(depsgraph, x=width, y=height)
    aperture = rt_viewport.aperture_fields(camera)
    viewport.view(view, projection, width, height, aperture=aperture)
    same = converged_frame(client, client.lines_sent)
    drawn = {"exported": viewport.shows_view(exported), "same": viewport.shows_view(same)}
    viewport.view(view, projection, width, height)
    pinhole = converged_frame(client, client.lines_sent)
    # A 10% longer lens: the projection's scales, 2·lens/sensor, 10% larger.
    longer = projection.copy()
    longer[0][0] *= 1.1
    longer[1][1] *= 1.1
    viewport.view(view, longer, width, height)
    zoomed = converged_frame(client, client.lines_sent)

    updates = []

    def view_update(_scene, graph):
        written = viewport.update(graph)
        if written:
            line, _ = viewport.reloads[-1]
            updates.append({"written": written, "reload": reload_line(client, line)})

    bpy.app.handlers.depsgraph_update_post.append(view_update)
    steps = edits(scene, cube, paint)
    by_step = {}
    for name, edit in steps.items():
        if name == "camera":
            edited = converged_frame(client, client.lines_sent)
        before = len(updates)
        edit()
        bpy.context.view_layer.update()
        by_step[name] = updates[before:]
    camera_moved = converged_frame(client, client.lines_sent)
    bpy.app.handlers.depsgraph_update_post.remove(view_update)

    report = {
        "size": [width, height],
        "same_camera_difference": block_difference(exported, same),
        "aperture": aperture,
        "drawn": drawn,
        "pinhole_difference": block_difference(exported, pinhole),
        "longer_lens_difference": block_difference(pinhole, zoomed),
        "camera_object_moved_difference": block_difference(edited, camera_moved),
        "updates": by_step,
        "errors": [m for m in client.take_messages() if m.startswith("error ")],
    }
    viewport.close()
    report["rt_exit"] = client.process.returncode
    with open(os.path.join(out, "viewport.json"), "w") as f:
        json.dump(report, f, indent=1)
    rt_blender.unregister()


if __name__ == "__main__":
    main(sys.argv[1])
