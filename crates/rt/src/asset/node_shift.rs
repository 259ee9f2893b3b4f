//! Where a node graph is evaluated: at the shading point, or a small step away along the
//! surface, as a Bump node reads its Height (Cycles compiles the nodes that feed a Bump's
//! Height three times, `ShaderGraph::bump_from_displacement` and the `*_bump_dx/dy` SVM
//! nodes: at the point and shifted along the two axes of its footprint). A node whose value
//! does not depend on where the point is (a constant, Light Path, Object Info, maths of those)
//! is compiled once and shared by all three.

use super::node_graph::{Input, NodeGraph};
use super::node_kinds::{self, Emit};
use std::collections::{HashMap, HashSet};

/// The point a value is computed at.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Shift {
    /// The shading point.
    At,
    /// A step along the surface's axis `axis` (1 or 2: the coordinate instruction's flags)
    /// of the Bump node `bump`, whose Filter Width scales the step.
    Along { bump: usize, axis: u32 },
}

impl Shift {
    /// The coordinate instruction's flags for this shift.
    pub fn flags(self) -> u32 {
        match self {
            Shift::At => 0,
            Shift::Along { axis, .. } => axis,
        }
    }
}

/// For each node of `graph`, whether its value depends on where the point is: coordinates
/// (Texture Coordinate, Geometry), a Bump, and every node that reads one of those.
pub fn positional(graph: &NodeGraph) -> Vec<bool> {
    fn visit(graph: &NodeGraph, i: usize, memo: &mut Vec<Option<bool>>, open: &mut HashSet<usize>) -> bool {
        if let Some(known) = memo[i] {
            return known;
        }
        // A cycle is the compiler's error to report; here it reads as not positional.
        if !open.insert(i) {
            return false;
        }
        let node = &graph.nodes[i];
        let own = match node_kinds::kind(&node.kind).map(|k| &k.emit) {
            Some(Emit::Coordinates(_)) => matches!(node.kind.as_str(), "TEX_COORD" | "NEW_GEOMETRY" | "CAMERA"),
            Some(Emit::Bump | Emit::Attribute) => true,
            _ => false,
        };
        let read = node.inputs.values().any(|input| match input {
            Input::Link { link: (from, _), .. } if *from < graph.nodes.len() => visit(graph, *from, memo, open),
            _ => false,
        });
        open.remove(&i);
        memo[i] = Some(own || read);
        own || read
    }
    let mut memo = vec![None; graph.nodes.len()];
    let mut open = HashSet::new();
    (0..graph.nodes.len()).map(|i| visit(graph, i, &mut memo, &mut open)).collect()
}

/// The shift node `node` is computed at when a reader at `shift` reads it.
pub fn effective(positional: &[bool], node: usize, shift: Shift) -> Shift {
    if positional.get(node).copied().unwrap_or(false) { shift } else { Shift::At }
}

/// How many links read each (node, output, shift), over the nodes the graph's outputs
/// reach, each at the shifts it is computed at (a node nothing reads is never compiled,
/// so its reads never come). A Bump reads its Height at the point and at its two steps.
pub fn uses(graph: &NodeGraph, positional: &[bool]) -> HashMap<(usize, String, Shift), u32> {
    let mut uses: HashMap<(usize, String, Shift), u32> = HashMap::new();
    let mut seen = HashSet::new();
    let mut stack: Vec<(&Input, Shift)> = graph.outputs.values().map(|i| (i, Shift::At)).collect();
    while let Some((input, shift)) = stack.pop() {
        let Input::Link { link: (node, output), .. } = input else { continue };
        let at = effective(positional, *node, shift);
        *uses.entry((*node, output.clone(), at)).or_default() += 1;
        let Some(n) = graph.nodes.get(*node) else { continue };
        if !seen.insert((*node, at)) {
            continue;
        }
        let bump = n.kind == "BUMP";
        for (key, input) in &n.inputs {
            stack.push((input, at));
            if bump && key == "Height" {
                stack.extend([1, 2].map(|axis| (input, Shift::Along { bump: *node, axis })));
            }
        }
    }
    uses
}
