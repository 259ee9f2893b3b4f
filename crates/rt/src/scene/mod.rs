//! Scene files (contract 3): schema, parsing with located errors, validation,
//! and the feature analysis that picks a specialised GPU pipeline.

mod atmosphere;
mod builtin;
mod camera;
mod environment;
pub mod feature_flags;
mod features;
mod light;
pub mod lobe;
mod material;
mod material_textures;
mod motion;
mod object_info;
mod panorama;
mod parse;
mod schema;
mod shadow_terminator;
#[cfg(test)]
mod tests;
mod validate;

pub use atmosphere::Atmosphere;
pub use builtin::{BUILTIN_PREFIX, default_scene};
pub use camera::{Camera, DepthOfField, MAX_BLADES, Projection, SensorFit};
pub use environment::Environment;
pub use feature_flags::{Flag, Role};
pub use features::{ALPHA_DELTA, FLAGS, FeatureSet, GeometrySummary, LampKinds, SkyFeature, Transmission};
pub use light::{AreaShape, Light, LightShape};
pub use material::{Material, Tangent, luminance, srgb_decode, srgb_encode};
pub use material_textures::{LAYER_COUNT, LayerTextures, MaterialTextures, UvSet, slots};
pub use motion::{Decomposed, MAX_CAMERA_MOTION_KEYS, MAX_MOTION_KEYS, Motion, interpolate};
pub use object_info::{MAX_OBJECT_INDEX, ObjectInfo};
pub use panorama::Panorama;
pub use parse::{SceneError, hint as did_you_mean, load, parse};
pub use shadow_terminator::ShadowTerminator;
pub use validate::MAX_IMAGE_SIDE;

use glam::{Mat4, Vec3};
use serde::Deserialize;
use std::path::PathBuf;

/// Defaults for `rt render`; the command line overrides them. Also the `[render]`
/// table's schema: every key is optional.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RenderSettings {
    pub width: u32,
    pub height: u32,
    pub spp: u32,
    pub max_bounces: u32,
    /// Exposure in EV, applied before tone mapping (PNG only).
    pub exposure: f32,
    pub sampling: Sampling,
    /// Candidates per resampled direction in `resampled` sampling.
    pub ris_candidates: u32,
    pub rough_transmission: RoughTransmission,
    pub light_sampler: LightSampler,
    /// Adaptive sampling: a pixel stops once the relative standard error of its mean
    /// luminance is below this (0: off), after `adaptive_min_samples` samples.
    pub noise_threshold: f32,
    pub adaptive_min_samples: u32,
    pub microfacet: Microfacet,
    /// Blender's Film › Transparent: the background seen by camera rays is left out of the
    /// image and each pixel's alpha is the share of its camera rays that met the scene.
    pub transparent: bool,
    /// Film › Transparent Glass: with a transparent film, the background seen through
    /// glass whose roughness is at most `transparent_glass_roughness` (Cycles' Roughness
    /// Threshold) is left out too, as Cycles leaves it out.
    pub transparent_glass: bool,
    pub transparent_glass_roughness: f32,
}

impl Default for RenderSettings {
    fn default() -> Self {
        Self {
            width: 640,
            height: 480,
            spp: 256,
            max_bounces: 12,
            exposure: 0.0,
            sampling: Sampling::Nee,
            ris_candidates: 8,
            rough_transmission: RoughTransmission::Ggx,
            light_sampler: LightSampler::Power,
            noise_threshold: 0.0,
            adaptive_min_samples: 16,
            microfacet: Microfacet::Multiscatter,
            transparent: false,
            transparent_glass: false,
            transparent_glass_roughness: 0.1,
        }
    }
}

impl RenderSettings {
    /// The GGX α (roughness²) up to which glass lets the camera see a transparent
    /// background: Cycles keeps glass whose roughness is at most the Roughness Threshold;
    /// negative where the film or its glass is not transparent.
    pub fn transparent_glass_alpha(&self) -> f32 {
        let threshold = self.transparent_glass_roughness;
        if self.transparent && self.transparent_glass { threshold * threshold } else { -1.0 }
    }
}

/// How a path finds light.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Deserialize, clap::ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum Sampling {
    /// No light sampling: each bounce resamples (RIS) candidate directions drawn
    /// from the BSDF and the sun disk, weighted by the BSDF. `"seed"` is read as an
    /// alias: the name of the renderer rt grew from, whose scheme this is.
    #[serde(alias = "seed")]
    #[value(alias = "seed")]
    Resampled,
    /// Next-event estimation towards emitters and the sun, combined with BSDF
    /// sampling by multiple importance sampling (power heuristic).
    #[default]
    Nee,
}

/// How next-event estimation picks the lamp or emissive surface to sample.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Deserialize, clap::ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum LightSampler {
    /// In proportion to power, wherever the shaded point is.
    #[default]
    Power,
    /// By a walk down the light tree, in proportion to each group's importance seen
    /// from the shaded point (its power, distance and orientation): for many lights.
    Tree,
}

/// The model of rough refraction.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Deserialize, clap::ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum RoughTransmission {
    /// GGX microfacet refraction (Walter et al. 2007).
    #[default]
    Ggx,
    /// A cheaper model: the refracted direction jittered in a cone.
    Cone,
}

/// The model of rough GGX lobes (reflection, metal and refraction).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Deserialize, clap::ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum Microfacet {
    /// Cycles' GGX: height-correlated Smith masking-shadowing and Cycles' energy
    /// compensation for the light that single scattering loses (`microfacet_ggx_preserve_energy`),
    /// F82-tint metals.
    #[default]
    Multiscatter,
    /// Single scattering with separable Smith masking-shadowing and the Fresnel of a
    /// non-absorbing conductor for metals: Mitsuba 3's `roughconductor`/`roughdielectric`.
    Single,
}

/// `[sky]`; black when the table is left out, white when `uniform` has no `color`.
#[derive(Clone, Debug, PartialEq)]
pub enum Sky {
    Black,
    Uniform {
        color: Vec3,
        /// Next-event estimation samples the sky as a light (uniformly over the sphere, as
        /// Mitsuba's `constant` emitter and Cycles' world without an importance map are).
        /// Off by default: a constant sky is found as well by BSDF sampling, and a light
        /// sample of it costs a shadow ray.
        sample_as_light: bool,
    },
    Atmosphere(Atmosphere),
    /// An equirectangular image (HDRI) around the scene.
    Environment(Environment),
    /// A World whose Background a shader node graph drives.
    Graph(WorldGraph),
}

/// `[sky] kind = "graph"`: a World's Background whose colour and strength a shader node
/// graph gives per direction (sky gradients, Light Path tricks), evaluated by every ray
/// that leaves the scene as Cycles evaluates a World's shader.
#[derive(Clone, Debug, PartialEq)]
pub struct WorldGraph {
    /// The graph (`rt_node_graph`, its `emission` output the Background's radiance), a
    /// JSON file resolved against the scene's folder.
    pub graph: PathBuf,
    /// Next-event estimation samples the world (uniformly over the sphere); on by default.
    pub sample_as_light: bool,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Sun {
    pub elevation_deg: f32,
    pub azimuth_deg: f32,
    pub angular_diameter_deg: f32,
    /// Disk radiance above the atmosphere; `None` means the real sun's.
    pub radiance: Option<Vec3>,
}

/// One `[[mesh]]`: an asset placed in the world.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshInstance {
    /// Resolved against the scene file's folder.
    pub asset: PathBuf,
    /// Name of a scene material that replaces the asset's own materials.
    pub material: Option<String>,
    /// `matrix` (row-major in the file), or `T * Rz * Ry * Rx * S`: scale, then rotate
    /// about X, Y, Z by `rotate_deg` (degrees, right-handed), then translate.
    pub object_to_world: Mat4,
    pub shadow_terminator: ShadowTerminator,
    /// Blender's Holdout (the object's or its collection's): the camera sees nothing
    /// where it sees this object, and the pixel's alpha loses it; reflections, shadows and
    /// light bounced from it stay.
    pub holdout: bool,
    /// Its Object Color and Random, for Object Info nodes.
    pub info: ObjectInfo,
    /// Its transforms over the shutter (`motion`): motion blur; `None`: it stands still.
    pub motion: Option<Motion>,
}

/// One `[[instances]]`: an asset placed once per record of an instance file.
#[derive(Clone, Debug, PartialEq)]
pub struct InstanceSet {
    /// Resolved against the scene file's folder, as a `[[mesh]]`'s.
    pub asset: PathBuf,
    /// The `.rtinst` file, resolved against the scene file's folder.
    pub file: PathBuf,
    /// Scene materials by name: a record's material index `i` overrides the asset's
    /// own materials with `materials[i]`.
    pub materials: Vec<String>,
    /// The Shadow Terminator settings of every instance of the file.
    pub shadow_terminator: ShadowTerminator,
    /// Every instance of the file is a holdout (see [`MeshInstance::holdout`]).
    pub holdout: bool,
    /// The Object Color and Random of every instance of the file.
    pub info: ObjectInfo,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Sphere {
    pub center: Vec3,
    pub radius: f32,
    pub material: Option<String>,
}

/// A validated scene: every reference resolves, every number is finite and in range.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// What to call this scene in messages: its path, or `<built-in>`.
    pub origin: String,
    pub render: RenderSettings,
    pub camera: Camera,
    pub sky: Sky,
    pub sun: Option<Sun>,
    /// Materials by name, in file order.
    pub materials: Vec<(String, Material)>,
    pub meshes: Vec<MeshInstance>,
    pub spheres: Vec<Sphere>,
    /// `[[light]]` lamps, in file order.
    pub lights: Vec<Light>,
    pub instance_sets: Vec<InstanceSet>,
}

impl Scene {
    pub fn material_index(&self, name: &str) -> Option<usize> {
        self.materials.iter().position(|(n, _)| n == name)
    }
}
