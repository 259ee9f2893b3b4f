//! BSDF lobes as modules. A lobe outside rt's Principled model (Blender's Toon BSDF, …) is
//! one Rust module that declares it — its name, its parameters, the Blender shader node it
//! renders and its WGSL file — and that file, which gives the lobe's evaluation, density and
//! sampling. Everything else reads [`LOBES`]: scene files and glTF extras (`lobe = { module =
//! "toon", … }`, parsed by the declared parameters), the cache and the GPU material (a module
//! number and its parameters' values), the shader assembler (`lobe_modules.wgsl`, made here:
//! the module's file behind its flag `lobe_NAME`, named accessors of its parameters and the
//! calls), and the Blender exporter (`rt lobes --json`, kept as
//! `blender/rt_blender/rt_lobes.json`, which a test holds equal to this registry).
//!
//! A module's lobe is the whole material's BSDF, weighted by the material's base colour
//! (the closure's colour, which textures and node graphs drive as they drive a Principled
//! BSDF's); emission, alpha and holdout stay the material's own. Adding a lobe is its
//! module, its WGSL file and one line in [`LOBES`].

mod toon;

use serde::Deserialize;
use std::collections::BTreeMap;
use std::fmt::Write;

/// How many numbers a module's parameters may take (the GPU material's `lobe_params`).
pub const MAX_PARAMS: usize = 4;

/// Every lobe module; a material's module number is its place here plus one (0: none).
pub const LOBES: &[&LobeModule] = &[&toon::TOON];

/// A lobe's declaration.
pub struct LobeModule {
    /// Its name in scene files and glTF extras, the prefix of its WGSL functions
    /// (`NAME_eval`, `NAME_pdf`, `NAME_sample`) and of its shader flag (`lobe_NAME`).
    pub name: &'static str,
    pub params: &'static [Param],
    /// Its WGSL file's name and text (`shaders/NAME`).
    pub wgsl: (&'static str, &'static str),
    /// The Blender shader node it renders, for the exporter.
    pub blender: BlenderNode,
}

/// One parameter: a number in a range, or one of named choices (their index on the GPU).
pub struct Param {
    pub name: &'static str,
    pub kind: ParamKind,
    pub default: f32,
}

pub enum ParamKind {
    /// Values outside the range are clamped to it, as Cycles clamps its closures' inputs.
    Number {
        min: f32,
        max: f32,
    },
    Choice(&'static [&'static str]),
}

/// How the exporter reads the node: `node` is Blender's node type (`BSDF_TOON`), `color`
/// the socket that becomes the material's base colour, `inputs` the sockets and
/// `properties` the node's settings (an enum's identifier, lower-cased, is a choice) that
/// give each parameter.
pub struct BlenderNode {
    pub node: &'static str,
    pub color: &'static str,
    pub inputs: &'static [(&'static str, &'static str)],
    pub properties: &'static [(&'static str, &'static str)],
}

/// A material's module lobe: which one, and its parameters' values in declaration order.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ModuleLobe {
    /// Index into [`LOBES`].
    pub module: usize,
    pub params: [f32; MAX_PARAMS],
}

impl ModuleLobe {
    pub fn declaration(&self) -> &'static LobeModule {
        LOBES[self.module]
    }

    /// The GPU material's module number (0: none).
    pub fn number(lobe: Option<&ModuleLobe>) -> u32 {
        lobe.map_or(0, |l| l.module as u32 + 1)
    }

    /// The lobe of GPU/cache module number `number`, or `None` (0, or one this build lacks).
    pub fn from_number(number: u32, params: [f32; MAX_PARAMS]) -> Option<Self> {
        let module = (number as usize).checked_sub(1).filter(|&m| m < LOBES.len())?;
        Some(Self { module, params })
    }

    /// The lobe a table of fields describes: `module` names it, every other key one of its
    /// parameters (those left out take their defaults).
    fn from_fields(mut fields: BTreeMap<String, Field>) -> Result<Self, String> {
        let known = || LOBES.iter().map(|l| l.name).collect::<Vec<_>>().join(", ");
        let name = match fields.remove("module") {
            Some(Field::Name(name)) => name,
            Some(Field::Number(_)) => return Err(format!("lobe: `module` must be a name ({})", known())),
            None => return Err(format!("lobe: `module` is missing ({})", known())),
        };
        let module = LOBES
            .iter()
            .position(|l| l.name == name)
            .ok_or_else(|| format!("lobe: no module `{name}` (rt has {})", known()))?;
        let declaration = LOBES[module];
        let mut params = [0.0; MAX_PARAMS];
        for (slot, param) in params.iter_mut().zip(declaration.params) {
            *slot = match fields.remove(param.name) {
                Some(field) => param.value(&field).map_err(|e| format!("lobe {name}: {}: {e}", param.name))?,
                None => param.default,
            };
        }
        if let Some(extra) = fields.keys().next() {
            let names: Vec<&str> = declaration.params.iter().map(|p| p.name).collect();
            return Err(format!("lobe {name}: no parameter `{extra}` (it has {})", names.join(", ")));
        }
        Ok(Self { module, params })
    }
}

/// A parameter's value as a table gives it.
#[derive(Deserialize)]
#[serde(untagged)]
enum Field {
    Number(f64),
    Name(String),
}

impl Param {
    fn value(&self, field: &Field) -> Result<f32, String> {
        match (&self.kind, field) {
            (ParamKind::Number { min, max }, Field::Number(v)) if v.is_finite() => Ok((*v as f32).clamp(*min, *max)),
            (ParamKind::Number { .. }, _) => Err("must be a finite number".into()),
            (ParamKind::Choice(choices), Field::Name(name)) => choices
                .iter()
                .position(|c| c == name)
                .map(|i| i as f32)
                .ok_or_else(|| format!("no choice `{name}` (one of {})", choices.join(", "))),
            (ParamKind::Choice(choices), Field::Number(_)) => Err(format!("must be one of {}", choices.join(", "))),
        }
    }
}

impl<'de> Deserialize<'de> for ModuleLobe {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let fields = BTreeMap::<String, Field>::deserialize(deserializer)?;
        Self::from_fields(fields).map_err(serde::de::Error::custom)
    }
}

/// The bit of module `index` in a feature set's `lobe_modules`.
pub fn bit(index: usize) -> u32 {
    1 << index
}

/// Every module's bit.
pub fn all_bits() -> u32 {
    (0..LOBES.len()).fold(0, |bits, i| bits | bit(i))
}

/// The shader flag of a module (`lobe_toon`), and the index of the module a flag names.
pub fn flag_index(flag: &str) -> Option<usize> {
    let name = flag.strip_prefix("lobe_")?;
    LOBES.iter().position(|l| l.name == name)
}

/// The shader file that the BSDF includes (`lobe_modules.wgsl`): each module's file behind
/// its flag, accessors named by its parameters, and the calls that pick a material's module.
/// A module's functions return its lobe per unit colour; the base colour weights them here.
pub fn wgsl() -> String {
    let mut code = String::from("//#include \"bsdf.wgsl\"\n");
    for (i, lobe) in LOBES.iter().enumerate() {
        let _ = writeln!(code, "//#if lobe_{}\n//#include \"{}\"", lobe.name, lobe.wgsl.0);
        for (slot, param) in lobe.params.iter().enumerate() {
            let field = ["x", "y", "z", "w"][slot];
            let _ = writeln!(
                code,
                "fn {}_{}(m: Material) -> f32 {{ return m.lobe_params.{field}; }}",
                lobe.name, param.name
            );
            if let ParamKind::Choice(choices) = param.kind {
                for (value, choice) in choices.iter().enumerate() {
                    let _ = writeln!(
                        code,
                        "const {}_{}_{}: f32 = {value}.0;",
                        lobe.name.to_uppercase(),
                        param.name.to_uppercase(),
                        choice.to_uppercase()
                    );
                }
            }
        }
        let _ = writeln!(code, "const LOBE_MODULE_{}: u32 = {}u;\n//#endif", lobe.name.to_uppercase(), i + 1);
    }
    code.push_str(&dispatch("eval", "wi: vec3f", "vec3f", "ctx.m.base_color * ", "vec3f(0.0)"));
    code.push_str(&dispatch("pdf", "wi: vec3f", "f32", "", "0.0"));
    code.push_str(&dispatch("sample", "u: vec2f", "BsdfSample", "tinted(ctx.m.base_color, ", "invalid_sample()"));
    code.push_str("fn tinted(color: vec3f, s: BsdfSample) -> BsdfSample {\n    var t = s;\n    t.weight *= color;\n    return t;\n}\n");
    code
}

/// `module_lobe_WHAT(ctx, ARG)`: the call of the material's module's `NAME_WHAT`.
fn dispatch(what: &str, arg: &str, returns: &str, wrap: &str, none: &str) -> String {
    let arg_name = arg.split(':').next().unwrap_or(arg);
    let close = if wrap.ends_with(", ") { ")" } else { "" };
    let mut code = format!("fn module_lobe_{what}(ctx: ShadingContext, {arg}) -> {returns} {{\n");
    for lobe in LOBES {
        let upper = lobe.name.to_uppercase();
        let _ = writeln!(
            code,
            "    //#if lobe_{0}\n    if ctx.m.lobe_module == LOBE_MODULE_{upper} {{\n        return {wrap}{0}_{what}(ctx, {arg_name}){close};\n    }}\n    //#endif",
            lobe.name
        );
    }
    let _ = writeln!(code, "    return {none};\n}}");
    code
}

/// The registry as the exporter reads it (`rt lobes --json`).
pub fn exporter_table() -> serde_json::Value {
    let lobes: Vec<serde_json::Value> = LOBES
        .iter()
        .map(|l| {
            let params: Vec<serde_json::Value> = l
                .params
                .iter()
                .map(|p| match p.kind {
                    ParamKind::Number { min, max } => {
                        serde_json::json!({"name": p.name, "min": min, "max": max, "default": p.default})
                    }
                    ParamKind::Choice(choices) => serde_json::json!({"name": p.name, "choices": choices}),
                })
                .collect();
            serde_json::json!({
                "module": l.name,
                "node": l.blender.node,
                "color": l.blender.color,
                "inputs": l.blender.inputs.iter().map(|(s, p)| serde_json::json!([s, p])).collect::<Vec<_>>(),
                "properties": l.blender.properties.iter().map(|(s, p)| serde_json::json!([s, p])).collect::<Vec<_>>(),
                "params": params,
            })
        })
        .collect();
    serde_json::json!({ "lobes": lobes })
}

#[cfg(test)]
mod tests;
