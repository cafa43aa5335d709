//! The compressed wide BVH node test against exact arithmetic.
//!
//! - Every decoded child box contains the exact quantized box
//!   `origin + 2^(e - 127) [min, max]`, whatever the origin's magnitude.
//! - The node test is, bit for bit, the box batch on the decoded boxes (in
//!   the target's copy and in the one `with_simd` picks).
//! - No false miss: a ray that meets an exact quantized box, decided with
//!   big rationals, is reported hitting that child.
//! - `QuantizedChildren::quantize` gives the tightest bytes whose decoded
//!   box contains the bounds it was given.

use num_traits::{One, Signed, Zero};
use rayhit::glam::Vec3;
use rayhit::{
    Bounds, Interval, PreparedRay, Ray,
    batch::{AabbBatchHits, InPlace, QuantizedChildren, Simd, SimdWork, TargetSimd, with_simd},
};
use rayhit_testkit::case_count;
use rayhit_testkit::oracle;
use rayhit_testkit::oracle::{R, r};
use rayhit_testkit::source::Source;

/// `2^k` exactly.
fn pow2(k: i32) -> R {
    let p = num_bigint::BigInt::one() << k.unsigned_abs();
    if k >= 0 {
        R::from_integer(p)
    } else {
        R::new(1.into(), p)
    }
}

/// A random node: an origin of any sign and magnitude from `2^-30` to
/// `2^30`, exponents that give extents from far below to far above the
/// origin's ulp, and random bytes (about one child in eight empty).
struct Node {
    origin: Vec3,
    exponents: [u8; 3],
    min: [[u8; 8]; 3],
    max: [[u8; 8]; 3],
}

impl Node {
    fn random(rng: &mut Source) -> Self {
        let mut coordinate = || {
            let m = rng.range(0.5, 1.0) * rng.log2_range(-30.0, 30.0);
            (if rng.one_in(2) { -m } else { m }) as f32
        };
        let origin = Vec3::new(coordinate(), coordinate(), coordinate());
        let exponents = [0, 1, 2].map(|k| {
            // Step relative to the origin's magnitude: from 2^-30 of it to 2^4.
            let mag = origin[k].abs().log2().floor() as i32;
            let e = mag + (rng.below(35) as i32) - 30 + 127 - 8;
            e.clamp(1, 254) as u8
        });
        let mut min = [[0u8; 8]; 3];
        let mut max = [[0u8; 8]; 3];
        for k in 0..3 {
            for c in 0..8 {
                let (a, b) = (rng.below(256) as u8, rng.below(256) as u8);
                let (lo, hi) = if rng.one_in(24) {
                    (a.max(b), a.min(b))
                } else {
                    (a.min(b), a.max(b))
                };
                (min[k][c], max[k][c]) = (lo, hi);
            }
        }
        Node {
            origin,
            exponents,
            min,
            max,
        }
    }

    fn view(&self) -> QuantizedChildren<'_> {
        QuantizedChildren {
            origin: self.origin,
            exponents: self.exponents,
            min: [&self.min[0], &self.min[1], &self.min[2]],
            max: [&self.max[0], &self.max[1], &self.max[2]],
        }
    }

    /// The exact quantized box of `child` on axis `k`.
    fn exact(&self, k: usize, child: usize) -> (R, R) {
        let s = pow2(i32::from(self.exponents[k]) - 127);
        let p = r(self.origin[k]);
        let q = |b: u8| R::from_integer(i64::from(b).into());
        (
            &p + &s * q(self.min[k][child]),
            &p + &s * q(self.max[k][child]),
        )
    }
}

#[test]
fn decoded_boxes_contain_the_exact_quantized_boxes() {
    let mut rng = Source::seeded(11);
    let mut children = 0;
    for _ in 0..case_count(4_000) {
        let node = Node::random(&mut rng);
        let view = node.view();
        assert!(view.is_valid());
        for child in 0..8 {
            let empty = (0..3).any(|k| node.min[k][child] > node.max[k][child]);
            let Some(b) = view.child_box(child) else {
                assert!(empty, "{child} of {:?}", node.origin);
                continue;
            };
            assert!(!empty);
            children += 1;
            for k in 0..3 {
                let (lo, hi) = node.exact(k, child);
                assert!(
                    r(b.min[k]) <= lo,
                    "{:?} {:?} {child} {k}",
                    node.origin,
                    node.exponents
                );
                assert!(
                    r(b.max[k]) >= hi,
                    "{:?} {:?} {child} {k}",
                    node.origin,
                    node.exponents
                );
                // And only a few ulps of the node's largest coordinate wider
                // (its origin or its far end), plus a few subnormals.
                let far = &r(node.origin[k])
                    + pow2(i32::from(node.exponents[k]) - 127) * R::from_integer(255.into());
                let scale = r(node.origin[k]).abs().max(far.abs());
                let band = &scale * pow2(-20) + pow2(-146);
                assert!((&lo - r(b.min[k])) <= band);
                assert!((r(b.max[k]) - &hi) <= band);
            }
        }
    }
    assert!(children > 20_000, "{children}");
}

/// Runs the node test through `with_simd` (the AVX2 copy where the CPU has
/// it).
struct ViaWithSimd<'a> {
    ray: &'a PreparedRay,
    node: QuantizedChildren<'a>,
    t_max: f32,
}

impl SimdWork for ViaWithSimd<'_> {
    type Output = AabbBatchHits<f32, 8>;
    #[inline(always)]
    fn run<I: Simd>(self, simd: I) -> Self::Output {
        self.node.clip(&simd.ray(self.ray), self.t_max)
    }
}

#[test]
fn node_test_is_the_box_batch_on_the_decoded_boxes() {
    let mut rng = Source::seeded(12);
    let (mut hits, mut interval_hits) = (0, 0);
    for i in 0..case_count(20_000) {
        let node = Node::random(&mut rng);
        let view = node.view();
        let boxes = view.boxes();
        // A ray from near the node towards a random child's decoded box.
        let child = rng.below(8) as usize;
        let target = view
            .child_box(child)
            .map_or(node.origin, |b| (b.min + b.max) * 0.5);
        let span = (view.step() * 255.0)
            .max_element()
            .max(node.origin.abs().max_element() * 1e-6);
        let mut around = || rng.range(-2.0, 2.0) as f32;
        let origin = target + Vec3::new(around(), around(), around()) * span;
        let dir = if i % 5 == 0 {
            Vec3::new(0.0, 1.0, 0.0)
        } else {
            target - origin
        };
        let ray = PreparedRay::new(&Ray::new(origin, dir));
        for t_max in [f32::INFINITY, 1.0, -1.0, f32::NAN] {
            let expected = boxes.clip(&ray, t_max);
            // The node read in place (`InPlace`): the view made inside the
            // test, the same answers.
            let in_place = InPlace(|| node.view());
            let ours = [
                view.clip(&ray, t_max),
                view.clip(&TargetSimd.ray(&ray), t_max),
                in_place.clip(&ray, t_max),
                in_place.clip(&TargetSimd.ray(&ray), t_max),
                with_simd(ViaWithSimd {
                    ray: &ray,
                    node: view,
                    t_max,
                }),
            ];
            // `meets`: the mask alone, from its own copy of the kernel.
            for got in [
                view.meets(&ray, t_max),
                view.meets(&TargetSimd.ray(&ray), t_max),
                in_place.meets(&ray, t_max),
            ] {
                assert_eq!(got, expected.mask, "meets {ray:?} {:?}", node.origin);
            }
            for got in ours {
                assert_eq!(got.mask, expected.mask, "{ray:?} {:?}", node.origin);
                for l in 0..8 {
                    assert_eq!(got.enter[l].to_bits(), expected.enter[l].to_bits());
                }
            }
            hits += expected.mask.count_ones();
            // Over intervals starting at zero, at the nearest child's
            // entry and just past it, and halfway to `t_max`.
            let nearest = expected.enter.iter().copied().fold(f32::INFINITY, f32::min);
            for lo in [0.0, nearest, nearest.next_up(), t_max * 0.5] {
                let Some(interval) = Interval::new(lo, t_max) else {
                    continue;
                };
                let expected = boxes.clip(&ray, interval);
                assert_eq!(view.meets(&ray, interval), expected.mask);
                assert_eq!(in_place.meets(&ray, interval), expected.mask);
                assert_eq!(in_place.clip(&ray, interval), expected);
                for got in [
                    view.clip(&ray, interval),
                    view.clip(&TargetSimd.ray(&ray), interval),
                ] {
                    assert_eq!(got.mask, expected.mask, "{ray:?} {interval:?}");
                    for l in 0..8 {
                        assert_eq!(got.enter[l].to_bits(), expected.enter[l].to_bits());
                    }
                }
                interval_hits += expected.mask.count_ones();
            }
        }
    }
    assert!(hits > 20_000, "{hits}");
    assert!(interval_hits > 20_000, "{interval_hits}");
}

/// The exact interval of `t >= 0` in which the ray is inside an exact box,
/// or `None` when it is empty.
fn exact_hit(ray: &Ray, lo: &[R; 3], hi: &[R; 3]) -> bool {
    let (o, d) = (oracle::rv(ray.origin), oracle::rv(ray.dir));
    let (mut enter, mut exit): (R, Option<R>) = (R::zero(), None);
    for k in 0..3 {
        if d[k].is_zero() {
            if o[k] < lo[k] || o[k] > hi[k] {
                return false;
            }
            continue;
        }
        let (t0, t1) = ((&lo[k] - &o[k]) / &d[k], (&hi[k] - &o[k]) / &d[k]);
        let (near, far) = if t0 <= t1 { (t0, t1) } else { (t1, t0) };
        enter = enter.max(near);
        exit = Some(exit.map_or(far.clone(), |x| x.min(far)));
    }
    exit.is_none_or(|x| enter <= x)
}

#[test]
fn no_false_miss_against_the_exact_quantized_boxes() {
    let mut rng = Source::seeded(13);
    let (mut exact_hits, mut checked) = (0, 0);
    for _ in 0..case_count(10_000) {
        let node = Node::random(&mut rng);
        let view = node.view();
        let child = rng.below(8) as usize;
        if (0..3).any(|k| node.min[k][child] > node.max[k][child]) {
            continue;
        }
        let (lo, hi): (Vec<R>, Vec<R>) = (0..3).map(|k| node.exact(k, child)).unzip();
        let (lo, hi) = (
            [lo[0].clone(), lo[1].clone(), lo[2].clone()],
            [hi[0].clone(), hi[1].clone(), hi[2].clone()],
        );
        // Aim at the nearest float to a corner, an edge point or the centre
        // of the exact box, from a random point around it.
        let pick = |k: usize, rng: &mut Source| -> f32 {
            let w = match rng.below(3) {
                0 => R::zero(),
                1 => R::one(),
                _ => R::new(1.into(), 2.into()),
            };
            let x = &lo[k] + (&hi[k] - &lo[k]) * w;
            oracle::to_f64(&x) as f32
        };
        let target = Vec3::new(pick(0, &mut rng), pick(1, &mut rng), pick(2, &mut rng));
        let span = (view.step() * 255.0)
            .max_element()
            .max(target.abs().max_element() * 1e-5);
        let mut around = || rng.range(-3.0, 3.0) as f32;
        let origin = target + Vec3::new(around(), around(), around()) * span;
        let ray = Ray::new(origin, target - origin);
        if !ray.is_valid() {
            continue;
        }
        checked += 1;
        if exact_hit(&ray, &lo, &hi) {
            exact_hits += 1;
            let hits = view.clip(&PreparedRay::new(&ray), f32::INFINITY);
            assert!(
                hits.mask & (1 << child) != 0,
                "false miss: {ray:?} {:?} {:?} child {child}",
                node.origin,
                node.exponents
            );
        }
    }
    assert!(
        checked > 5_000 && exact_hits > 2_000,
        "{checked} {exact_hits}"
    );
}

#[test]
fn quantize_bounds_is_tight_and_conservative() {
    let mut rng = Source::seeded(14);
    let mut some = 0;
    for _ in 0..case_count(50_000) {
        let node = Node::random(&mut rng);
        let (p, e) = (node.origin.x, node.exponents[0]);
        let s = f32::from_bits(u32::from(e) << 23);
        // Bounds inside (mostly) or around the node's extent.
        let x = |rng: &mut Source| p + s * rng.range(-8.0, 263.0) as f32;
        let (a, b) = (x(&mut rng), x(&mut rng));
        let (min, max) = (a.min(b), a.max(b));
        let decoded = |q: (u8, u8)| {
            let lo = [q.0; 8];
            let hi = [q.1; 8];
            let v = QuantizedChildren {
                origin: Vec3::splat(p),
                exponents: [e; 3],
                min: [&lo; 3],
                max: [&hi; 3],
            };
            v.child_box(0).map(|b| (b.min.x, b.max.x))
        };
        match QuantizedChildren::quantize(p, e, min, max) {
            Some((lo, hi)) => {
                some += 1;
                let (dlo, dhi) = decoded((lo, hi)).expect("lo <= hi");
                assert!(
                    dlo <= min && dhi >= max,
                    "{p} {e} [{min}, {max}] -> {lo}, {hi}"
                );
                // Tightest: one step in decodes past the bound.
                if lo < hi {
                    assert!(decoded((lo + 1, hi)).is_none_or(|(l, _)| l > min));
                    assert!(decoded((lo, hi - 1)).is_none_or(|(_, h)| h < max));
                }
            }
            None => {
                // Only when no byte reaches a bound.
                let (l0, _) = decoded((0, 255)).expect("0 <= 255");
                let (_, h255) = decoded((0, 255)).expect("0 <= 255");
                assert!(l0 > min || h255 < max, "{p} {e} [{min}, {max}]");
            }
        }
    }
    assert!(some > 30_000, "{some}");
    // Bad input.
    assert_eq!(QuantizedChildren::quantize(f32::NAN, 127, 0.0, 1.0), None);
    assert_eq!(QuantizedChildren::quantize(0.0, 255, 0.0, 1.0), None);
    assert_eq!(QuantizedChildren::quantize(0.0, 127, 2.0, 1.0), None);
    assert_eq!(
        QuantizedChildren::quantize(0.0, 127, 0.0, f32::INFINITY),
        None
    );
}

#[test]
fn invalid_nodes_and_rays_hit_nothing() {
    let (lo, hi) = ([0u8; 8], [255u8; 8]);
    let good = QuantizedChildren {
        origin: Vec3::ZERO,
        exponents: [127; 3],
        min: [&lo; 3],
        max: [&hi; 3],
    };
    let ray = PreparedRay::new(&Ray::new(Vec3::splat(-1.0), Vec3::ONE));
    assert_eq!(good.clip(&ray, f32::INFINITY).mask, 0xff);
    for bad in [
        QuantizedChildren {
            origin: Vec3::new(f32::NAN, 0.0, 0.0),
            ..good
        },
        QuantizedChildren {
            origin: Vec3::new(0.0, f32::INFINITY, 0.0),
            ..good
        },
        QuantizedChildren {
            exponents: [127, 255, 127],
            ..good
        },
        QuantizedChildren {
            origin: Vec3::splat(f32::MAX),
            ..good
        },
    ] {
        assert!(!bad.is_valid());
        let hits = bad.clip(&ray, f32::INFINITY);
        assert_eq!(hits.mask, 0);
        assert!(hits.enter.iter().all(|e| *e == f32::INFINITY));
        assert!(bad.child_box(0).is_none());
    }
    for t_max in [f32::NAN, -1.0] {
        assert_eq!(good.clip(&ray, t_max).mask, 0);
    }
    let invalid = PreparedRay::new(&Ray::new(Vec3::ZERO, Vec3::ZERO));
    assert_eq!(good.clip(&invalid, f32::INFINITY).mask, 0);
    assert!(good.child_box(8).is_none());
}
