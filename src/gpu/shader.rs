//! WGSL assembly: the pipeline for a feature set is built from the shader
//! files that set needs, and from stand-ins that do nothing for the effects it lacks.

use crate::scene::{FeatureSet, SkyFeature};

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
const BOTTOM_LEVEL_ABSENT: Part = shader!("bottom_level_absent.wgsl");
const SPHERE_TEST: Part = shader!("sphere_test.wgsl");
const SPHERE_ABSENT: Part = shader!("sphere_absent.wgsl");
const CAMERA: Part = shader!("camera.wgsl");
const SKY_BLACK: Part = shader!("sky_black.wgsl");
const SKY_UNIFORM: Part = shader!("sky_uniform.wgsl");
const EMISSION: Part = shader!("emission.wgsl");
const EMISSION_ABSENT: Part = shader!("emission_absent.wgsl");
const BSDF: Part = shader!("bsdf.wgsl");
const INTEGRATOR: Part = shader!("integrator.wgsl");
const TRACE_KERNEL: Part = shader!("trace_kernel.wgsl");

/// Which entry points a module carries.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Program {
    /// `render`: the path-tracing megakernel.
    Integrator,
    /// `trace`, `generate_camera_rays`, `generate_diffuse_rays`.
    Trace,
}

fn geometry_parts(features: &FeatureSet) -> Vec<Part> {
    let mut parts = vec![COMMON, RNG, RAY, TRAVERSE, SURFACE, CAMERA];
    parts.push(if features.triangles { BOTTOM_LEVEL } else { BOTTOM_LEVEL_ABSENT });
    if features.triangles {
        parts.push(TRIANGLE);
    }
    if features.spheres {
        parts.extend([SPHERE, SPHERE_TEST]);
    } else {
        parts.push(SPHERE_ABSENT);
    }
    parts
}

/// The WGSL source of `program` specialised to `features`.
pub fn assemble(program: Program, features: &FeatureSet) -> String {
    let mut parts = geometry_parts(features);
    match program {
        Program::Integrator => {
            parts.push(match features.sky {
                SkyFeature::Black => SKY_BLACK,
                // The atmosphere has no shader yet; `render` refuses such scenes before this.
                SkyFeature::Uniform | SkyFeature::Atmosphere => SKY_UNIFORM,
            });
            parts.push(if features.emission { EMISSION } else { EMISSION_ABSENT });
            parts.extend([BSDF, INTEGRATOR]);
        }
        Program::Trace => parts.extend([BSDF, TRACE_KERNEL]),
    }
    join(&parts)
}

fn join(parts: &[Part]) -> String {
    let mut source = String::new();
    for (name, text) in parts {
        source.push_str(&format!("// ---- shaders/{name}\n"));
        source.push_str(text);
        source.push('\n');
    }
    source
}

/// Every shader file in one module, for the struct layout test.
#[cfg(test)]
pub fn full_source_for_layout_checks() -> String {
    let mut parts = geometry_parts(&FeatureSet::all());
    parts.extend([SKY_UNIFORM, EMISSION, BSDF, INTEGRATOR, TRACE_KERNEL]);
    join(&parts)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn all_feature_sets() -> Vec<FeatureSet> {
        let mut sets = Vec::new();
        for bits in 0..8u32 {
            for sky in [SkyFeature::Black, SkyFeature::Uniform] {
                sets.push(FeatureSet {
                    triangles: bits & 1 != 0,
                    spheres: bits & 2 != 0,
                    emission: bits & 4 != 0,
                    sky,
                });
            }
        }
        sets
    }

    #[test]
    fn every_feature_set_assembles_to_valid_wgsl() {
        for features in all_feature_sets() {
            for program in [Program::Integrator, Program::Trace] {
                let source = assemble(program, &features);
                let module = wgpu::naga::front::wgsl::parse_str(&source)
                    .unwrap_or_else(|e| panic!("{features} {program:?}: {}", e.emit_to_string(&source)));
                wgpu::naga::valid::Validator::new(Default::default(), wgpu::naga::valid::Capabilities::all())
                    .validate(&module)
                    .unwrap_or_else(|e| panic!("{features} {program:?}: {}", e.emit_to_string(&source)));
            }
        }
    }

    #[test]
    fn absent_effects_leave_no_code() {
        let plain = FeatureSet { triangles: true, spheres: false, emission: false, sky: SkyFeature::Black };
        let source = assemble(Program::Integrator, &plain);
        assert!(!source.contains("fn intersect_sphere"));
        assert!(!source.contains("return m.emission"));
        assert!(!source.contains("frame.sky_color"));
    }
}
