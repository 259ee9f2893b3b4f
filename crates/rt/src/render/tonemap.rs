//! Display transform for PNG output: exposure, then the Khronos PBR Neutral
//! tone mapper (which keeps base colours as authored up to 0.8 and rolls off
//! highlights toward white), then the sRGB transfer function.

/// Khronos PBR Neutral (Khronos 3D Commerce group, 2024).
pub fn pbr_neutral(c: [f32; 3]) -> [f32; 3] {
    const START_COMPRESSION: f32 = 0.8 - 0.04;
    const DESATURATION: f32 = 0.15;
    let x = c[0].min(c[1]).min(c[2]);
    let offset = if x < 0.08 { x - 6.25 * x * x } else { 0.04 };
    let c = c.map(|v| v - offset);
    let peak = c[0].max(c[1]).max(c[2]);
    if peak < START_COMPRESSION {
        return c;
    }
    let d = 1.0 - START_COMPRESSION;
    let new_peak = 1.0 - d * d / (peak + d - START_COMPRESSION);
    let c = c.map(|v| v * new_peak / peak);
    let g = 1.0 - 1.0 / (DESATURATION * (peak - new_peak) + 1.0);
    c.map(|v| v + (new_peak - v) * g)
}

pub use crate::scene::srgb_encode;

/// Linear radiance to an 8-bit sRGB pixel.
pub fn display_pixel(radiance: [f32; 3], exposure_ev: f32) -> [u8; 3] {
    let scale = exposure_ev.exp2();
    pbr_neutral(radiance.map(|v| v.max(0.0) * scale)).map(|v| (srgb_encode(v) * 255.0 + 0.5) as u8)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn neutral_keeps_mid_tones_and_compresses_highlights() {
        let mid = pbr_neutral([0.5, 0.5, 0.5]);
        assert!((mid[0] - 0.46).abs() < 1e-6, "{mid:?}");
        let bright = pbr_neutral([100.0, 100.0, 100.0]);
        assert!(bright[0] < 1.0 && bright[0] > 0.99, "{bright:?}");
        assert_eq!(display_pixel([0.0; 3], 0.0), [0, 0, 0]);
        assert_eq!(display_pixel([1e9; 3], 0.0), [255, 255, 255]);
    }
}
