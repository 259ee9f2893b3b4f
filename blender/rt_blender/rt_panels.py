"""rt's panels in Blender, laid out as Cycles lays out its own (Sampling, Denoise, Light
Paths, Film, Performance; the view layer's Passes), and Blender's and Cycles' panels that
describe what rt renders, shown with rt picked by adding rt to their COMPAT_ENGINES: the
material's Surface and Volume (the Shader Editor shows the node trees too, see
`RtRenderEngine.bl_use_shading_nodes_custom`), the world's Surface, the light's settings,
the camera's Lens, Camera and Depth of Field, Format, Output, Frame Range, Color
Management, Motion Blur (the render's and each object's), and every panel that edits
geometry, particles or physics whatever the engine. Panels for what rt does not render
(light probes, bake, the shutter curve, grease
pencil and Freestyle lines, stereoscopy, volume objects, Cycles' own integrator
settings) stay hidden under rt.
"""

import bpy

from . import rt_shader_nodes

ENGINE = "RT"

# Cycles' panels that describe what rt renders as Cycles does.
CYCLES_PANELS = (
    "CYCLES_PT_context_material",
    "CYCLES_MATERIAL_PT_preview",
    "CYCLES_MATERIAL_PT_surface",
    "CYCLES_MATERIAL_PT_volume",
    "CYCLES_WORLD_PT_preview",
    "CYCLES_WORLD_PT_surface",
    "CYCLES_LIGHT_PT_preview",
    "CYCLES_LIGHT_PT_light",
    "CYCLES_LIGHT_PT_beam_shape",
    "CYCLES_CAMERA_PT_dof",
    "CYCLES_CAMERA_PT_dof_aperture",
    "CYCLES_PT_post_processing",
    "CYCLES_RENDER_PT_simplify",
    "CYCLES_RENDER_PT_motion_blur",
    "CYCLES_OBJECT_PT_motion_blur",
)
# Parts of the names of Blender's own panels for what rt does not render.
NOT_RENDERED = ("lightprobe", "stereoscopy", "output_views", "freestyle", "gpencil", "grease_pencil", "volume_render")


def shown_under_rt(name, cls):
    """Whether Blender's panel `name` shows with rt picked: Cycles' own from the list,
    engine-independent ones (those Cycles shows too) unless about what rt does not render."""
    engines = getattr(cls, "COMPAT_ENGINES", None)
    if not isinstance(engines, set) or "CYCLES" not in engines:
        return False
    if name in CYCLES_PANELS:
        return True
    own = name.startswith(("CYCLES_", "NODE_CYCLES_", "EEVEE_"))
    return not own and not any(part in name.lower() for part in NOT_RENDERED)


def compatible_panels():
    """Blender's and Cycles' panel classes that show under rt."""
    found = []
    for name in dir(bpy.types):
        cls = getattr(bpy.types, name, None)
        if isinstance(cls, type) and issubclass(cls, bpy.types.Panel) and shown_under_rt(name, cls):
            found.append(cls)
    return found


class RtPanel:
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "render"
    COMPAT_ENGINES = {ENGINE}

    @classmethod
    def poll(cls, context):
        return context.engine in cls.COMPAT_ENGINES


class RT_RENDER_PT_sampling(RtPanel, bpy.types.Panel):
    bl_label = "Sampling"

    def draw(self, context):
        pass


class RT_RENDER_PT_sampling_viewport(RtPanel, bpy.types.Panel):
    bl_label = "Viewport"
    bl_parent_id = "RT_RENDER_PT_sampling"

    def draw(self, context):
        settings = context.scene.rt_render
        layout = self.layout
        layout.use_property_split = True
        layout.prop(settings, "viewport_spp", text="Max Samples")
        layout.prop(settings, "viewport_pixel_size", text="Pixel Size")


class RT_RENDER_PT_sampling_render(RtPanel, bpy.types.Panel):
    bl_label = "Render"
    bl_parent_id = "RT_RENDER_PT_sampling"

    def draw(self, context):
        settings = context.scene.rt_render
        layout = self.layout
        layout.use_property_split = True
        heading = layout.column(align=True, heading="Noise Threshold")
        row = heading.row(align=True)
        row.prop(settings, "use_adaptive_sampling", text="")
        sub = row.row()
        sub.active = settings.use_adaptive_sampling
        sub.prop(settings, "adaptive_threshold", text="")
        layout.prop(settings, "spp", text="Max Samples")
        layout.prop(settings, "time_limit")
        layout.prop(settings, "preview_spp", text="Preview Samples")


class RT_RENDER_PT_sampling_denoise(RtPanel, bpy.types.Panel):
    bl_label = "Denoise"
    bl_parent_id = "RT_RENDER_PT_sampling_render"

    def draw_header(self, context):
        self.layout.prop(context.scene.rt_render, "use_denoising", text="")

    def draw(self, context):
        settings = context.scene.rt_render
        layout = self.layout
        layout.use_property_split = True
        layout.active = settings.use_denoising
        layout.label(text="Open Image Denoise, guided by albedo and normal")
        layout.prop(settings, "denoising_device")


class RT_RENDER_PT_sampling_advanced(RtPanel, bpy.types.Panel):
    bl_label = "Advanced"
    bl_parent_id = "RT_RENDER_PT_sampling"
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context):
        settings = context.scene.rt_render
        layout = self.layout
        layout.use_property_split = True
        row = layout.row(align=True)
        row.prop(settings, "seed")
        row.prop(settings, "use_animated_seed", text="", icon="TIME")
        layout.prop(settings, "sampling")


class RT_RENDER_PT_light_paths(RtPanel, bpy.types.Panel):
    bl_label = "Light Paths"
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context):
        settings = context.scene.rt_render
        layout = self.layout
        layout.use_property_split = True
        layout.prop(settings, "max_bounces", text="Total")
        layout.label(text="rt has one bounce limit for every kind of bounce", icon="INFO")
        layout.prop(settings, "clamp")


class RT_RENDER_PT_film(RtPanel, bpy.types.Panel):
    bl_label = "Film"
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.prop(context.scene.rt_render, "film_exposure")
        layout.prop(context.scene.render, "film_transparent", text="Transparent")
        cycles = getattr(context.scene, "cycles", None)
        if cycles is not None:
            # Cycles' own settings, which rt follows as Cycles does.
            column = layout.column()
            column.active = context.scene.render.film_transparent
            column.prop(cycles, "film_transparent_glass", text="Transparent Glass")
            sub = column.column()
            sub.active = context.scene.render.film_transparent and cycles.film_transparent_glass
            sub.prop(cycles, "film_transparent_roughness", text="Roughness Threshold")
        layout.label(text="Pixel filter: box, one pixel wide", icon="INFO")


class RT_RENDER_PT_performance(RtPanel, bpy.types.Panel):
    bl_label = "Performance"
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context):
        settings = context.scene.rt_render
        layout = self.layout
        layout.use_property_split = True
        layout.prop(settings, "adapter")
        layout.prop(settings, "bvh_quality")
        layout.prop(settings, "progressive_every")


class RT_RENDER_PT_passes(RtPanel, bpy.types.Panel):
    bl_label = "Passes"
    bl_context = "view_layer"

    def draw(self, context):
        layer = context.view_layer
        layout = self.layout
        layout.use_property_split = True
        column = layout.column(heading="Include", align=True)
        column.prop(layer, "use_pass_combined")
        column.prop(layer, "use_pass_z")
        column.prop(layer, "use_pass_normal")
        column.prop(layer, "use_pass_position")
        column.prop(layer, "use_pass_emit", text="Emission")
        column.prop(layer, "use_pass_diffuse_color", text="Diffuse Color")
        column.prop(layer.rt, "denoising_data")
        column.prop(layer.rt, "sample_count")
        column.prop(layer.rt, "noise")


class RT_MATERIAL_PT_notes(RtPanel, bpy.types.Panel):
    """What rt renders differently from Cycles in this material, as the last export found it."""

    bl_label = "rt"
    bl_context = "material"

    @classmethod
    def poll(cls, context):
        return super().poll(context) and context.material is not None

    def draw(self, context):
        notes = rt_shader_nodes.NOTES.get(context.material.name)
        if not notes:
            self.layout.label(text="Rendered as Cycles renders it" if notes is not None else "Not exported yet")
            return
        self.layout.label(text="rt renders this material approximately:", icon="ERROR")
        for note in notes:
            self.layout.label(text=note)


CLASSES = (
    RT_RENDER_PT_sampling,
    RT_RENDER_PT_sampling_render,
    RT_RENDER_PT_sampling_denoise,
    RT_RENDER_PT_sampling_viewport,
    RT_RENDER_PT_sampling_advanced,
    RT_RENDER_PT_light_paths,
    RT_RENDER_PT_film,
    RT_RENDER_PT_performance,
    RT_RENDER_PT_passes,
    RT_MATERIAL_PT_notes,
)


def register():
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    for panel in compatible_panels():
        # Cycles' panels share one set through their base class: each gets its own, or
        # adding rt to one would show them all.
        panel.COMPAT_ENGINES = set(panel.COMPAT_ENGINES) | {ENGINE}


def unregister():
    for panel in compatible_panels():
        panel.COMPAT_ENGINES = set(panel.COMPAT_ENGINES) - {ENGINE}
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
