//! Unit tests of `node_kinds`: the operations' numbering and the exporter's node table.

use super::*;

/// The operations are numbered 0, 1, 2, … in order, each with its name.
#[test]
fn operations_are_numbered_in_order() {
    let all: Vec<(&str, u32)> = operations().collect();
    assert_eq!(all.len(), 33);
    assert!(all.iter().enumerate().all(|(i, (name, op))| *op == i as u32 && !name.is_empty()));
    assert_eq!(all[23], ("VORONOI", NODE_OP_VORONOI));
    assert_eq!(all[30], ("VORONOI_DIMENSIONS", NODE_OP_VORONOI_DIMENSIONS));
}

/// The exporter follows exactly the node types rt evaluates, with the same outputs.
#[test]
fn the_exporter_declares_the_same_nodes() {
    let python = include_str!("../../../../blender/rt_blender/rt_node_graph.py");
    for k in &KINDS {
        let outputs: Vec<String> = k.outputs.iter().map(|o| format!("\"{o}\"")).collect();
        let line = format!("\"{}\": ({}{}),", k.name, outputs.join(", "), if outputs.len() == 1 { "," } else { "" });
        assert!(python.contains(&line), "rt_node_graph.py's EVALUATED lacks `{line}`");
    }
    let declared = python.lines().skip_while(|l| !l.starts_with("EVALUATED = {")).skip(1);
    let count = declared.take_while(|l| !l.starts_with('}')).count();
    assert_eq!(count, KINDS.len());
}

/// The attribute kinds the exporter writes (`rt_attributes.DATA`) are the ones rt reads.
#[test]
fn the_exporter_writes_attribute_kinds_rt_reads() {
    let python = include_str!("../../../../blender/rt_blender/rt_attributes.py");
    let table = python.lines().skip_while(|l| !l.starts_with("DATA = {")).skip(1);
    let rows: Vec<&str> = table.take_while(|l| !l.starts_with('}')).collect();
    assert!(rows.len() >= 8, "rt_attributes.py's DATA");
    for row in rows {
        let kind = row.split('(').nth(1).and_then(|r| r.split('"').nth(1)).unwrap_or_default();
        assert!(super::ATTRIBUTE_DATA.contains(&kind), "{row}: `{kind}` is not one of {:?}", super::ATTRIBUTE_DATA);
    }
}
