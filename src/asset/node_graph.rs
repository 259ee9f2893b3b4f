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
//! An operand is a register, or `CONSTANT | i`: the program's i-th constant.

use super::node_kinds::{self, Emit, Kind};
use serde::Deserialize;
use serde_json::{Map, Value};
use std::collections::{BTreeMap, HashMap};

pub const FORMAT_VERSION: u32 = 1;
/// The compiler's own version: caches of programs an earlier compiler wrote are rebuilt.
pub const COMPILER_VERSION: u32 = 3;
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
    let mut c = Compiler {
        graph,
        code: vec![0],
        constants: Vec::new(),
        busy: [false; REGISTERS as usize],
        remaining: HashMap::new(),
        uses: uses(graph),
        done: HashMap::new(),
        open: Vec::new(),
    };
    for (target, input) in &graph.outputs {
        let Some(mode) = node_kinds::TARGETS.iter().position(|t| t == target) else {
            return Err(format!(
                "rt_node_graph drives `{target}`, which is none of {}",
                node_kinds::TARGETS.join(", ")
            ));
        };
        let operand = c.operand(input)?;
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
    /// How many links read each (node, output), over the nodes the outputs reach.
    uses: HashMap<(usize, String), u32>,
    /// The operand of each (node, output) already compiled.
    done: HashMap<(usize, String), u32>,
    /// The nodes being compiled, to find cycles.
    open: Vec<usize>,
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

    fn operand(&mut self, input: &Input) -> Result<u32, String> {
        match input {
            Input::Value { value } => Ok(self.constant(value.vec4()?)),
            Input::Link { link: (node, output), from, to } => {
                let source = self.output(*node, output)?;
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

    /// The operand holding output `output` of node `index`, compiling the node first.
    fn output(&mut self, index: usize, output: &str) -> Result<u32, String> {
        if let Some(&operand) = self.done.get(&(index, output.to_owned())) {
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
        let compiled = self.node(index, node, kind, position).map_err(located);
        self.open.pop();
        let operand = compiled?;
        self.done.insert((index, output.to_owned()), operand);
        Ok(operand)
    }

    fn node(&mut self, index: usize, node: &GraphNode, kind: &Kind, output: usize) -> Result<u32, String> {
        match kind.emit {
            Emit::Constant => {
                let value = node.settings.get("value").ok_or("its value is missing")?;
                let numbers: Numbers = serde_json::from_value(value.clone()).map_err(|e| e.to_string())?;
                Ok(self.constant(numbers.vec4()?))
            }
            Emit::Coordinates(first) => {
                let out = self.allocate(1)?;
                let extra = if first + output as u32 == 0 { self.texture_space() } else { Vec::new() };
                self.instruction(node_kinds::NODE_OP_COORDINATE, first + output as u32, 0, out, &[], &extra);
                let reads = self.reads(index, kind.outputs[output]);
                self.hold(out, reads);
                Ok(out)
            }
            Emit::Operation(op) => {
                if let Some(unknown) = node.inputs.keys().find(|k| !kind.inputs.contains(&k.as_str())) {
                    return Err(format!("it has no input `{unknown}` that rt reads"));
                }
                let mut operands = Vec::with_capacity(kind.inputs.len());
                for key in kind.inputs {
                    operands.push(match node.inputs.get(*key) {
                        Some(input) => self.operand(input)?,
                        // Inputs the exporter leaves out read 0 (the shader takes a zero
                        // normal for the shading point's own).
                        None => self.constant([0.0; 4]),
                    });
                }
                let mode = node_kinds::mode(&node.kind, &node.settings)?;
                let extra = match op {
                    node_kinds::NODE_OP_RAMP => ramp_table(&node.settings)?,
                    node_kinds::NODE_OP_CURVES => curve_table(&node.settings)?,
                    node_kinds::NODE_OP_BRICK => brick_amounts(&node.settings)?,
                    _ => Vec::new(),
                };
                let out = self.allocate(kind.outputs.len() as u32)?;
                self.instruction(op, mode.mode, mode.flags, out, &operands, &extra);
                for (i, name) in kind.outputs.iter().enumerate() {
                    self.done.insert((index, (*name).to_owned()), out + i as u32);
                    let reads = self.reads(index, name);
                    self.hold(out + i as u32, reads);
                }
                Ok(out + output as u32)
            }
        }
    }

    fn reads(&self, node: usize, output: &str) -> u32 {
        self.uses.get(&(node, output.to_owned())).copied().unwrap_or(0)
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

/// How many links read each (node, output), counting only the nodes that the graph's
/// outputs reach (a node nothing reads is never compiled, so its reads never come).
fn uses(graph: &NodeGraph) -> HashMap<(usize, String), u32> {
    let mut uses: HashMap<(usize, String), u32> = HashMap::new();
    let mut seen = vec![false; graph.nodes.len()];
    let mut stack: Vec<&Input> = graph.outputs.values().collect();
    while let Some(input) = stack.pop() {
        let Input::Link { link: (node, output), .. } = input else { continue };
        *uses.entry((*node, output.clone())).or_default() += 1;
        if let Some(n) = graph.nodes.get(*node).filter(|_| !seen[*node]) {
            seen[*node] = true;
            stack.extend(n.inputs.values());
        }
    }
    uses
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
mod tests {
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
        let missing =
            graph(json!([]), json!({ "roughness": { "link": [3, "Value"], "from": "VALUE", "to": "VALUE" } }));
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
}
