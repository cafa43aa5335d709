//! The embedded regression corpus.

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

fn hex<F: Scalar>(s: &str) -> Option<F> {
    Some(match s.len() {
        8 => F::from_f64(f64::from(f32::from_bits(u32::from_str_radix(s, 16).ok()?))),
        _ => F::from_f64(f64::from_bits(u64::from_str_radix(s, 16).ok()?)),
    })
}

fn entry<V: Vector>(kind: &'static str, line: &str) -> Option<CorpusEntry<V>> {
    let mut parts = line.split('|').map(str::trim);
    let n: Vec<V::Scalar> = parts
        .next()?
        .split_whitespace()
        .map(hex)
        .collect::<Option<_>>()?;
    let a: Vec<&str> = parts.next()?.split_whitespace().collect();
    let band = if parts.next()? == "clear" {
        Band::Clear
    } else {
        Band::Edge
    };
    let v = |i: usize| V::new(n[i], n[i + 1], n[i + 2]);
    let x = |i: usize| a.get(i).and_then(|s| hex::<V::Scalar>(s));
    let hit = a.first() == Some(&"hit");
    let ray = Ray::new(v(0), v(3));
    let (case, answer) = match kind {
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
    };
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
