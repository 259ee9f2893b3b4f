//! Exact sample-range splits: `rt render --sample-range A..B` renders samples A to B of a
//! render into a part, and `rt merge` adds parts that tile 0..N into the image
//! `rt render --spp N` gives, bit for bit. A sample's random numbers follow from its
//! index in the whole render and the sums are exact integers, so how the samples were
//! split never shows.

mod file;
mod key;

pub use file::{read_part, write_part};
pub use key::{build_id, image_key};

use super::exact::ExactSums;
use super::{Aovs, Image, Session};
use anyhow::{Result, bail};
use serde::{Deserialize, Serialize};
use std::ops::Range;
use std::path::{Path, PathBuf};

/// The version of the part file's layout; older ones are refused by name.
pub const PART_FORMAT: u32 = 1;

/// What a part says of itself, kept in its file's header.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PartHeader {
    pub format: u32,
    /// Samples `first..end` of every pixel.
    pub first: u32,
    pub end: u32,
    pub width: u32,
    pub height: u32,
    pub seed: u32,
    /// See [`image_key`].
    pub image_key: String,
    /// See [`build_id`].
    pub build: String,
    /// The scene file, for messages only.
    pub scene: String,
    /// The GPU that rendered it: parts of one render from different GPUs merge, but may
    /// differ from one render on either by rounding.
    pub gpu: String,
    /// The sums hold the AOVs' too.
    pub aovs: bool,
    /// The merged image is written with its AOV layers (`rt render --aovs`).
    pub aov_layers: bool,
    /// The image has an alpha (a transparent film, holdouts).
    pub alpha: bool,
    /// Exposure in EV for PNG output.
    pub exposure: f32,
}

impl PartHeader {
    fn check_format(&self, path: &Path) -> Result<()> {
        if self.format != PART_FORMAT {
            bail!(
                "{}: a part of format {}, this rt reads format {PART_FORMAT}: render the part again with this rt",
                path.display(),
                self.format
            );
        }
        if self.first >= self.end {
            bail!("{}: its samples {}..{} are empty", path.display(), self.first, self.end);
        }
        Ok(())
    }

    /// The samples it holds.
    pub fn samples(&self) -> Range<u32> {
        self.first..self.end
    }
}

/// Parses `A..B` (samples A inclusive to B exclusive).
pub fn parse_sample_range(s: &str) -> Result<Range<u32>, String> {
    let (a, b) = s.split_once("..").ok_or_else(|| format!("expected FIRST..END, e.g. 0..64, not {s:?}"))?;
    let number = |v: &str| v.trim().parse::<u32>().map_err(|_| format!("{v:?} in {s:?} is not a sample index"));
    let (a, b) = (number(a)?, number(b)?);
    if a >= b {
        return Err(format!("{s:?} holds no samples: the end must be past the start"));
    }
    Ok(a..b)
}

/// What `rt render --sample-range` asks of the part it writes.
pub struct PartRequest<'a> {
    pub path: &'a Path,
    pub samples: Range<u32>,
    pub exposure: f32,
    pub aov_layers: bool,
}

/// Writes the samples `session` took as the part `request` names; the session must have
/// rendered with exact sums, from the part's first sample.
pub fn save(session: &Session, request: &PartRequest) -> Result<()> {
    let Some(sums) = session.exact_sums()? else {
        bail!("the render kept no exact sums: a part needs them");
    };
    let render = session.request();
    let alpha = session.features().has_alpha();
    let header = PartHeader {
        format: PART_FORMAT,
        first: request.samples.start,
        end: request.samples.end,
        width: render.width,
        height: render.height,
        seed: render.seed,
        image_key: image_key(session)?,
        build: build_id()?,
        scene: session.scene().origin.to_string(),
        gpu: session.ctx().adapter_info.name.clone(),
        aovs: sums.aovs,
        aov_layers: request.aov_layers,
        alpha,
        exposure: request.exposure,
    };
    let image = sums.image(request.samples.len() as u32, alpha);
    write_part(request.path, &header, &sums, &image)
}

/// Parts read from their files, checked to be of one render and to tile its samples.
pub struct Merged {
    pub header: PartHeader,
    pub sums: ExactSums,
    /// Samples per pixel of the whole.
    pub spp: u32,
    /// Warnings for the user (parts from different GPUs).
    pub warnings: Vec<String>,
}

impl Merged {
    /// The image `rt render --spp N` writes, and its AOVs if the parts have them.
    pub fn image(&self) -> (Image, Option<Aovs>) {
        (self.sums.image(self.spp, self.header.alpha), self.sums.aovs())
    }
}

/// Reads and merges `paths`; refuses parts of different renders, overlapping parts and
/// gaps, naming the files and samples.
pub fn merge(paths: &[PathBuf]) -> Result<Merged> {
    if paths.is_empty() {
        bail!("no parts to merge: give the files `rt render --sample-range` wrote");
    }
    let mut parts = Vec::with_capacity(paths.len());
    for path in paths {
        let (header, sums) = read_part(path)?;
        parts.push((path.as_path(), header, sums));
    }
    let first = parts[0].1.clone();
    let mut warnings = Vec::new();
    for (path, header, _) in &parts[1..] {
        check_same_render(parts[0].0, &first, path, header)?;
        if header.gpu != first.gpu {
            warnings.push(format!(
                "{} was rendered on {}, {} on {}: the merge may differ from one render on either by rounding",
                parts[0].0.display(),
                first.gpu,
                path.display(),
                header.gpu
            ));
        }
    }
    parts.sort_by_key(|(_, h, _)| h.first);
    check_tiling(&parts.iter().map(|(p, h, _)| (*p, h.samples())).collect::<Vec<_>>())?;
    let spp = parts.last().map_or(0, |(_, h, _)| h.end);
    let mut iter = parts.into_iter();
    let (_, header, mut sums) = iter.next().expect("one part at least");
    for (_, _, more) in iter {
        sums.add(&more);
    }
    Ok(Merged { header, sums, spp, warnings })
}

/// Refuses `b` unless it is a part of the same render as `a`, saying what differs.
fn check_same_render(a_path: &Path, a: &PartHeader, b_path: &Path, b: &PartHeader) -> Result<()> {
    let (a_name, b_name) = (a_path.display(), b_path.display());
    if (a.width, a.height) != (b.width, b.height) {
        bail!(
            "{a_name} is {}x{} and {b_name} {}x{}: parts of one render have one size",
            a.width,
            a.height,
            b.width,
            b.height
        );
    }
    if a.seed != b.seed {
        bail!("{a_name} has seed {} and {b_name} seed {}: parts of one render have one seed", a.seed, b.seed);
    }
    if a.build != b.build {
        bail!(
            "{a_name} was rendered by {} and {b_name} by {}: render every part with one build of rt",
            a.build,
            b.build
        );
    }
    if a.image_key != b.image_key {
        bail!(
            "{a_name} ({}) and {b_name} ({}) are of different scenes or render settings: render every part of one \
             scene with the same flags",
            a.scene,
            b.scene
        );
    }
    if (a.aov_layers, a.alpha, a.exposure) != (b.aov_layers, b.alpha, b.exposure) {
        bail!(
            "{a_name} and {b_name} ask for different outputs (--aovs, --transparent, --exposure): give every part the same"
        );
    }
    Ok(())
}

/// Refuses parts (sorted by their first sample) that do not tile 0..N exactly.
fn check_tiling(parts: &[(&Path, Range<u32>)]) -> Result<()> {
    let mut covered_to = 0u32;
    let mut previous: Option<&Path> = None;
    for (path, range) in parts {
        if range.start > covered_to {
            bail!(
                "samples {covered_to}..{} are in no part (the next, {}, starts at {}): render them with \
                 --sample-range {covered_to}..{}",
                range.start,
                path.display(),
                range.start,
                range.start
            );
        }
        if range.start < covered_to {
            let other = previous.map_or_else(String::new, |p| p.display().to_string());
            bail!(
                "{} and {other} both hold samples {}..{}: each sample must be in one part only",
                path.display(),
                range.start,
                covered_to.min(range.end)
            );
        }
        covered_to = range.end;
        previous = Some(path);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_parse_and_empty_ones_are_refused() {
        assert_eq!(parse_sample_range("0..64"), Ok(0..64));
        assert_eq!(parse_sample_range(" 3 .. 5"), Ok(3..5));
        assert!(parse_sample_range("5..5").unwrap_err().contains("no samples"));
        assert!(parse_sample_range("5").unwrap_err().contains("FIRST..END"));
        assert!(parse_sample_range("a..4").unwrap_err().contains("not a sample index"));
    }

    #[test]
    fn gaps_and_overlaps_are_named() {
        let (a, b) = (Path::new("a.exr"), Path::new("b.exr"));
        assert!(check_tiling(&[(a, 0..4), (b, 4..9)]).is_ok());
        let gap = check_tiling(&[(a, 0..4), (b, 6..9)]).unwrap_err().to_string();
        assert!(gap.contains("samples 4..6 are in no part"), "{gap}");
        let late = check_tiling(&[(a, 2..4)]).unwrap_err().to_string();
        assert!(late.contains("samples 0..2 are in no part"), "{late}");
        let overlap = check_tiling(&[(a, 0..4), (b, 3..9)]).unwrap_err().to_string();
        assert!(overlap.contains("b.exr and a.exr both hold samples 3..4"), "{overlap}");
    }
}
