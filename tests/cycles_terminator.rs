//! Coarse smooth-shaded spheres (12 segments, 6 rings) lit from the side, rt against Cycles:
//! the sun's terminator crosses faces whose interpolated normals differ from their true
//! ones by up to half a face. Cycles lifts shadow rays near the terminator to the smooth
//! surface and judges directions by the geometry rather than folding them (rt's model for
//! these, `smooth-normals`); without it a face turned from the sun whose normals face it
//! goes black, a step of 20-30% on one block of each sphere. The rows and their references
//! are made by `tests/cycles/make_principled_refs.py` (`terminator_sun`, `terminator_coat_sun`)
//! and compared as the other Principled rows are (`cycles_principled::check_row`).

use crate::cycles_principled::check_row;

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
