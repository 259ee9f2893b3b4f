//! The GPU structs: plain data that the BVH builder packs and the GPU room uploads as it
//! is, each declared once here with [`gpu_struct!`], which checks its layout against
//! WGSL's rules as it builds and writes the WGSL declaration the shaders include.

/// Constants the shaders share, declared once (see [`crate::shared_constants`]).
pub use crate::shared_constants::{
    ALPHA_BLEND, EMPTY_LINK, LAMP_AREA, LAMP_CAMERA, LAMP_ELLIPSE, LAMP_KIND, LAMP_POINT, LAMP_SPHERE, LAMP_SPOT,
    LAMP_SUN, LIGHT_TREE_ABSENT, LIGHT_TREE_LAMP, LIGHT_TREE_LEAF, LIGHT_TREE_TWO_SIDED, MOVING_INSTANCE, NO_MATERIAL,
    NO_PROGRAM, NO_TEXTURE, PANORAMA_EQUIRECTANGULAR, PANORAMA_FISHEYE_EQUIDISTANT, PANORAMA_FISHEYE_EQUISOLID,
    PANORAMA_MIRROR_BALL, PANORAMA_NONE, SPHERE_BIT, TANGENT_RADIAL_X, TANGENT_RADIAL_Y, TANGENT_RADIAL_Z, TANGENT_UV,
};

use crate::gpu_struct::{gpu_struct, gpu_struct_files};

gpu_struct_files!(
    GpuFrame,
    GpuMotionKey,
    GpuMotionMatrix,
    GpuBvhNode,
    GpuWideNode,
    GpuTriangle,
    GpuTriangleShading,
    GpuInstance,
    GpuObjectSettings,
    GpuSphere,
    GpuMaterial,
    GpuTriangleTangents,
    GpuTriangleUvs,
    GpuTriangleAttribute,
    GpuTexture,
    GpuEmitter,
    GpuLamp,
    GpuLampInfo,
    GpuLightTreeNode,
    GpuEnvironment,
    GpuAtmosphere,
    GpuTraceRay,
    GpuTraceHit,
);

gpu_struct! {
    #[derive(Debug, Default)]
    pub struct GpuFrame as "Frame" {
        pub camera_position: [f32; 3],
        /// Metres; 0: a pinhole.
        pub aperture_radius: f32,
        pub camera_right: [f32; 3],
        pub focus_distance: f32,
        pub camera_up: [f32; 3],
        pub width: u32,
        pub camera_forward: [f32; 3],
        pub height: u32,
        /// Half the image plane's size and its centre's offset (lens shift), at distance 1
        /// along the view (perspective) or in metres (orthographic).
        pub view_half_extent: [f32; 2],
        pub view_shift: [f32; 2],
        /// 1: parallel rays.
        pub orthographic: u32,
        /// 0: a round aperture; else the sides of a regular polygon.
        pub aperture_blades: u32,
        /// Radians.
        pub blade_rotation: f32,
        pub inv_aperture_ratio: f32,
        pub sky_color: [f32; 3],
        pub max_bounces: u32,
        pub sample_base: u32,
        pub samples_per_dispatch: u32,
        pub seed: u32,
        pub tlas_root: u32,
        /// Unit vector towards the sun's centre.
        pub sun_direction: [f32; 3],
        /// 1 − cos of the sun's angular radius, computed in f64 on the host: in f32,
        /// 1 − cos(0.265°) would keep only two digits.
        pub sun_one_minus_cos: f32,
        /// Disk radiance above any atmosphere.
        pub sun_radiance: [f32; 3],
        /// Probability that next-event estimation samples the sun rather than an emitter.
        pub sun_select_probability: f32,
        pub emitter_count: u32,
        /// Sum of the emitters' powers (area × luminance of emission).
        pub emitter_total_power: f32,
        pub ris_candidates: u32,
        /// Samples whose luminance exceeds this are scaled down to it (0: off). Biased: off by default.
        pub clamp_luminance: f32,
        /// Adaptive sampling: the relative standard error at which a pixel stops, after
        /// `adaptive_min_samples` samples.
        pub noise_threshold: f32,
        pub adaptive_min_samples: u32,
        /// Cycles' clip_start and clip_end, in metres along the view (a plane at each, for
        /// a perspective camera); the far one may be infinite.
        pub clip_start: f32,
        pub clip_end: f32,
        /// A panoramic camera (`panorama.wgsl`; PANORAMA_NONE: none): Cycles' φ = x·u + y,
        /// θ = z·v + w of the equirectangular panorama; the equisolid fisheye's sensor (mm);
        /// the fisheyes' field of view (radians) and the equisolid's lens (mm).
        pub equirectangular_range: [f32; 4],
        /// The equisolid fisheye's sensor width and height, millimetres.
        pub fisheye_sensor: [f32; 2],
        /// Radians.
        pub fisheye_fov: f32,
        /// Millimetres.
        pub fisheye_lens: f32,
        pub panorama: u32,
        /// Film › Transparent Glass: the GGX α up to which glass lets the camera's path keep
        /// the background transparent (the square of Cycles' Roughness Threshold); negative: off.
        pub transparent_glass: f32,
        /// The share of light samples that go to a uniform sky sampled as a light
        /// (`[sky] sample_as_light`), as an environment map's `light_share`.
        pub sky_light_share: f32,
        /// The index of the render's first sample (`--sample-range`): samples draw their random
        /// numbers by their index in the whole render, whichever part of it takes them.
        pub first_sample: u32,
        /// How many of `camera_motion` the camera moves through over the shutter (0: it stands
        /// still; `camera_*` above are its frame then).
        pub camera_motion_steps: u32,
        pub _pad0: [u32; 3],
        /// The camera's frames over the shutter (columns right, up, forward, position), split
        /// for interpolation (`shaders/motion.wgsl`).
        pub camera_motion: [GpuMotionKey; crate::scene::MAX_CAMERA_MOTION_KEYS],
    }
}

gpu_struct! {
    /// One key of a motion over the shutter (`scene::Decomposed`): a unit quaternion, the
    /// translation, and the stretch matrix S (rows r, columns c) as `stretch_xx` = S₀₀,
    /// `stretch_a` = (S₀₁, S₀₂, S₁₀, S₁₁), `stretch_b` = (S₁₂, S₂₀, S₂₁, S₂₂).
    #[derive(Debug, Default, PartialEq)]
    pub struct GpuMotionKey as "MotionKey" {
        /// (x, y, z, w).
        pub rotation: [f32; 4],
        pub translation: [f32; 3],
        pub stretch_xx: f32,
        pub stretch_a: [f32; 4],
        pub stretch_b: [f32; 4],
    }
}

impl From<&crate::scene::Decomposed> for GpuMotionKey {
    fn from(d: &crate::scene::Decomposed) -> Self {
        let s = d.stretch.transpose().to_cols_array_2d().map(|row| row.map(|v| v as f32));
        Self {
            rotation: d.rotation.as_quat().to_array(),
            translation: d.translation.as_vec3().to_array(),
            stretch_xx: s[0][0],
            stretch_a: [s[0][1], s[0][2], s[1][0], s[1][1]],
            stretch_b: [s[1][2], s[2][0], s[2][1], s[2][2]],
        }
    }
}

gpu_struct! {
    /// A moving instance's world-to-object matrix at one time of the shutter: the decomposed
    /// motion sampled densely on the host (`Motion::world_to_object_samples`), so that a ray
    /// meeting the instance only interpolates two of them linearly.
    #[derive(Debug, Default, PartialEq)]
    pub struct GpuMotionMatrix as "MotionMatrix" {
        pub world_to_object: [[f32; 4]; 3],
    }
}

impl From<&glam::DMat4> for GpuMotionMatrix {
    fn from(m: &glam::DMat4) -> Self {
        let row = |r: usize| m.row(r).as_vec4().to_array();
        Self { world_to_object: [row(0), row(1), row(2)] }
    }
}

/// The most motion matrices of all instances together (a motion keeps its first matrix's
/// index in 24 bits).
pub const MAX_INSTANCE_MOTION_MATRICES: usize = 1 << 24;

impl GpuInstance {
    /// Marks the record as moving through `motion` (see [`MOVING_INSTANCE`]).
    pub fn mark_moving(&mut self, motion: u32) {
        self.world_to_object[0][0] = f32::from_bits(MOVING_INSTANCE);
        self.world_to_object[0][1] = f32::from_bits(motion);
    }

    /// Whether the record is marked as moving (see [`MOVING_INSTANCE`]).
    pub fn is_moving(&self) -> bool {
        self.world_to_object[0][0].to_bits() == MOVING_INSTANCE
    }
}

gpu_struct! {
    /// A BVH2 node holding both children's boxes, so that one fetch decides where to go.
    /// count == 0: `link` is the child node's index; count > 0: a leaf of `count`
    /// primitives starting at `link`. An empty child has count 0 and link EMPTY_LINK.
    #[derive(Debug, Default, PartialEq)]
    pub struct GpuBvhNode as "BvhNode" {
        pub a_min: [f32; 3],
        pub a_link: u32,
        pub a_max: [f32; 3],
        pub a_count: u32,
        pub b_min: [f32; 3],
        pub b_link: u32,
        pub b_max: [f32; 3],
        pub b_count: u32,
    }
}

gpu_struct! {
    /// A compressed 8-wide BVH node of a mesh (Ylitie, Karras & Laine 2017; obvhs's
    /// CwBvhNode): child boxes on a grid origin + q · 2^(e − 127) per axis, q one byte per
    /// child and plane; see shaders/wide_bvh.wgsl.
    #[derive(Debug, Default, PartialEq)]
    pub struct GpuWideNode as "WideNode" {
        /// The quantisation grid's origin: the node box's minimum.
        pub origin: [f32; 3],
        /// Bytes 0..3: the biased exponents e of the x, y, z steps; byte 3: imask (bit i: slot i is an inner node).
        pub exponents_imask: [u8; 4],
        /// Index of the first inner child (relative to the mesh's first node); inner children are contiguous.
        pub child_base: u32,
        /// Index of the first triangle of the leaf children (relative to the mesh's first triangle).
        pub primitive_base: u32,
        /// One byte per slot: 0 empty; inner: 0b001_11000 + slot; leaf: the triangle count
        /// in unary in bits 5..8 and its first triangle's offset from primitive_base in bits 0..5.
        pub child_meta: [u8; 8],
        /// One byte per slot: children 0..4 in .x, 4..8 in .y.
        pub child_min_x: [u8; 8],
        pub child_max_x: [u8; 8],
        pub child_min_y: [u8; 8],
        pub child_max_y: [u8; 8],
        pub child_min_z: [u8; 8],
        pub child_max_z: [u8; 8],
    }
}

gpu_struct! {
    #[derive(Debug, Default, PartialEq)]
    pub struct GpuTriangle as "Triangle" {
        pub v0: [f32; 3],
        pub material: u32,
        pub v1: [f32; 3],
        pub _pad1: u32,
        pub v2: [f32; 3],
        pub _pad2: u32,
    }
}

gpu_struct! {
    /// Per-vertex shading normals of one triangle (the geometric normal when the mesh has
    /// none), and texture coordinates: u in the normals' spare words, the three v together.
    #[derive(Debug, Default, PartialEq)]
    pub struct GpuTriangleShading as "TriangleShading" {
        pub n0: [f32; 3],
        /// Texture coordinates of the three vertices: u in the normals' spare words, v together.
        pub u0: f32,
        pub n1: [f32; 3],
        pub u1: f32,
        pub n2: [f32; 3],
        pub u2: f32,
        pub v: [f32; 3],
        pub _pad0: u32,
    }
}

gpu_struct! {
    #[derive(Debug, Default, PartialEq)]
    pub struct GpuInstance as "Instance" {
        /// Rows of the affine 3×4 matrix. Its inverse is derived where a hit or a light
        /// sample needs it (`affine_inverse` in `shaders/transform.wgsl`): traversal, the
        /// hot path, needs only this one, and an instance stays at 64 bytes.
        pub world_to_object: [[f32; 4]; 3],
        pub node_offset: u32,
        pub triangle_offset: u32,
        pub material_base: u32,
        /// `NO_MATERIAL` unless the scene overrides the asset's materials.
        pub material_override: u32,
    }
}

gpu_struct! {
    /// An instance's settings that shading reads (see GpuObjectSettings): its Shadow Terminator
    /// offsets for smooth shading and the terminator shift, whether the object is a holdout,
    /// and Object Info's Random;
    /// beside the instances, so that traversal's records stay small.
    #[derive(Debug, PartialEq)]
    pub struct GpuObjectSettings as "ObjectSettings" {
        /// Blender's Geometry Offset: the cosine below which shadow rays start from the smooth surface.
        pub geometry_offset: f32,
        /// 1 / (1 - Shading Offset / 2): 1 leaves the lobes' cosines alone.
        pub frequency_multiplier: f32,
        /// Bit 0, 1: Blender's Holdout (the object's or its collection's): the camera sees
        /// through it to nothing, and the pixel's alpha loses what it covers; other rays see it
        /// as it is. The bits above: Object Info's Object Index (Blender's Pass Index).
        pub holdout_and_index: u32,
        /// Object Info's Random, in [0, 1] (its Color follows the settings in the same
        /// buffer when some object is coloured, see `SceneGeometry::object_settings`).
        pub random: f32,
    }
}

impl Default for GpuObjectSettings {
    fn default() -> Self {
        Self::new(crate::scene::ShadowTerminator::default(), false, crate::scene::ObjectInfo::default())
    }
}

impl GpuObjectSettings {
    pub fn new(t: crate::scene::ShadowTerminator, holdout: bool, info: crate::scene::ObjectInfo) -> Self {
        Self {
            geometry_offset: t.geometry_offset,
            frequency_multiplier: t.frequency_multiplier(),
            holdout_and_index: u32::from(holdout) | info.index.min(crate::scene::MAX_OBJECT_INDEX) << 1,
            random: info.random,
        }
    }
}

gpu_struct! {
    #[derive(Debug, Default, PartialEq)]
    pub struct GpuSphere as "Sphere" {
        pub center: [f32; 3],
        pub radius: f32,
        pub material: u32,
        /// |center|² − radius², in f64 before rounding (see `sphere_c` in `shaders/sphere.wgsl`).
        pub k: f32,
        pub _pad: [u32; 2],
    }
}

gpu_struct! {
    /// Lobe weights are normalised on the host so that they sum to at most 1.
    #[derive(Debug, Default, PartialEq)]
    pub struct GpuMaterial as "Material" {
        pub base_color: [f32; 3],
        pub diffuse: f32,
        pub emission: [f32; 3],
        pub specular: f32,
        pub absorption: [f32; 3],
        pub reflection: f32,
        pub volume_emission: [f32; 3],
        pub transmission: f32,
        pub ior: f32,
        /// GGX α of the specular, reflection and transmission lobes (from roughness or hardness).
        pub alpha: f32,
        /// Luminance of `emission`, for light selection probabilities.
        pub emission_luminance: f32,
        /// Indices into `textures`, or NO_TEXTURE (see texture.wgsl).
        pub base_color_texture: u32,
        pub metallic_roughness_texture: u32,
        pub emission_texture: u32,
        /// Used with `metallic_roughness_texture`: metal = metallic × B, roughness = roughness × G.
        pub metallic: f32,
        pub roughness: f32,
        /// Opacity = base_alpha × the base colour texture's alpha; below `alpha_cutoff`
        /// (0: opaque) the surface is not there.
        pub base_alpha: f32,
        /// Negative (ALPHA_BLEND): opacity is the probability that the surface is there.
        pub alpha_cutoff: f32,
        /// A tangent-space normal map, or NO_TEXTURE; its x and y are scaled by normal_scale.
        pub normal_texture: u32,
        /// glTF's `normalTexture.scale`: the map's x and y are multiplied by it.
        pub normal_scale: f32,
        /// The F82 tint of the `reflection` metal; the tint of the diffuse's coating's F0.
        pub specular_tint: [f32; 3],
        /// Index of the dielectric coating over the diffuse lobe (0: none; then the
        /// `specular` lobe is that coating), and its F0 before `specular_tint`.
        pub coating_eta: f32,
        /// The coating's F0 before `specular_tint` (Specular IOR Level applied).
        pub coating_f0: f32,
        /// Roughness of the sheen layer (Cycles keeps it in [0.001, 1] for its table).
        pub sheen_roughness: f32,
        /// The rough lobes' stretch along the surface tangent, and the tangent's turn about
        /// the normal (1: a full turn).
        pub anisotropy: f32,
        pub anisotropy_rotation: f32,
        /// The coat: a dielectric GGX layer of weight `coat` over every other lobe (0: none),
        /// and the tint of the light crossing it at normal incidence.
        pub coat_tint: [f32; 3],
        /// Weight of the coat layer over every other lobe; 0: none.
        pub coat: f32,
        pub coat_alpha: f32,
        pub coat_ior: f32,
        /// Which texture slots read the second uv set (`MaterialTextures::second_uv_set`).
        pub second_uv_set: u32,
        /// Oren-Nayar roughness of the diffuse lobe (0: Lambertian; see oren_nayar.wgsl).
        pub diffuse_roughness: f32,
        /// The sheen: Cycles' microfiber layer of weight `sheen` and colour `sheen_tint` over
        /// every other lobe, the coat included (0: none).
        pub sheen_tint: [f32; 3],
        /// Weight of the sheen layer over every other lobe (the coat included); 0: none.
        pub sheen: f32,
        /// The thin film on the specular, metal and glass lobes (see thin_film.wgsl): its
        /// thickness in nm (at most THIN_FILM_CUTOFF: none) and its index.
        pub thin_film_thickness: f32,
        pub thin_film_ior: f32,
        /// 1: Cycles' Bump Map Correction of glossy normals on smooth-shaded surfaces (see
        /// smooth_shading.wgsl), 0: none.
        pub bump_map_correction: u32,
        /// How much of the film there is (KHR_materials_iridescence's factor): the film's
        /// Fresnel and the bare one mixed by it.
        pub thin_film_weight: f32,
        /// The layered lobes' textures, or NO_TEXTURE (`layer_textured` in texture.wgsl): coat
        /// R × coat, G × coat roughness, coat tint RGB, sheen R × sheen and G × its roughness,
        /// sheen tint RGB, anisotropy R × anisotropy and G + rotation, specular tint RGB.
        pub coat_texture: u32,
        pub coat_roughness_texture: u32,
        pub coat_tint_texture: u32,
        pub sheen_texture: u32,
        /// Sheen tint RGB, anisotropy R with the rotation's G, specular tint RGB.
        pub sheen_tint_texture: u32,
        pub anisotropy_texture: u32,
        pub specular_tint_texture: u32,
        /// The anisotropic lobes' tangent: TANGENT_* in anisotropy.wgsl.
        pub tangent: u32,
        /// More layer textures: diffuse roughness R × diffuse_roughness, and the film's thickness
        /// G, from thin_film_minimum at 0 to thin_film_thickness at 1.
        pub diffuse_roughness_texture: u32,
        pub thin_film_texture: u32,
        pub thin_film_minimum: f32,
        /// Where the material's node program starts in the scene's program table, or
        /// `NO_PROGRAM` (see `asset::node_graph`).
        pub node_program: u32,
        /// The transmission texture: R × transmission_factor of the diffuse and its coating
        /// turns to glass (the weights above are those of the part that does not transmit);
        /// the specular IOR level's: A scales the coating's F0.
        pub transmission_texture: u32,
        pub transmission_factor: f32,
        pub specular_level_texture: u32,
        /// 1: the anisotropy texture is glTF's: RG a direction in the tangent frame, B × anisotropy.
        pub anisotropy_directions: u32,
        /// The coat's own normal map (Principled's Coat Normal; the base's own where the two
        /// share one), its x and y scaled by `coat_normal_scale`, or `NO_TEXTURE`: the coat then
        /// takes the interpolated normal, whatever `normal_texture` does to the other lobes.
        pub coat_normal_texture: u32,
        pub coat_normal_scale: f32,
        /// A Mix Shader's second material (the scene's table), which the node program's
        /// mix factor selects at each shading point, or `NO_MATERIAL`.
        pub mix_material: u32,
        /// The share of the surface that is a Holdout shader: the camera's paths lose it from
        /// the pixel's alpha, and every path loses it from its throughput.
        pub holdout: f32,
        /// The indices' texture (R the IOR, G the coat's, B the film's), each from its minimum
        /// here at 0 to the material's own at 1.
        pub ior_texture: u32,
        pub ior_minimum: f32,
        pub coat_ior_minimum: f32,
        pub thin_film_ior_minimum: f32,
        /// A lobe module's parameters (`scene::lobe`; read by the accessors its declaration
        /// makes) and its number, 1 + its place among `LOBES` (0: none, the lobes above).
        pub lobe_params: [f32; 4],
        pub lobe_module: u32,
        /// What the BSDF is scaled by (`Material::closure_weight`; its emission is not).
        pub closure_weight: f32,
        pub _pad_lobe: [u32; 2],
    }
}

gpu_struct! {
    /// The object-space tangents of a triangle's vertices (xyz, MikkTSpace) with the
    /// bitangent's sign (w), in the triangles' order; zero where a mesh has none.
    #[derive(Debug, Default, PartialEq)]
    pub struct GpuTriangleTangents as "TriangleTangents" {
        pub t0: [f32; 4],
        pub t1: [f32; 4],
        pub t2: [f32; 4],
    }
}

gpu_struct! {
    /// The second uv set's coordinates at a triangle's vertices, in the triangles' order;
    /// only for scenes whose textures read it (zero where a mesh has none).
    #[derive(Debug, Default, PartialEq)]
    pub struct GpuTriangleUvs as "TriangleUvs" {
        pub uv0: [f32; 2],
        pub uv1: [f32; 2],
        pub uv2: [f32; 2],
    }
}

gpu_struct! {
    /// One named mesh attribute (`MeshData::attributes`) at a triangle's vertices; each
    /// triangle has the scene's most attributes per mesh of them, in order (zero past a
    /// mesh's own); only for scenes whose node graphs read attributes.
    #[derive(Debug, Default, PartialEq)]
    pub struct GpuTriangleAttribute as "TriangleAttribute" {
        pub a0: [f32; 4],
        pub a1: [f32; 4],
        pub a2: [f32; 4],
    }
}

gpu_struct! {
    /// One texture of the texture store: its texels start at `offset` in `texels`, levels
    /// finest first. flags: bit 0 sRGB; bits 1-2 wrap of u, bits 3-4 wrap of v.
    #[derive(Debug, Default, PartialEq)]
    pub struct GpuTexture as "Texture" {
        /// Index of its first texel in the texel buffer; levels follow, finest first.
        pub offset: u32,
        pub width: u32,
        pub height: u32,
        pub levels: u32,
        /// Bit 0: sRGB; bits 1–2: wrap of u, bits 3–4: wrap of v (`Wrap::code`).
        pub flags: u32,
        /// log2 of how much the uv transform scales lengths (½ log2 |det|): added to the
        /// level of detail, as a uv scaled by 8 has a footprint 8× as wide in texels.
        pub transform_lod: f32,
        pub _pad: [u32; 2],
        /// The uv transform's rows (`asset::UvTransform`), the fourth component unused: the
        /// image is read at (dot(u_row.xyz, (u, v, 1)), dot(v_row.xyz, (u, v, 1))).
        pub u_row: [f32; 4],
        pub v_row: [f32; 4],
    }
}

gpu_struct! {
    /// An emissive triangle (of one instance) or sphere, for next-event estimation.
    #[derive(Debug, Default, PartialEq)]
    pub struct GpuEmitter as "Emitter" {
        /// Triangle index, or sphere index | `SPHERE_BIT`.
        pub primitive: u32,
        pub instance: u32,
        /// Cumulative selection probability up to and including this emitter.
        pub cdf: f32,
        pub _pad0: u32,
    }
}

gpu_struct! {
    /// A `[[light]]` lamp (`shaders/lamps.wgsl`): what each field holds depends on its kind.
    #[derive(Debug, Default, PartialEq)]
    pub struct GpuLamp as "Lamp" {
        /// Point, spot, area: the centre; sun: the unit vector towards it.
        pub position: [f32; 3],
        /// `LAMP_*` kind, with the `LAMP_SPHERE`, `LAMP_ELLIPSE` and `LAMP_CAMERA` bits.
        pub kind: u32,
        /// Radiance of the lamp's shape; intensity (W/sr) for a point of radius 0, irradiance
        /// for a sun of angle 0.
        pub emission: [f32; 3],
        /// Point, spot: the radius; sun: 1 − cos of the half-angle.
        pub radius: f32,
        /// Area: the unit X axis; spot: the unit direction of the cone.
        pub axis_u: [f32; 3],
        /// Area: the length along X; spot: cos of the cone's half-angle.
        pub len_u: f32,
        /// Area: the unit Y axis.
        pub axis_v: [f32; 3],
        /// Area: the length along Y; spot: the smoothstep's scale 1 / ((1 − cos) · blend).
        pub len_v: f32,
        /// Area: the unit normal of the emitting side.
        pub normal: [f32; 3],
        /// Cumulative selection probability among lamps, up to and including this one.
        pub cdf: f32,
    }
}

gpu_struct! {
    /// How next-event estimation splits its samples between the `[sun]`, emissive
    /// surfaces and lamps, when the scene has lamps.
    #[derive(Debug, Default, PartialEq)]
    pub struct GpuLampInfo as "LampInfo" {
        pub count: u32,
        pub sun_share: f32,
        pub emitter_share: f32,
        pub lamp_share: f32,
    }
}

gpu_struct! {
    /// A node of the light tree (`shaders/light_tree.wgsl`, built by `crate::bvh::light_tree`):
    /// the bounds of the lights below it, as pbrt-v4's `LightBounds`.
    #[derive(Debug, Default, PartialEq)]
    pub struct GpuLightTreeNode as "LightTreeNode" {
        pub bounds_min: [f32; 3],
        /// Luminous power of the lights below, in the units of a lamp's watts.
        pub power: f32,
        pub bounds_max: [f32; 3],
        /// Cosine of the half-angle of the cone of surface normals (or spot axes) about `axis`.
        pub cos_theta_o: f32,
        pub axis: [f32; 3],
        /// Cosine of the angle beyond `theta_o` into which the lights still emit.
        pub cos_theta_e: f32,
        /// Inner node: index of the second child (the first follows the node). Leaf: the
        /// light, an emitter index or a lamp index | `LIGHT_TREE_LAMP`.
        pub link: u32,
        /// `LIGHT_TREE_LEAF`, `LIGHT_TREE_TWO_SIDED`.
        pub flags: u32,
        pub _pad: [u32; 2],
    }
}

gpu_struct! {
    /// An environment image's constants (`shaders/environment.wgsl`), group 2 of the
    /// integrator; its texels and distribution are the group's storage buffer.
    #[derive(Debug, Default, PartialEq)]
    pub struct GpuEnvironment as "Environment" {
        /// Rows of the rotation from rt's world to the image's frame (Blender's axes, the
        /// Mapping node's rotation applied).
        pub to_image_x: [f32; 3],
        pub width: u32,
        pub to_image_y: [f32; 3],
        pub height: u32,
        pub to_image_z: [f32; 3],
        pub strength: f32,
        /// Probability that a light sample goes to the environment.
        pub light_share: f32,
        /// 1: light samples follow the distribution; 0: uniform over the sphere.
        pub importance: u32,
        /// 1: the texels are sRGB codes, decoded after the lookup (as Cycles filters them).
        pub srgb: u32,
        pub _pad: u32,
    }
}

gpu_struct! {
    /// The atmosphere's parameters (`shaders/atmosphere.wgsl`), group 2 of the
    /// integrator and group 0 of the table passes.
    #[derive(Debug, Default, PartialEq)]
    pub struct GpuAtmosphere as "Atmosphere" {
        /// Scattering coefficients at the ground, per metre.
        pub rayleigh_scattering: [f32; 3],
        pub bottom_radius: f32,
        pub mie_scattering: [f32; 3],
        pub top_altitude: f32,
        pub mie_absorption: [f32; 3],
        pub rayleigh_scale_height: f32,
        pub ozone_absorption: [f32; 3],
        pub mie_scale_height: f32,
        pub ground_albedo: [f32; 3],
        pub mie_g: f32,
        /// The ozone's density is a tent of this centre and half width.
        pub ozone_center: f32,
        pub ozone_half_width: f32,
        /// Altitude of rt's y = 0 plane.
        pub ground_altitude: f32,
        /// March steps per ray.
        pub steps: u32,
        /// Entries of the tables in `atmosphere_luts`: transmittance, then the planes
        /// of the multiple scattering table, then the ground's rows.
        pub transmittance_size: [u32; 2],
        pub scattering_size: [u32; 2],
        pub scattering_offset: u32,
        pub ground_offset: u32,
        /// 1 to add light scattered more than once, 0 for single scattering only.
        pub multiple_scattering: f32,
        pub _pad0: u32,
    }
}

gpu_struct! {
    /// Input of the trace kernel (`shaders/trace_kernel.wgsl`).
    #[derive(Debug, Default, PartialEq)]
    pub struct GpuTraceRay as "TraceRay" {
        pub origin: [f32; 3],
        pub t_max: f32,
        pub direction: [f32; 3],
        pub _pad: u32,
    }
}

gpu_struct! {
    /// Output of the trace kernel.
    #[derive(Debug, Default, PartialEq)]
    pub struct GpuTraceHit as "TraceHit" {
        pub t: f32,
        /// Triangle index, sphere index | `SPHERE_BIT`, or `EMPTY_LINK` for a miss.
        pub primitive: u32,
        pub instance: u32,
        pub overflowed: u32,
        /// Barycentric weights of the triangle's second and third vertices.
        pub b1: f32,
        pub b2: f32,
        pub _pad: [u32; 2],
    }
}

use crate::scene::Tangent;

/// The shaders' TANGENT_* of the tangent anisotropy follows.
fn tangent_mode(tangent: Tangent) -> u32 {
    match tangent {
        Tangent::RadialZ => TANGENT_RADIAL_Z,
        Tangent::RadialX => TANGENT_RADIAL_X,
        Tangent::RadialY => TANGENT_RADIAL_Y,
        Tangent::Uv => TANGENT_UV,
    }
}

impl From<&crate::scene::Material> for GpuMaterial {
    fn from(m: &crate::scene::Material) -> Self {
        let [diffuse, specular, reflection, transmission] = m.lobe_weights();
        let (coating_eta, coating_f0) = m.dielectric_coating().unwrap_or((0.0, 0.0));
        // The coating is the diffuse's own glossy layer, with the diffuse's weight.
        let specular = if coating_eta > 0.0 { diffuse } else { specular };
        let l = &m.textures.layers;
        let slot = |t: Option<u32>| t.unwrap_or(NO_TEXTURE);
        Self {
            base_color: m.base_color,
            diffuse,
            emission: m.emission,
            specular,
            absorption: m.absorption,
            reflection,
            volume_emission: m.volume_emission,
            transmission,
            ior: m.ior,
            alpha: m.alpha(),
            emission_luminance: crate::scene::luminance(m.emission),
            base_color_texture: m.textures.base_color.unwrap_or(NO_TEXTURE),
            metallic_roughness_texture: m.textures.metallic_roughness.unwrap_or(NO_TEXTURE),
            emission_texture: m.textures.emission.unwrap_or(NO_TEXTURE),
            metallic: m.textures.metallic,
            roughness: m.roughness,
            base_alpha: m.textures.base_alpha,
            alpha_cutoff: if m.textures.alpha_blend { ALPHA_BLEND } else { m.textures.alpha_cutoff },
            normal_texture: m.textures.normal.unwrap_or(NO_TEXTURE),
            normal_scale: m.textures.normal_scale,
            specular_tint: m.specular_tint,
            coating_eta,
            coating_f0,
            sheen_roughness: m.sheen_roughness.clamp(1e-3, 1.0),
            anisotropy: m.anisotropy,
            anisotropy_rotation: m.anisotropy_rotation,
            coat_tint: m.coat_tint,
            coat: m.coat,
            coat_alpha: m.coat_roughness * m.coat_roughness,
            coat_ior: m.coat_ior,
            second_uv_set: m.textures.second_uv_set,
            diffuse_roughness: m.diffuse_roughness,
            sheen_tint: m.sheen_tint,
            sheen: m.sheen,
            thin_film_thickness: m.thin_film_thickness,
            thin_film_ior: m.thin_film_ior,
            bump_map_correction: u32::from(m.bump_map_correction),
            thin_film_weight: m.thin_film_weight,
            coat_texture: slot(l.coat),
            coat_roughness_texture: slot(l.coat_roughness),
            coat_tint_texture: slot(l.coat_tint),
            sheen_texture: slot(l.sheen),
            sheen_tint_texture: slot(l.sheen_tint),
            anisotropy_texture: slot(l.anisotropy),
            specular_tint_texture: slot(l.specular_tint),
            tangent: tangent_mode(m.tangent),
            diffuse_roughness_texture: slot(l.diffuse_roughness),
            thin_film_texture: slot(l.thin_film_thickness),
            thin_film_minimum: m.textures.thin_film_minimum,
            node_program: NO_PROGRAM,
            transmission_texture: slot(l.transmission),
            transmission_factor: m.textures.transmission,
            specular_level_texture: slot(l.specular_level),
            anisotropy_directions: u32::from(m.textures.anisotropy_directions),
            coat_normal_texture: m.textures.coat_normal.unwrap_or(NO_TEXTURE),
            coat_normal_scale: m.textures.coat_normal_scale,
            mix_material: m.mix_material.unwrap_or(NO_MATERIAL),
            holdout: m.holdout,
            ior_texture: slot(l.ior),
            ior_minimum: m.textures.ior_minimum[0],
            coat_ior_minimum: m.textures.ior_minimum[1],
            thin_film_ior_minimum: m.textures.ior_minimum[2],
            lobe_params: m.lobe.map_or([0.0; 4], |l| l.params),
            lobe_module: crate::scene::lobe::ModuleLobe::number(m.lobe.as_ref()),
            closure_weight: m.closure_weight,
            _pad_lobe: [0; 2],
        }
    }
}
