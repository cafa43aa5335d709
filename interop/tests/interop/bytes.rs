//! The `bytemuck` and `serde` features: slices of shapes cast to bytes and
//! back, with the layout a GPU or a file reader expects, and serde round
//! trips that keep every bit of every float (NaN payloads, `-0.0`,
//! infinities, subnormals) in a binary format.

use core::mem::size_of;

use rayhit::glam::{DVec3, Vec3};
use rayhit::{
    Aabb, BoxFace, BoxHit, Plane, Ray, Side, Triangle, TriangleHit, TriangleHitError, ValidAabb,
};

/// Floats whose bits a careless conversion would change: a signalling NaN
/// with a payload, a quiet NaN with the sign set, `-0.0`, both infinities,
/// the smallest subnormal and the largest finite value.
const AWKWARD32: [u32; 8] = [
    0x7f80_0001,
    0xffc0_1234,
    0x8000_0000,
    0x7f80_0000,
    0xff80_0000,
    0x0000_0001,
    0x7f7f_ffff,
    0x3f80_0000,
];
const AWKWARD64: [u64; 8] = [
    0x7ff0_0000_0000_0001,
    0xfff8_0000_0000_1234,
    0x8000_0000_0000_0000,
    0x7ff0_0000_0000_0000,
    0xfff0_0000_0000_0000,
    0x0000_0000_0000_0001,
    0x7fef_ffff_ffff_ffff,
    0x3ff0_0000_0000_0000,
];

fn v32(i: usize) -> Vec3 {
    let f = |k: usize| f32::from_bits(AWKWARD32[(i + k) % AWKWARD32.len()]);
    Vec3::new(f(0), f(1), f(2))
}

fn v64(i: usize) -> DVec3 {
    let f = |k: usize| f64::from_bits(AWKWARD64[(i + k) % AWKWARD64.len()]);
    DVec3::new(f(0), f(1), f(2))
}

fn bits32(v: Vec3) -> [u32; 3] {
    v.to_array().map(f32::to_bits)
}

fn bits64(v: DVec3) -> [u64; 3] {
    v.to_array().map(f64::to_bits)
}

#[test]
fn the_plain_types_are_their_fields_in_order_with_no_padding() {
    assert_eq!(size_of::<Ray<Vec3>>(), 6 * 4);
    assert_eq!(size_of::<Aabb<Vec3>>(), 6 * 4);
    assert_eq!(size_of::<Triangle<Vec3>>(), 9 * 4);
    assert_eq!(size_of::<Plane<Vec3>>(), 6 * 4);
    assert_eq!(size_of::<TriangleHitError<f32>>(), 3 * 4);
    assert_eq!(size_of::<Triangle<DVec3>>(), 9 * 8);
    assert_eq!(size_of::<ValidAabb<DVec3>>(), 6 * 8);
}

#[test]
fn a_slice_of_triangles_is_its_corners_as_bytes_and_back() {
    let tris: Vec<Triangle> = (0..5)
        .map(|i| Triangle::new(v32(i), v32(i + 1), v32(i + 2)))
        .collect();
    let bytes: &[u8] = bytemuck::cast_slice(&tris);
    // What a GPU reading nine floats per triangle sees, built independently.
    let expected: Vec<u8> = tris
        .iter()
        .flat_map(|t| [t.a, t.b, t.c])
        .flat_map(|v| bits32(v).map(u32::to_ne_bytes))
        .flatten()
        .collect();
    assert_eq!(bytes, &expected[..]);
    // Back from a buffer that need not be aligned for f32.
    let back: Vec<Triangle> = bytemuck::pod_collect_to_vec(&expected);
    assert_eq!(back.len(), tris.len());
    for (x, y) in back.iter().zip(&tris) {
        for (p, q) in [(x.a, y.a), (x.b, y.b), (x.c, y.c)] {
            assert_eq!(bits32(p), bits32(q));
        }
    }
}

#[test]
fn rays_boxes_and_planes_cast_in_both_precisions() {
    let rays = [Ray::new(v64(0), v64(3)), Ray::new(v64(5), v64(1))];
    let bytes: &[u8] = bytemuck::cast_slice(&rays);
    assert_eq!(bytes.len(), 2 * 6 * 8);
    assert_eq!(bytes[8..16], AWKWARD64[1].to_ne_bytes());
    let back: Vec<Ray<DVec3>> = bytemuck::pod_collect_to_vec(bytes);
    assert_eq!(bits64(back[1].dir), bits64(rays[1].dir));

    let plane = Plane::new(v32(2), v32(4));
    let b: [u8; 24] = bytemuck::cast(plane);
    let p: Plane = bytemuck::cast(b);
    assert_eq!(
        (bits32(p.point), bits32(p.normal)),
        (bits32(plane.point), bits32(plane.normal))
    );
    let zero: Aabb<DVec3> = bytemuck::Zeroable::zeroed();
    assert_eq!(zero, Aabb::new(DVec3::ZERO, DVec3::ZERO));
}

#[test]
fn bytes_become_a_valid_box_only_when_the_box_is_valid() {
    let good = Aabb::new(Vec3::ZERO, Vec3::ONE);
    let inverted = Aabb::new(Vec3::ONE, Vec3::ZERO);
    let nan = Aabb::new(Vec3::ZERO, Vec3::new(1.0, f32::NAN, 1.0));
    let valid = [ValidAabb::new(good).unwrap()];
    // A valid box writes as the box it holds.
    assert_eq!(bytemuck::bytes_of(&valid[0]), bytemuck::bytes_of(&good));
    let boxes = [good, good];
    let ok: &[ValidAabb] =
        bytemuck::checked::try_cast_slice(bytemuck::cast_slice::<_, u8>(&boxes)).unwrap();
    assert_eq!(ok, &[valid[0], valid[0]]);
    for bad in [inverted, nan] {
        let bytes = bytemuck::cast_slice::<_, u8>(core::slice::from_ref(&bad));
        assert!(bytemuck::checked::try_cast_slice::<u8, ValidAabb>(bytes).is_err());
    }
}

fn round_trip<T: serde::Serialize + serde::de::DeserializeOwned>(x: &T) -> T {
    let bytes = postcard::to_allocvec(x).unwrap();
    postcard::from_bytes(&bytes).unwrap()
}

#[test]
fn a_ray_round_trips_through_serde_with_every_bit() {
    for i in 0..AWKWARD32.len() {
        let ray = Ray::new(v32(i), v32(i + 4));
        let back = round_trip(&ray);
        assert_eq!(
            (bits32(back.origin), bits32(back.dir)),
            (bits32(ray.origin), bits32(ray.dir))
        );
        let dray = Ray::new(v64(i), v64(i + 4));
        let back = round_trip(&dray);
        assert_eq!(
            (bits64(back.origin), bits64(back.dir)),
            (bits64(dray.origin), bits64(dray.dir))
        );
    }
}

#[test]
fn shapes_and_hits_round_trip_through_serde() {
    let tri = Triangle::new(v32(0), v32(1), v32(2));
    let back = round_trip(&tri);
    assert_eq!(
        [back.a, back.b, back.c].map(bits32),
        [tri.a, tri.b, tri.c].map(bits32)
    );
    let plane = Plane::new(v64(3), v64(6));
    let back = round_trip(&plane);
    assert_eq!(
        [back.point, back.normal].map(bits64),
        [plane.point, plane.normal].map(bits64)
    );
    let hit = TriangleHit {
        t: -0.0f32,
        u: f32::from_bits(1),
        v: 0.5,
        side: Side::Back,
    };
    let back = round_trip(&hit);
    assert_eq!(
        [back.t, back.u, back.v].map(f32::to_bits),
        [hit.t, hit.u, hit.v].map(f32::to_bits)
    );
    assert_eq!(back.side, Side::Back);
    for face in [None, Some(BoxFace::MinY), Some(BoxFace::MaxZ)] {
        let hit = BoxHit {
            enter: 1.0f64,
            exit: f64::INFINITY,
            face,
        };
        assert_eq!(round_trip(&hit), hit);
    }
    let err = TriangleHitError {
        t: 1e-7f32,
        u: 0.0,
        v: f32::INFINITY,
    };
    assert_eq!(round_trip(&err), err);
}

#[test]
fn a_valid_box_is_checked_when_it_is_read() {
    let good = ValidAabb::new(Aabb::new(DVec3::ZERO, DVec3::ONE)).unwrap();
    assert_eq!(round_trip(&good), good);
    // Written as its box: the bytes of a plain box read as a valid box.
    assert_eq!(
        postcard::to_allocvec(&good).unwrap(),
        postcard::to_allocvec(good.aabb()).unwrap()
    );
    for bad in [
        Aabb::new(DVec3::ONE, DVec3::ZERO),
        Aabb::new(DVec3::ZERO, DVec3::new(f64::INFINITY, 1.0, 1.0)),
        Aabb::new(DVec3::new(f64::NAN, 0.0, 0.0), DVec3::ONE),
    ] {
        let bytes = postcard::to_allocvec(&bad).unwrap();
        assert!(postcard::from_bytes::<ValidAabb<DVec3>>(&bytes).is_err());
    }
}
