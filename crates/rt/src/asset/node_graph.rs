//! A material's shader node graph as the exporter writes it (`extras.rt_node_graph` of a
//! glTF material, format version 1, documented in `docs/shader-nodes.md`), and its
//! compilation into a node program: the words `shaders/node_program.wgsl` interprets at
//! every shading point. A program is
//!
//! ```text
//! word 0        where the constants start, from the program's first word
//! instructions  [op | mode << 8 | flags << 24, output register, n, n operands, e, e extra words]
//! NODE_OP_END
//! constants     vec4s, read by operands with CONSTANT set
//! ```
//!
//! An operand is a register, or `CONSTANT | i`: the program's i-th constant. A coordinate
//! instruction with flags 1 or 2 reads the point a step along the surface's x or y axis, its
//! one operand the Bump's Filter Width (`node_shift`).

use super::node_kinds::{self, Emit, Kind};
use super::node_shift::{self, Shift};
use serde::Deserialize;
use serde_json::{Map, Value};
use std::collections::{BTreeMap, HashMap};

pub const FORMAT_VERSION: u32 = 1;
/// The compiler's own version: caches of programs an earlier compiler wrote are rebuilt.
pub const COMPILER_VERSION: u32 = 7;
/// An operand that reads a constant, not a register.
pub const CONSTANT: u32 = 0x8000_0000;
/// Registers of the interpreter (`NODE_REGISTERS` in the shader).
pub const REGISTERS: u32 = 32;
/// Operands an instruction may have (`NODE_MAX_OPERANDS` in the shader).
pub const MAX_OPERANDS: u32 = 10;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NodeGraph {
    pub version: u32,
    pub nodes: Vec<GraphNode>,
    /// Material inputs (`node_kinds::TARGETS`) and what drives them.
    pub outputs: BTreeMap<String, Input>,
    /// The mesh's texture space (Blender's `texspace_location` and `_size`), for Generated.
    #[serde(default)]
    pub texture_space: Option<TextureSpace>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TextureSpace {
    pub location: [f32; 3],
    pub size: [f32; 3],
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GraphNode {
    pub name: String,
    #[serde(rename = "type")]
    pub kind: String,
    #[serde(default)]
    pub settings: Map<String, Value>,
    #[serde(default)]
    pub inputs: BTreeMap<String, Input>,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
pub enum SocketType {
    #[serde(rename = "VALUE")]
    Value,
    #[serde(rename = "VECTOR")]
    Vector,
    #[serde(rename = "RGBA")]
    Color,
}

/// An input: its own value (a number or up to four), or a link from a node's output,
/// with the types at both ends (a colour or vector read as a value is converted).
#[derive(Debug, Deserialize)]
#[serde(untagged, deny_unknown_fields)]
pub enum Input {
    Value { value: Numbers },
    Link { link: (usize, String), from: SocketType, to: SocketType },
}

#[derive(Debug, Deserialize)]
#[serde(untagged)]
pub enum Numbers {
    One(f32),
    Many(Vec<f32>),
}

impl Numbers {
    /// As a register holds it: a value in every component, a vector's w 0, a colour's alpha kept.
    fn vec4(&self) -> Result<[f32; 4], String> {
        match self {
            Numbers::One(v) => Ok([*v; 4]),
            Numbers::Many(v) if (3..=4).contains(&v.len()) => Ok([v[0], v[1], v[2], v.get(3).copied().unwrap_or(0.0)]),
            Numbers::Many(v) => Err(format!("a value of {} numbers (rt reads 1, 3 or 4)", v.len())),
        }
    }
}

/// Parses and compiles `json`, the `rt_node_graph` of a material; errors name the node.
pub fn compile_json(json: &Value) -> Result<Vec<u32>, String> {
    let graph: NodeGraph = serde_json::from_value(json.clone()).map_err(|e| format!("rt_node_graph: {e}"))?;
    if graph.version != FORMAT_VERSION {
        return Err(format!(
            "rt_node_graph is of format version {} (this rt reads version {FORMAT_VERSION}); export the scene again",
            graph.version
        ));
    }
    compile(&graph)
}

pub fn compile(graph: &NodeGraph) -> Result<Vec<u32>, String> {
    let positional = node_shift::positional(graph);
    let mut c = Compiler {
        graph,
        code: vec![0],
        constants: Vec::new(),
        busy: [false; REGISTERS as usize],
        remaining: HashMap::new(),
        uses: node_shift::uses(graph, &positional),
        positional,
        done: HashMap::new(),
        open: Vec::new(),
        filter_widths: HashMap::new(),
    };
    for (target, input) in &graph.outputs {
        let Some(mode) = node_kinds::TARGETS.iter().position(|t| t == target) else {
            return Err(format!(
                "rt_node_graph drives `{target}`, which is none of {}",
                node_kinds::TARGETS.join(", ")
            ));
        };
        let operand = c.operand(input, Shift::At)?;
        c.instruction(node_kinds::NODE_OP_OUTPUT, mode as u32, 0, 0, &[operand], &[]);
    }
    c.code.push(node_kinds::NODE_OP_END);
    c.code[0] = c.code.len() as u32;
    c.code.extend(c.constants.iter().map(|v| v.to_bits()));
    Ok(c.code)
}

struct Compiler<'g> {
    graph: &'g NodeGraph,
    code: Vec<u32>,
    constants: Vec<f32>,
    /// Registers holding a value some instruction still reads.
    busy: [bool; REGISTERS as usize],
    /// Reads left of each busy register: it is free again after its last.
    remaining: HashMap<u32, u32>,
    /// How many links read each (node, output, shift), over the nodes the outputs reach.
    uses: HashMap<(usize, String, Shift), u32>,
    /// Whether each node's value depends on where the point is (`node_shift::positional`).
    positional: Vec<bool>,
    /// The operand of each (node, output, shift) already compiled.
    done: HashMap<(usize, String, Shift), u32>,
    /// The nodes being compiled, to find cycles.
    open: Vec<usize>,
    /// Each Bump's Filter Width, the constant its steps' coordinates read.
    filter_widths: HashMap<usize, u32>,
}

impl Compiler<'_> {
    fn constant(&mut self, v: [f32; 4]) -> u32 {
        let index = self.constants.len() as u32 / 4;
        self.constants.extend_from_slice(&v);
        CONSTANT | index
    }

    /// Emits an instruction; the registers it reads for the last time are free after it
    /// (never before: its outputs, allocated already, do not overwrite its operands).
    fn instruction(&mut self, op: u32, mode: u32, flags: u32, out: u32, operands: &[u32], extra: &[u32]) {
        self.code.push(op | mode << 8 | flags << 24);
        self.code.push(out);
        self.code.push(operands.len() as u32);
        self.code.extend_from_slice(operands);
        self.code.push(extra.len() as u32);
        self.code.extend_from_slice(extra);
        for &register in operands.iter().filter(|&&o| o & CONSTANT == 0) {
            if let Some(left) = self.remaining.get_mut(&register) {
                *left = left.saturating_sub(1);
                if *left == 0 {
                    self.busy[register as usize] = false;
                }
            }
        }
    }

    /// `count` consecutive free registers.
    fn allocate(&mut self, count: u32) -> Result<u32, String> {
        let count = count as usize;
        let first = (0..=self.busy.len().saturating_sub(count))
            .find(|&f| self.busy[f..f + count].iter().all(|b| !b))
            .ok_or(format!("the graph needs more than the {REGISTERS} registers rt evaluates it with"))?;
        self.busy[first..first + count].fill(true);
        Ok(first as u32)
    }

    /// `register` holds a value read `reads` times from now on (none: free at once).
    fn hold(&mut self, register: u32, reads: u32) {
        self.remaining.insert(register, reads);
        self.busy[register as usize] = reads > 0;
    }

    fn operand(&mut self, input: &Input, shift: Shift) -> Result<u32, String> {
        match input {
            Input::Value { value } => Ok(self.constant(value.vec4()?)),
            Input::Link { link: (node, output), from, to } => {
                let source = self.output(*node, output, shift)?;
                let convert = match (from, to) {
                    (SocketType::Color, SocketType::Value) => node_kinds::CONVERT_COLOR_TO_VALUE,
                    (SocketType::Vector, SocketType::Value) => node_kinds::CONVERT_VECTOR_TO_VALUE,
                    _ => return Ok(source),
                };
                let out = self.allocate(1)?;
                self.instruction(node_kinds::NODE_OP_CONVERT, convert, 0, out, &[source], &[]);
                self.hold(out, 1);
                Ok(out)
            }
        }
    }

    /// The operand holding output `output` of node `index` computed at `shift` (at the
    /// point, for a node that does not depend on where it is), compiling the node first.
    fn output(&mut self, index: usize, output: &str, shift: Shift) -> Result<u32, String> {
        let shift = node_shift::effective(&self.positional, index, shift);
        if let Some(&operand) = self.done.get(&(index, output.to_owned(), shift)) {
            return Ok(operand);
        }
        let graph = self.graph;
        let node = graph.nodes.get(index).ok_or_else(|| format!("a link from node {index}, which the graph lacks"))?;
        let located = |e: String| format!("node `{}` ({}): {e}", node.name, node.kind);
        if self.open.contains(&index) {
            return Err(located("it feeds itself (a cycle)".into()));
        }
        let kind = node_kinds::kind(&node.kind).ok_or_else(|| located("rt does not evaluate this node type".into()))?;
        let position = kind.outputs.iter().position(|o| *o == output);
        let position = position.ok_or_else(|| located(format!("it has no output `{output}` that rt evaluates")))?;
        self.open.push(index);
        let compiled = self.node(index, node, kind, position, shift).map_err(located);
        self.open.pop();
        let operand = compiled?;
        self.done.insert((index, output.to_owned(), shift), operand);
        Ok(operand)
    }

    fn node(
        &mut self,
        index: usize,
        node: &GraphNode,
        kind: &Kind,
        output: usize,
        shift: Shift,
    ) -> Result<u32, String> {
        match kind.emit {
            Emit::Constant => {
                let value = node.settings.get("value").ok_or("its value is missing")?;
                let numbers: Numbers = serde_json::from_value(value.clone()).map_err(|e| e.to_string())?;
                Ok(self.constant(numbers.vec4()?))
            }
            Emit::Coordinates(first) => {
                let extra = if first + output as u32 == 0 { self.texture_space() } else { Vec::new() };
                let (op, mode) = (node_kinds::NODE_OP_COORDINATE, first + output as u32);
                self.positional(index, kind.outputs[output], shift, (op, mode), &extra)
            }
            Emit::Attribute => self.attribute(index, node, kind.outputs[output], shift),
            Emit::Bump => self.bump(index, node, kind, shift),
            Emit::Operation(op) => {
                known_inputs(node, kind)?;
                let mut operands = Vec::with_capacity(kind.inputs.len());
                for key in kind.inputs {
                    operands.push(match node.inputs.get(*key) {
                        Some(input) => self.operand(input, shift)?,
                        // Inputs the exporter leaves out read 0 (the shader takes a zero
                        // normal for the shading point's own).
                        None => self.constant([0.0; 4]),
                    });
                }
                let mode = node_kinds::mode(&node.kind, &node.settings)?;
                let op = node_kinds::operation(&node.kind, op, &node.settings)?;
                let extra = match op {
                    node_kinds::NODE_OP_RAMP => ramp_table(&node.settings)?,
                    node_kinds::NODE_OP_CURVES => curve_table(&node.settings)?,
                    node_kinds::NODE_OP_BRICK => brick_amounts(&node.settings)?,
                    _ => Vec::new(),
                };
                let out = self.allocate(kind.outputs.len() as u32)?;
                self.instruction(op, mode.mode, mode.flags, out, &operands, &extra);
                for (i, name) in kind.outputs.iter().enumerate() {
                    self.done.insert((index, (*name).to_owned(), shift), out + i as u32);
                    let reads = self.reads(index, name, shift);
                    self.hold(out + i as u32, reads);
                }
                Ok(out + output as u32)
            }
        }
    }

    /// An instruction `(op, mode)` that reads the point (or, a step away, the point its
    /// Bump's Filter Width steps to, its one operand) into a register of its own.
    fn positional(
        &mut self,
        index: usize,
        output: &str,
        shift: Shift,
        code: (u32, u32),
        extra: &[u32],
    ) -> Result<u32, String> {
        let out = self.allocate(1)?;
        let width = match shift {
            Shift::At => Vec::new(),
            Shift::Along { bump, .. } => vec![self.filter_widths[&bump]],
        };
        self.instruction(code.0, code.1, shift.flags(), out, &width, extra);
        let reads = self.reads(index, output, shift);
        self.hold(out, reads);
        Ok(out)
    }

    /// Attribute and Color Attribute (Cycles' `svm_node_attr`, `svm_node_vertex_color`):
    /// the mesh's attribute number `slot`; where the mesh has no attribute of that name
    /// (no `slot`), what Cycles reads then: zeros, and an Attribute node's Alpha 1.
    fn attribute(&mut self, index: usize, node: &GraphNode, output: &str, shift: Shift) -> Result<u32, String> {
        let Some(slot) = node.settings.get("slot").filter(|s| !s.is_null()) else {
            let alpha = output == "Alpha" && node.kind == "ATTRIBUTE";
            return Ok(self.constant([if alpha { 1.0 } else { 0.0 }; 4]));
        };
        let slot = slot
            .as_u64()
            .filter(|&s| s < crate::asset::rtmesh::MAX_ATTRIBUTES as u64)
            .ok_or_else(|| format!("its attribute number {slot} is not one a mesh can carry"))?;
        let mode = node_kinds::attribute_mode(output, &node.settings)?;
        self.positional(index, output, shift, (node_kinds::NODE_OP_ATTRIBUTE, mode), &[slot as u32])
    }

    /// Bump (Cycles' `svm_node_set_bump`): its Height at the point and a step along each of
    /// the surface's two axes, the steps Filter Width times the point's footprint; operands
    /// Strength, Distance, Filter Width, the three heights, Normal.
    fn bump(&mut self, index: usize, node: &GraphNode, kind: &Kind, shift: Shift) -> Result<u32, String> {
        if shift != Shift::At {
            return Err("it feeds another Bump's Height, which rt does not evaluate".into());
        }
        known_inputs(node, kind)?;
        let width = match node.inputs.get("Filter Width") {
            Some(Input::Value { value }) => value.vec4()?,
            Some(Input::Link { .. }) => return Err("its Filter Width is linked; rt reads a constant one".into()),
            None => [0.1; 4],
        };
        let width = self.constant(width);
        self.filter_widths.insert(index, width);
        let read = |c: &mut Self, key: &str, at: Shift, default: f32| match node.inputs.get(key) {
            Some(input) => c.operand(input, at),
            None => Ok(c.constant([default; 4])),
        };
        let strength = read(self, "Strength", Shift::At, 1.0)?;
        let distance = read(self, "Distance", Shift::At, 1.0)?;
        let centre = read(self, "Height", Shift::At, 1.0)?;
        let x = read(self, "Height", Shift::Along { bump: index, axis: 1 }, 1.0)?;
        let y = read(self, "Height", Shift::Along { bump: index, axis: 2 }, 1.0)?;
        // No Normal: the zero vector, which the shader reads as the point's own.
        let normal = read(self, "Normal", Shift::At, 0.0)?;
        let mode = node_kinds::mode(&node.kind, &node.settings)?;
        let out = self.allocate(1)?;
        let operands = [strength, distance, width, centre, x, y, normal];
        self.instruction(node_kinds::NODE_OP_BUMP, mode.mode, mode.flags, out, &operands, &[]);
        let reads = self.reads(index, "Normal", Shift::At);
        self.hold(out, reads);
        Ok(out)
    }

    fn reads(&self, node: usize, output: &str, shift: Shift) -> u32 {
        self.uses.get(&(node, output.to_owned(), shift)).copied().unwrap_or(0)
    }

    /// Generated = (P − location) / (2 size) + ½ per axis, as Cycles maps a mesh's texture space.
    fn texture_space(&self) -> Vec<u32> {
        let (location, size) = match &self.graph.texture_space {
            Some(t) => (t.location, t.size),
            None => ([0.0; 3], [1.0; 3]),
        };
        let scale = size.map(|s| if s != 0.0 { 0.5 / s } else { 0.0 });
        let offset = [0, 1, 2].map(|i| 0.5 - location[i] * scale[i]);
        scale.iter().chain(offset.iter()).map(|v| v.to_bits()).collect()
    }
}

/// Refuses an input of `node` that its kind does not read.
fn known_inputs(node: &GraphNode, kind: &Kind) -> Result<(), String> {
    match node.inputs.keys().find(|k| !kind.inputs.contains(&k.as_str())) {
        Some(unknown) => Err(format!("it has no input `{unknown}` that rt reads")),
        None => Ok(()),
    }
}

/// Checks that `program` is one the shader can walk ([`super::node_program::instructions`]).
pub fn check_program(program: &[u32]) -> Result<(), String> {
    super::node_program::instructions(program).map(|_| ())
}

/// A Brick Texture's offset and squash amounts, as floats' words.
fn brick_amounts(settings: &Map<String, Value>) -> Result<Vec<u32>, String> {
    let amount = |key: &str| match settings.get(key).and_then(Value::as_f64) {
        Some(a) if a.is_finite() => Ok((a as f32).to_bits()),
        _ => Err(format!("{key} is missing or not a number")),
    };
    Ok(vec![amount("offset")?, amount("squash")?])
}

/// A curve's range (`range`: the lowest and highest x of its points) and table of
/// `RAMP_TABLE_SIZE` RGB(A) entries across it, as Cycles bakes RGB, vector and float curves.
fn curve_table(settings: &Map<String, Value>) -> Result<Vec<u32>, String> {
    let range: [f32; 2] = settings
        .get("range")
        .map(|r| serde_json::from_value(r.clone()).map_err(|e| format!("its range: {e}")))
        .transpose()?
        .ok_or("its range is missing")?;
    let mut words = vec![range[0].to_bits(), range[1].to_bits()];
    words.extend(ramp_table(settings)?);
    Ok(words)
}

/// A colour ramp's table: `RAMP_TABLE_SIZE` RGBA entries, as the exporter evaluates Blender's ramp.
fn ramp_table(settings: &Map<String, Value>) -> Result<Vec<u32>, String> {
    let table: Vec<[f32; 4]> = settings
        .get("table")
        .map(|t| serde_json::from_value(t.clone()).map_err(|e| format!("its table: {e}")))
        .transpose()?
        .ok_or("its table is missing")?;
    if table.len() != node_kinds::RAMP_TABLE_SIZE {
        return Err(format!("its table has {} entries, not {}", table.len(), node_kinds::RAMP_TABLE_SIZE));
    }
    Ok(table.iter().flatten().map(|v| v.to_bits()).collect())
}

#[cfg(test)]
#[path = "node_graph_tests.rs"]
mod tests;
