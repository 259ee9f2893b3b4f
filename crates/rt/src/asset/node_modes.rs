//! How a node's settings (Blender's enum properties and flags) become its operation's mode
//! and flags, and which operation a node whose settings choose its code becomes.

use super::node_kinds::{
    BLEND_TYPES, CONVERT_COLOR_TO_VALUE, MATH_OPERATIONS, NODE_OP_VORONOI_DIMENSIONS, VECTOR_MATH_OPERATIONS,
};
use serde_json::{Map, Value};

pub(super) const COLOR_MODES: [&str; 3] = ["RGB", "HSV", "HSL"];
pub(super) const WAVE_TYPES: [&str; 2] = ["BANDS", "RINGS"];
pub(super) const WAVE_BANDS: [&str; 4] = ["X", "Y", "Z", "DIAGONAL"];
pub(super) const WAVE_RINGS: [&str; 4] = ["X", "Y", "Z", "SPHERICAL"];
pub(super) const WAVE_PROFILES: [&str; 3] = ["SIN", "SAW", "TRI"];
pub(super) const VORONOI_FEATURES: [&str; 5] = ["F1", "F2", "SMOOTH_F1", "DISTANCE_TO_EDGE", "N_SPHERE_RADIUS"];
pub(super) const VORONOI_METRICS: [&str; 4] = ["EUCLIDEAN", "MANHATTAN", "CHEBYCHEV", "MINKOWSKI"];

pub(super) const MIX_DATA_TYPES: [&str; 3] = ["FLOAT", "VECTOR", "RGBA"];
pub(super) const MAP_RANGE_INTERPOLATIONS: [&str; 4] = ["LINEAR", "STEPPED", "SMOOTHSTEP", "SMOOTHERSTEP"];
pub(super) const MAP_RANGE_DATA_TYPES: [&str; 2] = ["FLOAT", "FLOAT_VECTOR"];
pub(super) const CLAMP_TYPES: [&str; 2] = ["MINMAX", "RANGE"];
pub(super) const MAPPING_TYPES: [&str; 4] = ["POINT", "TEXTURE", "VECTOR", "NORMAL"];
pub(super) const TRANSFORM_TYPES: [&str; 3] = ["POINT", "VECTOR", "NORMAL"];
pub(super) const TRANSFORM_SPACES: [&str; 3] = ["WORLD", "OBJECT", "CAMERA"];
/// What an attribute's values are (Cycles' `NodeAttributeType`): a value, two, three (a
/// vector) or four (a colour's RGBA); a value is also an integer or a boolean.
pub(super) const ATTRIBUTE_DATA: [&str; 4] = ["FLOAT", "FLOAT2", "FLOAT3", "FLOAT4"];
/// White Noise's dimensions, its mode.
pub(super) const NOISE_DIMENSIONS: [&str; 4] = ["1D", "2D", "3D", "4D"];
pub(super) const NOISE_TYPES: [&str; 5] =
    ["FBM", "MULTIFRACTAL", "HYBRID_MULTIFRACTAL", "RIDGED_MULTIFRACTAL", "HETERO_TERRAIN"];
pub(super) const GRADIENT_TYPES: [&str; 7] =
    ["LINEAR", "QUADRATIC", "EASING", "DIAGONAL", "SPHERICAL", "QUADRATIC_SPHERE", "RADIAL"];

/// The operation a node of `kind` with these settings becomes: its kind's, but a Voronoi of
/// 1, 2 or 4 dimensions has code of its own (3D's own code compiles and runs faster).
pub fn operation(kind: &str, op: u32, settings: &Map<String, Value>) -> Result<u32, String> {
    if kind == "TEX_VORONOI" && text(settings, "voronoi_dimensions")? != "3D" {
        return Ok(NODE_OP_VORONOI_DIMENSIONS);
    }
    Ok(op)
}

/// `NODE_OP_ATTRIBUTE`'s mode for `output` of an Attribute or Color Attribute node: what
/// it reads (0 the colour or vector, 1 Fac, 2 Alpha) | the attribute's data << 2.
pub fn attribute_mode(output: &str, settings: &Map<String, Value>) -> Result<u32, String> {
    let data = choice(settings, "data", &ATTRIBUTE_DATA)?;
    let read = match output {
        "Fac" => 1,
        "Alpha" => 2,
        _ => 0,
    };
    Ok(read | data << 2)
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
