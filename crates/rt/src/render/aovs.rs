//! Arbitrary output variables: what a denoiser is guided by, and what a compositor
//! reads beside the radiance.

/// Per pixel, rows from the top: the albedo and the shading normal (facing the camera,
/// world space) of the first surface that is not a perfect mirror or interface, as Open
/// Image Denoise expects them, and the distance along the camera ray to the first
/// surface; Cycles' Position and Emission passes: the world position where the camera
/// ray met the scene (nothing where it did not) and the light seen emitted there (by a
/// surface, or a lamp seen directly). Each is the mean over the pixel's samples; depth is
/// over the samples that hit something (infinite where none did).
#[derive(Clone, Debug, Default)]
pub struct Aovs {
    pub width: u32,
    pub height: u32,
    pub albedo: Vec<[f32; 3]>,
    pub normal: Vec<[f32; 3]>,
    pub depth: Vec<f32>,
    pub position: Vec<[f32; 3]>,
    pub emission: Vec<[f32; 3]>,
    /// Cycles' Diffuse Color: the weight of the diffuse lobe of the first surface the
    /// camera's ray met (past alpha).
    pub diffuse_color: Vec<[f32; 3]>,
}

/// vec4 per pixel in the GPU's AOV means and per sample in the lanes' scratch
/// (`AOV_VEC4S` in `shaders/aovs.wgsl`; a test checks both agree).
pub(crate) const MEANS_PER_PIXEL: usize = 5;

impl Aovs {
    /// From the GPU's running means: five vec4 per pixel (albedo and depth, normal and
    /// the count of samples that hit, position and the coverage's sum, emission, diffuse
    /// colour), see `shaders/aovs.wgsl`.
    pub fn from_means(width: u32, height: u32, means: &[[f32; 4]]) -> Self {
        let pixels = width as usize * height as usize;
        let mut aovs = Self { width, height, ..Default::default() };
        let xyz = |v: [f32; 4]| [v[0], v[1], v[2]];
        for pixel in means.chunks_exact(MEANS_PER_PIXEL).take(pixels) {
            let [a, b, position, emission, diffuse] = [pixel[0], pixel[1], pixel[2], pixel[3], pixel[4]];
            aovs.position.push(xyz(position));
            aovs.emission.push(xyz(emission));
            aovs.diffuse_color.push(xyz(diffuse));
            // Per sample, albedo estimates may exceed 1; their mean does not, but for rounding.
            aovs.albedo.push([a[0], a[1], a[2]].map(|v| v.clamp(0.0, 1.0)));
            aovs.normal.push([b[0], b[1], b[2]]);
            aovs.depth.push(if b[3] > 0.0 { a[3] } else { f32::INFINITY });
        }
        aovs
    }

    /// Per pixel, its alpha: the share of it its samples cover (a sample whose camera ray
    /// left the scene through a transparent film covers none, one held out covers none or
    /// what its holdout shader leaves), their sum (see `shaders/aovs.wgsl`) over the
    /// samples the pixel took.
    pub fn coverage(means: &[[f32; 4]], samples: &[u32]) -> Vec<f32> {
        let covered = means.chunks_exact(MEANS_PER_PIXEL).map(|pixel| pixel[2][3]);
        covered.zip(samples).map(|(sum, &n)| (sum / n.max(1) as f32).clamp(0.0, 1.0)).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::MEANS_PER_PIXEL;

    #[test]
    fn the_shader_lays_out_as_many_vec4_per_pixel() {
        let line = format!("const AOV_VEC4S: u32 = {MEANS_PER_PIXEL}u;");
        assert!(include_str!("../../shaders/aovs.wgsl").contains(&line), "aovs.wgsl lacks `{line}`");
    }
}
