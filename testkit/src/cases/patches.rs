//! Bilinear patch cases: a patch, a ray aimed at a point of it and a
//! `t_max`; and the shapes, places and directions they are made of (the
//! `patch` fuzz target's structured inputs too).

use rayhit::{Patch, Ray, Scalar, Vector};

use super::quads::near;
use super::{Generator, S, add, aimed, c, scaled, t_max, v};
use crate::source::Source;

/// One patch case: the patch, the ray and `t_max`.
pub type PatchCase<V> = (Patch<V>, Ray<V>, S<V>);

/// A patch's corners in `f64`, in the order `p00, p10, p01, p11`.
pub type Corners = [[f64; 3]; 4];

/// Every patch family of the corpus, with its seed.
pub fn generators<V: Vector>() -> [Generator<PatchCase<V>>; 5] {
    [
        ("patch twisted", 61, twisted_case::<V>),
        ("patch shapes", 62, shapes::<V>),
        ("patch folds", 63, folds::<V>),
        ("patch degenerate", 64, degenerate::<V>),
        ("patch near ends", 65, near_ends::<V>),
    ]
}

/// The patch oracle test's cases: a square of side `s` (`1e-3` to `1e3`)
/// in any orientation, its corners raised off its plane by up to `0.4 s`
/// each (some of them folded as seen from the ray), centred up to `1e5`
/// from the origin (`0`, `1e2` or `1e5` times a uniform offset); a ray
/// aimed at the rounded point `P(u0, v0)`, `(u0, v0)` uniform in `[-0.1,
/// 1.1]^2`, from `1` to `100` sizes away in any direction, or a quarter
/// of the time nearly along the patch (within `0.05` of an edge's
/// direction), its direction the offset back to that point; and `(u0,
/// v0)`.
pub fn twisted<V: Vector>(src: &mut Source) -> (Patch<V>, Ray<V>, [f64; 2]) {
    let size = 10f64.powf(src.range(-3.0, 3.0));
    let reach = [0.0, 1e2, 1e5][src.index(3)];
    let centre = [0; 3].map(|_| reach * src.range(-1.0, 1.0));
    let (e1, n) = (src.direction(), src.direction());
    // An orthonormal-ish frame: e2 = n x e1 (not normalised; any
    // non-degenerate square will do).
    let e2 = cross(n, e1);
    let mut corner = |a: f64, b: f64| {
        let h = 0.4 * src.range(-1.0, 1.0);
        v::<V>([0, 1, 2].map(|k| centre[k] + size * (a * e1[k] + b * e2[k] + h * n[k])))
    };
    let patch = Patch::new(
        corner(-0.5, -0.5),
        corner(0.5, -0.5),
        corner(-0.5, 0.5),
        corner(0.5, 0.5),
    );
    let w = [0, 1].map(|_| 0.5 + 0.6 * src.range(-1.0, 1.0));
    let f = S::<V>::from_f64;
    let target = patch.point_at(f(w[0]), f(w[1]));
    let away = if src.one_in(4) {
        // Nearly along the patch.
        let t = 0.05 * src.range(-1.0, 1.0);
        [0, 1, 2].map(|k| e1[k] + t * n[k])
    } else {
        src.direction()
    };
    let dist = size * 10f64.powf(2.0 * src.unit());
    let origin = target + v::<V>(away) * f(dist);
    (patch, Ray::new(origin, target - origin), w)
}

/// [`twisted`], and [`t_max`].
pub fn twisted_case<V: Vector>(src: &mut Source) -> PatchCase<V> {
    let (patch, ray, _) = twisted(src);
    (patch, ray, t_max::<V>(src))
}

/// Four corners around a centre in `[-64, 64]^3`, `2^-3` to `2^3` across:
/// a parallelogram with its fourth corner lifted off the plane (twisted,
/// from a hair to twice its size), a saddle, four corners on a dyadic grid
/// of `1/64` (planar or not, bow ties among them), or four points in a box.
pub fn corners(src: &mut Source) -> Corners {
    let centre = [0; 3].map(|_| src.range(-64.0, 64.0));
    let size = src.log2_range(-3.0, 3.0);
    let at = |q: [f64; 3]| add(centre, q);
    match src.index(4) {
        0 => {
            let e1 = scaled(src.direction(), size * src.range(0.25, 1.0));
            let e2 = scaled(src.direction(), size * src.range(0.25, 1.0));
            let lift = scaled(src.direction(), size * src.log2_range(-24.0, 1.0));
            [
                at([0.0; 3]),
                at(e1),
                at(e2),
                at([0, 1, 2].map(|k| e1[k] + e2[k] + lift[k])),
            ]
        }
        1 => {
            // `z = h x y` over `[-1, 1]^2`, in a random frame.
            let (a, b) = frame(src);
            let n = cross(a, b);
            let h = src.range(-2.0, 2.0);
            let corner = |x: f64, y: f64| {
                at([0, 1, 2].map(|k| size * (x * a[k] + y * b[k] + h * x * y * n[k])))
            };
            [
                corner(-1.0, -1.0),
                corner(1.0, -1.0),
                corner(-1.0, 1.0),
                corner(1.0, 1.0),
            ]
        }
        2 => grid(src),
        _ => [0; 4].map(|_| at([0; 3].map(|_| size * src.range(-1.0, 1.0)))),
    }
}

/// Four corners on a dyadic grid of `1/64` within `[-64, 64]^3` (exact in
/// both precisions, and so their sums and differences).
fn grid(src: &mut Source) -> Corners {
    let mut g = || f64::from(src.below(8192) as i32 - 4096) / 64.0;
    [0; 4].map(|_| [g(), g(), g()])
}

/// Two orthonormal vectors.
fn frame(src: &mut Source) -> ([f64; 3], [f64; 3]) {
    let a = src.direction();
    let m = src.direction();
    let b = cross(a, m);
    let len = dot(b, b).sqrt();
    if len > 1e-3 {
        (a, b.map(|x| x / len))
    } else {
        ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0])
    }
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Where to aim, `(u, v)`: a corner, a point of an edge, the interior, a
/// dyadic point of a diagonal, around the patch, or just off an edge.
pub fn place(src: &mut Source) -> (f64, f64) {
    let end = |src: &mut Source| f64::from(src.below(2));
    let swap = |src: &mut Source, (a, b): (f64, f64)| if src.one_in(2) { (a, b) } else { (b, a) };
    match src.index(6) {
        0 => (end(src), end(src)),
        1 => {
            let e = end(src);
            let along = if src.one_in(2) {
                src.unit()
            } else {
                f64::from(src.below(9)) / 8.0
            };
            swap(src, (e, along))
        }
        2 => (src.unit(), src.unit()),
        3 => {
            let k = f64::from(src.below(9)) / 8.0;
            if src.one_in(2) { (k, k) } else { (k, 1.0 - k) }
        }
        4 => (src.range(-0.25, 1.25), src.range(-0.25, 1.25)),
        _ => {
            let off = src.log2_range(-40.0, -10.0);
            let e = if src.one_in(2) { 1.0 + off } else { -off };
            let along = src.unit();
            swap(src, (e, along))
        }
    }
}

/// `P(u, v)` in `f64`.
pub fn bilinear(p: &Corners, u: f64, v: f64) -> [f64; 3] {
    [0, 1, 2].map(|k| {
        (1.0 - u) * (1.0 - v) * p[0][k]
            + u * (1.0 - v) * p[1][k]
            + (1.0 - u) * v * p[2][k]
            + u * v * p[3][k]
    })
}

/// The normal `dP/du x dP/dv` at `(u, v)` (clamped into the unit square),
/// in `f64`, not normalised.
fn normal(p: &Corners, u: f64, w: f64) -> [f64; 3] {
    let (u, w) = (u.clamp(0.0, 1.0), w.clamp(0.0, 1.0));
    let du = [0, 1, 2].map(|k| (1.0 - w) * (p[1][k] - p[0][k]) + w * (p[3][k] - p[2][k]));
    let dv = [0, 1, 2].map(|k| (1.0 - u) * (p[2][k] - p[0][k]) + u * (p[3][k] - p[1][k]));
    cross(du, dv)
}

/// A direction grazing the tangent plane at `(u, v)`: uniform, then
/// tilted out of that plane by `2^lo` to `2^hi` radians (about), either
/// way; uniform where the normal there is zero.
fn grazing(src: &mut Source, p: &Corners, u: f64, w: f64, (lo, hi): (f64, f64)) -> [f64; 3] {
    let n = normal(p, u, w);
    let d = src.direction();
    let nl = dot(n, n).sqrt();
    if !(nl > 0.0) {
        return d;
    }
    let dn = dot(d, n) / nl;
    let tilt = src.log2_range(lo, hi) * src.sign();
    [0, 1, 2].map(|k| d[k] - (dn - tilt) * n[k] / nl)
}

/// A direction: uniform (length `2^-6` to `2^6`), the crate's strategy
/// (axis-parallel and signed zeros among them), along an axis, or grazing
/// the tangent plane at `(u, v)` (tilted `2^-24` to `2^-8` out of it).
pub fn direction(src: &mut Source, p: &Corners, u: f64, w: f64) -> [f64; 3] {
    match src.index(4) {
        0 => scaled(src.direction(), src.pow2(-6, 6)),
        1 => c(super::direction::<rayhit::glam::DVec3>(src)),
        2 => {
            let mut d = [0.0; 3];
            d[src.index(3)] = src.sign();
            d
        }
        _ => grazing(src, p, u, w, (-24.0, -8.0)),
    }
}

/// Where a case is put: its points scaled about the origin, then moved.
struct Placement {
    scale: f64,
    offset: [f64; 3],
}

impl Placement {
    /// Scaled by `10^-3` to `10^3` and moved `0`, `1e2` or `1e5` times a
    /// uniform offset away.
    fn new(src: &mut Source) -> Self {
        let scale = 10f64.powf(src.range(-3.0, 3.0));
        let reach = [0.0, 1e2, 1e5][src.index(3)];
        let offset = [0; 3].map(|_| reach * src.range(-1.0, 1.0));
        Self { scale, offset }
    }

    /// The point `q` put there, in `f64`.
    fn at(&self, q: [f64; 3]) -> [f64; 3] {
        add(scaled(q, self.scale), self.offset)
    }

    /// The patch with corners `p` put there (each rounded once), and a ray
    /// aimed at `target` along `dir` (both put there) from `s` direction
    /// lengths back.
    fn case<V: Vector>(
        &self,
        p: &Corners,
        target: [f64; 3],
        dir: [f64; 3],
        s: f64,
    ) -> (Patch<V>, Ray<V>) {
        let [p00, p10, p01, p11] = p.map(|q| v::<V>(self.at(q)));
        let ray = aimed::<V>(self.at(target), scaled(dir, self.scale), s);
        (Patch::new(p00, p10, p01, p11), ray)
    }
}

/// A [`corners`] shape, aimed at by [`place`] and [`direction`] from
/// `2^-2` to `2^4` direction lengths back, scaled by `10^-3` to `10^3`
/// and moved up to `1e5` away; and [`t_max`].
pub fn shapes<V: Vector>(src: &mut Source) -> PatchCase<V> {
    let p = corners(src);
    let (u, w) = place(src);
    let target = bilinear(&p, u, w);
    let dir = direction(src, &p, u, w);
    let s = src.log2_range(-2.0, 4.0);
    let (patch, ray) = Placement::new(src).case(&p, target, dir, s);
    (patch, ray, t_max::<V>(src))
}

/// Folds and silhouettes: a [`corners`] shape that is not a
/// parallelogram, and a ray grazing its tangent plane at an interior point
/// (`(u, v)` in `[0.1, 0.9]^2`; tilted `2^-24` to `2^-1` out of the
/// plane), aimed at that point or at a point moved off the surface along
/// the normal by `2^-30` to `2^-4` of its size either way (lines that meet
/// a fold twice, touch it, or pass just by it), from `2^-2` to `2^4`
/// direction lengths back; scaled by `10^-3` to `10^3` and moved up to
/// `1e5` away; and [`t_max`].
pub fn folds<V: Vector>(src: &mut Source) -> PatchCase<V> {
    let p = loop {
        let p = corners(src);
        let twist = [0, 1, 2].map(|k| p[3][k] - p[2][k] - p[1][k] + p[0][k]);
        if dot(twist, twist) > 0.0 || src.bits() == 0 {
            break p;
        }
    };
    let (u, w) = (src.range(0.1, 0.9), src.range(0.1, 0.9));
    let mut target = bilinear(&p, u, w);
    if src.one_in(2) {
        let n = normal(&p, u, w);
        let size = dot(
            [0, 1, 2].map(|k| p[3][k] - p[0][k]),
            [0, 1, 2].map(|k| p[3][k] - p[0][k]),
        )
        .sqrt();
        let nl = dot(n, n).sqrt();
        if nl > 0.0 {
            let off = size * src.log2_range(-30.0, -4.0) * src.sign() / nl;
            target = add(target, scaled(n, off));
        }
    }
    let dir = grazing(src, &p, u, w, (-24.0, -1.0));
    let s = src.log2_range(-2.0, 4.0);
    let (patch, ray) = Placement::new(src).case(&p, target, dir, s);
    (patch, ray, t_max::<V>(src))
}

/// Degenerate patches, as their definition says: a collapsed edge (one
/// corner of a [`corners`] shape copied onto a neighbour: the triangle of
/// the other three), or an exact planar parallelogram (corners on the
/// dyadic grid, `p11 = p10 + p01 - p00`), aimed at by [`place`] and
/// [`direction`] from `2^-2` to `2^4` direction lengths back; the
/// parallelogram scaled by `2^-10` to `2^10` and moved by up to `2^16`
/// (whole numbers) on each axis, both exact, the collapsed patch scaled
/// and moved as [`shapes`]; and [`t_max`].
pub fn degenerate<V: Vector>(src: &mut Source) -> PatchCase<V> {
    let (p, put) = if src.one_in(2) {
        let mut p = grid(src);
        p[3] = [0, 1, 2].map(|k| p[1][k] + p[2][k] - p[0][k]);
        let scale = src.pow2(-10, 10);
        let offset = [0; 3].map(|_| f64::from(src.below(1 << 17) as i32 - (1 << 16)));
        (p, Placement { scale, offset })
    } else {
        let mut p = corners(src);
        match src.index(4) {
            0 => p[3] = p[2],
            1 => p[1] = p[0],
            2 => p[2] = p[0],
            _ => p[3] = p[1],
        }
        (p, Placement::new(src))
    };
    let (u, w) = place(src);
    let target = bilinear(&p, u, w);
    let dir = direction(src, &p, u, w);
    let s = src.log2_range(-2.0, 4.0);
    let (patch, ray) = put.case(&p, target, dir, s);
    (patch, ray, t_max::<V>(src))
}

/// The ends of the range: a [`corners`] shape aimed at an interior point
/// (`(u, v)` in `[0.05, 0.95]^2`), from within `2^-40` to `2^-8`
/// direction lengths of it (the origin on the surface, up to a rounding,
/// in front of it or behind), or from `2^0.5` to `2^6` back with `t_max`
/// at the crossing's `t` computed in `f64` (rounded) or up to four floats
/// either side of it; scaled by `10^-3` to `10^3` and moved up to `1e5`
/// away.
pub fn near_ends<V: Vector>(src: &mut Source) -> PatchCase<V> {
    let p = corners(src);
    let (u, w) = (src.range(0.05, 0.95), src.range(0.05, 0.95));
    let target = bilinear(&p, u, w);
    let dir = direction(src, &p, u, w);
    let put = Placement::new(src);
    if src.one_in(2) {
        let s = src.log2_range(-40.0, -8.0) * src.sign();
        let (patch, ray) = put.case(&p, target, dir, s);
        (patch, ray, S::<V>::INFINITY)
    } else {
        let s = src.log2_range(0.5, 6.0);
        let (patch, ray) = put.case(&p, target, dir, s);
        (patch, ray, near::<V>(src, s))
    }
}
