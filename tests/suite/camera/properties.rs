//! Camera properties: unit directions, the centre pixel, left-right mirror
//! symmetry, agreement with glam's view and projection matrices, and one
//! error per bad input.

use num_traits::Signed;
use proptest::prelude::*;
use rayhit::glam::{DMat4, DVec3, DVec4, Vec3};
use rayhit::strategies as strat;
use rayhit::{Camera, CameraSample, PinholeCamera, Scalar, Vector, camera::CameraError};
use rayhit_testkit::case_count;
use rayhit_testkit::oracle;
use rayhit_testkit::oracle::{R, gamma, rv};

type S<V> = <V as Vector>::Scalar;

fn config() -> ProptestConfig {
    ProptestConfig {
        cases: case_count(1024).try_into().unwrap_or(u32::MAX),
        ..ProptestConfig::default()
    }
}

fn one() -> R {
    R::from_integer(1.into())
}

/// A camera: eye in `[-64, 64]^3`, view from the direction strategy, up at
/// least 30 degrees from the view (sine >= 1/2, so the basis is well
/// conditioned and the bounds below stay tight), image 1 to 64 pixels each
/// way (odd and even), vertical field of view 10 to 150 degrees.
fn camera<V: Vector>() -> impl Strategy<Value = PinholeCamera<V>> {
    (
        strat::point::<V>(64.0),
        strat::direction::<V>(),
        strat::direction::<V>(),
        1u32..=64,
        1u32..=64,
        10.0..=150.0f64,
    )
        .prop_filter_map("up too close to the view", |(eye, view, up, w, h, fov)| {
            let (v, u) = (view.normalize_or_zero(), up.normalize_or_zero());
            if v.cross(u).length().to_f64() < 0.5 {
                return None;
            }
            PinholeCamera::from_fov(eye, view, up, S::<V>::from_f64(fov.to_radians()), w, h).ok()
        })
}

/// Every direction has length 1 within its rounding: `normalize` computes
/// the squared length (`gamma(3)` relative), its square root (halving that,
/// plus one rounding), the reciprocal (one) and the products (one each), so
/// the result's length is within `gamma(6)` of 1, and its square within
/// `2 gamma(6) + gamma(6)^2`.
fn check_unit<V: Vector>(cam: PinholeCamera<V>, x: f64, y: f64) -> Result<(), TestCaseError> {
    let ray = cam.ray(CameraSample::new(S::<V>::from_f64(x), S::<V>::from_f64(y)));
    let d = rv(ray.dir);
    let len2 = oracle::dot(&d, &d);
    let g = gamma::<S<V>>(6);
    prop_assert!(
        (&len2 - one()).abs() <= R::from_integer(2.into()) * &g + &g * &g,
        "length^2 = {}",
        oracle::to_f64(&len2)
    );
    prop_assert_eq!(ray.origin, cam.eye());
    Ok(())
}

/// The centre pixel of an odd-sized image looks along the view direction.
///
/// Its raster offset from the centre is exactly zero, so its direction is
/// `normalize(fl(forward * focal))` with `forward = normalize(view)`: each
/// component is `view_i * c * (1 + theta_i)` for one common positive scale
/// `c` and `|theta_i| <= gamma(3)` (the three products; the reciprocal
/// lengths are common to all components). So `|dir x view| <= gamma(3) c
/// |view|^2` and `c <= (1 + gamma(6)) / (|view| (1 - gamma(3)))`, which
/// the test squares to stay in exact arithmetic.
fn check_centre<V: Vector>(view: V, eye: V, up: V, w: u32, h: u32) -> Result<(), TestCaseError> {
    let Ok(cam) = PinholeCamera::new(eye, view, up, S::<V>::from_f64(100.0), 2 * w + 1, 2 * h + 1)
    else {
        return Ok(());
    };
    let dir = rv(cam.pixel_ray(w, h).dir);
    let v = rv(view);
    prop_assert!(oracle::dot(&dir, &v) > R::from_integer(0.into()));
    let c = oracle::cross(&dir, &v);
    let (g3, g6) = (gamma::<S<V>>(3), gamma::<S<V>>(6));
    let k = &g3 * (one() + &g6) / (one() - &g3);
    prop_assert!(
        oracle::dot(&c, &c) <= &k * &k * oracle::dot(&v, &v),
        "centre pixel off the view direction"
    );
    Ok(())
}

/// Pixels mirrored left-right are mirror images across the plane spanned by
/// the view and up directions: `dir' . right = -(dir . right)`, and the
/// components along forward and up are equal.
///
/// The raster offsets are exact negatives (`i + 0.5 - w/2` is exact), so
/// with the camera's computed basis `F, R, U` the exact combinations are
/// `v = f F + dx R + dy U` and `v' = f F - dx R + dy U`. Computing `v` rounds
/// each component by at most `gamma(3)` of `|f F_i| + |dx R_i| + |dy U_i|`
/// (a vector of length at most `sqrt(3) L`, `L = f + |dx| + |dy|`), and
/// normalising adds `gamma(6)`; with `|v| >= L / sqrt(3)` up to the basis's
/// non-orthogonality, each normalised direction is within `3 gamma(3) +
/// gamma(6) <= gamma(15)` of `v / |v|`, a distance of `2 gamma(15)` between
/// the two sides of each identity. The exact sides differ by the basis's
/// non-orthogonality, measured here exactly: `2 (f |F.R| + |dy| |U.R|)/|v|`
/// and the like, each at most twice the largest `|F.R|, |U.R|, |F.U|`, plus
/// the difference of `|v|` and `|v'|` from the same cause.
fn check_mirror<V: Vector>(cam: PinholeCamera<V>, i: u32, j: u32) -> Result<(), TestCaseError> {
    let (w, h) = (cam.width(), cam.height());
    let (i, j) = (i % w, j % h);
    let a = rv(cam.pixel_ray(i, j).dir);
    let b = rv(cam.pixel_ray(w - 1 - i, j).dir);
    let (f, rt, u) = (rv(cam.forward()), rv(cam.right()), rv(cam.up()));
    let skew = [
        oracle::dot(&f, &rt),
        oracle::dot(&u, &rt),
        oracle::dot(&f, &u),
    ]
    .into_iter()
    .map(|x| x.abs())
    .max()
    .unwrap();
    let bound = R::from_integer(4.into()) * gamma::<S<V>>(15) + R::from_integer(8.into()) * skew;
    let dot = oracle::dot;
    prop_assert!(
        (dot(&a, &rt) + dot(&b, &rt)).abs() <= bound,
        "right components are not opposite"
    );
    prop_assert!(
        (dot(&a, &f) - dot(&b, &f)).abs() <= bound,
        "forward components differ"
    );
    prop_assert!(
        (dot(&a, &u) - dot(&b, &u)).abs() <= bound,
        "up components differ"
    );
    Ok(())
}

/// The f32 camera agrees with unprojecting the pixel through glam's
/// right-handed look-to view matrix and Direct3D-style perspective matrix
/// (depth in [0, 1]), built in f64 from the same (f32) eye, direction, up and
/// field of view. glam 0.34 moved `Mat4::look_to_rh` and
/// `Mat4::perspective_rh` to `glam::camera::rh`; these are the same matrices.
///
/// Bound, first order in u (the f64 reference is exact to ~1e-12): forward
/// is within `eF = sqrt(3) gamma(6)` of exact; right is a cross product of
/// two such unit vectors divided by the sine `s` of their angle, so within
/// `eR = (2 eF + sqrt(2) gamma(2)) / s + sqrt(3) gamma(6)`; up is a cross
/// product of right and forward, within `eU = eR + eF + sqrt(2) gamma(2) +
/// sqrt(3) gamma(6)`. The unnormalised direction `f F + dx R + dy U` is then
/// within `(max(eF, eR, eU) + sqrt(3) gamma(3)) L` with `L = f + |dx| + |dy|
/// <= sqrt(3) |v|`, and normalising doubles the relative error and adds
/// `sqrt(3) gamma(6)`.
fn check_glam(
    cam: PinholeCamera<Vec3>,
    view: Vec3,
    up: Vec3,
    fov: f32,
    x: f64,
    y: f64,
) -> Result<(), TestCaseError> {
    let (w, h) = (f64::from(cam.width()), f64::from(cam.height()));
    let eye = cam.eye().as_dvec3();
    let dir = view.as_dvec3().normalize();
    let up64 = up.as_dvec3().normalize();
    let view_m = rayhit::glam::dcamera::rh::view::look_to_mat4(eye, dir, up64);
    let proj =
        rayhit::glam::dcamera::rh::proj::directx::perspective(f64::from(fov), w / h, 0.5, 100.0);
    let inv: DMat4 = (proj * view_m).inverse();
    let (nx, ny) = (2.0 * x / w - 1.0, 1.0 - 2.0 * y / h);
    let unproject = |z: f64| {
        let p = inv * DVec4::new(nx, ny, z, 1.0);
        p.truncate() / p.w
    };
    let expect: DVec3 = (unproject(1.0) - unproject(0.0)).normalize();
    let got = cam
        .ray(CameraSample::new(x as f32, y as f32))
        .dir
        .as_dvec3();

    let u = f64::from(f32::UNIT_ROUNDOFF);
    let g = |n: f64| n * u / (1.0 - n * u);
    let s = dir.cross(up64).length();
    let (r2, r3) = (2f64.sqrt(), 3f64.sqrt());
    let e_f = r3 * g(6.0);
    let e_r = (2.0 * e_f + r2 * g(2.0)) / s + r3 * g(6.0);
    let e_u = e_r + e_f + r2 * g(2.0) + r3 * g(6.0);
    let dv = e_f.max(e_r).max(e_u) + r3 * g(3.0);
    let bound = 2.0 * r3 * dv + r3 * g(6.0) + 1e-12;
    prop_assert!(
        (got - expect).length() <= bound,
        "{got} vs glam {expect}: {} > {bound}",
        (got - expect).length()
    );
    Ok(())
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn unit_directions_f32(cam in camera::<Vec3>(), x in -10.0..74.0f64, y in -10.0..74.0f64) {
        check_unit(cam, x, y)?;
    }

    #[test]
    fn unit_directions_f64(cam in camera::<DVec3>(), x in -10.0..74.0f64, y in -10.0..74.0f64) {
        check_unit(cam, x, y)?;
    }

    #[test]
    fn centre_pixel_f32(view in strat::direction::<Vec3>(), eye in strat::point::<Vec3>(64.0), up in strat::direction::<Vec3>(), w in 0u32..32, h in 0u32..32) {
        check_centre(view, eye, up, w, h)?;
    }

    #[test]
    fn centre_pixel_f64(view in strat::direction::<DVec3>(), eye in strat::point::<DVec3>(64.0), up in strat::direction::<DVec3>(), w in 0u32..32, h in 0u32..32) {
        check_centre(view, eye, up, w, h)?;
    }

    #[test]
    fn mirror_symmetry_f32(cam in camera::<Vec3>(), i in 0u32..64, j in 0u32..64) {
        check_mirror(cam, i, j)?;
    }

    #[test]
    fn mirror_symmetry_f64(cam in camera::<DVec3>(), i in 0u32..64, j in 0u32..64) {
        check_mirror(cam, i, j)?;
    }

    #[test]
    fn agrees_with_glam(eye in strat::point::<Vec3>(64.0), view in strat::direction::<Vec3>(), up in strat::direction::<Vec3>(),
                        w in 1u32..=64, h in 1u32..=64, fov in 10.0..=150.0f32, fx in 0.0..=1.0f64, fy in 0.0..=1.0f64) {
        let (v, u) = (view.normalize(), up.normalize());
        prop_assume!(v.cross(u).length() >= 0.5);
        let cam = PinholeCamera::from_fov(eye, view, up, fov.to_radians(), w, h).unwrap();
        check_glam(cam, view, up, fov.to_radians(), fx * f64::from(w), fy * f64::from(h))?;
    }
}

/// Worked example with numbers checkable by hand: a 4x2 image with focal
/// length 2 looking down -z with y up. Pixel (0, 0) has its centre at raster
/// (0.5, 0.5): offset (-1.5, +0.5) from the image centre (2, 1), so its
/// direction is (-1.5, 0.5, -2) normalised, length sqrt(6.5).
#[test]
fn corner_pixel_by_hand() {
    let cam = PinholeCamera::new(
        Vec3::new(1.0, 2.0, 3.0),
        Vec3::new(0.0, 0.0, -5.0),
        Vec3::new(0.0, 3.0, 0.0),
        2.0,
        4,
        2,
    )
    .unwrap();
    let d = cam.pixel_ray(0, 0).dir;
    let expect = Vec3::new(-1.5, 0.5, -2.0) / 6.5f32.sqrt();
    assert!((d - expect).length() < 1e-6, "{d} vs {expect}");
    assert_eq!(cam.pixel_ray(0, 0).origin, Vec3::new(1.0, 2.0, 3.0));
    assert_eq!(cam.right(), Vec3::X);
    assert_eq!(cam.up(), Vec3::Y);
    // y grows downwards: the bottom-right pixel looks right and down.
    let d = cam.pixel_ray(3, 1).dir;
    assert!(d.x > 0.0 && d.y < 0.0 && d.z < 0.0);
}

#[test]
fn one_error_per_bad_input() {
    let (e, v, u) = (Vec3::ZERO, -Vec3::Z, Vec3::Y);
    let new = |e, v, u, f, w, h| PinholeCamera::new(e, v, u, f, w, h).err();
    assert_eq!(
        new(Vec3::new(f32::NAN, 0.0, 0.0), v, u, 1.0, 1, 1),
        Some(CameraError::NonFiniteEye)
    );
    assert_eq!(
        new(Vec3::new(f32::INFINITY, 0.0, 0.0), v, u, 1.0, 1, 1),
        Some(CameraError::NonFiniteEye)
    );
    assert_eq!(
        new(e, Vec3::ZERO, u, 1.0, 1, 1),
        Some(CameraError::InvalidViewDir)
    );
    assert_eq!(
        new(e, Vec3::new(0.0, f32::NAN, -1.0), u, 1.0, 1, 1),
        Some(CameraError::InvalidViewDir)
    );
    assert_eq!(
        new(e, v, Vec3::ZERO, 1.0, 1, 1),
        Some(CameraError::InvalidUp)
    );
    assert_eq!(
        new(e, v, Vec3::new(f32::INFINITY, 1.0, 0.0), 1.0, 1, 1),
        Some(CameraError::InvalidUp)
    );
    assert_eq!(
        new(e, v, Vec3::Z, 1.0, 1, 1),
        Some(CameraError::UpParallelToView)
    );
    assert_eq!(
        new(e, v, Vec3::new(0.0, 1e-9, -1.0), 1.0, 1, 1),
        Some(CameraError::UpParallelToView)
    );
    assert_eq!(
        new(e, v, u, 0.0, 1, 1),
        Some(CameraError::InvalidFocalLength)
    );
    assert_eq!(
        new(e, v, u, -1.0, 1, 1),
        Some(CameraError::InvalidFocalLength)
    );
    assert_eq!(
        new(e, v, u, f32::NAN, 1, 1),
        Some(CameraError::InvalidFocalLength)
    );
    assert_eq!(
        new(e, v, u, f32::INFINITY, 1, 1),
        Some(CameraError::InvalidFocalLength)
    );
    assert_eq!(new(e, v, u, 1.0, 0, 1), Some(CameraError::EmptyImage));
    assert_eq!(new(e, v, u, 1.0, 1, 0), Some(CameraError::EmptyImage));
    let fov = |f| PinholeCamera::from_fov(e, v, u, f, 1, 1).err();
    for bad in [0.0, -1.0, std::f32::consts::PI, 4.0, f32::NAN] {
        assert_eq!(fov(bad), Some(CameraError::InvalidFieldOfView), "fov {bad}");
    }
    assert_eq!(fov(3.0), None);
    // Messages are readable and the type is a std error.
    let err: Box<dyn std::error::Error> = Box::new(CameraError::UpParallelToView);
    assert_eq!(
        err.to_string(),
        "camera up vector is parallel to the view direction"
    );
    // A nearly parallel but resolvable up vector is fine (sine 1e-3).
    assert!(PinholeCamera::new(e, v, Vec3::new(0.0, 1e-3, -1.0), 1.0, 1, 1).is_ok());
}
