"""rt as a Blender render engine: pick "rt" in Render Properties > Render Engine and press
F12 (or Ctrl+F12 for the frame range). Each frame is exported from the render's own
depsgraph (render visibility, render-level modifiers) into a cache folder, rendered by
the `rt` binary as a child process, and shown while it refines: rt writes the image so
far every second or so (`--snapshot`), and the Render Result is updated with it. The
passes the view layer asks for (rt_passes) are filled at the end. Esc stops rt at once
(SIGTERM: rt removes its temporaries and exits) and keeps the image so far.

Material, world and light previews render Blender's preview scenes the same way, small
and with few samples; the viewport's Rendered mode streams from `rt watch --stream`
(rt_viewport). The Shader Editor and Blender's and Cycles' panels show with rt picked
(rt_panels), since rt renders Cycles' node trees.
"""

import os
import time

import bpy
import numpy as np

from . import rt_export, rt_passes, rt_run, rt_viewport

# Names the tests and older scripts use.
RtError, RtCancelled = rt_run.RtError, rt_run.RtCancelled
rt_binary, cache_dir, run_rt = rt_run.rt_binary, rt_run.cache_dir, rt_run.run_rt


def render_frame(scene, settings, folder, binary, on_progress=None, should_stop=lambda: False, **more):
    """Exports `scene` (from `more["depsgraph"]`, else the context's) into `folder` and
    renders its current frame there. `more`: `preview` (few samples, no extras),
    `aov_dir` (write the AOVs there), `on_snapshot` (called with the path of each image so
    far, and its spp). Returns the EXR's path, rt's warnings, and the seconds spent
    exporting and in rt (start to exit)."""
    rt_run.check_binary(binary)
    os.makedirs(folder, exist_ok=True)
    scene_path = os.path.join(folder, "scene.toml")
    output = os.path.join(folder, f"frame_{scene.frame_current:04d}.exr")
    # A stale image of this frame must never pass for a new one.
    if os.path.exists(output):
        os.remove(output)
    start = time.perf_counter()
    rt_export.export_scene(scene, os.path.join(folder, "assets"), scene_path, depsgraph=more.get("depsgraph"),
                           frame_set=more.get("frame_set"))
    exported = time.perf_counter()
    command = [binary, "render", scene_path, "-o", output, "--progress", "json"]
    command += rt_run.render_options(settings, scene.frame_current, more.get("preview", False))
    if more.get("aov_dir"):
        command += ["--aov-files", more["aov_dir"]]
    on_snapshot = more.get("on_snapshot")
    if on_snapshot is not None:
        snapshot = os.path.join(folder, "snapshot.exr")
        command += ["--snapshot", snapshot, "--snapshot-every", f"{settings.progressive_every:.7g}"]
    done, warnings = rt_run.run_rt(command, on_progress, should_stop, on_snapshot=on_snapshot)
    timings = {"export_s": exported - start, "rt_s": time.perf_counter() - exported, "render_s": done["seconds"]}
    timings["spp"] = done.get("spp")
    return output, warnings, timings


class Region:
    """The pixels of the render that the Render Result holds: all of them, or with
    Border render the border's, as Blender and Cycles round it."""

    def __init__(self, scene, width, height):
        r = scene.render
        self.full = (width, height)
        if r.use_border:
            x0, x1 = int(r.border_min_x * width), int(r.border_max_x * width)
            y0, y1 = int(r.border_min_y * height), int(r.border_max_y * height)
            self.x, self.y, self.w, self.h = x0, y0, max(1, x1 - x0), max(1, y1 - y0)
        else:
            self.x, self.y, self.w, self.h = 0, 0, width, height

    def crop(self, pixels):
        """Rows bottom first, `channels` per pixel, of the whole image to the region's."""
        width, height = self.full
        grid = pixels.reshape(height, width, -1)
        return grid[self.y : self.y + self.h, self.x : self.x + self.w].reshape(self.w * self.h, -1)


class RtRenderEngine(bpy.types.RenderEngine):
    bl_idname = "RT"
    bl_label = "rt"
    bl_use_preview = True
    bl_use_postprocess = True
    # rt renders Cycles' shader nodes: the Shader Editor shows them (Blender hides them
    # for an engine that keeps this True).
    bl_use_shading_nodes_custom = False
    # The viewport's Material Preview mode stays EEVEE's.
    bl_use_eevee_viewport = True

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self.viewport = None

    def __del__(self):
        try:
            viewport = self.viewport
        except (AttributeError, ReferenceError):
            # Quitting, Blender frees the engine before this runs (then even reading an
            # attribute raises); rt sees its input close and exits by itself.
            return
        if viewport is not None:
            viewport.close()

    def update_render_passes(self, scene=None, renderlayer=None):
        rt_passes.register_passes(self, scene, renderlayer)

    # The viewport's Rendered mode: a streaming rt child (rt_viewport).
    def view_update(self, context, depsgraph):
        if self.viewport is None:
            self.viewport = rt_viewport.Viewport(rt_binary(), os.path.join(cache_dir(), "viewport"))
            try:
                self.viewport.update(depsgraph)
            except (OSError, ValueError) as e:
                self.viewport = None
                self.update_stats("", f"rt: {e}")
                return
            rt_viewport.keep_redrawing(self, self.viewport)
            return
        try:
            self.viewport.update(depsgraph)
        except (OSError, ValueError) as e:
            self.update_stats("", f"rt: {e}")
        for message in self.viewport.client.take_messages():
            if message.startswith("error "):
                self.update_stats("", f"rt: {rt_viewport.fields(message).get('message', message)}")

    def view_draw(self, context, depsgraph):
        if self.viewport is not None:
            self.viewport.draw(self, context, depsgraph)

    def render(self, depsgraph):
        scene, layer = depsgraph.scene, depsgraph.view_layer
        width, height = rt_export.render_size(scene)
        region = Region(scene, width, height)
        preview = self.is_preview
        folder = os.path.join(cache_dir(), "preview") if preview else cache_dir()
        passes = [] if preview else rt_passes.enabled(layer)
        aov_dir = os.path.join(folder, "aovs") if passes else None
        scale = rt_passes.exposure_scale(scene.rt_render)
        # With Border render, Blender's Render Result is the border's: its coordinates start there.
        result = self.begin_result(0, 0, region.w, region.h, layer=layer.name)
        started = time.perf_counter()

        def show(path):
            pixels = region.crop(rt_run.exr_pixels(path, width, height))
            pixels[:, :3] *= scale
            result.layers[0].passes["Combined"].rect = pixels
            self.update_result(result)

        def on_progress(event):
            spp, of = event.get("spp", 0), max(event.get("of", 1), 1)
            self.update_progress(spp / of)
            elapsed = time.perf_counter() - started
            self.update_stats("", f"rt: {spp}/{of} samples, {elapsed:.1f} s, {event.get('eta_s', 0.0):.1f} s left")

        def on_snapshot(event):
            try:
                show(event["file"])
            except (rt_run.RtError, RuntimeError, KeyError) as e:
                rt_export.log(f"cannot show the image so far: {e}")

        self.update_stats("", "rt: exporting")
        timings = None
        try:
            path, warnings, timings = render_frame(
                scene, scene.rt_render, folder, rt_binary(), on_progress, self.test_break,
                depsgraph=depsgraph, preview=preview, aov_dir=aov_dir, on_snapshot=None if preview else on_snapshot,
                # Motion blur: the render's depsgraph evaluated over the shutter, as Cycles does.
                frame_set=None if preview else self.frame_set,
            )
            for warning in warnings:
                self.report({"WARNING"}, f"rt: {warning}")
            show(path)
            self.fill_passes(result, passes, aov_dir, region, scene)
        except RtCancelled:
            # Esc: what was shown so far stays.
            pass
        except (RtError, OSError) as e:
            self.report({"ERROR"}, f"rt: {e}")
        finally:
            self.end_result(result)
        if timings is not None and not preview:
            rt_export.log(
                f"frame {scene.frame_current}: export {timings['export_s']:.2f} s, rt {timings['rt_s']:.2f} s "
                f"(render {timings['render_s']:.2f} s, {timings['spp']} spp)"
            )

    def fill_passes(self, result, passes, aov_dir, region, scene):
        """The passes the view layer asks for, from rt's AOV images."""
        if not passes:
            return
        width, height = region.full
        if scene.camera is None:
            scale, offset = np.ones(region.w * region.h, dtype=np.float32), 0.0
        else:
            scale, offset = rt_passes.view_depth(scene.camera, scene, width, height)
            scale = region.crop(scale).reshape(-1)
        images = {}
        for p in passes:
            if p.aov not in images:
                rgba = rt_run.exr_pixels(os.path.join(aov_dir, f"{p.aov}.exr"), width, height)
                images[p.aov] = region.crop(rgba)[:, :3]
            values = rt_passes.pass_pixels(p, images[p.aov], scale, offset)
            result.layers[0].passes[p.name].rect = np.ascontiguousarray(values, dtype=np.float32)


def register():
    bpy.utils.register_class(RtRenderEngine)


def unregister():
    bpy.utils.unregister_class(RtRenderEngine)
