//! The scene's bind group, declared once: each binding's buffer, kind, WGSL type and the
//! shader file that declares it (under which flag). [`scene_bindings!`] makes from the one
//! list the buffers' struct, the bind group's layout and entries in binding order, and the
//! WGSL `@group(0) @binding(i)` declarations that each shader file includes as
//! `FILE.bindings.wgsl`.

use super::bind::Binding;

macro_rules! scene_bindings {
    ($(
        $(#[doc = $doc:literal])*
        $name:ident: $kind:ident $wgsl_type:literal in $file:literal $(if $flag:literal)?
    ),* $(,)?) => {
        /// The scene's buffers, one per binding of group 0, so that a live reload can replace
        /// some of them and rebind.
        pub(super) struct SceneData {
            $(
                $(#[doc = $doc])*
                pub $name: wgpu::Buffer,
            )*
        }

        impl SceneData {
            /// The buffers in binding order.
            pub(super) fn bindings(&self) -> Vec<&wgpu::Buffer> {
                vec![$(&self.$name),*]
            }
        }

        /// What each binding of group 0 is, in binding order.
        pub(super) const SCENE_BINDINGS: &[Binding] = &[$(Binding::$kind),*];

        /// Every binding, in binding order.
        const ROWS: &[Row] = &[$(
            Row {
                name: stringify!($name),
                docs: &[$($doc),*],
                kind: Binding::$kind,
                wgsl_type: $wgsl_type,
                file: $file,
                flag: scene_bindings!(@flag $($flag)?),
            }
        ),*];
    };
    (@flag) => { None };
    (@flag $flag:literal) => { Some($flag) };
}

/// One binding of the scene group as WGSL declares it.
struct Row {
    /// The variable's name, also the buffer's.
    name: &'static str,
    docs: &'static [&'static str],
    kind: Binding,
    wgsl_type: &'static str,
    /// The shader file (without `.wgsl`) that declares it.
    file: &'static str,
    /// The flag the declaration needs, if any.
    flag: Option<&'static str>,
}

scene_bindings! {
    frame: Uniform "Frame" in "common",
    nodes: ReadOnly "array<BvhNode>" in "common",
    triangles: ReadOnly "array<Triangle>" in "common",
    shading: ReadOnly "array<TriangleShading>" in "common",
    instances: ReadOnly "array<Instance>" in "common",
    tlas_primitives: ReadOnly "array<u32>" in "common",
    spheres: ReadOnly "array<Sphere>" in "common",
    materials: ReadOnly "array<Material>" in "common",
    /// Counters (`STAT_*`).
    stats: ReadWrite "array<atomic<u32>>" in "common",
    emitters: ReadOnly "array<Emitter>" in "common",
    lamps: ReadOnly "array<Lamp>" in "lamps",
    /// The lamps' count and share of light samples.
    lamp_info: Uniform "LampInfo" in "lamps",
    wide_nodes: ReadOnly "array<WideNode>" in "common",
    /// The texture store (`crate::gpu::textures`): its table and its RGBA8 texels, red in
    /// the low byte.
    textures: ReadOnly "array<Texture>" in "common" if "textures",
    texels: ReadOnly "array<u32>" in "common" if "textures",
    light_tree_nodes: ReadOnly "array<LightTreeNode>" in "light_tree",
    /// Per light, emitters then lamps: the children taken from the root, bit d at depth d.
    light_tree_trails: ReadOnly "array<u32>" in "light_tree",
    /// Per-triangle tangents, for normal maps and uv tangents.
    tangent_frames: ReadOnly "array<TriangleTangents>" in "common" if "tangent_frames",
    /// Cycles' microfacet albedo tables (`crate::gpu::microfacet_tables`).
    microfacet_tables: ReadOnly "array<f32>" in "microfacet_tables",
    /// Per-triangle second uv set, for textures that read it.
    second_uvs: ReadOnly "array<TriangleUvs>" in "common" if "uv_sets",
    /// Per-instance settings that shading reads (Shadow Terminator, holdout).
    object_settings: ReadOnly "array<ObjectSettings>" in "common" if "object_settings",
    /// The materials' node programs (`crate::asset::node_graph`).
    node_programs: ReadOnly "array<u32>" in "node_step",
    /// The moving instances' transforms over the shutter (`shaders/motion.wgsl`).
    motion_matrices: ReadOnly "array<MotionMatrix>" in "motion",
    /// Per triangle, the meshes' named attributes (`SceneGeometry::attributes`).
    attributes: ReadOnly "array<TriangleAttribute>" in "node_attribute" if "attributes",
}

/// The WGSL declarations of the bindings that shader file `file` (without `.wgsl`)
/// declares, or `None` if it declares none.
pub(super) fn declarations(file: &str) -> Option<String> {
    let mut out = String::new();
    for (binding, row) in ROWS.iter().enumerate().filter(|(_, row)| row.file == file) {
        crate::gpu_struct::push_comment(&mut out, "", row.docs);
        let (space, name, ty) = (row.kind.wgsl_address_space(), row.name, row.wgsl_type);
        let declaration = format!("@group(0) @binding({binding}) var<{space}> {name}: {ty};\n");
        match row.flag {
            Some(flag) => out.push_str(&format!("//#if {flag}\n{declaration}//#endif\n")),
            None => out.push_str(&declaration),
        }
    }
    (!out.is_empty()).then_some(out)
}
