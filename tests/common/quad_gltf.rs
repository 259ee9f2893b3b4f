//! A textured quad as glTF text, for the texture tests.

/// One quad with texture coordinates (glTF's: origin at the top left of the image),
/// `corners` in order (0,0), (1,0), (1,1), (0,1); its one material is the JSON object
/// `material`, whose textures all use image 0 at `image_uri`; with `second`, a second set
/// of texture coordinates, `TEXCOORD_1`.
pub fn textured_quad(corners: [[f32; 3]; 4], material: &str, image_uri: &str, second: Option<[[f32; 2]; 4]>) -> String {
    let mut bytes = Vec::new();
    corners.iter().flatten().for_each(|f| bytes.extend(f.to_le_bytes()));
    [[0.0f32, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]].iter().flatten().for_each(|f| bytes.extend(f.to_le_bytes()));
    [0u32, 1, 2, 0, 2, 3].iter().for_each(|i| bytes.extend(i.to_le_bytes()));
    let (second_attribute, second_view, second_accessor) = match second {
        Some(uvs) => {
            uvs.iter().flatten().for_each(|f| bytes.extend(f.to_le_bytes()));
            (
                r#", "TEXCOORD_1": 3"#,
                r#", { "buffer": 0, "byteOffset": 104, "byteLength": 32 }"#,
                r#", { "bufferView": 3, "componentType": 5126, "count": 4, "type": "VEC2" }"#,
            )
        }
        None => ("", "", ""),
    };
    let bound = |pick: fn(f32, f32) -> f32| {
        let b = corners.iter().skip(1).fold(corners[0], |b, c| [0, 1, 2].map(|i| pick(b[i], c[i])));
        format!("[{}, {}, {}]", b[0], b[1], b[2])
    };
    let (min, max) = (bound(f32::min), bound(f32::max));
    let data = base64::encode(&bytes);
    format!(
        r#"{{
  "asset": {{ "version": "2.0" }}, "scene": 0, "scenes": [{{ "nodes": [0] }}], "nodes": [{{ "mesh": 0 }}],
  "meshes": [{{ "primitives": [{{ "attributes": {{ "POSITION": 0, "TEXCOORD_0": 1{second_attribute} }}, "indices": 2, "material": 0 }}] }}],
  "materials": [{material}],
  "textures": [{{ "source": 0 }}],
  "images": [{{ "uri": "{image_uri}" }}],
  "buffers": [{{ "byteLength": {len}, "uri": "data:application/octet-stream;base64,{data}" }}],
  "bufferViews": [{{ "buffer": 0, "byteLength": 48 }}, {{ "buffer": 0, "byteOffset": 48, "byteLength": 32 }},
    {{ "buffer": 0, "byteOffset": 80, "byteLength": 24 }}{second_view}],
  "accessors": [
    {{ "bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": {min}, "max": {max} }},
    {{ "bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2" }},
    {{ "bufferView": 2, "componentType": 5125, "count": 6, "type": "SCALAR" }}{second_accessor}]
}}"#,
        len = bytes.len()
    )
}
