//! `rt bench compare`: rt's throughput beside Mitsuba 3's on the same scenes, in one
//! run, with the ratios. Without an importable Mitsuba it says so and prints rt's
//! figures alone.

use super::mitsuba::{self, MitsubaCase, MitsubaFigures, MitsubaOutcome};
use super::throughput::{Throughput, ThroughputOptions, measure};
use crate::bvh::BuildQuality;
use crate::gpu::{GpuContext, GpuTimer};
use crate::render::{Session, human};
use crate::scene::{self, Microfacet, Scene};
use anyhow::Result;
use indicatif::ProgressBar;
use std::path::{Path, PathBuf};

pub struct CompareOptions {
    /// Scenes to compare at `size`; none: the held-in set below.
    pub scenes: Vec<PathBuf>,
    pub size: (u32, u32),
    pub runs: u32,
    /// The Python that imports `mitsuba`.
    pub python: String,
    pub variant: Option<String>,
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
    Ok(vec![
        Case {
            name: "Cornell box, 9 path vertices".into(),
            scene: with_bounces(&cornell, 8),
            size: (1024, 720),
            spp: 16,
            rays: false,
        },
        Case {
            name: "Cornell box, 65 path vertices".into(),
            scene: with_bounces(&cornell, 64),
            size: (1024, 720),
            spp: 16,
            rays: false,
        },
        // A small live window: the same work per dispatch as the window's pacing allows.
        Case {
            name: "Cornell box at 128x128".into(),
            scene: with_bounces(&cornell, 8),
            size: (128, 128),
            spp: 1024,
            rays: false,
        },
        // The small window's framing at a large size: at 1024x720 a quarter of the camera
        // rays pass beside the box and end at once, which makes those paths cheaper.
        Case {
            name: "Cornell box at 1024x1024".into(),
            scene: with_bounces(&cornell, 8),
            size: (1024, 1024),
            spp: 16,
            rays: false,
        },
        Case { name: "46k-triangle dragon, uniform sky".into(), scene: dragon, size: (1024, 720), spp: 16, rays: true },
    ])
}

/// The cases to time, each rendered by rt as Mitsuba renders it: its single-scattering
/// lobes, and smooth normals without Cycles' shadow-terminator handling (which Mitsuba
/// does not have), so that both renderers do the same work.
fn cases(options: &CompareOptions) -> Result<Vec<Case>> {
    let cases = match options.scenes.is_empty() {
        true => held_in(&options.root)?,
        false => options
            .scenes
            .iter()
            .map(|path| {
                let scene = scene::load(path)?;
                Ok(Case { name: path.display().to_string(), scene, size: options.size, spp: 16, rays: true })
            })
            .collect::<Result<_>>()?,
    };
    Ok(cases
        .into_iter()
        .map(|mut case| {
            case.scene.render.microfacet = Microfacet::Single;
            case
        })
        .collect())
}

fn mitsuba_figures(options: &CompareOptions, cases: &[Case]) -> Result<MitsubaOutcome> {
    let scratch = crate::files::ScratchDir::new("compare")?;
    let mut jobs = Vec::new();
    for c in cases {
        let case =
            MitsubaCase { name: &c.name, scene: &c.scene, size: c.size, spp: c.spp, runs: options.runs, rays: c.rays };
        jobs.push(mitsuba::translate(&case, scratch.path())?);
    }
    mitsuba::run(&options.python, options.variant.as_deref(), jobs, scratch.path())
}

fn ratio(rt: f64, other: Option<f64>) -> String {
    other.filter(|o| *o > 0.0).map_or("—".into(), |o| format!("{:.2}×", rt / o))
}

/// A rate, or a dash where there is none.
pub(super) fn rate(v: Option<f64>) -> String {
    v.map_or("—".into(), human)
}

fn rows(case: &Case, rt: &Throughput, mi: Option<&MitsubaFigures>) -> Vec<[String; 5]> {
    let mut rows = Vec::new();
    let name = format!("{} ({}x{}, {} spp)", case.name, case.size.0, case.size.1, case.spp);
    let mut push = |what: &str, ours: Option<f64>, theirs: Option<f64>| {
        if let Some(ours) = ours {
            rows.push([name.clone(), what.into(), human(ours), rate(theirs), ratio(ours, theirs)]);
        }
    };
    push("paths/s", Some(rt.paths_per_s()), mi.map(|m| m.paths_per_s));
    push("camera rays/s", rt.camera_rays_per_s(), mi.and_then(|m| m.camera_rays_per_s));
    push("diffuse rays/s", rt.diffuse_rays_per_s(), mi.and_then(|m| m.diffuse_rays_per_s));
    rows
}

pub fn compare(options: &CompareOptions, adapter: Option<&str>) -> Result<()> {
    let cases = cases(options)?;
    let ctx = GpuContext::new(adapter)?;
    println!("GPU      {} (timed by {})", ctx.describe(), GpuTimer::new(&ctx).method());
    let bar = ProgressBar::new(cases.iter().map(|c| (1 + c.rays as u64) * (options.runs.max(1) as u64 + 1)).sum());
    let mut ours = Vec::new();
    for case in &cases {
        let mut session = Session::open(&ctx, case.scene.clone(), BuildQuality::default())?;
        let t = ThroughputOptions { size: case.size, runs: options.runs, spp: case.spp, lanes: None, rays: case.rays };
        ours.push(measure(&mut session, &t, &bar)?);
    }
    bar.finish_and_clear();
    let theirs = match mitsuba_figures(options, &cases)? {
        MitsubaOutcome::Ran(run) => {
            println!("Mitsuba  {}", run.variant);
            Some(run.figures)
        }
        MitsubaOutcome::Unavailable(why) => {
            println!("Mitsuba  not available ({why}): rt's figures alone");
            None
        }
    };
    println!("\n| scene | figure | rt | Mitsuba 3 | rt / Mitsuba |\n|---|---|---|---|---|");
    for (i, (case, rt)) in cases.iter().zip(&ours).enumerate() {
        for row in rows(case, rt, theirs.as_ref().and_then(|t| t.get(i))) {
            println!("| {} |", row.join(" | "));
        }
    }
    if options.scenes.is_empty() {
        // The small window against the large ones, same scene and bounces.
        let small = ours[2].paths_per_s();
        println!(
            "\nrt at 128x128 runs at {:.2}× its 1024x720 rate and {:.2}× its 1024x1024 rate (same framing)",
            small / ours[0].paths_per_s(),
            small / ours[3].paths_per_s()
        );
    }
    Ok(())
}
