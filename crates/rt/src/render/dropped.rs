//! What the renderer could not compute: samples dropped for being non-finite
//! (with the event that produced the first per pixel) and traversal stack overflows.

use crate::shared_constants::{
    EVENT_AIR, EVENT_EMISSION, EVENT_LIGHT_SAMPLE, EVENT_LOBE, EVENT_MEDIUM, EVENT_SKY, LOBE_DIFFUSE, LOBE_REFLECTION,
    LOBE_SPECULAR, LOBE_TRANSMISSION,
};
use std::fmt;

/// The event that first produced a non-finite value in a sample
/// (`EVENT_*` in `crate::shared_constants`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum NonFiniteCause {
    Unknown,
    Emission,
    Sky,
    LightSample,
    Medium,
    Air,
    DiffuseLobe,
    SpecularLobe,
    ReflectionLobe,
    TransmissionLobe,
}

impl NonFiniteCause {
    pub fn from_code(code: u32) -> Self {
        match code {
            EVENT_EMISSION => Self::Emission,
            EVENT_SKY => Self::Sky,
            EVENT_LIGHT_SAMPLE => Self::LightSample,
            EVENT_MEDIUM => Self::Medium,
            EVENT_AIR => Self::Air,
            _ => match code.wrapping_sub(EVENT_LOBE) {
                LOBE_DIFFUSE => Self::DiffuseLobe,
                LOBE_SPECULAR => Self::SpecularLobe,
                LOBE_REFLECTION => Self::ReflectionLobe,
                LOBE_TRANSMISSION => Self::TransmissionLobe,
                _ => Self::Unknown,
            },
        }
    }
}

impl fmt::Display for NonFiniteCause {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::Unknown => "unknown",
            Self::Emission => "emission",
            Self::Sky => "sky or sun",
            Self::LightSample => "light sample",
            Self::Medium => "medium",
            Self::Air => "atmosphere",
            Self::DiffuseLobe => "diffuse lobe",
            Self::SpecularLobe => "specular lobe",
            Self::ReflectionLobe => "reflection lobe",
            Self::TransmissionLobe => "transmission lobe",
        })
    }
}

/// Per render: how many samples were dropped, in how many pixels, and why.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct DroppedSamples {
    pub non_finite_samples: u64,
    pub pixels_with_non_finite: usize,
    /// Pixels by the cause of their first non-finite sample, most frequent first.
    pub first_causes: Vec<(NonFiniteCause, usize)>,
    pub stack_overflows: u32,
}

impl DroppedSamples {
    pub fn from_pixels(per_pixel: &[(u32, NonFiniteCause)], stack_overflows: u32) -> Self {
        let mut causes = std::collections::BTreeMap::new();
        let mut s = DroppedSamples { stack_overflows, ..Default::default() };
        for &(count, cause) in per_pixel.iter().filter(|(c, _)| *c > 0) {
            s.non_finite_samples += count as u64;
            s.pixels_with_non_finite += 1;
            *causes.entry(cause).or_insert(0) += 1;
        }
        s.first_causes = causes.into_iter().collect();
        s.first_causes.sort_by_key(|&(_, n)| std::cmp::Reverse(n));
        s
    }

    pub fn is_clean(&self) -> bool {
        self.non_finite_samples == 0 && self.stack_overflows == 0
    }
}

impl fmt::Display for DroppedSamples {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} non-finite samples dropped", self.non_finite_samples)?;
        if self.non_finite_samples > 0 {
            let causes: Vec<String> = self.first_causes.iter().map(|(c, n)| format!("{c}: {n}")).collect();
            write!(f, " in {} pixels (first cause per pixel: {})", self.pixels_with_non_finite, causes.join(", "))?;
        }
        write!(f, "; {} rays overflowed the traversal stack", self.stack_overflows)
    }
}
