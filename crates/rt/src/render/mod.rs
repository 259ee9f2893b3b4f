//! Rendering: a scene on the GPU in a [`Session`], refined progressively, and the
//! images it makes.

mod accumulation;
mod aovs;
mod camera;
mod dropped;
pub mod exact;
pub mod frames;
mod image_out;
mod layers_out;
mod pacing;
pub mod part;
mod progress;
mod request;
mod session;
mod sun;
pub mod tonemap;
mod trace;

pub use accumulation::{Accumulation, check_exact_sums};
pub use aovs::Aovs;
pub use camera::set_camera;
pub use dropped::{DroppedSamples, NonFiniteCause};
pub use image_out::{ImageFormat, check_output, image_format, write_image, write_png};
pub use layers_out::{aov_channels, beauty_channels, write_layered_exr};
pub use pacing::Pacing;
pub use progress::{Progress, json_event};
pub use request::{MAX_SAMPLES_PER_DISPATCH, RenderFlags, RenderRequest};
pub use session::{GeometryUpdate, RenderReport, SceneUpdate, Session, Step};
pub use sun::{default_sun_radiance, sun_direction, sun_one_minus_cos};
pub use trace::TraceBuffers;

/// Mean radiance per pixel (linear, rows from the top), with the standard
/// error of each pixel's luminance.
#[derive(Clone, Debug)]
pub struct Image {
    pub width: u32,
    pub height: u32,
    pub samples: u32,
    pub pixels: Vec<[f32; 3]>,
    pub std_error: Vec<f32>,
    /// Finite samples each pixel's mean is over (they differ with adaptive sampling).
    pub sample_counts: Vec<u32>,
    /// With a transparent film: each pixel's alpha, the share of its camera rays that met
    /// the scene; `pixels` are then premultiplied by it (the background added nothing).
    pub alpha: Option<Vec<f32>>,
}

/// 12.3 M, 4.56 G: rates at a glance.
pub fn human(v: f64) -> String {
    let (scale, unit) = match v {
        v if v >= 1e9 => (1e9, " G"),
        v if v >= 1e6 => (1e6, " M"),
        v if v >= 1e3 => (1e3, " k"),
        _ => (1.0, " "),
    };
    format!("{:.3}{unit}", v / scale).replace("  ", " ")
}
