//! The physically based atmosphere of `[sky] kind = "atmosphere"`: its physical
//! parameters on the GPU and the look-up tables that compute passes build from
//! them (Hillaire, EGSR 2020, with the seed's L₂ / (1 − c) closure for light
//! scattered more than once). The march that uses them is
//! `shaders/atmosphere_sky.wgsl`. Also the equirectangular image of `[sky] kind =
//! "environment"`, read and turned into a distribution for light sampling.

mod environment;
mod environment_map;
mod model;
mod tables;

pub use environment::{Distribution, EnvironmentImage};
pub use environment_map::{EnvironmentMap, light_share, world_to_image};

pub use model::{
    BOTTOM_RADIUS_M, MIE_ABSORPTION, MIE_SCALE_HEIGHT_M, MIE_SCATTERING, OZONE_ABSORPTION, OZONE_CENTER_M,
    OZONE_HALF_WIDTH_M, RAYLEIGH_SCALE_HEIGHT_M, RAYLEIGH_SCATTERING, TOP_ALTITUDE_M, TableLayout, gpu_atmosphere,
};
pub use tables::AtmosphereTables;
