//! The argument sets of the sweep: per parameter type its extreme values and a nominal one; each
//! argument swept over its extremes with the others nominal, pairs for grazing and degenerate
//! geometry and for stiff products, and a seeded set of random combinations of extremes.
//!
//! Every value is representable in f32 (and integers in i32 or u32), so the f32 and f64
//! interpreters and the GPU all see the same arguments.

use patina_compiler::syntax::ast::TypeName;

use super::preconditions::Constraint;

/// A parameter type the sweep can generate values of.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Kind {
    /// `float` (and `clampf`).
    Float,
    /// `int`.
    Int,
    /// `uint`.
    Uint,
    /// `bool`.
    Bool,
    /// `point` or `float3`.
    Point,
    /// `vector`.
    Vector,
    /// `normal`.
    Normal,
    /// `color`.
    Color,
    /// `float4`.
    Float4,
    /// `matrix` (4x4).
    Matrix,
}

impl Kind {
    /// The kind of a type name, or `None` for types the sweep does not generate (strings,
    /// textures, 3x3 matrices).
    pub fn of(ty: TypeName) -> Option<Kind> {
        Some(match ty {
            TypeName::Float | TypeName::Clampf => Kind::Float,
            TypeName::Int => Kind::Int,
            TypeName::Uint => Kind::Uint,
            TypeName::Bool => Kind::Bool,
            TypeName::Point | TypeName::Float3 => Kind::Point,
            TypeName::Vector => Kind::Vector,
            TypeName::Normal => Kind::Normal,
            TypeName::Color => Kind::Color,
            TypeName::Float4 => Kind::Float4,
            TypeName::Matrix | TypeName::Matrix4 => Kind::Matrix,
            _ => return None,
        })
    }

    /// Values per point.
    pub fn components(self) -> usize {
        match self {
            Kind::Float | Kind::Int | Kind::Uint | Kind::Bool => 1,
            Kind::Point | Kind::Vector | Kind::Normal | Kind::Color => 3,
            Kind::Float4 => 4,
            Kind::Matrix => 16,
        }
    }

    fn is_triple(self) -> bool {
        matches!(self, Kind::Point | Kind::Vector | Kind::Normal)
    }

    /// The value the argument has while others are swept: ordinary, non-degenerate.
    pub fn nominal(self) -> Vec<f64> {
        match self {
            Kind::Float => vec![0.5],
            Kind::Int | Kind::Uint | Kind::Bool => vec![1.0],
            Kind::Point => vec![0.3, -0.5, 0.7],
            Kind::Vector => vec![0.6, 0.0, -0.8],
            Kind::Normal => vec![0.0, 0.0, 1.0],
            Kind::Color => vec![0.25, 0.5, 0.75],
            Kind::Float4 => vec![0.25, 0.5, 0.75, 1.0],
            Kind::Matrix => diagonal(1.0),
        }
    }

    /// The extreme values of the kind.
    pub fn extremes(self) -> Vec<Vec<f64>> {
        match self {
            Kind::Float => floats().into_iter().flat_map(|x| [vec![x], vec![-x]]).collect(),
            Kind::Int => INTS.iter().map(|&x| vec![x]).collect(),
            Kind::Uint => UINTS.iter().map(|&x| vec![x]).collect(),
            Kind::Bool => vec![vec![0.0], vec![1.0]],
            Kind::Point | Kind::Vector | Kind::Normal | Kind::Color => {
                let mut v = vec![vec![0.0; 3]];
                for axis in 0..3 {
                    for sign in [1.0, -1.0] {
                        let mut a = vec![0.0; 3];
                        a[axis] = sign;
                        v.push(a);
                    }
                }
                for m in [TINY, denormal(), 1e4, 1e7, 1e30, -1e30] {
                    v.push(vec![m; 3]);
                }
                v.extend([vec![-1e30, 1e30, 0.5], vec![1e7, -TINY, 0.0], vec![0.5, 0.5, 0.5]]);
                v
            }
            Kind::Float4 => {
                let mut v = vec![vec![0.0; 4], vec![1.0; 4]];
                for m in [TINY, denormal(), 1e7, 1e30, -1e30] {
                    v.push(vec![m; 4]);
                }
                v.push(vec![0.5, -1.0, 1e4, 0.0]);
                v
            }
            Kind::Matrix => {
                let mut v: Vec<Vec<f64>> = [0.0, -1.0, TINY, denormal(), 1e7, 1e30].map(diagonal).into();
                v.push(vec![1.0; 16]); // rank one
                let mut translated = diagonal(1.0);
                translated[12..15].copy_from_slice(&[1e30, -1e30, 1e7]);
                v.push(translated);
                v
            }
        }
    }
}

/// The float extremes (each is swept with both signs, so zero as 0 and -0): zero, tiny,
/// denormal, halves and ones, large coordinates (1e7: f32 spacing 1) and near f32's end.
fn floats() -> [f64; 9] {
    [0.0, TINY, denormal(), 0.5, 1.0, 1e4, 1e6, 1e7, 1e30]
}

/// A tiny normal magnitude.
const TINY: f64 = 1e-30;

/// The smallest f32 denormal, representable in both precisions.
fn denormal() -> f64 {
    f64::from(f32::from_bits(1))
}

/// Integers: zero, small, and large up to i32's ends (all exact in f32).
const INTS: [f64; 14] = [
    0.0,
    1.0,
    -1.0,
    7.0,
    -7.0,
    65536.0,
    -65536.0,
    16777216.0,
    -16777216.0,
    1073741824.0,
    -1073741824.0,
    2147483520.0,
    -2147483520.0,
    -2147483648.0,
];

/// Unsigned integers up to u32's end (exact in f32).
const UINTS: [f64; 7] = [0.0, 1.0, 7.0, 65536.0, 16777216.0, 2147483648.0, 4294967040.0];

fn diagonal(d: f64) -> Vec<f64> {
    (0..16).map(|i| if i % 5 == 0 { d } else { 0.0 }).collect()
}

/// Grazing and degenerate pairs of points, vectors and normals: perpendicular (N.I = 0),
/// parallel and antiparallel, nearly parallel, a zero-length first or second, coincident
/// (ordinary and huge), nearly coincident at a large coordinate.
fn triple_pairs() -> Vec<[Vec<f64>; 2]> {
    let z = vec![0.0, 0.0, 1.0];
    vec![
        [z.clone(), vec![1.0, 0.0, 0.0]],
        [z.clone(), z.clone()],
        [z.clone(), vec![0.0, 0.0, -1.0]],
        [z.clone(), vec![0.0, 1e-7, 1.0]],
        [z.clone(), vec![0.0, 1e-7, -1.0]],
        [vec![0.0; 3], z.clone()],
        [z, vec![0.0; 3]],
        [vec![1.0, 2.0, 3.0], vec![1.0, 2.0, 3.0]],
        [vec![1e30; 3], vec![1e30; 3]],
        [vec![1e7; 3], vec![1e7 + 1.0, 1e7, 1e7]],
    ]
}

/// Stiff pairs of floats (a density and a step, a frequency and a coordinate): products of 1e4,
/// 1e8 and 1e60.
const FLOAT_PAIRS: [[f64; 2]; 5] = [[1e2, 1e2], [1e4, 1.0], [1.0, 1e4], [1e4, 1e4], [1e30, 1e30]];

/// One input of a subject.
#[derive(Clone, Debug)]
pub struct Arg {
    /// The input's name in the program (`a0`, `a2_1`, `Kd`, `P`).
    pub slot: String,
    /// Its kind.
    pub kind: Kind,
    /// The parameter it stands for, as the user wrote it (`radius`, `clut[1]`).
    pub label: String,
    /// Its documented precondition.
    pub constraint: Constraint,
}

impl Arg {
    /// An input `slot` of `kind` standing for the parameter `label`.
    pub fn new(slot: String, kind: Kind, label: &str, constraint: Constraint) -> Arg {
        Arg { slot, kind, label: label.to_string(), constraint }
    }

    /// `value` with the precondition applied to each component and rounded to f32.
    fn admit(&self, value: &[f64]) -> Vec<f64> {
        value.iter().map(|&x| f64::from(self.constraint.apply(x) as f32)).collect()
    }
}

/// The argument sets, as one column per argument (`count * components` values each).
#[derive(Clone, Debug, PartialEq)]
pub struct Points {
    /// The number of points.
    pub count: usize,
    /// One column per argument, in the order of the arguments.
    pub columns: Vec<Vec<f64>>,
}

impl Points {
    /// Argument `arg`'s value at point `i`.
    pub fn value(&self, arg: usize, i: usize, components: usize) -> &[f64] {
        &self.columns[arg][i * components..(i + 1) * components]
    }
}

/// splitmix64: the deterministic random numbers of the combinations.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

/// The sweep's points for `args`: the nominal point; each argument over its extremes with the
/// others nominal; every pair of point-like arguments over `triple_pairs` and every pair of
/// floats over `FLOAT_PAIRS`; then `random` points whose every argument is, with even odds,
/// one of its extremes or nominal (seeded with `seed`).
pub fn points(args: &[Arg], random: usize, seed: u64) -> Points {
    let nominal: Vec<Vec<f64>> = args.iter().map(|a| a.kind.nominal()).collect();
    let extremes: Vec<Vec<Vec<f64>>> = args.iter().map(|a| a.kind.extremes()).collect();
    let mut sets: Vec<Vec<Vec<f64>>> = vec![nominal.clone()];
    for (i, values) in extremes.iter().enumerate() {
        for v in values {
            let mut set = nominal.clone();
            set[i] = v.clone();
            sets.push(set);
        }
    }
    for i in 0..args.len() {
        for j in i + 1..args.len() {
            let (a, b) = (args[i].kind, args[j].kind);
            let pairs: Vec<[Vec<f64>; 2]> = if a.is_triple() && b.is_triple() {
                triple_pairs()
            } else if a == Kind::Float && b == Kind::Float {
                FLOAT_PAIRS.iter().map(|[x, y]| [vec![*x], vec![*y]]).collect()
            } else {
                continue;
            };
            for [x, y] in pairs {
                let mut set = nominal.clone();
                set[i] = x;
                set[j] = y;
                sets.push(set);
            }
        }
    }
    let mut rng = Rng(seed);
    for _ in 0..random {
        let set = (0..args.len())
            .map(|i| {
                if rng.below(2) == 0 {
                    nominal[i].clone()
                } else {
                    extremes[i][rng.below(extremes[i].len())].clone()
                }
            })
            .collect();
        sets.push(set);
    }
    let mut columns = vec![Vec::new(); args.len()];
    for set in &sets {
        for (i, value) in set.iter().enumerate() {
            columns[i].extend(args[i].admit(value));
        }
    }
    Points { count: sets.len(), columns }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn arg(slot: &str, kind: Kind) -> Arg {
        Arg::new(slot.into(), kind, slot, Constraint::default())
    }

    #[test]
    fn each_argument_is_swept_with_the_others_nominal() {
        let pts = points(&[arg("x", Kind::Float), arg("n", Kind::Int)], 0, 1);
        // The nominal point, 18 float extremes, 14 integer extremes, no pairs of a float and an int.
        assert_eq!(pts.count, 1 + 18 + 14);
        assert_eq!((pts.columns[0][0], pts.columns[1][0]), (0.5, 1.0));
        let x_sweep = &pts.columns[0][1..19];
        assert!(x_sweep.contains(&-f64::from(1e30f32)) && x_sweep.contains(&f64::from(f32::from_bits(1))));
        assert!(pts.columns[1][1..19].iter().all(|n| *n == 1.0), "n stays nominal while x is swept");
        assert!(pts.columns[1][19..].contains(&-2147483648.0));
    }

    #[test]
    fn pairs_of_directions_meet_grazing_and_degenerate() {
        let pts = points(&[arg("N", Kind::Normal), arg("I", Kind::Vector)], 0, 1);
        let pair = |i: usize| (pts.value(0, i, 3).to_vec(), pts.value(1, i, 3).to_vec());
        let pairs: Vec<_> = (0..pts.count).map(pair).collect();
        let dot = |(a, b): &(Vec<f64>, Vec<f64>)| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
        assert!(pairs.iter().any(|p| dot(p) == 0.0 && p.0 == [0.0, 0.0, 1.0]), "N.I = 0");
        assert!(pairs.iter().any(|p| p.0 == p.1 && p.0 == [0.0, 0.0, 1.0]), "I parallel to N");
        assert!(pairs.iter().any(|p| p.0 == [0.0; 3] && p.1 == [0.0, 0.0, 1.0]), "zero-length N");
    }

    #[test]
    fn random_combinations_are_seeded_and_respect_preconditions() {
        let bounded = Arg::new(
            "k".into(),
            Kind::Float,
            "k",
            Constraint { range: Some((0.0, 16.0)), ..Default::default() },
        );
        let args = [arg("x", Kind::Float), bounded];
        let (a, b) = (points(&args, 32, 7), points(&args, 32, 7));
        assert_eq!(a, b);
        assert_ne!(a, points(&args, 32, 8));
        assert!(a.columns[1].iter().all(|k| (0.0..=16.0).contains(k)));
        assert!(a.columns[1].contains(&16.0) && a.columns[1].contains(&0.0));
        assert!(a.columns.iter().flatten().all(|v| f64::from(*v as f32) == *v), "every value is an f32");
    }
}
