//! `rt bench compare`: rt beside Mitsuba 3 on the same scenes, like for like. One
//! translation ([`super::mitsuba_scene`]) gives Mitsuba rt's scene with rt's estimator
//! settings; both renderers get the same warm-up and are timed by both clocks; and before
//! any ratio is printed their images are compared against each other's noise
//! ([`super::agreement`]): a case whose images disagree is reported as such, without a
//! ratio. Without an importable Mitsuba it says so and prints rt's figures alone.

use super::agreement::{self, Pair, Verdict};
use super::clocks::Timed;
use super::compare_rt::{RtFigures, measure};
use super::mitsuba::{self, MitsubaCase, MitsubaFigures, MitsubaOutcome};
use super::mitsuba_scene::translate;
use anyhow::{Context, Result, bail};
use indicatif::ProgressBar;
use rt::bvh::BuildQuality;
use rt::gpu::{GpuContext, GpuTimer};
use rt::render::{Session, human};
use rt::scene::{self, Microfacet, Scene, Sky};
use std::path::{Path, PathBuf};

pub struct CompareOptions {
    /// Scenes to compare at `size`; none: the held-in set below.
    pub scenes: Vec<PathBuf>,
    pub size: (u32, u32),
    /// Samples per pixel of each render of a given scene.
    pub spp: u32,
    /// Timed renders of each case (at least 2: the first two are compared).
    pub runs: u32,
    /// The Python that imports `mitsuba`.
    pub python: String,
    pub variant: Option<String>,
    /// Mitsuba's sampler (`independent`, `stratified`, `multijitter`, `orthogonal`, …).
    pub sampler: String,
    /// Where the held-in scenes live (the repository's root).
    pub root: PathBuf,
}

/// One row group of the table: a scene at a size and bounce limit.
struct Case {
    name: String,
    scene: Scene,
    size: (u32, u32),
    spp: u32,
    rays: bool,
}

/// The held-in set: the Cornell box at two path lengths, in a small window and at the
/// window's aspect, and a 46k-triangle dragon under a uniform sky (with trace rates).
fn held_in(root: &Path) -> Result<Vec<Case>> {
    let cornell = scene::load(&root.join("tests/refs/scenes/cornell_diffuse.toml"))?;
    let dragon = scene::load(&root.join("scenes/dragon_clay.toml"))?;
    let with_bounces = |s: &Scene, b: u32| {
        let mut s = s.clone();
        s.render.max_bounces = b;
        s
    };
    let case = |name: &str, scene: Scene, size, spp, rays| Case { name: name.into(), scene, size, spp, rays };
    Ok(vec![
        case("Cornell box, 9 path vertices", with_bounces(&cornell, 8), (1024, 720), 16, false),
        case("Cornell box, 65 path vertices", with_bounces(&cornell, 64), (1024, 720), 16, false),
        // A small live window: many samples per pixel.
        case("Cornell box at 128x128", with_bounces(&cornell, 8), (128, 128), 1024, false),
        // The small window's framing at a large size: at 1024x720 a quarter of the camera
        // rays pass beside the box and end at once, which makes those paths cheaper.
        case("Cornell box at 1024x1024", with_bounces(&cornell, 8), (1024, 1024), 16, false),
        case("46k-triangle dragon, uniform sky", dragon, (1024, 720), 16, true),
    ])
}

/// The cases to time, each rendered by rt as Mitsuba renders it: its single-scattering
/// lobes, and a uniform sky sampled as a light (Mitsuba's `constant` emitter always is).
fn cases(options: &CompareOptions) -> Result<Vec<Case>> {
    let cases = match options.scenes.is_empty() {
        true => held_in(&options.root)?,
        false => options
            .scenes
            .iter()
            .map(|path| {
                let scene = scene::load(path)?;
                Ok(Case { name: path.display().to_string(), scene, size: options.size, spp: options.spp, rays: true })
            })
            .collect::<Result<_>>()?,
    };
    Ok(cases
        .into_iter()
        .map(|mut case| {
            case.scene.render.microfacet = Microfacet::Single;
            if let Sky::Uniform { sample_as_light, .. } = &mut case.scene.sky {
                *sample_as_light = true;
            }
            case
        })
        .collect())
}

/// The cases as Mitsuba gets them, their PLY files and images in `dir`.
fn mitsuba_cases(cases: &[Case], runs: u32, dir: &Path) -> Result<Vec<MitsubaCase>> {
    cases
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let folder = dir.join(format!("case{i}"));
            std::fs::create_dir_all(&folder).with_context(|| format!("creating {}", folder.display()))?;
            Ok(MitsubaCase {
                name: c.name.clone(),
                scene: translate(&c.scene, c.size, c.spp, &folder)?,
                spp: c.spp,
                runs,
                rays: c.rays,
                images: [folder.join("mitsuba1.exr"), folder.join("mitsuba2.exr")],
            })
        })
        .collect()
}

/// Mitsuba's two renders of a case.
fn mitsuba_renders(case: &MitsubaCase) -> Result<[Vec<[f32; 3]>; 2]> {
    let read = |path: &PathBuf| -> Result<Vec<[f32; 3]>> {
        Ok(rt::files::image::read(path, "Mitsuba's image")
            .map_err(anyhow::Error::msg)?
            .into_rgb32f()
            .pixels()
            .map(|p| p.0)
            .collect())
    };
    Ok([read(&case.images[0])?, read(&case.images[1])?])
}

fn ratio(rt: Option<f64>, other: Option<f64>, agree: bool) -> String {
    match (rt, other.filter(|o| *o > 0.0)) {
        (Some(r), Some(o)) if agree => format!("{:.2}×", r / o),
        (Some(_), Some(_)) => "images disagree".into(),
        _ => "—".into(),
    }
}

/// A rate, or a dash where there is none.
pub(super) fn rate(v: Option<f64>) -> String {
    v.map_or("—".into(), human)
}

fn row(name: &str, what: &str, ours: &Timed, theirs: Option<&Timed>, agree: bool) -> String {
    let (rt_wall, rt_device) = (ours.wall_rate(), ours.device_rate());
    let (mi_wall, mi_device) = (theirs.and_then(Timed::wall_rate), theirs.and_then(Timed::device_rate));
    format!(
        "| {name} | {what} | {} | {} | {} | {} | {} | {} |",
        rate(rt_wall),
        rate(mi_wall),
        ratio(rt_wall, mi_wall, agree),
        rate(rt_device),
        rate(mi_device),
        ratio(rt_device, mi_device, agree)
    )
}

fn print_case(case: &Case, rt: &RtFigures, mi: Option<(&MitsubaFigures, &Verdict)>) {
    let name = format!("{} ({}x{}, {} spp)", case.name, case.size.0, case.size.1, case.spp);
    let agree = mi.is_some_and(|(_, v)| v.agree);
    println!("{}", row(&name, "paths/s", &rt.paths, mi.map(|m| &m.0.paths), agree));
    if let Some(camera) = &rt.camera_rays {
        println!("{}", row(&name, "camera rays/s", camera, mi.and_then(|m| m.0.camera_rays.as_ref()), agree));
    }
    if let Some(diffuse) = &rt.diffuse_rays {
        println!("{}", row(&name, "diffuse rays/s", diffuse, mi.and_then(|m| m.0.diffuse_rays.as_ref()), agree));
    }
}

pub fn compare(options: &CompareOptions, adapter: Option<&str>) -> Result<()> {
    if options.runs < 2 {
        bail!("--runs must be at least 2: the first two renders of each renderer are compared");
    }
    let cases = cases(options)?;
    let scratch = rt::files::ScratchDir::new("compare")?;
    let jobs = mitsuba_cases(&cases, options.runs, scratch.path())?;
    let ctx = GpuContext::new(adapter)?;
    println!("GPU      {} (timed by {} and the wall clock)", ctx.describe(), GpuTimer::new(&ctx).method());
    let bar = ProgressBar::new(cases.len() as u64 * options.runs as u64);
    let mut ours = Vec::new();
    for case in &cases {
        let mut session = Session::open(&ctx, case.scene.clone(), BuildQuality::default())?;
        ours.push(measure(&mut session, case.size, case.spp, options.runs, case.rays, &bar)?);
    }
    bar.finish_and_clear();
    let theirs =
        match mitsuba::run(&options.python, options.variant.as_deref(), &options.sampler, &jobs, scratch.path())? {
            MitsubaOutcome::Ran(run) => {
                println!(
                    "Mitsuba  {} ({} sampler; device time from Dr.Jit's kernel history)",
                    run.variant, options.sampler
                );
                Some(run.figures)
            }
            MitsubaOutcome::Unavailable(why) => {
                println!("Mitsuba  not available ({why}): rt's figures alone");
                None
            }
        };
    let mut verdicts = Vec::new();
    for ((case, job), rt) in cases.iter().zip(&jobs).zip(&ours) {
        if theirs.is_some() {
            let (w, h) = (case.size.0 as usize, case.size.1 as usize);
            let mi = mitsuba_renders(job)?;
            let ours = Pair { width: w, height: h, renders: [&rt.renders[0], &rt.renders[1]] };
            let verdict = agreement::compare(&ours, &Pair { width: w, height: h, renders: [&mi[0], &mi[1]] });
            println!("images   {}: {verdict}", case.name);
            verdicts.push(verdict);
        }
    }
    println!(
        "\n| scene | figure | rt (wall) | Mitsuba 3 (wall) | rt / Mitsuba | rt (device) | Mitsuba 3 (device) | rt / Mitsuba |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    for (i, (case, rt)) in cases.iter().zip(&ours).enumerate() {
        let mi = theirs.as_ref().and_then(|t| t.get(i)).zip(verdicts.get(i));
        print_case(case, rt, mi);
    }
    Ok(())
}
