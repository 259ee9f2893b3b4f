//! Coarse smooth-shaded spheres (12 segments, 6 rings) lit from the side, rt against Cycles:
//! the sun's terminator crosses faces whose interpolated normals differ from their true
//! ones by up to half a face. Cycles lifts shadow rays near the terminator to the smooth
//! surface and judges directions by the geometry rather than folding them (rt's model for
//! these, `smooth-normals`); without it a face turned from the sun whose normals face it
//! goes black, a step of 20-30% on one block of each sphere. The rows and their references
//! are made by `tests/cycles/make_principled_refs.py` (`terminator_sun`, `terminator_coat_sun`,
//! `terminator_glass_sun`, `terminator_sheen_sun`, `coarse_no_correction`) and compared as the
//! other Principled rows are (`cycles_principled::check_row`), the glass row as the rare
//! paths' (`cycles_rare_paths::check_batched`). Rows of objects with Shadow Terminator
//! settings of their own (`terminator_shading_offset_sun`, `terminator_offsets_sun`,
//! `terminator_shading_offset_mirrors`, `terminator_shading_offset_layers`) check that rt
//! applies each object's, which the exporter writes into the scene file.

use crate::common;
use crate::cycles_principled::{check_row, check_row_within};
use crate::cycles_rare_paths::check_batched_within;
use rt::scene::ShadowTerminator;

/// Lambertian, Oren-Nayar, the default dielectric, a rough metal and a coated base.
#[test]
fn coarse_spheres_at_the_terminator_match_cycles() {
    // Block (10, 2) by the terminator sits 1.1 % under Cycles' in the seed-0 render; over
    // 10 seeds the spheres agree within 0.3 % with independent and Sobol samples alike.
    check_row_within("principled_terminator_sun", crate::cycles_principled::SUNLIT_RESIDUAL * 1.5, 0.0);
}

/// A coat of roughness 0.2 to 0.6 over a rough red base.
#[test]
fn coarse_coated_spheres_at_the_terminator_match_cycles() {
    check_row("principled_terminator_coat_sun");
}

/// Rough glass of roughness 0.1 to 0.8 under a wide sun (20°, seen through the glass by rare
/// paths: the noise is measured from batches, as for `cycles_rare_paths`; reference 8192 spp).
/// Cycles' `bsdf_microfacet_eval` lets light through microfacets that a direction sees from
/// behind, which rough glass at grazing angles shows: without that, rt's sphere of roughness
/// 0.8 was 17% too dark (blocks at its rim 30-40%), 0.5 3%; and it judges a light's direction
/// by the glass's own normal, not by the face's (which changed no block measurably here).
#[test]
fn coarse_rough_glass_under_a_sun_matches_cycles() {
    // Over 10 seeds the spheres sit 0.2-0.7 % (independent samples) and 0.2-1.0 % (Sobol)
    // under Cycles', the two within 1.7 σ of each other: a residual, allowed.
    check_batched_within("principled_terminator_glass_sun", 8192.0, 0.01);
}

/// A sheen of roughness 0.1 to 1 on a dark base, lit from behind the silhouette: Cycles gives
/// the sheen the interpolated normal, not the one Bump Map Correction bends for the glossy
/// lobes where the view grazes the faces. The bent normal's sheen differed from it by at
/// most 3% on a few dim rim blocks, within this row's bounds: the row guards the sheen at
/// the terminator, it does not tell the two normals apart.
#[test]
fn coarse_sheened_spheres_at_the_terminator_match_cycles() {
    check_row("principled_terminator_sheen_sun");
}

/// Metals and dielectrics of roughness 0.05 and 0.15 and a coat of 0.05 with the material's
/// Bump Map Correction off, in a white world: their normals stay the interpolated ones at
/// the silhouettes, where Cycles drops the reflections they send below the faces and shades
/// no microfacet lobe where they face away from the viewer (with the setting ignored, rt
/// bends them to mirror the world: spheres 1.0-2.0% and blocks up to 5% brighter; with
/// reflections followed into the mesh and the face's normal shading the lobes, spheres
/// were 1.0-1.6% and silhouette pixels up to 48% brighter).
#[test]
fn coarse_spheres_without_bump_map_correction_match_cycles() {
    check_row("principled_coarse_no_correction");
}

/// Each lobe of `terminator_sun` on objects with a Shadow Terminator Shading Offset of 0.6:
/// Cycles multiplies every lobe's value by cos(kθ) / cos θ (k = 1 / (1 - 0.6 / 2)), θ to the
/// lobe's own normal, which darkens the spheres towards the terminator and ends their light
/// at 63° from the normal rather than at 90°.
#[test]
fn shading_offsets_shift_each_lobe_as_in_cycles() {
    check_row("principled_terminator_shading_offset_sun");
}

/// Perfect mirrors and interfaces with a Shading Offset of 0.6 in a white world: Cycles shifts
/// a singular lobe's reflection too (a metal, a dielectric's specular layer, glass, a coat),
/// by the cosine of the reflected direction; refraction is left alone.
#[test]
fn shading_offsets_shift_perfect_reflections_as_in_cycles() {
    check_row("principled_terminator_shading_offset_mirrors");
}

/// Sheens of roughness 0.3 and 1, rough glass of 0.3 and 0.6 and a coat of 0.3, with a Shading
/// Offset of 1, in a white world: the sheen by its own normal, glass's reflection only.
#[test]
fn shading_offsets_shift_sheens_glass_and_coats_as_in_cycles() {
    check_row("principled_terminator_shading_offset_layers");
}

/// Lambertian spheres with Shading Offsets 0.3, 0.6 and 1, then Geometry Offsets 0 (no shadow
/// ray starts from the smooth surface: the faces turned from the sun whose normals face it go
/// dark) and 1 (every shadow ray does).
#[test]
fn shading_and_geometry_offsets_match_cycles() {
    check_row("principled_terminator_offsets_sun");
}

/// Each object's Shadow Terminator settings travel with it: into its [[mesh]] entry, and for
/// instances into the [[instances]] entry of an instance file of their own (a collection of
/// two objects sharing a mesh, one with offsets of its own, instanced twice); no warning.
#[test]
fn shadow_terminator_settings_are_exported_per_object_and_per_instance() {
    let out = common::empty_temp_dir("shadow-terminator-export");
    let stderr = common::run_bpy_script("shadow_terminator_export.py", &out);
    assert!(!stderr.contains("Shadow Terminator"), "a setting is warned about:\n{stderr}");
    let scene = rt::scene::load(&out.join("scene.toml")).unwrap_or_else(|e| panic!("{e}"));
    let offsets = |t: &ShadowTerminator| (t.geometry_offset, t.shading_offset);
    // The [[mesh]] entries in the order of their objects' names: lifted, plain, shifted.
    let meshes: Vec<_> = scene.meshes.iter().map(|m| offsets(&m.shadow_terminator)).collect();
    assert_eq!(meshes, [(0.3, 0.0), (0.1, 0.0), (0.1, 0.5)]);
    let mut sets: Vec<_> = scene
        .instance_sets
        .iter()
        .map(|s| {
            let count = rt::asset::rtinst::read(&s.file).unwrap_or_else(|e| panic!("{e}")).records.len();
            (offsets(&s.shadow_terminator), count, s.asset.clone())
        })
        .collect();
    sets.sort_by(|a, b| a.0.partial_cmp(&b.0).expect("finite"));
    assert_eq!(sets.iter().map(|s| (s.0, s.1)).collect::<Vec<_>>(), [((0.0, 0.6), 2), ((0.1, 0.0), 2)]);
    assert_eq!(sets[0].2, sets[1].2, "the instances of both objects share one asset");
    assert_ne!(scene.instance_sets[0].file, scene.instance_sets[1].file);
}
