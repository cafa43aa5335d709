//! Inputs the fuzzers (`fuzz/`) found in the cameras and ray differentials,
//! kept as literal floats. Each test says which target found its input and
//! what went wrong: a fault of the fuzzer's check, of the kernel, or of the
//! docs (see the suite's documentation, `tests/suite/main.rs`).

use rayhit::glam::{DVec3, Vec3};
use rayhit::{Camera, CameraSample, PinholeCamera, Ray, Triangle, ray_triangle};
use rayhit_testkit::oracle::{R, r};

/// `camera` (raw): a finite, nonzero view direction whose squared length
/// underflows (`4.8e-44` along x, a subnormal) was rejected as
/// `InvalidViewDir`, which the docs define as "zero or not finite"; so were
/// views and up vectors whose squared length overflows (`1e30`). The camera
/// now normalises in a frame scaled by a power of two.
#[test]
fn camera_view_with_underflowing_length() {
    let tiny = f32::from_bits(34); // 4.8e-44
    for (view, up) in [
        (Vec3::new(tiny, 0.0, 0.0), Vec3::Y),
        (Vec3::new(1e30, 0.0, 0.0), Vec3::Y),
        (-Vec3::Z, Vec3::new(0.0, tiny, 0.0)),
        (-Vec3::Z, Vec3::new(0.0, 3e38, 3e38)),
    ] {
        assert!(view.is_finite() && view != Vec3::ZERO);
        let cam = PinholeCamera::new(Vec3::ZERO, view, up, 1.0, 1, 1).expect("valid camera");
        // The one pixel looks along the view direction (exactly: x and y are
        // at the image centre), and is a unit vector.
        let dir = cam.pixel_ray(0, 0).dir;
        let axis = if view.x != 0.0 { Vec3::X } else { -Vec3::Z };
        assert_eq!(dir, axis, "view {view}, up {up}");
    }
}

/// Found while writing the `camera` target: a focal length is accepted when
/// positive and finite, but above about `2^64` pixels the squared length of
/// every ray direction overflowed and `ray` returned a zero direction, not
/// the documented unit one; below about `2^-64` the centre pixel's squared
/// length underflowed the same way.
#[test]
fn camera_huge_focal_length_gives_unit_directions() {
    for focal in [1e30, 1e-30] {
        let cam = PinholeCamera::new(Vec3::ZERO, -Vec3::Z, Vec3::Y, focal, 3, 3).unwrap();
        // The centre pixel of an odd image looks exactly along the view.
        assert_eq!(cam.pixel_ray(1, 1).dir, -Vec3::Z, "focal {focal}");
        // A corner: the documented unit length (gamma(6), about 4e-7).
        let dir = cam.pixel_ray(0, 0).dir;
        assert!((dir.length() - 1.0).abs() < 1e-6, "focal {focal}: {dir}");
    }
}

/// `thin_lens` (raw): a zero lens radius and a NaN lens sample. The ray
/// went down the lens's path (the offset `0 * NaN` is NaN, not zero) and
/// came out NaN; the docs say a zero radius is the pinhole camera, bit for
/// bit, and now it is, whatever the sample.
#[test]
fn thin_lens_zero_radius_with_nan_sample_is_the_pinhole() {
    use rayhit::camera::ThinLensCamera;
    let pinhole = PinholeCamera::new(Vec3::ZERO, -Vec3::Z, Vec3::Y, 100.0, 64, 64).unwrap();
    let cam = ThinLensCamera::new(pinhole, 0.0, 3.0).unwrap();
    for (s, t) in [(0.1, f32::NAN), (f32::NAN, f32::NAN), (f32::INFINITY, 0.3)] {
        assert_eq!(
            cam.ray(CameraSample::new(10.0, 10.0).with_lens(s, t)),
            pinhole.ray(CameraSample::new(10.0, 10.0))
        );
    }
}

/// `equirectangular` and `equal_area` (structured): an up vector nearly
/// parallel to the view direction (the sine of their angle just above the
/// cameras' `gamma(16)` limit). `right`, normalised from the cross product,
/// was off orthogonal to `forward` by the product's rounding over that
/// sine (over 100 `gamma(13)` here), and the round trip missed the bound
/// that assumed a basis orthonormal within `gamma(13)`. The basis now
/// removes `right`'s component along `forward` once more: orthonormal
/// within `gamma(13)` for this up vector too, and the round trips within
/// the bounds for that basis.
#[test]
fn panorama_round_trip_with_a_nearly_parallel_up_vector() {
    use rayhit::camera::{EqualAreaCamera, EquirectangularCamera};
    use rayhit_testkit::fuzz::panoramic::basis_skew;
    let view = Vec3::new(-0.2036, -0.6923, -0.6923);
    // Sine 3e-6: up is the view turned by 3e-6 radians.
    let up = view.normalize() + Vec3::new(0.0, 3e-6, -3e-6) * 0.7;
    let equi = EquirectangularCamera::new(Vec3::ZERO, view, up, 1, 1).unwrap();
    let g13 = f64::from(<f32 as rayhit::Scalar>::gamma_n(13));
    // basis_skew is never below gamma(13): equal means within it.
    assert_eq!(basis_skew([equi.right(), equi.up(), equi.forward()]), g13);
    let (x, y) = equi
        .raster_position(equi.ray(CameraSample::new(0.5, 0.5)).dir)
        .unwrap();
    let (bx, by) = equi.raster_position_error(0.5, 0.5);
    let (ex, ey) = ((x - 0.5).abs(), (y - 0.5).abs());
    assert!(ex <= bx && ey <= by, "({ex}, {ey}) beyond ({bx}, {by})");
    let area = EqualAreaCamera::new(
        DVec3::new(6.0, -8.0, 0.0),
        view.as_dvec3(),
        up.as_dvec3(),
        1,
        1,
    )
    .unwrap();
    let g13 = <f64 as rayhit::Scalar>::gamma_n(13);
    assert_eq!(basis_skew([area.right(), area.up(), area.forward()]), g13);
    let (bx, by) = area.raster_position_error(0.5, 0.5);
    let (x, y) = area
        .raster_position(area.ray(CameraSample::new(0.5, 0.5)).dir)
        .unwrap();
    assert!((x - 0.5).abs() <= bx && (y - 0.5).abs() <= by);
}

/// `thin_lens` (raw): a subnormal lens radius, `1e-45`, and the lens sample
/// `(0.3, 0.7)`. The offset `radius * disc point` rounds to zero, and the
/// camera took the pinhole ray (unit direction, not through the focus
/// point), against its docs (only the lens centre and a zero radius give
/// the pinhole ray). Now every other sample takes the lens's path and
/// meets the focus point exactly.
#[test]
fn thin_lens_subnormal_radius_meets_the_focus_point() {
    use rayhit::camera::ThinLensCamera;
    let pinhole = PinholeCamera::new(
        Vec3::new(100000.0, -30000.0, 200000.0),
        Vec3::X,
        Vec3::Z,
        1000.0,
        1920,
        1080,
    )
    .unwrap();
    let cam = ThinLensCamera::new(pinhole, 1e-45, 1.875).unwrap();
    let focus = cam.focus(0.5, 1079.5);
    let ray = cam.ray_through(&focus, 0.3, 0.7);
    assert_eq!(ray.at(1.0), focus.point());
    assert_ne!(ray, pinhole.ray(CameraSample::new(0.5, 1079.5)));
}

// `equal_area` (structured, f64), `equirectangular` (structured, f64) and
// `matrix_camera` (structured, f32): the checks' faults, the cameras were
// right (their reproducers are replayed from fuzz/crashes by
// testkit/tests/fuzz_replay.rs). The equal-area differentials were
// compared with a central difference of a camera rebuilt from this one's
// `forward` and `up`, whose basis differs from this one's by more than a
// rounding when the up vector was nearly parallel to the view (now the
// map on this camera's own basis); the equirectangular differentials are
// the unnormalised map's derivative, which the normalisation changes in
// proportion to the basis's departure from orthonormal (now in the
// bound); and a matrix camera of an axis-aligned view stores components
// in the subnormal range, where a rounding's error is absolute, not
// relative (now half a subnormal per rounding in the bound).

// `hit_differentials` (structured, f32): a triangle generated around the
// ray's point with two nearly opposite corner offsets, a sliver whose
// normal is known to less than its own length; the running error bound
// was infinite, as it should be (the division by `|n|^2` has no certain
// room), and the check expected it finite for any hit that was not
// grazing. The check's fault: it now also exempts slivers (reproducer in
// fuzz/crashes/hit_differentials).

/// `hit_differentials` (structured; an orthographic camera's ray): the ray
/// is exactly parallel to the triangle's plane (every direction component
/// `-0.57735026`, and `dir . n = 0` in exact arithmetic), yet the
/// watertight test reports a hit: it decides on the sheared, rounded
/// corners, which the ray does cross. The fuzzer's check took every hit to
/// have an exact transfer; the kernel was right: the transfer's values are
/// finite and every bound on them is infinite, since the computed `dir .
/// n` is rounding alone.
#[test]
fn hit_differentials_of_a_ray_exactly_parallel_to_the_plane() {
    use rayhit::camera::RayDifferential;
    let dir = Vec3::splat(-0.577_350_26);
    let diff = RayDifferential {
        ray: Ray::new(Vec3::new(-13.125122, -2.718715, 5.558_819_3), dir),
        dx_origin: Vec3::new(-1.194_736_2, 1.194_699_8, 3.643_913e-5),
        dx_dir: Vec3::ZERO,
        dy_origin: Vec3::new(0.689_739_3, 0.689_802_4, -1.379_541_6),
        dy_dir: Vec3::ZERO,
    };
    let tri = Triangle::new(
        Vec3::new(-25.340595, -7.755_673_4, 4.415_642_7),
        Vec3::new(-13.488924, -3.082_516_7, 5.195_017_3),
        Vec3::new(-15.758787, -12.530894, -8.147142),
    );
    let hit = ray_triangle(&diff.ray, &tri, f32::INFINITY).expect("the reported hit");
    assert_eq!(hit.t, 5.631_909_4);
    // Exactly parallel: the direction's dot product with the exact normal.
    let rv = |v: Vec3| [r(v.x), r(v.y), r(v.z)];
    let (a, b, c, d) = (rv(tri.a), rv(tri.b), rv(tri.c), rv(dir));
    let e1: [R; 3] = core::array::from_fn(|k| &b[k] - &a[k]);
    let e2: [R; 3] = core::array::from_fn(|k| &c[k] - &a[k]);
    let n = [
        &e1[1] * &e2[2] - &e1[2] * &e2[1],
        &e1[2] * &e2[0] - &e1[0] * &e2[2],
        &e1[0] * &e2[1] - &e1[1] * &e2[0],
    ];
    let dn = &d[0] * &n[0] + &d[1] * &n[1] + &d[2] * &n[2];
    assert_eq!(dn, r(0.0f32));
    let got = tri.hit_differentials(&diff, hit.t).expect("a transfer");
    assert!(got.dp_dx.is_finite() && got.dp_dy.is_finite());
    assert!(
        [got.du_dx, got.dv_dx, got.du_dy, got.dv_dy]
            .iter()
            .all(|x| x.is_finite())
    );
    let err = tri.hit_differentials_error(&diff, hit.t);
    assert!(err.dp_dx.min_element() == f32::INFINITY && err.dp_dy.min_element() == f32::INFINITY);
    assert!(
        [err.du_dx, err.dv_dx, err.du_dy, err.dv_dy]
            .iter()
            .all(|x| x.is_infinite())
    );
    rayhit_testkit::fuzz::hit_differentials::check(&diff, &tri, hit.t, true);
}

/// `matrix_camera` (structured, `f64`): an image one pixel high. At its
/// only row the vertical `raster_error` is the subnormal slack alone,
/// below the normal range, and its `f64` evaluation multiplied the
/// smallest subnormal by the slack's factor first: rounded there, the
/// bound came out 0.02% below the derivation. The kernel was at fault: the
/// slack is now carried as a multiple of the smallest subnormal to the
/// last step. Every perspective kind, both handednesses, a few fields of
/// view and near planes.
#[test]
fn matrix_camera_one_pixel_high_in_f64() {
    use rayhit::camera::ClipSpace;
    use rayhit::glam::DMat4;
    use rayhit::glam::dcamera::{lh, rh};
    use rayhit_testkit::fuzz::matrix_camera::check_matrix_pixel;
    let eye = DVec3::new(6.0004, -8.0006, 0.0);
    let dir = DVec3::new(0.0, -1.0, -1.0).normalize();
    let aspect = 1825.0;
    let (d3d, gl, vk) = (ClipSpace::Direct3D, ClipSpace::OpenGl, ClipSpace::Vulkan);
    for fov in [10.0f64, 40.0, 120.0].map(f64::to_radians) {
        for near in [1.0 / 64.0, 0.1, 4.0] {
            let far = near * 8.0;
            let views = [
                rh::view::look_to_mat4(eye, dir, DVec3::X),
                lh::view::look_to_mat4(eye, dir, DVec3::X),
            ];
            let projections: [[(DMat4, ClipSpace); 4]; 2] = [
                [
                    (rh::proj::directx::perspective(fov, aspect, near, far), d3d),
                    (
                        rh::proj::directx::perspective_infinite_reverse(fov, aspect, near),
                        d3d,
                    ),
                    (rh::proj::opengl::perspective(fov, aspect, near, far), gl),
                    (rh::proj::vulkan::perspective(fov, aspect, near, far), vk),
                ],
                [
                    (lh::proj::directx::perspective(fov, aspect, near, far), d3d),
                    (
                        lh::proj::directx::perspective_infinite_reverse(fov, aspect, near),
                        d3d,
                    ),
                    (lh::proj::opengl::perspective(fov, aspect, near, far), gl),
                    (lh::proj::vulkan::perspective(fov, aspect, near, far), vk),
                ],
            ];
            for (view, projections) in views.iter().zip(projections) {
                for (proj, clip) in projections {
                    let m = (&view.to_cols_array_2d(), &proj.to_cols_array_2d());
                    check_matrix_pixel::<DVec3>(m, clip, (1825, 1), (0, 0));
                }
            }
        }
    }
}
