"""rt in the 3D viewport's Rendered mode. The engine's view_update exports the scene into
a cache folder once and starts `rt watch SCENE --stream` as a child; after that each
view_update re-exports only what the depsgraph says changed (a moved object rewrites the
scene file, an edited mesh or material its asset) and tells rt which files to reload.
view_draw sends the viewport's camera (its view and projection matrices, and the scene
camera's depth of field when the viewport looks through it) and size, and draws the
latest frame rt sent as a texture, through Blender's colour management.

Timings go to the logger "rt.viewport" at debug level: how long the first frame took to
be drawn, and each camera change or edit until the first frame that shows it is drawn.
In Blender's Python console: `import logging; logging.basicConfig(level=logging.DEBUG)`.

The protocol (README.md, "Streaming to a client"): command lines to rt's standard input,
message lines and frames (a header line, then linear RGBA float32 pixels, rows from the
top) from its standard output, read here on a thread of their own.
"""

import collections
import logging
import math
import os
import re
import subprocess
import threading
import time

import bpy
import numpy as np

from . import rt_export

# A field of a message line: key=value or key="a quoted value".
FIELD = re.compile(r'(\w+)=("([^"]*)"|\S+)')
# How often a new frame is looked for, to redraw the viewport (seconds).
REDRAW_POLL_S = 1 / 30
# How long rt gets to quit before it is stopped.
QUIT_GRACE_S = 1.0

LOG = logging.getLogger("rt.viewport")


def fields(text):
    """{key: value} of a message line's key=value fields."""
    return {m.group(1): m.group(3) if m.group(3) is not None else m.group(2) for m in FIELD.finditer(text)}


def matrix_rows(matrix):
    """A 4x4 mathutils Matrix as the protocol's 16 numbers, row by row."""
    return ",".join(f"{matrix[r][c]:.9g}" for r in range(4) for c in range(4))


def camera_command(view_matrix, window_matrix, aperture=None):
    """The camera command for Blender's view matrix (world to view, Blender's Z-up world)
    and projection matrix: rt's world is Y up, so world points go through FROM_RT first.
    `aperture`: the protocol's depth-of-field fields (see `aperture_fields`)."""
    view = view_matrix @ rt_export.FROM_RT
    command = f"camera view={matrix_rows(view)} projection={matrix_rows(window_matrix)}"
    if aperture:
        command += " " + " ".join(f"{key}={value:.9g}" for key, value in aperture.items())
    return command


def aperture_fields(camera):
    """The depth of field of a camera object as Cycles renders it, as the camera command's
    fields, or None for a pinhole. The aperture goes as its radius: the viewport's
    projection matrix zooms with the view, the camera's own focal length does not."""
    data = camera.data
    if not data.dof.use_dof:
        return None
    dof = data.dof
    fstop = max(dof.aperture_fstop, 1e-5)  # Cycles clamps it so
    radius = (1.0 if data.type == "ORTHO" else data.lens * 1e-3) / (2.0 * fstop)
    return {
        "aperture": radius,
        "focus": max(rt_export.focus_distance(camera), 1e-5),
        # Cycles renders fewer than 3 blades as a round aperture.
        "blades": dof.aperture_blades if dof.aperture_blades >= 3 else 0,
        "blade_rotation": math.degrees(dof.aperture_rotation),
        "aperture_ratio": dof.aperture_ratio,
    }


class Frame:
    def __init__(self, header, pixels):
        self.header = header
        self.line = int(header["line"])
        self.spp = int(header["spp"])
        self.width, self.height = int(header["width"]), int(header["height"])
        # height x width x 4, rows from the top.
        self.pixels = pixels


class StreamClient:
    """`rt watch SCENE --stream` as a child process."""

    def __init__(self, command):
        try:
            self.process = subprocess.Popen(
                command, stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE
            )
        except OSError as e:
            raise OSError(f"cannot run {command[0]!r} ({e}): set the path to rt in the add-on's preferences") from e
        self.lines_sent = 0
        self.lock = threading.Lock()
        self.hello = None
        self.frame = None
        self.frames = 0  # frames received so far
        self.messages = collections.deque(maxlen=200)  # reload and error lines, oldest first
        self.stderr = collections.deque(maxlen=20)
        self.closed = False
        threading.Thread(target=self._read, daemon=True).start()
        threading.Thread(target=self._read_stderr, daemon=True).start()

    def _read(self):
        out = self.process.stdout
        for raw in iter(out.readline, b""):
            line = raw.decode("utf-8", "replace").rstrip("\n")
            if line.startswith("frame "):
                header = fields(line)
                size = int(header.get("bytes", "0"))
                data = out.read(size)
                if len(data) != size:
                    break
                width, height = int(header["width"]), int(header["height"])
                pixels = np.frombuffer(data, dtype="<f4").reshape(height, width, 4)
                with self.lock:
                    self.frame = Frame(header, pixels)
                    self.frames += 1
            elif line.startswith("hello "):
                self.hello = fields(line)
            else:
                with self.lock:
                    self.messages.append(line)
        self.closed = True

    def _read_stderr(self):
        for raw in iter(self.process.stderr.readline, b""):
            self.stderr.append(raw.decode("utf-8", "replace").rstrip("\n"))

    def send(self, line):
        """Sends a command; returns its line number, or None if rt is gone."""
        if self.closed:
            return None
        try:
            self.process.stdin.write(line.encode("utf-8") + b"\n")
            self.process.stdin.flush()
        except (OSError, ValueError):
            self.closed = True
            return None
        self.lines_sent += 1
        return self.lines_sent

    def latest(self):
        """(the latest frame or None, how many frames came so far)."""
        with self.lock:
            return self.frame, self.frames

    def take_messages(self):
        with self.lock:
            messages = list(self.messages)
            self.messages.clear()
        return messages

    def close(self):
        self.send("quit")
        try:
            self.process.wait(QUIT_GRACE_S)
        except subprocess.TimeoutExpired:
            self.process.terminate()
            self.process.wait()
        for pipe in (self.process.stdin, self.process.stdout, self.process.stderr):
            try:
                pipe.close()
            except OSError:
                pass


def stream_command(binary, scene_path, settings):
    return [
        binary,
        "watch",
        scene_path,
        "--stream",
        "--spp",
        str(settings.viewport_spp),
    ]


class Viewport:
    """One viewport's rt: the export it streams, the child, the texture of its last frame."""

    def __init__(self, binary, folder):
        self.binary = binary
        self.folder = folder
        self.assets = os.path.join(folder, "assets")
        self.scene_path = os.path.join(folder, "scene.toml")
        self.export = None
        self.client = None
        self.sent = {}  # what the last camera, size and spp commands said
        self.texture = None
        self.texture_frame = 0
        self.reloads = []  # (command line, files) of each reload sent, for tests
        self.started = None  # when the first update began (perf_counter)
        # What waits to be seen: {kind: (command line, when it began, a note)}; a newer
        # change of a kind replaces the older, which no frame will show on its own.
        self.waiting = {}
        # The line of the first size and camera commands: rt's frames before it show the
        # exported camera at the render size, not this view, and are not drawn.
        self.view_line = None

    def update(self, depsgraph):
        """view_update: the first time, export everything and start rt; then re-export what
        the depsgraph's updates changed and have rt reload the files that were rewritten."""
        began = time.perf_counter()
        scene = depsgraph.scene
        if self.export is None:
            self.started = began
            os.makedirs(self.folder, exist_ok=True)
            self.export = rt_export.export_scene(scene, self.assets, self.scene_path, depsgraph=depsgraph)
            self.client = StreamClient(stream_command(self.binary, self.scene_path, scene.rt_render))
            self.sent["spp"] = scene.rt_render.viewport_spp
            LOG.debug("exported the scene and started rt in %.0f ms", 1e3 * (time.perf_counter() - began))
            return []
        self.send_once("spp", f"spp {scene.rt_render.viewport_spp}")
        changes = rt_export.classify_updates(depsgraph.updates)
        if not rt_export.any_change(changes):
            return []
        tracked = {"objects": set(), "meshes": set(), "materials": set()}
        rt_export.add_changes(tracked, changes)
        only = rt_export.changed_objects(scene, tracked)
        self.export = rt_export.export_scene(scene, self.assets, self.scene_path, only, self.export, depsgraph=depsgraph)
        written = [os.path.relpath(path, self.folder).replace(os.sep, "/") for path in self.export.written]
        if written:
            line = self.client.send("reload " + " ".join(written))
            self.reloads.append((line, written))
            exported_ms = 1e3 * (time.perf_counter() - began)
            self.waiting["edit"] = (line, began, f"export {exported_ms:.0f} ms, {' '.join(written)}")
            # A scene file whose camera changed (the camera object moved) takes the place
            # of the camera rt was sent; the viewport still looks through its own.
            if "camera" in self.sent:
                self.client.send(self.sent["camera"])
        return written

    def send_once(self, key, command):
        """Sends `command` unless it is the last one sent for `key`; returns its line
        number, or None if nothing was sent."""
        if self.client is not None and self.sent.get(key) != command:
            line = self.client.send(command)
            if line is not None:
                self.sent[key] = command
            return line
        return None

    def view(self, view_matrix, window_matrix, width, height, pixel_size=1, aperture=None):
        """The viewport's camera and size, sent when they change."""
        began = time.perf_counter()
        size = self.send_once("size", f"size {max(1, width // pixel_size)} {max(1, height // pixel_size)}")
        camera = self.send_once("camera", camera_command(view_matrix, window_matrix, aperture))
        if camera is not None:
            LOG.debug("camera sent: line %d", camera)
        if self.view_line is None and (size or camera):
            self.view_line = max(size or 0, camera or 0)
        if camera is not None and self.texture is not None:
            self.waiting["camera"] = (camera, began, "")
        elif size is not None and self.texture is not None:
            self.waiting["size"] = (size, began, f"{width // pixel_size}x{height // pixel_size}")

    def shows_view(self, frame):
        """Whether `frame` shows this viewport's view: rt's frames from before its first
        size and camera commands show the exported camera at the render size."""
        return frame.line >= (self.view_line or 0)

    def draw(self, engine, context, depsgraph):
        """view_draw: the viewport's camera and size to rt, its latest frame to the screen."""
        import gpu
        from gpu_extras.presets import draw_texture_2d

        region, region_data = context.region, context.region_data
        scene = depsgraph.scene
        # Looking through the scene camera, the viewport shows its depth of field, as Cycles does.
        through_camera = region_data.view_perspective == "CAMERA" and scene.camera is not None
        self.view(
            region_data.view_matrix,
            region_data.window_matrix,
            region.width,
            region.height,
            scene.rt_render.viewport_pixel_size,
            aperture_fields(scene.camera) if through_camera and scene.camera.type == "CAMERA" else None,
        )
        frame, count = self.client.latest() if self.client is not None else (None, 0)
        if frame is None or not self.shows_view(frame):
            self.show_if_stopped(engine)
            return
        if count != self.texture_frame:
            # Blender's textures start with the bottom row.
            pixels = np.ascontiguousarray(frame.pixels[::-1]).ravel()
            buffer = gpu.types.Buffer("FLOAT", pixels.size, pixels)
            self.texture = gpu.types.GPUTexture((frame.width, frame.height), format="RGBA16F", data=buffer)
            new, first = True, self.texture_frame == 0
            self.texture_frame = count
        else:
            new = first = False
        gpu.state.blend_set("ALPHA_PREMULT")
        engine.bind_display_space_shader(scene)
        draw_texture_2d(self.texture, (0, 0), region.width, region.height)
        engine.unbind_display_space_shader()
        gpu.state.blend_set("NONE")
        engine.update_stats("", f"rt: {frame.spp}/{scene.rt_render.viewport_spp} spp")
        if new:
            self.drawn(frame, first, scene.rt_render.viewport_spp)
        self.show_if_stopped(engine)

    def drawn(self, frame, first, spp):
        """Logs a new frame drawn, and how long what it shows took to reach the screen."""
        now = time.perf_counter()
        LOG.debug("frame drawn: line %d, %d/%d spp", frame.line, frame.spp, spp)
        if first and self.started is not None:
            LOG.debug(
                "first frame drawn %.2f s after the viewport started (%dx%d, %d spp)",
                now - self.started, frame.width, frame.height, frame.spp,
            )
        for kind, (line, began, note) in list(self.waiting.items()):
            if frame.line >= line:
                del self.waiting[kind]
                LOG.debug(
                    "%s -> first frame drawn: %.0f ms (%dx%d, %d spp%s)",
                    kind, 1e3 * (now - began), frame.width, frame.height, frame.spp, f"; {note}" if note else "",
                )

    def show_if_stopped(self, engine):
        """rt's last words in the status bar, once it has stopped."""
        if self.client is not None and self.client.closed:
            engine.update_stats("", f"rt stopped: {self.client.stderr[-1] if self.client.stderr else 'no message'}")

    def close(self):
        if self.client is not None:
            self.client.close()
            self.client = None


def keep_redrawing(engine, viewport):
    """A timer that redraws the viewport whenever rt sent a new frame; it ends with the
    engine (Blender frees it when the viewport leaves Rendered mode)."""
    drawn = [0]

    def poll():
        client = viewport.client
        if client is None:
            return None
        _, count = client.latest()
        try:
            if count != drawn[0]:
                drawn[0] = count
                engine.tag_redraw()
            else:
                engine.is_preview  # raises once Blender has freed the engine
        except ReferenceError:
            viewport.close()
            return None
        return REDRAW_POLL_S

    bpy.app.timers.register(poll, first_interval=REDRAW_POLL_S)
