//! Feature sets that put every pair of flag values together: a pairwise covering array
//! over the dimensions of [`FeatureSet`], within the rules a scene's analysis obeys (an
//! alpha mask comes with textures, a medium with transmission, …). Compiling each of
//! them compiles every two effects side by side, in far fewer pipelines than all
//! combinations.

use crate::scene::{FLAGS, FeatureSet, Flag, RoughTransmission, Sampling, SkyFeature, Transmission};

/// One value of a dimension: how to give it to a set, and whether a set has it.
struct Level {
    name: &'static str,
    set: Box<dyn Fn(&mut FeatureSet)>,
    holds: Box<dyn Fn(&FeatureSet) -> bool>,
}

/// A dimension of the feature space and the values it takes.
struct Factor {
    name: &'static str,
    levels: Vec<Level>,
}

/// A boolean flag of the set's declaration as a factor of two levels.
fn flag(flag: &'static Flag) -> Factor {
    let level = |name, on: bool| Level {
        name,
        set: Box::new(move |f: &mut FeatureSet| (flag.set)(f, on)),
        holds: Box::new(move |f: &FeatureSet| (flag.get)(f) == on),
    };
    Factor { name: flag.name, levels: vec![level("off", false), level("on", true)] }
}

/// A boolean field of the lamp kinds as a factor of two levels.
macro_rules! lamp {
    ($kind:ident) => {
        Factor {
            name: concat!("lamps.", stringify!($kind)),
            levels: vec![
                Level { name: "off", set: Box::new(|f| f.lamps.$kind = false), holds: Box::new(|f| !f.lamps.$kind) },
                Level { name: "on", set: Box::new(|f| f.lamps.$kind = true), holds: Box::new(|f| f.lamps.$kind) },
            ],
        }
    };
}

/// An enum-valued field as a factor, one level per value.
macro_rules! choice {
    ($field:ident: $($name:literal => $value:expr),+ $(,)?) => {
        Factor {
            name: stringify!($field),
            levels: vec![$(Level {
                name: $name,
                set: Box::new(|f| f.$field = $value),
                holds: Box::new(|f| f.$field == $value),
            }),+],
        }
    };
}

/// Every dimension: the fields that are not flags, then every declared flag.
fn factors() -> Vec<Factor> {
    let mut factors = vec![
        choice!(sky: "black" => SkyFeature::Black, "uniform" => SkyFeature::Uniform,
            "uniform_light" => SkyFeature::UniformLight,
            "atmosphere" => SkyFeature::Atmosphere, "environment" => SkyFeature::Environment,
            "graph" => SkyFeature::Graph),
        choice!(transmission: "none" => Transmission::None, "smooth" => Transmission::Smooth,
            "ggx" => Transmission::Rough(RoughTransmission::Ggx), "cone" => Transmission::Rough(RoughTransmission::Cone)),
        choice!(sampling: "nee" => Sampling::Nee, "resampled" => Sampling::Resampled),
        lamp!(point),
        lamp!(spot),
        lamp!(area),
        lamp!(sun),
    ];
    factors.extend(FLAGS.iter().map(flag));
    factors.extend((0..crate::scene::lobe::LOBES.len()).map(lobe_module));
    factors
}

/// A lobe module (`scene::lobe`) as a factor of two levels: absent or used.
fn lobe_module(index: usize) -> Factor {
    let bit = crate::scene::lobe::bit(index);
    let level = |name, on: bool| Level {
        name,
        set: Box::new(move |f: &mut FeatureSet| {
            f.lobe_modules = if on { f.lobe_modules | bit } else { f.lobe_modules & !bit }
        }),
        holds: Box::new(move |f: &FeatureSet| (f.lobe_modules & bit != 0) == on),
    };
    Factor { name: crate::scene::lobe::LOBES[index].name, levels: vec![level("off", false), level("on", true)] }
}

/// What a scene can ask for together: every flag with what it needs, and some geometry.
fn possible(f: &FeatureSet) -> bool {
    (f.triangles || f.spheres) && f.consistent()
}

/// Turns on what the set's effects need (an alpha mask's textures, a medium's glass).
fn complete(f: &mut FeatureSet) {
    f.complete();
    if !f.spheres {
        f.triangles = true;
    }
}

/// (factor, level) of each factor in `f`.
fn levels_of(factors: &[Factor], f: &FeatureSet) -> Vec<(usize, usize)> {
    let level = |factor: &Factor| factor.levels.iter().position(|l| (l.holds)(f)).expect("a level holds");
    factors.iter().enumerate().map(|(i, factor)| (i, level(factor))).collect()
}

type Pair = ((usize, usize), (usize, usize));

fn pairs_of(levels: &[(usize, usize)]) -> impl Iterator<Item = Pair> + '_ {
    levels.iter().enumerate().flat_map(move |(i, a)| levels[i + 1..].iter().map(move |b| (*a, *b)))
}

/// The set that holds `pair`, with each other factor at the level that adds most pairs not
/// yet in `covered`; `None` when no possible set holds the pair.
fn row_for(
    factors: &[Factor],
    base: FeatureSet,
    pair: Pair,
    covered: &std::collections::HashSet<Pair>,
) -> Option<FeatureSet> {
    let ((fa, la), (fb, lb)) = pair;
    let mut set = base;
    (factors[fa].levels[la].set)(&mut set);
    (factors[fb].levels[lb].set)(&mut set);
    complete(&mut set);
    let keeps = |s: &FeatureSet| (factors[fa].levels[la].holds)(s) && (factors[fb].levels[lb].holds)(s) && possible(s);
    if !keeps(&set) {
        return None;
    }
    for (i, factor) in factors.iter().enumerate() {
        let fixed = levels_of(factors, &set);
        let gain = |s: &FeatureSet| {
            let level = levels_of(factors, s)[i];
            fixed.iter().filter(|other| other.0 != i && !covered.contains(&ordered(level, **other))).count()
        };
        let candidates = factor.levels.iter().map(|l| {
            let mut s = set;
            (l.set)(&mut s);
            complete(&mut s);
            s
        });
        let unchanged = |s: &FeatureSet| levels_of(factors, s).iter().zip(&fixed).all(|(a, b)| a.0 == i || a == b);
        if let Some(best) = candidates.filter(|s| keeps(s) && unchanged(s)).max_by_key(gain) {
            set = best;
        }
    }
    Some(set)
}

fn ordered(a: (usize, usize), b: (usize, usize)) -> Pair {
    if a.0 < b.0 { (a, b) } else { (b, a) }
}

/// Feature sets in which every possible pair of factor levels occurs at least once, and
/// how many possible pairs there are.
pub(super) fn pairwise(base: FeatureSet) -> (Vec<FeatureSet>, usize) {
    let factors = factors();
    let all: Vec<Pair> = pairs_of(
        &factors.iter().enumerate().flat_map(|(i, f)| (0..f.levels.len()).map(move |l| (i, l))).collect::<Vec<_>>(),
    )
    .filter(|(a, b)| a.0 != b.0)
    .collect();
    let mut covered = std::collections::HashSet::new();
    let (mut rows, mut possible_pairs) = (Vec::new(), 0);
    for &pair in &all {
        if covered.contains(&pair) {
            possible_pairs += 1;
            continue;
        }
        let Some(row) = row_for(&factors, base, pair, &covered) else { continue };
        possible_pairs += 1;
        covered.extend(pairs_of(&levels_of(&factors, &row)));
        rows.push(row);
    }
    (rows, possible_pairs)
}

/// The pairs of levels that some possible set holds and none of `sets` does, by name.
pub(super) fn uncovered(sets: &[FeatureSet], base: FeatureSet) -> Vec<String> {
    let factors = factors();
    let held: std::collections::HashSet<Pair> =
        sets.iter().flat_map(|s| pairs_of(&levels_of(&factors, s)).collect::<Vec<_>>()).collect();
    let mut missing = Vec::new();
    for (i, a) in factors.iter().enumerate() {
        for (j, b) in factors.iter().enumerate().skip(i + 1) {
            for (la, level_a) in a.levels.iter().enumerate() {
                for (lb, level_b) in b.levels.iter().enumerate() {
                    let pair = ((i, la), (j, lb));
                    let feasible = row_for(&factors, base, pair, &Default::default()).is_some();
                    if feasible && !held.contains(&pair) {
                        missing.push(format!("{}={} with {}={}", a.name, level_a.name, b.name, level_b.name));
                    }
                }
            }
        }
    }
    missing
}
