"""Blender's shader nodes on rt's material model, for rt_export.py.

rt renders one material model, Cycles' Principled BSDF. `surface()` follows the node
linked to a material's Material Output and describes it as a `Surface`: the Principled
inputs that give the same light (exactly where rt can, else the nearest, with a warning
that names the material and the node). What each node becomes:

  Principled BSDF    itself (Subsurface Weight > 0: the diffuse base, ~2% brighter than
                     Cycles' random walk, with a warning)
  Diffuse BSDF       diffuse of its Color and Roughness (Cycles' energy-preserving
                     Oren-Nayar, the Principled's Diffuse Roughness), no specular layer
  Glossy BSDF        a GGX lobe without Fresnel tinted by its Color (`extras.rt_glossy_color`),
                     as Cycles' Glossy: exact for (Multiscatter) GGX
  Glass BSDF         transmission of its IOR and Roughness, tinted by Color per refraction
                     (a tinted Color also tints the reflection in Cycles, not in rt: warned)
  Refraction BSDF    the same glass (Cycles' Refraction does not reflect: warned)
  Emission           black, emitting Color x Strength
  Transparent BSDF   alpha 0 (a colour other than white is warned about)
  Translucent BSDF   Lambertian diffuse of its Color (warned: rt has no diffuse transmission)
  Mix Shader         constant Fac, two mappable shaders: Transparent mixes into alpha,
                     Emission into the other's emission with the other's lobes scaled (exact
                     when the other is Diffuse or Emission), two Diffuse into one (of their
                     mean roughness: exact for Lambertian ones, else warned);
                     otherwise the dominant shader, warned
  Add Shader         Emission + X is X with the emission added; otherwise warned
  Toon BSDF, …       a lobe module of rt (rt_lobes.json: crates/rt/src/scene/lobe), its
                     colour the base colour, its inputs and settings its parameters

A node group is followed in: the shader its output gives is read as above, its inputs
taking the values and links of the group node's (rt_node_groups).

Anything else is a warning naming the material and the node; the material then keeps
its viewport colour (inside a Mix or Add Shader, the node is black, as an empty input is).
"""

import sys

import numpy as np

from . import rt_node_groups, rt_shader_graphs

# Inputs of a Principled BSDF that rt_export.py follows into textures: the base ones and
# the layered lobes' (LAYER_SOCKETS).
LAYER_SOCKETS = ("Coat Weight", "Coat Roughness", "Coat Tint", "Sheen Weight", "Sheen Roughness", "Sheen Tint",
                 "Anisotropic", "Anisotropic Rotation", "Specular Tint", "Diffuse Roughness", "Thin Film Thickness",
                 "Transmission Weight", "Specular IOR Level")
# The indices, fed by an image through a Map Range or Math Multiply node (rt_export's `ranged_texture`).
IOR_SOCKETS = ("IOR", "Coat IOR", "Thin Film IOR")
TEXTURE_SOCKETS = ("Base Color", "Alpha", "Roughness", "Metallic", "Normal", "Emission Color",
                   "Emission Strength") + LAYER_SOCKETS + IOR_SOCKETS


def log(message):
    print(f"rt_export: {message}", file=sys.stderr)


def owner_name(node):
    """The name of the material, world or lamp whose node tree holds `node` (their own trees
    are all named "Shader Nodetree"), or of the node group."""
    import bpy

    tree = node.id_data
    if tree.is_embedded_data:
        for owners in (bpy.data.materials, bpy.data.worlds, bpy.data.lights):
            for owner in owners:
                if owner.node_tree == tree:
                    return owner.name
    return tree.name


# Through node groups: a node inside one is a GroupNode (rt_node_groups), read as any node.
linked_node = rt_node_groups.linked_node


# The Principled BSDF's inputs that Blender 4.0 renamed, under their 3.x names (rt
# supports 4.2+; these let 3.4 export plain materials for the screenshots). 3.x's
# "Specular Tint" is a number, not 4.x's colour, so it is left out and takes the default.
PRE_4_0_SOCKETS = {
    "Emission Color": "Emission",
    "Transmission Weight": "Transmission",
    "Specular IOR Level": "Specular",
    "Coat Weight": "Clearcoat",
    "Coat Roughness": "Clearcoat Roughness",
}


def constant_node_value(source):
    """The value an RGB or Value node gives, or None for any other node."""
    return source.outputs[0].default_value if source.type in {"RGB", "VALUE"} else None


def socket_value(node, name, default):
    """A node input's value; a texture or other link stands for what it would give
    on average, which rt cannot know, so the socket's own value is used and noted."""
    if node.type == "BSDF_PRINCIPLED" and "Specular IOR Level" not in node.inputs:  # before 4.0
        if name == "Specular Tint":
            return default
        name = PRE_4_0_SOCKETS.get(name, name)
    socket = node.inputs.get(name)
    if socket is None:
        return default
    if socket.is_linked and rt_shader_graphs.drives(node, name):
        # rt evaluates the graph per shading point; the factor is what the graph scales.
        return rt_shader_graphs.NEUTRAL.get(name, socket.default_value)
    source = linked_node(socket)
    if source is not None:
        if (constant := constant_node_value(source)) is not None:
            return constant
        if node.type == "BSDF_PRINCIPLED" and name in TEXTURE_SOCKETS:
            # Followed, or warned about, by rt_export's `texture_channel`.
            return socket.default_value
        if node.type == "BSDF_PRINCIPLED" and source.type in {"TEX_IMAGE", "SEPARATE_COLOR"}:
            log(f"{owner_name(node)}: {node.name}.{name} is linked to an image, which rt reads for no such "
                f"input; using its own value")
            return socket.default_value
        if source.type in {"TEX_IMAGE", "SEPARATE_COLOR", "NORMAL_MAP"}:
            # The other nodes' images are followed, or warned about, by rt_shader_nodes' mappings.
            return socket.default_value
        log(f"{owner_name(node)}: {node.name}.{name} is linked to {source.type}; using its own value")
    return socket.default_value


def rgb(value):
    return [float(value[0]), float(value[1]), float(value[2])]


class Surface:
    """A surface shader as Principled inputs. `emission` is radiance (colour x strength);
    `glossy` is the colour of a Glossy BSDF's lobe (then base, metallic and the specular
    layer are unused); `principled` is the Principled BSDF node whose textures and coat
    the export follows, if the surface is one."""

    def __init__(self, **fields):
        self.base = [0.8, 0.8, 0.8]
        self.metallic = 0.0
        self.roughness = 0.5
        # The diffuse lobe's Oren-Nayar roughness (0: Lambertian).
        self.diffuse_roughness = 0.0
        self.ior = 1.5
        self.transmission = 0.0
        self.emission = [0.0, 0.0, 0.0]
        self.specular_level = 0.5
        self.specular_tint = [1.0, 1.0, 1.0]
        self.alpha = 1.0
        self.glossy = None
        self.principled = None
        # The Principled's own Emission Strength times what mixing scaled it by (for its texture).
        self.emission_strength = 0.0
        # The share of the surface that is a Holdout shader.
        self.holdout = 0.0
        # A Sheen BSDF's (weight, roughness, colour), written as the Principled's sheen layer.
        self.sheen = None
        # A lobe module's `extras.rt_lobe` ({"module": name, parameter: value, ...}).
        self.module = None
        self.kind = "principled"
        for key, value in fields.items():
            setattr(self, key, value)

    def scaled_lobes(self, w):
        """This surface with its lobes and emission scaled by w, when that is exact."""
        # Not a Glossy BSDF's colour: Cycles compensates its lost energy by the unscaled colour.
        if self.kind == "diffuse" or self.module is not None:
            self.base = [c * w for c in self.base]
        elif self.kind != "emission":
            return False
        self.emission = [e * w for e in self.emission]
        return True


# What the last export of each material (by name) rendered differently from Cycles: the
# warnings below, for the UI (rt's material panel) as well as the log.
NOTES = {}


def warn(material, node, what):
    log(f"{material.name}: {node.name!r} ({node.bl_idname}): {what}")
    NOTES.setdefault(material.name, []).append(f"{node.name}: {what}")


def distribution_note(material, node):
    """Cycles' Multiscatter GGX is rt's default model; the others are warned about."""
    distribution = getattr(node, "distribution", "MULTI_GGX")
    if distribution == "MULTI_GGX":
        return
    if distribution == "GGX":
        warn(material, node, "single-scattering GGX: rt renders the scene's [render] microfacet model "
             "(multiscatter by default, brighter where rough)")
        return
    warn(material, node, f"the {distribution} distribution is rendered as rt's GGX")


def principled(material, node):
    s = Surface(principled=node)
    s.base = rgb(socket_value(node, "Base Color", s.base))
    s.metallic = float(socket_value(node, "Metallic", 0.0))
    s.roughness = float(socket_value(node, "Roughness", 0.5))
    s.diffuse_roughness = float(socket_value(node, "Diffuse Roughness", 0.0))
    s.ior = float(socket_value(node, "IOR", 1.5))
    s.transmission = float(socket_value(node, "Transmission Weight", 0.0))
    strength = float(socket_value(node, "Emission Strength", 0.0))
    s.emission = [c * strength for c in rgb(socket_value(node, "Emission Color", (0, 0, 0)))]
    s.emission_strength = strength
    s.specular_level = float(socket_value(node, "Specular IOR Level", 0.5))
    s.specular_tint = rgb(socket_value(node, "Specular Tint", s.specular_tint))
    s.alpha = float(socket_value(node, "Alpha", 1.0))
    subsurface = float(socket_value(node, "Subsurface Weight", 0.0))
    if subsurface > 0.0 and s.metallic < 1.0 and s.transmission < 1.0:
        # Cycles' random walk is set up so that the light it scatters back has the base colour
        # as its albedo: the diffuse base is its nearest lobe. Measured against Cycles
        # (tests/cycles_principled.rs), rt is about 2% brighter, more at grazing angles.
        radius = max(rgb(socket_value(node, "Subsurface Radius", (1, 1, 1))))
        scale = float(socket_value(node, "Subsurface Scale", 0.05))
        warn(material, node, f"Subsurface Weight {subsurface:g} is rendered as the diffuse base "
             f"(no light travels under the surface: radius {radius * scale:g} m)")
    return s


def diffuse(material, node):
    # Cycles 5.0 gives the Diffuse BSDF's Roughness the closure of the Principled's Diffuse Roughness.
    return Surface(kind="diffuse", base=rgb(socket_value(node, "Color", (0.8, 0.8, 0.8))), roughness=1.0,
                   diffuse_roughness=float(socket_value(node, "Roughness", 0.0)), specular_level=0.0)


def glossy(material, node):
    distribution_note(material, node)
    if float(socket_value(node, "Anisotropy", 0.0)) != 0.0:
        warn(material, node, "anisotropy is not rendered by rt: isotropic")
    color = rgb(socket_value(node, "Color", (0.8, 0.8, 0.8)))
    return Surface(kind="glossy", glossy=color, base=[min(max(c, 0.0), 1.0) for c in color], metallic=1.0,
                   roughness=float(socket_value(node, "Roughness", 0.5)), specular_level=0.0)


def conductor_fresnel(cos_i, n, k):
    """The unpolarised Fresnel reflectance of a conductor of complex index n + ik (pbrt-v4's
    FrComplex), per channel."""
    def one(eta, kappa):
        c = complex(cos_i, 0.0)
        sin2 = 1.0 - cos_i * cos_i
        e = complex(eta, kappa)
        t = (1.0 - sin2 / (e * e)) ** 0.5
        parallel = (e * c - t) / (e * c + t)
        perpendicular = (c - e * t) / (c + e * t)
        return 0.5 * (abs(parallel) ** 2 + abs(perpendicular) ** 2)
    return [one(eta, kappa) for eta, kappa in zip(n, k)]


def f82_tint_fit(n, k):
    """(F0, F82 tint) of the F82-tint metal nearest a conductor of complex index n + ik, per
    channel: the least-squares fit over the cosine μ, weighted by μ, of Cycles' model
    F(μ) = Schlick(μ; F0) − b·μ(1 − μ)⁶ (b linear in the tint, Cycles'
    `bsdf_microfacet_setup_fresnel_f82_tint`) to the conductor's exact Fresnel, F0 searched
    within 0.05 of the conductor's own (the tint, at most 1, cannot lift the model above
    Schlick's curve, where gold's blue lies: F0 takes up that part)."""
    mu = (np.arange(256) + 0.5) / 256.0
    exact = np.array([conductor_fresnel(m, n, k) for m in mu])  # (256, 3)
    f = 6.0 / 7.0
    shape = mu * (1.0 - mu) ** 6
    fit_f0, fit_tint = [], []
    for channel, own in enumerate(conductor_fresnel(1.0, n, k)):
        best = None
        for f0 in np.clip(own + np.linspace(-0.05, 0.05, 101), 0.0, 1.0):
            schlick = f0 + (1.0 - f0) * (1.0 - mu) ** 5
            # The model's b for tint t is K (1 − t), K = Schlick(1/7) · 7 / f⁶.
            g = (f0 + (1.0 - f0) * f ** 5) * 7.0 / f ** 6 * shape
            t = float(np.clip((mu * g * (exact[:, channel] - schlick + g)).sum() / max((mu * g * g).sum(), 1e-12),
                              0.0, 1.0))
            error = (mu * (schlick - g * (1.0 - t) - exact[:, channel]) ** 2).sum()
            if best is None or error < best[0]:
                best = (error, float(f0), t)
        fit_f0.append(best[1])
        fit_tint.append(best[2])
    return fit_f0, fit_tint


def metallic(material, node):
    """Blender's Metallic BSDF: Cycles' F82-tint conductor, the very closure of the Principled
    BSDF's metal (Base Color its F0, Edge Tint its F82 tint). A Physical Conductor (an IOR and
    an extinction per channel) becomes the F82-tint metal nearest it (`f82_tint_fit`: close,
    not exact)."""
    distribution_note(material, node)
    for name in ("Anisotropy", "Thin Film Thickness"):
        if float(socket_value(node, name, 0.0)) != 0.0:
            warn(material, node, f"its {name} is not rendered by rt on a Metallic BSDF (a Principled BSDF's is)")
    clamp = lambda v: [min(max(c, 0.0), 1.0) for c in v]  # noqa: E731
    base = clamp(rgb(socket_value(node, "Base Color", (0.617, 0.577, 0.54))))
    tint = clamp(rgb(socket_value(node, "Edge Tint", (0.695, 0.726, 0.77))))
    if node.fresnel_type == "PHYSICAL_CONDUCTOR":
        n = [max(c, 0.0) for c in rgb(socket_value(node, "IOR", (2.757, 2.513, 2.231)))]
        k = [max(c, 0.0) for c in rgb(socket_value(node, "Extinction", (3.867, 3.404, 3.009)))]
        base, tint = f82_tint_fit(n, k)
        base = clamp(base)
        warn(material, node, "its Physical Conductor is rendered as the F82-tint metal nearest it (close, not exact)")
    return Surface(kind="metallic", base=base, metallic=1.0, specular_tint=tint,
                   roughness=float(socket_value(node, "Roughness", 0.5)))


def sheen(material, node):
    """Blender's Sheen BSDF (Microfiber): Cycles' sheen closure alone, which is the Principled's
    sheen layer of weight 1 tinted by its Color over nothing (a black base, no specular layer)."""
    if node.distribution != "MICROFIBER":
        warn(material, node, f"the {node.distribution} sheen is rendered as Cycles' Microfiber sheen")
    color = rgb(socket_value(node, "Color", (0.8, 0.8, 0.8)))
    if any(c > 1.0 for c in color):
        warn(material, node, "its Color is clamped to 1 (the Principled's Sheen Tint)")
    roughness = min(max(float(socket_value(node, "Roughness", 0.5)), 0.0), 1.0)
    return Surface(kind="sheen", base=[0.0, 0.0, 0.0], roughness=1.0, specular_level=0.0,
                   sheen=(1.0, roughness, [min(max(c, 0.0), 1.0) for c in color]))


def subsurface(material, node):
    """Blender's Subsurface Scattering: rendered as the Principled's subsurface is, a diffuse
    base of its Color (close for a small radius; warned)."""
    radius = max(rgb(socket_value(node, "Radius", (1, 1, 1))))
    scale = float(socket_value(node, "Scale", 0.05))
    warn(material, node, f"rendered as a diffuse surface of its Color (no light travels under the surface: "
         f"radius {radius * scale:g} m)")
    return Surface(kind="diffuse", base=rgb(socket_value(node, "Color", (0.8, 0.8, 0.8))), roughness=1.0,
                   specular_level=0.0)


def glass(material, node):
    distribution_note(material, node)
    color = [min(max(c, 0.0), 1.0) for c in rgb(socket_value(node, "Color", (1, 1, 1)))]
    if node.type == "BSDF_REFRACTION":
        warn(material, node, "rendered as glass: rt's refraction also reflects (Fresnel)")
    elif any(c < 1.0 for c in color):
        warn(material, node, "its Color tints refraction only: rt's glass reflects untinted")
    # rt's glass (as Cycles' Principled) tints each refraction by the square root of its base colour.
    return Surface(kind="glass", base=[c * c for c in color], transmission=1.0,
                   ior=float(socket_value(node, "IOR", 1.5)), roughness=float(socket_value(node, "Roughness", 0.0)))


def emission(material, node):
    strength = float(socket_value(node, "Strength", 1.0))
    radiance = [c * strength for c in rgb(socket_value(node, "Color", (1, 1, 1)))]
    return Surface(kind="emission", base=[0.0, 0.0, 0.0], roughness=1.0, specular_level=0.0, emission=radiance)


def transparent(material, node):
    color = rgb(socket_value(node, "Color", (1, 1, 1)))
    if any(abs(c - 1.0) > 1e-6 for c in color):
        warn(material, node, "rt's transparency is colourless: rendered white")
    return Surface(kind="transparent", alpha=0.0)


def translucent(material, node):
    warn(material, node, "rt has no diffuse transmission: rendered as a diffuse reflector")
    return Surface(kind="diffuse", base=rgb(socket_value(node, "Color", (0.8, 0.8, 0.8))), roughness=1.0,
                   specular_level=0.0)


def holdout(material, node):
    return Surface(kind="holdout", base=[0.0, 0.0, 0.0], roughness=1.0, specular_level=0.0, holdout=1.0)


def module_lobe(material, node):
    """A lobe module of rt (rt_shader_graphs.LOBES): its colour socket the base colour, its
    sockets' and settings' values (an enum's identifier lower-cased) its parameters."""
    lobe = rt_shader_graphs.LOBES[node.type]
    params = {param: float(socket_value(node, socket, 0.0)) for socket, param in lobe["inputs"]}
    params.update({param: str(getattr(node, prop)).lower() for prop, param in lobe["properties"]})
    return Surface(kind=lobe["module"], base=rgb(socket_value(node, lobe["color"], (0.8, 0.8, 0.8))), roughness=1.0,
                   specular_level=0.0, module={"module": lobe["module"], **params})


def shader_inputs(node):
    return [s for s in node.inputs if s.type == "SHADER"]


def with_transparency(surface, opacity):
    surface.alpha *= opacity
    return surface


def mix(material, node):
    fac_socket = node.inputs["Fac"]
    w = min(max(float(fac_socket.default_value), 0.0), 1.0)
    if fac_socket.is_linked:
        warn(material, node, f"its Fac is linked; rt mixes by its own value {w:g}")
    a_socket, b_socket = shader_inputs(node)
    a, b = shader(material, linked_node(a_socket)), shader(material, linked_node(b_socket))
    if a is None and b is None:
        return None
    # An input left empty (or unsupported, already warned about) is black in Cycles.
    a, b = a or black(), b or black()
    return mixed(material, node, a, 1.0 - w, b, w)


def black():
    return Surface(kind="diffuse", base=[0.0, 0.0, 0.0], roughness=1.0, specular_level=0.0)


def mixed(material, node, a, wa, b, wb):
    """a x wa + b x wb, in parameters where that is exact."""
    if wb == 0.0 or wa == 0.0:
        return a if wb == 0.0 else b
    if b.kind == "holdout" or a.kind == "holdout":
        # Cycles weighs the other's closures by its share and holds out the holdout's.
        held, hw, other, ow = (b, wb, a, wa) if b.kind == "holdout" else (a, wa, b, wb)
        other.holdout = other.holdout * ow + held.holdout * hw
        return other
    if b.kind == "transparent":
        return with_transparency(a, wa)
    if a.kind == "transparent":
        return with_transparency(b, wb)
    if b.kind == "emission" or a.kind == "emission":
        light, lw, other, ow = (b, wb, a, wa) if b.kind == "emission" else (a, wa, b, wb)
        glow = [e * lw for e in light.emission]
        if not other.scaled_lobes(ow):
            warn(material, node, f"rt cannot scale a {other.kind} surface by {ow:g}: its lobes keep their full "
                 "weight beside the mixed-in emission")
            other.emission = [e * ow for e in other.emission]
            other.emission_strength *= ow
        other.emission = [e + g for e, g in zip(other.emission, glow)]
        return other
    if a.kind == "diffuse" and b.kind == "diffuse":
        if a.diffuse_roughness > 0.0 or b.diffuse_roughness > 0.0:
            warn(material, node, "two Oren-Nayar diffuse surfaces are mixed as one of their mean colour and "
                 "roughness (close, not exact)")
        a.base = [x * wa + y * wb for x, y in zip(a.base, b.base)]
        a.diffuse_roughness = a.diffuse_roughness * wa + b.diffuse_roughness * wb
        return a
    dominant, weight = (a, wa) if wa >= wb else (b, wb)
    warn(material, node, f"rt cannot mix a {a.kind} and a {b.kind} surface: using the {dominant.kind} one "
         f"(weight {weight:g})")
    return dominant


def add(material, node):
    a_socket, b_socket = shader_inputs(node)
    a, b = shader(material, linked_node(a_socket)), shader(material, linked_node(b_socket))
    if a is None or b is None:
        return a or b
    if b.kind == "emission" or a.kind == "emission":
        light, other = (b, a) if b.kind == "emission" else (a, b)
        other.emission = [e + g for e, g in zip(other.emission, light.emission)]
        return other
    warn(material, node, f"rt cannot add a {a.kind} and a {b.kind} surface: using the first one")
    return a


MAPPINGS = {
    "BSDF_PRINCIPLED": principled,
    "BSDF_DIFFUSE": diffuse,
    "BSDF_GLOSSY": glossy,
    "BSDF_METALLIC": metallic,
    "BSDF_SHEEN": sheen,
    "SUBSURFACE_SCATTERING": subsurface,
    "BSDF_GLASS": glass,
    "BSDF_REFRACTION": glass,
    "EMISSION": emission,
    "BSDF_TRANSPARENT": transparent,
    "BSDF_TRANSLUCENT": translucent,
    "HOLDOUT": holdout,
    "MIX_SHADER": mix,
    "ADD_SHADER": add,
    **{node: module_lobe for node in rt_shader_graphs.LOBES},
}


def shader(material, node):
    """The Surface of the shader node `node` (None for no node), warning about what rt
    cannot render. An unsupported node gives None."""
    if node is None:
        return None
    mapping = MAPPINGS.get(node.type)
    if mapping is None:
        warn(material, node, "this shader node is not supported by rt (inside a Mix or Add Shader: black)")
        return None
    return mapping(material, node)


def surface(material, node):
    """The Surface of what is linked to a Material Output's Surface (`node`), or one of the
    material's viewport colour (with a warning) when rt cannot render that node."""
    found = shader(material, node) if node is not None else None
    if found is None:
        found = Surface(kind="viewport", base=rgb(material.diffuse_color), metallic=float(material.metallic),
                        roughness=float(material.roughness))
        if node is not None:
            log(f"{material.name}: its surface is rendered with the material's viewport colour")
    # Clamped as Cycles clamps the Principled's inputs.
    found.alpha = float(np.clip(found.alpha, 0.0, 1.0))
    return found
