//! Zero-area triangles: `is_degenerate` against exact arithmetic, and
//! hits on them safe to use (no NaN in the hit point, the normal, its
//! error bound or a spawned ray).

use num_traits::Zero;
use proptest::prelude::*;
use rayhit::glam::{DVec3, Vec3};
use rayhit::{
    EdgeRule, Intersect, IntersectLanes, PreparedRay, Ray, Scalar, Surface, Triangle, Vector,
    batch::TriangleBatch, ray_triangle,
};
use rayhit_testkit::case_count;
use rayhit_testkit::cases;
use rayhit_testkit::oracle;
use rayhit_testkit::oracle::{cross, rv, sub};
use rayhit_testkit::source::Source;

type S<V> = <V as Vector>::Scalar;

/// The exact answer: `(b - a) x (c - a)` is the zero vector.
fn exactly_degenerate<V: Vector>(t: &Triangle<V>) -> bool {
    let (a, b, c) = (rv(t.a), rv(t.b), rv(t.c));
    cross(&sub(&b, &a), &sub(&c, &a)).iter().all(Zero::is_zero)
}

/// Triangles that are exactly collinear (on a dyadic grid, `c = a + k (b -
/// a)` with a small `k`, so the coordinates stay exact), coincident, one
/// ulp off collinear, tiny, huge, and ordinary.
///
/// Within the documented preconditions: coordinates below `2^60` (so that
/// `f32` cross products do not overflow; the kernels assume `2^63`), and a
/// coordinate one ulp off is bumped only where it is not zero (one ulp
/// above zero is the smallest subnormal, whose products with the other
/// differences underflow: `is_degenerate` documents that it is exact only
/// where they do not, as the `f64` exact-sign fallback does).
fn triangle<V: Vector>(rng: &mut Source) -> Triangle<V> {
    let scale = 2f64.powi(rng.below(114) as i32 - 60);
    let grid = |rng: &mut Source| (f64::from(rng.below(2048) as i32 - 1024) / 16.0) * scale;
    let (a, b) = (
        [grid(rng), grid(rng), grid(rng)],
        [grid(rng), grid(rng), grid(rng)],
    );
    let f = |p: [f64; 3]| cases::v::<V>(p);
    let k = f64::from(rng.below(9) as i32 - 4) / 2.0;
    let c = [0, 1, 2].map(|i| a[i] + k * (b[i] - a[i]));
    match rng.below(6) {
        0 | 1 => Triangle::new(f(a), f(b), f(c)),
        2 => Triangle::new(f(a), f(a), f(b)),
        3 => {
            let mut c = f(c);
            let bumped = [c.x(), c.y(), c.z()];
            let Some(i) = (0..3).find(|&i| bumped[i] != S::<V>::ZERO) else {
                return Triangle::new(f(a), f(b), c);
            };
            c = V::new(
                if i == 0 {
                    bumped[0].next_up()
                } else {
                    bumped[0]
                },
                if i == 1 {
                    bumped[1].next_up()
                } else {
                    bumped[1]
                },
                if i == 2 {
                    bumped[2].next_up()
                } else {
                    bumped[2]
                },
            );
            Triangle::new(f(a), f(b), c)
        }
        _ => Triangle::new(f(a), f(b), f([grid(rng), grid(rng), grid(rng)])),
    }
}

fn is_degenerate_is_exact<V: Vector>() {
    let mut rng = Source::seeded(41);
    let (mut yes, mut no) = (0, 0);
    for _ in 0..case_count(50_000) {
        let t = triangle::<V>(&mut rng);
        let exact = exactly_degenerate(&t);
        assert_eq!(t.is_degenerate(), exact, "{t:?}");
        if exact {
            yes += 1;
        } else {
            no += 1;
        }
    }
    assert!(yes > 10_000 && no > 10_000, "{yes} {no}");
}

#[test]
fn is_degenerate_is_exact_f32() {
    is_degenerate_is_exact::<Vec3>();
}

#[test]
fn is_degenerate_is_exact_f64() {
    is_degenerate_is_exact::<DVec3>();
}

/// A hit on a zero-area triangle is safe to use: every number derived from
/// it is finite (the normal is zero or meaningless, and says so by its
/// error bound), and a ray spawned from it in any direction is finite.
fn hits_are_safe<V: Vector>() {
    let mut rng = Source::seeded(43);
    let mut hits = 0;
    for _ in 0..case_count(100_000) {
        let t = triangle::<V>(&mut rng);
        if !t.is_degenerate() {
            continue;
        }
        // Aim at a point of the segment, from a random side.
        let w = cases::v::<V>([rng.unit(), rng.unit(), rng.unit()]);
        let target = t.a + (t.b - t.a) * w.x();
        let origin = target + cases::v::<V>(rng.direction()) * (t.b - t.a).length();
        let ray = Ray::new(origin, target - origin);
        let Some(hit) = ray_triangle(&ray, &t, S::<V>::INFINITY) else {
            continue;
        };
        hits += 1;
        assert!(hit.t.is_finite() && hit.u.is_finite() && hit.v.is_finite());
        // `t` is a convex combination of the corners' depths along the ray
        // (the edge functions share a sign), up to rounding: between the
        // nearest and the farthest corner. (Measured on the ray's main
        // axis, as the kernel does; the slack is far above its `gamma(8)`
        // rounding term and far below the corners' spread in these cases.)
        let d = ray.dir.abs();
        let k = if d.x() >= d.y() && d.x() >= d.z() {
            0
        } else if d.y() >= d.z() {
            1
        } else {
            2
        };
        let depth = |p: V| ((p - ray.origin)[k] / ray.dir[k]).to_f64();
        let z = [depth(t.a), depth(t.b), depth(t.c)];
        let (lo, hi) = (
            z.iter().copied().fold(f64::INFINITY, f64::min),
            z.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        );
        let slack = 1e-5 * hi.abs().max(lo.abs());
        let th = hit.t.to_f64();
        assert!(
            lo - slack <= th && th <= hi + slack,
            "{t:?} {ray:?} {hit:?} {z:?}"
        );
        let (n, err) = (t.normal(), t.normal_error());
        assert!(n.is_finite() && err.is_finite(), "{t:?}");
        let surface = t.surface_point_at(hit.u, hit.v);
        assert!(surface.point.is_finite() && surface.point_error.is_finite());
        for dir in [ray.dir, -ray.dir, n, cases::v::<V>(rng.direction())] {
            let spawned = surface.spawn(dir);
            assert!(spawned.origin.is_finite(), "{t:?} {hit:?} {dir:?}");
        }
    }
    assert!(hits > 1_000, "{hits}");
}

#[test]
fn hits_on_zero_area_triangles_are_safe_f32() {
    hits_are_safe::<Vec3>();
}

#[test]
fn hits_on_zero_area_triangles_are_safe_f64() {
    hits_are_safe::<DVec3>();
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: case_count(256).try_into().unwrap_or(u32::MAX),
        ..ProptestConfig::default()
    })]

    #[test]
    fn is_degenerate_matches_exact_on_strategy_triangles(t in rayhit::strategies::triangle::<Vec3>()) {
        prop_assert_eq!(t.is_degenerate(), exactly_degenerate(&t));
    }
}

/// A T-junction closed with a zero-area filler: the edge `A B` of `T1 =
/// (A, B, C)` meets, on the other side, the two triangles `T2 = (A, D, M)`
/// and `T3 = (M, D, B)` through the midpoint `M` of `A B`, and the filler
/// `F = (A, M, B)` (corners exactly collinear: `M` is exact) joins them,
/// every shared edge traversed in opposite directions. Around any interior
/// point of `A B` the four triangles close the surface (for a ray that sees
/// the real ones from one side), so the watertight test must hit one of
/// them for every ray aimed there, from near (some corners behind the
/// origin) or far; rounding opens a
/// sliver between `A B` and `A M`, `M B` in the ray's frame, which only the
/// filler covers, and some rays go through it. The one-hit rule, decided
/// exactly, reports the crossing once, on a real triangle.
fn t_junctions<V: Vector>() {
    let mut rng = Source::seeded(47);
    let f = |p: [f64; 3]| cases::v::<V>(p);
    let (mut rays, mut only_filler) = (0u32, 0u32);
    for _ in 0..case_count(4_000) {
        // Integer corners (exact in both precisions), `B - A` even and on
        // no axis, so that `M` is exact; a random power-of-two scale.
        let scale = 2f64.powi(rng.below(40) as i32 - 20);
        let int = |rng: &mut Source, n: u32| f64::from(rng.below(2 * n + 1) as i32 - n as i32);
        let a = [int(&mut rng, 512), int(&mut rng, 512), int(&mut rng, 512)];
        let mut k = [0.0; 3];
        for kk in &mut k {
            while *kk == 0.0 {
                *kk = int(&mut rng, 256);
            }
        }
        let b = [0, 1, 2].map(|i| a[i] + 2.0 * k[i]);
        let m = [0, 1, 2].map(|i| a[i] + k[i]);
        // C and D on either side of A B, about |A B| away.
        let ab = [0, 1, 2].map(|i| b[i] - a[i]);
        let len = (ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2]).sqrt();
        let q = rng.direction();
        let side = [
            q[1] * ab[2] - q[2] * ab[1],
            q[2] * ab[0] - q[0] * ab[2],
            q[0] * ab[1] - q[1] * ab[0],
        ];
        let sl = (side[0] * side[0] + side[1] * side[1] + side[2] * side[2]).sqrt();
        if sl < 0.1 * len {
            continue;
        }
        let side = side.map(|x| x / sl * len);
        let normal = [
            ab[1] * side[2] - ab[2] * side[1],
            ab[2] * side[0] - ab[0] * side[2],
            ab[0] * side[1] - ab[1] * side[0],
        ];
        let nl = (normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]).sqrt();
        let c = [0, 1, 2].map(|i| m[i] + side[i] + 0.3 * rng.range(-1.0, 1.0) * len);
        let d = [0, 1, 2].map(|i| m[i] - side[i] + 0.3 * rng.range(-1.0, 1.0) * len);
        let s = |p: [f64; 3]| f(p.map(|x| x * scale));
        let (pa, pb, pc, pd, pm) = (s(a), s(b), s(c), s(d), s(m));
        let tris = [
            Triangle::new(pa, pb, pc),
            Triangle::new(pa, pd, pm),
            Triangle::new(pm, pd, pb),
            Triangle::new(pa, pm, pb),
        ];
        assert!(tris[3].is_degenerate() && !tris[0].is_degenerate());
        let batch = TriangleBatch::<V, 8>::from_slice(&tris);
        for _ in 0..100 {
            // Aim at an interior point of A B from either side, not grazing,
            // from near (some corners behind the origin) and far.
            let w = rng.range(0.1, 0.9);
            let target = [0, 1, 2].map(|i| a[i] + w * ab[i]);
            let sign = if rng.one_in(2) { 1.0 } else { -1.0 };
            let r = rng.direction();
            let from = [0, 1, 2].map(|i| {
                target[i] + (sign * normal[i] / nl + 0.5 * r[i]) * rng.range(0.2, 2.0) * len
            });
            let (o, t) = (s(from), s(target));
            let ray = Ray::new(o, t - o);
            // Only where the ray sees the three real triangles from the same
            // side, well away from edge-on: otherwise the patch folds at
            // `A B` as seen from the ray, `A B` is a silhouette, and a ray
            // passing it on the open side rightly hits nothing.
            let facing = |tri: &Triangle<V>| {
                let (n, dir) = (tri.normal(), ray.dir);
                let cos = n.dot(dir).to_f64() / (n.length() * dir.length()).to_f64();
                if cos > 0.1 {
                    1
                } else if cos < -0.1 {
                    -1
                } else {
                    0
                }
            };
            let sides = [facing(&tris[0]), facing(&tris[1]), facing(&tris[2])];
            if sides[0] == 0 || sides[1] != sides[0] || sides[2] != sides[0] {
                continue;
            }
            let found = tris.map(|tri| ray_triangle(&ray, &tri, S::<V>::INFINITY));
            let hits = found.map(|h| h.is_some());
            // The batch (the filler's lane marked zero-area when stored)
            // gives the scalar answers, bit for bit.
            let lanes = batch.map(|b| b.hit(&PreparedRay::new(&ray), S::<V>::INFINITY));
            for (k, h) in found.iter().enumerate() {
                assert_eq!(
                    lanes
                        .as_ref()
                        .and_then(|l| l.get(k))
                        .map(|x| (x.t, x.u, x.v, x.side)),
                    h.map(|x| (x.t, x.u, x.v, x.side)),
                    "lane {k}: {ray:?} {tris:?}"
                );
            }
            assert!(
                hits.iter().any(|&h| h),
                "a ray slipped through: {ray:?} {tris:?}"
            );
            // Every hit within its documented bound of the exact answer:
            // the plane's crossing for the real triangles, where the ray
            // passes the segment for the filler.
            // (The real triangles on one ray in 16: exact arithmetic on
            // `f64` is slow.)
            for (k, (tri, hit)) in tris.iter().zip(found).enumerate() {
                let Some(hit) = hit else { continue };
                if k < 3 && rays % 16 != 0 {
                    continue;
                }
                let err = tri.hit_error(&ray, &hit);
                let exact = if k == 3 {
                    oracle::segment_crossing(&ray, tri)
                } else {
                    oracle::triangle(&ray, tri).t.expect("not parallel")
                };
                assert!(
                    oracle::close(hit.t, &exact, err.t),
                    "triangle {k}: t = {:?}, exact {}, bound {:?}: {ray:?} {tris:?}",
                    hit.t,
                    oracle::to_f64(&exact),
                    err.t
                );
            }
            if hits == [false, false, false, true] {
                only_filler += 1;
            }
            // The one-hit rule decides exactly for the ray moved off every
            // edge line: `M` lies exactly on `A B`, so the moved ray crosses
            // exactly one of the real triangles and never the filler (zero
            // area exactly), wherever rounding puts `M` in the ray's frame.
            // (Over the interval `(0, inf]`, whose ends are decided exactly.)
            let all = rayhit::Interval::up_to(S::<V>::INFINITY).unwrap();
            let one_hit = tris.map(|tri| tri.hit(&ray, (all, EdgeRule::OneHit)).is_some());
            assert_eq!(
                one_hit.iter().filter(|&&h| h).count(),
                1,
                "{one_hit:?}: {ray:?} {tris:?}"
            );
            assert!(!one_hit[3], "the filler: {ray:?} {tris:?}");
            rays += 1;
        }
    }
    assert!(rays > 300_000, "{rays}");
    // The filler is what closes the mesh for some rays (so the test fails
    // if zero-area triangles are dropped).
    assert!(only_filler > 100, "{only_filler} of {rays}");
}

#[test]
fn t_junctions_closed_by_a_zero_area_filler_leak_nothing_f32() {
    t_junctions::<Vec3>();
}

#[test]
fn t_junctions_closed_by_a_zero_area_filler_leak_nothing_f64() {
    t_junctions::<DVec3>();
}

/// A ray through the split vertex `M` of a T-junction closed by a filler
/// `(A, M, B)` (`M = A + (B - A) / 4` exactly), from a scanned-style mesh:
/// by the rounded frame's tie-break the whole triangle, the split piece
/// and the filler were all hit at `t = 1` (two fronts and a back). Decided
/// exactly, the moved ray crosses one of them, as the exact module says.
#[test]
fn a_ray_through_a_split_vertex_is_reported_once() {
    let v = |b: [u32; 3]| Vec3::from_array(b.map(f32::from_bits));
    let (a, m, b) = (
        v([0xbfc9bd00, 0xbf773400, 0x3e2f2000]),
        v([0xbfbeaa00, 0xbf89d900, 0x3db6a000]),
        v([0xbf9d7100, 0xbfb49600, 0xbe202000]),
    );
    let ray = Ray::new(
        v([0xc1908bb0, 0x40ddbb40, 0x40269a80]),
        v([0x4184a110, 0xc10018c0, 0xc020e580]),
    );
    assert_eq!(ray.origin + ray.dir, m);
    let tris = [
        Triangle::new(v([0xbfa02500, 0xbfb7f700, 0x3efbcc00]), a, b),
        Triangle::new(m, a, v([0xbfb7e900, 0xbf672000, 0xbedfe800])),
        Triangle::new(a, m, b),
    ];
    assert!(tris[2].is_degenerate());
    let all = rayhit::Interval::up_to(f32::INFINITY).unwrap();
    let hits: Vec<bool> = tris
        .iter()
        .map(|t| t.hit(&ray, (all, EdgeRule::OneHit)).is_some())
        .collect();
    let exact: Vec<bool> = tris
        .iter()
        .map(|t| oracle::one_hit_line_hits(&ray, t) == Some(true))
        .collect();
    assert_eq!(hits, exact);
    assert_eq!(hits.iter().filter(|&&h| h).count(), 1, "{hits:?}");
    // The closed rule reports every triangle whose closed area holds the
    // crossing: here the whole triangle and the piece.
    let closed = tris.iter().filter(|t| t.hit(&ray, all).is_some()).count();
    assert!(closed >= 2, "{closed}");
}

/// Slivers: the filler `(A, M, B)` of a T-junction whose split vertex `M`
/// is the rounded midpoint of `A B` moved by an ulp (so the filler has a
/// tiny area, exactly), 1e3 to 1e5 from the origin and of sizes from
/// `2^-12` to `2^4`, crossed by rays aimed at `M`, at a point of `A B` or
/// at the sliver's middle, from a few to a few hundred sizes away. The
/// one-hit rule hits the sliver exactly when the ray, moved off the edge
/// lines, crosses it at `t* > 0` (exact arithmetic), on a plain and on a
/// prepared ray, also where rounding leaves the sliver no area in the
/// ray's frame (every edge function within its rounding of zero): there
/// the hit's `t` is the corners' mean depth, within their spread of `t*`.
fn slivers<V: Vector>() -> (usize, usize) {
    let mut rng = Source::seeded(53);
    let all = rayhit::Interval::up_to(S::<V>::INFINITY).unwrap();
    let (mut rays, mut hits) = (0, 0);
    let f = |x: f64| S::<V>::from_f64(x);
    for _ in 0..case_count(3_000) {
        let size = rng.log2_range(-12.0, 4.0);
        let far = rng.log2_range(10.0, 16.6);
        let at = rng.direction().map(|x| x * far);
        let a = V::new(f(at[0]), f(at[1]), f(at[2]));
        let e = rng.direction().map(|x| x * size);
        let b = a + V::new(f(e[0]), f(e[1]), f(e[2]));
        let half = f(0.5);
        let mid = a + (b - a) * half;
        let k = rng.below(3) as usize;
        let up = rng.one_in(2);
        let nudged = |x: S<V>| if up { x.next_up() } else { x.next_down() };
        let m = match k {
            0 => V::new(nudged(mid.x()), mid.y(), mid.z()),
            1 => V::new(mid.x(), nudged(mid.y()), mid.z()),
            _ => V::new(mid.x(), mid.y(), nudged(mid.z())),
        };
        let tri = if rng.one_in(2) {
            Triangle::new(a, m, b)
        } else {
            Triangle::new(a, b, m)
        };
        for _ in 0..8 {
            let target = match rng.below(3) {
                0 => m,
                1 => a + (b - a) * f(rng.range(0.05, 0.95)),
                _ => (a + b + m) * f(1.0 / 3.0),
            };
            let away = rng.direction().map(|x| x * size * rng.log2_range(1.0, 8.0));
            let origin = target + V::new(f(away[0]), f(away[1]), f(away[2]));
            let ray = Ray::new(origin, target - origin);
            if !ray.is_valid() {
                continue;
            }
            let exact = oracle::triangle(&ray, &tri);
            let crossed = oracle::one_hit_line_hits(&ray, &tri) == Some(true)
                && exact.t.as_ref().is_some_and(|t| *t > oracle::int(0));
            let got = tri.hit(&ray, (all, EdgeRule::OneHit));
            assert_eq!(got.is_some(), crossed, "{ray:?} {tri:?}");
            let prepared = tri.hit(&PreparedRay::new(&ray), (all, EdgeRule::OneHit));
            assert_eq!(
                prepared.map(|h| (h.t, h.u, h.v, h.side)),
                got.map(|h| (h.t, h.u, h.v, h.side)),
                "{ray:?} {tri:?}"
            );
            if let Some(h) = got {
                assert!(h.t > S::<V>::ZERO && h.t.is_finite() && h.u >= S::<V>::ZERO);
                // Each barycentric in [0, 1]: the kernels clamp the rounded
                // quotient at 1, and the no-area path reports 1/3 each.
                assert!(h.v >= S::<V>::ZERO && h.u <= S::<V>::ONE && h.v <= S::<V>::ONE);
                let err = tri.hit_error(&ray, &h);
                let t_exact = exact.t.as_ref().expect("crossed");
                assert!(
                    !err.t.is_finite() || oracle::close(h.t, t_exact, err.t),
                    "t {:?}, exact {}, bound {:?}: {ray:?} {tri:?}",
                    h.t,
                    oracle::to_f64(t_exact),
                    err.t
                );
                hits += 1;
            }
            rays += 1;
        }
    }
    (rays, hits)
}

#[test]
fn slivers_are_hit_exactly_where_the_moved_ray_crosses_them_f32() {
    let (rays, hits) = slivers::<Vec3>();
    assert!(rays > 20_000 && hits > rays / 20, "{hits} of {rays}");
}

#[test]
fn slivers_are_hit_exactly_where_the_moved_ray_crosses_them_f64() {
    let (rays, hits) = slivers::<DVec3>();
    assert!(rays > 20_000 && hits > rays / 20, "{hits} of {rays}");
}
