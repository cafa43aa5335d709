//! The cameras beyond the pinhole: each camera's checks (the ones its fuzz
//! target runs, in `rayhit_testkit::fuzz`) on seeded structured cases in
//! both precisions, and worked examples with numbers a reader can check.
//!
//! More cases: `CAMERA_CASES=100000 cargo test --release --test cameras`.

use rayhit::glam::{DVec3, Vec3};
use rayhit::{CameraError, PinholeCamera, ThinLensCamera};
use rayhit_testkit::fuzz::{Check, Input};
use rayhit_testkit::source::Source;

/// Cases per check and precision: `CAMERA_CASES`, or 1000.
fn cases() -> u64 {
    std::env::var("CAMERA_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1000)
}

/// Runs `C`'s structured checks on seeded sources, in `f32` and `f64`.
fn structured<C: Check>(seed: u64) {
    for i in 0..cases() {
        let mut input = Input::Structured(Box::new(Source::seeded(seed ^ (i << 20))));
        C::run::<Vec3>(&mut input);
        let mut input = Input::Structured(Box::new(Source::seeded(seed ^ (i << 20) ^ 1)));
        C::run::<DVec3>(&mut input);
    }
}

#[test]
fn thin_lens_checks() {
    structured::<rayhit_testkit::fuzz::thin_lens::ThinLens>(0x7e25);
}

/// A lens of radius 1 at the origin looking down `-z`, focused at 4: the
/// focus point of the centre pixel is `(0, 0, -4)`, and the lens sample
/// `(1, 0.5)` is the lens's right edge, `(1, 0, 0)` (the concentric map
/// sends `a = 1, b = 0` to radius 1, angle 0): its ray is `(-1, 0, -4)`
/// from there.
#[test]
fn thin_lens_by_hand() {
    let pinhole = PinholeCamera::new(Vec3::ZERO, -Vec3::Z, Vec3::Y, 8.0, 3, 3).unwrap();
    let cam = ThinLensCamera::new(pinhole, 1.0, 4.0).unwrap();
    let focus = cam.focus(1.5, 1.5);
    assert_eq!(focus.point(), Vec3::new(0.0, 0.0, -4.0));
    let ray = cam.ray_through(&focus, 1.0, 0.5);
    assert_eq!(ray.origin, Vec3::new(1.0, 0.0, 0.0));
    assert_eq!(ray.dir, Vec3::new(-1.0, 0.0, -4.0));
    // The pixel to the right: its focus point is half a unit over (one
    // pixel is 4 / 8 units on the plane of focus).
    assert_eq!(cam.focus(2.5, 1.5).point(), Vec3::new(0.5, 0.0, -4.0));
    let diff = cam.ray_differential(1.5, 1.5, 1.0, 0.5);
    assert_eq!(diff.dx_dir, Vec3::new(0.5, 0.0, 0.0));
    assert_eq!(diff.dy_dir, Vec3::new(0.0, -0.5, 0.0));
    // Zero radius: the pinhole camera, bit for bit, whatever the sample.
    let flat = ThinLensCamera::new(pinhole, 0.0, 4.0).unwrap();
    assert_eq!(flat.ray(0.3, 2.9, 0.1, 0.7), pinhole.ray(0.3, 2.9));
    // One error per bad input.
    let err = |r: f32, d: f32| ThinLensCamera::new(pinhole, r, d).err();
    for bad in [-1.0, f32::NAN, f32::INFINITY] {
        assert_eq!(err(bad, 1.0), Some(CameraError::InvalidLensRadius));
    }
    for bad in [0.0, -1.0, f32::NAN, f32::INFINITY] {
        assert_eq!(err(0.5, bad), Some(CameraError::InvalidFocalDistance));
    }
    assert_eq!(err(f32::MAX, 1.0), Some(CameraError::InvalidLensRadius));
    assert_eq!(err(1.0, 1e-45), Some(CameraError::InvalidFocalDistance));
}

#[test]
fn orthographic_checks() {
    structured::<rayhit_testkit::fuzz::orthographic::Orthographic>(0x0e7f);
}

/// A camera 1000 units up, pixels 1/8 wide: the origins are on the plane
/// through the centre, exactly here (every product and sum is exact), and
/// carry the centre's precision, not the height's: the origin of pixel
/// (0, 0) is `(0.125 * (0.5 - 2), 1000, ...)`.
#[test]
fn orthographic_by_hand() {
    use rayhit::OrthographicCamera;
    let cam = OrthographicCamera::new(
        Vec3::new(3.0, 1000.0, -2.0),
        -Vec3::Y,
        -Vec3::Z,
        0.125,
        4,
        4,
    )
    .unwrap();
    let ray = cam.pixel_ray(0, 0);
    assert_eq!(ray.origin, Vec3::new(3.0 - 0.1875, 1000.0, -2.0 - 0.1875));
    assert_eq!(ray.dir, -Vec3::Y);
    let diff = cam.ray_differential(0.5, 0.5);
    assert_eq!(diff.dx_origin, Vec3::new(0.125, 0.0, 0.0));
    assert_eq!(diff.dy_origin, Vec3::new(0.0, 0.0, 0.125));
    assert_eq!(cam.ray_cone().width, 0.125);
    let err = |s: f32| OrthographicCamera::new(Vec3::ZERO, -Vec3::Z, Vec3::Y, s, 4, 4).err();
    for bad in [0.0, -1.0, f32::NAN, f32::INFINITY] {
        assert_eq!(err(bad), Some(CameraError::InvalidPixelSize));
    }
}

#[test]
fn equirectangular_checks() {
    structured::<rayhit_testkit::fuzz::panoramic::Equirectangular>(0x3a11);
}

#[test]
fn equal_area_checks() {
    structured::<rayhit_testkit::fuzz::panoramic::EqualArea>(0xea5e);
}
