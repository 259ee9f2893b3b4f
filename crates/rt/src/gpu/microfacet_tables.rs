//! Cycles' microfacet albedo tables (`shaders/microfacet_tables.wgsl` reads them): the
//! directional and average albedo of GGX reflection and of GGX dielectrics, and the
//! Fresnel interpolation factor of a rough dielectric coating, baked by
//! `scripts/make_microfacet_tables.py` into `microfacet_tables.bin` (little-endian f32,
//! compiled into the binary) with Cycles' definitions, sizes and layout; then Cycles' sheen
//! fit (`shaders/sheen.wgsl` reads it), brought over from Cycles' source by
//! `scripts/make_sheen_table.py` into `sheen_ltc.bin`; then Cycles' thin-film sensitivity
//! table (`shaders/thin_film.wgsl` reads it), made by `scripts/make_thin_film_table.py`
//! into `thin_film_table.bin`.

/// Floats in the tables, in the order of the offsets in `shaders/microfacet_tables.wgsl`:
/// ggx_E 32², ggx_Eavg 32, glass E 16³ and Eavg 16² (index above 1, then below), and the
/// coating's Fresnel factor 16³.
pub const MICROFACET_TABLE_LEN: usize = 32 * 32 + 32 + 2 * (16 * 16 * 16 + 16 * 16) + 16 * 16 * 16;
/// Floats in the sheen table: its transform's a and b and its albedo, each [32 roughness][32 mu].
pub const SHEEN_TABLE_LEN: usize = 3 * 32 * 32;
/// Floats in the thin-film table: the real parts of R, G, B, then their imaginary parts, each 512.
pub const THIN_FILM_TABLE_LEN: usize = 6 * 512;

const BYTES: &[u8] = include_bytes!("microfacet_tables.bin");
const _: () = assert!(BYTES.len() == 4 * MICROFACET_TABLE_LEN, "microfacet_tables.bin has the wrong size");
const SHEEN_BYTES: &[u8] = include_bytes!("sheen_ltc.bin");
const _: () = assert!(SHEEN_BYTES.len() == 4 * SHEEN_TABLE_LEN, "sheen_ltc.bin has the wrong size");
const THIN_FILM_BYTES: &[u8] = include_bytes!("thin_film_table.bin");
const _: () = assert!(THIN_FILM_BYTES.len() == 4 * THIN_FILM_TABLE_LEN, "thin_film_table.bin has the wrong size");

/// The tables as floats, for upload: the microfacet tables, then the sheen's (from
/// `TABLE_SHEEN_LTC` in `shaders/sheen.wgsl` on), then the thin film's (`TABLE_THIN_FILM`
/// in `shaders/thin_film.wgsl`).
pub fn microfacet_tables() -> Vec<f32> {
    BYTES
        .iter()
        .chain(SHEEN_BYTES)
        .chain(THIN_FILM_BYTES)
        .copied()
        .collect::<Vec<u8>>()
        .chunks_exact(4)
        .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sheen_table_follows_the_microfacet_tables_where_the_shader_reads_it() {
        let t = microfacet_tables();
        assert_eq!(t.len(), MICROFACET_TABLE_LEN + SHEEN_TABLE_LEN + THIN_FILM_TABLE_LEN);
        let wgsl = include_str!("../../shaders/sheen.wgsl");
        assert!(wgsl.contains(&format!("const TABLE_SHEEN_LTC: u32 = {MICROFACET_TABLE_LEN}u;")));
        let sheen = &t[MICROFACET_TABLE_LEN..MICROFACET_TABLE_LEN + SHEEN_TABLE_LEN];
        let (a, b, albedo) = (&sheen[..1024], &sheen[1024..2048], &sheen[2048..]);
        // At normal incidence the lobe is symmetric (no shear); the albedo of the roughest
        // sheen falls from grazing (0.75) to normal incidence (0.34), as in Cycles.
        for r in 8..32 {
            assert!(b[r * 32 + 31].abs() < 5e-3, "roughness row {r}: b = {}", b[r * 32 + 31]);
            assert!(a[r * 32 + 31] > 0.3, "roughness row {r}: a = {}", a[r * 32 + 31]);
        }
        assert!((albedo[31 * 32] - 0.74973).abs() < 1e-6 && (albedo[31 * 32 + 31] - 0.34187).abs() < 1e-6);
        assert!(albedo.iter().all(|v| (0.0..1.0).contains(v)));
    }

    #[test]
    fn thin_film_table_follows_the_sheen_where_the_shader_reads_it() {
        let t = microfacet_tables();
        let offset = MICROFACET_TABLE_LEN + SHEEN_TABLE_LEN;
        let wgsl = include_str!("../../shaders/thin_film.wgsl");
        assert!(wgsl.contains(&format!("const TABLE_THIN_FILM: u32 = {offset}u;")));
        let film = &t[offset..];
        // Each channel's matching function has area 1 (its DC term), and its transform
        // decays: at 60 µm of path difference no colour is left.
        for c in 0..3 {
            assert_eq!(film[c * 512], 1.0, "channel {c}");
            assert_eq!(film[(3 + c) * 512], 0.0, "channel {c}");
            let tail = (film[c * 512 + 511].powi(2) + film[(3 + c) * 512 + 511].powi(2)).sqrt();
            assert!(tail < 5e-3, "channel {c}: {tail}");
        }
    }

    #[test]
    fn tables_are_albedos_and_reflection_keeps_all_when_smooth() {
        let t = microfacet_tables();
        assert!(t[..MICROFACET_TABLE_LEN].iter().all(|v| (0.0..=1.0).contains(v)));
        // ggx_E[mu][rough]: a smooth mirror keeps everything at any angle but grazing.
        for mu in 1..32 {
            assert!((t[mu * 32] - 1.0).abs() < 1e-3, "mu row {mu}: {}", t[mu * 32]);
        }
        // At normal incidence and α = 1, GGX with height-correlated masking keeps 1 − ln 2.
        assert!((t[31 * 32 + 31] - (1.0 - 2f32.ln())).abs() < 2e-3, "{}", t[31 * 32 + 31]);
    }
}
