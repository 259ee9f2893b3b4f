#!/usr/bin/env python3
"""Rows of Principled BSDF spheres under a uniform world (or a sun, for the rows named in
SUNLIT), one row per swept input, rendered with Cycles and exported with blender/rt_export.py, for `tests/cycles_principled.rs`:

    /work/main/.venv-bpy/bin/python tests/cycles/make_principled_refs.py [--spp 1024] [NAME...]

For each NAME it writes `tests/cycles/principled_NAME.exr` (Cycles, linear, 32-bit) and
`tests/cycles/scenes/principled_NAME/` (the exported assets and `scene.toml`).

Cycles is set up as a reference (see make_texture_refs.py) with the Principled BSDF's
default distribution, Multiscatter GGX: rt's `[render] microfacet = "multiscatter"`.
"""

import argparse
import math

import bpy

import cycles_reference as cycles
import make_texture_refs as refs

WIDTH, HEIGHT = 160, 32
STEPS = [0.0, 0.25, 0.5, 0.75, 1.0]
TINTS = [(1.0, 1.0, 1.0), (1.0, 0.4, 0.4), (0.4, 1.0, 0.4), (0.4, 0.4, 1.0), (1.0, 0.8, 0.2)]
# The sheen shows on a dark base.
SHEEN_BASE = {"Base Color": (0.05, 0.05, 0.08), "Roughness": 0.5}
SHEEN_ROUGHNESS_BASE = {**SHEEN_BASE, "Sheen Weight": 1.0, "Sheen Tint": (1.0, 0.8, 0.6)}
ANISOTROPIC_METAL = {"Base Color": (0.95, 0.75, 0.5), "Metallic": 1.0, "Roughness": 0.4}
# Thin films from none to 1 µm: on a dark dielectric (the film's colours show in its specular
# layer), on a metal (Cycles 5.0 puts the film over its F82 conductor too) and on glass.
THICKNESSES = [0.0, 250.0, 500.0, 750.0, 1000.0]
FILM_DIELECTRIC = {"Base Color": (0.1, 0.1, 0.12), "Roughness": 0.2, "Thin Film IOR": 1.33}
FILM_METAL = {"Base Color": (0.9, 0.75, 0.5), "Metallic": 1.0, "Roughness": 0.3, "Thin Film IOR": 1.6}
FILM_GLASS = {"Base Color": (1.0, 1.0, 1.0), "Transmission Weight": 1.0, "IOR": 1.5, "Roughness": 0.15,
              "Thin Film IOR": 1.33}
# Diffuse Roughness (Cycles' energy-preserving Oren-Nayar) on a coloured base under the
# default specular layer (Specular IOR Level 0.5).
ROUGH_DIFFUSE = {"Base Color": (0.8, 0.35, 0.2), "Roughness": 0.5}

# Diffuse (no specular layer, smooth and rough), the default dielectric, a metal and a
# coated base: each lobe where a coarse sphere's shading normals meet its terminator.
TERMINATOR = [
    {"Specular IOR Level": 0.0, "Roughness": 1.0},
    {"Specular IOR Level": 0.0, "Roughness": 1.0, "Diffuse Roughness": 1.0},
    {"Roughness": 0.3},
    {"Metallic": 1.0, "Roughness": 0.3},
    {"Roughness": 0.5, "Coat Weight": 1.0, "Coat Roughness": 0.1},
]

# Delta lobes: a mirror metal, a smooth dielectric, smooth glass, a smooth coat over a
# rough base, and a Lambertian base for comparison.
MIRRORS = [
    {"Metallic": 1.0, "Roughness": 0.0},
    {"Roughness": 0.0},
    {"Transmission Weight": 1.0, "Roughness": 0.0, "IOR": 1.45},
    {"Roughness": 0.5, "Coat Weight": 1.0, "Coat Roughness": 0.0},
    {"Specular IOR Level": 0.0, "Roughness": 1.0},
]

# Roughness under a sun from 0.2: a sharp highlight of a 0.53° sun lights the neighbouring
# spheres by rare bright paths (a sphere's glint seen in the next one), whose noise the
# standard errors underestimate; from 0.1 (and a coat of 0.1), blocks facing a neighbour
# were 1-3% off in both directions, at 5-11 σ, at any sample count.
SUN_STEPS = [0.2, 0.4, 0.6, 0.8, 1.0]

# Glossy lobes whose normals Bump Map Correction bends: sharp and less sharp metal and dielectric, and a coat.
GLOSSY_TERMINATOR = [
    {"Metallic": 1.0, "Roughness": 0.05},
    {"Metallic": 1.0, "Roughness": 0.15},
    {"Roughness": 0.05},
    {"Roughness": 0.15},
    {"Roughness": 0.5, "Coat Weight": 1.0, "Coat Roughness": 0.05},
]

# Inputs that a row under the white world and its row under a sun share.
DIELECTRIC = {"Base Color": (0.8, 0.3, 0.2)}
METAL = {"Base Color": (0.95, 0.65, 0.3), "Metallic": 1.0}
IOR_ROW = ({"Base Color": (0.2, 0.4, 0.8), "Roughness": 0.3}, [{"IOR": i} for i in (1.05, 1.3, 1.5, 2.0, 3.0)])
SPECULAR_TINT_ROW = ({"Base Color": (0.1, 0.1, 0.1), "Roughness": 0.3}, [{"Specular Tint": t} for t in TINTS])
METAL_TINT_ROW = ({"Base Color": (0.9, 0.85, 0.8), "Metallic": 1.0, "Roughness": 0.3},
                  [{"Specular Tint": t} for t in TINTS])
GLASS = {"Base Color": (0.9, 0.95, 1.0), "Transmission Weight": 1.0, "IOR": 1.45}
COATED = {"Base Color": (0.1, 0.3, 0.8), "Roughness": 0.6, "Coat Weight": 1.0, "Coat Tint": (0.9, 0.7, 0.5)}

# Blender's Metallic BSDF: F82 tint (the Principled's metal) and physical conductors of
# measured complex indices (copper, gold, aluminium, silver, chromium).
METALLIC_F82 = [
    {"Base Color": (0.95, 0.64, 0.54), "Edge Tint": (1.0, 0.9, 0.8), "Roughness": 0.1},
    {"Base Color": (1.0, 0.78, 0.34), "Edge Tint": (0.9, 0.7, 0.4), "Roughness": 0.3},
    {"Base Color": (0.91, 0.92, 0.92), "Edge Tint": (0.3, 0.5, 0.9), "Roughness": 0.5},
    {"Base Color": (0.55, 0.56, 0.55), "Edge Tint": (0.6, 0.6, 0.6), "Roughness": 0.7},
    {"Base Color": (0.8, 0.3, 0.2), "Edge Tint": (1.0, 1.0, 1.0), "Roughness": 1.0},
]
CONDUCTORS = [
    {"IOR": (0.27, 0.68, 1.22), "Extinction": (3.61, 2.63, 2.29)},
    {"IOR": (0.18, 0.42, 1.37), "Extinction": (3.42, 2.35, 1.77)},
    {"IOR": (1.50, 0.98, 0.62), "Extinction": (7.60, 6.60, 5.40)},
    {"IOR": (0.16, 0.14, 0.13), "Extinction": (4.00, 3.20, 2.40)},
    {"IOR": (3.20, 3.10, 2.30), "Extinction": (3.30, 3.30, 3.10)},
]

SHEEN_BSDF = [
    {"Color": (1.0, 1.0, 1.0), "Roughness": 0.1},
    {"Color": (1.0, 0.6, 0.3), "Roughness": 0.3},
    {"Color": (0.4, 0.7, 1.0), "Roughness": 0.5},
    {"Color": (0.9, 0.9, 0.5), "Roughness": 0.7},
    {"Color": (0.8, 0.3, 0.6), "Roughness": 1.0},
]

# Toon BSDFs (an rt lobe module): per sphere its Size, Smooth and Color.
TOON_DIFFUSE = [
    {"Size": 0.2, "Smooth": 0.0, "Color": (0.9, 0.9, 0.9)},
    {"Size": 0.5, "Smooth": 0.0, "Color": (1.0, 0.5, 0.2)},
    {"Size": 0.5, "Smooth": 0.2, "Color": (0.3, 0.7, 1.0)},
    {"Size": 0.8, "Smooth": 0.1, "Color": (0.8, 0.8, 0.3)},
    {"Size": 1.0, "Smooth": 0.5, "Color": (0.7, 0.3, 0.6)},
]
TOON_GLOSSY = [
    {"Size": 0.05, "Smooth": 0.0, "Color": (0.9, 0.9, 0.9)},
    {"Size": 0.1, "Smooth": 0.05, "Color": (1.0, 0.5, 0.2)},
    {"Size": 0.2, "Smooth": 0.0, "Color": (0.3, 0.7, 1.0)},
    {"Size": 0.3, "Smooth": 0.3, "Color": (0.8, 0.8, 0.3)},
    {"Size": 0.6, "Smooth": 0.1, "Color": (0.7, 0.3, 0.6)},
]

# Per row: the inputs every sphere shares, and per sphere the inputs that change.
ROWS = {
    "dielectric_roughness": (DIELECTRIC, [{"Roughness": r} for r in STEPS]),
    "metal_roughness": (METAL, [{"Roughness": r} for r in STEPS]),
    "glass_roughness": (GLASS, [{"Roughness": r} for r in STEPS]),
    "ior": IOR_ROW,
    "ior_level": (
        {"Base Color": (0.2, 0.6, 0.3), "Roughness": 0.2},
        [{"Specular IOR Level": level} for level in STEPS],
    ),
    "specular_tint": SPECULAR_TINT_ROW,
    "coat_weight": (
        {"Base Color": (0.8, 0.2, 0.1), "Roughness": 0.6, "Coat Roughness": 0.1},
        [{"Coat Weight": w} for w in STEPS],
    ),
    "coat_roughness": (COATED, [{"Coat Roughness": r} for r in STEPS]),
    # Emission under the coat, which dims it by its reflectance and its tint (Cycles' svm/closure.h).
    "emission_coat": (
        {"Base Color": (0.05, 0.05, 0.05), "Roughness": 0.5, "Emission Color": (1.0, 0.6, 0.3),
         "Emission Strength": 2.0, "Coat Roughness": 0.2, "Coat Tint": (0.6, 0.8, 1.0)},
        [{"Coat Weight": w} for w in STEPS],
    ),
    # Emission under the sheen, which dims it by the sheen's albedo (Cycles' svm/closure.h).
    "emission_sheen": (
        {"Base Color": (0.05, 0.05, 0.05), "Roughness": 0.5, "Emission Color": (1.0, 0.6, 0.3),
         "Emission Strength": 2.0, "Sheen Roughness": 0.3, "Sheen Tint": (0.8, 0.9, 1.0)},
        [{"Sheen Weight": w} for w in STEPS],
    ),
    # Subsurface scattering, which rt renders as the diffuse base: close for a small radius.
    "subsurface": (
        {"Base Color": (0.8, 0.4, 0.3), "Roughness": 0.5, "Subsurface Weight": 1.0},
        [{"Subsurface Scale": r} for r in (0.001, 0.003, 0.01, 0.03, 0.1)],
    ),
    "metal_tint": METAL_TINT_ROW,
    # The rows above, under a sun.
    "dielectric_roughness_sun": (DIELECTRIC, [{"Roughness": r} for r in SUN_STEPS]),
    "metal_roughness_sun": (METAL, [{"Roughness": r} for r in SUN_STEPS]),
    "ior_sun": IOR_ROW,
    "ior_level_sun": (
        {"Base Color": (0.2, 0.6, 0.3), "Roughness": 0.35},
        [{"Specular IOR Level": level} for level in STEPS],
    ),
    "specular_tint_sun": SPECULAR_TINT_ROW,
    "metal_tint_sun": METAL_TINT_ROW,
    "coat_weight_sun": (
        {"Base Color": (0.8, 0.2, 0.1), "Roughness": 0.6, "Coat Roughness": 0.3},
        [{"Coat Weight": w} for w in STEPS],
    ),
    "coat_roughness_sun": (COATED, [{"Coat Roughness": r} for r in SUN_STEPS]),
    "sheen_weight": (SHEEN_BASE, [{"Sheen Weight": w} for w in STEPS]),
    "sheen_roughness": (SHEEN_ROUGHNESS_BASE, [{"Sheen Roughness": r} for r in STEPS]),
    "sheen_weight_sun": (SHEEN_BASE, [{"Sheen Weight": w} for w in STEPS]),
    "sheen_roughness_sun": (SHEEN_ROUGHNESS_BASE, [{"Sheen Roughness": r} for r in STEPS]),
    "anisotropy_sun": (ANISOTROPIC_METAL, [{"Anisotropic": a} for a in STEPS]),
    "anisotropy_rotation_sun": (
        {**ANISOTROPIC_METAL, "Anisotropic": 0.8},
        [{"Anisotropic Rotation": r} for r in (0.0, 0.1, 0.2, 0.3, 0.4)],
    ),
    "anisotropy_dielectric_sun": (
        {"Base Color": (0.2, 0.3, 0.6), "Roughness": 0.3},
        [{"Anisotropic": a} for a in STEPS],
    ),
    # A Tangent node into the Tangent input: along the uv map (whose u runs along the
    # meridians here, see UV_SWAPPED), or radial about X.
    "anisotropy_uv_tangent_sun": (ANISOTROPIC_METAL, [{"Anisotropic": a} for a in STEPS]),
    "anisotropy_radial_x_sun": (ANISOTROPIC_METAL, [{"Anisotropic": a} for a in STEPS]),
    "thin_film_dielectric": (FILM_DIELECTRIC, [{"Thin Film Thickness": t} for t in THICKNESSES]),
    "thin_film_dielectric_sun": (FILM_DIELECTRIC, [{"Thin Film Thickness": t} for t in THICKNESSES]),
    "thin_film_metal": (FILM_METAL, [{"Thin Film Thickness": t} for t in THICKNESSES]),
    "thin_film_metal_sun": (FILM_METAL, [{"Thin Film Thickness": t} for t in THICKNESSES]),
    "thin_film_glass": (FILM_GLASS, [{"Thin Film Thickness": t} for t in THICKNESSES]),
    "diffuse_roughness": (ROUGH_DIFFUSE, [{"Diffuse Roughness": r} for r in STEPS]),
    "diffuse_roughness_sun": (ROUGH_DIFFUSE, [{"Diffuse Roughness": r} for r in STEPS]),
    # Specular Tint on glass: Cycles tints its reflection's F0 and keeps the real Fresnel's
    # rise to 1 at grazing angles (lit by a sun, whose highlight shows the tint).
    # Rough glass under a sun, seen through (the sun wide, see WIDE_SUNS) and in its highlights.
    "glass_roughness_sun": (GLASS, [{"Roughness": r} for r in SUN_STEPS]),
    "glass_tint_sun": (
        {"Base Color": (1.0, 1.0, 1.0), "Transmission Weight": 1.0, "IOR": 1.5, "Roughness": 0.2},
        [{"Specular Tint": t} for t in TINTS],
    ),
    # Specular IOR Level 0 leaves no specular layer, but Cycles keeps one for a film (over index 1).
    "thin_film_level_zero": (
        {**FILM_DIELECTRIC, "Specular IOR Level": 0.0},
        [{"Thin Film Thickness": t} for t in THICKNESSES],
    ),
    # Coarse smooth spheres lit from the side (see COARSE): the shadow terminator crosses
    # facets whose interpolated normals differ from their true ones by up to half a facet.
    "terminator_sun": ({"Base Color": (0.8, 0.5, 0.3)}, TERMINATOR),
    "terminator_coat_sun": (
        {"Base Color": (0.8, 0.2, 0.1), "Roughness": 0.6, "Coat Weight": 1.0},
        [{"Coat Roughness": r} for r in (0.2, 0.3, 0.4, 0.5, 0.6)],
    ),
    # Rough glass, whose silhouettes Cycles shades by the glass's normal, not by the faces'.
    "terminator_glass_sun": (
        {"Base Color": (1.0, 1.0, 1.0), "Transmission Weight": 1.0, "IOR": 1.45},
        [{"Roughness": r} for r in (0.1, 0.2, 0.3, 0.5, 0.8)],
    ),
    # The sheen, on the interpolated normal where Bump Map Correction bends the glossy lobes'.
    "terminator_sheen_sun": (
        {**SHEEN_BASE, "Sheen Weight": 1.0, "Sheen Tint": (1.0, 0.8, 0.6)},
        [{"Sheen Roughness": r} for r in (0.1, 0.3, 0.5, 0.7, 1.0)],
    ),
    # The objects' own Shadow Terminator settings (see OBJECT_SETTINGS): Shading Offsets on
    # each lobe of `terminator_sun`, and from none to full with two Geometry Offsets on a
    # Lambertian base.
    "terminator_shading_offset_sun": ({"Base Color": (0.8, 0.5, 0.3)}, TERMINATOR),
    "terminator_offsets_sun": ({"Base Color": (0.8, 0.5, 0.3), **TERMINATOR[0]}, [{}] * 5),
    # Perfect mirrors and interfaces (a metal, a dielectric, glass, a coat) beside a
    # Lambertian sphere, with a Shading Offset of 0.6, in the white world they reflect.
    "terminator_shading_offset_mirrors": ({"Base Color": (0.8, 0.5, 0.3)}, MIRRORS),
    # The sheen, rough glass and a rough coat, with a Shading Offset of 1, in the white world.
    "terminator_shading_offset_layers": ({"Base Color": (0.8, 0.5, 0.3)}, [
        {**SHEEN_BASE, "Sheen Weight": 1.0, "Sheen Roughness": 0.3},
        {**SHEEN_BASE, "Sheen Weight": 1.0, "Sheen Roughness": 1.0},
        {"Transmission Weight": 1.0, "Roughness": 0.3, "IOR": 1.45},
        {"Transmission Weight": 1.0, "Roughness": 0.6, "IOR": 1.45},
        {"Roughness": 0.5, "Coat Weight": 1.0, "Coat Roughness": 0.3},
    ]),
    # Glossy lobes on coarse spheres with the material's Bump Map Correction off (see
    # NO_BUMP_MAP_CORRECTION), under the white world that their silhouettes mirror.
    "coarse_no_correction": ({"Base Color": (0.8, 0.5, 0.3)}, GLOSSY_TERMINATOR),
    "metallic_f82": ({}, METALLIC_F82),
    "metallic_conductor": ({"Roughness": 0.3}, CONDUCTORS),
    # Blender's Sheen BSDF alone (Microfiber), its Color and Roughness, in the white world and
    # lit from the side in a black one.
    # Blender's Subsurface Scattering node, which rt renders as a diffuse surface of its Color.
    "subsurface_node": (
        {"Color": (0.8, 0.4, 0.3)},
        [{"Scale": r} for r in (0.001, 0.003, 0.01, 0.03, 0.1)],
    ),
    "sheen_bsdf": ({}, SHEEN_BSDF),
    "sheen_bsdf_sun": ({}, SHEEN_BSDF),
    "toon_diffuse": ({}, TOON_DIFFUSE),
    "toon_diffuse_sun": ({}, TOON_DIFFUSE),
    "toon_glossy": ({}, TOON_GLOSSY),
    "toon_glossy_sun": ({}, TOON_GLOSSY),
}

# Rows of another shader node than the Principled BSDF: its type and its settings.
SHADER_NODES = {
    "metallic_f82": ("ShaderNodeBsdfMetallic", {"fresnel_type": "F82"}),
    "metallic_conductor": ("ShaderNodeBsdfMetallic", {"fresnel_type": "PHYSICAL_CONDUCTOR"}),
    "subsurface_node": ("ShaderNodeSubsurfaceScattering", {}),
    "sheen_bsdf": ("ShaderNodeBsdfSheen", {}),
    "sheen_bsdf_sun": ("ShaderNodeBsdfSheen", {}),
    "toon_diffuse": ("ShaderNodeBsdfToon", {"component": "DIFFUSE"}),
    "toon_diffuse_sun": ("ShaderNodeBsdfToon", {"component": "DIFFUSE"}),
    "toon_glossy": ("ShaderNodeBsdfToon", {"component": "GLOSSY"}),
    "toon_glossy_sun": ("ShaderNodeBsdfToon", {"component": "GLOSSY"}),
}

# Rows whose Principled BSDF's Tangent input is linked to a Tangent node: "UV_MAP" or a radial axis.
TANGENT_NODES = {"anisotropy_uv_tangent_sun": "UV_MAP", "anisotropy_radial_x_sun": "X"}
# Rows whose spheres' uv maps swap u and v, so that the uv tangent follows the meridians
# rather than the parallels (where it would be the default radial tangent about Z).
UV_SWAPPED = {"anisotropy_uv_tangent_sun"}

# Rows lit by a sun: its rotation and the world's colour. The sheen's from the right, a
# little behind the spheres (the terminator and the grazing light along it), in a black
# world; the anisotropic highlights from the front, above and to the right, in a dim
# world, whose light keeps rt's noise estimate honest where the spheres see only each
# other (rare paths that a black world would leave to the reference's noise alone).
SHEEN_SUN = ((math.radians(70), 0.0, math.radians(70)), (0.0, 0.0, 0.0))
FRONT_SUN = ((math.radians(35), 0.0, math.radians(25)), (0.1, 0.1, 0.1))
SIDE_SUN = ((math.radians(70), 0.0, math.radians(70)), (0.1, 0.1, 0.1))
SUNLIT = {
    "dielectric_roughness_sun": FRONT_SUN,
    "metal_roughness_sun": FRONT_SUN,
    "ior_sun": FRONT_SUN,
    "ior_level_sun": FRONT_SUN,
    "specular_tint_sun": FRONT_SUN,
    "metal_tint_sun": FRONT_SUN,
    "coat_weight_sun": FRONT_SUN,
    "coat_roughness_sun": FRONT_SUN,
    "terminator_sun": SIDE_SUN,
    "terminator_coat_sun": SIDE_SUN,
    "terminator_glass_sun": SIDE_SUN,
    "terminator_sheen_sun": SHEEN_SUN,
    "terminator_shading_offset_sun": SIDE_SUN,
    "terminator_offsets_sun": SIDE_SUN,
    "sheen_weight_sun": SHEEN_SUN,
    "sheen_roughness_sun": SHEEN_SUN,
    "sheen_bsdf_sun": SHEEN_SUN,
    "toon_diffuse_sun": SIDE_SUN,
    "toon_glossy_sun": FRONT_SUN,
    "anisotropy_sun": FRONT_SUN,
    "anisotropy_rotation_sun": FRONT_SUN,
    "anisotropy_dielectric_sun": FRONT_SUN,
    "anisotropy_uv_tangent_sun": FRONT_SUN,
    "anisotropy_radial_x_sun": FRONT_SUN,
    "thin_film_dielectric_sun": FRONT_SUN,
    "thin_film_metal_sun": FRONT_SUN,
    "diffuse_roughness_sun": FRONT_SUN,
    "glass_tint_sun": FRONT_SUN,
    "glass_roughness_sun": FRONT_SUN,
}

# Rows of coarse spheres: segments around (and half as many rings), instead of 48.
COARSE = {name: 12 for name in ("terminator_sun", "terminator_coat_sun", "terminator_glass_sun", "terminator_sheen_sun",
                                 "terminator_shading_offset_sun", "terminator_offsets_sun",
                                 "terminator_shading_offset_mirrors", "terminator_shading_offset_layers",
                                 "coarse_no_correction")}

# Rows whose spheres have Shadow Terminator settings (Object > Shading) of their own, one
# dict of object properties per sphere (Blender's defaults: Geometry Offset 0.1, Shading 0).
OBJECT_SETTINGS = {
    "terminator_shading_offset_sun": [{"shadow_terminator_shading_offset": 0.6}] * 5,
    "terminator_shading_offset_mirrors": [{"shadow_terminator_shading_offset": 0.6}] * 5,
    "terminator_shading_offset_layers": [{"shadow_terminator_shading_offset": 1.0}] * 5,
    "terminator_offsets_sun": [
        {"shadow_terminator_shading_offset": 0.3},
        {"shadow_terminator_shading_offset": 0.6},
        {"shadow_terminator_shading_offset": 1.0},
        {"shadow_terminator_geometry_offset": 0.0},
        {"shadow_terminator_geometry_offset": 1.0},
    ],
}

# Rows whose materials have Bump Map Correction off (Blender's Material > Settings).
NO_BUMP_MAP_CORRECTION = {"coarse_no_correction"}

# Rows whose sun is wider than the default 0.53°: seen only through glass, which no light
# sampling reaches, a small sun is found by rare samples whose noise the standard errors
# underestimate.
WIDE_SUNS = {"glass_tint_sun": 20.0, "glass_roughness_sun": 20.0, "terminator_glass_sun": 20.0}

# Rows rendered with more samples than the others, by this factor: light through rare paths
# (the sun through rough glass) leaves a 2048-spp reference's 8x8 blocks 2-3% from converged.
SPP_FACTOR = {"glass_tint_sun": 8, "glass_roughness_sun": 8, "terminator_glass_sun": 4}


# References of a row's exported scene under other bounce limits (only the image is
# written): NAME -> (the row, Cycles' Max Bounces). Cycles' Max Bounces N shades N + 1
# surfaces along a path (0 is direct light), rt's `max_bounces` N shades N: the tests
# render rt with one more.
BOUNCE_REFERENCES = {"glass_tint_sun_one_bounce": ("glass_tint_sun", 1)}


def set_input(bsdf, name, value):
    socket = bsdf.inputs[name]
    socket.default_value = (*value, 1.0) if isinstance(value, tuple) and len(socket.default_value) == 4 else value


def link_tangent(tree, bsdf, kind):
    """A Tangent node along the uv map (`kind` "UV_MAP") or radial about axis `kind`, into the Tangent input."""
    node = tree.nodes.new("ShaderNodeTangent")
    if kind == "UV_MAP":
        node.direction_type = "UV_MAP"
    else:
        node.direction_type = "RADIAL"
        node.axis = kind
    tree.links.new(node.outputs["Tangent"], bsdf.inputs["Tangent"])


def swap_uv(mesh):
    layer = mesh.uv_layers[0]
    uvs = [0.0] * (len(mesh.loops) * 2)
    layer.uv.foreach_get("vector", uvs)
    uvs[0::2], uvs[1::2] = uvs[1::2], uvs[0::2]
    layer.uv.foreach_set("vector", uvs)


def build(scene, name):
    shared, spheres = ROWS[name]
    if name in SUNLIT:
        rotation, sky = SUNLIT[name]
        cycles.uniform_world(scene, sky)
        refs.sun(scene, rotation)
        if name in WIDE_SUNS:
            bpy.data.objects["sun"].data.angle = math.radians(WIDE_SUNS[name])
    else:
        cycles.uniform_world(scene, (1.0, 1.0, 1.0))
    materials = [principled(f"{name}_{i}", {**shared, **own}, SHADER_NODES.get(name)) for i, own in enumerate(spheres)]
    objects = sphere_row(scene, materials, COARSE.get(name, 48))
    for material, sphere in zip(materials, objects):
        if name in TANGENT_NODES:
            link_tangent(material.node_tree, material.node_tree.nodes["Principled BSDF"], TANGENT_NODES[name])
        if name in UV_SWAPPED:
            swap_uv(sphere.data)
        if name in NO_BUMP_MAP_CORRECTION:
            material.cycles.use_bump_map_correction = False
    for sphere, settings in zip(objects, OBJECT_SETTINGS.get(name, [])):
        for key, value in settings.items():
            setattr(sphere, key, value)


def principled(name, inputs, node=None):
    """A material of a Principled BSDF, or of the shader `node` ((type, settings)) in its place."""
    material = bpy.data.materials.new(name)
    bsdf = material.node_tree.nodes["Principled BSDF"]
    if node is not None:
        tree = material.node_tree
        tree.nodes.remove(bsdf)
        bsdf = tree.nodes.new(node[0])
        for key, value in node[1].items():
            setattr(bsdf, key, value)
        tree.links.new(bsdf.outputs[0], tree.nodes["Material Output"].inputs["Surface"])
    for key, value in inputs.items():
        set_input(bsdf, key, value)
    return material


def row_scene():
    """A new reference scene of a row's size."""
    scene = refs.reset()
    scene.render.resolution_x, scene.render.resolution_y = WIDTH, HEIGHT
    return scene


def sphere_row(scene, materials, segments=48):
    """Five smooth spheres of `segments` around, side by side, one of each material (made as
    they are placed), in the view of a narrow camera far in front of them; returns the spheres."""
    spheres = []
    for i, material in enumerate(materials):
        spheres.append(refs.add_object(scene, f"sphere_{i}", bpy.ops.mesh.primitive_uv_sphere_add, material,
                                       radius=0.45, segments=segments, ring_count=segments // 2,
                                       location=(i - 2.0, 0.0, 0.0)))
        bpy.ops.object.shade_smooth()
    refs.camera(scene, (0.0, -12.0, 0.0), (0.0, 0.0, 0.0), 2.0 * math.degrees(math.atan(0.5 / 12.0)))
    return spheres


def main():
    args = cycles.arguments(__doc__, 1024, list(ROWS) + list(BOUNCE_REFERENCES))
    for name in args.names:
        scene = row_scene()
        row, bounces = BOUNCE_REFERENCES.get(name, (name, None))
        build(scene, row)
        if bounces is None:
            cycles.export(scene, f"principled_{name}")
        else:
            c = scene.cycles
            c.max_bounces = c.diffuse_bounces = c.glossy_bounces = c.transmission_bounces = bounces
        spp = args.spp * SPP_FACTOR.get(row, 1)
        cycles.render(scene, f"principled_{name}", argparse.Namespace(**{**vars(args), "spp": spp}))


if __name__ == "__main__":
    main()
