//! Feature analysis: which effects a scene needs, so that the GPU runs only their code.

use super::feature_flags::{self, Flag};
use super::lobe;
use super::{
    Light, LightSampler, LightShape, Material, Microfacet, Projection, RoughTransmission, Sampling, Scene, Sky,
};
use std::fmt;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SkyFeature {
    Black,
    Uniform,
    /// A uniform sky, light-sampled by next-event estimation too (`sample_as_light`).
    UniformLight,
    Atmosphere,
    /// An equirectangular image, light-sampled by next-event estimation.
    Environment,
    /// A World's node graph, evaluated by the rays that leave the scene.
    Graph,
}

impl SkyFeature {
    pub fn of(sky: &Sky) -> Self {
        match sky {
            Sky::Black => SkyFeature::Black,
            Sky::Uniform { sample_as_light: false, .. } => SkyFeature::Uniform,
            Sky::Uniform { sample_as_light: true, .. } => SkyFeature::UniformLight,
            Sky::Atmosphere(_) => SkyFeature::Atmosphere,
            Sky::Environment(_) => SkyFeature::Environment,
            Sky::Graph(_) => SkyFeature::Graph,
        }
    }
}

/// What refraction the scene's materials need.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Transmission {
    None,
    /// Only perfectly smooth interfaces.
    Smooth,
    /// At least one rough interface, with this model (smooth ones are handled too).
    Rough(RoughTransmission),
}

impl Transmission {
    /// What the materials that may transmit need; rough ones take `model`.
    fn of(transmissive: &[&Material], model: RoughTransmission) -> Self {
        if transmissive.is_empty() {
            Transmission::None
        } else if transmissive.iter().any(|m| m.alpha() >= ALPHA_DELTA) {
            Transmission::Rough(model)
        } else {
            Transmission::Smooth
        }
    }
}

/// Which kinds of `[[light]]` lamps a scene has: each kind's code is in the pipeline only
/// when one is present.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct LampKinds {
    pub point: bool,
    pub spot: bool,
    pub area: bool,
    pub sun: bool,
}

impl LampKinds {
    pub fn of(lights: &[Light]) -> Self {
        let mut kinds = Self::default();
        for l in lights {
            match l.shape {
                LightShape::Point { .. } => kinds.point = true,
                LightShape::Spot { .. } => kinds.spot = true,
                LightShape::Area { .. } => kinds.area = true,
                LightShape::Sun { .. } => kinds.sun = true,
            }
        }
        kinds
    }

    pub fn any(&self) -> bool {
        self.point || self.spot || self.area || self.sun
    }

    pub const ALL: Self = Self { point: true, spot: true, area: true, sun: true };
}

feature_flags::feature_set! {
    /// The effects a scene calls for. Each one selects shader code; an absent
    /// effect's code is not in the pipeline that runs. The flags are declared once, here
    /// (`feature_flags`): each flag's name is its name in the shaders' `//#if` lines.
    #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
    pub struct FeatureSet {
        pub sky: SkyFeature,
        pub transmission: Transmission,
        /// `[[light]]` lamps, by kind.
        pub lamps: LampKinds,
        pub sampling: Sampling,
        /// Names the node programs' shapes whose code the pipeline specialises (the scene
        /// geometry's `node_code`); 0: the node programs are interpreted.
        pub node_code: u64,
        /// The lobe modules some material uses (`lobe::bit`), each one's code behind its
        /// flag `lobe_NAME`.
        pub lobe_modules: u32,
    }
    flags {
        triangles: Effect;
        spheres: Effect;
        emission: Effect;
        /// The sky's sun (`[sun]`).
        sun: Effect;
        /// GGX reflection: a rough `specular` or `reflection` lobe.
        glossy: Effect;
        /// Absorption or emission inside transmissive materials.
        media: Effect needs glass;
        /// Image textures on some material (or a node graph, which reads the uvs they read).
        textures: Effect;
        /// Shader node graphs drive some material's inputs (`asset::node_graph`).
        node_graphs: Effect needs textures, glossy;
        /// Cut-outs: some material's alpha can remove parts of its surface, for every ray.
        alpha_mask: Effect needs textures;
        /// Stochastic transparency: some material's opacity is a probability (glTF BLEND).
        alpha_blend: Effect needs alpha_mask;
        /// Tangent-space normal maps on some material.
        normal_maps: Effect needs textures;
        /// Some material's texture reads a mesh's second uv set.
        uv_sets: Effect needs textures;
        /// Some node graph reads a mesh's named attributes (Attribute, Color Attribute).
        attributes: Effect needs node_graphs;
        /// A thin-lens camera: rays start across the aperture.
        depth_of_field: Setting;
        /// A panoramic camera (equirectangular, fisheye, mirror ball).
        panorama: Setting;
        /// Light sampling walks the light tree (`light_sampler = "tree"`, with lights to put in it).
        light_tree: Setting needs nee;
        /// Albedo, normal and depth images beside the radiance (asked for by a render, not a scene).
        aovs: Output;
        /// Pixels stop taking samples once their noise is below a threshold (asked for by a render).
        adaptive: Output;
        /// Exact integer sums of the samples beside the running means, so that parts of a
        /// render merge into the image one render gives (asked for by `rt render`).
        exact_sums: PricedOutput;
        /// Film › Transparent: camera rays that leave the scene add nothing and count as
        /// uncovered (`[render] transparent`).
        transparent_film: Output;
        /// Cycles' multiscatter GGX (`[render] microfacet`) for the scene's rough lobes, metals
        /// and glass.
        multiscatter: Setting;
        /// Some diffuse lobe lies under a dielectric coating (`specular_ior_level`).
        coating: Effect;
        /// Some material has a coat layer (`coat`).
        coat: Effect;
        /// Some coat is shaded with a normal of its own (Principled's Coat Normal): a coat over
        /// a normal map it does not share, or with a normal map of its own.
        coat_normal: Effect needs coat, normal_maps;
        /// Some material has a sheen layer (`sheen`).
        sheen: Effect;
        /// Some material's rough lobes are anisotropic (`anisotropy`).
        anisotropy: Effect;
        /// Some material has a thin film (`thin_film_thickness`).
        thin_film: Effect;
        /// Textures on some material's coat, sheen, anisotropy or specular tint.
        layer_textures: Effect needs textures;
        /// Some anisotropic material follows its uv map's tangents (`tangent = "uv"`).
        uv_tangents: Effect needs anisotropy;
        /// Some diffuse lobe is Oren-Nayar (`diffuse_roughness`).
        rough_diffuse: Effect;
        /// Triangles with interpolated normals shaded as Cycles shades them (in Cycles'
        /// material model, `microfacet = "multiscatter"`): the shadow terminator offset,
        /// directions judged by the geometry rather than folded, and Bump Map Correction.
        smooth_normals: Effect needs triangles;
        /// Some object has a Shadow Terminator Shading Offset: its lobes' cosines are shifted
        /// towards the light (Cycles' `shift_cos_in`).
        terminator_offset: Effect needs triangles;
        /// Some material's BSDF is scaled (`closure_weight`: an Add Shader's halves).
        closure_weights: Effect;
        /// Some material is (partly) a Holdout shader, or some object a holdout: the pixels'
        /// alpha is counted, and held-out surfaces take from it.
        holdout: Effect;
        /// Some object's Object Color is not white: Object Info nodes read the instances'
        /// colours, after their settings (white otherwise).
        object_colors: Setting needs node_graphs;
        /// Motion blur of the camera: it moves over the shutter; each sample has a time, at
        /// which its camera ray starts.
        camera_motion: Effect;
        /// Motion blur of objects: some instance moves over the shutter; each sample has a
        /// time, at which every ray of its path sees the instances.
        object_motion: Effect;
    }
}

/// The α below which a lobe is a perfect mirror or interface (`ALPHA_DELTA` in `shaders/bsdf.wgsl`).
pub const ALPHA_DELTA: f32 = 1e-3;

/// What the loaded geometry holds, as far as the feature set cares: a summary the
/// BVH room makes of a scene once its assets are loaded.
#[derive(Clone, Debug, Default)]
pub struct GeometrySummary {
    pub triangles: bool,
    pub spheres: bool,
    /// Some triangle's vertex normals differ from its face's (a smooth-shaded mesh).
    pub smooth_normals: bool,
    /// Some placed instance has a Shadow Terminator Shading Offset.
    pub shading_offsets: bool,
    /// Some placed instance is a holdout.
    pub held_out: bool,
    /// Some placed instance's Object Color is not white.
    pub object_colors: bool,
    /// Some placed instance moves over the shutter.
    pub moving: bool,
    /// Some emissive instance moves over the shutter: lights are sampled by power, not the tree.
    pub moving_lights: bool,
    /// Names the node programs' shapes when the pipeline specialises them (0: the interpreter).
    pub node_code: u64,
    /// Some material in use has a node graph that sets its normal (a Bump node).
    pub graph_normals: bool,
    /// Some mesh has named attributes and some node graph in use reads them.
    pub attributes_read: bool,
    /// Every material some triangle or sphere uses (an asset's own materials may
    /// emit or refract).
    pub materials_in_use: Vec<Material>,
}

impl FeatureSet {
    /// Derives the set from what the scene really contains, after its assets are loaded.
    pub fn analyse(scene: &Scene, geometry: &GeometrySummary) -> Self {
        let settings = &scene.render;
        let materials_in_use = &geometry.materials_in_use;
        let rough = |m: &&Material| m.alpha() >= ALPHA_DELTA;
        let transmissive: Vec<&Material> = materials_in_use.iter().filter(|m| m.may_transmit()).collect();
        Self {
            triangles: geometry.triangles,
            spheres: geometry.spheres,
            emission: materials_in_use.iter().any(|m| m.is_emissive()),
            sky: SkyFeature::of(&scene.sky),
            sun: scene.sun.is_some(),
            // A metallic-roughness texture may make any texel a rough metal.
            glossy: materials_in_use.iter().any(|m| {
                ((m.specular > 0.0 || m.reflection > 0.0 || m.dielectric_coating().is_some()) && rough(&m))
                    || m.textures.metallic_roughness.is_some()
                    || !m.node_program.is_empty()
                    || m.coat_roughness * m.coat_roughness >= ALPHA_DELTA && m.coat > 0.0
            }),
            transmission: Transmission::of(&transmissive, settings.rough_transmission),
            media: transmissive.iter().any(|m| m.has_medium()),
            lamps: LampKinds::of(&scene.lights),
            // Alpha from a factor alone (a Mix Shader with Transparent) still reads the
            // texture code that tests opacity.
            textures: materials_in_use.iter().any(|m| m.textures.any() || m.textures.has_alpha())
                || materials_in_use.iter().any(|m| !m.node_program.is_empty()),
            node_graphs: materials_in_use.iter().any(|m| !m.node_program.is_empty()),
            node_code: geometry.node_code,
            lobe_modules: materials_in_use.iter().filter_map(|m| m.lobe).fold(0, |bits, l| bits | lobe::bit(l.module)),
            alpha_mask: materials_in_use.iter().any(|m| m.textures.has_alpha()),
            alpha_blend: materials_in_use.iter().any(|m| m.textures.alpha_blend),
            normal_maps: materials_in_use.iter().any(|m| m.textures.has_normal_map()) || geometry.graph_normals,
            uv_sets: materials_in_use.iter().any(|m| m.textures.uses_second_uv_set()),
            attributes: geometry.attributes_read,
            sampling: settings.sampling,
            depth_of_field: scene.camera.depth_of_field.is_some(),
            panorama: matches!(scene.camera.projection, Projection::Panoramic { .. }),
            light_tree: settings.light_sampler == LightSampler::Tree
                && !geometry.moving_lights
                && settings.sampling == Sampling::Nee
                && (materials_in_use.iter().any(|m| m.is_emissive()) || scene.lights.iter().any(|l| !l.is_sun())),
            aovs: false,
            adaptive: false,
            exact_sums: false,
            transparent_film: settings.transparent,
            multiscatter: settings.microfacet == Microfacet::Multiscatter
                && materials_in_use.iter().any(|m| {
                    m.reflection > 0.0
                        || m.may_transmit()
                        || m.textures.metallic_roughness.is_some()
                        || !m.node_program.is_empty()
                        || (rough(&m) && (m.specular > 0.0 || m.dielectric_coating().is_some()))
                        || m.coat > 0.0
                }),
            coating: materials_in_use.iter().any(|m| m.dielectric_coating().is_some()),
            coat: materials_in_use.iter().any(|m| m.coat > 0.0),
            coat_normal: materials_in_use.iter().any(Material::has_own_coat_normal),
            sheen: materials_in_use.iter().any(|m| m.sheen > 0.0),
            anisotropy: materials_in_use.iter().any(|m| m.anisotropy > 0.0),
            thin_film: materials_in_use.iter().any(|m| m.has_thin_film()),
            layer_textures: materials_in_use.iter().any(|m| m.textures.layers.any()),
            uv_tangents: materials_in_use.iter().any(|m| m.reads_uv_tangents()),
            rough_diffuse: materials_in_use.iter().any(|m| m.has_rough_diffuse()),
            // Mitsuba's material model (`single`) folds leaking directions above the surface.
            smooth_normals: geometry.smooth_normals && settings.microfacet == Microfacet::Multiscatter,
            terminator_offset: geometry.shading_offsets,
            closure_weights: materials_in_use.iter().any(|m| m.closure_weight != 1.0),
            holdout: geometry.held_out || materials_in_use.iter().any(|m| m.holdout > 0.0),
            object_colors: geometry.object_colors && materials_in_use.iter().any(|m| !m.node_program.is_empty()),
            camera_motion: scene.camera.motion.is_some(),
            object_motion: geometry.moving,
        }
    }

    /// Every effect on: the pipeline a scene would run without specialisation.
    pub fn all(sky: SkyFeature, sampling: Sampling, rough: RoughTransmission) -> Self {
        let mut set =
            Self::with_flags_off(sky, Transmission::Rough(rough), LampKinds::ALL, sampling, 0, lobe::all_bits());
        for flag in FLAGS.iter().filter(|f| f.in_all_features()) {
            (flag.set)(&mut set, true);
        }
        // A flag whose needs the kept choices deny stays off (the light tree under resampling).
        for flag in FLAGS {
            if !set.needs_met(flag) {
                (flag.set)(&mut set, false);
            }
        }
        set
    }

    /// Whether the image has an alpha channel: a transparent film's, or one that holdouts
    /// take from (counted with the AOVs).
    pub fn has_alpha(&self) -> bool {
        self.transparent_film || self.holdout
    }

    /// Whether the preprocessor flag `name` (as in `//#if name` in `shaders/`) is on: one
    /// of the set's flags, or one derived from them.
    pub fn flag(&self, name: &str) -> Option<bool> {
        match feature_flags::named(name) {
            Some(flag) => Some((flag.get)(self)),
            None => self.derived_flag(name),
        }
    }

    /// Whether `flag` is off, or on with everything it needs.
    pub fn needs_met(&self, flag: &Flag) -> bool {
        !(flag.get)(self) || flag.needs.iter().all(|need| self.flag(need) == Some(true))
    }

    /// Whether every flag that is on has what it needs: a set a scene's analysis can give.
    pub fn consistent(&self) -> bool {
        FLAGS.iter().all(|flag| self.needs_met(flag))
    }

    /// Turns on what the set's flags need (an alpha mask's textures, a medium's glass),
    /// and what those need in turn.
    pub fn complete(&mut self) {
        while let Some(flag) = FLAGS.iter().find(|flag| !self.needs_met(flag)) {
            for need in flag.needs {
                self.turn_on(need);
            }
        }
    }

    /// Turns on the flag `name`: one of the set's own, smooth glass where there is none,
    /// or next-event estimation.
    fn turn_on(&mut self, name: &str) {
        match (feature_flags::named(name), name) {
            (Some(flag), _) => (flag.set)(self, true),
            (None, "glass") if self.transmission == Transmission::None => self.transmission = Transmission::Smooth,
            (None, "nee") => self.sampling = Sampling::Nee,
            _ => {}
        }
    }

    /// The flags made of others or of the fields that are not flags.
    fn derived_flag(&self, name: &str) -> Option<bool> {
        Some(match name {
            "sky_black" => self.sky == SkyFeature::Black,
            "sky_uniform" => matches!(self.sky, SkyFeature::Uniform | SkyFeature::UniformLight),
            "sky_uniform_light" => self.sky == SkyFeature::UniformLight,
            "sky_atmosphere" => self.sky == SkyFeature::Atmosphere,
            "sky_environment" => self.sky == SkyFeature::Environment,
            "sky_graph" => self.sky == SkyFeature::Graph,
            "glass" => self.transmission != Transmission::None,
            "rough_glass_ggx" => self.transmission == Transmission::Rough(RoughTransmission::Ggx),
            "rough_glass_cone" => self.transmission == Transmission::Rough(RoughTransmission::Cone),
            "lamps" => self.lamps.any(),
            "lamp_point" => self.lamps.point,
            "lamp_spot" => self.lamps.spot,
            // Point and spot lamps share their shapes (a point, a facing disk, a sphere).
            "lamp_round" => self.lamps.point || self.lamps.spot,
            "lamp_area" => self.lamps.area,
            "lamp_sun" => self.lamps.sun,
            // Specialised node code, appended to the module (`gpu::node_code`).
            "node_code" => self.node_graphs && self.node_code != 0,
            "nee" => self.sampling == Sampling::Nee,
            // Normal maps and uv tangents read the triangles' tangents.
            "tangent_frames" => self.normal_maps || self.uv_tangents,
            // Surfaces whose lobes follow Cycles' rules (lobe_hemispheres.wgsl) exist.
            "cycles_lobe_rules" => self.normal_maps || self.smooth_normals,
            // A time per sample.
            "motion" => self.camera_motion || self.object_motion,
            // Each instance's Shadow Terminator settings, read by both, its holdout, and
            // what Object Info nodes read.
            "object_settings" => self.smooth_normals || self.terminator_offset || self.holdout || self.node_graphs,
            "microfacet_tables" => self.multiscatter || self.coating || self.coat || self.sheen || self.thin_film,
            // Lobe modules (`scene::lobe`), any and each.
            "lobe_modules" => self.lobe_modules != 0,
            _ => return lobe::flag_index(name).map(|i| self.lobe_modules & lobe::bit(i) != 0),
        })
    }
}

impl fmt::Display for FeatureSet {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut parts: Vec<String> = FLAGS.iter().filter(|flag| (flag.get)(self)).map(Flag::label).collect();
        if self.node_graphs
            && self.node_code != 0
            && let Some(graphs) = parts.iter_mut().find(|p| *p == "node-graphs")
        {
            graphs.push_str("=specialised");
        }
        match self.transmission {
            Transmission::None => {}
            Transmission::Smooth => parts.push("glass".into()),
            Transmission::Rough(RoughTransmission::Ggx) => parts.push("rough-glass=ggx".into()),
            Transmission::Rough(RoughTransmission::Cone) => parts.push("rough-glass=cone".into()),
        }
        let lamps: Vec<&str> = [
            (self.lamps.point, "point"),
            (self.lamps.spot, "spot"),
            (self.lamps.area, "area"),
            (self.lamps.sun, "sun"),
        ]
        .iter()
        .filter(|(on, _)| *on)
        .map(|(_, name)| *name)
        .collect();
        if !lamps.is_empty() {
            parts.push(format!("lamps={}", lamps.join(",")));
        }
        parts.push(format!("sky={}", format!("{:?}", self.sky).to_lowercase()));
        parts.push(format!("sampling={}", format!("{:?}", self.sampling).to_lowercase()));
        let lobes: Vec<&str> = (lobe::LOBES.iter().enumerate())
            .filter(|(i, _)| self.lobe_modules & lobe::bit(*i) != 0)
            .map(|(_, l)| l.name)
            .collect();
        if !lobes.is_empty() {
            parts.push(format!("lobes={}", lobes.join(",")));
        }
        f.write_str(&parts.join(" "))
    }
}

#[cfg(test)]
#[path = "features_tests.rs"]
mod tests;
