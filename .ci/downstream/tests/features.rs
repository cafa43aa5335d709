//! The downstream crate's view of rayhit's features.

use rayhit::glam::Vec3;
use rayhit::{Ray, Triangle};
use rayhit_downstream::*;

fn tri() -> Triangle {
    Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y)
}

#[test]
fn the_kernel_works_without_std() {
    assert_eq!(hit_t(&down_onto(0.25, 0.25), &tri()), Some(1.0));
    assert_eq!(hit_t(&down_onto(0.75, 0.75), &tri()), None);
}

#[cfg(feature = "bytemuck")]
#[test]
fn triangles_are_nine_floats_each() {
    let tris = [tri(), Triangle::new(Vec3::Z, Vec3::ONE, -Vec3::ONE)];
    let bytes = triangle_bytes(&tris);
    assert_eq!(bytes.len(), 2 * 36);
    let floats: Vec<f32> = bytes
        .chunks_exact(4)
        .map(|b| f32::from_ne_bytes(b.try_into().unwrap()))
        .collect();
    assert_eq!(floats[..9], [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]);
    assert_eq!(floats[9..12], [0.0, 0.0, 1.0]);
    assert_eq!(floats[15..18], [-1.0, -1.0, -1.0]);
}

#[cfg(feature = "serde")]
#[test]
fn a_ray_round_trips_with_every_bit() {
    let ray = Ray::new(
        Vec3::new(-0.0, f32::from_bits(0x7fc0_0123), f32::MIN_POSITIVE / 4.0),
        Vec3::new(f32::NEG_INFINITY, 1.0, -2.5),
    );
    let mut buf = [0u8; 64];
    let used = save_ray(&ray, &mut buf).unwrap().len();
    let back: Ray = load_ray(&buf[..used]).unwrap();
    let bits = |r: &Ray| [r.origin.to_array(), r.dir.to_array()].map(|v| v.map(f32::to_bits));
    assert_eq!(bits(&back), bits(&ray));
}
