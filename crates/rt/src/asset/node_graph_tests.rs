//! Tests of the node graph compiler (src/asset/node_graph.rs).

use super::*;
use serde_json::json;

fn graph(nodes: Value, outputs: Value) -> Value {
    json!({ "version": 1, "nodes": nodes, "outputs": outputs })
}

#[test]
fn a_noise_into_the_base_colour_compiles_to_coordinate_noise_output() {
    let g = graph(
        json!([
            { "name": "Texture Coordinate", "type": "TEX_COORD" },
            { "name": "Noise", "type": "TEX_NOISE", "settings": { "noise_dimensions": "3D", "noise_type": "FBM", "normalize": true },
              "inputs": { "Vector": { "link": [0, "Object"], "from": "VECTOR", "to": "VECTOR" }, "Scale": { "value": 5.0 } } }
        ]),
        json!({ "base_color": { "link": [1, "Color"], "from": "RGBA", "to": "RGBA" } }),
    );
    let program = compile_json(&g).unwrap();
    let ops: Vec<u32> = instructions(&program).iter().map(|w| w & 0xff).collect();
    assert_eq!(ops, [node_kinds::NODE_OP_COORDINATE, node_kinds::NODE_OP_NOISE, node_kinds::NODE_OP_OUTPUT]);
    assert_eq!(program[program[0] as usize - 1], node_kinds::NODE_OP_END);
}

/// The first word of each instruction.
fn instructions(program: &[u32]) -> Vec<u32> {
    let mut at = 1;
    let mut out = Vec::new();
    while program[at] != node_kinds::NODE_OP_END {
        out.push(program[at]);
        let operands = program[at + 2] as usize;
        let extra = program[at + 3 + operands] as usize;
        at += 4 + operands + extra;
    }
    out
}

#[test]
fn a_colour_read_as_a_value_is_converted() {
    let g = graph(
        json!([{ "name": "RGB", "type": "RGB", "settings": { "value": [0.2, 0.4, 0.6, 1.0] } }]),
        json!({ "roughness": { "link": [0, "Color"], "from": "RGBA", "to": "VALUE" } }),
    );
    let ops: Vec<u32> = instructions(&compile_json(&g).unwrap()).iter().map(|w| w & 0xff).collect();
    assert_eq!(ops, [node_kinds::NODE_OP_CONVERT, node_kinds::NODE_OP_OUTPUT]);
}

#[test]
fn errors_name_the_node_and_what_is_wrong() {
    let cycle = graph(
        json!([{ "name": "Loop", "type": "MATH", "settings": { "operation": "ADD" },
                 "inputs": { "Value": { "link": [0, "Value"], "from": "VALUE", "to": "VALUE" } } }]),
        json!({ "roughness": { "link": [0, "Value"], "from": "VALUE", "to": "VALUE" } }),
    );
    let e = compile_json(&cycle).unwrap_err();
    assert!(e.contains("node `Loop` (MATH)") && e.contains("cycle"), "{e}");
    let unknown = graph(
        json!([{ "name": "Sky", "type": "TEX_SKY" }]),
        json!({ "base_color": { "link": [0, "Color"], "from": "RGBA", "to": "RGBA" } }),
    );
    let e = compile_json(&unknown).unwrap_err();
    assert!(e.contains("`Sky` (TEX_SKY)") && e.contains("does not evaluate"), "{e}");
    let operation = graph(
        json!([{ "name": "M", "type": "MATH", "settings": { "operation": "NOPE" } }]),
        json!({ "metallic": { "link": [0, "Value"], "from": "VALUE", "to": "VALUE" } }),
    );
    let e = compile_json(&operation).unwrap_err();
    assert!(e.contains("operation `NOPE`"), "{e}");
    let newer = json!({ "version": 2, "nodes": [], "outputs": {} });
    assert!(compile_json(&newer).unwrap_err().contains("format version 2"));
    let missing = graph(json!([]), json!({ "roughness": { "link": [3, "Value"], "from": "VALUE", "to": "VALUE" } }));
    assert!(compile_json(&missing).unwrap_err().contains("node 3"));
}

/// Registers are reused: a value's register is free once its last reader has run, so a
/// chain of 200 maths fits; 40 values that all stay to be read again do not.
#[test]
fn registers_are_reused_and_a_graph_too_wide_for_them_is_refused() {
    let math = |i: usize, inputs: Value| json!({ "name": format!("M{i}"), "type": "MATH", "settings": { "operation": "ADD" }, "inputs": inputs });
    let link = |i: usize| json!({ "link": [i, "Value"], "from": "VALUE", "to": "VALUE" });
    let mut chain = vec![math(0, json!({}))];
    chain.extend((1..200).map(|i| math(i, json!({ "Value": link(i - 1) }))));
    let program = compile_json(&graph(Value::Array(chain), json!({ "roughness": link(199) }))).unwrap();
    check_program(&program).unwrap();
    assert_eq!(instructions(&program).len(), 201);

    // 40 leaves summed by one chain: each leaf is free once added.
    let mut wide: Vec<Value> = (0..40).map(|i| math(i, json!({ "Value": { "value": i as f32 } }))).collect();
    wide.push(math(40, json!({ "Value": link(0), "Value_001": link(1) })));
    wide.extend((41..79).map(|i| math(i, json!({ "Value": link(i - 1), "Value_001": link(i - 39) }))));
    check_program(&compile_json(&graph(Value::Array(wide.clone()), json!({ "roughness": link(78) }))).unwrap())
        .unwrap();
    // Summed again by a second chain after the first: all 40 are live at once.
    wide.push(math(79, json!({ "Value": link(78), "Value_001": link(0) })));
    wide.extend((80..119).map(|i| math(i, json!({ "Value": link(i - 1), "Value_001": link(i - 79) }))));
    let e = compile_json(&graph(Value::Array(wide), json!({ "roughness": link(118) }))).unwrap_err();
    assert!(e.contains("registers"), "{e}");
}

/// A Bump reads its Height at the point and a step along each axis: the nodes that depend on
/// where the point is are compiled three times (the steps' coordinates reading the filter
/// width), a constant scale once; a Bump in another's Height and a linked Filter Width are refused.
#[test]
fn a_bump_compiles_its_height_at_the_point_and_two_steps() {
    let link = |i: usize, output: &str, from: &str, to: &str| json!({ "link": [i, output], "from": from, "to": to });
    let nodes = json!([
        { "name": "Texture Coordinate", "type": "TEX_COORD" },
        { "name": "Scale", "type": "VALUE", "settings": { "value": 4.0 } },
        { "name": "Noise", "type": "TEX_NOISE", "settings": { "noise_dimensions": "3D", "noise_type": "FBM", "normalize": true },
          "inputs": { "Vector": link(0, "Object", "VECTOR", "VECTOR"), "Scale": link(1, "Value", "VALUE", "VALUE") } },
        { "name": "Bump", "type": "BUMP", "settings": { "invert": true },
          "inputs": { "Strength": { "value": 0.5 }, "Distance": { "value": 0.2 }, "Filter Width": { "value": 0.1 },
                      "Height": link(2, "Fac", "VALUE", "VALUE") } }
    ]);
    let program =
        compile_json(&graph(nodes.clone(), json!({ "normal": link(3, "Normal", "VECTOR", "VECTOR") }))).unwrap();
    check_program(&program).unwrap();
    let read = super::super::node_program::instructions(&program).unwrap();
    let ops: Vec<(u32, u32)> = read.iter().map(|i| (i.op(), i.word >> 24)).collect();
    use node_kinds::{NODE_OP_BUMP as B, NODE_OP_COORDINATE as C, NODE_OP_NOISE as N, NODE_OP_OUTPUT as O};
    assert_eq!(ops, [(C, 0), (N, 1), (C, 1), (N, 1), (C, 2), (N, 1), (B, 1), (O, 0)]);
    let width = read[6].operands[2];
    assert_eq!((read[2].operands.clone(), read[4].operands.clone()), (vec![width], vec![width]));
    assert!(super::super::node_program::drives(&program, "normal"));

    let mut nested = nodes.as_array().unwrap().clone();
    nested
        .push(json!({ "name": "Outer", "type": "BUMP", "inputs": { "Height": link(3, "Normal", "VECTOR", "VALUE") } }));
    let e = compile_json(&graph(Value::Array(nested), json!({ "normal": link(4, "Normal", "VECTOR", "VECTOR") })))
        .unwrap_err();
    assert!(e.contains("`Bump` (BUMP)") && e.contains("another Bump's Height"), "{e}");
    let mut linked = nodes.as_array().unwrap().clone();
    linked[3]["inputs"]["Filter Width"] = link(1, "Value", "VALUE", "VALUE");
    let e = compile_json(&graph(Value::Array(linked), json!({ "normal": link(3, "Normal", "VECTOR", "VECTOR") })))
        .unwrap_err();
    assert!(e.contains("Filter Width is linked"), "{e}");
}

/// An attribute the mesh has is read by number, its kind in the mode; one it lacks is what
/// Cycles reads then (an Attribute's Alpha 1, a Color Attribute's 0); a number no mesh can
/// carry is refused.
#[test]
fn attributes_are_read_by_number_or_folded_when_missing() {
    let read = |settings: Value, kind: &str, output: &str| {
        compile_json(&graph(
            json!([{ "name": "Attr", "type": kind, "settings": settings }]),
            json!({ "roughness": { "link": [0, output], "from": "VALUE", "to": "VALUE" } }),
        ))
    };
    let program = read(json!({ "slot": 3, "data": "FLOAT4" }), "ATTRIBUTE", "Alpha").unwrap();
    assert_eq!(instructions(&program)[0], node_kinds::NODE_OP_ATTRIBUTE | (2 | 3 << 2) << 8);
    assert_eq!(super::super::node_program::attributes_read(&program), [3]);

    for (kind, alpha) in [("ATTRIBUTE", 1.0f32), ("VERTEX_COLOR", 0.0)] {
        let program = read(json!({ "slot": null, "data": "FLOAT" }), kind, "Alpha").unwrap();
        let ops: Vec<u32> = instructions(&program).iter().map(|w| w & 0xff).collect();
        assert_eq!(ops, [node_kinds::NODE_OP_OUTPUT], "{kind}");
        assert_eq!(f32::from_bits(program[program[0] as usize]), alpha, "{kind}");
    }
    let e = read(json!({ "slot": 40, "data": "FLOAT" }), "ATTRIBUTE", "Fac").unwrap_err();
    assert!(e.contains("node `Attr` (ATTRIBUTE)") && e.contains("attribute number 40"), "{e}");
    let e = read(json!({ "slot": 0, "data": "MATRIX" }), "ATTRIBUTE", "Fac").unwrap_err();
    assert!(e.contains("data `MATRIX`"), "{e}");
}
