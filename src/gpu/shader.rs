//! WGSL assembly: the module for a feature set is built from the shader files
//! that set needs, with the lines of absent effects removed.
//!
//! Inside a file, `//#if NAME`, `//#if !NAME`, `//#else` and `//#endif` (on
//! lines of their own, nestable) keep or drop lines by the feature flags of
//! [`FeatureSet::flag`]. Being comments, they leave every file valid WGSL.

use crate::scene::{FeatureSet, SkyFeature, Transmission};
use std::path::PathBuf;

macro_rules! shader {
    ($name:literal) => {
        ($name, include_str!(concat!("../../shaders/", $name)))
    };
}

type Part = (&'static str, &'static str);

const COMMON: Part = shader!("common.wgsl");
const RNG: Part = shader!("rng.wgsl");
const RAY: Part = shader!("ray.wgsl");
const TRIANGLE: Part = shader!("triangle.wgsl");
const SPHERE: Part = shader!("sphere.wgsl");
const TRAVERSE: Part = shader!("traverse.wgsl");
const SURFACE: Part = shader!("surface.wgsl");
const BOTTOM_LEVEL: Part = shader!("bottom_level.wgsl");
const SPHERE_TEST: Part = shader!("sphere_test.wgsl");
const CAMERA: Part = shader!("camera.wgsl");
const SKY: Part = shader!("sky.wgsl");
const MICROFACET: Part = shader!("microfacet.wgsl");
const BSDF: Part = shader!("bsdf.wgsl");
const DIELECTRIC: Part = shader!("dielectric.wgsl");
const SAMPLING: Part = shader!("sampling.wgsl");
const SUN: Part = shader!("sun.wgsl");
const LIGHTS: Part = shader!("lights.wgsl");
const LAMPS: Part = shader!("lamps.wgsl");
const SEGMENT: Part = shader!("segment.wgsl");
const INTEGRATOR: Part = shader!("integrator.wgsl");
const TRACE_KERNEL: Part = shader!("trace_kernel.wgsl");
const ATMOSPHERE: Part = shader!("atmosphere.wgsl");
const ATMOSPHERE_PATH: Part = shader!("atmosphere_path.wgsl");
const ATMOSPHERE_STEPS: Part = shader!("atmosphere_steps.wgsl");
const ATMOSPHERE_LUT: Part = shader!("atmosphere_lut.wgsl");
const ATMOSPHERE_SKY: Part = shader!("atmosphere_sky.wgsl");
const ATMOSPHERE_TABLES: Part = shader!("atmosphere_tables.wgsl");
const ATMOSPHERE_SCATTERING: Part = shader!("atmosphere_scattering.wgsl");

/// The atmosphere's model, shared by the render programs and the table passes.
const ATMOSPHERE_MODEL: [Part; 4] = [ATMOSPHERE, ATMOSPHERE_PATH, ATMOSPHERE_STEPS, ATMOSPHERE_LUT];

/// Every shader file, for checks that must see them all.
pub const ALL_PARTS: &[Part] = &[
    COMMON,
    RNG,
    RAY,
    TRIANGLE,
    SPHERE,
    TRAVERSE,
    SURFACE,
    BOTTOM_LEVEL,
    SPHERE_TEST,
    CAMERA,
    SKY,
    MICROFACET,
    BSDF,
    DIELECTRIC,
    SAMPLING,
    SUN,
    LIGHTS,
    LAMPS,
    SEGMENT,
    INTEGRATOR,
    TRACE_KERNEL,
    ATMOSPHERE,
    ATMOSPHERE_PATH,
    ATMOSPHERE_STEPS,
    ATMOSPHERE_LUT,
    ATMOSPHERE_SKY,
    ATMOSPHERE_TABLES,
    ATMOSPHERE_SCATTERING,
];

/// Which entry points a module carries.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Program {
    /// `render`: the path-tracing megakernel.
    Integrator,
    /// `trace`, `generate_camera_rays`, `generate_diffuse_rays`, `generate_through_rays`.
    Trace,
}

fn parts(program: Program, f: &FeatureSet) -> Vec<Part> {
    let mut parts = vec![COMMON, RNG, RAY, TRAVERSE, SURFACE, CAMERA, SKY];
    if f.triangles {
        parts.extend([TRIANGLE, BOTTOM_LEVEL]);
    }
    if f.spheres {
        parts.extend([SPHERE, SPHERE_TEST]);
    }
    if f.glossy || f.transmission != Transmission::None {
        parts.push(MICROFACET);
    }
    parts.extend([BSDF, SAMPLING]);
    if f.transmission != Transmission::None {
        parts.push(DIELECTRIC);
    }
    if f.sun {
        parts.push(SUN);
    }
    if f.flag("nee") == Some(true) {
        parts.push(LIGHTS);
    }
    if f.lamps.any() {
        parts.push(LAMPS);
    }
    if f.media || f.sky == SkyFeature::Atmosphere {
        parts.push(SEGMENT);
    }
    if f.sky == SkyFeature::Atmosphere {
        parts.extend(ATMOSPHERE_MODEL);
        parts.push(ATMOSPHERE_SKY);
    }
    parts.push(match program {
        Program::Integrator => INTEGRATOR,
        Program::Trace => TRACE_KERNEL,
    });
    parts
}

/// Where the shader files are read from.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub enum ShaderFiles {
    /// The copies compiled into the binary.
    #[default]
    BuiltIn,
    /// A `shaders/` folder on disk, read at every assembly: `rt watch --dev` edits shaders live.
    Dir(PathBuf),
}

impl ShaderFiles {
    /// The text of one shader file.
    fn read(&self, (name, built_in): Part) -> Result<String, String> {
        match self {
            ShaderFiles::BuiltIn => Ok(built_in.to_owned()),
            ShaderFiles::Dir(dir) => {
                let path = dir.join(name);
                std::fs::read_to_string(&path).map_err(|e| format!("{}: cannot read: {e}", path.display()))
            }
        }
    }
}

/// The program that builds the atmosphere's tables (entry points
/// `build_transmittance`, `build_second_order`, `build_third_order`,
/// `build_fourth_order`, `build_closure`).
/// Its files take no directives.
pub fn atmosphere_tables_source() -> String {
    let mut source = String::new();
    for (name, text) in [ATMOSPHERE_TABLES, ATMOSPHERE_SCATTERING, SEGMENT].iter().chain(&ATMOSPHERE_MODEL) {
        source.push_str(&format!("// ---- shaders/{name}\n"));
        source.push_str(&preprocess(name, text, &|_| None).unwrap_or_else(|e| panic!("{e}")));
    }
    source
}

/// The WGSL source of `program` specialised to `features`, from the built-in shaders.
pub fn assemble(program: Program, features: &FeatureSet) -> String {
    // The built-in files are checked by the tests for every feature set.
    assemble_from(&ShaderFiles::BuiltIn, program, features).unwrap_or_else(|e| panic!("{e}"))
}

/// The WGSL source of `program` specialised to `features`, from `files`; an error names
/// the file that cannot be read or whose directives are wrong.
pub fn assemble_from(files: &ShaderFiles, program: Program, features: &FeatureSet) -> Result<String, String> {
    let mut source = String::new();
    for part in parts(program, features) {
        let text = files.read(part)?;
        source.push_str(&format!("// ---- shaders/{}\n", part.0));
        source.push_str(&preprocess(part.0, &text, &|flag| features.flag(flag))?);
    }
    if let ShaderFiles::Dir(_) = files {
        check_syntax(&source)?;
    }
    Ok(source)
}

/// A WGSL syntax error in an assembled module, named by the file it is in and the line's
/// text: wgpu's own message counts lines of the whole module, which no file has.
fn check_syntax(source: &str) -> Result<(), String> {
    let Err(e) = wgpu::naga::front::wgsl::parse_str(source) else { return Ok(()) };
    let Some(at) = e.location(source) else { return Err(e.message().to_owned()) };
    let lines: Vec<&str> = source.lines().collect();
    let line = (at.line_number as usize).clamp(1, lines.len().max(1)) - 1;
    let file = lines.iter().take(line + 1).rev().find_map(|l| l.strip_prefix("// ---- ")).unwrap_or("shaders");
    let text = lines.get(line).map_or("", |l| l.trim());
    Err(format!("{file}: {}: `{text}`", e.message()))
}

/// Applies the `//#if` directives of one file; a mistake in them (an unknown flag,
/// unbalanced directives) is an error naming the file and line.
pub fn preprocess(file: &str, text: &str, flag: &dyn Fn(&str) -> Option<bool>) -> Result<String, String> {
    let mut out = String::new();
    // For each open `#if`: (its branch is taken, the enclosing lines are kept).
    let mut stack: Vec<(bool, bool)> = Vec::new();
    let keeping = |stack: &[(bool, bool)]| stack.last().is_none_or(|&(taken, outer)| taken && outer);
    for (n, line) in text.lines().enumerate() {
        let at = || format!("shaders/{file}:{}", n + 1);
        let directive = line.trim_start();
        if let Some(cond) = directive.strip_prefix("//#if ") {
            let cond = cond.trim();
            let (negated, name) = cond.strip_prefix('!').map_or((false, cond), |n| (true, n));
            let value = flag(name).ok_or_else(|| format!("{}: unknown flag `{name}`", at()))?;
            let outer = keeping(&stack);
            stack.push((value != negated, outer));
        } else if directive.starts_with("//#else") {
            let top = stack.last_mut().ok_or_else(|| format!("{}: #else without #if", at()))?;
            top.0 = !top.0;
        } else if directive.starts_with("//#endif") {
            stack.pop().ok_or_else(|| format!("{}: #endif without #if", at()))?;
        } else if keeping(&stack) {
            out.push_str(line);
            out.push('\n');
        }
    }
    if !stack.is_empty() {
        return Err(format!("shaders/{file}: unclosed #if"));
    }
    Ok(out)
}

/// Both programs with every flag on, under each sky that brings structs of its
/// own, and the atmosphere's tables program: for the struct layout test.
#[cfg(test)]
pub fn full_sources_for_layout_checks() -> [String; 4] {
    use crate::scene::{RoughTransmission, Sampling};
    let all = FeatureSet::all(SkyFeature::Uniform, Sampling::Nee, RoughTransmission::Ggx);
    let atmosphere = FeatureSet { sky: SkyFeature::Atmosphere, ..all };
    [
        assemble(Program::Integrator, &all),
        assemble(Program::Trace, &all),
        assemble(Program::Integrator, &atmosphere),
        atmosphere_tables_source(),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{LampKinds, RoughTransmission, Sampling};

    /// A spread of feature sets: each flag on and off, in many combinations.
    fn feature_sets() -> Vec<FeatureSet> {
        let mut sets = Vec::new();
        for bits in 0..256u32 {
            let on = |b: u32| bits & (1 << b) != 0;
            let transmission = match bits % 4 {
                0 => Transmission::None,
                1 => Transmission::Smooth,
                2 => Transmission::Rough(RoughTransmission::Ggx),
                _ => Transmission::Rough(RoughTransmission::Cone),
            };
            sets.push(FeatureSet {
                triangles: on(2) || !on(3),
                spheres: on(3),
                emission: on(4),
                sky: match (on(5), on(2)) {
                    (true, _) => SkyFeature::Uniform,
                    (false, true) => SkyFeature::Atmosphere,
                    (false, false) => SkyFeature::Black,
                },
                sun: on(6),
                glossy: on(7),
                transmission,
                media: on(1) && transmission != Transmission::None,
                // Lamp kinds cycle with the bits, each on and off with the others.
                lamps: LampKinds {
                    point: bits % 3 == 1,
                    spot: bits % 5 == 2,
                    area: bits % 7 >= 5,
                    sun: (bits / 8) % 3 == 1,
                },
                sampling: if on(0) { Sampling::Nee } else { Sampling::Seed },
            });
        }
        sets
    }

    fn validate(source: &str, what: &str) {
        let module = wgpu::naga::front::wgsl::parse_str(source)
            .unwrap_or_else(|e| panic!("{what}: {}", e.emit_to_string(source)));
        wgpu::naga::valid::Validator::new(Default::default(), wgpu::naga::valid::Capabilities::all())
            .validate(&module)
            .unwrap_or_else(|e| panic!("{what}: {}", e.emit_to_string(source)));
    }

    #[test]
    fn every_feature_set_assembles_to_valid_wgsl() {
        for features in feature_sets() {
            for program in [Program::Integrator, Program::Trace] {
                validate(&assemble(program, &features), &format!("[{features}] {program:?}"));
            }
        }
    }

    #[test]
    fn atmosphere_tables_program_is_valid_wgsl() {
        validate(&atmosphere_tables_source(), "atmosphere tables");
    }

    #[test]
    fn every_directive_names_a_known_flag() {
        let any = FeatureSet::all(SkyFeature::Uniform, Sampling::Nee, RoughTransmission::Ggx);
        for (name, text) in ALL_PARTS {
            preprocess(name, text, &|flag| any.flag(flag)).unwrap_or_else(|e| panic!("{e}"));
        }
    }

    #[test]
    fn absent_effects_leave_no_code() {
        let plain = FeatureSet {
            triangles: true,
            spheres: false,
            emission: false,
            sky: SkyFeature::Black,
            sun: false,
            glossy: false,
            transmission: Transmission::None,
            media: false,
            lamps: LampKinds::default(),
            sampling: Sampling::Nee,
        };
        let source = assemble(Program::Integrator, &plain);
        for absent in [
            "fn intersect_sphere",
            "m.emission *",
            "frame.sky_color",
            "fn ggx_d",
            "fn refract_direction",
            "fn sample_sun",
            "fn integrate_segment",
            "atmosphere_",
            "var<uniform> atmosphere",
            "fn sun_limb_darkening",
            "@group(2)",
            "struct Lamp",
            "lamps",
            "@binding(10)",
            "@binding(11)",
        ] {
            assert!(!source.contains(absent), "{absent:?} is in the plain pipeline");
        }
        // Each kind of lamp brings its own code only.
        let only = |lamps: LampKinds| assemble(Program::Integrator, &FeatureSet { lamps, ..plain });
        let point = only(LampKinds { point: true, ..Default::default() });
        assert!(point.contains("fn lamps_seen") && point.contains("fn round_lamp_hit"));
        for absent in ["fn spot_attenuation", "LAMP_AREA {", "LAMP_SUN {"] {
            assert!(!point.contains(absent), "{absent:?} is in a pipeline with point lamps only");
        }
        let area = only(LampKinds { area: true, ..Default::default() });
        assert!(area.contains("LAMP_AREA {") && !area.contains("fn round_lamp_hit") && !area.contains("LAMP_SUN {"));
        let sun = only(LampKinds { sun: true, ..Default::default() });
        assert!(sun.contains("LAMP_SUN {") && !sun.contains("fn round_lamp_hit") && !sun.contains("LAMP_AREA {"));
        let spot = only(LampKinds { spot: true, ..Default::default() });
        assert!(spot.contains("fn spot_attenuation") && spot.contains("fn round_lamp_hit"));
        let uniform_sun = FeatureSet { sky: SkyFeature::Uniform, sun: true, ..plain };
        for program in [Program::Integrator, Program::Trace] {
            let source = assemble(program, &uniform_sun);
            assert!(!source.contains("atmosphere_"), "the atmosphere is in a uniform sky's {program:?} pipeline");
        }
    }

    #[test]
    fn shaders_on_disk_assemble_like_the_built_in_ones_and_errors_name_the_file() {
        let all = FeatureSet::all(SkyFeature::Uniform, Sampling::Nee, RoughTransmission::Ggx);
        let disk = ShaderFiles::Dir(PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("shaders"));
        assert_eq!(assemble_from(&disk, Program::Integrator, &all), Ok(assemble(Program::Integrator, &all)));
        let missing = ShaderFiles::Dir(PathBuf::from("/nonexistent/shaders"));
        let error = assemble_from(&missing, Program::Trace, &all).expect_err("no files");
        assert!(error.starts_with("/nonexistent/shaders/common.wgsl: cannot read"), "{error}");
        let broken = std::env::temp_dir().join(format!("rt-broken-shaders-{}", std::process::id()));
        std::fs::create_dir_all(&broken).expect("temp folder");
        for (name, text) in ALL_PARTS {
            let text = if *name == "sky.wgsl" { format!("{text}\nfn oops( {{\n") } else { text.to_string() };
            std::fs::write(broken.join(name), text).expect("shader copy");
        }
        let error = assemble_from(&ShaderFiles::Dir(broken.clone()), Program::Integrator, &all).expect_err("broken");
        assert!(error.starts_with("shaders/sky.wgsl: ") && error.contains("oops"), "{error}");
        let _ = std::fs::remove_dir_all(&broken);
        let unbalanced = preprocess("bsdf.wgsl", "a\n//#if glossy\nb\n", &|f| all.flag(f)).expect_err("unclosed");
        assert_eq!(unbalanced, "shaders/bsdf.wgsl: unclosed #if");
        let unknown = preprocess("bsdf.wgsl", "//#if shiny\n//#endif\n", &|f| all.flag(f)).expect_err("unknown");
        assert_eq!(unknown, "shaders/bsdf.wgsl:1: unknown flag `shiny`");
    }

    #[test]
    fn preprocessor_nests_and_negates() {
        let text = "a\n//#if x\nb\n//#if !y\nc\n//#else\nd\n//#endif\n//#else\ne\n//#endif\nf\n";
        let run = |x: bool, y: bool| preprocess("t", text, &|n| Some(if n == "x" { x } else { y })).expect("balanced");
        assert_eq!(run(true, false), "a\nb\nc\nf\n");
        assert_eq!(run(true, true), "a\nb\nd\nf\n");
        assert_eq!(run(false, false), "a\ne\nf\n");
    }
}
