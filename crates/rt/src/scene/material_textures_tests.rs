//! The texture slots' numbers, against the material's fields and the shader's bits.

use super::*;

#[test]
fn each_slot_names_its_texture() {
    let mut t = MaterialTextures::default();
    for (i, index) in t.indices_mut().into_iter().enumerate() {
        *index = Some(i as u32);
    }
    let l = &t.layers;
    let named = [
        (slots::BASE_COLOR, t.base_color),
        (slots::METALLIC_ROUGHNESS, t.metallic_roughness),
        (slots::EMISSION, t.emission),
        (slots::NORMAL, t.normal),
        (slots::COAT, l.coat),
        (slots::COAT_ROUGHNESS, l.coat_roughness),
        (slots::COAT_TINT, l.coat_tint),
        (slots::SHEEN, l.sheen),
        (slots::SHEEN_TINT, l.sheen_tint),
        (slots::ANISOTROPY, l.anisotropy),
        (slots::SPECULAR_TINT, l.specular_tint),
        (slots::DIFFUSE_ROUGHNESS, l.diffuse_roughness),
        (slots::THIN_FILM_THICKNESS, l.thin_film_thickness),
        (slots::TRANSMISSION, l.transmission),
        (slots::SPECULAR_LEVEL, l.specular_level),
        (slots::IOR, l.ior),
        (slots::COAT_NORMAL, t.coat_normal),
    ];
    assert_eq!(named.len(), slots::COUNT);
    for (slot, index) in named {
        assert_eq!(index, Some(slot as u32), "slot {slot}");
    }
}

#[test]
fn layer_textures_come_back_from_their_slots() {
    let slots: [Option<u32>; LAYER_COUNT] = std::array::from_fn(|i| Some(i as u32 + 4));
    assert_eq!(LayerTextures::from_slots(slots).slots(), slots);
}

#[test]
fn the_coat_normal_differs_unless_it_is_the_base_maps() {
    let base = MaterialTextures { normal: Some(2), ..Default::default() };
    assert!(base.coat_normal_differs(), "a base map does not bend the coat");
    assert!(!MaterialTextures::default().coat_normal_differs());
    let shared = MaterialTextures { coat_normal: Some(2), ..base };
    assert!(!shared.coat_normal_differs());
    assert!(MaterialTextures { coat_normal_scale: 0.5, ..shared }.coat_normal_differs());
    assert!(MaterialTextures { second_uv_set: 1 << slots::COAT_NORMAL, ..shared }.coat_normal_differs());
    let own = MaterialTextures { coat_normal: Some(3), ..Default::default() };
    assert!(own.coat_normal_differs());
    assert_eq!(MaterialTextures { second_uv_set: 1 << slots::COAT_NORMAL, ..own }.normal_uv_set(), UvSet::Second);
}
