//! The materials' node programs as the GPU reads them: one table holding each program
//! after one word, the number of its shape; and the shapes themselves (one program of
//! each), from which the pipeline's specialised code is made (`gpu::node_code`). Programs
//! that share a shape differ only in values, which the code reads from the table.

use crate::asset::node_program::{instructions, shape};
use crate::scene::Material;
use std::collections::BTreeMap;

/// At most this many shapes are specialised; a scene with more runs the interpreter,
/// whose pipeline does not grow with the programs.
pub const MAX_SPECIALISED_SHAPES: usize = 16;
/// At most this many instructions over all specialised shapes.
pub const MAX_SPECIALISED_INSTRUCTIONS: usize = 256;

#[derive(Clone, Debug, Default, PartialEq)]
pub struct NodeTable {
    /// The programs one after another, each after its shape's number.
    pub words: Vec<u32>,
    /// Per material, where its program's first word is (`GpuMaterial::node_program`).
    pub starts: Vec<Option<u32>>,
    /// One program of each shape, by shape number; empty when there are too many to
    /// specialise.
    pub shapes: Vec<Vec<u32>>,
    /// Names the shapes (0: none, or not specialised): the pipeline's specialised code.
    pub key: u64,
}

impl NodeTable {
    pub fn of(materials: &[Material]) -> Self {
        // Each program read once: its shape (None: no program, or one that cannot be read).
        let shapes: Vec<Option<Vec<u32>>> = materials
            .iter()
            .map(|m| (!m.node_program.is_empty()).then(|| shape(&m.node_program).ok()).flatten())
            .collect();
        // The cache and the importer check programs; one that still cannot be read leaves
        // the whole table to the interpreter, which bounds its walk.
        let unreadable = materials.iter().zip(&shapes).any(|(m, s)| !m.node_program.is_empty() && s.is_none());
        let mut by_shape: BTreeMap<&Vec<u32>, &Vec<u32>> = BTreeMap::new();
        if !unreadable {
            for (m, s) in materials.iter().zip(&shapes) {
                if let Some(s) = s {
                    by_shape.entry(s).or_insert(&m.node_program);
                }
            }
        }
        let numbers: BTreeMap<&Vec<u32>, u32> = by_shape.keys().copied().zip(0..).collect();
        let count: usize = by_shape.values().map(|p| instructions(p).map_or(0, |i| i.len())).sum();
        let specialised =
            !by_shape.is_empty() && by_shape.len() <= MAX_SPECIALISED_SHAPES && count <= MAX_SPECIALISED_INSTRUCTIONS;
        if !by_shape.is_empty() {
            let how = if specialised { "specialised" } else { "interpreted" };
            log::debug!("node programs: {} shapes, {count} instructions: {how}", by_shape.len());
        }
        let mut table = NodeTable::default();
        for (m, s) in materials.iter().zip(&shapes) {
            if m.node_program.is_empty() {
                table.starts.push(None);
                continue;
            }
            table.words.push(s.as_ref().and_then(|s| numbers.get(s).copied()).unwrap_or(u32::MAX));
            table.starts.push(Some(table.words.len() as u32));
            table.words.extend(&m.node_program);
        }
        if specialised {
            let mut hasher = blake3::Hasher::new();
            for s in by_shape.keys() {
                hasher.update(bytemuck::cast_slice(s));
                hasher.update(&[0xff; 4]);
            }
            let bytes = hasher.finalize();
            table.key = u64::from_le_bytes(bytes.as_bytes()[..8].try_into().unwrap_or_default()).max(1);
            table.shapes = by_shape.into_values().cloned().collect();
        }
        table
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::asset::node_graph::CONSTANT;
    use crate::asset::node_kinds::{NODE_OP_END, NODE_OP_MATH, NODE_OP_OUTPUT};

    // Math operation `mode` of constants 0 and 1 into the roughness.
    fn math(mode: u32, value: f32) -> Material {
        let mut p = vec![
            0,
            NODE_OP_MATH | mode << 8,
            0,
            2,
            CONSTANT,
            CONSTANT | 1,
            0,
            NODE_OP_OUTPUT | 1 << 8,
            0,
            1,
            0,
            0,
            NODE_OP_END,
        ];
        p[0] = p.len() as u32;
        p.extend([value, 0.0, 0.0, 0.0, 0.5, 0.0, 0.0, 0.0].map(f32::to_bits));
        Material { node_program: p, ..Material::default() }
    }

    #[test]
    fn programs_of_one_shape_share_its_code_and_each_follows_its_number() {
        let materials = [Material::default(), math(2, 0.1), math(2, 0.7), math(3, 0.1)];
        let table = NodeTable::of(&materials);
        assert_eq!(table.shapes.len(), 2, "two shapes: the values do not count");
        assert_ne!(table.key, 0);
        assert_eq!(table.starts[0], None);
        for (m, start) in materials.iter().zip(&table.starts).skip(1) {
            let start = start.expect("a program") as usize;
            assert_eq!(&table.words[start..start + m.node_program.len()], m.node_program.as_slice());
            let number = table.words[start - 1] as usize;
            assert_eq!(shape(&table.shapes[number]), shape(&m.node_program));
        }
        assert_eq!(
            table.words[table.starts[1].unwrap() as usize - 1],
            table.words[table.starts[2].unwrap() as usize - 1]
        );
        // The key names the shapes, not the values.
        assert_eq!(NodeTable::of(&[math(3, 0.9), math(2, 0.2)]).key, table.key);
        assert_ne!(NodeTable::of(&[math(3, 0.9)]).key, table.key);
    }

    #[test]
    fn too_many_shapes_are_interpreted() {
        let many: Vec<Material> = (0..=MAX_SPECIALISED_SHAPES as u32).map(|mode| math(mode, 0.5)).collect();
        let table = NodeTable::of(&many);
        assert_eq!((table.key, table.shapes.len()), (0, 0));
        assert_eq!(table.starts.iter().flatten().count(), many.len(), "the programs are still in the table");
        let fewer = NodeTable::of(&many[1..]);
        assert_ne!(fewer.key, 0);
        assert_eq!(NodeTable::of(&[Material::default()]).key, 0);
    }
}
