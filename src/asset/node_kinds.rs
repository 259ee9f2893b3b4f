//! The shader nodes rt evaluates on the GPU: for each of Blender's node types, the
//! program operation it becomes, its inputs in operand order and its outputs in register
//! order, and how its settings become the operation's mode and flags. The operations'
//! numbers are shared constants (`NODE_OP_*`, `src/shared_constants.rs`), the same in the
//! shaders; a unit test checks that `blender/rt_blender/rt_node_graph.py` exports exactly
//! these nodes.

use serde_json::{Map, Value};

pub use crate::shared_constants::{
    NODE_OP_BRICK, NODE_OP_BRIGHT_CONTRAST, NODE_OP_BUMP, NODE_OP_CHECKER, NODE_OP_CLAMP, NODE_OP_COMBINE,
    NODE_OP_CONVERT, NODE_OP_COORDINATE, NODE_OP_CURVES, NODE_OP_END, NODE_OP_FRESNEL, NODE_OP_GAMMA, NODE_OP_GRADIENT,
    NODE_OP_HUE_SATURATION, NODE_OP_INVERT, NODE_OP_LAYER_WEIGHT, NODE_OP_MAGIC, NODE_OP_MAP_RANGE, NODE_OP_MAPPING,
    NODE_OP_MATH, NODE_OP_MIX, NODE_OP_NOISE, NODE_OP_OUTPUT, NODE_OP_RAMP, NODE_OP_SEPARATE, NODE_OP_SPECTRUM,
    NODE_OP_VECTOR_MATH, NODE_OP_VECTOR_TRANSFORM, NODE_OP_VORONOI, NODE_OP_VORONOI_DIMENSIONS, NODE_OP_WAVE,
    NODE_OP_WHITE_NOISE,
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
const COLOR_MODES: [&str; 3] = ["RGB", "HSV", "HSL"];
const WAVE_TYPES: [&str; 2] = ["BANDS", "RINGS"];
const WAVE_BANDS: [&str; 4] = ["X", "Y", "Z", "DIAGONAL"];
const WAVE_RINGS: [&str; 4] = ["X", "Y", "Z", "SPHERICAL"];
const WAVE_PROFILES: [&str; 3] = ["SIN", "SAW", "TRI"];
const VORONOI_FEATURES: [&str; 5] = ["F1", "F2", "SMOOTH_F1", "DISTANCE_TO_EDGE", "N_SPHERE_RADIUS"];
const VORONOI_METRICS: [&str; 4] = ["EUCLIDEAN", "MANHATTAN", "CHEBYCHEV", "MINKOWSKI"];

const MIX_DATA_TYPES: [&str; 3] = ["FLOAT", "VECTOR", "RGBA"];
const MAP_RANGE_INTERPOLATIONS: [&str; 4] = ["LINEAR", "STEPPED", "SMOOTHSTEP", "SMOOTHERSTEP"];
const MAP_RANGE_DATA_TYPES: [&str; 2] = ["FLOAT", "FLOAT_VECTOR"];
const CLAMP_TYPES: [&str; 2] = ["MINMAX", "RANGE"];
const MAPPING_TYPES: [&str; 4] = ["POINT", "TEXTURE", "VECTOR", "NORMAL"];
const TRANSFORM_TYPES: [&str; 3] = ["POINT", "VECTOR", "NORMAL"];
const TRANSFORM_SPACES: [&str; 3] = ["WORLD", "OBJECT", "CAMERA"];
/// White Noise's dimensions, its mode.
const NOISE_DIMENSIONS: [&str; 4] = ["1D", "2D", "3D", "4D"];
const NOISE_TYPES: [&str; 5] = ["FBM", "MULTIFRACTAL", "HYBRID_MULTIFRACTAL", "RIDGED_MULTIFRACTAL", "HETERO_TERRAIN"];
const GRADIENT_TYPES: [&str; 7] =
    ["LINEAR", "QUADRATIC", "EASING", "DIAGONAL", "SPHERICAL", "QUADRATIC_SPHERE", "RADIAL"];

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

pub const KINDS: [Kind; 41] = [
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
        ],
    },
    Kind {
        name: "OBJECT_INFO",
        emit: Emit::Coordinates(22),
        inputs: &[],
        outputs: &["Location", "Color", "Alpha", "Random"],
    },
    Kind {
        name: "CAMERA",
        emit: Emit::Coordinates(26),
        inputs: &[],
        outputs: &["View Vector", "View Z Depth", "View Distance"],
    },
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
        "node programs {} {} {ops:?} {MATH_OPERATIONS:?} {VECTOR_MATH_OPERATIONS:?} {TRANSFORM_TYPES:?} {TRANSFORM_SPACES:?} {BLEND_TYPES:?} {RAMP_TABLE_SIZE} {kinds:?} {VORONOI_FEATURES:?} {VORONOI_METRICS:?} {NOISE_DIMENSIONS:?} {WAVE_TYPES:?} {WAVE_BANDS:?} {WAVE_RINGS:?} {WAVE_PROFILES:?}",
        super::node_graph::FORMAT_VERSION,
        super::node_graph::COMPILER_VERSION
    )
}

pub fn kind(name: &str) -> Option<&'static Kind> {
    KINDS.iter().find(|k| k.name == name)
}

/// The operation a node of `kind` with these settings becomes: its kind's, but a Voronoi of
/// 1, 2 or 4 dimensions has code of its own (3D's own code compiles and runs faster).
pub fn operation(kind: &str, op: u32, settings: &Map<String, Value>) -> Result<u32, String> {
    if kind == "TEX_VORONOI" && text(settings, "voronoi_dimensions")? != "3D" {
        return Ok(NODE_OP_VORONOI_DIMENSIONS);
    }
    Ok(op)
}

/// An operation's mode and flags from the node's settings.
pub struct Mode {
    pub mode: u32,
    pub flags: u32,
}

fn text<'a>(settings: &'a Map<String, Value>, key: &str) -> Result<&'a str, String> {
    settings.get(key).and_then(Value::as_str).ok_or_else(|| format!("setting `{key}` is missing or not text"))
}

fn flag(settings: &Map<String, Value>, key: &str) -> bool {
    settings.get(key).and_then(Value::as_bool).unwrap_or(false)
}

fn choice(settings: &Map<String, Value>, key: &str, options: &[&str]) -> Result<u32, String> {
    let value = text(settings, key)?;
    options
        .iter()
        .position(|o| *o == value)
        .map(|i| i as u32)
        .ok_or_else(|| format!("{key} `{value}` is not one rt evaluates (it evaluates {})", options.join(", ")))
}

/// The mode of node type `name` with `settings`, or what rt cannot evaluate.
pub fn mode(name: &str, settings: &Map<String, Value>) -> Result<Mode, String> {
    let plain = |mode| Ok(Mode { mode, flags: 0 });
    match name {
        "MATH" => Ok(Mode {
            mode: choice(settings, "operation", &MATH_OPERATIONS)?,
            flags: flag(settings, "use_clamp") as u32,
        }),
        "VECT_MATH" => plain(choice(settings, "operation", &VECTOR_MATH_OPERATIONS)?),
        "MIX" => mix_mode(settings),
        "MIX_RGB" => Ok(Mode {
            mode: choice(settings, "blend_type", &BLEND_TYPES)?,
            // The legacy node clamps its factor always; its Clamp is the result's.
            flags: 1 | (flag(settings, "use_clamp") as u32) << 1 | 2 << 2,
        }),
        // Flags: clamped, and (2) of vectors.
        "MAP_RANGE" => Ok(Mode {
            mode: choice(settings, "interpolation_type", &MAP_RANGE_INTERPOLATIONS)?,
            flags: flag(settings, "clamp") as u32 | choice(settings, "data_type", &MAP_RANGE_DATA_TYPES)? << 1,
        }),
        "CLAMP" => plain(choice(settings, "clamp_type", &CLAMP_TYPES)?),
        "VALTORGB" => Ok(Mode { mode: 0, flags: (text(settings, "interpolation")? != "CONSTANT") as u32 }),
        // Mode 1: a float curve; flags: extrapolated beyond the curves' range.
        "CURVE_RGB" | "CURVE_VEC" | "CURVE_FLOAT" => Ok(Mode {
            mode: (name == "CURVE_FLOAT") as u32,
            flags: (text(settings, "extend")? == "EXTRAPOLATED") as u32,
        }),
        "RGBTOBW" => plain(CONVERT_COLOR_TO_VALUE),
        // Mode 1: a wavelength, not a temperature.
        "WAVELENGTH" => plain(1),
        // Flags: the height inverted.
        "BUMP" => Ok(Mode { mode: 0, flags: flag(settings, "invert") as u32 }),
        "SEPARATE_COLOR" | "COMBINE_COLOR" => plain(choice(settings, "mode", &COLOR_MODES)?),
        "MAPPING" => plain(choice(settings, "vector_type", &MAPPING_TYPES)?),
        // Mode: the type | the space from << 2 | the space to << 4.
        "VECT_TRANSFORM" => plain(
            choice(settings, "vector_type", &TRANSFORM_TYPES)?
                | choice(settings, "convert_from", &TRANSFORM_SPACES)? << 2
                | choice(settings, "convert_to", &TRANSFORM_SPACES)? << 4,
        ),
        name if name.starts_with("TEX_") => texture_mode(name, settings),
        _ => plain(0),
    }
}

/// The mode of texture node type `name` with `settings`.
fn texture_mode(name: &str, settings: &Map<String, Value>) -> Result<Mode, String> {
    let plain = |mode| Ok(Mode { mode, flags: 0 });
    match name {
        "TEX_WHITE_NOISE" => plain(choice(settings, "noise_dimensions", &NOISE_DIMENSIONS)?),
        // Mode: the type | the dimensions' index << 4.
        "TEX_NOISE" => Ok(Mode {
            mode: choice(settings, "noise_type", &NOISE_TYPES)?
                | choice(settings, "noise_dimensions", &NOISE_DIMENSIONS)? << 4,
            flags: flag(settings, "normalize") as u32,
        }),
        "TEX_GRADIENT" => plain(choice(settings, "gradient_type", &GRADIENT_TYPES)?),
        "TEX_WAVE" => {
            let kind = choice(settings, "wave_type", &WAVE_TYPES)?;
            let direction = match kind {
                0 => choice(settings, "bands_direction", &WAVE_BANDS)?,
                _ => choice(settings, "rings_direction", &WAVE_RINGS)?,
            };
            plain(kind | direction << 1 | choice(settings, "wave_profile", &WAVE_PROFILES)? << 4)
        }
        // Mode: the depth, 0 to 10 (Blender's range).
        "TEX_MAGIC" => match settings.get("turbulence_depth").and_then(Value::as_f64) {
            Some(depth) if (0.0..=10.0).contains(&depth) => plain(depth as u32),
            _ => Err("turbulence_depth is missing or outside 0..=10".into()),
        },
        // Mode: the offset's frequency, and the squash's << 8 (Blender's 1 to 99 each); the
        // amounts are the instruction's extra words.
        "TEX_BRICK" => {
            let frequency = |key: &str| match settings.get(key).and_then(Value::as_f64) {
                Some(f) if (1.0..=99.0).contains(&f) => Ok(f as u32),
                _ => Err(format!("{key} is missing or outside 1..=99")),
            };
            plain(frequency("offset_frequency")? | frequency("squash_frequency")? << 8)
        }
        // Mode: the feature | the metric << 4 | the dimensions' index << 8.
        "TEX_VORONOI" => {
            let feature = choice(settings, "feature", &VORONOI_FEATURES)?;
            Ok(Mode {
                mode: feature
                    | choice(settings, "distance", &VORONOI_METRICS)? << 4
                    | choice(settings, "voronoi_dimensions", &NOISE_DIMENSIONS)? << 8,
                flags: flag(settings, "normalize") as u32,
            })
        }
        _ => plain(0),
    }
}

fn mix_mode(settings: &Map<String, Value>) -> Result<Mode, String> {
    let data_type = choice(settings, "data_type", &MIX_DATA_TYPES)?;
    // Floats and vectors only mix; colours blend by the blend type.
    let blend = if data_type == 2 { choice(settings, "blend_type", &BLEND_TYPES)? } else { 0 };
    let non_uniform = data_type == 1 && text(settings, "factor_mode").is_ok_and(|m| m == "NON_UNIFORM");
    let flags = flag(settings, "clamp_factor") as u32
        | (flag(settings, "clamp_result") as u32) << 1
        | data_type << 2
        | (non_uniform as u32) << 4;
    Ok(Mode { mode: blend, flags })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The operations are numbered 0, 1, 2, … in order, each with its name.
    #[test]
    fn operations_are_numbered_in_order() {
        let all: Vec<(&str, u32)> = operations().collect();
        assert_eq!(all.len(), 32);
        assert!(all.iter().enumerate().all(|(i, (name, op))| *op == i as u32 && !name.is_empty()));
        assert_eq!(all[23], ("VORONOI", NODE_OP_VORONOI));
        assert_eq!(all[30], ("VORONOI_DIMENSIONS", NODE_OP_VORONOI_DIMENSIONS));
    }

    /// The exporter follows exactly the node types rt evaluates, with the same outputs.
    #[test]
    fn the_exporter_declares_the_same_nodes() {
        let python = include_str!("../../blender/rt_blender/rt_node_graph.py");
        for k in &KINDS {
            let outputs: Vec<String> = k.outputs.iter().map(|o| format!("\"{o}\"")).collect();
            let line =
                format!("\"{}\": ({}{}),", k.name, outputs.join(", "), if outputs.len() == 1 { "," } else { "" });
            assert!(python.contains(&line), "rt_node_graph.py's EVALUATED lacks `{line}`");
        }
        let declared = python.lines().skip_while(|l| !l.starts_with("EVALUATED = {")).skip(1);
        let count = declared.take_while(|l| !l.starts_with('}')).count();
        assert_eq!(count, KINDS.len());
    }
}
