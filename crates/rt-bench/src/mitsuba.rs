//! Mitsuba 3 timed through its Python API (`mitsuba_compare.py`, run as a child process)
//! on scenes translated by [`super::mitsuba_scene`].

use super::clocks::Timed;
use anyhow::{Context, Result, bail};
use serde_json::{Value, json};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

const SCRIPT: &str = include_str!("mitsuba_compare.py");
const SCENE_LOADER: &str = include_str!("mitsuba_scene.py");

/// One measurement Mitsuba makes: a translated scene, rendered `runs` times at `spp`.
pub struct MitsubaCase {
    pub name: String,
    /// The Mitsuba scene dictionary ([`super::mitsuba_scene::translate`]).
    pub scene: Value,
    pub spp: u32,
    pub runs: u32,
    pub rays: bool,
    /// Where the first two renders' images go (EXR).
    pub images: [PathBuf; 2],
}

/// Mitsuba's figures for one case.
#[derive(Clone, Debug)]
pub struct MitsubaFigures {
    pub paths: Timed,
    pub camera_rays: Option<Timed>,
    pub diffuse_rays: Option<Timed>,
}

/// What came back from the child: the variant it ran and one result per case.
pub struct MitsubaRun {
    pub variant: String,
    pub figures: Vec<MitsubaFigures>,
}

/// Why Mitsuba gave no figures: not installed (a plain fact), or a failure.
pub enum MitsubaOutcome {
    Ran(MitsubaRun),
    Unavailable(String),
}

fn timed(v: &Value) -> Option<Timed> {
    let times = v["times"].as_array()?;
    let pairs: Option<Vec<(f64, f64)>> = times.iter().map(|t| Some((t[0].as_f64()?, t[1].as_f64()?))).collect();
    let (wall, device) = pairs?.into_iter().unzip();
    Some(Timed { count: v["count"].as_u64()?, wall, device })
}

fn figures(line: &Value) -> Result<MitsubaFigures> {
    Ok(MitsubaFigures {
        paths: timed(&line["paths"]).with_context(|| format!("no path times in Mitsuba's answer {line}"))?,
        camera_rays: timed(&line["rays"]["camera"]),
        diffuse_rays: timed(&line["rays"]["diffuse"]),
    })
}

/// Runs the cases with `python`, which must import `mitsuba`: `variant`, or the first of
/// `cuda_ad_rgb` and `llvm_ad_rgb` that works, with the sampler `sampler`. `dir` holds
/// the scripts while they run.
pub fn run(
    python: &str,
    variant: Option<&str>,
    sampler: &str,
    cases: &[MitsubaCase],
    dir: &Path,
) -> Result<MitsubaOutcome> {
    let script = dir.join("mitsuba_compare.py");
    std::fs::write(&script, SCRIPT)?;
    std::fs::write(dir.join("mitsuba_scene.py"), SCENE_LOADER)?;
    let child =
        Command::new(python).arg(&script).stdin(Stdio::piped()).stdout(Stdio::piped()).stderr(Stdio::piped()).spawn();
    let mut child = match child {
        Ok(c) => c,
        Err(e) => return Ok(MitsubaOutcome::Unavailable(format!("cannot run {python}: {e}"))),
    };
    let cases: Vec<Value> = cases
        .iter()
        .map(|c| json!({ "name": c.name, "scene": c.scene, "spp": c.spp, "runs": c.runs, "rays": c.rays, "images": c.images }))
        .collect();
    let job = json!({ "variant": variant, "sampler": sampler, "cases": cases });
    if let Some(mut stdin) = child.stdin.take() {
        // A child that exits at once (no mitsuba) closes its end: that is reported below.
        let _ = stdin.write_all(job.to_string().as_bytes());
    }
    let output = child.wait_with_output()?;
    let stderr = String::from_utf8_lossy(&output.stderr);
    if output.status.code() == Some(3) {
        return Ok(MitsubaOutcome::Unavailable(format!("{python}: {}", stderr.trim())));
    }
    if !output.status.success() {
        bail!("Mitsuba failed ({}):\n{}", output.status, stderr.trim());
    }
    let mut lines = std::str::from_utf8(&output.stdout)?
        .lines()
        .map(serde_json::from_str::<Value>)
        .collect::<Result<Vec<_>, _>>()
        .context("reading Mitsuba's figures")?
        .into_iter();
    let head = lines.next().context("Mitsuba printed nothing")?;
    let variant = format!("{} {}", head["variant"].as_str().unwrap_or("?"), head["version"].as_str().unwrap_or(""));
    Ok(MitsubaOutcome::Ran(MitsubaRun { variant, figures: lines.map(|l| figures(&l)).collect::<Result<_>>()? }))
}
