//! Coarse smooth-shaded spheres (12 segments, 6 rings) lit from the side, rt against Cycles:
//! the sun's terminator crosses faces whose interpolated normals differ from their true
//! ones by up to half a face. Cycles lifts shadow rays near the terminator to the smooth
//! surface and judges directions by the geometry rather than folding them (rt's model for
//! these, `smooth-normals`); without it a face turned from the sun whose normals face it
//! goes black, a step of 20-30% on one block of each sphere. The rows and their references
//! are made by `tests/cycles/make_principled_refs.py` (`terminator_sun`, `terminator_coat_sun`,
//! `terminator_glass_sun`, `terminator_sheen_sun`, `coarse_no_correction`) and compared as the
//! other Principled rows are (`cycles_principled::check_row`), the glass row as the rare
//! paths' (`cycles_rare_paths::check_batched`). What the exporter cannot carry, the objects'
//! own Shadow Terminator offsets, is a warning naming the object.

use crate::common;
use crate::cycles_principled::check_row;
use crate::cycles_rare_paths::check_batched;

/// Lambertian, Oren-Nayar, the default dielectric, a rough metal and a coated base.
#[test]
fn coarse_spheres_at_the_terminator_match_cycles() {
    check_row("principled_terminator_sun");
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
    check_batched("principled_terminator_glass_sun", 8192.0);
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

/// rt renders every object with Blender's default Shadow Terminator offsets (Geometry 0.1,
/// Shading 0): the exporter warns of other settings, naming the object.
#[test]
fn shadow_terminator_settings_other_than_the_defaults_are_warned_about() {
    let out = common::empty_temp_dir("shadow-terminator-warnings");
    let stderr = common::run_bpy_script("shadow_terminator_warnings.py", &out);
    for needle in [
        "object lifted: Shadow Terminator Geometry Offset 0.3 is not supported; rendered with 0.1",
        "object shifted: Shadow Terminator Shading Offset 0.5 is not supported; rendered with 0",
    ] {
        assert!(stderr.contains(needle), "{needle:?} missing from:\n{stderr}");
    }
    assert!(!stderr.contains("object plain"), "the defaults are warned about:\n{stderr}");
    assert_eq!(stderr.matches("Shadow Terminator").count(), 2, "{stderr}");
}
