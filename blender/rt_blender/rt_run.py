"""Running the `rt` binary for the engine: where it is, the cache folder, the options a
scene's render settings make, and `rt render ... --progress json` as a child whose
progress, snapshot, warning and error events come back as they happen. A stop ends rt
with SIGTERM (it removes its temporaries and exits 143), SIGKILL after a grace period.

Where `rt` is: the add-on preference, else the environment variable RT_BINARY, else `rt`
on PATH; if it cannot be run, the error says where to set it. The cache: the add-on
preference, else a folder under the system temp dir, one subfolder per .blend.
"""

import json
import os
import queue
import shutil
import subprocess
import tempfile
import threading

import bpy
import numpy as np

from . import rt_export, rt_settings

# How long a stopped rt gets to clean up before it is killed.
STOP_GRACE_S = 1.0


class RtError(Exception):
    """rt failed: the message is rt's own (or why it could not run)."""


class RtCancelled(Exception):
    """The render was stopped before rt finished; the argument is rt's exit status
    (143 once rt has removed its temporaries, -15 if the signal came before it had any)."""


def rt_binary():
    prefs = rt_settings.preferences()
    if prefs is not None and prefs.rt_binary:
        return bpy.path.abspath(prefs.rt_binary)
    return os.environ.get("RT_BINARY") or "rt"


def check_binary(binary):
    """An RtError that says what to do when `binary` is neither a file nor on PATH."""
    if os.path.isfile(binary) or shutil.which(binary):
        return
    raise RtError(
        f"cannot find the rt binary {binary!r}: set its path in Edit > Preferences > Add-ons > rt, "
        "or the environment variable RT_BINARY, or put rt on PATH (cargo install --path . in rt's repository)"
    )


def cache_dir():
    prefs = rt_settings.preferences()
    base = bpy.path.abspath(prefs.cache_dir) if prefs is not None and prefs.cache_dir else tempfile.gettempdir()
    stem = bpy.path.display_name_from_filepath(bpy.data.filepath) or "untitled"
    return os.path.join(base, f"rt-{rt_export.sanitize(stem)}")


def frame_seed(settings, frame):
    return settings.seed + frame if settings.use_animated_seed else settings.seed


def render_options(settings, frame=0, preview=False):
    """`rt render` options for a scene's render settings (`scene.rt_render`). rt's
    max_bounces counts the surfaces a path shades; Cycles' Max Bounces one fewer."""
    spp = settings.preview_spp if preview else settings.spp
    options = ["--spp", str(spp), "--max-bounces", str(settings.max_bounces + 1)]
    options += ["--sampling", settings.sampling, "--seed", str(frame_seed(settings, frame))]
    options += ["--quality", settings.bvh_quality]
    if preview:
        return options
    if settings.use_adaptive_sampling:
        options += ["--noise-threshold", f"{settings.adaptive_threshold:.7g}"]
    if settings.time_limit > 0:
        options += ["--time-limit", f"{settings.time_limit:.7g}"]
    if settings.clamp > 0:
        options += ["--clamp", f"{settings.clamp:.7g}"]
    if settings.use_denoising:
        options += ["--denoise", "--denoise-device", settings.denoising_device]
    if settings.adapter:
        options += ["--adapter", settings.adapter]
    return options


def stop(process):
    """SIGTERM, then SIGKILL if rt has not exited within STOP_GRACE_S."""
    process.terminate()
    try:
        process.wait(STOP_GRACE_S)
    except subprocess.TimeoutExpired:
        process.kill()
        process.wait()


def start(command):
    try:
        return subprocess.Popen(
            command, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True
        )
    except OSError as e:
        raise RtError(f"cannot run {command[0]!r} ({e}): set the path to rt in the add-on's preferences") from e


def events(process):
    """A queue of rt's stderr lines (None at the end), filled by a thread of its own."""
    lines = queue.Queue()

    def read():
        for line in process.stderr:
            lines.put(line)
        lines.put(None)

    threading.Thread(target=read, daemon=True).start()
    return lines


def run_rt(command, on_progress=None, should_stop=lambda: False, poll_s=0.05, on_snapshot=None):
    """Runs `rt render ... --progress json`, calling `on_progress(event)` for each
    progress event and `on_snapshot(event)` for each snapshot, and returns (done event,
    warning messages). Raises RtError with rt's message if it fails, RtCancelled (after
    stopping it) once `should_stop()`."""
    process = start(command)
    lines = events(process)
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
            elif kind == "snapshot" and on_snapshot is not None:
                on_snapshot(event)
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


def exr_pixels(path, width, height):
    """An EXR rt wrote as width*height RGBA rows, bottom row first (as a Render Result's
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
