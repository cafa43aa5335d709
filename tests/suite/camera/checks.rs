//! The cameras beyond the pinhole: each camera's checks (the ones its fuzz
//! target runs, in `rayhit_testkit::fuzz`) on seeded structured cases in
//! both precisions, and worked examples with numbers a reader can check.
//!
//! More cases: `RAYHIT_CASES=250 cargo test --release --test suite camera::checks::`.

use rayhit::glam::{DVec3, Vec3};
use rayhit::{
    Camera, CameraSample, PinholeCamera,
    camera::{CameraError, ThinLensCamera},
};
use rayhit_testkit::fuzz::{Check, Input};
use rayhit_testkit::source::Source;

/// Cases per check and precision: 400 times `RAYHIT_CASES`.
fn cases() -> u64 {
    rayhit_testkit::case_count(400) as u64
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
    let diff = cam.ray_differential(CameraSample::new(1.5, 1.5).with_lens(1.0, 0.5));
    assert_eq!(diff.dx_dir, Vec3::new(0.5, 0.0, 0.0));
    assert_eq!(diff.dy_dir, Vec3::new(0.0, -0.5, 0.0));
    // Zero radius: the pinhole camera, bit for bit, whatever the sample.
    let flat = ThinLensCamera::new(pinhole, 0.0, 4.0).unwrap();
    assert_eq!(
        flat.ray(CameraSample::new(0.3, 2.9).with_lens(0.1, 0.7)),
        pinhole.ray(CameraSample::new(0.3, 2.9))
    );
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
    use rayhit::camera::OrthographicCamera;
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
    let diff = cam.ray_differential(CameraSample::new(0.5, 0.5));
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

#[test]
fn matrix_camera_checks() {
    structured::<rayhit_testkit::fuzz::matrix_camera::MatrixCameraCheck>(0x3a72);
}

#[test]
fn pinhole_checks() {
    structured::<rayhit_testkit::fuzz::camera::Camera>(0x914e);
}

/// The matrix camera of glam's `f32` look-to and Direct3D perspective
/// matrices agrees with the pinhole camera of the same eye, view, up and
/// focal length (`P[1][1] height / 2`, from the matrix itself, rounded
/// once), within the sum of their distances from the exact camera.
///
/// Bound (first order in `u`, as `camera::properties`'s `check_glam`): with
/// `s` the sine between view and up, each camera's basis vectors are
/// within `e = max(e_F, e_R, e_U)` of the exact ones (`e_F = sqrt(3)
/// gamma(6)`, `e_R = (2 e_F + sqrt(2) gamma(2)) / s + sqrt(3) gamma(6)`,
/// `e_U = e_R + e_F + sqrt(2) gamma(2) + sqrt(3) gamma(6)`; glam's
/// look-to makes the same normalised vectors, and its `u` unnormalised is
/// no further). The pinhole ray is then within `2 sqrt(3) (e + sqrt(3)
/// gamma(3)) + sqrt(3) gamma(6)` of the exact direction. The matrix
/// camera's exact ray (of the float matrices) uses the inverse of the
/// view's rotation, whose rows are orthonormal within `2 e` per entry:
/// `sqrt(3) 6 e` more than the transpose; its focal lengths are the
/// pinhole's within `2 u` across (`aspect` and `P[0][0]` rounded) and `u`
/// (the pinhole's focal rounded), moving a ray by at most `3 u (|dx| +
/// |dy|) / f`; the view's translation (`-eye . s`, three roundings each,
/// within `gamma(3) sqrt(3) |eye|`) moves the camera centre by at most
/// `3 gamma(3)` of `|eye| <= sqrt(3) max |eye_i|` through the rotation's
/// inverse (norm `1 + 6 e`), and the camera's eye is one rounding (and
/// `f64`'s) from that; and its
/// computed ray is within `2 (gamma(5) + gamma_64(17)) |K| / |p|` of its
/// exact one (`K` the linear form's magnitudes, at most `3 |p|` here: `|c|
/// ~ f`, `|dx a|`, `|dy b|` each at most `|p|`).
#[test]
fn matrix_agrees_with_pinhole() {
    use rayhit::glam::camera::rh::{proj::directx, view};
    use rayhit::{
        Scalar,
        camera::{ClipSpace, MatrixCamera},
    };
    let mut src = Source::seeded(0xa9e5);
    let u = f64::from(f32::UNIT_ROUNDOFF);
    let g = |n: u32| f64::from(f32::gamma_n(n));
    let (r2, r3) = (2f64.sqrt(), 3f64.sqrt());
    let mut checked = 0;
    for _ in 0..cases() {
        let eye = Vec3::new(
            src.range(-64.0, 64.0) as f32,
            src.range(-64.0, 64.0) as f32,
            src.range(-64.0, 64.0) as f32,
        );
        let d = src.direction();
        let up_d = src.direction();
        let dir = Vec3::new(d[0] as f32, d[1] as f32, d[2] as f32).normalize();
        let up = Vec3::new(up_d[0] as f32, up_d[1] as f32, up_d[2] as f32).normalize();
        let s = f64::from(dir.cross(up).length());
        if s < 0.5 {
            continue;
        }
        let (w, h) = (1 + src.below(2048), 1 + src.below(2048));
        let fov = src.range(10.0, 150.0).to_radians() as f32;
        let proj = directx::perspective(fov, w as f32 / h as f32, 0.1, 1000.0);
        let cam = MatrixCamera::from_mat4(
            view::look_to_mat4(eye, dir, up),
            proj,
            ClipSpace::Direct3D,
            w,
            h,
        )
        .unwrap();
        let focal = proj.y_axis.y * (h as f32 * 0.5);
        let pinhole = PinholeCamera::new(eye, dir, up, focal, w, h).unwrap();
        let (i, j) = (src.below(w), src.below(h));
        let (a, b) = (cam.pixel_ray(i, j), pinhole.pixel_ray(i, j));
        let e_f = r3 * g(6);
        let e_r = (2.0 * e_f + r2 * g(2)) / s + r3 * g(6);
        let e = e_r + e_f + r2 * g(2) + r3 * g(6);
        let pin = 2.0 * r3 * (e + r3 * g(3)) + r3 * g(6);
        let (dx, dy) = (
            (f64::from(i) + 0.5 - f64::from(w) / 2.0).abs(),
            (f64::from(j) + 0.5 - f64::from(h) / 2.0).abs(),
        );
        let f = f64::from(focal);
        let mat =
            pin + r3 * 6.0 * e + 3.0 * u * (dx + dy) / f + 2.0 * (g(5) + f64::gamma_n(17)) * 3.0;
        let gap = (a.dir - b.dir).length();
        assert!(
            f64::from(gap) <= (pin + mat) * (1.0 + 1e-6),
            "{gap} > {}: pixel ({i}, {j}) of {w}x{h}, fov {fov}, {cam:?} vs {pinhole:?}",
            pin + mat
        );
        let eye_gap = (a.origin - b.origin).abs().max_element();
        let eye_bound =
            (3.0 * r3 * g(3) + 2.0 * u) * (1.0 + 6.0 * e) * f64::from(eye.abs().max_element());
        assert!(
            f64::from(eye_gap) <= eye_bound.max(1e-30),
            "eye {} vs {}: {eye_gap} > {eye_bound}",
            a.origin,
            b.origin
        );
        checked += 1;
    }
    assert!(checked > cases() / 4, "{checked}");
}

/// Errors, and glam's orthographic matrices by hand: a 4x2 image of the
/// box `[-2, 2] x [-1, 1]` seen down `-z` from `z = 10`, near 1, far 21:
/// pixel (0, 0)'s ray starts at `(-1.5, 0.5, 9)` on the near plane and
/// runs down `-z`; Vulkan's `y` runs the other way.
#[test]
fn matrix_camera_by_hand() {
    use rayhit::camera::{ClipSpace, MatrixCamera};
    use rayhit::glam::camera::rh::{proj::directx, proj::vulkan, view};
    use rayhit::glam::{Mat4, Vec4};
    let v = view::look_to_mat4(Vec3::new(0.0, 0.0, 10.0), -Vec3::Z, Vec3::Y);
    let p = directx::orthographic(-2.0, 2.0, -1.0, 1.0, 1.0, 21.0);
    let cam = MatrixCamera::from_mat4(v, p, ClipSpace::Direct3D, 4, 2).unwrap();
    assert!(cam.is_orthographic());
    let ray = cam.pixel_ray(0, 0);
    assert_eq!(ray.origin, Vec3::new(-1.5, 0.5, 9.0));
    assert_eq!(ray.dir, -Vec3::Z);
    let pv = vulkan::orthographic(-2.0, 2.0, -1.0, 1.0, 1.0, 21.0);
    let cam = MatrixCamera::from_mat4(v, pv, ClipSpace::Vulkan, 4, 2).unwrap();
    assert_eq!(cam.pixel_ray(0, 0).origin, Vec3::new(-1.5, 0.5, 9.0));
    // One error per bad input.
    let mut nan = p;
    nan.x_axis.x = f32::NAN;
    let err = |v: Mat4, p: Mat4| MatrixCamera::from_mat4(v, p, ClipSpace::Direct3D, 4, 2).err();
    assert_eq!(err(v, nan), Some(CameraError::NonFiniteMatrix));
    assert_eq!(err(Mat4::ZERO, p), Some(CameraError::SingularMatrix));
    let mut flat = p;
    flat.y_axis = Vec4::ZERO;
    assert_eq!(err(v, flat), Some(CameraError::SingularMatrix));
    assert_eq!(
        MatrixCamera::from_mat4(v, p, ClipSpace::Direct3D, 0, 2).err(),
        Some(CameraError::EmptyImage)
    );
    // The perspective camera's cone: the pinhole's angle, atan(1 / f).
    let persp = directx::perspective(1.0, 1.0, 0.1, 100.0);
    let cam = MatrixCamera::from_mat4(v, persp, ClipSpace::Direct3D, 64, 64).unwrap();
    let f = persp.y_axis.y * 32.0;
    assert!((cam.ray_cone().spread - (1.0 / f).atan()).abs() < 1e-6);
}

#[test]
fn hit_differentials_checks() {
    structured::<rayhit_testkit::fuzz::hit_differentials::HitDifferentialsCheck>(0xd1ff);
}

/// Every camera's basis (one construction, `PinholeCamera`'s, shared by
/// all) is orthonormal within `gamma(13)`: each entry of `B^T B - I`, for
/// random view and up vectors and for up vectors turned from the view by
/// angles down to the cameras' limit (a sine of `gamma(16)`), where the
/// cross product alone would leave `right` tilted towards `forward` by its
/// rounding over that sine. Both precisions.
#[test]
fn every_basis_is_orthonormal_within_gamma_13() {
    use rayhit::Scalar;
    use rayhit_testkit::fuzz::panoramic::basis_skew;
    use rayhit_testkit::rng::Pcg32;
    let mut rng = Pcg32::new(0xba5e);
    let mut near = [0u32; 2];
    for i in 0..rayhit_testkit::case_count(4000) {
        let view = rng.sphere().as_dvec3() * f64::from(rng.range(0.01, 100.0));
        let up = if i % 2 == 0 {
            rng.sphere().as_dvec3()
        } else {
            // The view turned by an angle whose sine is 10^-1 .. 10^-15.
            let sine = 10f64.powf(-f64::from(rng.range(1.0, 15.0)));
            let side = view.cross(rng.sphere().as_dvec3()).normalize();
            view.normalize() + side * sine
        };
        if let Ok(c) = PinholeCamera::new(Vec3::ZERO, view.as_vec3(), up.as_vec3(), 1.0, 1, 1) {
            let g = f64::from(f32::gamma_n(13));
            let skew = basis_skew([c.right(), c.up(), c.forward()]);
            assert!(skew <= g + 4.0 * f64::EPSILON, "{view} {up}: {skew}");
            near[0] += u32::from(
                i % 2 == 1 && c.forward().cross(up.as_vec3().normalize()).length() < 1e-4,
            );
        }
        if let Ok(c) = PinholeCamera::new(DVec3::ZERO, view, up, 1.0, 1, 1) {
            let g = f64::gamma_n(13);
            let skew = basis_skew([c.right(), c.up(), c.forward()]);
            assert!(skew <= g + 4.0 * f64::EPSILON, "{view} {up}: {skew}");
            near[1] += u32::from(i % 2 == 1 && c.forward().cross(up.normalize()).length() < 1e-12);
        }
    }
    // Not vacuous: many nearly parallel up vectors were accepted.
    assert!(near[0] > 100 && near[1] > 50, "{near:?}");
}
