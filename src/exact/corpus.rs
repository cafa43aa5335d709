//! The embedded regression corpus.

use std::format;
use std::string::String;
use std::vec::Vec;

use super::{Band, Case, Claim};
use crate::glam::{DVec3, Vec3};
use crate::{Aabb, Plane, Ray, Scalar, Triangle, Vector};

/// One corpus case of precision `V`: the case, its exact answer (values
/// rounded to nearest) and its band.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CorpusEntry<V: Vector> {
    /// The family: `box`, `triangle` or `plane`.
    pub kind: &'static str,
    /// The question.
    pub case: Case<V>,
    /// The exact answer, as a claim: [`Claim::Miss`], or the hit with its
    /// exact values rounded to nearest (box: entry and exit; triangle: `t`,
    /// `u`, `v`; plane: `t`). [`judge`](super::judge) finds it right, each
    /// value within half an ulp.
    pub answer: Claim<V::Scalar>,
    /// Outside (`Clear`) or inside (`Edge`) the crate's rounding band: see
    /// [`band`](super::band).
    pub band: Band,
}

/// A corpus case in either precision.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CorpusCase {
    /// Single precision.
    F32(CorpusEntry<Vec3>),
    /// Double precision.
    F64(CorpusEntry<DVec3>),
}

const FILES: [(&str, &str); 6] = [
    ("box", include_str!("data/box_f32.txt")),
    ("box", include_str!("data/box_f64.txt")),
    ("triangle", include_str!("data/triangle_f32.txt")),
    ("triangle", include_str!("data/triangle_f64.txt")),
    ("plane", include_str!("data/plane_f32.txt")),
    ("plane", include_str!("data/plane_f64.txt")),
];

fn hex<F: Scalar>(s: &str) -> Result<F, String> {
    let bad = || format!("not an f32 or f64 bit pattern in hex: {s}");
    Ok(match s.len() {
        8 => F::from_f64(f64::from(f32::from_bits(
            u32::from_str_radix(s, 16).map_err(|_| bad())?,
        ))),
        16 => F::from_f64(f64::from_bits(
            u64::from_str_radix(s, 16).map_err(|_| bad())?,
        )),
        _ => return Err(bad()),
    })
}

/// Reads a case and an answer in the corpus's text form: `kind` is `box`,
/// `triangle` or `plane`; `inputs` the case's floats as IEEE bit patterns
/// in hex (box: origin, dir, min, max, `t_max`; triangle: origin, dir, a,
/// b, c, `t_max`; plane: origin, dir, point, normal, `t_max`); `answer`
/// `miss`, or `hit` and the values (box: entry, exit; triangle: `t`, `u`,
/// `v`; plane: `t`) in hex, any further words ignored. An error says what
/// is wrong.
///
/// ```
/// use rayhit::{exact::{self, Case, Claim}, glam::Vec3};
/// let (case, claim) = exact::parse_case::<Vec3>(
///     "plane",
///     "00000000 3f800000 00000000 00000000 bf800000 00000000 \
///      00000000 00000000 00000000 00000000 3f800000 00000000 7f800000",
///     "hit 3f800000",
/// )
/// .unwrap();
/// assert!(matches!(case, Case::Plane(..)));
/// assert_eq!(claim, Claim::Plane { t: 1.0 });
/// ```
pub fn parse_case<V: Vector>(
    kind: &str,
    inputs: &str,
    answer: &str,
) -> Result<(Case<V>, Claim<V::Scalar>), String> {
    let n: Vec<V::Scalar> = inputs
        .split_whitespace()
        .map(hex)
        .collect::<Result<_, _>>()?;
    let want = match kind {
        "box" | "plane" => 13,
        "triangle" => 16,
        _ => return Err(format!("unknown kind {kind}")),
    };
    if n.len() != want {
        return Err(format!("{kind} needs {want} numbers, got {}", n.len()));
    }
    let a: Vec<&str> = answer.split_whitespace().collect();
    let hit = match a.first() {
        Some(&"hit") => true,
        Some(&"miss") => false,
        _ => return Err("the answer is neither `hit` nor `miss`".into()),
    };
    let x = |i: usize| -> Result<V::Scalar, String> {
        hex(a.get(i).ok_or("too few numbers in the answer")?)
    };
    let v = |i: usize| V::new(n[i], n[i + 1], n[i + 2]);
    let ray = Ray::new(v(0), v(3));
    Ok(match kind {
        "box" => (
            Case::Box(ray, Aabb::new(v(6), v(9)), n[12]),
            if hit {
                Claim::Box {
                    enter: x(1)?,
                    exit: x(2)?,
                }
            } else {
                Claim::Miss
            },
        ),
        "triangle" => (
            Case::Triangle(ray, Triangle::new(v(6), v(9), v(12)), n[15]),
            if hit {
                Claim::Triangle {
                    t: x(1)?,
                    u: x(2)?,
                    v: x(3)?,
                }
            } else {
                Claim::Miss
            },
        ),
        _ => (
            Case::Plane(ray, Plane::new(v(6), v(9)), n[12]),
            if hit {
                Claim::Plane { t: x(1)? }
            } else {
                Claim::Miss
            },
        ),
    })
}

fn entry<V: Vector>(kind: &'static str, line: &str) -> Option<CorpusEntry<V>> {
    let mut parts = line.split('|').map(str::trim);
    let (inputs, answer) = (parts.next()?, parts.next()?);
    let band = if parts.next()? == "clear" {
        Band::Clear
    } else {
        Band::Edge
    };
    let (case, answer) = parse_case(kind, inputs, answer).ok()?;
    Some(CorpusEntry {
        kind,
        case,
        answer,
        band,
    })
}

/// The embedded regression corpus: about 1000 box, triangle and plane cases
/// in both precisions (a sample of the repository's corpus), each decided in
/// exact arithmetic and placed in or out of the rounding band, built around
/// faces, edges, corners, slivers, grazing rays and extreme scales. Parsed
/// on each call (cheap next to judging).
///
/// ```
/// use rayhit::exact::{self, Band, CorpusCase, Verdict};
/// let mut clear = 0;
/// for case in exact::corpus() {
///     if let CorpusCase::F32(e) = case {
///         // The crate's own kernels get every clear box case right.
///         if let exact::Case::Box(ray, b, t_max) = e.case {
///             let claim = match rayhit::ray_aabb(&ray, &b, t_max) {
///                 Some((enter, exit)) => exact::Claim::Box { enter, exit },
///                 None => exact::Claim::Miss,
///             };
///             let j = exact::judge(&e.case, &claim, f64::INFINITY);
///             assert!(e.band == Band::Edge || j.verdict == Verdict::Right);
///             clear += usize::from(e.band == Band::Clear);
///         }
///     }
/// }
/// assert!(clear > 50);
/// ```
pub fn corpus() -> impl Iterator<Item = CorpusCase> {
    FILES.into_iter().flat_map(|(kind, text)| {
        let single = text.contains("_f32.txt");
        text.lines()
            .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
            .filter_map(move |l| {
                if single {
                    entry::<Vec3>(kind, l).map(CorpusCase::F32)
                } else {
                    entry::<DVec3>(kind, l).map(CorpusCase::F64)
                }
            })
    })
}

/// One instance question of the embedded corpus, with its exact answer.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum InstanceQuestion<V: Vector> {
    /// The world box of an object box.
    Box {
        /// The object box.
        object: Aabb<V>,
        /// The exact image of `object`, rounded outward: the smallest box
        /// of floats that contains it (see
        /// [`ImageBox::outward`](super::ImageBox::outward)). A box of
        /// floats contains the exact image exactly when it contains this
        /// one.
        image: Aabb<V>,
    },
    /// The world point of an object point.
    Point {
        /// The object point.
        object: V,
        /// Its exact image `M p + T`, each component rounded to nearest.
        image: V,
    },
}

/// An instance case of the embedded corpus: the transform (the matrix's
/// columns, glam's convention, and the translation; every one builds an
/// [`Instance`](crate::Instance)) and the question with its exact answer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InstanceCorpusEntry<V: Vector> {
    /// The columns of `M`.
    pub columns: [V; 3],
    /// `T`.
    pub translation: V,
    /// The question and its exact answer.
    pub question: InstanceQuestion<V>,
}

/// An instance case in either precision.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum InstanceCorpusCase {
    /// Single precision.
    F32(InstanceCorpusEntry<Vec3>),
    /// Double precision.
    F64(InstanceCorpusEntry<DVec3>),
}

const INSTANCE_FILES: [(&str, &str); 4] = [
    ("box", include_str!("data/instance_box_f32.txt")),
    ("box", include_str!("data/instance_box_f64.txt")),
    ("point", include_str!("data/instance_point_f32.txt")),
    ("point", include_str!("data/instance_point_f64.txt")),
];

fn instance_entry<V: Vector>(kind: &str, line: &str) -> Option<InstanceCorpusEntry<V>> {
    let (inputs, answer) = line.split_once('|')?;
    let n: Vec<V::Scalar> = inputs
        .split_whitespace()
        .map(hex)
        .collect::<Result<_, _>>()
        .ok()?;
    let a: Vec<V::Scalar> = answer
        .split_whitespace()
        .map(hex)
        .collect::<Result<_, _>>()
        .ok()?;
    let v = |x: &[V::Scalar], i: usize| V::new(x[i], x[i + 1], x[i + 2]);
    let question = match (kind, n.len(), a.len()) {
        ("box", 18, 6) => InstanceQuestion::Box {
            object: Aabb::new(v(&n, 12), v(&n, 15)),
            image: Aabb::new(v(&a, 0), v(&a, 3)),
        },
        ("point", 15, 3) => InstanceQuestion::Point {
            object: v(&n, 12),
            image: v(&a, 0),
        },
        _ => return None,
    };
    Some(InstanceCorpusEntry {
        columns: [v(&n, 0), v(&n, 3), v(&n, 6)],
        translation: v(&n, 9),
        question,
    })
}

/// The embedded instance corpus: about 340 cases in both precisions (a
/// sample of the repository's), each a transform (rotations, scales from
/// `1e-3` to `1e3`, shears, translations up to `1e5`, and exact signed
/// permutations with power-of-two scales) with an object box (ordinary,
/// flat, a point, tiny and far away, with `-0.0` corners) or an object
/// point, and its exact image: the box rounded outward, the point rounded
/// to nearest. Parsed on each call.
///
/// ```
/// use rayhit::exact::{self, InstanceCorpusCase, InstanceQuestion};
/// use rayhit::Instance;
/// let mut boxes = 0;
/// for case in exact::instance_corpus() {
///     if let InstanceCorpusCase::F32(e) = case {
///         let inst = Instance::new(e.columns, e.translation).unwrap();
///         if let InstanceQuestion::Box { object, image } = e.question {
///             // The crate's world box contains the exact image.
///             let world = inst.object_to_world_box(&object).unwrap();
///             assert!(world.min.cmple(image.min).all() && image.max.cmple(world.max).all());
///             boxes += 1;
///         }
///     }
/// }
/// assert!(boxes > 50);
/// ```
pub fn instance_corpus() -> impl Iterator<Item = InstanceCorpusCase> {
    INSTANCE_FILES.into_iter().flat_map(|(kind, text)| {
        let single = text.contains("_f32.txt");
        text.lines()
            .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
            .filter_map(move |l| {
                if single {
                    instance_entry::<Vec3>(kind, l).map(InstanceCorpusCase::F32)
                } else {
                    instance_entry::<DVec3>(kind, l).map(InstanceCorpusCase::F64)
                }
            })
    })
}
