//! The shader nodes rt evaluates on the GPU: for each of Blender's node types, the
//! program operation it becomes, its inputs in operand order and its outputs in register
//! order, and how its settings become the operation's mode and flags. The operations'
//! numbers are shared constants (`NODE_OP_*`, `src/shared_constants.rs`), the same in the
//! shaders; a unit test checks that `blender/rt_blender/rt_node_graph.py` exports exactly
//! these nodes.

use super::node_modes::{
    ATTRIBUTE_DATA, NOISE_DIMENSIONS, TRANSFORM_SPACES, TRANSFORM_TYPES, VORONOI_FEATURES, VORONOI_METRICS, WAVE_BANDS,
    WAVE_PROFILES, WAVE_RINGS, WAVE_TYPES,
};
pub use super::node_modes::{Mode, attribute_mode, mode, operation};

pub use crate::shared_constants::{
    NODE_OP_ATTRIBUTE, NODE_OP_BRICK, NODE_OP_BRIGHT_CONTRAST, NODE_OP_BUMP, NODE_OP_CHECKER, NODE_OP_CLAMP,
    NODE_OP_COMBINE, NODE_OP_CONVERT, NODE_OP_COORDINATE, NODE_OP_CURVES, NODE_OP_END, NODE_OP_FRESNEL, NODE_OP_GAMMA,
    NODE_OP_GRADIENT, NODE_OP_HUE_SATURATION, NODE_OP_INVERT, NODE_OP_LAYER_WEIGHT, NODE_OP_MAGIC, NODE_OP_MAP_RANGE,
    NODE_OP_MAPPING, NODE_OP_MATH, NODE_OP_MIX, NODE_OP_NOISE, NODE_OP_OUTPUT, NODE_OP_RAMP, NODE_OP_SEPARATE,
    NODE_OP_SPECTRUM, NODE_OP_VECTOR_MATH, NODE_OP_VECTOR_TRANSFORM, NODE_OP_VORONOI, NODE_OP_VORONOI_DIMENSIONS,
    NODE_OP_WAVE, NODE_OP_WHITE_NOISE,
};

/// Every operation by its name in the shader (`VORONOI` for `NODE_OP_VORONOI`), in order.
pub fn operations() -> impl Iterator<Item = (&'static str, u32)> {
    crate::shared_constants::NODE_OPERATIONS.iter().filter_map(|c| match c.value {
        crate::shared_constants::Value::U32(op) => Some((c.name.strip_prefix("NODE_OP_")?, op)),
        crate::shared_constants::Value::F32(_) => None,
    })
}

/// `NODE_OP_CONVERT` modes: a colour to a value (its luminance), a vector to one (the mean).
pub const CONVERT_COLOR_TO_VALUE: u32 = 0;
pub const CONVERT_VECTOR_TO_VALUE: u32 = 1;

/// The material inputs a graph can drive (`NODE_OP_OUTPUT` modes); `mix_factor` is a Mix
/// Shader's factor, the probability of the material's `mix_material` at a point; `normal`
/// the shading normal (a Bump node's).
pub const TARGETS: [&str; 6] = ["base_color", "roughness", "metallic", "emission", "mix_factor", "normal"];

/// Math's operations, Blender's identifiers in the order of `node_math` in the shader.
pub const MATH_OPERATIONS: [&str; 41] = [
    "ADD",
    "SUBTRACT",
    "MULTIPLY",
    "DIVIDE",
    "MULTIPLY_ADD",
    "POWER",
    "LOGARITHM",
    "SQRT",
    "INVERSE_SQRT",
    "ABSOLUTE",
    "EXPONENT",
    "MINIMUM",
    "MAXIMUM",
    "LESS_THAN",
    "GREATER_THAN",
    "SIGN",
    "COMPARE",
    "SMOOTH_MIN",
    "SMOOTH_MAX",
    "ROUND",
    "FLOOR",
    "CEIL",
    "TRUNC",
    "FRACT",
    "MODULO",
    "FLOORED_MODULO",
    "WRAP",
    "SNAP",
    "PINGPONG",
    "SINE",
    "COSINE",
    "TANGENT",
    "ARCSINE",
    "ARCCOSINE",
    "ARCTANGENT",
    "ARCTAN2",
    "SINH",
    "COSH",
    "TANH",
    "RADIANS",
    "DEGREES",
];

/// Vector Math's, in the order of `node_vector_math` in the shader.
pub const VECTOR_MATH_OPERATIONS: [&str; 29] = [
    "ADD",
    "SUBTRACT",
    "MULTIPLY",
    "DIVIDE",
    "MULTIPLY_ADD",
    "CROSS_PRODUCT",
    "PROJECT",
    "REFLECT",
    "REFRACT",
    "FACEFORWARD",
    "DOT_PRODUCT",
    "DISTANCE",
    "LENGTH",
    "SCALE",
    "NORMALIZE",
    "ABSOLUTE",
    "MINIMUM",
    "MAXIMUM",
    "FLOOR",
    "CEIL",
    "FRACTION",
    "MODULO",
    "WRAP",
    "SNAP",
    "SINE",
    "COSINE",
    "TANGENT",
    "POWER",
    "SIGN",
];

pub const BLEND_TYPES: [&str; 19] = [
    "MIX",
    "DARKEN",
    "MULTIPLY",
    "BURN",
    "LIGHTEN",
    "SCREEN",
    "DODGE",
    "ADD",
    "OVERLAY",
    "SOFT_LIGHT",
    "LINEAR_LIGHT",
    "DIFFERENCE",
    "EXCLUSION",
    "SUBTRACT",
    "DIVIDE",
    "HUE",
    "SATURATION",
    "VALUE",
    "COLOR",
];
/// Entries of a colour ramp's table, as Cycles bakes it: at 0, 1/256, …, 1.
pub const RAMP_TABLE_SIZE: usize = 257;

/// How a node becomes code.
pub enum Emit {
    /// One operation writing its outputs to consecutive registers.
    Operation(u32),
    /// Each output used is its own `NODE_OP_COORDINATE` of mode `first + its index`.
    Coordinates(u32),
    /// A constant: the node's own value (`settings.value`).
    Constant,
    /// Bump: `NODE_OP_BUMP` of the height at the point and a step away along two
    /// directions of the surface, its Height's graph compiled for each (`node_bump`).
    Bump,
    /// Each output used is its own `NODE_OP_ATTRIBUTE` reading the mesh's attribute
    /// `settings.slot` (the exporter numbers the mesh's), or a constant where it has none.
    Attribute,
}

pub struct Kind {
    /// Blender's node type (`bpy.types.Node.type`).
    pub name: &'static str,
    pub emit: Emit,
    /// Input keys in operand order: Blender's socket identifiers (the Mix node's without
    /// their data type's suffix), as the exporter writes them.
    pub inputs: &'static [&'static str],
    pub outputs: &'static [&'static str],
}

const fn op(name: &'static str, op: u32, inputs: &'static [&'static str], outputs: &'static [&'static str]) -> Kind {
    Kind { name, emit: Emit::Operation(op), inputs, outputs }
}

pub const KINDS: [Kind; 43] = [
    Kind { name: "VALUE", emit: Emit::Constant, inputs: &[], outputs: &["Value"] },
    Kind { name: "RGB", emit: Emit::Constant, inputs: &[], outputs: &["Color"] },
    Kind {
        name: "TEX_COORD",
        emit: Emit::Coordinates(0),
        inputs: &[],
        outputs: &["Generated", "Normal", "UV", "Object", "Camera", "Window", "Reflection"],
    },
    Kind {
        name: "NEW_GEOMETRY",
        emit: Emit::Coordinates(7),
        inputs: &[],
        outputs: &["Position", "Normal", "True Normal", "Incoming", "Backfacing"],
    },
    Kind {
        name: "LIGHT_PATH",
        emit: Emit::Coordinates(12),
        inputs: &[],
        outputs: &[
            "Is Camera Ray",
            "Is Shadow Ray",
            "Is Diffuse Ray",
            "Is Glossy Ray",
            "Is Singular Ray",
            "Is Reflection Ray",
            "Is Transmission Ray",
            "Is Volume Scatter Ray",
            "Ray Length",
            "Ray Depth",
            "Diffuse Depth",
            "Glossy Depth",
            "Transmission Depth",
        ],
    },
    Kind {
        name: "OBJECT_INFO",
        emit: Emit::Coordinates(25),
        inputs: &[],
        outputs: &["Location", "Color", "Alpha", "Random", "Object Index"],
    },
    Kind {
        name: "CAMERA",
        emit: Emit::Coordinates(30),
        inputs: &[],
        outputs: &["View Vector", "View Z Depth", "View Distance"],
    },
    Kind { name: "ATTRIBUTE", emit: Emit::Attribute, inputs: &[], outputs: &["Color", "Vector", "Fac", "Alpha"] },
    Kind { name: "VERTEX_COLOR", emit: Emit::Attribute, inputs: &[], outputs: &["Color", "Alpha"] },
    op("VECT_TRANSFORM", NODE_OP_VECTOR_TRANSFORM, &["Vector"], &["Vector"]),
    op("MATH", NODE_OP_MATH, &["Value", "Value_001", "Value_002"], &["Value"]),
    op("VECT_MATH", NODE_OP_VECTOR_MATH, &["Vector", "Vector_001", "Vector_002", "Scale"], &["Vector", "Value"]),
    op("MIX", NODE_OP_MIX, &["Factor", "A", "B"], &["Result"]),
    op("MIX_RGB", NODE_OP_MIX, &["Fac", "Color1", "Color2"], &["Color"]),
    op("MAP_RANGE", NODE_OP_MAP_RANGE, &["Value", "From Min", "From Max", "To Min", "To Max", "Steps"], &["Result"]),
    op("CLAMP", NODE_OP_CLAMP, &["Value", "Min", "Max"], &["Result"]),
    op("INVERT", NODE_OP_INVERT, &["Fac", "Color"], &["Color"]),
    op("VALTORGB", NODE_OP_RAMP, &["Fac"], &["Color", "Alpha"]),
    op("CURVE_RGB", NODE_OP_CURVES, &["Fac", "Color"], &["Color"]),
    op("CURVE_VEC", NODE_OP_CURVES, &["Fac", "Vector"], &["Vector"]),
    op("CURVE_FLOAT", NODE_OP_CURVES, &["Factor", "Value"], &["Value"]),
    op("RGBTOBW", NODE_OP_CONVERT, &["Color"], &["Val"]),
    op("SEPXYZ", NODE_OP_SEPARATE, &["Vector"], &["X", "Y", "Z"]),
    op("SEPARATE_COLOR", NODE_OP_SEPARATE, &["Color"], &["Red", "Green", "Blue"]),
    op("COMBXYZ", NODE_OP_COMBINE, &["X", "Y", "Z"], &["Vector"]),
    op("COMBINE_COLOR", NODE_OP_COMBINE, &["Red", "Green", "Blue"], &["Color"]),
    op("BLACKBODY", NODE_OP_SPECTRUM, &["Temperature"], &["Color"]),
    op("WAVELENGTH", NODE_OP_SPECTRUM, &["Wavelength"], &["Color"]),
    op("MAPPING", NODE_OP_MAPPING, &["Vector", "Location", "Rotation", "Scale"], &["Vector"]),
    op(
        "TEX_NOISE",
        NODE_OP_NOISE,
        &["Vector", "W", "Scale", "Detail", "Roughness", "Lacunarity", "Offset", "Gain", "Distortion"],
        &["Fac", "Color"],
    ),
    op("TEX_CHECKER", NODE_OP_CHECKER, &["Vector", "Color1", "Color2", "Scale"], &["Color", "Fac"]),
    op("TEX_GRADIENT", NODE_OP_GRADIENT, &["Vector"], &["Color", "Fac"]),
    op("LAYER_WEIGHT", NODE_OP_LAYER_WEIGHT, &["Blend", "Normal"], &["Fresnel", "Facing"]),
    op("FRESNEL", NODE_OP_FRESNEL, &["IOR", "Normal"], &["Fac"]),
    op("HUE_SAT", NODE_OP_HUE_SATURATION, &["Hue", "Saturation", "Value", "Fac", "Color"], &["Color"]),
    op("BRIGHTCONTRAST", NODE_OP_BRIGHT_CONTRAST, &["Color", "Bright", "Contrast"], &["Color"]),
    op("GAMMA", NODE_OP_GAMMA, &["Color", "Gamma"], &["Color"]),
    op("TEX_WHITE_NOISE", NODE_OP_WHITE_NOISE, &["Vector", "W"], &["Value", "Color"]),
    op(
        "TEX_WAVE",
        NODE_OP_WAVE,
        &["Vector", "Scale", "Distortion", "Detail", "Detail Scale", "Detail Roughness", "Phase Offset"],
        &["Color", "Fac"],
    ),
    op("TEX_MAGIC", NODE_OP_MAGIC, &["Vector", "Scale", "Distortion"], &["Color", "Fac"]),
    op(
        "TEX_BRICK",
        NODE_OP_BRICK,
        &[
            "Vector",
            "Color1",
            "Color2",
            "Mortar",
            "Scale",
            "Mortar Size",
            "Mortar Smooth",
            "Bias",
            "Brick Width",
            "Row Height",
        ],
        &["Color", "Fac"],
    ),
    op(
        "TEX_VORONOI",
        NODE_OP_VORONOI,
        &["Vector", "W", "Scale", "Detail", "Roughness", "Lacunarity", "Smoothness", "Exponent", "Randomness"],
        &["Distance", "Color", "Position", "W", "Radius"],
    ),
    Kind {
        name: "BUMP",
        emit: Emit::Bump,
        inputs: &["Strength", "Distance", "Filter Width", "Height", "Normal"],
        outputs: &["Normal"],
    },
];

/// What a compiled program depends on besides its graph: the operations, their modes and
/// the program layout's version; caches of programs compiled otherwise are stale.
pub fn compiler_signature() -> String {
    let kinds: Vec<_> = KINDS.iter().map(|k| (k.name, k.inputs, k.outputs)).collect();
    let ops: Vec<_> = operations().collect();
    format!(
        "node programs {} {} {ops:?} {MATH_OPERATIONS:?} {VECTOR_MATH_OPERATIONS:?} {TRANSFORM_TYPES:?} {TRANSFORM_SPACES:?} {BLEND_TYPES:?} {RAMP_TABLE_SIZE} {kinds:?} {VORONOI_FEATURES:?} {VORONOI_METRICS:?} {NOISE_DIMENSIONS:?} {WAVE_TYPES:?} {WAVE_BANDS:?} {WAVE_RINGS:?} {WAVE_PROFILES:?} {ATTRIBUTE_DATA:?}",
        super::node_graph::FORMAT_VERSION,
        super::node_graph::COMPILER_VERSION
    )
}

pub fn kind(name: &str) -> Option<&'static Kind> {
    KINDS.iter().find(|k| k.name == name)
}

#[cfg(test)]
#[path = "node_kinds_tests.rs"]
mod tests;
