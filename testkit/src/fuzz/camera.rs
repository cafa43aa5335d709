//! `camera`: [`PinholeCamera::new`], [`PinholeCamera::from_fov`],
//! [`PinholeCamera::ray`] and [`PinholeCamera::pixel_ray`].
//!
//! Input: raw mode, eye, view and up as raw-bit vectors, focal length, field
//! of view and a raster position as raw-bit scalars, width, height and a
//! pixel as raw `u32`s; structured mode, an eye in `[-64, 64]^3`, view and
//! up from [`cases::direction`], an image of 1 to 2048 pixels each way, a
//! field of view of 10 to 150 degrees and a position in the image.
//!
//! Checks: no panic; a camera is built only from valid input, and each
//! error names an input that is bad in the way the error says; the ray
//! starts at the eye; `pixel_ray(i, j)` is `ray(i + 0.5, j + 0.5)` bit for
//! bit; a NaN or infinite position gives a non-finite direction; and where
//! the unnormalised direction is finite and nonzero (the camera normalises
//! in a frame scaled by a power of two, so its squares neither overflow nor
//! underflow) the direction has unit length within `2 gamma(6) + gamma(6)^2`
//! (squared length), the tests/suite/camera/properties.rs bound. Structured inputs also: the centre
//! pixel of an odd-sized image looks along the view direction, within the
//! tests/suite/camera/properties.rs bound.

use arbitrary::Arbitrary;
use rayhit::{Camera as _, CameraSample, PinholeCamera, Scalar, Vector, camera::CameraError};

use super::exact::{R, cross, dot, gamma, int, rv};
use super::{Check, Input, S, raw, raw_vec};
use crate::bits::vector_bits;
use crate::cases;

/// The `camera` target.
#[derive(Debug)]
pub struct Camera;

impl Check for Camera {
    fn run<'a, V>(input: &mut Input<'a>)
    where
        V: Vector,
        S<V>: Arbitrary<'a> + Scalar,
    {
        match input {
            Input::Raw(u) => {
                let (eye, view, up) = (raw_vec::<V>(u), raw_vec::<V>(u), raw_vec::<V>(u));
                let (focal, fov) = (raw::<S<V>>(u), raw::<S<V>>(u));
                let (w, h) = (raw::<u32>(u), raw::<u32>(u));
                let (x, y) = (raw::<S<V>>(u), raw::<S<V>>(u));
                let (i, j) = (raw::<u32>(u), raw::<u32>(u));
                let cam = PinholeCamera::new(eye, view, up, focal, w, h);
                check_new(&cam, eye, view, up, focal, w, h);
                let by_fov = PinholeCamera::from_fov(eye, view, up, fov, w, h);
                check_fov(&by_fov, fov);
                for cam in [cam, by_fov].into_iter().flatten() {
                    check_rays(&cam, x, y, i, j);
                }
            }
            Input::Structured(src) => {
                let eye = cases::point::<V>(src, 64.0);
                let (view, up) = (cases::direction::<V>(src), cases::direction::<V>(src));
                let mut size = || 1 + src.below(256) * 8 + src.below(8);
                let (w, h) = (size(), size());
                let fov = S::<V>::from_f64(src.range(10.0, 150.0).to_radians());
                let Ok(cam) = PinholeCamera::from_fov(eye, view, up, fov, w, h) else {
                    return;
                };
                let x = S::<V>::from_f64(src.range(0.0, f64::from(w)));
                let y = S::<V>::from_f64(src.range(0.0, f64::from(h)));
                let (i, j) = (src.below(256) % w, src.below(256) % h);
                check_rays(&cam, x, y, i, j);
                if w % 2 == 1 && h % 2 == 1 {
                    check_centre(&cam, view);
                }
                check_pinhole_differential(&cam, i, j);
            }
        }
    }
}

fn check_new<V: Vector>(
    cam: &Result<PinholeCamera<V>, CameraError>,
    eye: V,
    view: V,
    up: V,
    focal: S<V>,
    w: u32,
    h: u32,
) {
    let zero = S::<V>::ZERO;
    let ctx = || format!("eye {eye:?}, view {view:?}, up {up:?}, focal {focal:?}, {w}x{h}");
    // Documented: zero or non-finite (a finite nonzero vector whose squared
    // length under- or overflows is fine: tests/suite/fuzz_regressions.rs).
    let bad_view = !view.is_finite() || view == V::ZERO;
    let bad_up = !up.is_finite() || up == V::ZERO;
    let bad_focal = !(focal > zero && focal.is_finite());
    match cam {
        Ok(cam) => {
            let documented_ok =
                view.is_finite() && view != V::ZERO && up.is_finite() && up != V::ZERO;
            assert!(
                eye.is_finite() && documented_ok && !bad_focal && w > 0 && h > 0,
                "camera from bad input: {}",
                ctx()
            );
            assert_eq!(cam.eye(), eye, "{}", ctx());
            assert!(
                cam.focal_length() == focal && cam.width() == w && cam.height() == h,
                "{}",
                ctx()
            );
        }
        Err(e) => {
            let ok = match e {
                CameraError::NonFiniteEye => !eye.is_finite(),
                CameraError::InvalidViewDir => bad_view,
                CameraError::InvalidUp => bad_up,
                CameraError::UpParallelToView => true,
                CameraError::InvalidFocalLength => bad_focal,
                CameraError::EmptyImage => w == 0 || h == 0,
                _ => false,
            };
            assert!(ok, "{e:?} for input that is not bad that way: {}", ctx());
        }
    }
}

fn check_fov<V: Vector>(cam: &Result<PinholeCamera<V>, CameraError>, fov: S<V>) {
    let fov_ok = fov > S::<V>::ZERO && fov < S::<V>::PI;
    match cam {
        Ok(_) => assert!(fov_ok, "camera from field of view {fov:?}"),
        Err(CameraError::InvalidFieldOfView) => assert!(!fov_ok, "{fov:?} rejected"),
        Err(_) => {}
    }
}

/// The unnormalised direction, computed as `PinholeCamera::ray` does.
fn unnormalised<V: Vector>(cam: &PinholeCamera<V>, x: S<V>, y: S<V>) -> V {
    let half = S::<V>::HALF;
    let dx = x - S::<V>::from_u32(cam.width()) * half;
    let dy = S::<V>::from_u32(cam.height()) * half - y;
    cam.forward() * cam.focal_length() + cam.right() * dx + cam.up() * dy
}

/// Where the unit-length claim holds: the unnormalised direction is finite
/// and nonzero, however large or small.
fn normalisable<V: Vector>(d: V) -> bool {
    d.is_finite() && d != V::ZERO
}

fn check_rays<V: Vector>(cam: &PinholeCamera<V>, x: S<V>, y: S<V>, i: u32, j: u32) {
    let ctx = || format!("camera {cam:?}, position ({x:?}, {y:?}), pixel ({i}, {j})");
    let ray = cam.ray(CameraSample::new(x, y));
    assert_eq!(ray.origin, cam.eye(), "{}", ctx());
    if !(x.is_finite() && y.is_finite()) {
        assert!(
            !ray.dir.is_finite(),
            "non-finite position, finite direction: {}",
            ctx()
        );
    } else if normalisable(unnormalised(cam, x, y)) {
        unit(ray.dir, &ctx);
    }
    let half = S::<V>::HALF;
    let (pi, pj) = (S::<V>::from_u32(i) + half, S::<V>::from_u32(j) + half);
    let a = cam.pixel_ray(i, j);
    let b = cam.ray(CameraSample::new(pi, pj));
    assert!(
        vector_bits(a.dir) == vector_bits(b.dir) && vector_bits(a.origin) == vector_bits(b.origin),
        "pixel_ray {a:?} is not ray(i + 0.5, j + 0.5) {b:?}: {}",
        ctx()
    );
    if normalisable(unnormalised(cam, pi, pj)) {
        unit(a.dir, &ctx);
    }
}

/// `|len^2 - 1| <= 2 gamma(6) + gamma(6)^2`: `normalize` computes the
/// squared length (`gamma(3)`), its square root (halving that, plus one
/// rounding), the reciprocal and the products (one each), so each component
/// is within `gamma(6)` of the exact unit vector's.
fn unit<V: Vector>(d: V, ctx: &dyn Fn() -> String) {
    assert!(d.is_finite(), "direction {d:?} not finite: {}", ctx());
    let dv = rv(d);
    let len2 = dot(&dv, &dv);
    let g = gamma::<S<V>>(6);
    let dev = super::exact::abs(&(&len2 - int(1)));
    assert!(
        dev <= int(2) * &g + &g * &g,
        "direction {d:?} has squared length {}: {}",
        super::exact::f(&len2),
        ctx()
    );
}

/// The centre pixel of an odd-sized image looks along the view direction
/// (tests/suite/camera/properties.rs): `dir . view > 0` and
/// `|dir x view| <= k |view|`, `k = gamma(3) (1 + gamma(6)) / (1 - gamma(3))`.
fn check_centre<V: Vector>(cam: &PinholeCamera<V>, view: V) {
    let dir = rv(cam.pixel_ray(cam.width() / 2, cam.height() / 2).dir);
    let v = rv(view);
    assert!(dot(&dir, &v) > int(0), "centre pixel looks away: {cam:?}");
    let c = cross(&dir, &v);
    let (g3, g6) = (gamma::<S<V>>(3), gamma::<S<V>>(6));
    let k: R = &g3 * (int(1) + &g6) / (int(1) - &g3);
    assert!(
        dot(&c, &c) <= &k * &k * dot(&v, &v),
        "centre pixel off the view direction {view:?}: {cam:?}"
    );
}

/// A ray of a linear camera: its direction is `unit(c + dx a + dy b)`,
/// evaluated as `(c + a dx) + b dy` (for the pinhole camera `c` is `focal
/// forward`, whose product is part of the evaluation), and its
/// differential along `step` (`a`, or `-b` for raster `y`) is `(step - dir
/// (dir . step)) / |p|` with `1 / |p|` the normalisation's factor; or,
/// for a camera whose frame is orthonormal within `orthonormal` (each
/// entry of `B^T B - I` for the frame `c / |c|`, `a`, `b`), with `dx /
/// |p|` and `dy / |p|` standing for `dir . a` and `dir . b`, which they
/// equal for an exactly orthonormal frame.
#[derive(Clone, Copy, Debug)]
pub struct Linear<V> {
    /// The constant term (exactly, as the camera's arithmetic sees it).
    pub c: [f64; 3],
    /// The step per unit of `dx`.
    pub a: V,
    /// The step per unit of `dy`.
    pub b: V,
    /// Zero where the camera forms `dir . step`; else the bound on its
    /// frame's departure from orthonormal that lets it use `dx` and `dy`.
    pub orthonormal: f64,
}

/// The derivative along `step` of the direction at `(dx, dy)`, against
/// the neighbour's direction one step on, in exact arithmetic on the
/// computed directions:
///
/// `|next - dir - diff| <= t(dir) + t(next) + t_diff + t_2`, where, with
/// `p~` the exact `c + dx a + dy b`, `K` its magnitudes `|c| + |dx| |a| +
/// |dy| |b|` and `eta = gamma(4) + gamma(3) |K| / |p~|` (the factor
/// `1 / |p|`'s error: the squared length's three roundings, the square
/// root's and the reciprocal's, and the computed `p`'s distance from `p~`,
/// `gamma(3) |K|`):
///
/// - `t = 2 eta + 2 u`: a computed direction is within that of `p~ /
///   |p~|` (`p`'s error over `|p|`, the factor's, and one rounding per
///   component);
/// - `t_diff = (|step| / |p~|) (gamma(28) + 5 gamma(3) |K| / |p~|)`: the
///   differential's own (the direction's error twice through `dir (dir .
///   step)`, the dot product's `gamma(3)`, two more roundings, and the
///   factor's error);
/// - `t_2 = 2 |step|^2 / (|p~| - |step|)^2`: the second-order term (the
///   unit direction's second derivative is at most `4 |p'|^2 / |p|^2`
///   long, and `|p|` stays above `|p~| - |step|` over the step);
/// - `t_frame = e (|c| + |dx| |a| + |dy| |b|) / ((1 - e) |p~|^2)` with `e`
///   the frame's `orthonormal` bound, for a camera using `dx` for `p~ .
///   a` (and `dy` for `p~ . b`): with `c = focal forward`, `p~ . a =
///   focal (forward . a) + dx (a . a) + dy (b . a)` is within `e (focal +
///   |dx| + |dy|)` of `dx`, and each unit vector's length is at least `1
///   - e`; through `dir (dir . step) / |p|` that moves the differential by
///   that over `|p~|^2`.
///
/// `error` is the camera's own bound on the differential's rounding (its
/// `ray_differential_error`), checked here to be at least `t_diff +
/// t_frame` and used in their place. The norms are taken in `f64` (a
/// relative `1e-15`, covered by a factor `1 + 1e-9` on the bound); the
/// comparison is exact.
#[allow(clippy::too_many_arguments)]
pub fn check_linear_differential<V: Vector>(
    lin: &Linear<V>,
    dx: S<V>,
    dy: S<V>,
    step: V,
    dir: V,
    next: V,
    diff: V,
    error: S<V>,
    ctx: &dyn Fn() -> String,
) {
    let f = |x: S<V>| x.to_f64();
    let v64 = |v: V| [f(v.x()), f(v.y()), f(v.z())];
    let (a, b) = (v64(lin.a), v64(lin.b));
    let norm = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    let at = |dx: f64, dy: f64| {
        let p: [f64; 3] = core::array::from_fn(|k| lin.c[k] + dx * a[k] + dy * b[k]);
        let k: [f64; 3] = core::array::from_fn(|i| {
            lin.c[i].abs() + dx.abs() * a[i].abs() + dy.abs() * b[i].abs()
        });
        (norm(p), norm(k))
    };
    let s = v64(step);
    let s_len = norm(s);
    let (p0, k0) = at(f(dx), f(dy));
    // The neighbour's offsets: one step along `step` (a, or -b).
    let along_x = s == a;
    let (p1, k1) = if along_x {
        at(f(dx) + 1.0, f(dy))
    } else {
        at(f(dx), f(dy) - 1.0)
    };
    if !(p0 > 2.0 * s_len && p1 > 2.0 * s_len) {
        return;
    }
    let g = |n: u32| S::<V>::gamma_n(n).to_f64();
    let u = S::<V>::UNIT_ROUNDOFF.to_f64();
    let t = |p: f64, k: f64| 2.0 * (g(4) + g(3) * k / p) + 2.0 * u;
    let t_diff = s_len / p0 * (g(28) + 5.0 * g(3) * k0 / p0);
    let t_2 = 2.0 * s_len * s_len / ((p0 - s_len) * (p0 - s_len));
    let e = lin.orthonormal;
    let reach = norm(lin.c) + f(dx).abs() * norm(a) + f(dy).abs() * norm(b);
    let t_frame = e * reach / ((1.0 - e) * p0 * p0);
    assert!(
        t_diff + t_frame <= error.to_f64(),
        "ray_differential_error {error:?} below its derivation {}: {}",
        t_diff + t_frame,
        ctx()
    );
    let bound = (t(p0, k0) + t(p1, k1) + error.to_f64() + t_2) * (1.0 + 1e-9);
    let (d0, d1, dd) = (rv(dir), rv(next), rv(diff));
    let res: [R; 3] = core::array::from_fn(|k| &d1[k] - &d0[k] - &dd[k]);
    let b2 = R::from_float(bound * bound).expect("a finite bound");
    assert!(
        dot(&res, &res) <= b2,
        "neighbour off the differential by {} > {bound}: {}",
        super::exact::f(&dot(&res, &res)).sqrt(),
        ctx()
    );
}

/// The pinhole camera's differentials at a pixel centre, against its
/// neighbours' rays ([`check_linear_differential`]), and its ray.
pub fn check_pinhole_differential<V: Vector>(cam: &PinholeCamera<V>, i: u32, j: u32) {
    let ctx = || format!("{cam:?} at pixel ({i}, {j})");
    let half = S::<V>::HALF;
    let (x, y) = (S::<V>::from_u32(i) + half, S::<V>::from_u32(j) + half);
    let diff = cam.ray_differential(CameraSample::new(x, y));
    let ray = cam.ray(CameraSample::new(x, y));
    assert!(
        vector_bits(diff.ray.dir) == vector_bits(ray.dir)
            && vector_bits(diff.ray.origin) == vector_bits(ray.origin),
        "{}",
        ctx()
    );
    assert_eq!(vector_bits(diff.dx_origin), vector_bits(V::ZERO));
    let fl = cam.focal_length().to_f64();
    let fw = cam.forward();
    let lin = Linear {
        c: [0, 1, 2].map(|k| fw[k].to_f64() * fl),
        a: cam.right(),
        b: cam.up(),
        // The camera's frame is orthonormal within gamma(13) (its docs).
        orthonormal: S::<V>::gamma_n(13).to_f64(),
    };
    let dx = x - S::<V>::from_u32(cam.width()) * half;
    let dy = S::<V>::from_u32(cam.height()) * half - y;
    let one = S::<V>::ONE;
    let next_x = cam.ray(CameraSample::new(x + one, y)).dir;
    let next_y = cam.ray(CameraSample::new(x, y + one)).dir;
    let error = cam.ray_differential_error(x, y);
    let (a, b) = (lin.a, -lin.b);
    check_linear_differential(&lin, dx, dy, a, ray.dir, next_x, diff.dx_dir, error, &ctx);
    check_linear_differential(&lin, dx, dy, b, ray.dir, next_y, diff.dy_dir, error, &ctx);
}
