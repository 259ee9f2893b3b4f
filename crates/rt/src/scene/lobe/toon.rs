//! Blender's Toon BSDF as Cycles renders it (`kernel/closure/bsdf_toon.h`): light within a
//! cone about the normal (Diffuse) or about the view's mirror direction (Glossy) is reflected
//! at full intensity up to Size × 90°, fading to nothing over a further Smooth × 90°; its
//! value is the cone's uniform density times that intensity, so that a sample's weight is
//! the intensity itself. The lobe: `shaders/lobe_toon.wgsl`.

use super::{BlenderNode, LobeModule, Param, ParamKind};

pub const TOON: LobeModule = LobeModule {
    name: "toon",
    params: &[
        // Cycles clamps Size to [1e-5, 1] and Smooth to [0, 1].
        Param { name: "size", kind: ParamKind::Number { min: 1e-5, max: 1.0 }, default: 0.5 },
        Param { name: "smooth", kind: ParamKind::Number { min: 0.0, max: 1.0 }, default: 0.0 },
        Param { name: "component", kind: ParamKind::Choice(&["diffuse", "glossy"]), default: 0.0 },
    ],
    wgsl: ("lobe_toon.wgsl", include_str!("../../../shaders/lobe_toon.wgsl")),
    blender: BlenderNode {
        node: "BSDF_TOON",
        color: "Color",
        inputs: &[("Size", "size"), ("Smooth", "smooth")],
        properties: &[("component", "component")],
    },
};
