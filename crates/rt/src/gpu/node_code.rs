//! Node programs specialised: for each shape of the scene's node programs
//! (`bvh::node_table`), a WGSL function that runs its instructions one after another, each
//! written as a `NodeStep` of constants. With the operation and the registers known, the
//! shader compiler keeps only each operation's own code and holds the registers in
//! registers, where the interpreter (`run_node_program` in `shaders/node_program.wgsl`)
//! carries every operation's code and an array it indexes at run time. Values (constants,
//! ramp tables) are still read from the program table, so editing one needs no new
//! pipeline; a new shape does.

use crate::asset::node_graph::MAX_OPERANDS;
use crate::asset::node_kinds::operations;
use crate::asset::node_program::{Instruction, instructions};
use crate::bvh::SceneGeometry;
use std::fmt::Write;

/// The WGSL of `run_node_program` for the geometry's node shapes, or `None` when its
/// programs are interpreted.
pub fn of_geometry(geometry: &SceneGeometry) -> Option<String> {
    (geometry.node_code != 0).then(|| generate(&geometry.node_shapes))
}

/// The WGSL of `run_node_program` for `shapes` (one program of each, by shape number).
pub fn generate(shapes: &[Vec<u32>]) -> String {
    let mut code = String::from("// ---- node programs, specialised to the scene's shapes (rt)\n");
    code.push_str(
        "fn run_node_program(start: u32, p: NodePoint) -> NodeOutputs {\n    switch node_programs[start - 1u] {\n",
    );
    for number in 0..shapes.len() {
        let _ = writeln!(code, "        case {number}u: {{ return node_shape_{number}(start, p); }}");
    }
    code.push_str("        default: { return node_outputs_none(); }\n    }\n}\n");
    for (number, program) in shapes.iter().enumerate() {
        // The table's programs were read when it was made; one that cannot be is left out.
        let steps = instructions(program).unwrap_or_default();
        let _ = writeln!(code, "\nfn node_shape_{number}(start: u32, p: NodePoint) -> NodeOutputs {{");
        code.push_str("    var outputs = node_outputs_none();\n");
        for step in &steps {
            let _ = match operation_name(step.op()) {
                Some("OUTPUT") => writeln!(code, "    node_op_output(start, {}, &outputs);", node_step(step)),
                Some(name) => writeln!(code, "    node_op_{}(start, {}, p);", name.to_lowercase(), node_step(step)),
                None => Ok(()),
            };
        }
        code.push_str("    return outputs;\n}\n");
    }
    code
}

/// The name of operation `op` (`NODE_OP_NAME`, `node_op_name` in the shader).
fn operation_name(op: u32) -> Option<&'static str> {
    operations().find(|(_, o)| *o == op).map(|(name, _)| name)
}

/// `step` as a WGSL `NodeStep` of constants, its extra words found from the program's start.
fn node_step(step: &Instruction) -> String {
    let mut operands: Vec<String> = step.operands.iter().map(|o| format!("{o:#x}u")).collect();
    operands.resize(MAX_OPERANDS as usize, "0u".into());
    format!(
        "NodeStep({}u, {}u, {}u, {}u, start + {}u, array<u32, NODE_MAX_OPERANDS>({}))",
        step.op(),
        (step.word >> 8) & 0xffff,
        step.word >> 24,
        step.out,
        step.extra,
        operands.join(", ")
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::asset::node_kinds::KINDS;

    #[test]
    fn every_operation_fits_a_node_step() {
        let wgsl = include_str!("../../shaders/node_step.wgsl");
        assert!(wgsl.contains(&format!("const NODE_MAX_OPERANDS: u32 = {MAX_OPERANDS}u;")));
        for kind in KINDS {
            assert!(kind.inputs.len() <= MAX_OPERANDS as usize, "{} has {} inputs", kind.name, kind.inputs.len());
        }
    }

    #[test]
    fn every_operation_has_its_function() {
        let wgsl = include_str!("../../shaders/node_ops.wgsl");
        for (name, _) in operations().skip(2) {
            let head = format!("fn node_op_{}(start: u32, step: NodeStep, p: NodePoint)", name.to_lowercase());
            assert!(wgsl.contains(&head), "node_ops.wgsl lacks `{head}`");
        }
        assert!(wgsl.contains("fn node_op_output(start: u32, step: NodeStep, outputs: ptr<function, NodeOutputs>)"));
    }
}
