//! Hillaire's Earth (EGSR 2020, table 1), scaled by the scene's `[sky]` keys, in
//! the layout the shaders read.

use crate::layout::GpuAtmosphere;
use crate::scene::Atmosphere;

pub const BOTTOM_RADIUS_M: f32 = 6_360_000.0;
/// The top of the atmosphere, 6460 km from the planet's centre.
pub const TOP_ALTITUDE_M: f32 = 100_000.0;
/// Per metre at the ground, for red, green and blue (680, 550, 440 nm).
pub const RAYLEIGH_SCATTERING: [f32; 3] = [5.802e-6, 13.558e-6, 33.1e-6];
pub const RAYLEIGH_SCALE_HEIGHT_M: f32 = 8_000.0;
pub const MIE_SCATTERING: f32 = 3.996e-6;
pub const MIE_ABSORPTION: f32 = 4.40e-6;
pub const MIE_SCALE_HEIGHT_M: f32 = 1_200.0;
pub const OZONE_ABSORPTION: [f32; 3] = [0.650e-6, 1.881e-6, 0.085e-6];
/// The ozone's density is a tent: 1 at 25 km, 0 below 10 km and above 40 km.
pub const OZONE_CENTER_M: f32 = 25_000.0;
pub const OZONE_HALF_WIDTH_M: f32 = 15_000.0;

/// Where each table lies in the one storage buffer that holds them all, in vec4 entries.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TableLayout {
    pub transmittance: [u32; 2],
    pub scattering: [u32; 2],
    /// Start of the multiple scattering table's planes: L₂, L₃, L₄, Ψ.
    pub scattering_offset: u32,
    /// Start of the ground's rows, per sun zenith entry: its irradiance by the
    /// sky's light of orders 1, 2, 3, and ≥ 2.
    pub ground_offset: u32,
    pub entries: u32,
}

impl TableLayout {
    pub fn of(a: &Atmosphere) -> Self {
        let [tw, th] = a.transmittance_lut;
        let [sw, sh] = a.multiple_scattering_lut;
        let scattering_offset = tw * th;
        let ground_offset = scattering_offset + 4 * sw * sh;
        Self {
            transmittance: a.transmittance_lut,
            scattering: a.multiple_scattering_lut,
            scattering_offset,
            ground_offset,
            entries: ground_offset + 4 * sw,
        }
    }
}

pub fn gpu_atmosphere(a: &Atmosphere) -> GpuAtmosphere {
    let layout = TableLayout::of(a);
    let mie_absorption = if a.mie_absorption { MIE_ABSORPTION * a.turbidity } else { 0.0 };
    GpuAtmosphere {
        rayleigh_scattering: RAYLEIGH_SCATTERING.map(|s| s * a.rayleigh_scale),
        bottom_radius: BOTTOM_RADIUS_M,
        mie_scattering: [MIE_SCATTERING * a.turbidity; 3],
        top_altitude: TOP_ALTITUDE_M,
        mie_absorption: [mie_absorption; 3],
        rayleigh_scale_height: RAYLEIGH_SCALE_HEIGHT_M,
        ozone_absorption: if a.ozone { OZONE_ABSORPTION } else { [0.0; 3] },
        mie_scale_height: MIE_SCALE_HEIGHT_M,
        ground_albedo: a.ground_albedo.to_array(),
        mie_g: a.mie_g,
        ozone_center: OZONE_CENTER_M,
        ozone_half_width: OZONE_HALF_WIDTH_M,
        ground_altitude: a.ground_altitude_m,
        steps: a.steps,
        transmittance_size: layout.transmittance,
        scattering_size: layout.scattering,
        scattering_offset: layout.scattering_offset,
        ground_offset: layout.ground_offset,
        multiple_scattering: if a.multiple_scattering { 1.0 } else { 0.0 },
        _pad0: 0,
    }
}
