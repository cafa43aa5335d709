//! Every vector type of a precision gives the same answers, bit for bit:
//! glam's `Vec3A` (16 bytes, SIMD) against its `Vec3`, and with the features
//! `glam-029` to `glam-033` on, the `Vec3`, `Vec3A` and `DVec3` of each
//! older glam against this glam's `Vec3` and `DVec3`, through every public
//! kernel, on the oracle suite's generators (rays through edges, corners and
//! faces, slivers, tiny components, far scenes) and on raw bit patterns (NaN,
//! infinities, subnormals, `-0.0`). The kernels do the same arithmetic on
//! all of them (products and sums in the same order), so any difference is a
//! bug in a vector type's implementation.
//!
//! This package's dependency on the crate turns those features on, so
//! `cargo test -p rayhit-interop` runs every type.

use rayhit::glam::Vec3;
use rayhit::{
    Aabb, Bounds, Camera, CameraSample, EdgeRule, Intersect, IntersectLanes, PinholeCamera, Plane,
    PreparedRay, Ray, Scalar, Surface, Triangle, Vector,
    batch::{AabbBatch, TriangleBatch},
    ray_aabb, ray_plane, ray_triangle,
};
use rayhit_testkit::bits::{bits, hit_bits, interval_bits, vector_bits};
use rayhit_testkit::cases::{boxes, planes, triangles};
use rayhit_testkit::source::Source;

type S<V> = <V as Vector>::Scalar;

/// The same components in another vector type of the precision.
fn to<W: Vector, V: Vector<Scalar = S<W>>>(v: V) -> W {
    W::new(v.x(), v.y(), v.z())
}

fn ray<W: Vector, V: Vector<Scalar = S<W>>>(r: &Ray<V>) -> Ray<W> {
    Ray::new(to(r.origin), to(r.dir))
}

/// Raw bit patterns of a precision, half the time a special value.
trait Raw: Scalar {
    fn raw(rng: &mut Source) -> Self;
}

macro_rules! raw {
    ($f:ty, $bits:expr) => {
        impl Raw for $f {
            fn raw(rng: &mut Source) -> Self {
                const SPECIAL: [$f; 8] = [
                    0.0,
                    -0.0,
                    <$f>::NAN,
                    <$f>::INFINITY,
                    <$f>::NEG_INFINITY,
                    <$f>::from_bits(1),
                    <$f>::MAX,
                    1.0,
                ];
                if rng.one_in(2) {
                    SPECIAL[rng.below(8) as usize]
                } else {
                    <$f>::from_bits($bits(rng))
                }
            }
        }
    };
}
raw!(f32, |rng: &mut Source| rng.bits() as u32);
raw!(f64, |rng: &mut Source| rng.bits());

fn raw_v<V: Vector>(rng: &mut Source) -> V
where
    S<V>: Raw,
{
    V::new(S::<V>::raw(rng), S::<V>::raw(rng), S::<V>::raw(rng))
}

/// Boxes: every box kernel, the prepared ray, the face and the batches.
fn check_box<V: Vector, W: Vector<Scalar = S<V>>>(b: &Aabb<V>, r: &Ray<V>, t_max: S<V>) -> bool {
    let (ba, ra) = (Aabb::<W>::new(to(b.min), to(b.max)), ray::<W, V>(r));
    let got = ray_aabb(r, b, t_max);
    assert_eq!(interval_bits(got), interval_bits(ray_aabb(&ra, &ba, t_max)));
    let (p, pa) = (PreparedRay::new(r), PreparedRay::new(&ra));
    assert_eq!(
        interval_bits(b.clip(&p, t_max)),
        interval_bits(ba.clip(&pa, t_max))
    );
    assert_eq!(
        interval_bits(b.clip_by_faces(r, t_max)),
        interval_bits(ba.clip_by_faces(&ra, t_max))
    );
    let (f, fa) = (b.hit(r, t_max), ba.hit(&ra, t_max));
    assert_eq!(f.map(|h| h.face), fa.map(|h| h.face));
    assert_eq!(ba.hit(&pa, t_max).map(|h| h.face), f.map(|h| h.face));
    if let (Some(f), Some(fa)) = (f, fa) {
        let (s, sa) = (b.surface_point(r, &f), ba.surface_point(&ra, &fa));
        assert_eq!(
            s.map(|s| vector_bits(s.point)),
            sa.map(|s| vector_bits(s.point))
        );
        if let (Some(s), Some(sa)) = (s, sa) {
            let d = V::new(
                S::<V>::from_f64(0.3),
                S::<V>::from_f64(-0.5),
                S::<V>::from_f64(0.8),
            );
            assert_eq!(
                vector_bits(s.spawn(d).origin),
                vector_bits(sa.spawn(to(d)).origin)
            );
        }
    }
    if let (Some(batch), Some(batch_a)) = (
        AabbBatch::<V, 8>::from_slice(&[*b]),
        AabbBatch::<W, 8>::from_slice(&[ba]),
    ) {
        let (h, ha) = (batch.clip(&p, t_max), batch_a.clip(&pa, t_max));
        assert_eq!(h.mask, ha.mask);
        assert_eq!(h.enter.map(bits::<S<V>>), ha.enter.map(bits::<S<V>>));
    }
    got.is_some()
}

/// Triangles: every triangle kernel, the error bounds, the hit point, the
/// spawned ray and the batch.
fn check_triangle<V: Vector, W: Vector<Scalar = S<V>>>(
    t: &Triangle<V>,
    r: &Ray<V>,
    t_max: S<V>,
) -> bool {
    let (ta, ra) = (
        Triangle::<W>::new(to(t.a), to(t.b), to(t.c)),
        ray::<W, V>(r),
    );
    let got = ray_triangle(r, t, t_max);
    assert_eq!(hit_bits(got), hit_bits(ray_triangle(&ra, &ta, t_max)));
    let (p, pa) = (PreparedRay::new(r), PreparedRay::new(&ra));
    assert_eq!(hit_bits(t.hit(&p, t_max)), hit_bits(ta.hit(&pa, t_max)));
    assert_eq!(
        hit_bits(t.hit(r, (t_max, EdgeRule::OneHit))),
        hit_bits(ta.hit(&ra, (t_max, EdgeRule::OneHit)))
    );
    assert_eq!(
        hit_bits(t.moller_trumbore(r, t_max)),
        hit_bits(ta.moller_trumbore(&ra, t_max))
    );
    assert_eq!(t.is_degenerate(), ta.is_degenerate());
    let (n, na) = (
        (t.normal(), t.normal_error()),
        (ta.normal(), ta.normal_error()),
    );
    assert_eq!(
        (vector_bits(n.0), vector_bits(n.1)),
        (vector_bits(na.0), vector_bits(na.1))
    );
    if let Some(h) = got {
        let (e, ea) = (t.hit_error(r, &h), ta.hit_error(&ra, &h));
        assert_eq!([e.t, e.u, e.v].map(bits), [ea.t, ea.u, ea.v].map(bits));
        let (s, sa) = (t.surface_point(r, &h), ta.surface_point(&ra, &h));
        let (q, qa) = ((s.point, s.point_error), (sa.point, sa.point_error));
        assert_eq!(
            (vector_bits(q.0), vector_bits(q.1)),
            (vector_bits(qa.0), vector_bits(qa.1))
        );
        let d = V::new(
            S::<V>::from_f64(-0.2),
            S::<V>::from_f64(0.9),
            S::<V>::from_f64(0.4),
        );
        assert_eq!(
            vector_bits(t.surface_point_at(h.u, h.v).spawn(d).origin),
            vector_bits(ta.surface_point_at(h.u, h.v).spawn(to(d)).origin)
        );
    }
    if let (Some(batch), Some(batch_a)) = (
        TriangleBatch::<V, 8>::from_slice(&[*t]),
        TriangleBatch::<W, 8>::from_slice(&[ta]),
    ) {
        let (h, ha) = (batch.hit(&p, t_max), batch_a.hit(&pa, t_max));
        assert_eq!((h.mask, h.front), (ha.mask, ha.front));
        assert_eq!(h.t.map(bits::<S<V>>), ha.t.map(bits::<S<V>>));
    }
    got.is_some()
}

fn check_plane<V: Vector, W: Vector<Scalar = S<V>>>(
    pl: &Plane<V>,
    r: &Ray<V>,
    t_max: S<V>,
) -> bool {
    let (pa, ra) = (Plane::<W>::new(to(pl.point), to(pl.normal)), ray::<W, V>(r));
    let got = ray_plane(r, pl, t_max);
    assert_eq!(
        got.map(bits::<S<V>>),
        ray_plane(&ra, &pa, t_max).map(bits::<S<V>>)
    );
    if let Some(t) = got {
        assert_eq!(bits(pl.hit_error(r, &t)), bits(pa.hit_error(&ra, &t)));
        let (q, qa) = (
            {
                let s = pl.surface_point(r, &t);
                (s.point, s.point_error)
            },
            {
                let s = pa.surface_point(&ra, &t);
                (s.point, s.point_error)
            },
        );
        assert_eq!(
            (vector_bits(q.0), vector_bits(q.1)),
            (vector_bits(qa.0), vector_bits(qa.1))
        );
    }
    got.is_some()
}

/// Every kernel on the generators' cases, in `V` and in `W`.
fn same_bits_on_the_generators<V: Vector, W: Vector<Scalar = S<V>>>() {
    let (mut hits, mut misses) = (0, 0);
    let mut count = |hit: bool| if hit { hits += 1 } else { misses += 1 };
    for (_, seed, generate) in boxes::generators::<V>() {
        let mut rng = Source::seeded(seed ^ 0xa11);
        for _ in 0..2_000 {
            let (b, r, t_max) = generate(&mut rng);
            count(check_box::<V, W>(&b, &r, t_max));
        }
    }
    for (_, seed, generate) in triangles::generators::<V>() {
        let mut rng = Source::seeded(seed ^ 0xa11);
        for _ in 0..2_000 {
            let (t, r, t_max) = generate(&mut rng);
            count(check_triangle::<V, W>(&t, &r, t_max));
        }
    }
    let mut rng = Source::seeded(0xa11);
    for _ in 0..4_000 {
        let (pl, r, t_max) = planes::plane::<V>(&mut rng);
        count(check_plane::<V, W>(&pl, &r, t_max));
    }
    // Both answers are common, so agreement means something.
    assert!(
        hits > 10_000 && misses > 10_000,
        "{hits} hits, {misses} misses"
    );
}

/// Every kernel on raw bit patterns, in `V` and in `W`.
fn same_bits_on_raw_bit_patterns<V: Vector, W: Vector<Scalar = S<V>>>()
where
    S<V>: Raw,
{
    let mut rng = Source::seeded(0xb175);
    for _ in 0..20_000 {
        let r = Ray::new(raw_v::<V>(&mut rng), raw_v::<V>(&mut rng));
        let t_max = if rng.one_in(2) {
            S::<V>::INFINITY
        } else {
            S::<V>::raw(&mut rng)
        };
        let b = Aabb::new(raw_v::<V>(&mut rng), raw_v::<V>(&mut rng));
        check_box::<V, W>(&b, &r, t_max);
        let t = Triangle::new(raw_v::<V>(&mut rng), raw_v(&mut rng), raw_v(&mut rng));
        check_triangle::<V, W>(&t, &r, t_max);
        let pl = Plane::new(raw_v::<V>(&mut rng), raw_v::<V>(&mut rng));
        check_plane::<V, W>(&pl, &r, t_max);
    }
}

/// Every camera's rays and differentials (and the panoramas' inverses),
/// in `V` and in `W`, bit for bit.
fn same_camera_rays<V: Vector, W: Vector<Scalar = S<V>>>() {
    use rayhit::camera::{
        ClipSpace, EqualAreaCamera, EquirectangularCamera, MatrixCamera, OrthographicCamera,
        RayDifferential, ThinLensCamera,
    };
    let f = S::<V>::from_f64;
    let (eye, view, up) = (
        V::new(f(0.5), f(2.0), f(7.0)),
        V::new(f(-0.1), f(-0.3), f(-1.0)),
        V::new(f(0.0), f(1.0), f(0.0)),
    );
    let (eye_w, view_w, up_w) = (to::<W, V>(eye), to::<W, V>(view), to::<W, V>(up));
    let cam = PinholeCamera::from_fov(eye, view, up, f(0.9), 64, 48).unwrap();
    let cam_w = PinholeCamera::from_fov(eye_w, view_w, up_w, f(0.9), 64, 48).unwrap();
    let lens = ThinLensCamera::new(cam, f(0.1), f(5.0)).unwrap();
    let lens_w = ThinLensCamera::new(cam_w, f(0.1), f(5.0)).unwrap();
    let ortho = OrthographicCamera::new(eye, view, up, f(0.05), 64, 48).unwrap();
    let ortho_w = OrthographicCamera::new(eye_w, view_w, up_w, f(0.05), 64, 48).unwrap();
    let equi = EquirectangularCamera::new(eye, view, up, 64, 48).unwrap();
    let equi_w = EquirectangularCamera::new(eye_w, view_w, up_w, 64, 48).unwrap();
    let area = EqualAreaCamera::new(eye, view, up, 64, 48).unwrap();
    let area_w = EqualAreaCamera::new(eye_w, view_w, up_w, 64, 48).unwrap();
    let v64 = rayhit::glam::dcamera::rh::view::look_to_mat4(
        rayhit::glam::DVec3::new(0.5, 2.0, 7.0),
        rayhit::glam::DVec3::new(-0.1, -0.3, -1.0).normalize(),
        rayhit::glam::DVec3::Y,
    );
    let p64 = rayhit::glam::dcamera::rh::proj::directx::perspective(0.9, 64.0 / 48.0, 0.1, 100.0);
    let cols = |m: rayhit::glam::DMat4| m.to_cols_array_2d().map(|c| c.map(f));
    let matrix = MatrixCamera::<V>::new(cols(v64), cols(p64), ClipSpace::Direct3D, 64, 48).unwrap();
    let matrix_w =
        MatrixCamera::<W>::new(cols(v64), cols(p64), ClipSpace::Direct3D, 64, 48).unwrap();
    let ray = |r: rayhit::Ray<V>| (vector_bits(r.origin), vector_bits(r.dir));
    let ray_w = |r: rayhit::Ray<W>| (vector_bits(r.origin), vector_bits(r.dir));
    let diff = |d: RayDifferential<V>| {
        (
            ray(d.ray),
            [d.dx_origin, d.dx_dir, d.dy_origin, d.dy_dir].map(vector_bits),
        )
    };
    let diff_w = |d: RayDifferential<W>| {
        (
            ray_w(d.ray),
            [d.dx_origin, d.dx_dir, d.dy_origin, d.dy_dir].map(vector_bits),
        )
    };
    let back = |p: Option<(S<V>, S<V>)>| p.map(|(x, y)| (bits(x), bits(y)));
    for j in 0..48 {
        for i in 0..64 {
            let (x, y) = (f(f64::from(i) + 0.5), f(f64::from(j) + 0.5));
            let (s, t) = (f(f64::from(i) / 64.0), f(f64::from(j) / 48.0));
            assert_eq!(ray(cam.pixel_ray(i, j)), ray_w(cam_w.pixel_ray(i, j)));
            assert_eq!(
                diff(cam.ray_differential(CameraSample::new(x, y))),
                diff_w(cam_w.ray_differential(CameraSample::new(x, y)))
            );
            assert_eq!(
                ray(lens.ray(CameraSample::new(x, y).with_lens(s, t))),
                ray_w(lens_w.ray(CameraSample::new(x, y).with_lens(s, t)))
            );
            assert_eq!(
                diff(lens.ray_differential(CameraSample::new(x, y).with_lens(s, t))),
                diff_w(lens_w.ray_differential(CameraSample::new(x, y).with_lens(s, t)))
            );
            assert_eq!(
                diff(ortho.ray_differential(CameraSample::new(x, y))),
                diff_w(ortho_w.ray_differential(CameraSample::new(x, y)))
            );
            assert_eq!(
                diff(matrix.ray_differential(CameraSample::new(x, y))),
                diff_w(matrix_w.ray_differential(CameraSample::new(x, y)))
            );
            assert_eq!(
                diff(equi.ray_differential(CameraSample::new(x, y))),
                diff_w(equi_w.ray_differential(CameraSample::new(x, y)))
            );
            assert_eq!(
                diff(area.ray_differential(CameraSample::new(x, y))),
                diff_w(area_w.ray_differential(CameraSample::new(x, y)))
            );
            let d = equi.ray(CameraSample::new(x, y)).dir;
            assert_eq!(
                back(equi.raster_position(d)),
                back(equi_w.raster_position(to(d)))
            );
            let d = area.ray(CameraSample::new(x, y)).dir;
            assert_eq!(
                back(area.raster_position(d)),
                back(area_w.raster_position(to(d)))
            );
        }
    }
}

/// The three checks for a vector type `$W` against this glam's `$V`.
macro_rules! same_bits {
    ($name:ident, $V:ty, $W:ty) => {
        mod $name {
            use super::*;

            #[test]
            fn on_the_generators() {
                same_bits_on_the_generators::<$V, $W>();
            }

            #[test]
            fn on_raw_bit_patterns() {
                same_bits_on_raw_bit_patterns::<$V, $W>();
            }

            #[test]
            fn camera_rays() {
                same_camera_rays::<$V, $W>();
            }
        }
    };
}

/// The checks for `Vec3`, `Vec3A` and `DVec3` of an older glam.
macro_rules! older_glam {
    ($name:ident, $glam:ident) => {
        mod $name {
            use super::*;
            same_bits!(vec3, Vec3, $glam::Vec3);
            same_bits!(vec3a, Vec3, $glam::Vec3A);
            same_bits!(dvec3, rayhit::glam::DVec3, $glam::DVec3);
        }
    };
}

same_bits!(vec3a, Vec3, rayhit::glam::Vec3A);
older_glam!(glam_0_29, glam029);
older_glam!(glam_0_30, glam030);
older_glam!(glam_0_31, glam031);
older_glam!(glam_0_32, glam032);
older_glam!(glam_0_33, glam033);
