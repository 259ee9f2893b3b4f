//! A node program's words read back as instructions (the layout is in
//! [`super::node_graph`]'s header): to check a program before the GPU walks it, and to
//! find its shape — everything but its values — from which the shader is specialised.

use super::node_graph::{CONSTANT, MAX_OPERANDS, REGISTERS};
use super::node_kinds;

/// One instruction of a program, with where its words are, counted from the program's
/// first word.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Instruction {
    /// `op | mode << 8 | flags << 24`.
    pub word: u32,
    pub out: u32,
    /// Registers, or `CONSTANT | i` for the program's i-th constant.
    pub operands: Vec<u32>,
    /// Where the instruction starts.
    pub at: u32,
    /// Where its extra words (a ramp's table, a texture space) start, and how many.
    pub extra: u32,
    pub extra_len: u32,
}

impl Instruction {
    pub fn op(&self) -> u32 {
        self.word & 0xff
    }
}

/// The instructions of `program`, checked to be ones the shader can walk: they end before
/// the constants, their operations are known, their registers and constants in range.
pub fn instructions(program: &[u32]) -> Result<Vec<Instruction>, String> {
    let constants_at = *program.first().ok_or("empty")? as usize;
    if constants_at > program.len() || !(program.len() - constants_at).is_multiple_of(4) {
        return Err(format!("its constants start at word {constants_at} of {}", program.len()));
    }
    let constants = ((program.len() - constants_at) / 4) as u32;
    let word =
        |i: usize| program.get(i).copied().filter(|_| i < constants_at).ok_or("an instruction runs past its end");
    let mut out = Vec::new();
    let mut at = 1;
    loop {
        let op = word(at)? & 0xff;
        if op == node_kinds::NODE_OP_END {
            return Ok(out);
        }
        if !node_kinds::operations().any(|(_, o)| o == op) {
            return Err(format!("unknown operation {op} at word {at}"));
        }
        let register = word(at + 1)?;
        if register >= REGISTERS {
            return Err(format!("output register {register} at word {at}"));
        }
        let count = word(at + 2)?;
        if count > MAX_OPERANDS {
            return Err(format!("{count} operands at word {at}"));
        }
        let count = count as usize;
        let mut operands = Vec::with_capacity(count);
        for i in 0..count {
            let operand = word(at + 3 + i)?;
            let bad = if operand & CONSTANT != 0 { operand & !CONSTANT >= constants } else { operand >= REGISTERS };
            if bad {
                return Err(format!("operand {operand:#x} at word {} is out of range", at + 3 + i));
            }
            operands.push(operand);
        }
        let extra_len = word(at + 3 + count)?;
        let extra = at + 4 + count;
        if extra + extra_len as usize > constants_at {
            return Err(format!("the extra words at word {extra} run past the instructions"));
        }
        out.push(Instruction {
            word: word(at)?,
            out: register,
            operands,
            at: at as u32,
            extra: extra as u32,
            extra_len,
        });
        at = extra + extra_len as usize;
    }
}

/// What specialised code depends on: the instructions' words and where each one's extra
/// words lie, without the values (the constants and the extra words' contents, which the
/// shader reads from the program table, so that editing a value needs no new pipeline).
pub fn shape(program: &[u32]) -> Result<Vec<u32>, String> {
    let mut shape = vec![program.first().copied().unwrap_or(0)];
    for i in instructions(program)? {
        shape.extend([i.word, i.out, i.operands.len() as u32]);
        shape.extend(&i.operands);
        shape.push(i.extra_len);
    }
    Ok(shape)
}

/// Whether `program` sets material input `target` (one of `node_kinds::TARGETS`).
pub fn drives(program: &[u32], target: &str) -> bool {
    let Some(mode) = node_kinds::TARGETS.iter().position(|t| *t == target) else { return false };
    let output = |i: &Instruction| i.op() == node_kinds::NODE_OP_OUTPUT && (i.word >> 8) & 0xffff == mode as u32;
    instructions(program).is_ok_and(|all| all.iter().any(output))
}

/// The attribute numbers `program` reads (its Attribute and Color Attribute nodes).
pub fn attributes_read(program: &[u32]) -> Vec<u32> {
    let reads = |i: &Instruction| i.op() == node_kinds::NODE_OP_ATTRIBUTE && i.extra_len > 0;
    let all = instructions(program).unwrap_or_default();
    all.iter().filter(|i| reads(i)).filter_map(|i| program.get(i.extra as usize).copied()).collect()
}

/// Whether `program` reads a mesh attribute.
pub fn reads_attributes(program: &[u32]) -> bool {
    !attributes_read(program).is_empty()
}

#[cfg(test)]
mod tests {
    use super::*;

    // Coordinate (Generated, with a 6-word texture space) into register 0, Checker of it
    // with constants 0 to 2 into register 1, that register to the base colour.
    fn checker(color: f32) -> Vec<u32> {
        let mut p = vec![0];
        p.extend([node_kinds::NODE_OP_COORDINATE, 0, 0, 6, 0, 0, 0, 0, 0, 0]);
        p.extend([node_kinds::NODE_OP_CHECKER, 1, 4, 0, CONSTANT, CONSTANT | 1, CONSTANT | 2, 0]);
        p.extend([node_kinds::NODE_OP_OUTPUT, 0, 1, 1, 0]);
        p.push(node_kinds::NODE_OP_END);
        p[0] = p.len() as u32;
        for v in [color, 0.0, 0.0, 1.0, 0.5, 0.5, 0.5, 1.0, 20.0, 20.0, 20.0, 20.0] {
            p.push(v.to_bits());
        }
        p
    }

    #[test]
    fn instructions_are_read_back_with_their_places() {
        let p = checker(0.8);
        let read = instructions(&p).unwrap();
        assert_eq!(read.len(), 3);
        assert_eq!(
            (read[0].op(), read[0].at, read[0].extra, read[0].extra_len),
            (node_kinds::NODE_OP_COORDINATE, 1, 5, 6)
        );
        assert_eq!((read[1].op(), read[1].at, read[1].out), (node_kinds::NODE_OP_CHECKER, 11, 1));
        assert_eq!(read[1].operands, vec![0, CONSTANT, CONSTANT | 1, CONSTANT | 2]);
        assert_eq!(read[2].operands, vec![1]);
    }

    #[test]
    fn what_a_program_drives_is_read_from_its_outputs() {
        assert!(drives(&checker(0.8), "base_color"));
        assert!(!drives(&checker(0.8), "normal"));
        assert!(!drives(&checker(0.8), "no such input"));
        // The shader tests the normal's bit by name.
        let normal = 1u32 << node_kinds::TARGETS.iter().position(|t| *t == "normal").unwrap();
        let wgsl = include_str!("../../shaders/node_step.wgsl");
        assert!(wgsl.contains(&format!("const NODE_DRIVES_NORMAL: u32 = {normal}u;")));
    }

    #[test]
    fn a_value_is_not_part_of_the_shape_and_an_operation_is() {
        assert_eq!(shape(&checker(0.8)), shape(&checker(0.1)));
        let mut other = checker(0.8);
        other[11] = node_kinds::NODE_OP_GRADIENT;
        assert_ne!(shape(&checker(0.8)), shape(&other));
    }

    #[test]
    fn bad_programs_are_refused() {
        let mut p = checker(0.8);
        p[11] = 200;
        assert!(instructions(&p).unwrap_err().contains("unknown operation 200"));
        let mut p = checker(0.8);
        p[15] = CONSTANT | 9;
        assert!(instructions(&p).unwrap_err().contains("out of range"));
        let mut p = checker(0.8);
        p[4] = 60;
        assert!(instructions(&p).is_err());
        assert!(instructions(&[]).is_err());
    }
}
