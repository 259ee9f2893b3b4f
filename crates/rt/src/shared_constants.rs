//! Constants the host and the shaders share, declared once. Each group below makes the
//! Rust `pub const`s and the WGSL `const` lines of the shaders' generated file
//! `shared_constants.wgsl` ([`wgsl`]), so the two cannot differ: a shader that needs one
//! includes that file (through `common.wgsl`) and declares none of its own.

use crate::scene::slots;

/// One shared constant as WGSL writes it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Value {
    U32(u32),
    F32(f32),
}

/// A constant's name and value.
pub struct Shared {
    pub name: &'static str,
    pub value: Value,
}

/// Declares a group of shared constants: `pub const`s and a table of them named `$group`.
macro_rules! shared_constants {
    ($group:ident; $($(#[doc = $doc:literal])* $name:ident: $ty:ident = $value:expr;)*) => {
        $($(#[doc = $doc])* pub const $name: $ty = $value;)*
        pub const $group: &[Shared] = &[
            $(Shared { name: stringify!($name), value: shared_constants!(@value $ty $name) },)*
        ];
    };
    (@value u32 $name:ident) => { Value::U32($name) };
    (@value f32 $name:ident) => { Value::F32($name) };
}

shared_constants! { PANORAMA;
    /// `GpuFrame::panorama`: which panorama maps the image to directions (`shaders/panorama.wgsl`).
    PANORAMA_NONE: u32 = 0;
    PANORAMA_EQUIRECTANGULAR: u32 = 1;
    PANORAMA_FISHEYE_EQUIDISTANT: u32 = 2;
    PANORAMA_FISHEYE_EQUISOLID: u32 = 3;
    PANORAMA_MIRROR_BALL: u32 = 4;
}

shared_constants! { TANGENTS;
    /// `GpuMaterial::tangent`: Cycles' Tangent node, radial about Blender's Z (the default),
    /// X or Y, or the MikkTSpace tangent of the first uv set (`shaders/anisotropy.wgsl`).
    /// Radial about Blender's axis A is A × (the point's generated coordinates about the
    /// texture space's centre), in rt's axes (x, y, z) = Blender's (x, z, −y).
    TANGENT_RADIAL_Z: u32 = 0;
    TANGENT_RADIAL_X: u32 = 1;
    TANGENT_RADIAL_Y: u32 = 2;
    TANGENT_UV: u32 = 3;
}

shared_constants! { NODE_OPERATIONS;
    /// A node program's operations (`asset::node_kinds`: which Blender node becomes which;
    /// `shaders/node_step.wgsl` and `node_ops.wgsl` run them), in order.
    NODE_OP_END: u32 = 0;
    NODE_OP_OUTPUT: u32 = 1;
    NODE_OP_CONVERT: u32 = 2;
    NODE_OP_COORDINATE: u32 = 3;
    NODE_OP_MATH: u32 = 4;
    NODE_OP_VECTOR_MATH: u32 = 5;
    NODE_OP_MIX: u32 = 6;
    NODE_OP_MAP_RANGE: u32 = 7;
    NODE_OP_CLAMP: u32 = 8;
    NODE_OP_INVERT: u32 = 9;
    NODE_OP_RAMP: u32 = 10;
    NODE_OP_SEPARATE: u32 = 11;
    NODE_OP_COMBINE: u32 = 12;
    NODE_OP_MAPPING: u32 = 13;
    NODE_OP_NOISE: u32 = 14;
    NODE_OP_CHECKER: u32 = 15;
    NODE_OP_GRADIENT: u32 = 16;
    NODE_OP_LAYER_WEIGHT: u32 = 17;
    NODE_OP_FRESNEL: u32 = 18;
    NODE_OP_HUE_SATURATION: u32 = 19;
    NODE_OP_BRIGHT_CONTRAST: u32 = 20;
    NODE_OP_GAMMA: u32 = 21;
    NODE_OP_WHITE_NOISE: u32 = 22;
    NODE_OP_VORONOI: u32 = 23;
    NODE_OP_WAVE: u32 = 24;
    NODE_OP_CURVES: u32 = 25;
    NODE_OP_MAGIC: u32 = 26;
    NODE_OP_BRICK: u32 = 27;
    NODE_OP_SPECTRUM: u32 = 28;
    NODE_OP_BUMP: u32 = 29;
    NODE_OP_VORONOI_DIMENSIONS: u32 = 30;
    NODE_OP_VECTOR_TRANSFORM: u32 = 31;
    NODE_OP_ATTRIBUTE: u32 = 32;
}

shared_constants! { LIGHT_TREE;
    /// `GpuLightTreeNode::flags`: the node is a leaf.
    LIGHT_TREE_LEAF: u32 = 1;
    /// The lights below emit from both sides of their surfaces.
    LIGHT_TREE_TWO_SIDED: u32 = 2;
    /// A leaf's `link` names a lamp rather than an emitter.
    LIGHT_TREE_LAMP: u32 = 0x8000_0000;
    /// The trail of a light that is not in the tree (it emits nothing, or is a sun).
    LIGHT_TREE_ABSENT: u32 = u32::MAX;
}

shared_constants! { LAMPS;
    /// `GpuLamp::kind`'s low byte: the kind of lamp (`shaders/lamps.wgsl`).
    LAMP_POINT: u32 = 0;
    LAMP_SPOT: u32 = 1;
    LAMP_AREA: u32 = 2;
    LAMP_SUN: u32 = 3;
    /// The bits of `GpuLamp::kind` that hold the kind.
    LAMP_KIND: u32 = 0xff;
    /// A point or spot lamp that is a sphere rather than a disk facing the shaded point.
    LAMP_SPHERE: u32 = 0x100;
    /// An area lamp that is an ellipse rather than a rectangle.
    LAMP_ELLIPSE: u32 = 0x200;
    /// Camera rays see the lamp.
    LAMP_CAMERA: u32 = 0x400;
}

shared_constants! { LINKS;
    /// The bits of a NaN (which no placed matrix holds) that mark a moving instance's record:
    /// its `world_to_object[0][0]` holds them and `[0][1]` the bits of its motion (the index
    /// of its first matrix << 8 | how many), and the GPU interpolates its matrix at each
    /// sample's time (`shaders/motion.wgsl`). Traversal reads the record anyway, so an
    /// instance that stands still pays one comparison.
    MOVING_INSTANCE: u32 = 0x7fc0_4d56;
    /// A BVH node's child or an emitter's link that leads nowhere.
    EMPTY_LINK: u32 = u32::MAX;
    /// An instance without a material override.
    NO_MATERIAL: u32 = u32::MAX;
    /// Top-level leaves hold instances and spheres; the top bit says which.
    SPHERE_BIT: u32 = 0x8000_0000;
    /// A material slot without a texture.
    NO_TEXTURE: u32 = u32::MAX;
    /// A material without a node program.
    NO_PROGRAM: u32 = u32::MAX;
    /// `GpuMaterial::alpha_cutoff` of glTF's `BLEND`: stochastic transparency.
    ALPHA_BLEND: f32 = -1.0;
}

shared_constants! { PATHS;
    /// Bounces after which Russian roulette may end a path (`shaders/integrator.wgsl`).
    ROULETTE_START: u32 = 3;
}

shared_constants! { TEXTURES;
    /// `GpuTexture::flags` bit 0: the texels are sRGB-encoded (`shaders/texture.wgsl`).
    TEXTURE_SRGB: u32 = 1;
    /// Where `GpuTexture::flags` holds how the texture wraps in u and in v (`WRAP_*`, each
    /// in the bits of `TEXTURE_WRAP_MASK`).
    TEXTURE_WRAP_U_SHIFT: u32 = 1;
    TEXTURE_WRAP_V_SHIFT: u32 = 3;
    TEXTURE_WRAP_MASK: u32 = 3;
    /// `GpuTexture::flags` bit 5: read the closest texel of the full-size image.
    TEXTURE_CLOSEST: u32 = 1 << 5;
    /// How a texture wraps.
    WRAP_REPEAT: u32 = 0;
    WRAP_CLAMP: u32 = 1;
    WRAP_MIRROR: u32 = 2;
    /// Bits of `GpuMaterial::second_uv_set`: the texture slots (`scene::slots`) that read
    /// the second uv set.
    UV1_BASE_COLOR: u32 = 1 << slots::BASE_COLOR;
    UV1_METALLIC_ROUGHNESS: u32 = 1 << slots::METALLIC_ROUGHNESS;
    UV1_EMISSION: u32 = 1 << slots::EMISSION;
    UV1_NORMAL: u32 = 1 << slots::NORMAL;
    UV1_COAT: u32 = 1 << slots::COAT;
    UV1_COAT_ROUGHNESS: u32 = 1 << slots::COAT_ROUGHNESS;
    UV1_COAT_TINT: u32 = 1 << slots::COAT_TINT;
    UV1_SHEEN: u32 = 1 << slots::SHEEN;
    UV1_SHEEN_TINT: u32 = 1 << slots::SHEEN_TINT;
    UV1_ANISOTROPY: u32 = 1 << slots::ANISOTROPY;
    UV1_SPECULAR_TINT: u32 = 1 << slots::SPECULAR_TINT;
    UV1_DIFFUSE_ROUGHNESS: u32 = 1 << slots::DIFFUSE_ROUGHNESS;
    UV1_THIN_FILM: u32 = 1 << slots::THIN_FILM_THICKNESS;
    UV1_TRANSMISSION: u32 = 1 << slots::TRANSMISSION;
    UV1_SPECULAR_LEVEL: u32 = 1 << slots::SPECULAR_LEVEL;
    UV1_IOR: u32 = 1 << slots::IOR;
    UV1_COAT_NORMAL: u32 = 1 << slots::COAT_NORMAL;
}

shared_constants! { EVENTS;
    /// What produced a sample's first non-finite value, recorded per pixel
    /// (`shaders/integrator.wgsl`, read by `render::dropped`).
    EVENT_NONE: u32 = 0;
    EVENT_EMISSION: u32 = 1;
    EVENT_SKY: u32 = 2;
    EVENT_LIGHT_SAMPLE: u32 = 3;
    EVENT_MEDIUM: u32 = 4;
    EVENT_AIR: u32 = 5;
    /// `EVENT_LOBE` + a lobe's index (`LOBE_*`): the BSDF sample of that lobe.
    EVENT_LOBE: u32 = 6;
    /// The BSDF's lobes (`shaders/bsdf.wgsl`).
    LOBE_DIFFUSE: u32 = 0;
    LOBE_SPECULAR: u32 = 1;
    LOBE_REFLECTION: u32 = 2;
    LOBE_TRANSMISSION: u32 = 3;
    /// The coat, sampled before the other lobes (see `bsdf_sample`); its samples are
    /// labelled `LOBE_SPECULAR`.
    LOBE_COAT: u32 = 4;
    /// The sheen, sampled before the coat; its samples are labelled `LOBE_DIFFUSE` (as
    /// Cycles' are).
    LOBE_SHEEN: u32 = 5;
}

/// Every group, in the order `shared_constants.wgsl` lists them.
const ALL: [&[Shared]; 9] = [PANORAMA, TANGENTS, NODE_OPERATIONS, LIGHT_TREE, LAMPS, LINKS, PATHS, TEXTURES, EVENTS];

/// The WGSL of every shared constant (what each means is said in this file).
pub fn wgsl() -> String {
    let mut wgsl = String::from("// Generated from src/shared_constants.rs, which says what each one means.\n");
    for group in ALL {
        for constant in group {
            let (ty, literal) = match constant.value {
                Value::U32(v) if v < 0x1000 => ("u32", format!("{v}u")),
                Value::U32(v) => ("u32", format!("{v:#x}u")),
                Value::F32(v) => ("f32", format!("{v:?}")),
            };
            wgsl.push_str(&format!("const {}: {ty} = {literal};\n", constant.name));
        }
    }
    wgsl
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_wgsl_declares_each_constant_with_the_hosts_value() {
        let wgsl = wgsl();
        assert!(wgsl.contains("const LAMP_CAMERA: u32 = 1024u;\n"), "{wgsl}");
        assert!(wgsl.contains("const MOVING_INSTANCE: u32 = 0x7fc04d56u;\n"), "{wgsl}");
        assert!(wgsl.contains("const NO_TEXTURE: u32 = 0xffffffffu;\n"), "{wgsl}");
        assert!(wgsl.contains("const ALPHA_BLEND: f32 = -1.0;\n"), "{wgsl}");
        assert!(f32::from_bits(MOVING_INSTANCE).is_nan(), "no placed matrix may hold the mark");
        let count = ALL.iter().map(|g| g.len()).sum::<usize>();
        assert_eq!(wgsl.lines().filter(|l| l.starts_with("const ")).count(), count);
    }
}
