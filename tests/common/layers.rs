//! Multilayer EXRs (Blender's Render Result, rt's `--aovs` output) by channel, and the 8×8
//! blocks images are compared by.

use std::collections::BTreeMap;
use std::path::Path;

/// Width, height and every channel of an EXR by its full name (`ViewLayer.Depth.Z`, `albedo.R`).
pub fn channels(path: &Path) -> (usize, usize, BTreeMap<String, Vec<f32>>) {
    let image =
        exr::prelude::read_all_flat_layers_from_file(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut all = BTreeMap::new();
    let mut size = (0, 0);
    for layer in &image.layer_data {
        size = (layer.size.0, layer.size.1);
        let prefix = layer.attributes.layer_name.as_ref().map(|n| format!("{n}.")).unwrap_or_default();
        for channel in &layer.channel_data.list {
            let values: Vec<f32> = channel.sample_data.values_as_f32().collect();
            all.insert(format!("{prefix}{}", channel.name), values);
        }
    }
    (size.0, size.1, all)
}

/// The channel whose full name ends with `suffix`.
pub fn channel<'a>(all: &'a BTreeMap<String, Vec<f32>>, suffix: &str) -> &'a [f32] {
    let found = all.iter().find(|(name, _)| name.ends_with(suffix));
    found
        .map(|(_, v)| v.as_slice())
        .unwrap_or_else(|| panic!("no channel {suffix} in {:?}", all.keys().collect::<Vec<_>>()))
}

/// The whole `block`×`block` blocks of a `width`×`height` image, row by row: each block's
/// (x, y) and its pixels' indices.
pub fn blocks(width: usize, height: usize, block: usize) -> impl Iterator<Item = ((usize, usize), Vec<usize>)> {
    (0..height / block).flat_map(move |by| {
        (0..width / block).map(move |bx| {
            let pixels = (by * block..(by + 1) * block)
                .flat_map(|y| (bx * block..(bx + 1) * block).map(move |x| y * width + x))
                .collect();
            ((bx, by), pixels)
        })
    })
}
