//! `matrix_camera`: [`MatrixCamera`]: its construction from a view and a
//! projection matrix, its rays and their reprojection, its differentials.
//!
//! Input: raw mode, the two matrices' 32 entries as raw bits, a clip-space
//! byte, width, height and a raster position; structured mode, a frame
//! from [`cases::cameras`](crate::cases::cameras) and a projection drawn from glam's (`f64`)
//! perspective, infinite reversed-depth, OpenGL, Vulkan, orthographic and
//! off-centre frustum matrices, right- or left-handed, the entries
//! rounded once to the camera's precision, and three pixel centres.
//!
//! Checks, any input: no panic; `NonFiniteMatrix` exactly for a matrix with
//! a NaN or infinite entry (or whose product overflows); the differential's
//! ray is the ray; a finite position gives a finite ray where the camera's
//! unnormalised direction (or origin) is finite and nonzero. Structured
//! inputs also, in exact arithmetic on the matrices given: a perspective
//! ray looks into positive clip `w` and its direction's vanishing point is
//! the pixel's NDC within the bound [`MatrixCamera`] states, and the eye is
//! the camera centre within [`eye_bound`]; an orthographic ray's origin
//! projects to the pixel within its bound and its direction keeps it there
//! within the same form; the differentials are the neighbouring rays' less
//! the ray within the second-order term and the rays' errors.

use arbitrary::Arbitrary;
use rayhit::glam::dcamera::{lh, rh};
use rayhit::glam::{DMat4, DVec3};
use rayhit::{
    Camera, CameraSample, Scalar, Vector,
    camera::{ClipSpace, MatrixCamera},
};

use super::camera::{Linear, check_linear_differential};
use super::exact::{R, R3, abs, cross, dot, gamma, int, r, rv};
use super::{Check, Input, S, raw, raw_vec};
use crate::bits::vector_bits;
use crate::cases::cameras::frame;
use crate::source::Source;

/// The `matrix_camera` target.
#[derive(Debug)]
pub struct MatrixCameraCheck;

/// A projection and its clip space, from glam's `f64` functions.
fn projection(src: &mut Source, aspect: f64) -> (DMat4, ClipSpace, bool) {
    let fov = src.range(10.0, 150.0).to_radians();
    let near = src.log2_range(-6.0, 2.0);
    let far = near * src.log2_range(1.0, 20.0);
    let half_h = src.log2_range(-3.0, 8.0);
    let half_w = half_h * aspect;
    let right_handed = src.one_in(2);
    let (p, clip) = match (src.below(7), right_handed) {
        (0, true) => (
            rh::proj::directx::perspective(fov, aspect, near, far),
            ClipSpace::Direct3D,
        ),
        (0, false) => (
            lh::proj::directx::perspective(fov, aspect, near, far),
            ClipSpace::Direct3D,
        ),
        (1, true) => (
            rh::proj::directx::perspective_infinite_reverse(fov, aspect, near),
            ClipSpace::Direct3D,
        ),
        (1, false) => (
            lh::proj::directx::perspective_infinite_reverse(fov, aspect, near),
            ClipSpace::Direct3D,
        ),
        (2, true) => (
            rh::proj::opengl::perspective(fov, aspect, near, far),
            ClipSpace::OpenGl,
        ),
        (2, false) => (
            lh::proj::opengl::perspective(fov, aspect, near, far),
            ClipSpace::OpenGl,
        ),
        (3, true) => (
            rh::proj::vulkan::perspective(fov, aspect, near, far),
            ClipSpace::Vulkan,
        ),
        (3, false) => (
            lh::proj::vulkan::perspective(fov, aspect, near, far),
            ClipSpace::Vulkan,
        ),
        (4, true) => (
            rh::proj::directx::orthographic(-half_w, half_w, -half_h, half_h, near, far),
            ClipSpace::Direct3D,
        ),
        (4, false) => (
            lh::proj::directx::orthographic(-half_w, half_w, -half_h, half_h, near, far),
            ClipSpace::Direct3D,
        ),
        (5, _) => (
            rh::proj::opengl::orthographic(-half_w, half_w * 0.5, -half_h, half_h, near, far),
            ClipSpace::OpenGl,
        ),
        _ => {
            // Off-centre (a jittered or tiled frustum).
            let (l, t) = (src.range(-1.0, 0.5) * near, src.range(0.1, 1.0) * near);
            (
                rh::proj::directx::frustum(l, l + near * aspect, t - near, t, near, far),
                ClipSpace::Direct3D,
            )
        }
    };
    (p, clip, right_handed)
}

/// A glam `f64` matrix's columns rounded to precision `F`.
fn columns<F: Scalar>(m: DMat4) -> [[F; 4]; 4] {
    m.to_cols_array_2d().map(|c| c.map(F::from_f64))
}

impl Check for MatrixCameraCheck {
    fn run<'a, V>(input: &mut Input<'a>)
    where
        V: Vector,
        S<V>: Arbitrary<'a> + Scalar,
    {
        match input {
            Input::Raw(u) => {
                let mut m = || [0; 4].map(|_| [0; 4].map(|_| raw::<S<V>>(u)));
                let (view, proj) = (m(), m());
                let clip = [ClipSpace::Direct3D, ClipSpace::OpenGl, ClipSpace::Vulkan]
                    [usize::from(raw::<u8>(u) % 3)];
                let (w, h) = (raw::<u32>(u), raw::<u32>(u));
                let (x, y) = (raw::<S<V>>(u), raw::<S<V>>(u));
                let _ = raw_vec::<V>(u);
                let cam = MatrixCamera::<V>::new(view, proj, clip, w, h);
                let finite = |m: &[[S<V>; 4]; 4]| m.iter().flatten().all(|c| c.is_finite());
                match cam {
                    Err(rayhit::camera::CameraError::NonFiniteMatrix) => {}
                    Err(rayhit::camera::CameraError::EmptyImage) => {
                        assert!(w == 0 || h == 0)
                    }
                    Err(rayhit::camera::CameraError::SingularMatrix) => {
                        assert!(finite(&view) && finite(&proj))
                    }
                    Err(e) => panic!("{e:?} from matrices"),
                    Ok(cam) => {
                        assert!(finite(&view) && finite(&proj) && w > 0 && h > 0);
                        check_ray_raw(&cam, x, y);
                    }
                }
            }
            Input::Structured(src) => {
                let f = frame::<V>(src);
                let view_dir = DVec3::new(
                    f.view.x().to_f64(),
                    f.view.y().to_f64(),
                    f.view.z().to_f64(),
                )
                .normalize();
                let up =
                    DVec3::new(f.up.x().to_f64(), f.up.y().to_f64(), f.up.z().to_f64()).normalize();
                // Well away from parallel: the matrices are then far from
                // singular, and the bounds mean something.
                if view_dir.cross(up).length() < 0.5 {
                    return;
                }
                let eye = DVec3::new(f.eye.x().to_f64(), f.eye.y().to_f64(), f.eye.z().to_f64());
                let aspect = f64::from(f.width) / f64::from(f.height);
                let (p, clip, right_handed) = projection(src, aspect);
                let v = if right_handed {
                    rh::view::look_to_mat4(eye, view_dir, up)
                } else {
                    lh::view::look_to_mat4(eye, view_dir, up)
                };
                let (view, proj) = (columns::<S<V>>(v), columns::<S<V>>(p));
                let cam = MatrixCamera::<V>::new(view, proj, clip, f.width, f.height)
                    .expect("glam's matrices of a well-conditioned view");
                let exact = Exact::new(&view, &proj);
                let given = (&view, &proj);
                if !cam.is_orthographic() {
                    check_eye(&cam, given, &exact);
                }
                for _ in 0..3 {
                    let (i, j) = (src.below(f.width), src.below(f.height));
                    check_pixel(&cam, given, &exact, clip, i, j);
                }
            }
        }
    }
}

/// `M = projection * view` in exact arithmetic, and `|projection| *
/// |view|` (absolute values entry by entry), by rows.
pub struct Exact {
    m: [[R; 4]; 4],
    mag: [[R; 4]; 4],
}

impl Exact {
    /// The product of two matrices given as columns.
    pub fn new<F: Scalar>(view: &[[F; 4]; 4], proj: &[[F; 4]; 4]) -> Self {
        let at = |c: &[[F; 4]; 4], i: usize, j: usize| r(c[j][i]);
        let m = core::array::from_fn(|i| {
            core::array::from_fn(|j| (0..4).map(|k| at(proj, i, k) * at(view, k, j)).sum())
        });
        let mag = core::array::from_fn(|i| {
            core::array::from_fn(|j| {
                (0..4)
                    .map(|k| abs(&at(proj, i, k)) * abs(&at(view, k, j)))
                    .sum()
            })
        });
        Self { m, mag }
    }

    fn row(&self, i: usize) -> R3 {
        core::array::from_fn(|k| self.m[i][k].clone())
    }

    fn row_mag(&self, i: usize) -> R3 {
        core::array::from_fn(|k| self.mag[i][k].clone())
    }
}

/// The cross product's magnitudes: `(a x b)_k` with every product taken in
/// absolute value and added.
fn cross_mag(a: &R3, b: &R3) -> R3 {
    [
        &a[1] * &b[2] + &a[2] * &b[1],
        &a[2] * &b[0] + &a[0] * &b[2],
        &a[0] * &b[1] + &a[1] * &b[0],
    ]
}

fn add3(a: &R3, b: &R3) -> R3 {
    core::array::from_fn(|k| &a[k] + &b[k])
}

fn scale3(a: &R3, s: &R) -> R3 {
    core::array::from_fn(|k| &a[k] * s)
}

/// `e = gamma(5) + gamma_64(17)`, the relative error of the rays' linear
/// forms (see [`MatrixCamera`]).
fn e<F: Scalar>() -> R {
    gamma::<F>(5) + gamma::<f64>(17)
}

/// `sum_k |n_k| e K_k / (|D| - sum_k |m_k| e K_k)`: the bound on the NDC
/// of a vector `v* + err` (`|err_k| <= e K_k`) off the exact one, where `n
/// . v* = 0` and `m . v* = D`; `None` when the denominator is not positive.
fn ndc_bound(n: &R3, m: &R3, d: &R, k: &R3, e: &R, tiny: &R) -> Option<R> {
    let num: R = (0..3).map(|i| abs(&n[i]) * (e * &k[i] + tiny)).sum();
    let den = abs(d) - (0..3).map(|i| abs(&m[i]) * (e * &k[i] + tiny)).sum::<R>();
    (den > int(0)).then(|| num / den)
}

/// The absolute error that roundings into the subnormal range add, where
/// a relative bound says nothing (half the smallest subnormal each): the
/// stored `c`, `a`, `b` (one each, times `1`, `|dx|`, `|dy|`), the ray's
/// three products and sums, and the normalisation's product (in the
/// unnormalised vector's units, times its length), in all
/// `TINY (4 + |dx| + |dy| + |v|)`. Matrices of an axis-aligned view make
/// such components (products of the view's tiny off-axis roundings).
fn subnormal_slack<F: Scalar>(dx: &R, dy: &R, length: &R) -> R {
    r(F::TINY) * (int(4) + abs(dx) + abs(dy) + length)
}

/// The NDC of pixel `(i, j)`'s centre: `nx = (2/w) dx`, `ny = +-(2/h) dy`
/// with the computed (exact, on the half-pixel grid) offsets.
fn ndc<F: Scalar>(w: u32, h: u32, clip: ClipSpace, i: u32, j: u32) -> (R, R) {
    let half = F::HALF;
    let dx = F::from_u32(i) + half - F::from_u32(w) * half;
    let dy = F::from_u32(h) * half - (F::from_u32(j) + half);
    let nx = int(2) * r(dx) / int(i64::from(w));
    let ny = int(2) * r(dy) / int(i64::from(h));
    (nx, if clip == ClipSpace::Vulkan { -ny } else { ny })
}

/// The matrices a camera was made from, `(view, projection)`, as columns.
pub type Given<'a, F> = (&'a [[F; 4]; 4], &'a [[F; 4]; 4]);

fn check_pixel<V: Vector>(
    cam: &MatrixCamera<V>,
    (view, proj): Given<'_, S<V>>,
    ex: &Exact,
    clip: ClipSpace,
    i: u32,
    j: u32,
) {
    let ctx = || format!("{cam:?} at pixel ({i}, {j})");
    let (w, h) = (cam.width(), cam.height());
    let ray = cam.pixel_ray(i, j);
    assert!(ray.origin.is_finite() && ray.dir.is_finite(), "{}", ctx());
    let (nx, ny) = ndc::<S<V>>(w, h, clip, i, j);
    let (m0, m1, m2, m3) = (ex.row(0), ex.row(1), ex.row(2), ex.row(3));
    let (a0, a1, a2, a3) = (ex.row_mag(0), ex.row_mag(1), ex.row_mag(2), ex.row_mag(3));
    let d = rv(ray.dir);
    let e = e::<S<V>>();
    // The raster offsets, |dx| and |dy|.
    let dx = abs(&(&nx * int(i64::from(w)) / int(2)));
    let dy = abs(&(&ny * int(i64::from(h)) / int(2)));
    if !cam.is_orthographic() {
        let det = dot(&m0, &cross(&m1, &m3));
        let k = add3(
            &add3(
                &cross_mag(&a0, &a1),
                &scale3(&cross_mag(&a1, &a3), &abs(&nx)),
            ),
            &scale3(&cross_mag(&a3, &a0), &abs(&ny)),
        );
        let w_rate = dot(&m3, &d);
        assert!(w_rate > int(0), "looks away from positive w: {}", ctx());
        let length: R = k.iter().sum();
        let tiny = subnormal_slack::<S<V>>(&dx, &dy, &length);
        let half = S::<V>::HALF;
        let (x, y) = (S::<V>::from_u32(i) + half, S::<V>::from_u32(j) + half);
        let (bx, by) = cam.raster_error(view, proj, x, y);
        for (coord, n, pixels, crate_bound) in [
            ("x", core::array::from_fn(|q| &m0[q] - &nx * &m3[q]), w, bx),
            ("y", core::array::from_fn(|q| &m1[q] - &ny * &m3[q]), h, by),
        ] {
            let n: R3 = n;
            let bound = ndc_bound(&n, &m3, &det, &k, &e, &tiny).expect("a well-conditioned camera");
            let bound = in_ndc(crate_bound, pixels, &bound, coord, &ctx);
            let off = abs(&(dot(&n, &d) / &w_rate));
            assert!(
                off <= bound,
                "vanishing point's {coord} off by {} > {}: {}",
                super::exact::f(&off),
                super::exact::f(&bound),
                ctx()
            );
        }
    } else {
        let d3 = ex.m[3][3].clone();
        let det = dot(&m0, &cross(&m1, &m2));
        // The origin: (m_i . o + d_i) / d3 is the NDC, within
        // sum_k |m_ik| E_k / |d3| with E_k the origin's error bound
        // (the magnitudes of Cramer's rule over |det|, times e (1 +
        // kappa), kappa = |m0| . |m1 x m2| / |det| the determinant's own
        // relative error's growth).
        let z0 = if clip == ClipSpace::OpenGl {
            int(-1)
        } else {
            int(0)
        };
        let x = cross_mag(&a1, &a2);
        let y = cross_mag(&a2, &a0);
        let z = cross_mag(&a0, &a1);
        let coeff = |c: &R, dd: &R| abs(&(c * &d3)) + abs(dd);
        let (d0, d1, d2) = (&ex.m[0][3], &ex.m[1][3], &ex.m[2][3]);
        let kappa = dot(&a0, &x) / abs(&det);
        let origin_mag: R3 = core::array::from_fn(|q| {
            (coeff(&nx, d0) * &x[q] + coeff(&ny, d1) * &y[q] + coeff(&z0, d2) * &z[q]) / abs(&det)
        });
        let eo = &e * (int(1) + &kappa);
        let slack = subnormal_slack::<S<V>>(&dx, &dy, &int(0));
        let length: R = z.iter().sum();
        let tiny = subnormal_slack::<S<V>>(&int(0), &int(0), &length);
        let o = rv(ray.origin);
        let half = S::<V>::HALF;
        let (x, y) = (S::<V>::from_u32(i) + half, S::<V>::from_u32(j) + half);
        let (bx, by) = cam.raster_error(view, proj, x, y);
        for (coord, mrow, target, dd, pixels, crate_bound) in
            [("x", &m0, &nx, d0, w, bx), ("y", &m1, &ny, d1, h, by)]
        {
            let value = (dot(mrow, &o) + dd) / &d3;
            let bound: R = (0..3)
                .map(|q| abs(&mrow[q]) * (&eo * &origin_mag[q] + &slack))
                .sum::<R>()
                / abs(&d3);
            let bound = in_ndc(crate_bound, pixels, &bound, coord, &ctx);
            assert!(
                abs(&(value - target)) <= bound,
                "origin's {coord} off its pixel: {}",
                ctx()
            );
            // The direction keeps the ray on the pixel: its NDC drift per
            // unit of depth, within the same form (the direction is
            // m0 x m1 in f64, normalised, rounded: within (u + gamma_64(20))
            // of its magnitudes, as a vector up to its length).
            let ed = r(S::<V>::UNIT_ROUNDOFF) + gamma::<f64>(20);
            let bound = ndc_bound(mrow, &m2, &det, &z, &ed, &tiny).expect("well-conditioned");
            let drift = abs(&(dot(mrow, &d) / dot(&m2, &d)));
            assert!(
                drift <= bound,
                "direction drifts off the pixel in {coord}: {}",
                ctx()
            );
        }
    }
    let diff = cam.ray_differential(CameraSample::new(
        S::<V>::from_u32(i) + S::<V>::HALF,
        S::<V>::from_u32(j) + S::<V>::HALF,
    ));
    assert!(
        vector_bits(diff.ray.dir) == vector_bits(ray.dir)
            && vector_bits(diff.ray.origin) == vector_bits(ray.origin),
        "{}",
        ctx()
    );
    check_neighbours(cam, i, j, &diff);
}

/// The eye is the camera centre: `|eye_k - e*_k| <= [gamma_64(14) N_k /
/// |D| + |e*_k| delta] / (1 - delta) + (gamma_64(1) + u) |eye_k| (1 + u)`,
/// with `e* = -(d0 X + d1 Y + d3 Z) / D` exactly (`X = m1 x m3`, `Y = m3 x
/// m0`, `Z = m0 x m1`, `D = m0 . X`), `N_k` the magnitudes of that sum,
/// and `delta = gamma_64(14) |m0| . |X| / |D|`: the cross products and the
/// sum within `gamma_64(14)` of their magnitudes in `f64` (the rows
/// themselves within `gamma_64(4)` of theirs), the determinant likewise,
/// the quotient and the rounding to the camera's precision one rounding
/// each.
pub fn eye_bound(ex: &Exact) -> Option<(R3, R3)> {
    let (m0, m1, m3) = (ex.row(0), ex.row(1), ex.row(3));
    let (a0, a1, a3) = (ex.row_mag(0), ex.row_mag(1), ex.row_mag(3));
    let (d0, d1, d3) = (&ex.m[0][3], &ex.m[1][3], &ex.m[3][3]);
    let (x, y, z) = (cross(&m1, &m3), cross(&m3, &m0), cross(&m0, &m1));
    let det = dot(&m0, &x);
    let eye: R3 = core::array::from_fn(|k| -(d0 * &x[k] + d1 * &y[k] + d3 * &z[k]) / &det);
    let (xm, ym, zm) = (
        cross_mag(&a1, &a3),
        cross_mag(&a3, &a0),
        cross_mag(&a0, &a1),
    );
    let (b0, b1, b3) = (&ex.mag[0][3], &ex.mag[1][3], &ex.mag[3][3]);
    let g14 = gamma::<f64>(14);
    let delta = &g14 * dot(&a0, &xm) / abs(&det);
    if delta >= int(1) {
        return None;
    }
    let bound = core::array::from_fn(|k| {
        let n = b0 * &xm[k] + b1 * &ym[k] + b3 * &zm[k];
        (&g14 * n / abs(&det) + abs(&eye[k]) * &delta) / (int(1) - &delta)
    });
    Some((eye, bound))
}

/// The crate's `eye_error` held: the eye within it of the exact centre.
fn check_eye<V: Vector>(cam: &MatrixCamera<V>, (view, proj): Given<'_, S<V>>, ex: &Exact) {
    // Matrices the camera was not made from get no bound: the projection's
    // horizontal scale doubled (glam's projections have it alone in their
    // first row, so the product's first row doubles) halves the camera's
    // step across exactly: another camera. (Matrices that give this camera bit for bit would
    // rightly get a bound: it is derived from the matrices passed.)
    let mut other = *proj;
    other[0][0] = other[0][0] + other[0][0];
    assert!(
        !cam.eye_error(view, &other).is_finite(),
        "an eye bound for matrices the camera was not made from: {cam:?}"
    );
    let Some((eye, _)) = eye_bound(ex) else {
        return;
    };
    let got = rv(cam.pixel_ray(0, 0).origin);
    let bound = cam.eye_error(view, proj);
    assert!(
        bound.is_finite(),
        "no eye bound for glam's well-conditioned matrices: {cam:?}"
    );
    let bound = rv(bound);
    for k in 0..3 {
        assert!(
            abs(&(&got[k] - &eye[k])) <= bound[k],
            "eye {:?} off the camera centre in component {k}: {cam:?}",
            cam.pixel_ray(0, 0).origin
        );
    }
}

/// The crate's `raster_error` coordinate (pixels across `pixels`) in
/// device units, checked to be at least the derivation's `derived`.
fn in_ndc<F: Scalar>(
    crate_bound: F,
    pixels: u32,
    derived: &R,
    coord: &str,
    ctx: &dyn Fn() -> String,
) -> R {
    let bound = r(crate_bound) * int(2) / int(i64::from(pixels));
    assert!(
        *derived <= bound,
        "raster_error's {coord} {} below its derivation {}: {}",
        super::exact::f(&bound),
        super::exact::f(derived),
        ctx()
    );
    bound
}

/// The differentials against the neighbouring pixels' rays, on the
/// camera's own linear form: perspective, [`check_linear_differential`];
/// orthographic (where `ray_differential_error` is zero, checked), the origins `fl(fl(c + fl(a dx)) + fl(b dy))` are each
/// within `gamma(3) K` (per component, `K = |c| + |dx| |a| + |dy| |b|`) of
/// the exact `c + dx a + dy b`, a pixel apart exactly, and the
/// differential is `a` (or `-b`) itself, so the neighbours' origins less
/// the differential are within the sum of the two bounds.
fn check_neighbours<V: Vector>(
    cam: &MatrixCamera<V>,
    i: u32,
    j: u32,
    diff: &rayhit::camera::RayDifferential<V>,
) {
    let ctx = || format!("{cam:?} at pixel ({i}, {j})");
    let [c, a, b] = cam.linear_form();
    let half = S::<V>::HALF;
    let (x, y) = (S::<V>::from_u32(i) + half, S::<V>::from_u32(j) + half);
    let dx = x - S::<V>::from_u32(cam.width()) * half;
    let dy = S::<V>::from_u32(cam.height()) * half - y;
    let one = S::<V>::ONE;
    let (next_x, next_y) = (
        cam.ray(CameraSample::new(x + one, y)),
        cam.ray(CameraSample::new(x, y + one)),
    );
    if !cam.is_orthographic() {
        let lin = Linear {
            c: [0, 1, 2].map(|k| c[k].to_f64()),
            a,
            b,
            orthonormal: 0.0,
        };
        let error = cam.ray_differential_error(x, y);
        let dir = diff.ray.dir;
        check_linear_differential(&lin, dx, dy, a, dir, next_x.dir, diff.dx_dir, error, &ctx);
        check_linear_differential(&lin, dx, dy, -b, dir, next_y.dir, diff.dy_dir, error, &ctx);
        return;
    }
    assert_eq!(cam.ray_differential_error(x, y), S::<V>::ZERO, "{}", ctx());
    assert_eq!(vector_bits(diff.dx_origin), vector_bits(a), "{}", ctx());
    assert_eq!(vector_bits(diff.dy_origin), vector_bits(-b), "{}", ctx());
    let (cr, ar, br) = (rv(c), rv(a), rv(b));
    let mags = |dx: S<V>, dy: S<V>| -> R3 {
        core::array::from_fn(|k| {
            abs(&cr[k]) + abs(&r(dx)) * abs(&ar[k]) + abs(&r(dy)) * abs(&br[k])
        })
    };
    let g3 = gamma::<S<V>>(3);
    for (next, d, ndx, ndy) in [
        (next_x, diff.dx_origin, dx + one, dy),
        (next_y, diff.dy_origin, dx, dy - one),
    ] {
        let (k0, k1) = (mags(dx, dy), mags(ndx, ndy));
        let (o0, o1, dv) = (rv(diff.ray.origin), rv(next.origin), rv(d));
        for k in 0..3 {
            let res = &o1[k] - &o0[k] - &dv[k];
            assert!(
                abs(&res) <= &g3 * (&k0[k] + &k1[k]),
                "orthographic neighbour's origin off the differential: {}",
                ctx()
            );
        }
    }
}

fn check_ray_raw<V: Vector>(cam: &MatrixCamera<V>, x: S<V>, y: S<V>) {
    let ray = cam.ray(CameraSample::new(x, y));
    let diff = cam.ray_differential(CameraSample::new(x, y));
    assert_eq!(vector_bits(diff.ray.dir), vector_bits(ray.dir));
    assert_eq!(vector_bits(diff.ray.origin), vector_bits(ray.origin));
    // The camera's fixed part is finite (checked when it was made).
    let fixed = if cam.is_orthographic() {
        ray.dir
    } else {
        ray.origin
    };
    assert!(fixed.is_finite(), "{cam:?}: {ray:?}");
    if x.to_f64().is_nan() || y.to_f64().is_nan() {
        assert!(
            !(ray.origin.is_finite() && ray.dir.is_finite()),
            "{cam:?}: {ray:?}"
        );
    }
}

/// The structured checks of pixel `(i, j)` (its ray's reprojection and
/// `raster_error` against their derivations) for the camera
/// [`MatrixCamera::new`] makes of `view` and `proj` (columns): for the
/// regression tests' literal cases.
pub fn check_matrix_pixel<V: Vector>(
    (view, proj): Given<'_, S<V>>,
    clip: ClipSpace,
    (width, height): (u32, u32),
    (i, j): (u32, u32),
) {
    let cam = MatrixCamera::<V>::new(*view, *proj, clip, width, height)
        .expect("a camera the matrices define");
    check_pixel(&cam, (view, proj), &Exact::new(view, proj), clip, i, j);
}
