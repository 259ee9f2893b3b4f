"""rt's settings in Blender: the add-on's preferences (where rt is, the cache folder),
the scene's render settings (`scene.rt_render`, laid out as Cycles lays out its own, each
turned into an `rt render` option by `rt_run.render_options`), and the view layer's passes
(`view_layer.rt`, beside Blender's own Z and Normal pass switches).
"""

import bpy

# The add-on's name, which its preferences are registered under.
ADDON = __package__ or __name__


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
    # Sampling
    spp: bpy.props.IntProperty(
        name="Samples", description="Samples per pixel of a final render (F12)", default=128, min=1, soft_max=16384
    )
    viewport_spp: bpy.props.IntProperty(
        name="Viewport Samples",
        description="Samples per pixel the viewport's Rendered mode refines to",
        default=64,
        min=1,
        soft_max=4096,
    )
    preview_spp: bpy.props.IntProperty(
        name="Preview Samples",
        description="Samples per pixel of material, world and light previews",
        default=16,
        min=1,
        soft_max=1024,
    )
    use_adaptive_sampling: bpy.props.BoolProperty(
        name="Noise Threshold",
        description="Pixels stop taking samples once their noise is below the threshold (adaptive sampling)",
        default=False,
    )
    adaptive_threshold: bpy.props.FloatProperty(
        name="Noise Threshold",
        description="Relative standard error of a pixel's mean luminance at which it stops (as Cycles' noise threshold)",
        default=0.01,
        min=0.0001,
        max=1.0,
        precision=4,
    )
    time_limit: bpy.props.FloatProperty(
        name="Time Limit",
        description="Stop after this many seconds with the samples taken so far (0: no limit)",
        default=0.0,
        min=0.0,
        subtype="TIME_ABSOLUTE",
        unit="TIME_ABSOLUTE",
    )
    seed: bpy.props.IntProperty(name="Seed", description="The same seed gives the same image", default=0, min=0)
    use_animated_seed: bpy.props.BoolProperty(
        name="Use Animated Seed",
        description="Each frame's seed is the seed plus the frame number, so that noise changes from frame to frame",
        default=False,
    )
    # Denoise
    use_denoising: bpy.props.BoolProperty(
        name="Denoise",
        description="Denoise F12 renders with Open Image Denoise, guided by albedo and normals "
        "(needs an rt built with the denoise feature)",
        default=False,
    )
    denoising_device: bpy.props.EnumProperty(
        name="Device",
        description="Where Open Image Denoise runs",
        items=(
            ("auto", "Automatic", "A CUDA GPU when Open Image Denoise has one, else the CPU"),
            ("cpu", "CPU", "The CPU"),
            ("cuda", "GPU (CUDA)", "A CUDA GPU; an error when there is none"),
        ),
        default="auto",
    )
    # Light paths
    max_bounces: bpy.props.IntProperty(
        name="Max Bounces",
        description="Bounces a path may take, counted as Cycles counts them (its Total): 0 lights only what "
        "the camera sees directly",
        default=12,
        min=0,
        max=1023,
    )
    sampling: bpy.props.EnumProperty(
        name="Light Sampling",
        description="How paths find light",
        items=(
            ("nee", "Next Event Estimation", "Light sampling with multiple importance sampling, as Cycles"),
            ("resampled", "Resampled", "No light sampling: resampled BSDF and sun directions"),
        ),
        default="nee",
    )
    clamp: bpy.props.FloatProperty(
        name="Clamp",
        description="Scale every sample down to at most this luminance: hides fireflies at the price of bias "
        "(0: off; rt has one clamp where Cycles has a direct and an indirect one)",
        default=0.0,
        min=0.0,
    )
    # Film
    film_exposure: bpy.props.FloatProperty(
        name="Exposure",
        description="Image brightness scale, in stops, applied to the render (as Cycles' Film > Exposure)",
        default=0.0,
        soft_min=-10.0,
        soft_max=10.0,
    )
    # Performance
    adapter: bpy.props.StringProperty(
        name="GPU",
        description="Part of the name of the GPU rt renders on (empty: rt picks a discrete GPU first)",
        default="",
    )
    bvh_quality: bpy.props.EnumProperty(
        name="BVH Quality",
        description="Build quality of the meshes' acceleration structures",
        items=(
            ("fastest", "Fastest", "Quickest to build, slowest to trace"),
            ("medium", "Medium", "rt's default"),
            ("slow", "Slow", "Spatial splits: slower to build, faster to trace"),
        ),
        default="medium",
    )
    progressive_every: bpy.props.FloatProperty(
        name="Refresh",
        description="Seconds between updates of the image while F12 renders",
        default=1.0,
        min=0.1,
        soft_max=10.0,
    )
    viewport_pixel_size: bpy.props.IntProperty(
        name="Viewport Pixel Size",
        description="The viewport renders one pixel of rt per this many screen pixels across (faster)",
        default=2,
        min=1,
        max=8,
    )


class RtViewLayerSettings(bpy.types.PropertyGroup):
    """Passes beside Blender's own switches (Z, Normal) that rt can write."""

    denoising_data: bpy.props.BoolProperty(
        name="Denoising Data",
        description="Denoising Albedo and Denoising Normal passes, as Open Image Denoise takes them",
        default=False,
    )
    sample_count: bpy.props.BoolProperty(
        name="Sample Count",
        description="How many samples each pixel took (with adaptive sampling they differ), as Cycles' "
        "Debug Sample Count",
        default=False,
    )
    noise: bpy.props.BoolProperty(
        name="Noise",
        description="Each pixel's standard error of its mean luminance",
        default=False,
    )


CLASSES = (RtPreferences, RtRenderSettings, RtViewLayerSettings)


def preferences():
    addon = bpy.context.preferences.addons.get(ADDON)
    return addon.preferences if addon is not None else None


def register():
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    bpy.types.Scene.rt_render = bpy.props.PointerProperty(type=RtRenderSettings)
    bpy.types.ViewLayer.rt = bpy.props.PointerProperty(type=RtViewLayerSettings)


def unregister():
    del bpy.types.ViewLayer.rt
    del bpy.types.Scene.rt_render
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
