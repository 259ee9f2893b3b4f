//! The Blender exporter's sRGB (it decodes images' codes and encodes glTF colour slots in
//! Python, inside Blender) is rt's: `rt_export.srgb_to_linear` and `linear_to_srgb`
//! against `rt::scene::srgb_decode` and `srgb_encode`, on a grid fine enough to fall
//! between each curve's threshold and a neighbour.

use crate::common::{bpy_python, repo};
use std::process::Command;

/// Grid points of [0, 1.5] the comparison takes.
const STEPS: usize = 15_000;

/// The exporter's function `name` at every grid point, as Blender's Python computes it.
fn exporter(name: &str) -> Vec<f64> {
    let script = format!(
        "import sys, json, numpy as np\n\
         sys.path.insert(0, {blender:?})\n\
         from rt_blender import rt_export\n\
         c = np.arange({STEPS} + 1, dtype=np.float64) * 1.5 / {STEPS}\n\
         print(json.dumps(rt_export.{name}(c).tolist()))\n",
        blender = repo().join("blender").display().to_string(),
    );
    let out = Command::new(bpy_python()).args(["-c", &script]).output().expect("bpy runs");
    assert!(out.status.success(), "{name}: {}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8_lossy(&out.stdout);
    let line = text.lines().last().expect("a line of values");
    serde_json::from_str(line).unwrap_or_else(|e| panic!("{name}'s values: {e}"))
}

/// Each value within f32 rounding of rt's (relative 10⁻⁶).
fn check(name: &str, rt: fn(f32) -> f32) {
    let values = exporter(name);
    assert_eq!(values.len(), STEPS + 1);
    for (i, python) in values.into_iter().enumerate() {
        let c = i as f64 * 1.5 / STEPS as f64;
        let ours = rt(c as f32) as f64;
        let bound = 1e-6 * ours.abs().max(1e-3);
        assert!((python - ours).abs() <= bound, "{name}({c}): the exporter gives {python}, rt {ours}");
    }
}

#[test]
fn the_exporters_srgb_decoding_is_rts() {
    check("srgb_to_linear", rt::scene::srgb_decode);
}

#[test]
fn the_exporters_srgb_encoding_is_rts() {
    check("linear_to_srgb", rt::scene::srgb_encode);
}
