//! `proptest` strategies for rays and shapes, built to land near boundaries.
//!
//! Enabled by the `proptest` feature. These are the generators the crate's
//! own property tests use; downstream renderers can use them to test their
//! own kernels against this crate's. Every strategy is generic over the
//! precision (`Vec3` or `DVec3`): values are drawn in `f64` and rounded once
//! to the target precision.
//!
//! Rays are *aimed*: a strategy picks a target point (inside a shape, on its
//! boundary, or just outside) and then an origin behind it, so hits and
//! misses are both common and many rays pass through edges, corners and
//! faces, where kernels go wrong. A target on a boundary is rounded like any
//! other point, so "on an edge" means within an ulp or so of it. Rays at
//! spheres also run along tangents (grazing) and start inside the ball;
//! rays at discs aim at their circles, run nearly along their plane and
//! start on it.
//!
//! Ranges, and why:
//! - coordinates: shape centres in `[-64, 64]^3`, sizes (a sphere's
//!   and a disc's radius among them) from `2^-4` to `2^4`: a few orders of magnitude of
//!   scale and of distance from the origin, all well inside the range
//!   where no kernel overflows;
//! - directions: random orientation, length `2^k` for `k` in `[-6, 6]`
//!   (powers of two, so scaling tests stay exact), with one case in eight
//!   axis-parallel and one in eight with a zero (`+0.0` or `-0.0`)
//!   component, because those are the slab test's special cases;
//! - origins: the target minus `s * dir` with `s` from `2^-4` to `2^6`;
//! - `t_max`: infinite half the time, else uniform in `[0, 128]`.
//!
//! Every choice among cases is made from uniform floats and booleans, never
//! by drawing an integer in a range (which rejects and redraws), so the
//! strategies also run on a fuzzer's bytes through proptest's
//! `RngAlgorithm::PassThrough`, which hands out the bytes as they are and
//! then zeros.
//!
//! ```
//! use proptest::prelude::*;
//! use rayhit::{Aabb, Ray, ray_aabb, glam::Vec3, strategies};
//!
//! proptest!(|((aabb, ray) in strategies::aabb_and_ray::<Vec3>())| {
//!     if let Some((enter, exit)) = ray_aabb(&ray, &aabb, f32::INFINITY) {
//!         prop_assert!(0.0 <= enter && enter <= exit);
//!     }
//! });
//! ```

use proptest::prelude::*;

use crate::num::{S, Scalar, Vector};
use crate::{Aabb, Disc, Plane, Ray, Sphere, Triangle};

/// A value uniform in `[-scale, scale]`, rounded to the precision of `V`.
pub fn coordinate<V: Vector>(scale: f64) -> impl Strategy<Value = S<V>> + Clone {
    (-scale..=scale).prop_map(S::<V>::from_f64)
}

/// A point with each coordinate uniform in `[-scale, scale]`.
pub fn point<V: Vector>(scale: f64) -> impl Strategy<Value = V> + Clone {
    (
        coordinate::<V>(scale),
        coordinate::<V>(scale),
        coordinate::<V>(scale),
    )
        .prop_map(|(x, y, z)| V::new(x, y, z))
}

/// `2^k` for `k` uniform in `[lo, hi]`: an exact scale factor.
pub fn power_of_two(lo: i32, hi: i32) -> impl Strategy<Value = f64> + Clone {
    index(lo.abs_diff(hi) as usize + 1).prop_map(move |k| 2f64.powi(lo.min(hi) + k as i32))
}

/// An index uniform in `[0, n)`, from one uniform float (for `n >= 1`).
fn index(n: usize) -> impl Strategy<Value = usize> + Clone {
    (0.0..1.0f64).prop_map(move |x| ((x * n as f64) as usize).min(n - 1))
}

/// One of `weights.len()` cases, case `i` with probability `weights[i] /
/// sum`, from one uniform float.
fn case<const N: usize>(weights: [u32; N]) -> impl Strategy<Value = usize> + Clone {
    let total: u32 = weights.iter().sum();
    (0.0..1.0f64).prop_map(move |x| {
        let mut below = x * f64::from(total);
        for (i, &w) in weights.iter().enumerate() {
            if below < f64::from(w) {
                return i;
            }
            below -= f64::from(w);
        }
        N - 1
    })
}

/// `+0.0` or `-0.0`.
fn signed_zero(negative: bool) -> f64 {
    if negative { -0.0 } else { 0.0 }
}

/// A nonzero direction: random orientation (6 in 8), axis-parallel (1 in 8,
/// the other components `+0.0` or `-0.0`), or random with one component
/// `+0.0` or `-0.0` (1 in 8); length `2^k` times a factor in `[0.2, 1]` for
/// the random ones, `k` in `[-6, 6]`.
pub fn direction<V: Vector>() -> impl Strategy<Value = V> + Clone {
    let cube = (-1.0..=1.0f64, -1.0..=1.0f64, -1.0..=1.0f64);
    (
        case([6, 1, 1]),
        cube,
        index(3),
        any::<[bool; 3]>(),
        power_of_two(-6, 6),
    )
        .prop_filter_map("direction too short", |(kind, (x, y, z), k, b, s)| {
            let c = match kind {
                0 => {
                    if x * x + y * y + z * z <= 0.04 {
                        return None;
                    }
                    [x * s, y * s, z * s]
                }
                1 => {
                    let mut c = [signed_zero(b[1]), signed_zero(b[2]), 0.0];
                    c.rotate_right(k + 1);
                    c[k] = if b[0] { -s } else { s };
                    c
                }
                _ => {
                    let c = [x, y, z];
                    let (a, d) = (c[(k + 1) % 3], c[(k + 2) % 3]);
                    if a * a + d * d <= 0.04 {
                        return None;
                    }
                    let mut c = c.map(|x| x * s);
                    c[k] = signed_zero(b[1]);
                    c
                }
            };
            Some(V::new(cv::<V>(c[0]), cv::<V>(c[1]), cv::<V>(c[2])))
        })
}

fn cv<V: Vector>(x: f64) -> S<V> {
    S::<V>::from_f64(x)
}

/// A ray aimed at `target`: direction from [`direction`], origin
/// `target - s * dir` with `s` uniform in `[2^-4, 2^6]` (rounded), so the
/// ray passes within rounding of `target` near `t = s`.
pub fn ray_through<V: Vector>(target: V) -> impl Strategy<Value = Ray<V>> + Clone {
    (direction::<V>(), 0.0625..=64.0f64)
        .prop_map(move |(dir, s)| Ray::new(target - dir * cv::<V>(s), dir))
}

/// `t_max`: `+inf` half the time, else uniform in `[0, 128]`.
pub fn t_max<V: Vector>() -> impl Strategy<Value = S<V>> + Clone {
    (any::<bool>(), 0.0..=128.0f64)
        .prop_map(|(inf, x)| if inf { S::<V>::INFINITY } else { cv::<V>(x) })
}

/// A valid box: centre in `[-64, 64]^3`, half extent per axis `2^k` with
/// `k` uniform in `[-4, 4]`, or zero thickness on an axis one time in eight.
pub fn aabb<V: Vector>() -> impl Strategy<Value = Aabb<V>> + Clone {
    let half = (case([7, 1]), -4.0..=4.0f64)
        .prop_map(|(kind, k)| if kind == 0 { 2f64.powf(k) } else { 0.0 });
    (point::<V>(64.0), half.clone(), half.clone(), half).prop_map(|(c, hx, hy, hz)| {
        let h = V::new(cv::<V>(hx), cv::<V>(hy), cv::<V>(hz));
        // Round min down and max up by construction: c - h and c + h are
        // rounded, but min <= max holds because h >= 0.
        Aabb::new(c - h, c + h)
    })
}

/// A target for a ray at `b`: a point in the box grown by half its size on
/// each side (so about a third of the time inside), on a face, on an edge,
/// or at a corner (one time in four each for the last three together).
pub fn aabb_target<V: Vector>(b: Aabb<V>) -> impl Strategy<Value = V> + Clone {
    // A coordinate per axis as a fraction of the way from min to max.
    let lerp = move |f: [f64; 3]| {
        let c = |k: usize| {
            let (lo, hi) = (b.min[k].to_f64(), b.max[k].to_f64());
            cv::<V>(lo + (hi - lo) * f[k])
        };
        V::new(c(0), c(1), c(2))
    };
    let frac = -0.5..=1.5f64;
    // Inside (3 in 4); else 1, 2 or 3 coordinates fixed to a side: a face,
    // an edge, a corner.
    (
        case([3, 1]),
        (frac.clone(), frac.clone(), frac),
        index(3),
        index(3),
        any::<[bool; 3]>(),
        (0.0..=1.0f64, 0.0..=1.0f64),
    )
        .prop_map(move |(kind, (x, y, z), fixed, k, sides, (f1, f2))| {
            if kind == 0 {
                return lerp([x, y, z]);
            }
            let mut f = [f1, f2, 0.5];
            f.rotate_right(k);
            for (i, side) in sides.iter().enumerate().take(fixed + 1) {
                f[(k + i) % 3] = if *side { 1.0 } else { 0.0 };
            }
            lerp(f)
        })
}

/// A box and a ray aimed at it by [`aabb_target`] and [`ray_through`].
pub fn aabb_and_ray<V: Vector>() -> impl Strategy<Value = (Aabb<V>, Ray<V>)> + Clone {
    aabb::<V>().prop_flat_map(|b| (Just(b), aabb_target(b).prop_flat_map(ray_through)))
}

/// A non-degenerate triangle: centre in `[-64, 64]^3`, corners at offsets of
/// length `2^k`, `k` uniform in `[-3, 3]`, in random directions; one time in
/// eight a long thin one (the third corner within 1% of the first edge).
pub fn triangle<V: Vector>() -> impl Strategy<Value = Triangle<V>> + Clone {
    let offset = (direction::<V>(), power_of_two(-3, 3)).prop_map(|(d, s)| {
        let len = d.length().to_f64();
        d * cv::<V>(s / len)
    });
    (
        case([7, 1]),
        point::<V>(64.0),
        (offset.clone(), offset.clone(), offset),
        0.0..=1.0f64,
        -0.01..=0.01f64,
    )
        .prop_map(|(kind, c, (a, b, d), along, across)| {
            if kind == 0 {
                return Triangle::new(c + a, c + b, c + d);
            }
            // Long and thin: the third corner within 1% of the first edge.
            let (pa, pb) = (c + a, c + b);
            let e = pb - pa;
            let side = e.cross(V::new(cv::<V>(0.6), cv::<V>(0.8), cv::<V>(0.0)));
            let side = if side.length().to_f64() > 0.0 {
                side
            } else {
                e.cross(V::new(cv::<V>(0.0), cv::<V>(0.6), cv::<V>(0.8)))
            };
            let scale = e.length().to_f64() / side.length().to_f64();
            Triangle::new(
                pa,
                pb,
                pa + e * cv::<V>(along) + side * cv::<V>(across * scale),
            )
        })
        .prop_filter("degenerate triangle", |t| {
            let n = t.normal();
            n.is_finite() && n.length().to_f64() > 0.0
        })
}

/// A target for a ray at `t`: a point `a + u (b - a) + v (c - a)` with `u, v`
/// in `[-0.25, 1]` (inside about a third of the time), on an edge, or at a
/// corner (one time in four together). Evaluated in `f64` and rounded once.
pub fn triangle_target<V: Vector>(t: Triangle<V>) -> impl Strategy<Value = V> + Clone {
    let at = move |u: f64, v: f64| {
        let c = |k: usize| {
            let (a, b, c) = (t.a[k].to_f64(), t.b[k].to_f64(), t.c[k].to_f64());
            cv::<V>(a + u * (b - a) + v * (c - a))
        };
        V::new(c(0), c(1), c(2))
    };
    // Inside or near (6 in 8), on an edge (1 in 8), at a corner (1 in 8).
    (
        case([6, 1, 1]),
        -0.25..=1.0f64,
        -0.25..=1.0f64,
        index(3),
        0.0..=1.0f64,
    )
        .prop_map(move |(kind, u, v, k, s)| match (kind, k) {
            (0, _) => at(u, v),
            (1, 0) => at(s, 0.0),
            (1, 1) => at(0.0, s),
            (1, _) => at(s, 1.0 - s),
            (_, 0) => at(0.0, 0.0),
            (_, 1) => at(1.0, 0.0),
            _ => at(0.0, 1.0),
        })
}

/// A triangle and a ray aimed at it by [`triangle_target`] and
/// [`ray_through`].
pub fn triangle_and_ray<V: Vector>() -> impl Strategy<Value = (Triangle<V>, Ray<V>)> + Clone {
    triangle::<V>().prop_flat_map(|t| (Just(t), triangle_target(t).prop_flat_map(ray_through)))
}

/// A plane: a point in `[-64, 64]^3` and a normal from [`direction`].
pub fn plane<V: Vector>() -> impl Strategy<Value = Plane<V>> + Clone {
    (point::<V>(64.0), direction::<V>()).prop_map(|(p, n)| Plane::new(p, n))
}

/// A plane and a ray aimed at a point of it within 64 of its `point`, the
/// point computed in `f64` and rounded.
pub fn plane_and_ray<V: Vector>() -> impl Strategy<Value = (Plane<V>, Ray<V>)> + Clone {
    (plane::<V>(), -64.0..=64.0f64, -64.0..=64.0f64).prop_flat_map(|(pl, s, t)| {
        let n = [
            pl.normal.x().to_f64(),
            pl.normal.y().to_f64(),
            pl.normal.z().to_f64(),
        ];
        // Two tangents: n x (axis of n's smallest component), and n x that.
        let k = (0..3)
            .min_by(|&i, &j| n[i].abs().total_cmp(&n[j].abs()))
            .unwrap_or(0);
        let mut axis = [0.0; 3];
        axis[k] = 1.0;
        let t1 = unit(cross(n, axis));
        let t2 = unit(cross(n, t1));
        let c = |i: usize| cv::<V>(pl.point[i].to_f64() + s * t1[i] + t * t2[i]);
        (Just(pl), ray_through(V::new(c(0), c(1), c(2))))
    })
}

/// A sphere: centre in `[-64, 64]^3`, radius `2^x` with `x` uniform in
/// `[-4, 4]` (positive, and a power of two only by chance).
pub fn sphere<V: Vector>() -> impl Strategy<Value = Sphere<V>> + Clone {
    (point::<V>(64.0), -4.0..=4.0f64).prop_map(|(c, x)| Sphere::new(c, cv::<V>(x.exp2())))
}

/// A sphere from [`sphere`] and a ray at it, one of three kinds:
///
/// - aimed (half the time) at a target on the sphere, inside the ball (a
///   uniform fraction of the radius from the centre), just outside (a
///   relative `2^-24` to `2^-10` beyond the surface) or outside (one to
///   three radii from the centre), one time in four each, along a
///   [`direction`] from `2^-4` to `2^6` direction lengths back (as
///   [`ray_through`] aims): the line misses only where it passes a point
///   outside at enough of an angle; the origin may fall inside the ball;
/// - grazing (one time in four): along a tangent at a point of the sphere,
///   that point on the sphere one time in four, else moved off it, inward
///   or outward, by a relative `2^-24` to `2^-10`; the direction of length
///   `2^k` (`k` in `[-6, 6]`; axis-parallel where the tangent is), the
///   origin `2^-4` to `2^6` direction lengths back;
/// - from inside (one time in four): the origin up to `0.99` radii from
///   the centre, the direction from [`direction`].
///
/// Every point is computed in `f64` from the rounded sphere (an origin
/// behind a target, from the rounded direction) and rounded once, so "on
/// the sphere" means within an ulp or so of it, and an origin drawn
/// inside is inside exactly.
pub fn sphere_and_ray<V: Vector>() -> impl Strategy<Value = (Sphere<V>, Ray<V>)> + Clone {
    let draws = (
        0.0..1.0f64,
        -24.0..=-10.0f64,
        any::<bool>(),
        0.0625..=64.0f64,
    );
    (
        sphere::<V>(),
        case([2, 1, 1]),
        index(4),
        (direction::<V>(), direction::<V>()),
        draws,
        power_of_two(-6, 6),
    )
        .prop_map(|(sph, kind, reach, (a, b), (f, x, outward, back), len)| {
            let c = [0, 1, 2].map(|i| sph.center[i].to_f64());
            let r = sph.radius.to_f64();
            let n = unit([0, 1, 2].map(|i| a[i].to_f64()));
            let round = |p: [f64; 3]| V::new(cv::<V>(p[0]), cv::<V>(p[1]), cv::<V>(p[2]));
            // The point `scale` radii from the centre along `n`.
            let at = |scale: f64| round([0, 1, 2].map(|i| c[i] + r * scale * n[i]));
            // `s` lengths of `dir` back from `target`.
            let behind = |target: V, dir: V, s: f64| {
                round([0, 1, 2].map(|i| target[i].to_f64() - s * dir[i].to_f64()))
            };
            let off = if outward { x.exp2() } else { -x.exp2() };
            let ray = match kind {
                0 => {
                    let target = match reach {
                        0 => at(1.0),
                        1 => at(f),
                        2 => at(1.0 + x.exp2()),
                        _ => at(1.0 + 2.0 * f),
                    };
                    Ray::new(behind(target, b, back), b)
                }
                1 => {
                    // A tangent at the point: n x b, or n x (the axis of n's
                    // smallest component) where b is parallel to n.
                    let m = [0, 1, 2].map(|i| b[i].to_f64());
                    let mut t = cross(n, m);
                    if t.iter().map(|v| v * v).sum::<f64>() < 1e-6 {
                        let k = (0..3)
                            .min_by(|&i, &j| n[i].abs().total_cmp(&n[j].abs()))
                            .unwrap_or(0);
                        let mut axis = [0.0; 3];
                        axis[k] = 1.0;
                        t = cross(n, axis);
                    }
                    let dir = round(unit(t).map(|v| v * len));
                    let touch = at(if reach == 0 { 1.0 } else { 1.0 + off });
                    Ray::new(behind(touch, dir, back), dir)
                }
                _ => Ray::new(at(0.99 * f), b),
            };
            (sph, ray)
        })
}

/// A disc or an annulus: centre in `[-64, 64]^3`, normal from
/// [`direction`] (any orientation and length `2^-6` to `2^6`,
/// axis-parallel or with a signed-zero component one time in eight each),
/// outer radius `2^x` with `x` uniform in `[-4, 4]`; a full disc half the
/// time, else an annulus whose hole's radius is a uniform `0.1` to `0.9`
/// of the outer one (3 in 8), or a ring of no width, both radii equal (1
/// in 8: only its circle is hit).
pub fn disc<V: Vector>() -> impl Strategy<Value = Disc<V>> + Clone {
    (
        point::<V>(64.0),
        direction::<V>(),
        -4.0..=4.0f64,
        case([4, 3, 1]),
        // (A half-open unit range: proptest's sampler of an inclusive
        // range with ends such as 0.1 trips its own debug assertion on
        // some raw fuzzer bytes.)
        0.0..1.0f64,
    )
        .prop_map(|(c, n, x, kind, f)| {
            let r = x.exp2();
            let inner = match kind {
                0 => 0.0,
                1 => r * (0.1 + 0.8 * f),
                _ => r,
            };
            Disc::annulus(c, n, cv::<V>(r), cv::<V>(inner))
        })
}

/// A disc from [`disc`] and a ray at a target in its plane, `rho` from the
/// centre in a uniformly random direction within the plane, one time in
/// six each: on the outer circle, on the hole's circle (the centre for a
/// full disc), inside the annulus, in the hole, just off one of the
/// circles (a relative `2^-24` to `2^-10` in or out), or outside (one to
/// three radii). The ray, one of three kinds:
///
/// - from anywhere (5 in 8): a [`direction`], the origin `2^-4` to `2^6`
///   direction lengths back from the target (as [`ray_through`] aims);
/// - nearly along the plane (2 in 8): a direction within the plane tilted
///   out of it by a relative `2^-30` to `2^-8` (either way), of length
///   `2^k` (`k` in `[-6, 6]`), the origin `2^-4` to `2^6` lengths back;
/// - from the plane (1 in 8): the origin at the target itself (so within
///   rounding of the plane: the crossing is at `t` near zero, ahead or
///   behind), a [`direction`].
///
/// Every point is computed in `f64` from the rounded disc (an origin behind
/// a target, from the rounded direction) and rounded once, so "on a
/// circle" means within an ulp or so of it.
pub fn disc_and_ray<V: Vector>() -> impl Strategy<Value = (Disc<V>, Ray<V>)> + Clone {
    let target = (
        index(6),
        0.0..1.0f64,
        -24.0..=-10.0f64,
        any::<bool>(),
        any::<bool>(),
    );
    let aim = (
        case([5, 2, 1]),
        0.0..1.0f64,
        0.0..1.0f64,
        -30.0..=-8.0f64,
        any::<bool>(),
    );
    (
        disc::<V>(),
        target,
        aim,
        direction::<V>(),
        0.0625..=64.0f64,
        power_of_two(-6, 6),
    )
        .prop_map(
            |(d, (reach, f, x, outer, outward), (kind, theta, phi, y, up), dir, back, len)| {
                let c = [0, 1, 2].map(|i| d.center[i].to_f64());
                let (r, inner) = (d.radius.to_f64(), d.inner_radius.to_f64());
                let n = unit([0, 1, 2].map(|i| d.normal[i].to_f64()));
                // Two unit vectors within the plane: n x (the axis of n's
                // smallest component), and n x that.
                let k = (0..3)
                    .min_by(|&i, &j| n[i].abs().total_cmp(&n[j].abs()))
                    .unwrap_or(0);
                let mut axis = [0.0; 3];
                axis[k] = 1.0;
                let t1 = unit(cross(n, axis));
                let t2 = cross(n, t1);
                let within = |a: f64| {
                    let (s, co) = (a * core::f64::consts::TAU).sin_cos();
                    [0, 1, 2].map(|i| co * t1[i] + s * t2[i])
                };
                let u = within(theta);
                let off = if outward { x.exp2() } else { -x.exp2() };
                let rho = match reach {
                    0 => r,
                    1 => inner,
                    2 => inner + f * (r - inner),
                    3 => f * inner,
                    4 => (if outer { r } else { inner }) * (1.0 + off),
                    _ => r * (1.0 + 2.0 * f),
                };
                let round = |p: [f64; 3]| V::new(cv::<V>(p[0]), cv::<V>(p[1]), cv::<V>(p[2]));
                let target = [0, 1, 2].map(|i| c[i] + rho * u[i]);
                let behind = |dir: V| round([0, 1, 2].map(|i| target[i] - back * dir[i].to_f64()));
                let ray = match kind {
                    0 => Ray::new(behind(dir), dir),
                    1 => {
                        let v = within(phi);
                        let tilt = if up { y.exp2() } else { -y.exp2() };
                        let along = round([0, 1, 2].map(|i| (v[i] + tilt * n[i]) * len));
                        Ray::new(behind(along), along)
                    }
                    _ => Ray::new(round(target), dir),
                };
                (d, ray)
            },
        )
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn unit(a: [f64; 3]) -> [f64; 3] {
    let l = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
    [a[0] / l, a[1] / l, a[2] / l]
}

/// An object-to-world affine transform for an [`Instance`](crate::Instance):
/// the matrix's columns and the translation, `M = rotation * scale *
/// shear`, each part present three times in four.
///
/// Ranges, and why: rotations from a uniform unit quaternion; per-axis
/// scales from `1e-3` to `1e3` (uniform or independent per axis, each
/// mirrored one time in eight), which puts condition numbers up to `1e6`
/// in reach; shears up to 2 in each upper entry; translations zero, uniform
/// in `[-1e5, 1e5]^3`, or of magnitude `2^-10` to `1e5` in a random
/// direction. Build the instance with
/// [`Instance::new`](crate::Instance::new); these matrices are never
/// singular.
///
/// ```
/// use proptest::prelude::*;
/// use rayhit::{Instance, glam::DVec3, strategies};
///
/// proptest!(|((cols, t) in strategies::transform::<DVec3>())| {
///     prop_assert!(Instance::new(cols, t).is_ok());
/// });
/// ```
pub fn transform<V: Vector>() -> impl Strategy<Value = ([V; 3], V)> + Clone {
    let unit = || 0.0..1.0f64;
    let sym = || -1.0..=1.0f64;
    let parts = (unit(), unit(), unit());
    let quat = (sym(), sym(), sym(), sym());
    let scale = (
        unit(),
        -9.97..=9.97f64,
        [-9.97..=9.97f64, -9.97..=9.97, -9.97..=9.97],
        [unit(), unit(), unit()],
    );
    let shear = ([unit(), unit(), unit()], [sym(), sym(), sym()]);
    let translation = (unit(), [sym(), sym(), sym()], -10.0..=16.6f64);
    (parts, quat, scale, shear, translation).prop_map(
        |(
            (p_rot, p_scale, p_shear),
            q,
            (uniform, base, exps, mirrors),
            (shear_on, shears),
            (mode, dir, mag),
        )| {
            type M = [[f64; 3]; 3];
            let mul = |a: M, b: M| -> M {
                let mut c = [[0.0; 3]; 3];
                for (i, row) in c.iter_mut().enumerate() {
                    for (j, entry) in row.iter_mut().enumerate() {
                        *entry = (0..3).map(|k| a[i][k] * b[k][j]).sum();
                    }
                }
                c
            };
            let mut m: M = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
            if p_shear < 0.75 {
                let s = |k: usize| {
                    if shear_on[k] < 0.5 {
                        2.0 * shears[k]
                    } else {
                        0.0
                    }
                };
                m = mul([[1.0, s(0), s(1)], [0.0, 1.0, s(2)], [0.0, 0.0, 1.0]], m);
            }
            if p_scale < 0.75 {
                let k = |i: usize| {
                    let e = if uniform < 0.5 { base } else { exps[i] };
                    let k = e.exp2();
                    if mirrors[i] < 0.125 { -k } else { k }
                };
                m = mul([[k(0), 0.0, 0.0], [0.0, k(1), 0.0], [0.0, 0.0, k(2)]], m);
            }
            let (w, x, y, z) = q;
            let l = (w * w + x * x + y * y + z * z).sqrt();
            if p_rot < 0.75 && l > 0.1 {
                let (w, x, y, z) = (w / l, x / l, y / l, z / l);
                let rot = [
                    [
                        1.0 - 2.0 * (y * y + z * z),
                        2.0 * (x * y - w * z),
                        2.0 * (x * z + w * y),
                    ],
                    [
                        2.0 * (x * y + w * z),
                        1.0 - 2.0 * (x * x + z * z),
                        2.0 * (y * z - w * x),
                    ],
                    [
                        2.0 * (x * z - w * y),
                        2.0 * (y * z + w * x),
                        1.0 - 2.0 * (x * x + y * y),
                    ],
                ];
                m = mul(rot, m);
            }
            let t = if mode < 0.25 {
                [0.0; 3]
            } else if mode < 0.5 {
                dir.map(|c| c * 1e5)
            } else {
                let len = (dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]).sqrt();
                let s = if len > 1e-3 {
                    mag.exp2().min(1e5) / len
                } else {
                    0.0
                };
                dir.map(|c| c * s)
            };
            let v = |a: [f64; 3]| {
                V::new(
                    S::<V>::from_f64(a[0]),
                    S::<V>::from_f64(a[1]),
                    S::<V>::from_f64(a[2]),
                )
            };
            let cols = [0, 1, 2].map(|j| v([m[0][j], m[1][j], m[2][j]]));
            (cols, v(t))
        },
    )
}
