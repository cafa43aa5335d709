//! `equirectangular` and `equal_area`: [`EquirectangularCamera`] and
//! [`EqualAreaCamera`]: construction, rays, the inverse, differentials.
//!
//! Input: raw mode, eye, view and up as raw-bit vectors, width, height, a
//! raster position and a direction; structured mode, a frame from
//! [`cases::cameras`](crate::cases::cameras) and three raster positions in the image.
//!
//! Checks, any input: no panic; a camera only from valid input; the
//! differential's ray is the ray bit for bit; a finite position gives a
//! unit direction (length within `4 u` of 1), a NaN
//! one a NaN direction; `raster_position` is `None` exactly for
//! a zero or non-finite direction and otherwise in the image. Structured
//! inputs also: the centre pixel of an odd-sized image looks along the
//! view (within `4 gamma(6)` per component); the round trip
//! `raster_position(ray(x, y).dir)` is `(x, y)` within the crate's
//! `raster_position_error`; the
//! differentials are the difference of the neighbouring pixels' rays within
//! the second-order bound plus the rays' errors (equirectangular), or a
//! central difference of the `f64` map within its truncation and rounding
//! error (equal area, away from the map's creases), and the equal-area
//! differentials span a pixel's solid angle, `4 pi / (width height)`.

use arbitrary::Arbitrary;
use rayhit::glam::DVec3;
use rayhit::{
    Camera, CameraSample, Scalar, Vector,
    camera::{CameraError, EqualAreaCamera, EquirectangularCamera},
};

use super::exact::{abs, dot, gamma, int, rv};
use super::{Check, Input, S, raw, raw_vec};
use crate::bits::vector_bits;
use crate::cases::cameras::{Frame, frame, raster};

/// The `equirectangular` target.
#[derive(Debug)]
pub struct Equirectangular;

/// The `equal_area` target.
#[derive(Debug)]
pub struct EqualArea;

/// What the checks need of either camera beyond [`Camera`]: how to make
/// one, and its inverse and frame.
trait Panorama<V: Vector>: Camera<V> + core::fmt::Debug + Sized {
    /// True for the equal-area map, whose square's edges fold.
    const FOLDS: bool;
    fn make(f: &Frame<V>) -> Result<Self, CameraError>;
    fn back(&self, dir: V) -> Option<(S<V>, S<V>)>;
    fn forward(&self) -> V;
    fn basis(&self) -> [V; 3];
}

impl<V: Vector> Panorama<V> for EquirectangularCamera<V> {
    const FOLDS: bool = false;
    fn make(f: &Frame<V>) -> Result<Self, CameraError> {
        EquirectangularCamera::new(f.eye, f.view, f.up, f.width, f.height)
    }
    fn back(&self, dir: V) -> Option<(S<V>, S<V>)> {
        self.raster_position(dir)
    }
    fn forward(&self) -> V {
        EquirectangularCamera::forward(self)
    }
    fn basis(&self) -> [V; 3] {
        [
            self.right(),
            self.up(),
            EquirectangularCamera::forward(self),
        ]
    }
}

impl<V: Vector> Panorama<V> for EqualAreaCamera<V> {
    const FOLDS: bool = true;
    fn make(f: &Frame<V>) -> Result<Self, CameraError> {
        EqualAreaCamera::new(f.eye, f.view, f.up, f.width, f.height)
    }
    fn back(&self, dir: V) -> Option<(S<V>, S<V>)> {
        self.raster_position(dir)
    }
    fn forward(&self) -> V {
        EqualAreaCamera::forward(self)
    }
    fn basis(&self) -> [V; 3] {
        [self.right(), self.up(), EqualAreaCamera::forward(self)]
    }
}

/// The raw checks, for either camera.
fn raw_checks<'a, V, C>(u: &mut arbitrary::Unstructured<'a>)
where
    V: Vector,
    S<V>: Arbitrary<'a>,
    C: Panorama<V>,
{
    let (eye, view, up) = (raw_vec::<V>(u), raw_vec::<V>(u), raw_vec::<V>(u));
    let (width, height) = (raw::<u32>(u), raw::<u32>(u));
    let (x, y) = (raw::<S<V>>(u), raw::<S<V>>(u));
    let dir = raw_vec::<V>(u);
    let f = Frame {
        eye,
        view,
        up,
        width,
        height,
    };
    let cam = match C::make(&f) {
        Ok(cam) => cam,
        Err(e) => {
            let ok = match e {
                CameraError::NonFiniteEye => !eye.is_finite(),
                CameraError::InvalidViewDir => !view.is_finite() || view == V::ZERO,
                CameraError::InvalidUp => !up.is_finite() || up == V::ZERO,
                CameraError::UpParallelToView => true,
                CameraError::EmptyImage => width == 0 || height == 0,
                _ => false,
            };
            assert!(ok, "{e:?} for {f:?}");
            return;
        }
    };
    check_ray(&cam, x, y);
    check_back(&cam, dir);
}

/// The ray, its differential's ray, and its direction's length.
fn check_ray<V: Vector, C: Panorama<V>>(cam: &C, x: S<V>, y: S<V>) {
    let ctx = || format!("{cam:?} at ({x:?}, {y:?})");
    let ray = cam.ray(CameraSample::new(x, y));
    let diff = cam.ray_differential(CameraSample::new(x, y));
    assert!(
        vector_bits(diff.ray.dir) == vector_bits(ray.dir)
            && vector_bits(diff.ray.origin) == vector_bits(ray.origin),
        "differential's ray is not the ray: {}",
        ctx()
    );
    if x.to_f64().is_nan() || y.to_f64().is_nan() {
        assert!(!ray.dir.is_finite(), "finite direction: {}", ctx());
        return;
    }
    if !(x.is_finite() && y.is_finite()) {
        // Documented: a NaN direction for the equirectangular camera (its
        // angle has no value), the edge's for the equal-area one (clamped).
        return;
    }
    assert!(ray.dir.is_finite(), "non-finite direction: {}", ctx());
    // Unit within 4 u (both cameras' docs): 4 gamma(1) is slightly more.
    let d = rv(ray.dir);
    let g = gamma::<S<V>>(1) * int(4);
    assert!(
        abs(&(dot(&d, &d) - int(1))) <= int(2) * &g + &g * &g,
        "direction {:?} not unit: {}",
        ray.dir,
        ctx()
    );
}

/// `None` exactly for a zero or non-finite direction, else in the image.
fn check_back<V: Vector, C: Panorama<V>>(cam: &C, dir: V) {
    let (w, h) = (cam.width(), cam.height());
    match cam.back(dir) {
        None => assert!(!dir.is_finite() || dir == V::ZERO, "{cam:?}: {dir:?}"),
        Some((x, y)) => {
            assert!(dir.is_finite() && dir != V::ZERO);
            let inside = |p: S<V>, n: u32| p >= S::<V>::ZERO && p <= S::<V>::from_u32(n);
            assert!(
                inside(x, w) && inside(y, h),
                "{cam:?}: {dir:?} at ({x:?}, {y:?})"
            );
        }
    }
}

/// `(TRIG, ATAN)`: the `n` of the crate's sine and cosine bound,
/// `gamma(TRIG + 2)` absolute (`num::trig::sin_cos_turns`), and of its
/// arctangent's, `gamma(ATAN)` turns.
fn trig<F: Scalar>() -> (u32, u32) {
    if F::UNIT_ROUNDOFF.to_f64() > 1e-10 {
        (26, 12)
    } else {
        (42, 24)
    }
}

/// The basis's departure from orthonormal: the largest entry of `B^T B -
/// I` (`B` the camera's `right`, `up`, `forward` as columns), computed in
/// `f64` (exact products for `f32`; for `f64` within a few `f64` ulps,
/// which the `4 u` added covers), and at least `gamma(13)`. The cameras'
/// basis is orthonormal within `gamma(13)` (`2 gamma(6) + gamma(6)^2` on
/// the diagonal, the cross products' and the re-orthogonalisation's
/// rounding off it), also for up vectors nearly parallel to the view; the
/// checks measure it rather than assume it. The crate measures it the same
/// way for its own bounds; this copy is the checks' own, so that a change
/// there cannot move the derivation the crate's bounds are held to.
pub fn basis_skew<V: Vector>(b: [V; 3]) -> f64 {
    let d = |p: V, q: V| (0..3).map(|k| p[k].to_f64() * q[k].to_f64()).sum::<f64>();
    let mut m = S::<V>::gamma_n(13).to_f64();
    for i in 0..3 {
        for j in 0..3 {
            let target = if i == j { 1.0 } else { 0.0 };
            m = m.max((d(b[i], b[j]) - target).abs() + 4.0 * f64::EPSILON);
        }
    }
    m
}

/// The angle, in radians, between the computed direction and the exact
/// one of the computed angles, for either camera's forward map, plus the
/// inverse's recovery of the local components (in terms of `gamma(n)`,
/// `n` from [`trig`], and the basis's measured `skew`, [`basis_skew`]):
///
/// - the local components `(X, Y, Z)`: products of two sines or cosines
///   (each within `gamma(T)`, `T = TRIG + 2`) and a rounding, within
///   `gamma(2T + 2)`; the equal-area map's `r sqrt(2 - r^2)` and `1 - r^2`
///   add `gamma(10)` (its `r` within three roundings, relative: see
///   `square` in the camera);
/// - the world vector `X right + Y up + Z forward`: the components' errors
///   times `|right_i| + |up_i| + |forward_i|`, and three roundings of the
///   sum: per component within `(|right_i| + |up_i| + |forward_i|)
///   gamma(2T + 15)`, a vector at most `3 gamma(2T + 15)` long (the
///   basis vectors have length 1 within `gamma(6)`);
/// - normalising, in the forward map and again in the inverse: a common
///   factor, and one rounding per component each time (`2 sqrt(3) u`);
/// - the inverse's dot products with the basis (`gamma(3)` each, `sqrt(3)
///   gamma(3)` as a vector) and the basis's departure from orthonormal
///   (`B^T B - I`, each entry at most `skew`): `3 skew`.
fn direction_angle<F: Scalar>(skew: f64) -> f64 {
    let (tr, _) = trig::<F>();
    let g = |n: u32| F::gamma_n(n).to_f64();
    let u = F::UNIT_ROUNDOFF.to_f64();
    3.0 * g(2 * tr + 15) + 2.0 * 3f64.sqrt() * u + 3f64.sqrt() * g(3) + 3.0 * skew
}

impl Check for Equirectangular {
    fn run<'a, V>(input: &mut Input<'a>)
    where
        V: Vector,
        S<V>: Arbitrary<'a> + Scalar,
    {
        match input {
            Input::Raw(u) => raw_checks::<V, EquirectangularCamera<V>>(u),
            Input::Structured(src) => {
                let f = frame::<V>(src);
                let Ok(cam) = EquirectangularCamera::make(&f) else {
                    return;
                };
                check_centre(&cam);
                for _ in 0..3 {
                    let (x, y) = raster::<S<V>>(src, f.width, f.height);
                    check_ray(&cam, x, y);
                    let inside = x.to_f64() >= 0.0
                        && x.to_f64() <= f64::from(f.width)
                        && y.to_f64() >= 0.0
                        && y.to_f64() <= f64::from(f.height);
                    if !inside {
                        continue;
                    }
                    let (bx, by) = cam.raster_position_error(x, y);
                    check_round_trip(&cam, x, y, bx.to_f64(), by.to_f64());
                    check_equirectangular_neighbours(&cam, x, y);
                }
            }
        }
    }
}

impl Check for EqualArea {
    fn run<'a, V>(input: &mut Input<'a>)
    where
        V: Vector,
        S<V>: Arbitrary<'a> + Scalar,
    {
        match input {
            Input::Raw(u) => raw_checks::<V, EqualAreaCamera<V>>(u),
            Input::Structured(src) => {
                let f = frame::<V>(src);
                let Ok(cam) = EqualAreaCamera::make(&f) else {
                    return;
                };
                check_centre(&cam);
                for _ in 0..3 {
                    let (x, y) = raster::<S<V>>(src, f.width, f.height);
                    check_ray(&cam, x, y);
                    let inside = x.to_f64() >= 0.0
                        && x.to_f64() <= f64::from(f.width)
                        && y.to_f64() >= 0.0
                        && y.to_f64() <= f64::from(f.height);
                    if inside {
                        let (bx, by) = cam.raster_position_error(x, y);
                        check_round_trip(&cam, x, y, bx.to_f64(), by.to_f64());
                        check_equal_area_derivatives(&cam, x, y);
                    }
                }
            }
        }
    }
}

/// The centre pixel of an odd-sized image looks along `forward`: its
/// angles are exactly zero, so its direction is `forward` normalised again
/// (within `gamma(6)` per component of `forward / |forward|`, itself unit
/// within `gamma(6)`).
fn check_centre<V: Vector, C: Panorama<V>>(cam: &C) {
    let (w, h) = (cam.width(), cam.height());
    if w % 2 == 0 || h % 2 == 0 {
        return;
    }
    let half = S::<V>::HALF;
    let d = cam
        .ray(CameraSample::new(
            S::<V>::from_u32(w / 2) + half,
            S::<V>::from_u32(h / 2) + half,
        ))
        .dir;
    let f = cam.forward();
    let g = 4.0 * S::<V>::gamma_n(6).to_f64();
    for i in 0..3 {
        assert!(
            (d[i].to_f64() - f[i].to_f64()).abs() <= g,
            "centre pixel {d:?} off forward {f:?}: {cam:?}"
        );
    }
}

/// The round trip lands within `(bx, by)` of `(x, y)` or of a position
/// with the same direction: for the equirectangular map the same position
/// a turn away in longitude; for the equal-area map, the mirror image
/// across the centre line of a position on the image's edge (the square's
/// edges fold onto each other: `(u, 1)` and `(-u, 1)` are one direction, and
/// likewise `(1, v)` and `(1, -v)`), for positions within the bound of an
/// edge.
fn check_round_trip<V: Vector, C: Panorama<V>>(cam: &C, x: S<V>, y: S<V>, bx: f64, by: f64) {
    let dir = cam.ray(CameraSample::new(x, y)).dir;
    let (rx, ry) = cam.back(dir).expect("a unit direction");
    let (rx, ry) = (rx.to_f64(), ry.to_f64());
    let (w, h) = (f64::from(cam.width()), f64::from(cam.height()));
    let (x, y) = (x.to_f64(), y.to_f64());
    let near = |p: f64, n: f64, b: f64| p <= b || p >= n - b;
    let mut same = vec![(x, y), (x - w, y), (x + w, y)];
    if C::FOLDS {
        if near(y, h, by) {
            same.push((w - x, y));
        }
        if near(x, w, bx) {
            same.push((x, h - y));
        }
        if near(y, h, by) && near(x, w, bx) {
            same.push((w - x, h - y));
        }
    }
    let hit = same
        .iter()
        .any(|&(sx, sy)| (rx - sx).abs() <= bx && (ry - sy).abs() <= by);
    assert!(
        hit,
        "round trip ({x}, {y}) -> {dir:?} -> ({rx}, {ry}): bound ({bx}, {by}): {cam:?}"
    );
}

/// The equirectangular differentials are the neighbours' rays less the
/// ray, within the second-order term (`(2 pi / w)^2 / 2` across, `(pi /
/// h)^2 / 2` down: the map's second derivatives are at most 1 long in
/// radians), both rays' errors (each within `direction_angle + 2 pi
/// gamma(2) / 2` of its exact place: the angle's rounding), the
/// differential's own (its sines and cosines within `gamma(TRIG + 2)`,
/// their products, the basis and the scale: `(2 pi / w) 3 gamma(2T +
/// 15)`, likewise), and the normalisation's effect on the derivative
/// where the basis is not exactly orthonormal (see the code).
fn check_equirectangular_neighbours<V: Vector>(cam: &EquirectangularCamera<V>, x: S<V>, y: S<V>) {
    // The second-order term assumes an orthonormal basis (to within a
    // rounding's effect on it), as every camera's is (see `basis_skew`).
    assert!(basis_skew(cam.basis()) <= 1e-3);
    let (tr, _) = trig::<S<V>>();
    let g = |n: u32| S::<V>::gamma_n(n).to_f64();
    let pi = core::f64::consts::PI;
    let (w, h) = (f64::from(cam.width()), f64::from(cam.height()));
    let diff = cam.ray_differential(CameraSample::new(x, y));
    // The forward map alone: no inverse, so no dot products and no skew.
    let ray_error = direction_angle::<S<V>>(0.0)
        - 3f64.sqrt() * g(3)
        - 3f64.sqrt() * S::<V>::UNIT_ROUNDOFF.to_f64()
        + pi * g(2);
    for (step, nx, ny, d) in [
        (2.0 * pi / w, x + S::<V>::ONE, y, diff.dx_dir),
        (pi / h, x, y + S::<V>::ONE, diff.dy_dir),
    ] {
        let next = cam.ray(CameraSample::new(nx, ny)).dir;
        // The differential is the unnormalised map's derivative; the rays
        // are normalised. With the basis orthonormal within `skew`, the
        // map's length is 1 within `2 skew` and its derivative along it at
        // most `2 skew step`: the normalised derivative is within `5 skew
        // step` of it, and the second derivative within `1 + 4 skew`.
        let skew = basis_skew(cam.basis());
        let bound = step * step / 2.0 * (1.0 + 4.0 * skew)
            + 5.0 * skew * step
            + 2.0 * ray_error
            + step * 3.0 * g(2 * tr + 15);
        let off = (0..3)
            .map(|i| next[i].to_f64() - diff.ray.dir[i].to_f64() - d[i].to_f64())
            .map(|e| e * e)
            .sum::<f64>()
            .sqrt();
        assert!(
            off <= bound * (1.0 + 1e-9),
            "neighbour of ({x:?}, {y:?}) off the differential by {off} > {bound}: {cam:?}"
        );
    }
}

/// The equal-area differentials against a central difference of the same
/// map in `f64` (the octahedral formulas on this camera's own basis,
/// unnormalised, with the `f64` library's sine and cosine; step `1e-4`
/// pixels, away from the map's creases and the image's edge).
///
/// Truncation: the central difference is within `step^2 |d'''| / 6` of the
/// derivative. In a face (say `u, v > 0` in front: `r = u + v`, `phi =
/// (pi/2) v / r`, `d = (cos(phi) S(r), sin(phi) S(r), 1 - r^2)`), along
/// `u` `phi' = -(pi/2) v / r^2`, `phi'' = pi v / r^3`, `phi''' = -3 pi v
/// / r^4`, with `v <= r`, and `S`, `S'`, `S''`, `S'''` at most `sqrt(2)`,
/// `sqrt(2)`, `6` and `30` on `[0, 1]`; the terms of `(cos(phi) S)'''`
/// are then at most `13.4 + 5.5 + 21 + 13.4 + 10.5` over `r^2`, `28 / r`
/// and `30`, below `122 / r^2` (`r <= 1`), likewise behind and along `v`,
/// so `|d'''| <= 250 / r^2` per unit of `u`, and `250 (2 / w)^3 / r^2` per
/// pixel (a numerical survey of the faces away from the creases finds
/// below `12 / r^2`). Rounding: the `f64` map is within `e` =
/// [`direction_angle`] (in `f64`; the library's sine and cosine are far
/// more accurate than the crate's bound) of the exact map, so the
/// difference adds `e / step`. Each camera's differential is within `3
/// gamma(2T + 15) |derivative|_1` of the exact map's derivative (its sines
/// and cosines, products and basis, as a vector).
/// The two differentials span the pixel's solid angle, `|dx x dy| = 4 pi
/// / (w h)` (the map is equal-area), within the cross product of those
/// errors (`2 sqrt(3)` of the relative error times `|dx| |dy|`) and the
/// basis's departure from orthonormal (`3 gamma(13)` relative).
fn check_equal_area_derivatives<V: Vector>(cam: &EqualAreaCamera<V>, x: S<V>, y: S<V>) {
    // As for the neighbours above: a nearly orthonormal basis.
    if basis_skew(cam.basis()) > 1e-3 {
        return;
    }
    let (w, h) = (cam.width(), cam.height());
    // The map in f64 on this camera's own basis (its exact map up to f64's
    // roundings), unnormalised as the differentials' formulas are.
    let [rt, up, fw] = cam.basis().map(c64);
    let map = |x: f64, y: f64| {
        let (u, v) = (2.0 * x / f64::from(w) - 1.0, 1.0 - 2.0 * y / f64::from(h));
        let (au, av) = (u.abs(), v.abs());
        let front = au + av <= 1.0;
        let (r, p) = if front {
            (au + av, av)
        } else {
            ((1.0 - au) + (1.0 - av), 1.0 - au)
        };
        let phi = core::f64::consts::FRAC_PI_2 * p / r;
        let ring = r * (2.0 - r * r).sqrt();
        let z = if front { 1.0 - r * r } else { r * r - 1.0 };
        rt * (phi.cos().copysign(u) * ring) + up * (phi.sin().copysign(v) * ring) + fw * z
    };
    let (xf, yf) = (x.to_f64(), y.to_f64());
    let (u, v) = (2.0 * xf / f64::from(w) - 1.0, 1.0 - 2.0 * yf / f64::from(h));
    let r = if u.abs() + v.abs() <= 1.0 {
        u.abs() + v.abs()
    } else {
        2.0 - u.abs() - v.abs()
    };
    let step = 1e-4;
    let margin = 4.0 * step * 2.0 / f64::from(w.min(h));
    // The creases, and the image's edge (where the map is clamped).
    let crease = u.abs() < margin
        || v.abs() < margin
        || (u.abs() + v.abs() - 1.0).abs() < margin
        || u.abs() > 1.0 - margin
        || v.abs() > 1.0 - margin;
    if crease || r < 1e-2 {
        return;
    }
    let (tr, _) = trig::<S<V>>();
    let rel = 3.0 * S::<V>::gamma_n(2 * tr + 15).to_f64();
    let scale = 2.0 / f64::from(w.min(h));
    let e64 = direction_angle::<f64>(0.0);
    let truncation = step * step * 250.0 * scale.powi(3) / (r * r) / 6.0 + e64 / step;
    let diff = cam.ray_differential(CameraSample::new(x, y));
    for (dx, dy, got) in [(step, 0.0, diff.dx_dir), (0.0, step, diff.dy_dir)] {
        let (a, b) = (map(xf + dx, yf + dy), map(xf - dx, yf - dy));
        let central = (a - b) / (2.0 * step);
        let got = c64(got);
        let bound = rel * got.abs().element_sum() + truncation;
        assert!(
            (got - central).length() <= bound,
            "differential {got} vs central difference {central} at ({x:?}, {y:?}): {cam:?}"
        );
    }
    // Equal area: the differentials span the pixel's solid angle.
    let area = c64(diff.dx_dir).cross(c64(diff.dy_dir)).length();
    let exact = 4.0 * core::f64::consts::PI / (f64::from(w) * f64::from(h));
    let span = c64(diff.dx_dir).length() * c64(diff.dy_dir).length();
    let skew = 3.0 * basis_skew(cam.basis());
    assert!(
        (area - exact).abs() <= 2.0 * 3f64.sqrt() * rel * span + skew * exact,
        "pixel solid angle {area} vs {exact} at ({x:?}, {y:?}): {cam:?}"
    );
}

/// A vector in `f64`.
fn c64<V: Vector>(v: V) -> DVec3 {
    DVec3::new(v.x().to_f64(), v.y().to_f64(), v.z().to_f64())
}
