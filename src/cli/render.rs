//! `rt render` and `rt merge`: a scene to an image (or frames, or a sample range's part), and parts to the image.

use super::args::RenderArgs;
use crate::load_scene;
use anyhow::{Context, Result, bail};
use rt::bvh::SceneGeometry;
use rt::denoise::Denoiser;
use rt::gpu::GpuContext;
use rt::gpu::PipelineCache;
use rt::render::RenderReport;
use rt::render::part::PartRequest;
use rt::render::{
    DroppedSamples, Image, ImageFormat, Progress, RenderRequest, Session, aov_channels, check_output, human,
    image_format, json_event, write_image, write_layered_exr,
};
use rt::scene::Scene;
use std::path::{Path, PathBuf};

/// `--strict` found dropped samples or rays: a finished render, but not a clean one.
#[derive(Debug, thiserror::Error)]
#[error("--strict: the render dropped samples or rays ({0})")]
pub(crate) struct StrictFinding(DroppedSamples);

pub(crate) fn render(args: RenderArgs, adapter: Option<&str>) -> Result<()> {
    check_output(&args.output)?;
    check_sample_range(&args)?;
    let json = args.progress == Progress::Json;
    // With JSON progress, stderr holds JSON lines only.
    let say = |line: String| {
        if !json {
            eprintln!("{line}");
        }
    };
    if args.aovs && image_format(&args.output)? != ImageFormat::Exr {
        bail!("--aovs: AOVs are written as one multi-layer OpenEXR; give -o an .exr path");
    }
    if let Some(snapshot) = &args.snapshot
        && image_format(snapshot)? != ImageFormat::Exr
    {
        bail!("--snapshot: snapshots are linear OpenEXR images; give an .exr path");
    }
    // Before any rendering: a missing denoiser is known at once.
    let mut denoiser = match args.denoise {
        true => Some(Denoiser::new(args.denoise_device).context("--denoise")?),
        false => None,
    };
    if let Some(denoiser) = &denoiser {
        say(format!("denoising with Open Image Denoise on {}", denoiser.describe()));
    }
    let frames = match args.frames.clone() {
        Some(frames) => frames.map(|f| args.at_frame(f)).collect::<Result<Vec<_>>>()?,
        None => vec![args],
    };
    // With --frames, every frame's scene is there before the first is rendered (what else
    // is wrong with one is said when it is read).
    for frame in frames.iter().skip(1) {
        if let Some(scene) = &frame.scene
            && std::fs::metadata(scene).is_err_and(|e| e.kind() == std::io::ErrorKind::NotFound)
        {
            bail!("{}: no such scene file (a frame of --frames)", scene.display());
        }
    }
    // The first scene is read and the flags checked before the GPU starts: a mistake is said at once.
    let mut first = Some(scene_and_request(&frames[0])?);
    let ctx = GpuContext::new(adapter)?;
    say(format!("GPU: {}", ctx.describe()));
    let mut pipelines = None;
    for frame in &frames {
        let scene_request = match first.take() {
            Some(first) => first,
            None => scene_and_request(frame)?,
        };
        pipelines = Some(render_frame(frame, &ctx, scene_request, denoiser.as_mut(), pipelines.take(), &say)?);
    }
    Ok(())
}

/// The scene `args` names, with the flags written into it, and the request they make.
pub(crate) fn scene_and_request(args: &RenderArgs) -> Result<(Scene, RenderRequest)> {
    let mut scene = load_scene(args.scene.as_deref())?;
    let request = RenderRequest {
        progress: args.progress,
        exact_sums: true,
        first_sample: args.sample_range.as_ref().map_or(0, |r| r.start),
        ..args.flags().apply(&mut scene)?
    };
    Ok((scene, request))
}

/// One image of `rt render` (a frame of `--frames`), with the pipelines built so far;
/// returns them, for the next frame.
pub(crate) fn render_frame(
    args: &RenderArgs,
    ctx: &GpuContext,
    (scene, request): (Scene, RenderRequest),
    denoiser: Option<&mut Denoiser>,
    pipelines: Option<PipelineCache>,
    say: &dyn Fn(String),
) -> Result<PipelineCache> {
    let json = args.progress == Progress::Json;
    let exposure = scene.render.exposure;
    let origin = scene.origin.clone();
    let geometry = SceneGeometry::build(&scene, args.quality)?;
    let pipelines = pipelines.unwrap_or_else(|| PipelineCache::new(ctx));
    let mut session = Session::with_pipelines(ctx, scene, geometry, pipelines)?;
    say(format!("{origin}: features [{}]", session.features()));
    if args.sample_range.is_some() {
        check_part_request(&session, &request)?;
    }
    if let Some(tables) = session.atmosphere() {
        say(format!("atmosphere tables built in {:.1} ms", tables.build_time.as_secs_f64() * 1e3));
    }
    let time_limit = args.time_limit.map(std::time::Duration::from_secs_f64);
    let mut snapshots = Snapshots::new(args.snapshot.as_deref(), args.snapshot_every, json);
    let (image, report) = session.render_with(&request, None, time_limit, |s| snapshots.after_step(s))?;
    if let Some(samples) = args.sample_range.clone() {
        let part = PartRequest { path: &args.output, samples, exposure, aov_layers: args.aovs };
        rt::render::part::save(&session, &part)?;
        say(format!("wrote {} (samples {:?} of each pixel)", args.output.display(), part.samples));
        return Ok(session.into_pipelines());
    }
    write_outputs(args, &session, &image, denoiser, exposure, say)?;
    say(format!(
        "wrote {} ({}x{}, {} spp) in {:.2} s: {}samples/s",
        args.output.display(),
        request.width,
        request.height,
        report.samples_per_pixel,
        report.elapsed.as_secs_f64(),
        human(report.samples_per_second)
    ));
    report_end(args, &report)?;
    Ok(session.into_pipelines())
}

/// What a finished render says last: its dropped samples (an error with `--strict`), and
/// with JSON progress the `done` event.
pub(crate) fn report_end(args: &RenderArgs, report: &RenderReport) -> Result<()> {
    let json = args.progress == Progress::Json;
    if !report.dropped.is_clean() {
        match json {
            true => {
                eprintln!("{}", json_event("warning", serde_json::json!({ "message": report.dropped.to_string() })))
            }
            false => eprintln!("warning: {}", report.dropped),
        }
        if args.strict {
            return Err(StrictFinding(report.dropped.clone()).into());
        }
    }
    if json {
        let fields = serde_json::json!({
            "file": args.output,
            "seconds": report.elapsed.as_secs_f64(),
            "spp": report.samples_per_pixel,
        });
        eprintln!("{}", json_event("done", fields));
    }
    Ok(())
}

/// Writes what `rt render` was asked for: the image, denoised or not, with or without its
/// AOV layers, and the AOV files.
pub(crate) fn write_outputs(
    args: &RenderArgs,
    session: &Session,
    image: &Image,
    denoiser: Option<&mut Denoiser>,
    exposure: f32,
    say: &dyn Fn(String),
) -> Result<()> {
    let aovs = if session.request().aovs { Some(session.aovs()?) } else { None };
    let denoised = match (denoiser, &aovs) {
        (Some(denoiser), Some(aovs)) => {
            let start = std::time::Instant::now();
            let clean = denoiser.denoise(image, aovs)?;
            let took = start.elapsed().as_secs_f64();
            say(format!("denoised with Open Image Denoise ({} device) in {took:.2} s", denoiser.device()));
            Some(clean)
        }
        _ => None,
    };
    if let (Some(dir), Some(aovs)) = (&args.aov_files, &aovs) {
        write_aov_files(dir, image, aovs)?;
    }
    match (&aovs, denoised) {
        (Some(aovs), denoised) if args.aovs => {
            let channels = aov_channels(image, aovs, denoised.as_deref());
            write_layered_exr(&args.output, image.width, image.height, channels)
        }
        (_, Some(clean)) => write_image(&Image { pixels: clean, ..image.clone() }, &args.output, exposure),
        _ => write_image(image, &args.output, exposure),
    }
}

/// Refuses a part the session cannot make: one under adaptive sampling, or one whose exact
/// sums do not fit the GPU.
pub(crate) fn check_part_request(session: &Session, request: &RenderRequest) -> Result<()> {
    if request.adaptive() {
        bail!(
            "--sample-range: adaptive sampling stops pixels by all the samples before, so it cannot be split; \
             add --noise-threshold 0"
        );
    }
    let aovs = request.aovs || session.features().has_alpha();
    rt::render::check_exact_sums(session.ctx(), request.width, request.height, aovs).context("--sample-range")
}

/// Refuses what a part of a render cannot hold: it is the samples' sums, finished by `rt merge`.
pub(crate) fn check_sample_range(args: &RenderArgs) -> Result<()> {
    let Some(range) = &args.sample_range else { return Ok(()) };
    let refused = [
        (args.spp.is_some(), "--spp (the range says which samples)"),
        (args.denoise, "--denoise (denoise the merged image)"),
        (args.time_limit.is_some(), "--time-limit (a part holds all of its samples)"),
        (args.snapshot.is_some(), "--snapshot"),
        (args.aov_files.is_some(), "--aov-files"),
    ];
    if let Some((_, what)) = refused.iter().find(|(given, _)| *given) {
        bail!("--sample-range {}..{}: a part cannot take {what}", range.start, range.end);
    }
    if image_format(&args.output)? != ImageFormat::Exr {
        bail!("--sample-range: a part is an OpenEXR that `rt merge` reads; give -o an .exr path");
    }
    Ok(())
}

/// `rt merge`: the parts' sums added, written as `rt render` writes its image.
pub(crate) fn merge(parts: &[PathBuf], output: &Path) -> Result<()> {
    check_output(output)?;
    let merged = rt::render::part::merge(parts)?;
    for warning in &merged.warnings {
        log::warn!("{warning}");
    }
    let (image, aovs) = merged.image();
    let header = &merged.header;
    match aovs {
        Some(aovs) if header.aov_layers => {
            write_layered_exr(output, image.width, image.height, aov_channels(&image, &aovs, None))?
        }
        _ => write_image(&image, output, header.exposure)?,
    }
    let parts = match parts.len() {
        1 => "1 part".to_string(),
        n => format!("{n} parts"),
    };
    eprintln!("wrote {} ({}x{}, {} spp from {parts})", output.display(), image.width, image.height, merged.spp);
    Ok(())
}

/// `--aov-files DIR`: each AOV as a plain OpenEXR of its own.
pub(crate) fn write_aov_files(dir: &Path, image: &Image, aovs: &rt::render::Aovs) -> Result<()> {
    rt::files::check_folder(dir).context("--aov-files")?;
    let grey = |values: Vec<f32>| values.into_iter().map(|v| [v; 3]).collect::<Vec<_>>();
    let files = [
        ("albedo", aovs.albedo.clone()),
        ("normal", aovs.normal.clone()),
        ("depth", grey(aovs.depth.clone())),
        ("position", aovs.position.clone()),
        ("emission", aovs.emission.clone()),
        ("diffuse_color", aovs.diffuse_color.clone()),
        ("error", grey(image.std_error.clone())),
        ("samples", grey(image.sample_counts.iter().map(|&n| n as f32).collect())),
    ];
    for (name, pixels) in files {
        write_image(&Image { pixels, alpha: None, ..image.clone() }, &dir.join(format!("{name}.exr")), 0.0)?;
    }
    Ok(())
}

/// `--snapshot`: the image so far, written every so often while rendering.
pub(crate) struct Snapshots<'a> {
    pub(crate) path: Option<&'a Path>,
    pub(crate) every: std::time::Duration,
    pub(crate) json: bool,
    pub(crate) last: std::time::Instant,
}

impl<'a> Snapshots<'a> {
    fn new(path: Option<&'a Path>, every: f64, json: bool) -> Self {
        let every = std::time::Duration::from_secs_f64(every);
        Self { path, every, json, last: std::time::Instant::now() }
    }

    fn after_step(&mut self, session: &Session) -> Result<()> {
        let Some(path) = self.path.filter(|_| self.last.elapsed() >= self.every && !session.converged()) else {
            return Ok(());
        };
        let image = session.image()?;
        write_image(&image, path, 0.0)?;
        if self.json {
            let fields = serde_json::json!({ "file": path, "spp": image.samples });
            eprintln!("{}", json_event("snapshot", fields));
        }
        self.last = std::time::Instant::now();
        Ok(())
    }
}
