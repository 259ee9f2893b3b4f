//! Frames of an animation as files: `shot_####.toml` names frame 7 `shot_0007.toml`, and
//! `out_####.png` its image. The run of `#` is the frame number, zero-padded to its width.

use anyhow::{Result, bail};
use std::ops::RangeInclusive;
use std::path::{Path, PathBuf};

/// Parses `A..B`: frames A to B, both included (as Blender's frame range).
pub fn parse_frame_range(s: &str) -> Result<RangeInclusive<u32>, String> {
    let (a, b) = s.split_once("..").ok_or_else(|| format!("expected FIRST..LAST, e.g. 1..24, not {s:?}"))?;
    let number = |v: &str| v.trim().parse::<u32>().map_err(|_| format!("{v:?} in {s:?} is not a frame number"));
    let (a, b) = (number(a)?, number(b)?);
    if b < a {
        return Err(format!("{s:?}: the last frame comes before the first"));
    }
    Ok(a..=b)
}

/// `pattern` with its run of `#` replaced by `frame`, zero-padded to the run's width; an
/// error names the path when it has no `#`.
pub fn frame_path(pattern: &Path, frame: u32, what: &str) -> Result<PathBuf> {
    let text = pattern.to_string_lossy();
    let Some(start) = text.find('#') else {
        bail!("{what} {}: with --frames, the path needs #### where the frame number goes", pattern.display());
    };
    let width = text[start..].chars().take_while(|&c| c == '#').count();
    Ok(PathBuf::from(format!("{}{frame:0width$}{}", &text[..start], &text[start + width..])))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_numbers_fill_the_run_of_hashes() {
        let at = |p: &str, f| frame_path(Path::new(p), f, "scene").map(|p| p.display().to_string());
        assert_eq!(at("shot_####.toml", 7).unwrap(), "shot_0007.toml");
        assert_eq!(at("a/#/b.png", 12).unwrap(), "a/12/b.png");
        assert!(at("shot.toml", 1).unwrap_err().to_string().contains("needs ####"));
        assert_eq!(parse_frame_range("1..3"), Ok(1..=3));
        assert!(parse_frame_range("3..1").unwrap_err().contains("before the first"));
    }
}
