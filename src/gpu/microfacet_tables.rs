//! Cycles' microfacet albedo tables (`shaders/microfacet_tables.wgsl` reads them): the
//! directional and average albedo of GGX reflection and of GGX dielectrics, and the
//! Fresnel interpolation factor of a rough dielectric coating, baked by
//! `scripts/make_microfacet_tables.py` into `microfacet_tables.bin` (little-endian f32,
//! compiled into the binary) with Cycles' definitions, sizes and layout.

/// Floats in the tables, in the order of the offsets in `shaders/microfacet_tables.wgsl`:
/// ggx_E 32², ggx_Eavg 32, glass E 16³ and Eavg 16² (index above 1, then below), and the
/// coating's Fresnel factor 16³.
pub const MICROFACET_TABLE_LEN: usize = 32 * 32 + 32 + 2 * (16 * 16 * 16 + 16 * 16) + 16 * 16 * 16;

const BYTES: &[u8] = include_bytes!("microfacet_tables.bin");
const _: () = assert!(BYTES.len() == 4 * MICROFACET_TABLE_LEN, "microfacet_tables.bin has the wrong size");

/// The tables as floats, for upload.
pub fn microfacet_tables() -> Vec<f32> {
    BYTES.chunks_exact(4).map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]])).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tables_are_albedos_and_reflection_keeps_all_when_smooth() {
        let t = microfacet_tables();
        assert!(t.iter().all(|v| (0.0..=1.0).contains(v)));
        // ggx_E[mu][rough]: a smooth mirror keeps everything at any angle but grazing.
        for mu in 1..32 {
            assert!((t[mu * 32] - 1.0).abs() < 1e-3, "mu row {mu}: {}", t[mu * 32]);
        }
        // At normal incidence and α = 1, GGX with height-correlated masking keeps 1 − ln 2.
        assert!((t[31 * 32 + 31] - (1.0 - 2f32.ln())).abs() < 2e-3, "{}", t[31 * 32 + 31]);
    }
}
