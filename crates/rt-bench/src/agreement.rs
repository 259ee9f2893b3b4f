//! Whether two renderers made the same image: each renders it twice with independent
//! random numbers, and per colour channel the means of every 8×8 block (and of the whole
//! image) are compared against both images' noise, measured from the two renders' difference.
//! A rate is compared only between images that agree: a ratio between different images
//! would measure different work.

/// Blocks are 8×8 pixels; a partial block at the right or bottom edge is left out.
const BLOCK: usize = 8;
/// The chance of calling two renders of the same image different, over all blocks and
/// channels together.
const FALSE_ALARM: f64 = 1e-3;

/// One renderer's two renders of the same image, linear RGB, rows from the top.
pub struct Pair<'a> {
    pub width: usize,
    pub height: usize,
    pub renders: [&'a [[f32; 3]]; 2],
}

impl Pair<'_> {
    /// The mean of the two renders over `pixels` in channel `c`, and the variance of that
    /// mean: each pixel's (x₁ − x₂)²/4 estimates the variance of its mean (x₁ + x₂)/2.
    fn mean_and_variance(&self, pixels: &[usize], c: usize) -> (f64, f64) {
        let n = pixels.len() as f64;
        let (mut sum, mut var) = (0.0, 0.0);
        for &i in pixels {
            let (a, b) = (self.renders[0][i][c] as f64, self.renders[1][i][c] as f64);
            sum += 0.5 * (a + b);
            var += 0.25 * (a - b) * (a - b);
        }
        (sum / n, var / (n * n))
    }
}

/// The comparison's result.
#[derive(Clone, Debug)]
pub struct Verdict {
    pub agree: bool,
    /// The largest |z| of any block and channel, with its block's corner and the channel.
    pub worst_block: (f64, usize, usize, usize),
    /// The threshold a block's |z| is held to (a Bonferroni bound over all blocks).
    pub block_threshold: f64,
    /// Per channel: the whole image's z, and its mean's relative difference (a/b − 1).
    pub global: [(f64, f64); 3],
}

/// The whole image's mean may differ by this many standard errors at most.
const GLOBAL_THRESHOLD: f64 = 4.0;

/// Differences this small relative to the values are rounding, not disagreement: where
/// neither image has noise (a sky seen directly) two renderers' floats still differ.
const ROUNDING: f64 = 1e-5;

fn z(a: (f64, f64), b: (f64, f64)) -> f64 {
    let rounding = ROUNDING * a.0.abs().max(b.0.abs());
    let (diff, var) = (a.0 - b.0, a.1 + b.1 + rounding * rounding);
    match var > 0.0 {
        true => diff / var.sqrt(),
        false if diff == 0.0 => 0.0,
        false => f64::INFINITY,
    }
}

/// Compares `a` and `b` (the same size).
pub fn compare(a: &Pair, b: &Pair) -> Verdict {
    assert_eq!((a.width, a.height), (b.width, b.height), "images of different sizes");
    let (bw, bh) = (a.width / BLOCK, a.height / BLOCK);
    let blocks = (bw * bh * 3).max(1) as f64;
    // A z beyond √(2 ln(K/α)) has a Gaussian chance below α/K: at most α over K tests.
    let block_threshold = (2.0 * (blocks / FALSE_ALARM).ln()).sqrt();
    let mut worst = (0.0, 0, 0, 0);
    for by in 0..bh {
        for bx in 0..bw {
            let pixels: Vec<usize> = (by * BLOCK..(by + 1) * BLOCK)
                .flat_map(|y| (bx * BLOCK..(bx + 1) * BLOCK).map(move |x| y * a.width + x))
                .collect();
            for c in 0..3 {
                let zb = z(a.mean_and_variance(&pixels, c), b.mean_and_variance(&pixels, c));
                if zb.abs() > worst.0 {
                    worst = (zb.abs(), bx * BLOCK, by * BLOCK, c);
                }
            }
        }
    }
    let all: Vec<usize> = (0..a.width * a.height).collect();
    let global = [0, 1, 2].map(|c| {
        let (ma, mb) = (a.mean_and_variance(&all, c), b.mean_and_variance(&all, c));
        (z(ma, mb), if mb.0 != 0.0 { ma.0 / mb.0 - 1.0 } else { 0.0 })
    });
    let agree = worst.0 <= block_threshold && global.iter().all(|(z, _)| z.abs() <= GLOBAL_THRESHOLD);
    Verdict { agree, worst_block: worst, block_threshold, global }
}

impl std::fmt::Display for Verdict {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        let (z, x, y, c) = self.worst_block;
        let channel = ["red", "green", "blue"][c];
        let means = self.global.map(|(z, d)| format!("{:+.2}% ({z:+.1} σ)", 100.0 * d));
        write!(
            f,
            "{}: means R {} G {} B {}; worst 8x8 block {z:.1} σ ({channel}, at {x},{y}; bound {:.1})",
            if self.agree { "agree" } else { "DISAGREE" },
            means[0],
            means[1],
            means[2],
            self.block_threshold
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two noisy renders of a gradient: `shift` added to one channel of a block.
    fn renders(seed: u64, shift: f32) -> [Vec<[f32; 3]>; 2] {
        let mut state = seed;
        let mut noise = move || {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((state >> 40) as f32 / (1u64 << 24) as f32 - 0.5) * 0.2
        };
        [0, 1].map(|_| {
            (0..32 * 32)
                .map(|i| {
                    let base = (i % 32) as f32 / 32.0 + 0.5;
                    let bump = if i / 32 < 8 && i % 32 < 8 { shift } else { 0.0 };
                    [base + noise() + bump, base + noise(), base + noise()]
                })
                .collect()
        })
    }

    fn pair(r: &[Vec<[f32; 3]>; 2]) -> Pair<'_> {
        Pair { width: 32, height: 32, renders: [&r[0], &r[1]] }
    }

    #[test]
    fn the_same_image_agrees_and_a_shifted_block_does_not() {
        let (a, b) = (renders(1, 0.0), renders(2, 0.0));
        let same = compare(&pair(&a), &pair(&b));
        assert!(same.agree, "{same}");
        // 0.05 on one channel of one block: its mean's standard error is about 0.006.
        let shifted = renders(3, 0.05);
        let v = compare(&pair(&a), &pair(&shifted));
        assert!(!v.agree && v.worst_block.1 == 0 && v.worst_block.2 == 0 && v.worst_block.3 == 0, "{v}");
    }
}
