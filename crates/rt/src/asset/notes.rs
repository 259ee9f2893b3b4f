//! What an asset's materials render differently from Blender's Cycles, as the exporter
//! wrote it (`extras.rt_notes` of each glTF material: the node, and what rt does instead),
//! for `rt info` to list.

use super::source::{AssetFiles, AssetKind};
use std::path::Path;

/// Each material of the asset at `path` that has notes, with them, in the file's order.
/// An asset without a glTF (OBJ, `.glb`) or one that cannot be read has none: loading it
/// reports what is wrong with it.
pub fn material_notes(path: &Path) -> Vec<(String, Vec<String>)> {
    let Ok(files) = AssetFiles::resolve(path) else {
        return Vec::new();
    };
    let gltf = match &files.kind {
        AssetKind::RtMesh { materials } => materials.clone(),
        AssetKind::Gltf if files.main.extension().is_some_and(|e| e.eq_ignore_ascii_case("gltf")) => files.main,
        _ => return Vec::new(),
    };
    let Ok(bytes) = crate::files::input::read(&gltf) else {
        return Vec::new();
    };
    let Ok(json) = serde_json::from_slice::<serde_json::Value>(&bytes) else {
        return Vec::new();
    };
    let materials = json.get("materials").and_then(|m| m.as_array()).cloned().unwrap_or_default();
    materials
        .iter()
        .filter_map(|m| {
            let notes: Vec<String> = m
                .get("extras")?
                .get(super::material_extras::NOTES)?
                .as_array()?
                .iter()
                .filter_map(|n| n.as_str().map(String::from))
                .collect();
            let name = m.get("name").and_then(|n| n.as_str()).unwrap_or("(unnamed)").to_owned();
            (!notes.is_empty()).then_some((name, notes))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn notes_come_from_the_materials_extras() {
        let dir = std::env::temp_dir().join(format!("rt-notes-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        let path = dir.join("a.gltf");
        let text = r#"{"asset": {"version": "2.0"}, "materials": [
            {"name": "plain"},
            {"name": "rusty", "extras": {"rt_notes": ["Brick Texture: not evaluated; Base Color uses its own value"]}}]}"#;
        std::fs::write(&path, text).expect("write");
        let notes = material_notes(&path);
        assert_eq!(
            notes,
            [("rusty".to_owned(), vec!["Brick Texture: not evaluated; Base Color uses its own value".to_owned()])]
        );
        assert!(material_notes(&dir.join("missing.gltf")).is_empty());
        std::fs::remove_dir_all(&dir).ok();
    }
}
