"""rt as a Blender render engine: pick "rt" in Render Properties > Render Engine and press
F12 (or Ctrl+F12 for the frame range). Each frame is exported with rt_export's own code
into a cache folder, rendered by the `rt` binary as a child process
(`rt render SCENE.toml -o FRAME.exr --progress json ...`) and its linear EXR loaded into
the Render Result. Esc stops the child (SIGTERM: rt removes its temporaries and exits),
so no half-written image is left; rt's error message is reported on failure.

Where `rt` is: the add-on preference, else the environment variable RT_BINARY, else `rt`
on PATH. The cache: the add-on preference, else a folder under the system temp dir,
in both cases one subfolder per .blend.
"""

import json
import os
import queue
import subprocess
import tempfile
import threading
import time

import bpy
import numpy as np

try:
    from . import rt_export, rt_viewport
except ImportError:  # run from the blender/ folder, outside the packaged extension
    import rt_export
    import rt_viewport

# The add-on's name, which its preferences are registered under.
ADDON = __package__ or __name__
# How long a stopped rt gets to clean up before it is killed.
STOP_GRACE_S = 1.0


class RtError(Exception):
    """rt failed: the message is rt's own (or why it could not run)."""


class RtCancelled(Exception):
    """The render was stopped before rt finished; the argument is rt's exit status
    (143 once rt has removed its temporaries, -15 if the signal came before it had any)."""


# --- settings ---------------------------------------------------------------------


class RtPreferences(bpy.types.AddonPreferences):
    bl_idname = ADDON

    rt_binary: bpy.props.StringProperty(
        name="rt binary",
        description="Path to the rt executable (empty: $RT_BINARY, else rt on PATH)",
        subtype="FILE_PATH",
        default="",
    )
    cache_dir: bpy.props.StringProperty(
        name="Cache folder",
        description="Where each .blend's frames are exported and rendered (empty: the system temp folder)",
        subtype="DIR_PATH",
        default="",
    )

    def draw(self, _context):
        self.layout.prop(self, "rt_binary")
        self.layout.prop(self, "cache_dir")


class RtRenderSettings(bpy.types.PropertyGroup):
    spp: bpy.props.IntProperty(name="Samples", description="Samples per pixel", default=128, min=1, soft_max=16384)
    max_bounces: bpy.props.IntProperty(
        name="Max Bounces", description="Longest path; 0 shows emitters and the sky only", default=12, min=0, max=1024
    )
    sampling: bpy.props.EnumProperty(
        name="Sampling",
        description="How paths find light",
        items=(
            ("nee", "Light Sampling", "Next-event estimation with multiple importance sampling"),
            ("resampled", "Resampled", "No light sampling: resampled BSDF and sun directions"),
        ),
        default="nee",
    )
    seed: bpy.props.IntProperty(name="Seed", description="The same seed gives the same image", default=0, min=0)
    viewport_spp: bpy.props.IntProperty(
        name="Viewport Samples",
        description="Samples per pixel the viewport's Rendered mode refines to",
        default=64,
        min=1,
        soft_max=4096,
    )
    viewport_pixel_size: bpy.props.IntProperty(
        name="Viewport Pixel Size",
        description="The viewport renders one pixel of rt per this many screen pixels across (faster)",
        default=2,
        min=1,
        max=8,
    )


class RT_PT_render(bpy.types.Panel):
    bl_label = "rt"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "render"
    COMPAT_ENGINES = {"RT"}

    @classmethod
    def poll(cls, context):
        return context.engine in cls.COMPAT_ENGINES

    def draw(self, context):
        settings = context.scene.rt_render
        layout = self.layout
        layout.use_property_split = True
        for name in ("spp", "max_bounces", "sampling", "seed", "viewport_spp", "viewport_pixel_size"):
            layout.prop(settings, name)


def preferences():
    addon = bpy.context.preferences.addons.get(ADDON)
    return addon.preferences if addon is not None else None


def rt_binary():
    prefs = preferences()
    if prefs is not None and prefs.rt_binary:
        return bpy.path.abspath(prefs.rt_binary)
    return os.environ.get("RT_BINARY") or "rt"


def cache_dir():
    prefs = preferences()
    base = bpy.path.abspath(prefs.cache_dir) if prefs is not None and prefs.cache_dir else tempfile.gettempdir()
    stem = bpy.path.display_name_from_filepath(bpy.data.filepath) or "untitled"
    return os.path.join(base, f"rt-{rt_export.sanitize(stem)}")


# --- running rt -------------------------------------------------------------------


def rt_command(binary, scene_path, output, settings):
    return [
        binary,
        "render",
        scene_path,
        "-o",
        output,
        "--progress",
        "json",
        "--spp",
        str(settings.spp),
        "--max-bounces",
        str(settings.max_bounces),
        "--sampling",
        settings.sampling,
        "--seed",
        str(settings.seed),
    ]


def stop(process):
    """SIGTERM, then SIGKILL if rt has not exited within STOP_GRACE_S."""
    process.terminate()
    try:
        process.wait(STOP_GRACE_S)
    except subprocess.TimeoutExpired:
        process.kill()
        process.wait()


def run_rt(command, on_progress=None, should_stop=lambda: False, poll_s=0.05):
    """Runs `rt render ... --progress json`, calling `on_progress(event)` for each
    progress event, and returns (done event, warning messages). Raises RtError with
    rt's message if it fails, RtCancelled (after stopping it) once `should_stop()`."""
    try:
        process = subprocess.Popen(
            command, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True
        )
    except OSError as e:
        raise RtError(f"cannot run {command[0]!r} ({e}): set the path to rt in the add-on's preferences") from e
    lines = queue.Queue()

    def read():
        for line in process.stderr:
            lines.put(line)
        lines.put(None)

    threading.Thread(target=read, daemon=True).start()
    done, error, warnings, other = None, None, [], []
    try:
        while True:
            if should_stop():
                stop(process)
                raise RtCancelled(process.returncode)
            try:
                line = lines.get(timeout=poll_s)
            except queue.Empty:
                continue
            if line is None:
                break
            try:
                event = json.loads(line)
            except ValueError:
                event = None
            if not isinstance(event, dict):
                other.append(line.rstrip("\n"))  # a line that is not an event, e.g. a signal notice
                continue
            kind = event.get("event")
            if kind == "progress" and on_progress is not None:
                on_progress(event)
            elif kind == "warning":
                warnings.append(str(event.get("message", "")))
            elif kind == "done":
                done = event
            elif kind == "error":
                error = str(event.get("message", ""))
    finally:
        if process.poll() is None and done is None:
            stop(process)
        process.wait()
    if process.returncode != 0 or done is None:
        message = error or "\n".join(other[-5:]) or f"rt exited with status {process.returncode}"
        raise RtError(message)
    return done, warnings


def render_frame(scene, settings, folder, binary, on_progress=None, should_stop=lambda: False):
    """Exports `scene` into `folder` and renders its current frame there. Returns the
    EXR's path and the seconds spent exporting and in rt (start to exit)."""
    os.makedirs(folder, exist_ok=True)
    scene_path = os.path.join(folder, "scene.toml")
    output = os.path.join(folder, f"frame_{scene.frame_current:04d}.exr")
    # A stale image of this frame must never pass for a new one.
    if os.path.exists(output):
        os.remove(output)
    start = time.perf_counter()
    rt_export.export_scene(scene, os.path.join(folder, "assets"), scene_path)
    exported = time.perf_counter()
    done, warnings = run_rt(rt_command(binary, scene_path, output, settings), on_progress, should_stop)
    timings = {"export_s": exported - start, "rt_s": time.perf_counter() - exported, "render_s": done["seconds"]}
    return output, warnings, timings


def exr_pixels(path, width, height):
    """rt's linear EXR as width*height RGBA rows, bottom row first (as a Render Result's
    rect). Read through bpy.data.images as data, so that no colour transform touches it:
    RenderLayer.load_from_file wants Blender's multilayer channel names."""
    image = bpy.data.images.load(path, check_existing=False)
    try:
        image.colorspace_settings.is_data = True
        if tuple(image.size) != (width, height):
            raise RtError(f"{path}: {image.size[0]}x{image.size[1]}, expected {width}x{height}")
        pixels = np.empty(width * height * 4, dtype=np.float32)
        image.pixels.foreach_get(pixels)
    finally:
        bpy.data.images.remove(image)
    return pixels.reshape(-1, 4)


# --- the engine -------------------------------------------------------------------


class RtRenderEngine(bpy.types.RenderEngine):
    bl_idname = "RT"
    bl_label = "rt"
    bl_use_preview = False
    bl_use_postprocess = True

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
        scene = depsgraph.scene
        width, height = rt_export.render_size(scene)

        def on_progress(event):
            spp, of = event.get("spp", 0), max(event.get("of", 1), 1)
            self.update_progress(spp / of)
            self.update_stats("", f"rt: {spp}/{of} spp, {event.get('eta_s', 0.0):.1f} s left")

        self.update_stats("", "rt: exporting")
        try:
            path, warnings, timings = render_frame(
                scene, scene.rt_render, cache_dir(), rt_binary(), on_progress, self.test_break
            )
        except RtCancelled:
            return
        except (RtError, OSError) as e:
            self.report({"ERROR"}, f"rt: {e}")
            return
        for warning in warnings:
            self.report({"WARNING"}, f"rt: {warning}")
        try:
            pixels = exr_pixels(path, width, height)
        except RtError as e:
            self.report({"ERROR"}, f"rt: {e}")
            return
        result = self.begin_result(0, 0, width, height)
        try:
            result.layers[0].passes["Combined"].rect = pixels
        finally:
            self.end_result(result)
        rt_export.log(
            f"frame {scene.frame_current}: export {timings['export_s']:.2f} s, rt {timings['rt_s']:.2f} s "
            f"(render {timings['render_s']:.2f} s)"
        )


def engine_panels():
    """Blender's own panels that apply to rt too (output size, colour management)."""
    names = ("RENDER_PT_color_management", "RENDER_PT_format", "RENDER_PT_frame_range", "RENDER_PT_output")
    return [p for p in (getattr(bpy.types, n, None) for n in names) if p is not None and hasattr(p, "COMPAT_ENGINES")]


CLASSES = (RtPreferences, RtRenderSettings, RT_PT_render, RtRenderEngine)


def register():
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    bpy.types.Scene.rt_render = bpy.props.PointerProperty(type=RtRenderSettings)
    for panel in engine_panels():
        panel.COMPAT_ENGINES.add(RtRenderEngine.bl_idname)


def unregister():
    for panel in engine_panels():
        panel.COMPAT_ENGINES.discard(RtRenderEngine.bl_idname)
    del bpy.types.Scene.rt_render
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
