//! `rt bench sky`: what the atmosphere's knobs cost and buy. The scene is
//! rendered with each setting, and with settings far past the defaults from
//! the same samples (same seed, so the paths are the same and only the
//! atmosphere differs); the difference is the setting's error, shown beside the
//! time of its render and of its tables.

use anyhow::{Result, bail};
use rt::bvh::BuildQuality;
use rt::gpu::GpuContext;
use rt::render::{Image, RenderRequest, Session};
use rt::scene::{Atmosphere, Scene, Sky, luminance};

/// Median and 95th percentile of the pixels' relative error in luminance.
fn relative_errors(image: &Image, reference: &Image) -> (f64, f64) {
    let mut errors: Vec<f64> = image
        .pixels
        .iter()
        .zip(&reference.pixels)
        .map(|(a, b)| {
            let (a, b) = (luminance(*a) as f64, luminance(*b) as f64);
            (a - b).abs() / b.max(1e-12)
        })
        .collect();
    errors.sort_by(f64::total_cmp);
    let at = |q: f64| errors[((errors.len() - 1) as f64 * q) as usize];
    (at(0.5), at(0.95))
}

pub fn sky(scene: Scene, (width, height): (u32, u32), spp: u32, adapter: Option<&str>) -> Result<()> {
    let Sky::Atmosphere(defaults) = scene.sky.clone() else {
        bail!("{}: the sky is not an atmosphere", scene.origin);
    };
    let ctx = GpuContext::new(adapter)?;
    let mut session = Session::open(&ctx, scene, BuildQuality::default())?;
    let mut request = RenderRequest::from_scene(session.scene());
    (request.width, request.height, request.spp) = (width, height, spp);
    println!("GPU       {}", ctx.describe());
    println!("scene     {} at {width}x{height}, {spp} spp", session.scene().origin);
    let reference = Atmosphere {
        steps: 256,
        transmittance_lut: [1024, 256],
        multiple_scattering_lut: [96, 96],
        ..defaults.clone()
    };
    session.set_atmosphere(&reference)?;
    let (truth, _) = session.render(&request, None)?;
    println!("reference 256 steps, tables 1024x256 and 96x96; relative error of the pixels, median / 95th percentile:");
    let mut run = |label: String, params: Atmosphere| -> Result<()> {
        let rebuilt = session.set_atmosphere(&params)?;
        let (image, report) = session.render(&request, None)?;
        let (median, p95) = relative_errors(&image, &truth);
        let tables = match (rebuilt, session.atmosphere()) {
            (true, Some(t)) => format!(", tables built in {:.1} ms", t.build_time.as_secs_f64() * 1e3),
            _ => String::new(),
        };
        let ms = report.elapsed.as_secs_f64() * 1e3;
        println!("  {label:<40} {:>8.2e} / {:>8.2e}  render {ms:>8.1} ms{tables}", median, p95);
        Ok(())
    };
    for steps in [4, 8, 16, 32, 64, 128] {
        run(format!("{steps} steps"), Atmosphere { steps, ..defaults.clone() })?;
    }
    for (t, m) in [([64, 16], [8, 8]), ([128, 32], [16, 16]), ([256, 64], [32, 32]), ([512, 128], [64, 64])] {
        let label = format!("tables {}x{} and {}x{}", t[0], t[1], m[0], m[1]);
        run(label, Atmosphere { transmittance_lut: t, multiple_scattering_lut: m, ..defaults.clone() })?;
    }
    run("single scattering only".into(), Atmosphere { multiple_scattering: false, ..defaults })?;
    Ok(())
}
