//! Blender's shader nodes other than the Principled BSDF, as rt_export.py maps them onto
//! rt's material model (README: "Other shader nodes"). `tests/cycles/make_shader_node_refs.py`
//! builds rows of five spheres in bpy (Diffuse, Glossy, Glass, Emission, and Mix and Add
//! Shaders of them with Transparent and Emission), renders them with Cycles
//! (`tests/cycles/nodes_NAME.exr`, 2048 spp) and exports them
//! (`tests/cycles/scenes/nodes_NAME/`); rt must match per sphere and per 8×8 block within
//! the noise (the bounds of `cycles_principled`). What the exporter cannot map is a warning
//! naming the material and the node.

use crate::common;
use crate::cycles_principled::check_row;

#[test]
fn single_nodes_match_cycles() {
    check_row("nodes_single");
}

/// The Diffuse BSDF's Roughness 0…1 under a sun: Cycles 5.0's Oren-Nayar closure, the one
/// of the Principled's Diffuse Roughness.
#[test]
fn rough_diffuse_nodes_match_cycles() {
    check_row("nodes_rough_diffuse_sun");
}

#[test]
fn mixed_and_added_nodes_match_cycles() {
    check_row("nodes_mixed");
}

#[test]
fn unmappable_nodes_warn_naming_material_and_node() {
    let out = common::empty_temp_dir("shader-node-warnings");
    let stderr = common::run_bpy_script("shader_node_warnings.py", &out);
    for needle in [
        "hair_mat: 'Strands' (ShaderNodeBsdfHair): this shader node is not supported by rt",
        "hair_mat: its surface is rendered with the material's viewport colour",
        "noisy_mix: 'Blend' (ShaderNodeMixShader): its Fac is linked",
        "glossy_glass: 'Both' (ShaderNodeMixShader): rt cannot mix a glossy and a glass surface: using the glass one",
        "skin_mat: 'Skin' (ShaderNodeBsdfPrincipled): Subsurface Weight 0.5 is rendered as the diffuse base",
        "leaf_mat: 'Leaf' (ShaderNodeBsdfTranslucent): rt has no diffuse transmission",
        "lens_mat: IOR is linked to TEX_IMAGE; rt follows an image through a Map Range or a Math Multiply node only",
        "lens_mat: Lens.Subsurface Weight is linked to an image, which rt reads for no such input; using its own value",
    ] {
        assert!(stderr.contains(needle), "{needle:?} missing from:\n{stderr}");
    }
    // A Toon BSDF is a lobe module of rt: no warning, its settings exported as its parameters.
    assert!(!stderr.contains("toon_mat"), "a Toon BSDF is warned about:\n{stderr}");
    let toon = rt::asset::load_mesh(&out.join("assets/Cube_008")).expect("loads");
    let lobe = toon.materials[0].1.lobe.expect("a lobe module");
    assert_eq!((lobe.declaration().name, lobe.params), ("toon", [0.3, 0.0, 0.0, 0.0]), "{lobe:?}");
    // A rough Diffuse BSDF is Cycles' Oren-Nayar, which rt renders: no warning, its roughness exported.
    assert!(!stderr.contains("felt_mat"), "a rough Diffuse BSDF is warned about:\n{stderr}");
    let rough = std::fs::read_dir(out.join("assets"))
        .expect("assets")
        .filter_map(|e| rt::asset::load_mesh(&e.expect("entry").path()).ok())
        .flat_map(|mesh| mesh.materials.into_iter().map(|(_, m)| m))
        .filter(|m| m.diffuse_roughness > 0.0)
        .collect::<Vec<_>>();
    assert!(matches!(&rough[..], [m] if m.diffuse_roughness == 0.5 && m.diffuse == 1.0), "{rough:?}");
    // The dominant shader of the mix is what rt renders: Glass (weight 0.7) over Glossy.
    let glass = rt::asset::load_mesh(&out.join("assets/Cube_002")).expect("loads");
    let m = &glass.materials[0].1;
    assert_eq!((m.transmission, m.specular, m.diffuse), (1.0, 0.0, 0.0), "{m:?}");
    // An empty input of a Mix Shader is black: half of the Diffuse's colour.
    let half = rt::asset::load_mesh(&out.join("assets/Cube_006")).expect("loads");
    let m = &half.materials[0].1;
    let expected = [0.4, 0.3, 0.2];
    assert!(m.base_color.iter().zip(expected).all(|(a, b)| (a - b).abs() < 1e-6), "{m:?}");
    assert_eq!((m.diffuse, m.specular_ior_level), (1.0, 0.0), "{m:?}");
    // `rt info` lists what each material renders differently, as the export noted it.
    let info = std::process::Command::new(env!("CARGO_BIN_EXE_rt"))
        .arg("info")
        .arg(out.join("scene.toml"))
        .output()
        .expect("rt info runs");
    let listed = String::from_utf8_lossy(&info.stdout);
    for needle in [
        "material `hair_mat`: Strands: this shader node is not supported by rt",
        "material `leaf_mat`: Leaf: rt has no diffuse transmission",
    ] {
        assert!(listed.contains(needle), "{needle:?} missing from rt info:\n{listed}");
    }
    let _ = std::fs::remove_dir_all(&out);
}
