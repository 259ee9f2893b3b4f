//! The keys of a glTF material's `extras` that rt reads, declared once: rt's own values
//! where glTF has no field (a Principled BSDF's coat tint, sheen weight, holdout, node
//! graph…). The glTF reader takes its keys from here, a key that starts with `rt_` and is
//! none of them is reported (a typo in an exporter would otherwise be lost silently), and
//! a test checks that the Blender exporter writes exactly these keys.

macro_rules! material_extras {
    ($($(#[doc = $doc:literal])* $name:ident = $key:literal;)*) => {
        $($(#[doc = $doc])* pub const $name: &str = $key;)*

        /// Every key, in declaration order.
        pub const ALL: &[&str] = &[$($key),*];
    };
}

material_extras! {
    /// Principled's Specular IOR Level (0.5 is the IOR's own reflectance).
    SPECULAR_IOR_LEVEL = "rt_specular_ior_level";
    /// The coat's weight, roughness, IOR and tint (`KHR_materials_clearcoat` has no IOR or tint).
    COAT = "rt_coat";
    COAT_ROUGHNESS = "rt_coat_roughness";
    COAT_IOR = "rt_coat_ior";
    COAT_TINT = "rt_coat_tint";
    /// The sheen's weight, roughness and tint (`KHR_materials_sheen` has no weight).
    SHEEN = "rt_sheen";
    SHEEN_ROUGHNESS = "rt_sheen_roughness";
    SHEEN_TINT = "rt_sheen_tint";
    /// Anisotropy and its rotation as Principled gives them (a turn in [0, 1)).
    ANISOTROPY = "rt_anisotropy";
    ANISOTROPY_ROTATION = "rt_anisotropy_rotation";
    /// What the anisotropy's tangent follows: "radial_x", "radial_y", "radial_z" or "uv".
    TANGENT = "rt_tangent";
    /// Principled's Diffuse Roughness (Oren–Nayar).
    DIFFUSE_ROUGHNESS = "rt_diffuse_roughness";
    /// Cycles' Bump Map Correction of the material (on unless false).
    BUMP_MAP_CORRECTION = "rt_bump_map_correction";
    /// Light emitted inside the material's medium, per metre.
    VOLUME_EMISSION = "rt_volume_emission";
    /// A Glossy BSDF's colour: the material is a coloured mirror lobe.
    GLOSSY_COLOR = "rt_glossy_color";
    /// The share of the material that is a Holdout shader.
    HOLDOUT = "rt_holdout";
    /// The material's shader node graph (docs/shader-nodes.md).
    NODE_GRAPH = "rt_node_graph";
    /// The material a node graph's Mix Shader mixes in, by index.
    MIX_MATERIAL = "rt_mix_material";
    /// What the material's BSDF is scaled by (an Add Shader's halves: 2).
    CLOSURE_WEIGHT = "rt_closure_weight";
    /// A lobe module's BSDF (`scene::lobe`): `{"module": "toon", "size": 0.5, …}`.
    LOBE = "rt_lobe";
    /// Textures of the layers glTF has no texture for: the coat's tint, the sheen (weight
    /// and roughness), its tint, the anisotropy, the diffuse roughness and the indices.
    COAT_TINT_TEXTURE = "rt_coat_tint_texture";
    SHEEN_TEXTURE = "rt_sheen_texture";
    SHEEN_TINT_TEXTURE = "rt_sheen_tint_texture";
    ANISOTROPY_TEXTURE = "rt_anisotropy_texture";
    DIFFUSE_ROUGHNESS_TEXTURE = "rt_diffuse_roughness_texture";
    IOR_TEXTURE = "rt_ior_texture";
    /// The indices an index texture's 0 stands for (base, coat, thin film).
    IOR_MINIMUM = "rt_ior_minimum";
    COAT_IOR_MINIMUM = "rt_coat_ior_minimum";
    THIN_FILM_IOR_MINIMUM = "rt_thin_film_ior_minimum";
    /// What the material renders differently from Cycles, for `rt info` to list.
    NOTES = "rt_notes";
}

/// The keys of `extras` (a JSON object) that look like rt's and are none that rt reads,
/// each with the nearest one it may have meant.
pub fn unknown_keys(extras: &serde_json::Value) -> Vec<String> {
    let Some(object) = extras.as_object() else {
        return Vec::new();
    };
    object
        .keys()
        .filter(|key| key.starts_with("rt_") && !ALL.contains(&key.as_str()))
        .map(|key| format!("extras.{key}{}", crate::scene::did_you_mean(key, ALL.iter().copied())))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::BTreeSet;

    /// The Blender exporter (rt_export.py and the node modules it calls) writes every key rt reads, and every `rt_` string it writes is a
    /// key rt reads or one of its own names that are not material extras.
    #[test]
    fn the_exporter_writes_the_keys_rt_reads() {
        let exporter = [
            include_str!("../../../../blender/rt_blender/rt_export.py"),
            include_str!("../../../../blender/rt_blender/rt_node_graph.py"),
            include_str!("../../../../blender/rt_blender/rt_shader_graphs.py"),
            include_str!("../../../../blender/rt_blender/rt_shader_nodes.py"),
        ]
        .concat();
        let written: BTreeSet<&str> = exporter
            .split('"')
            .skip(1)
            .step_by(2)
            .filter(|s| s.starts_with("rt_") && s.chars().all(|c| c.is_ascii_lowercase() || c == '_'))
            .collect();
        // The exporter's scratch image for bakes, not a key.
        let not_extras = ["rt_bake_scratch"];
        let read: BTreeSet<&str> = ALL.iter().copied().chain(not_extras).collect();
        assert_eq!(written, read, "keys written by the Blender exporter and read by rt differ");
    }

    #[test]
    fn an_unknown_rt_key_is_named_with_the_nearest_known_one() {
        let extras = serde_json::json!({ "rt_coat_roughnes": 0.2, "rt_coat": 1.0, "other_tool": 3 });
        let unknown = unknown_keys(&extras);
        assert_eq!(unknown.len(), 1, "{unknown:?}");
        assert!(unknown[0].starts_with("extras.rt_coat_roughnes") && unknown[0].contains("rt_coat_roughness"));
        assert!(unknown_keys(&serde_json::json!([1, 2])).is_empty());
    }

    #[test]
    fn keys_are_declared_once() {
        let unique: BTreeSet<&str> = ALL.iter().copied().collect();
        assert_eq!(unique.len(), ALL.len());
        assert!(ALL.iter().all(|k| k.starts_with("rt_")));
    }
}
