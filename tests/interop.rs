//! Every vector type of a precision gives the same answers, bit for bit:
//! `glam::Vec3A` (16 bytes, SIMD) against `glam::Vec3`, through every public
//! kernel, on the oracle suite's generators (rays through edges, corners and
//! faces, slivers, tiny components, far scenes) and on raw bit patterns (NaN,
//! infinities, subnormals, `-0.0`). The kernels do the same arithmetic on
//! both (products and sums in the same order), so any difference is a bug in
//! the vector type's implementation.

mod support;

use rayhit::glam::{Vec3, Vec3A};
use rayhit::{
    Aabb, AabbBatch, PinholeCamera, Plane, PreparedRay, Ray, SurfacePoint, Triangle, TriangleBatch,
    TriangleHit, ray_aabb, ray_aabb_batch, ray_aabb_face, ray_aabb_naive, ray_aabb_prepared,
    ray_aabb_prepared_face, ray_plane, ray_plane_hit_point, ray_plane_t_error, ray_triangle,
    ray_triangle_batch, ray_triangle_error_bounds, ray_triangle_mt, ray_triangle_one_hit,
    ray_triangle_prepared, triangle_hit_point,
};
use support::Pcg32;
use support::generators::{box_generators, gen_plane, triangle_generators};

fn a(v: Vec3) -> Vec3A {
    v.into()
}

fn ray(r: &Ray<Vec3>) -> Ray<Vec3A> {
    Ray::new(a(r.origin), a(r.dir))
}

/// The bits of a float, every NaN as one pattern: the payload of a NaN
/// produced by arithmetic is not specified (x86 SIMD and scalar code pass on
/// different operands' payloads), only that it is NaN.
fn fbits(x: f32) -> u32 {
    if x.is_nan() {
        f32::NAN.to_bits()
    } else {
        x.to_bits()
    }
}

fn bits(v: Vec3) -> [u32; 3] {
    v.to_array().map(fbits)
}

fn bits_a(v: Vec3A) -> [u32; 3] {
    bits(v.into())
}

fn hit_bits(h: Option<TriangleHit<f32>>) -> Option<([u32; 3], bool)> {
    h.map(|h| {
        (
            [h.t.to_bits(), h.u.to_bits(), h.v.to_bits()],
            h.side == rayhit::Side::Front,
        )
    })
}

fn interval_bits(x: Option<(f32, f32)>) -> Option<(u32, u32)> {
    x.map(|(e, x)| (e.to_bits(), x.to_bits()))
}

/// A float from raw bits, half the time a special one.
fn raw(rng: &mut Pcg32) -> f32 {
    const SPECIAL: [f32; 8] = [
        0.0,
        -0.0,
        f32::NAN,
        f32::INFINITY,
        f32::NEG_INFINITY,
        1e-45,
        f32::MAX,
        1.0,
    ];
    if rng.one_in(2) {
        SPECIAL[rng.below(8) as usize]
    } else {
        f32::from_bits(rng.next_u32())
    }
}

fn raw_v(rng: &mut Pcg32) -> Vec3 {
    Vec3::new(raw(rng), raw(rng), raw(rng))
}

/// Boxes: every box kernel, the prepared ray, the face and the batches.
fn check_box(b: &Aabb<Vec3>, r: &Ray<Vec3>, t_max: f32) -> bool {
    let (ba, ra) = (Aabb::new(a(b.min), a(b.max)), ray(r));
    let got = ray_aabb(r, b, t_max);
    assert_eq!(interval_bits(got), interval_bits(ray_aabb(&ra, &ba, t_max)));
    let (p, pa) = (PreparedRay::new(r), PreparedRay::new(&ra));
    assert_eq!(
        interval_bits(ray_aabb_prepared(&p, b, t_max)),
        interval_bits(ray_aabb_prepared(&pa, &ba, t_max))
    );
    assert_eq!(
        interval_bits(ray_aabb_naive(r, b, t_max)),
        interval_bits(ray_aabb_naive(&ra, &ba, t_max))
    );
    let (f, fa) = (ray_aabb_face(r, b, t_max), ray_aabb_face(&ra, &ba, t_max));
    assert_eq!(f.map(|h| h.face), fa.map(|h| h.face));
    assert_eq!(
        ray_aabb_prepared_face(&pa, &ba, t_max).map(|h| h.face),
        f.map(|h| h.face)
    );
    if let (Some(f), Some(fa)) = (f, fa) {
        let (s, sa) = (
            SurfacePoint::on_box(r, b, &f),
            SurfacePoint::on_box(&ra, &ba, &fa),
        );
        assert_eq!(s.map(|s| bits(s.point)), sa.map(|s| bits_a(s.point)));
        if let (Some(s), Some(sa)) = (s, sa) {
            let d = Vec3::new(0.3, -0.5, 0.8);
            assert_eq!(bits(s.spawn(d).origin), bits_a(sa.spawn(a(d)).origin));
        }
    }
    if let (Some(batch), Some(batch_a)) = (
        AabbBatch::<Vec3, 8>::from_slice(&[*b]),
        AabbBatch::<Vec3A, 8>::from_slice(&[ba]),
    ) {
        let (h, ha) = (
            ray_aabb_batch(&p, &batch, t_max),
            ray_aabb_batch(&pa, &batch_a, t_max),
        );
        assert_eq!(h.mask, ha.mask);
        assert_eq!(h.enter.map(fbits), ha.enter.map(fbits));
    }
    got.is_some()
}

/// Triangles: every triangle kernel, the error bounds, the hit point, the
/// spawned ray and the batch.
fn check_triangle(t: &Triangle<Vec3>, r: &Ray<Vec3>, t_max: f32) -> bool {
    let (ta, ra) = (Triangle::new(a(t.a), a(t.b), a(t.c)), ray(r));
    let got = ray_triangle(r, t, t_max);
    assert_eq!(hit_bits(got), hit_bits(ray_triangle(&ra, &ta, t_max)));
    let (p, pa) = (PreparedRay::new(r), PreparedRay::new(&ra));
    assert_eq!(
        hit_bits(ray_triangle_prepared(&p, t, t_max)),
        hit_bits(ray_triangle_prepared(&pa, &ta, t_max))
    );
    assert_eq!(
        hit_bits(ray_triangle_one_hit(r, t, t_max)),
        hit_bits(ray_triangle_one_hit(&ra, &ta, t_max))
    );
    assert_eq!(
        hit_bits(ray_triangle_mt(r, t, t_max)),
        hit_bits(ray_triangle_mt(&ra, &ta, t_max))
    );
    assert_eq!(t.is_degenerate(), ta.is_degenerate());
    let (n, na) = (t.normal_with_error(), ta.normal_with_error());
    assert_eq!((bits(n.0), bits(n.1)), (bits_a(na.0), bits_a(na.1)));
    if let Some(h) = got {
        let (e, ea) = (
            ray_triangle_error_bounds(r, t, &h),
            ray_triangle_error_bounds(&ra, &ta, &h),
        );
        assert_eq!([e.t, e.u, e.v].map(fbits), [ea.t, ea.u, ea.v].map(fbits));
        let (q, qa) = (triangle_hit_point(t, &h), triangle_hit_point(&ta, &h));
        assert_eq!((bits(q.0), bits(q.1)), (bits_a(qa.0), bits_a(qa.1)));
        let d = Vec3::new(-0.2, 0.9, 0.4);
        assert_eq!(
            bits(SurfacePoint::on_triangle(t, &h).spawn(d).origin),
            bits_a(SurfacePoint::on_triangle(&ta, &h).spawn(a(d)).origin)
        );
    }
    if let (Some(batch), Some(batch_a)) = (
        TriangleBatch::<Vec3, 8>::from_slice(&[*t]),
        TriangleBatch::<Vec3A, 8>::from_slice(&[ta]),
    ) {
        let (h, ha) = (
            ray_triangle_batch(&p, &batch, t_max),
            ray_triangle_batch(&pa, &batch_a, t_max),
        );
        assert_eq!((h.mask, h.front), (ha.mask, ha.front));
        assert_eq!(h.t.map(fbits), ha.t.map(fbits));
    }
    got.is_some()
}

fn check_plane(pl: &Plane<Vec3>, r: &Ray<Vec3>, t_max: f32) -> bool {
    let (pa, ra) = (Plane::new(a(pl.point), a(pl.normal)), ray(r));
    let got = ray_plane(r, pl, t_max);
    assert_eq!(got.map(fbits), ray_plane(&ra, &pa, t_max).map(fbits));
    if let Some(t) = got {
        assert_eq!(
            ray_plane_t_error(r, pl, t).to_bits(),
            ray_plane_t_error(&ra, &pa, t).to_bits()
        );
        let (q, qa) = (
            ray_plane_hit_point(r, pl, t),
            ray_plane_hit_point(&ra, &pa, t),
        );
        assert_eq!((bits(q.0), bits(q.1)), (bits_a(qa.0), bits_a(qa.1)));
    }
    got.is_some()
}

#[test]
fn vec3a_gives_vec3s_bits_on_the_generators() {
    let (mut hits, mut misses) = (0, 0);
    let mut count = |hit: bool| if hit { hits += 1 } else { misses += 1 };
    for (_, seed, generate) in box_generators::<Vec3>() {
        let mut rng = Pcg32::new(seed ^ 0xa11);
        for _ in 0..2_000 {
            let (b, r, t_max) = generate(&mut rng);
            count(check_box(&b, &r, t_max));
        }
    }
    for (_, seed, generate) in triangle_generators::<Vec3>() {
        let mut rng = Pcg32::new(seed ^ 0xa11);
        for _ in 0..2_000 {
            let (t, r, t_max) = generate(&mut rng);
            count(check_triangle(&t, &r, t_max));
        }
    }
    let mut rng = Pcg32::new(0xa11);
    for _ in 0..4_000 {
        let (pl, r, t_max) = gen_plane::<Vec3>(&mut rng);
        count(check_plane(&pl, &r, t_max));
    }
    // Both answers are common, so agreement means something.
    assert!(
        hits > 10_000 && misses > 10_000,
        "{hits} hits, {misses} misses"
    );
}

#[test]
fn vec3a_gives_vec3s_bits_on_raw_bit_patterns() {
    let mut rng = Pcg32::new(0xb175);
    for _ in 0..20_000 {
        let r = Ray::new(raw_v(&mut rng), raw_v(&mut rng));
        let t_max = if rng.one_in(2) {
            f32::INFINITY
        } else {
            raw(&mut rng)
        };
        check_box(&Aabb::new(raw_v(&mut rng), raw_v(&mut rng)), &r, t_max);
        let t = Triangle::new(raw_v(&mut rng), raw_v(&mut rng), raw_v(&mut rng));
        check_triangle(&t, &r, t_max);
        check_plane(&Plane::new(raw_v(&mut rng), raw_v(&mut rng)), &r, t_max);
    }
}

#[test]
fn vec3a_cameras_give_vec3s_rays() {
    let eye = Vec3::new(0.5, 2.0, 7.0);
    let (view, up) = (Vec3::new(-0.1, -0.3, -1.0), Vec3::Y);
    let cam = PinholeCamera::from_fov(eye, view, up, 0.9, 64, 48).unwrap();
    let cam_a = PinholeCamera::from_fov(a(eye), a(view), a(up), 0.9, 64, 48).unwrap();
    for j in 0..48 {
        for i in 0..64 {
            let (r, ra) = (cam.pixel_ray(i, j), cam_a.pixel_ray(i, j));
            assert_eq!(
                (bits(r.origin), bits(r.dir)),
                (bits_a(ra.origin), bits_a(ra.dir))
            );
        }
    }
}
