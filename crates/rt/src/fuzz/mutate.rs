//! The stable harness's mutator: bit flips, truncation, nasty 32-bit words (counts near
//! the integer limits, NaN, infinities), repeated and spliced ranges, and for text, a
//! number swapped for a nasty one or a line repeated many times (where a list of many
//! equal entries once took quadratic time).

/// A small, fast, seedable generator (xorshift64*).
pub struct Rng(pub u64);

impl Rng {
    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    /// A number in `0..n` (0 when `n` is 0).
    pub fn below(&mut self, n: usize) -> usize {
        if n == 0 { 0 } else { (self.next_u64() % n as u64) as usize }
    }
}

const NASTY_WORDS: [u32; 9] =
    [0, 1, 0xffff_ffff, 0x7fff_ffff, 0x8000_0000, 0x7fc0_0000, 0x7f80_0000, 0xff80_0000, 0x0001_0000];
const NASTY_NUMBERS: [&str; 12] =
    ["nan", "inf", "-inf", "1e39", "-1", "0", "4294967295", "1e-45", "99999999999", "-0", "1e308", "65536"];

/// A mutant of `input`; `other` (another corpus entry) may be spliced in.
pub fn mutate(input: &[u8], other: &[u8], rng: &mut Rng, text: bool) -> Vec<u8> {
    let mut b = input.to_vec();
    for _ in 0..1 + rng.below(3) {
        let kinds = if text { 8 } else { 6 };
        match rng.below(kinds) {
            0 => flip_bits(&mut b, rng),
            1 => b.truncate(rng.below(b.len() + 1)),
            2 => nasty_word(&mut b, rng),
            3 => repeat_range(&mut b, rng),
            4 => splice(&mut b, other, rng),
            5 => {
                let i = rng.below(b.len() + 1);
                b.insert(i, [0u8, 0xff, b'\n', b'"', b'[', b'\\'][rng.below(6)]);
            }
            6 => nasty_number(&mut b, rng),
            _ => repeat_line(&mut b, rng),
        }
    }
    b
}

fn flip_bits(b: &mut [u8], rng: &mut Rng) {
    for _ in 0..1 + rng.below(4) {
        let i = rng.below(b.len());
        if let Some(byte) = b.get_mut(i) {
            *byte ^= 1 << rng.below(8);
        }
    }
}

fn nasty_word(b: &mut [u8], rng: &mut Rng) {
    if b.len() >= 4 {
        let i = rng.below(b.len() / 4) * 4;
        b[i..i + 4].copy_from_slice(&NASTY_WORDS[rng.below(NASTY_WORDS.len())].to_le_bytes());
    }
}

fn repeat_range(b: &mut Vec<u8>, rng: &mut Rng) {
    let (i, j) = (rng.below(b.len()), rng.below(b.len()));
    let (i, j) = (i.min(j), i.max(j).min(i + 4096));
    let slice = b[i..j].to_vec();
    for _ in 0..1 + rng.below(4) {
        b.splice(j..j, slice.iter().copied());
    }
}

fn splice(b: &mut Vec<u8>, other: &[u8], rng: &mut Rng) {
    if other.is_empty() {
        return;
    }
    let (i, j) = (rng.below(other.len()), rng.below(other.len()));
    let at = rng.below(b.len() + 1);
    b.splice(at..at, other[i.min(j)..i.max(j)].iter().copied());
}

/// A number in the text becomes a nasty one.
fn nasty_number(b: &mut Vec<u8>, rng: &mut Rng) {
    let s = String::from_utf8_lossy(b).into_owned();
    let starts: Vec<usize> = s
        .char_indices()
        .filter(|&(i, c)| c.is_ascii_digit() && (i == 0 || !s.as_bytes()[i - 1].is_ascii_alphanumeric()))
        .map(|(i, _)| i)
        .collect();
    if let Some(&start) = starts.get(rng.below(starts.len())) {
        let end = s[start..]
            .find(|c: char| !(c.is_ascii_digit() || c == '.' || c == 'e' || c == '-'))
            .map_or(s.len(), |e| start + e);
        let replacement = NASTY_NUMBERS[rng.below(NASTY_NUMBERS.len())];
        *b = format!("{}{replacement}{}", &s[..start], &s[end..]).into_bytes();
    }
}

/// A run of lines (a TOML table with its keys, say) repeated up to 2,000 times.
fn repeat_line(b: &mut Vec<u8>, rng: &mut Rng) {
    let lines: Vec<usize> =
        std::iter::once(0).chain(b.iter().enumerate().filter(|(_, c)| **c == b'\n').map(|(i, _)| i + 1)).collect();
    if lines.len() < 2 {
        return;
    }
    let first = rng.below(lines.len() - 1);
    let last = (first + 1 + rng.below(4)).min(lines.len() - 1);
    let block = b[lines[first]..lines[last]].to_vec();
    let times = [2, 10, 100, 2000][rng.below(4)];
    let at = lines[last];
    b.splice(at..at, block.iter().copied().cycle().take(block.len() * times));
}
