//! A scene's lamps, and the light tree over them and its emitters.

use super::light_bounds::lamp_bounds;
use super::light_tree::{LightBounds, LightTree, TreeLight};
use super::lights::{LampTable, lamp_table, scene_radius};
use crate::layout::*;
use crate::scene::{LightSampler, Sampling, Scene};
use anyhow::Result;
use glam::Vec3;
use std::time::{Duration, Instant};

/// The scene's lamps and the light tree over them and the emitters.
pub(super) struct SceneLights {
    pub lamps: Vec<GpuLamp>,
    pub lamp_info: GpuLampInfo,
    pub tree: LightTree,
    pub tree_build_time: Duration,
}

impl SceneLights {
    pub fn of(
        scene: &Scene,
        emitters: &[GpuEmitter],
        emitter_bounds: &[LightBounds],
        moving_lights: bool,
        (bounds_min, bounds_max): (Vec3, Vec3),
    ) -> Result<Self> {
        // The tree bounds each light where the frame has it; a light that moves over the
        // shutter could leave its bounds, so such scenes sample lights by power.
        let mut light_sampler = scene.render.light_sampler;
        if moving_lights && light_sampler == LightSampler::Tree {
            log::warn!("{}: an emissive mesh moves over the shutter: lights are sampled by power", scene.origin);
            light_sampler = LightSampler::Power;
        }
        if scene.render.sampling == Sampling::Resampled {
            for (i, _) in scene.lights.iter().enumerate().filter(|(_, l)| l.is_delta()) {
                log::warn!(
                    "{}: light {} has no size (a point, or a sun of angle 0): with sampling = \"seed\" no ray finds it and it lights nothing",
                    scene.origin,
                    i + 1
                );
            }
        }
        let LampTable { lamps, info: lamp_info } = lamp_table(
            &scene.lights,
            scene.sun.is_some(),
            !emitters.is_empty(),
            scene_radius(bounds_min, bounds_max),
            light_sampler,
        );
        let start = Instant::now();
        // Scenes that sample by power pay nothing for the tree: theirs is empty, and a
        // pipeline with the tree's code (all features) then finds emitters by BSDF rays only.
        let tree = if light_sampler == LightSampler::Tree {
            tree_of(emitter_bounds, &scene.lights, &lamps)?
        } else {
            LightTree::build(&[], emitter_bounds.len() + lamps.len())?
        };
        let tree_build_time = start.elapsed();
        log::info!(
            "light tree: {} nodes over {} lights in {:.2} ms",
            tree.nodes.len(),
            tree.trails.len(),
            tree_build_time.as_secs_f64() * 1e3
        );
        Ok(Self { lamps, lamp_info, tree, tree_build_time })
    }
}

/// The light tree over emitters (trail and link `j` for emitter j) and lamps (link
/// `i | LIGHT_TREE_LAMP`, trail `emitter count + i` for lamp i).
fn tree_of(emitter_bounds: &[LightBounds], lights: &[crate::scene::Light], lamps: &[GpuLamp]) -> Result<LightTree> {
    let count = emitter_bounds.len();
    let emitters =
        emitter_bounds.iter().enumerate().map(|(j, b)| TreeLight { bounds: *b, link: j as u32, trail_index: j as u32 });
    let lamps = lights.iter().zip(lamps).enumerate().filter_map(|(i, (l, lamp))| {
        let bounds = lamp_bounds(l, lamp)?;
        Some(TreeLight { bounds, link: i as u32 | LIGHT_TREE_LAMP, trail_index: (count + i) as u32 })
    });
    let tree_lights: Vec<TreeLight> = emitters.chain(lamps).collect();
    LightTree::build(&tree_lights, count + lights.len())
}
