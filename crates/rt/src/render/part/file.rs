//! A part's file: an OpenEXR whose R, G, B (and A) show the part's own image in any
//! viewer, and whose `rt.` channels hold what a merge needs: the exact sums, three 32-bit
//! words each (`rt.sum.VV.W`), and the samples each pixel took and dropped. The header's
//! `rt.part` attribute holds the [`PartHeader`] as JSON.

use super::PartHeader;
use crate::render::exact::{self, ExactSums};
use crate::render::{Image, beauty_channels};
use anyhow::{Context, Result, bail};
use exr::meta::attribute::{AttributeValue, Text};
use exr::prelude::{AnyChannel, FlatSamples, LayerAttributes, ReadChannels, ReadLayers, SmallVec};
use std::io::Cursor;
use std::path::Path;

/// The header attribute that holds the part's header.
const HEADER_ATTRIBUTE: &str = "rt.part";

fn sum_channel(value: usize, word: usize) -> String {
    format!("rt.sum.{value:02}.{word}")
}

/// Writes the part atomically: `image` is what the part's samples alone show.
pub fn write_part(path: &Path, header: &PartHeader, sums: &ExactSums, image: &Image) -> Result<()> {
    let values = exact::values_per_pixel(sums.aovs);
    let mut list: SmallVec<[AnyChannel<FlatSamples>; 4]> = SmallVec::new();
    for (name, samples) in beauty_channels(&image.pixels, image.alpha.as_deref()) {
        list.push(AnyChannel::new(name.as_str(), FlatSamples::F32(samples)));
    }
    for value in 0..values {
        let words: Vec<[u32; 3]> = sums.sums.iter().skip(value).step_by(values).map(|&s| exact::to_words(s)).collect();
        for word in 0..exact::WORDS {
            let channel = words.iter().map(|w| w[word]).collect();
            list.push(AnyChannel::new(sum_channel(value, word).as_str(), FlatSamples::U32(channel)));
        }
    }
    list.push(AnyChannel::new("rt.taken", FlatSamples::U32(sums.taken.clone())));
    list.push(AnyChannel::new("rt.dropped", FlatSamples::U32(sums.dropped.clone())));
    let mut attributes = LayerAttributes::default();
    let json = serde_json::to_string(header)?;
    attributes.other.insert(Text::from(HEADER_ATTRIBUTE), AttributeValue::Text(Text::from(json.as_str())));
    crate::render::layers_out::write_exr(path, (sums.width, sums.height), list, attributes, "part")
}

/// Reads a part written by [`write_part`]; an error names the file and what is wrong.
pub fn read_part(path: &Path) -> Result<(PartHeader, ExactSums)> {
    let bytes = crate::files::input::read(path)?;
    let image = exr::prelude::read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .first_valid_layer()
        .all_attributes()
        .from_buffered(Cursor::new(bytes))
        .map_err(|e| anyhow::anyhow!("{}: not a readable OpenEXR ({e})", path.display()))?;
    let layer = &image.layer_data;
    let header: PartHeader = match layer.attributes.other.get(&Text::from(HEADER_ATTRIBUTE)) {
        Some(AttributeValue::Text(text)) => serde_json::from_str(&text.to_string())
            .with_context(|| format!("{}: its `{HEADER_ATTRIBUTE}` header is not one rt can read", path.display()))?,
        _ => bail!(
            "{}: not a part of a render (no `{HEADER_ATTRIBUTE}` header): make parts with `rt render --sample-range`",
            path.display()
        ),
    };
    header.check_format(path)?;
    let (width, height) = (layer.size.0 as u32, layer.size.1 as u32);
    if (width, height) != (header.width, header.height) {
        bail!(
            "{}: its pixels are {width}x{height}, its header says {}x{}",
            path.display(),
            header.width,
            header.height
        );
    }
    let words = |name: &str| -> Result<&Vec<u32>> {
        let channel = layer.channel_data.list.iter().find(|c| c.name == *name);
        match channel.map(|c| &c.sample_data) {
            Some(FlatSamples::U32(v)) => Ok(v),
            Some(_) => bail!("{}: channel {name} is not of 32-bit integers", path.display()),
            None => bail!("{}: channel {name} is missing", path.display()),
        }
    };
    let values = exact::values_per_pixel(header.aovs);
    let pixels = width as usize * height as usize;
    let mut sums = vec![0i128; pixels * values];
    for value in 0..values {
        let w: Vec<&Vec<u32>> =
            (0..exact::WORDS).map(|word| words(&sum_channel(value, word))).collect::<Result<_>>()?;
        for (pixel, sum) in sums.iter_mut().skip(value).step_by(values).enumerate() {
            *sum = exact::to_i128([w[0][pixel], w[1][pixel], w[2][pixel]]);
        }
    }
    let (taken, dropped) = (words("rt.taken")?.clone(), words("rt.dropped")?.clone());
    let aovs = header.aovs;
    Ok((header, ExactSums { width, height, aovs, sums, taken, dropped }))
}
