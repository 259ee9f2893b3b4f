//! Feature analysis: which effects a scene needs, so that the GPU runs only their code.

use super::{Material, Sky};
use std::fmt;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SkyFeature {
    Black,
    Uniform,
    Atmosphere,
}

/// The effects a scene calls for. Each one selects shader code; an absent
/// effect's code is not in the pipeline that runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct FeatureSet {
    pub triangles: bool,
    pub spheres: bool,
    pub emission: bool,
    pub sky: SkyFeature,
}

impl FeatureSet {
    /// Derives the set from what the scene really contains, after its assets
    /// are loaded (an asset's own materials may emit).
    pub fn analyse(has_triangles: bool, has_spheres: bool, materials_in_use: &[&Material], sky: &Sky) -> Self {
        Self {
            triangles: has_triangles,
            spheres: has_spheres,
            emission: materials_in_use.iter().any(|m| m.is_emissive()),
            sky: match sky {
                Sky::Black => SkyFeature::Black,
                Sky::Uniform { .. } => SkyFeature::Uniform,
                Sky::Atmosphere => SkyFeature::Atmosphere,
            },
        }
    }

    /// Every effect on: the pipeline a scene would run without specialisation.
    pub fn all() -> Self {
        Self { triangles: true, spheres: true, emission: true, sky: SkyFeature::Uniform }
    }
}

impl fmt::Display for FeatureSet {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut parts = Vec::new();
        if self.triangles {
            parts.push("triangles");
        }
        if self.spheres {
            parts.push("spheres");
        }
        if self.emission {
            parts.push("emission");
        }
        parts.push(match self.sky {
            SkyFeature::Black => "sky=black",
            SkyFeature::Uniform => "sky=uniform",
            SkyFeature::Atmosphere => "sky=atmosphere",
        });
        f.write_str(&parts.join(" "))
    }
}
