"""The render passes rt makes, named and laid out as Cycles names them, so that the
compositor, the image editor and multilayer EXR output see them as they would see
Cycles' own: Depth (Z), Normal, Position, Emission, Diffuse Color, Denoising Normal and Albedo, Debug
Sample Count, and rt's Noise. rt writes each as a plain OpenEXR (`rt render --aov-files DIR`); here they are
read, turned into Blender's conventions (Z-up world normals and positions, depth along the view axis
as Cycles' camera_z_depth, 1e10 where nothing was hit), and put in the Render Result.
"""

import math

import numpy as np

# Cycles' depth where a camera ray met nothing.
NO_HIT_DEPTH = 1.0e10


class Pass:
    def __init__(self, name, chan_id, kind, aov, enabled):
        self.name, self.chan_id, self.kind, self.aov, self.enabled = name, chan_id, kind, aov, enabled

    @property
    def channels(self):
        return len(self.chan_id)


PASSES = (
    Pass("Depth", "Z", "VALUE", "depth", lambda layer: layer.use_pass_z),
    Pass("Normal", "XYZ", "VECTOR", "normal", lambda layer: layer.use_pass_normal),
    Pass("Position", "XYZ", "VECTOR", "position", lambda layer: layer.use_pass_position),
    Pass("Emission", "RGB", "COLOR", "emission", lambda layer: layer.use_pass_emit),
    Pass("Diffuse Color", "RGB", "COLOR", "diffuse_color", lambda layer: layer.use_pass_diffuse_color),
    Pass("Denoising Normal", "XYZ", "VECTOR", "normal", lambda layer: layer.rt.denoising_data),
    Pass("Denoising Albedo", "RGB", "COLOR", "albedo", lambda layer: layer.rt.denoising_data),
    Pass("Debug Sample Count", "X", "VALUE", "samples", lambda layer: layer.rt.sample_count),
    Pass("Noise", "X", "VALUE", "error", lambda layer: layer.rt.noise),
)


def enabled(view_layer):
    """The passes `view_layer` asks for, besides Combined."""
    return [p for p in PASSES if p.enabled(view_layer)]


def register_passes(engine, scene, view_layer):
    """RenderEngine.update_render_passes: Combined and every pass the layer asks for."""
    engine.register_pass(scene, view_layer, "Combined", 4, "RGBA", "COLOR")
    for p in enabled(view_layer):
        engine.register_pass(scene, view_layer, p.name, p.channels, p.chan_id, p.kind)


def blender_vectors(rgb):
    """rt's world is Y up, Blender's Z up: rt's (x, y, z) is Blender's (x, -z, y)."""
    return np.stack([rgb[:, 0], -rgb[:, 2], rgb[:, 1]], axis=1)


def view_depth(camera, scene, width, height):
    """(scale per pixel, bottom row first; offset): the depth along the camera's view axis
    is rt's depth AOV (the distance from where the camera ray starts, on the near clip
    plane) times the scale plus the offset. For a perspective camera the scale is the
    cosine between the ray through the pixel's centre and the view axis; orthographic
    rays run along the axis; a panorama's depth is the distance itself, as in Cycles."""
    data = camera.data
    ones = np.ones(width * height, dtype=np.float32)
    if data.type != "PERSP":
        return ones, data.clip_start
    # The view frame's corners in camera space (sensor fit and shift included), z < 0.
    corners = [tuple(v) for v in data.view_frame(scene=scene)]
    xs, ys = [c[0] for c in corners], [c[1] for c in corners]
    depth = -corners[0][2]
    u = (np.arange(width, dtype=np.float64) + 0.5) / width
    v = (np.arange(height, dtype=np.float64) + 0.5) / height
    x = min(xs) + u * (max(xs) - min(xs))
    y = min(ys) + v * (max(ys) - min(ys))
    gx, gy = np.meshgrid(x, y)
    cos = depth / np.sqrt(gx * gx + gy * gy + depth * depth)
    return cos.astype(np.float32).reshape(-1), data.clip_start


def pass_pixels(p, rgb, depth_scale, depth_offset):
    """A pass's values (bottom row first, `p.channels` per pixel) from its AOV image's RGB;
    the depth through `view_depth`'s scale and offset."""
    if p.aov == "depth":
        distance = rgb[:, 0]
        z = np.where(np.isfinite(distance), distance * depth_scale + depth_offset, NO_HIT_DEPTH)
        return z.reshape(-1, 1)
    if p.aov in ("normal", "position"):
        return blender_vectors(rgb)
    if p.channels == 1:
        return rgb[:, :1]
    return rgb


def exposure_scale(settings):
    return math.pow(2.0, settings.film_exposure)
