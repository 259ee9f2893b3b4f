"""Screenshots of rt inside a real Blender window, and the viewport's latencies there.

    xvfb-run -a -s "-screen 0 1600x900x24" env LIBGL_ALWAYS_SOFTWARE=1 \\
        blender --factory-startup --enable-event-simulate -p 0 0 1600 900 \\
        --python docs/blender/screenshots.py -- --rt target/release/rt --out docs/images

(Blender 4.2 or later, which rt supports, with a display or under Xvfb as above; `rt` built first;
--enable-event-simulate lets the script press Esc on the first-start splash and drag an
object with the simulated pointer, and makes Blender ignore the real one). It installs
rt's add-on from blender/ as a legacy add-on (the blender/rt_blender package, in a
temporary folder), builds the Cornell box of
docs/blender/cornell.py with rt as the render engine, and steps through the UI with a
timer: Render Properties with rt's panel, F12 into Blender's render view (the main
window's Maximized Area), the 3D viewport in Rendered shading (rt's view_draw) while its
view orbits and an object is dragged (G, pointer moves, a click), the view through the
scene camera with its depth of field, and the Render Engine menu. It writes
OUT/blender_*.png (cropped from Blender's own screenshots) and prints the viewport's
timings from the "rt.viewport" debug log, then quits; on a failure it prints why and
exits with status 1.
"""

import logging
import math
import os
import shutil
import statistics
import struct
import sys
import tempfile
import time
import traceback
import zlib

import addon_utils
import bpy
import numpy as np
from mathutils import Euler

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
import cornell  # noqa: E402

ADDON = "rt_blender"
POLL_S = 0.1
# How long one UI state may take on a slow machine (lavapipe on 2 shared cores).
STEP_TIMEOUT_S = 600


def arguments():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    args = {"--rt": os.path.join(REPO, "target", "release", "rt"), "--out": os.path.join(REPO, "docs", "images")}
    for key, value in zip(argv[::2], argv[1::2]):
        if key not in args:
            sys.exit(f"screenshots.py: unknown option {key}; options: {', '.join(args)}")
        args[key] = value
    return os.path.abspath(args["--rt"]), os.path.abspath(args["--out"])


def install_addon(folder, rt_binary):
    """blender/rt_blender, the whole package, as Blender installs a legacy add-on."""
    package = os.path.join(folder, ADDON)
    shutil.copytree(os.path.join(REPO, "blender", "rt_blender"), package,
                    ignore=shutil.ignore_patterns("__pycache__"))
    sys.path.insert(0, folder)
    if addon_utils.enable(ADDON, default_set=True, handle_error=None) is None:
        raise RuntimeError(f"the add-on {ADDON} did not enable")
    prefs = bpy.context.preferences.addons[ADDON].preferences
    prefs.rt_binary = rt_binary
    prefs.cache_dir = os.path.join(folder, "cache")


class Timings(logging.Handler):
    """The viewport's debug log, kept."""

    def __init__(self):
        super().__init__(logging.DEBUG)
        self.records = []  # (perf_counter, message)
        self.start = time.perf_counter()

    def emit(self, record):
        message = record.getMessage()
        now = time.perf_counter()
        self.records.append((now, message))
        print(f"rt.viewport: {now - self.start:8.2f} s  {message}", file=sys.stderr)

    def count(self, prefix):
        return sum(1 for _, m in self.records if m.startswith(prefix))

    def frames_since(self, since):
        """(line, spp, of) of each frame drawn after `since`."""
        frames = []
        for at, message in self.records:
            if at > since and message.startswith("frame drawn: line "):
                words = message.replace(",", "").replace("/", " ").split()
                frames.append((int(words[3]), int(words[4]), int(words[5])))
        return frames


# --- images -------------------------------------------------------------------------


def png_bytes(rgb):
    """An 8-bit RGB PNG of an (h, w, 3) uint8 array, rows from the top."""
    h, w, _ = rgb.shape
    raw = b"".join(b"\0" + rgb[y].tobytes() for y in range(h))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    header = struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")


def crop_save(shot, path, box=None, scale=1, bits=8):
    """Crops Blender's screenshot `shot` to `box` = (x, y, w, h) in window pixels from the
    bottom left (as Blender's areas give them), shrinks it `scale` times and writes a PNG
    with `bits` per channel (fewer: a smaller file of a noisy render)."""
    image = bpy.data.images.load(shot, check_existing=False)
    w, h = image.size
    pixels = np.empty(w * h * 4, np.float32)
    image.pixels.foreach_get(pixels)
    bpy.data.images.remove(image)
    rgb = pixels.reshape(h, w, 4)[:, :, :3]
    if box is not None:
        x, y, bw, bh = box
        rgb = rgb[max(y, 0):y + bh, max(x, 0):x + bw]
    if scale > 1:
        sh, sw = rgb.shape[0] // scale * scale, rgb.shape[1] // scale * scale
        rgb = rgb[:sh, :sw].reshape(sh // scale, scale, sw // scale, scale, 3).mean(axis=(1, 3))
    rgb = np.round(rgb[::-1] * 255).clip(0, 255).astype(np.uint8) & (0xFF << (8 - bits) & 0xFF)
    rgb = np.ascontiguousarray(rgb)
    with open(path, "wb") as f:
        f.write(png_bytes(rgb))
    print(f"screenshots.py: wrote {path} ({rgb.shape[1]}x{rgb.shape[0]}, {os.path.getsize(path) // 1024} KB)")


def screenshot(window, path, area=None):
    """Blender's screenshot of the whole window (Blender 3.4's operator has no area option:
    the caller crops)."""
    with bpy.context.temp_override(window=window, screen=window.screen, area=area or window.screen.areas[0]):
        bpy.ops.screen.screenshot(filepath=path)


def area_of(window, kind):
    return max((a for a in window.screen.areas if a.type == kind), key=lambda a: a.width * a.height)


def box(area):
    return (area.x, area.y, area.width, area.height)


# --- the steps ----------------------------------------------------------------------


def wait_until(condition, what, timeout=STEP_TIMEOUT_S):
    """A condition for the runner: true once `condition()` is; fails after `timeout`."""
    deadline = time.monotonic() + timeout

    def check():
        if condition():
            return True
        if time.monotonic() > deadline:
            raise TimeoutError(f"waited {timeout} s for {what}")
        return False

    return check


def wait_s(seconds):
    until = time.monotonic() + seconds
    return lambda: time.monotonic() >= until


def steps(rt_binary, out, temp, log):
    wm = bpy.context.window_manager
    window = wm.windows[0]
    # The splash of a first start (no preferences saved) covers the window: Esc closes it.
    if bpy.app.use_event_simulate:
        window.event_simulate(type="ESC", value="PRESS")
        window.event_simulate(type="ESC", value="RELEASE")
    shot = os.path.join(temp, "shot.png")
    install_addon(os.path.join(temp, "addons"), rt_binary)
    scene, camera, sphere = cornell.build(200, 200)
    scene.render.engine = "RT"
    settings = scene.rt_render
    settings.spp, settings.viewport_spp, settings.viewport_pixel_size = 24, 16, 3
    properties = area_of(window, "PROPERTIES")
    properties.spaces.active.context = "RENDER"
    view3d = area_of(window, "VIEW_3D")
    space = view3d.spaces.active
    region = space.region_3d
    region.view_perspective = "PERSP"
    region.view_location = (0.0, 0.0, 1.0)
    region.view_rotation = Euler((math.radians(78), 0.0, math.radians(-24))).to_quaternion()
    region.view_distance = 6.5
    yield wait_s(2.0)

    # Render Properties with rt's panel.
    screenshot(window, shot)
    crop_save(shot, os.path.join(out, "blender_render_properties.png"), box(properties))

    # F12: rt renders into Blender's render view. Without a window manager (Xvfb) a new
    # render window is drawn before it gets its size, so the render takes the main window.
    bpy.context.preferences.view.render_display_type = "SCREEN"
    done = []
    bpy.app.handlers.render_complete.append(lambda *_: done.append(time.perf_counter()))
    bpy.app.handlers.render_cancel.append(lambda *_: done.append(None))
    began = time.perf_counter()
    with bpy.context.temp_override(window=window, screen=window.screen, area=view3d):
        bpy.ops.render.render("INVOKE_DEFAULT")
    yield wait_until(lambda: done, "F12 to finish")
    if done[0] is None:
        raise RuntimeError("the F12 render was cancelled")
    print(f"screenshots.py: F12 at 200x200, {settings.spp} spp: {done[0] - began:.1f} s")
    editor = area_of(window, "IMAGE_EDITOR")
    editor_region = next(r for r in editor.regions if r.type == "WINDOW")
    with bpy.context.temp_override(window=window, screen=window.screen, area=editor, region=editor_region):
        bpy.ops.image.view_zoom_ratio(ratio=2.0)
    yield wait_s(1.5)
    screenshot(window, shot)
    crop_save(shot, os.path.join(out, "blender_f12.png"), scale=2, bits=6)
    with bpy.context.temp_override(window=window, screen=window.screen, area=editor):
        bpy.ops.render.view_cancel()
    yield wait_s(1.0)

    # The viewport in Rendered shading: rt's view_update starts `rt watch --stream`, its
    # view_draw draws the frames.
    began = time.perf_counter()
    space.shading.type = "RENDERED"
    yield wait_until(lambda: log.count("first frame drawn"), "the viewport's first frame")
    yield wait_until(
        lambda: any(spp >= of for _, spp, of in log.frames_since(began)), "the viewport to reach its samples"
    )
    refined = [spp for _, spp, _ in log.frames_since(began)]
    print(f"screenshots.py: the viewport's frames refined through {refined} spp")
    yield wait_s(0.5)
    screenshot(window, shot)
    crop_save(shot, os.path.join(out, "blender_viewport.png"), scale=2, bits=6)

    # Orbits as a drag of the view makes them, each once its first frame is drawn.
    for step in range(6):
        seen = log.count("camera -> first frame drawn")
        region.view_rotation = Euler((math.radians(78), 0.0, math.radians(-24 + 3 * (step + 1)))).to_quaternion()
        view3d.tag_redraw()
        yield wait_until(lambda: log.count("camera -> first frame drawn") > seen, "a frame of the turned view")
        yield wait_s(0.3)
    # An object dragged: G on the selected sphere, the pointer moved in steps (each one
    # depsgraph update, as a hand's drag makes them), a click to confirm. Without event
    # simulation the script moves the sphere itself, as each of those updates does.
    for obj in bpy.context.view_layer.objects:
        obj.select_set(obj == sphere)
    bpy.context.view_layer.objects.active = sphere
    view_region = next(r for r in view3d.regions if r.type == "WINDOW")
    x, y = view_region.x + view_region.width // 2, view_region.y + view_region.height // 2
    simulate = bpy.app.use_event_simulate
    if simulate:
        window.event_simulate(type="MOUSEMOVE", value="NOTHING", x=x, y=y)
        window.event_simulate(type="G", value="PRESS", x=x, y=y)
        window.event_simulate(type="G", value="RELEASE", x=x, y=y)
        yield wait_s(0.5)
    start_x = sphere.location.x
    for step in range(6):
        seen = log.count("edit -> first frame drawn")
        if simulate:
            window.event_simulate(type="MOUSEMOVE", value="NOTHING", x=x - 8 * (step + 1), y=y)
        else:
            sphere.location.x -= 0.04
        yield wait_until(lambda: log.count("edit -> first frame drawn") > seen, "a frame of the dragged sphere")
        yield wait_s(0.3)
    if simulate:
        window.event_simulate(type="LEFTMOUSE", value="PRESS", x=x - 48, y=y)
        window.event_simulate(type="LEFTMOUSE", value="RELEASE", x=x - 48, y=y)
        yield wait_s(0.5)
    print(f"screenshots.py: the drag moved the sphere by {sphere.location.x - start_x:+.3f} m along x")

    # Through the scene camera: its depth of field, focused on the sphere.
    began = time.perf_counter()
    region.view_perspective = "CAMERA"
    view3d.tag_redraw()
    yield wait_until(
        lambda: any(spp >= of for _, spp, of in log.frames_since(began)), "the camera view to reach its samples"
    )
    yield wait_s(0.5)
    screenshot(window, shot)
    # The camera's frame, in the middle of the view.
    frame = (view3d.x + view3d.width // 5, view3d.y, view3d.width * 3 // 5, view3d.height)
    crop_save(shot, os.path.join(out, "blender_viewport_camera_dof.png"), frame, scale=2, bits=6)

    # Last, as it stays open: the Render Engine menu, over the Properties editor.
    region_window = next(r for r in properties.regions if r.type == "WINDOW")
    x, y = region_window.x + region_window.width // 2, region_window.y + region_window.height - 60
    window.cursor_warp(x, y)
    if bpy.app.use_event_simulate:  # then the window takes no pointer but the simulated one
        window.event_simulate(type="MOUSEMOVE", value="NOTHING", x=x, y=y)
    bpy.context.preferences.view.show_tooltips = False
    with bpy.context.temp_override(window=window, screen=window.screen, area=properties, region=region_window):
        bpy.ops.wm.context_menu_enum("INVOKE_DEFAULT", data_path="scene.render.engine")
    yield wait_s(1.0)
    if bpy.app.use_event_simulate:  # onto the menu's last item, rt
        window.event_simulate(type="MOUSEMOVE", value="NOTHING", x=x, y=y - 62)
    yield wait_s(1.0)
    screenshot(window, shot)
    crop_save(shot, os.path.join(out, "blender_engine_menu.png"), (x - 240, y - 200, 480, 260))
    report(log)


def report(log):
    latencies = {}
    for _, message in log.records:
        for kind in ("first frame drawn", "camera -> first frame drawn", "edit -> first frame drawn"):
            if message.startswith(kind):
                value = message[len(kind):].split()[0 if kind == "first frame drawn" else 1]
                seconds = float(value) if kind == "first frame drawn" else float(value) / 1e3
                latencies.setdefault(kind, []).append(seconds)
    for kind, values in latencies.items():
        print(
            f"screenshots.py: {kind}: median {statistics.median(values):.2f} s, "
            f"min {min(values):.2f} s, max {max(values):.2f} s over {len(values)}"
        )


def run(generator):
    """Steps through `generator` from a timer: each item it yields is a condition that
    must hold before it goes on. Quits Blender at the end, with status 1 on a failure."""
    pending = [None]

    def tick():
        try:
            if pending[0] is not None and not pending[0]():
                return POLL_S
            pending[0] = next(generator)
            return POLL_S
        except StopIteration:
            bpy.ops.wm.quit_blender()
        except Exception:
            traceback.print_exc()
            sys.stderr.flush()
            os._exit(1)
        return None

    bpy.app.timers.register(tick, first_interval=1.0)


def main():
    rt_binary, out = arguments()
    if not os.access(rt_binary, os.X_OK):
        sys.exit(f"screenshots.py: {rt_binary} is not an executable rt; build it or pass --rt PATH")
    os.makedirs(out, exist_ok=True)
    temp = tempfile.mkdtemp(prefix="rt-screenshots-")
    log = Timings()
    viewport_log = logging.getLogger("rt.viewport")
    viewport_log.setLevel(logging.DEBUG)
    viewport_log.addHandler(log)
    run(steps(rt_binary, out, temp, log))


main()
