//! How one glTF texture reference reads its image: the uv set (`texCoord`, which
//! `KHR_texture_transform` may override) and the extension's offset, rotation and scale,
//! as a [`UvTransform`] of rt's texture coordinates. Each reference keeps its own: two
//! textures of a material on one uv set may be tiled differently.
//!
//! The extension's GLSL listing rotates the other way from its text ("counter-clockwise
//! in uv space", where v points down), from its sample model TextureTransformTest and from
//! Blender's importer and exporter: rt follows those, `R = [[cos, sin], [−sin, cos]]`.

use super::texture::{IDENTITY_UV_TRANSFORM as IDENTITY, UvTransform};
use gltf::json::Value;

/// A texture reference's uv set and transform.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct TextureUse {
    pub tex_coord: u32,
    pub transform: UvTransform,
}

/// `translation · rotation · scale` of glTF's coordinates (v down), as a map of rt's
/// (v up): with F(u, v) = (u, 1 − v), rt's map is F ∘ M ∘ F.
fn rt_transform([ox, oy]: [f32; 2], rotation: f32, [sx, sy]: [f32; 2]) -> UvTransform {
    let (s, c) = rotation.sin_cos();
    let [[a00, a01], [a10, a11]] = [[c * sx, s * sy], [-s * sx, c * sy]];
    [[a00, -a01, a01 + ox], [-a10, a11, 1.0 - a11 - oy]]
}

/// A typed texture info's use.
pub(super) fn of_info(info: &gltf::texture::Info) -> TextureUse {
    match info.texture_transform() {
        Some(t) => TextureUse {
            tex_coord: t.tex_coord().unwrap_or(info.tex_coord()),
            transform: rt_transform(t.offset(), t.rotation(), t.scale()),
        },
        None => TextureUse { tex_coord: info.tex_coord(), transform: IDENTITY },
    }
}

/// The use of a texture info whose `texCoord` is `tex_coord` and whose
/// `extensions.KHR_texture_transform` is `extension` (raw JSON), `what` naming it in errors.
pub(super) fn of_json(tex_coord: u32, extension: Option<&Value>, what: &str) -> Result<TextureUse, String> {
    let Some(ext) = extension else { return Ok(TextureUse { tex_coord, transform: IDENTITY }) };
    let what = format!("{what}.extensions.KHR_texture_transform");
    let pair = |key: &str, default: [f32; 2]| -> Result<[f32; 2], String> {
        let Some(v) = ext.get(key) else { return Ok(default) };
        match v.as_array().map(|a| a.iter().map(Value::as_f64).collect::<Option<Vec<f64>>>()) {
            Some(Some(a)) if a.len() == 2 => Ok([a[0] as f32, a[1] as f32]),
            _ => Err(format!("{what}.{key} must be two numbers, got {v}")),
        }
    };
    let rotation = match ext.get("rotation") {
        None => 0.0,
        Some(v) => v.as_f64().ok_or_else(|| format!("{what}.rotation must be a number, got {v}"))? as f32,
    };
    let tex_coord = match ext.get("texCoord") {
        None => tex_coord,
        Some(v) => v.as_u64().ok_or_else(|| format!("{what}.texCoord must be a whole number, got {v}"))? as u32,
    };
    Ok(TextureUse { tex_coord, transform: rt_transform(pair("offset", [0.0; 2])?, rotation, pair("scale", [1.0; 2])?) })
}

/// A normal texture info's use (gltf models its extension as raw JSON only).
pub(super) fn of_normal(n: &gltf::material::NormalTexture) -> Result<TextureUse, String> {
    of_json(n.tex_coord(), n.extension_value("KHR_texture_transform"), "normalTexture")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn apply(t: UvTransform, [u, v]: [f32; 2]) -> [f32; 2] {
        let [a, b] = t;
        [a[0] * u + a[1] * v + a[2], b[0] * u + b[1] * v + b[2]]
    }

    #[test]
    fn a_transform_of_gltf_coordinates_becomes_one_of_rts() {
        // glTF: offset (0.5, 0.25), a quarter turn, scale (2, 1): (u, v) → (v + 0.5, −2u + 0.25).
        let t = rt_transform([0.5, 0.25], std::f32::consts::FRAC_PI_2, [2.0, 1.0]);
        for [u, v] in [[0.0, 0.0], [1.0, 0.0], [0.3, 0.7]] {
            let gltf = [v + 0.5, -2.0 * u + 0.25];
            // rt's coordinates of the same point: v from the bottom.
            let got = apply(t, [u, 1.0 - v]);
            assert!((got[0] - gltf[0]).abs() < 1e-6 && (got[1] - (1.0 - gltf[1])).abs() < 1e-6, "{got:?} {gltf:?}");
        }
    }

    #[test]
    fn the_extension_may_override_tex_coord_and_rejects_bad_values() {
        let ext: Value = serde_json::from_str(r#"{ "scale": [8, 8], "texCoord": 1 }"#).unwrap();
        let used = of_json(0, Some(&ext), "x").unwrap();
        assert_eq!(used.tex_coord, 1);
        assert_eq!(used.transform, [[8.0, 0.0, 0.0], [0.0, 8.0, -7.0]]);
        let bad: Value = serde_json::from_str(r#"{ "scale": 8 }"#).unwrap();
        let err = of_json(0, Some(&bad), "normalTexture").unwrap_err();
        assert!(err.contains("normalTexture.extensions.KHR_texture_transform.scale"), "{err}");
    }
}
