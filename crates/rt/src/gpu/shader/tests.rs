use super::resolve::{include_of, kept_lines, resolve};
use super::*;
use crate::scene::{FLAGS, LampKinds, RoughTransmission, Sampling, SkyFeature, Transmission};
use std::collections::{BTreeSet, HashSet};
use std::path::Path;

/// A spread of feature sets: each declared flag on or off by a hash of the set's number
/// and the flag's, then completed with what the flags need.
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
        let sky = match (on(5), on(2)) {
            (true, _) => SkyFeature::Uniform,
            (false, true) => SkyFeature::Atmosphere,
            (false, false) if on(7) => SkyFeature::Environment,
            (false, false) => SkyFeature::Black,
        };
        // Lamp kinds cycle with the bits, each on and off with the others.
        let lamps =
            LampKinds { point: bits % 3 == 1, spot: bits % 5 == 2, area: bits % 7 >= 5, sun: (bits / 8) % 3 == 1 };
        let sampling = if on(0) { Sampling::Nee } else { Sampling::Resampled };
        let mut set = FeatureSet::with_flags_off(sky, transmission, lamps, sampling, 0, 0);
        for (i, flag) in FLAGS.iter().enumerate() {
            let hash =
                (bits.wrapping_mul(0x9e37_79b9) ^ (i as u32).wrapping_mul(0x85eb_ca6b)).wrapping_mul(0xc2b2_ae35);
            (flag.set)(&mut set, hash >> 31 == 1);
        }
        set.complete();
        set.triangles |= !set.spheres;
        sets.push(set);
    }
    sets
}

fn all_on() -> FeatureSet {
    FeatureSet::all(SkyFeature::Uniform, Sampling::Nee, RoughTransmission::Ggx)
}

/// Triangles and nothing else.
fn plain() -> FeatureSet {
    let none =
        FeatureSet::with_flags_off(SkyFeature::Black, Transmission::None, LampKinds::default(), Sampling::Nee, 0, 0);
    FeatureSet { triangles: true, ..none }
}

/// Parses and validates `source`, then writes it as SPIR-V, as the Vulkan backend does:
/// the writer refuses (or panics on) some modules the validator lets through, such as a
/// pointer to part of a variable given to a function.
fn validate(source: &str, what: &str) {
    use wgpu::naga::back::spv;
    let module =
        wgpu::naga::front::wgsl::parse_str(source).unwrap_or_else(|e| panic!("{what}: {}", e.emit_to_string(source)));
    let info = wgpu::naga::valid::Validator::new(Default::default(), wgpu::naga::valid::Capabilities::all())
        .validate(&module)
        .unwrap_or_else(|e| panic!("{what}: {}", e.emit_to_string(source)));
    spv::write_vec(&module, &info, &spv::Options::default(), None).unwrap_or_else(|e| panic!("{what}: SPIR-V: {e}"));
}

/// The files an assembled module is made of, in the order it holds them.
fn files_in(source: &str) -> Vec<&str> {
    source.lines().filter_map(|l| l.strip_prefix("// ---- shaders/")).collect()
}

/// A folder of shader files for one test, made of (name, text) pairs.
fn folder(test: &str, files: &[(&str, &str)]) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rt-shaders-{test}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp folder");
    for (name, text) in files {
        std::fs::write(dir.join(name), text).expect("shader file");
    }
    dir
}

#[test]
fn every_feature_set_assembles_to_valid_wgsl() {
    for features in feature_sets() {
        for program in [Program::Integrator, Program::Trace] {
            validate(&assemble(program, &features), &format!("[{features}] {program:?}"));
        }
    }
}

/// Every two flag values a scene can ask for together, compiled side by side: the 256
/// sets above leave pairs out (panorama and sheen share a bit there).
#[test]
fn every_pair_of_effects_assembles_to_valid_wgsl() {
    let (sets, pairs) = super::covering::pairwise(plain());
    let missing = super::covering::uncovered(&sets, plain());
    assert!(missing.is_empty(), "pairs no set holds: {missing:?}");
    // The check finds what a short list leaves out.
    assert!(!super::covering::uncovered(&[plain(), all_on()], plain()).is_empty());
    println!("{} feature sets hold all {pairs} possible pairs of flag values", sets.len());
    for features in &sets {
        for program in [Program::Integrator, Program::Trace] {
            validate(&assemble(program, features), &format!("[{features}] {program:?}"));
        }
    }
}

/// Specialised node code (one shape running every operation) with the integrator that
/// calls it.
#[test]
fn specialised_node_code_is_valid_wgsl() {
    use crate::asset::node_graph::CONSTANT;
    use crate::asset::node_kinds::{NODE_OP_END, NODE_OP_OUTPUT, operations};
    let mut program = vec![0];
    for (_, op) in operations().skip(2) {
        program.extend([op, 0, 1, CONSTANT, 0]);
    }
    program.extend([NODE_OP_OUTPUT, 0, 1, 0, 0, NODE_OP_END]);
    program[0] = program.len() as u32;
    program.extend([0; 4]);
    let features = FeatureSet { node_code: 1, ..all_on() };
    let mut source = assemble(Program::Integrator, &features);
    assert!(!source.contains("fn run_node_program"), "the interpreter is left out");
    source.push_str(&crate::gpu::node_code::generate(&[program.clone(), program]));
    assert!(source.contains("node_op_voronoi(start, NodeStep(23u"));
    validate(&source, "specialised node code");
}

#[test]
fn atmosphere_tables_program_is_valid_wgsl() {
    validate(&atmosphere_tables_source(), "atmosphere tables");
}

#[test]
fn every_directive_names_a_known_flag() {
    let any = all_on();
    for (name, text) in built_in_files() {
        kept_lines(name, text, &|flag| any.flag(flag)).unwrap_or_else(|e| panic!("{e}"));
    }
}

#[test]
fn each_file_comes_once_and_after_the_files_it_includes() {
    // Each module with the feature set it was assembled for (none: the tables program).
    let mut modules: Vec<(String, Option<FeatureSet>)> = vec![(atmosphere_tables_source(), None)];
    for features in feature_sets().into_iter().step_by(7) {
        for program in [Program::Integrator, Program::Trace] {
            modules.push((assemble(program, &features), Some(features)));
        }
    }
    for (source, features) in &modules {
        let flag = |f: &str| features.and_then(|features| features.flag(f));
        let files = files_in(source);
        for (i, name) in files.iter().enumerate() {
            assert!(!files[..i].contains(name), "{name} is in a module twice");
            let text = ShaderFiles::BuiltIn.read(name).expect("built-in");
            for (_, line) in kept_lines(name, &text, &flag).expect("directives") {
                if let Some(Ok(included)) = include_of(line) {
                    assert!(files[..i].contains(&included), "{name} comes before {included}, which it includes");
                }
            }
        }
        assert!(!source.contains("//#include"), "an include line is left in the module");
    }
}

#[test]
fn every_shader_file_is_built_in_and_used_by_a_program() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("shaders");
    let on_disk: BTreeSet<String> = std::fs::read_dir(&dir)
        .expect("shaders/")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .filter(|name| name != "display.wgsl")
        .collect();
    let built_in: BTreeSet<String> = built_in_files().map(|(name, _)| name.to_string()).collect();
    assert_eq!(on_disk, built_in, "the files of shaders/ and the built-in ones differ");
    let mut used = BTreeSet::new();
    for sky in [SkyFeature::Uniform, SkyFeature::Atmosphere, SkyFeature::Environment, SkyFeature::Graph] {
        for sampling in [Sampling::Nee, Sampling::Resampled] {
            for rough in [RoughTransmission::Ggx, RoughTransmission::Cone] {
                // AOVs, adaptive sampling and exact sums are asked for by a render, not in the set of effects.
                let features = FeatureSet {
                    aovs: true,
                    adaptive: true,
                    exact_sums: true,
                    ..FeatureSet::all(sky, sampling, rough)
                };
                for program in [Program::Integrator, Program::Trace] {
                    used.extend(files_in(&assemble(program, &features)).into_iter().map(str::to_owned));
                }
            }
        }
    }
    used.extend(files_in(&atmosphere_tables_source()).into_iter().map(str::to_owned));
    used.retain(|name| super::generated(name).is_none());
    assert_eq!(used, built_in, "some built-in files are included by no program");
}

#[test]
fn no_private_variable_is_shared_between_files() {
    let words = |text: &str| -> HashSet<String> {
        text.split(|c: char| !(c.is_alphanumeric() || c == '_')).map(str::to_owned).collect()
    };
    for (name, text) in built_in_files() {
        for line in text.lines() {
            let Some(rest) = line.trim().strip_prefix("var<private> ") else { continue };
            let variable: String = rest.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
            for (other, other_text) in built_in_files().filter(|(other, _)| *other != name) {
                assert!(
                    !words(other_text).contains(&variable),
                    "{other} uses `{variable}`, a private variable of {name}"
                );
            }
        }
    }
}

/// Code and bindings the plain pipeline (`plain()`) must not hold.
const ABSENT_FROM_THE_PLAIN_PIPELINE: [&str; 31] = [
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
    "fn sample_aperture",
    "frame.aperture_radius",
    "fn panorama_direction",
    "frame.panorama",
    "struct Lamp",
    "lamps",
    "@binding(10)",
    "@binding(11)",
    "fn sample_texture",
    "var<storage, read> texels",
    "fn opaque_at",
    "fn normal_mapped",
    "tangent_frames",
    "fn alpha_coin",
    "uv_lod",
    "fn environment_radiance",
    "fn sample_environment",
    "var<uniform> environment",
    "aov",
    "pixel_samples",
];

#[test]
fn absent_effects_leave_no_code() {
    let plain = plain();
    let source = assemble(Program::Integrator, &plain);
    for absent in ABSENT_FROM_THE_PLAIN_PIPELINE {
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
    for program in [Program::Integrator, Program::Trace] {
        let lens = assemble(program, &FeatureSet { depth_of_field: true, ..plain });
        assert!(lens.contains("fn sample_aperture"), "no aperture in the depth-of-field {program:?} pipeline");
        let panorama = assemble(program, &FeatureSet { panorama: true, ..plain });
        assert!(panorama.contains("fn panorama_direction"), "no panorama in the panoramic {program:?} pipeline");
    }
    // Includes inside dropped blocks are not followed: the files are not there at all.
    for file in [
        "sphere.wgsl",
        "sphere_test.wgsl",
        "microfacet.wgsl",
        "dielectric.wgsl",
        "sun.wgsl",
        "segment.wgsl",
        "texture.wgsl",
        "environment.wgsl",
        "panorama.wgsl",
    ] {
        assert!(!files_in(&source).contains(&file), "{file} is in the plain pipeline");
    }
    let uniform_sun = FeatureSet { sky: SkyFeature::Uniform, sun: true, ..plain };
    for program in [Program::Integrator, Program::Trace] {
        let source = assemble(program, &uniform_sun);
        assert!(!source.contains("atmosphere_"), "the atmosphere is in a uniform sky's {program:?} pipeline");
    }
    let trace = assemble(Program::Trace, &all_on());
    for file in ["bsdf.wgsl", "sampling.wgsl", "lights.wgsl", "integrator.wgsl"] {
        assert!(!files_in(&trace).contains(&file), "{file} is in the trace kernel");
    }
}

#[test]
fn shaders_on_disk_assemble_like_the_built_in_ones_and_errors_name_the_file() {
    let all = all_on();
    let disk = ShaderFiles::Dir(PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("shaders"));
    for program in [Program::Integrator, Program::Trace] {
        assert_eq!(assemble_from(&disk, program, &all), Ok(assemble(program, &all)));
    }
    let missing = ShaderFiles::Dir(PathBuf::from("/nonexistent/shaders"));
    let error = assemble_from(&missing, Program::Trace, &all).expect_err("no files");
    assert!(error.starts_with("/nonexistent/shaders/trace_kernel.wgsl: cannot read"), "{error}");
    let copies: Vec<(&str, String)> = built_in_files()
        .map(|(name, text)| {
            (name, if name == "sky.wgsl" { format!("{text}\nfn oops( {{\n") } else { text.to_string() })
        })
        .collect();
    let copies: Vec<(&str, &str)> = copies.iter().map(|(name, text)| (*name, text.as_str())).collect();
    let broken = folder("broken", &copies);
    let error = assemble_from(&ShaderFiles::Dir(broken.clone()), Program::Integrator, &all).expect_err("broken");
    assert!(error.starts_with("shaders/sky.wgsl: ") && error.contains("oops"), "{error}");
    let _ = std::fs::remove_dir_all(&broken);
}

#[test]
fn a_missing_include_or_an_include_cycle_is_an_error_naming_both_files() {
    let none = |_: &str| None;
    let dir = folder(
        "includes",
        &[
            ("entry.wgsl", "// entry\n//#include \"a.wgsl\"\nfn entry() {}\n"),
            ("a.wgsl", "//#include \"b.wgsl\"\nfn a() {}\n"),
            ("b.wgsl", "\n//#include \"a.wgsl\"\n"),
            ("lost.wgsl", "//#include \"nowhere.wgsl\"\n"),
            ("odd.wgsl", "//#include <a.wgsl>\n"),
            ("diamond.wgsl", "//#include \"left.wgsl\"\n//#include \"right.wgsl\"\n"),
            ("left.wgsl", "//#include \"base.wgsl\"\nfn left() {}\n"),
            ("right.wgsl", "//#include \"base.wgsl\"\nfn right() {}\n"),
            ("base.wgsl", "fn base() {}\n"),
        ],
    );
    let files = ShaderFiles::Dir(dir.clone());
    let cycle = resolve(&files, "entry.wgsl", &none).expect_err("a cycle");
    assert_eq!(cycle, "shaders/b.wgsl:2: including a.wgsl closes a cycle: a.wgsl → b.wgsl → a.wgsl");
    let lost = resolve(&files, "lost.wgsl", &none).expect_err("a missing file");
    let expected = format!(
        "shaders/lost.wgsl:1: cannot include nowhere.wgsl: {}: cannot read",
        dir.join("nowhere.wgsl").display()
    );
    assert!(lost.starts_with(&expected), "{lost}");
    let odd = resolve(&files, "odd.wgsl", &none).expect_err("a malformed include");
    assert!(odd.starts_with("shaders/odd.wgsl:1: expected `//#include \"file.wgsl\"`"), "{odd}");
    let diamond = resolve(&files, "diamond.wgsl", &none).expect("no cycle");
    assert_eq!(files_in(&diamond), ["base.wgsl", "left.wgsl", "right.wgsl", "diamond.wgsl"]);
    let built_in = resolve(&ShaderFiles::BuiltIn, "nowhere.wgsl", &none).expect_err("not built in");
    assert_eq!(built_in, "shaders/nowhere.wgsl: no such file among the built-in shaders");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn includes_follow_the_flags() {
    let dir = folder(
        "flags",
        &[
            ("entry.wgsl", "//#if x\n//#include \"on.wgsl\"\n//#else\n//#include \"off.wgsl\"\n//#endif\n"),
            ("on.wgsl", "fn on() {}\n"),
        ],
    );
    let files = ShaderFiles::Dir(dir.clone());
    let source = resolve(&files, "entry.wgsl", &|_| Some(true)).expect("off.wgsl is not read");
    assert_eq!(source, "// ---- shaders/on.wgsl\nfn on() {}\n// ---- shaders/entry.wgsl\n");
    let error = resolve(&files, "entry.wgsl", &|_| Some(false)).expect_err("off.wgsl is missing");
    assert!(error.starts_with("shaders/entry.wgsl:4: cannot include off.wgsl"), "{error}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn directive_mistakes_name_the_file_and_line() {
    let all = all_on();
    let unbalanced = kept_lines("bsdf.wgsl", "a\n//#if glossy\nb\n", &|f| all.flag(f)).expect_err("unclosed");
    assert_eq!(unbalanced, "shaders/bsdf.wgsl: unclosed #if");
    let unknown = kept_lines("bsdf.wgsl", "//#if shiny\n//#endif\n", &|f| all.flag(f)).expect_err("unknown");
    assert_eq!(unknown, "shaders/bsdf.wgsl:1: unknown flag `shiny`");
}

#[test]
fn preprocessor_nests_and_negates() {
    let text = "a\n//#if x\nb\n//#if !y\nc\n//#else\nd\n//#endif\n//#else\ne\n//#endif\nf\n";
    let run = |x: bool, y: bool| {
        let kept = kept_lines("t", text, &|n| Some(if n == "x" { x } else { y })).expect("balanced");
        kept.into_iter().map(|(_, line)| line).collect::<Vec<_>>().join("")
    };
    assert_eq!(run(true, false), "abcf");
    assert_eq!(run(true, true), "abdf");
    assert_eq!(run(false, false), "aef");
}
