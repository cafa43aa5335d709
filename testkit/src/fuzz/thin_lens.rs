//! `thin_lens`: [`ThinLensCamera`]: its construction, focus points, rays
//! and differentials.
//!
//! Input: raw mode, a pinhole camera's inputs (as the `camera` target), a
//! lens radius, a focal distance, a raster position and two lens samples
//! as raw bits; structured mode, a frame from [`cases::cameras`], a
//! field of view, a lens ([`cases::cameras::lens`]), a raster position and
//! four lens samples.
//!
//! Checks, any input: no panic; a camera only from a valid pinhole camera,
//! a radius `>= 0` and finite and a focal distance `> 0` and finite, and
//! each error names an input that is bad that way; `ray` is `ray_through`
//! of `focus` bit for bit, and `ray_differential`'s ray is `ray`; a lens
//! sample at the lens centre, or a zero radius, gives the pinhole ray bit
//! for bit; every other ray whose lens sample is in `[0, 1]^2` and whose
//! coordinates stay below `MAX / 16` meets the focus point exactly:
//! `origin + dir` is the focus point in exact arithmetic and `ray.at(1)`
//! is it bit for bit. Structured inputs also: the focus point is within
//! its derived bound of the exact `eye + (focal_distance / focal_length)
//! p` (`check_focus`), the lens point is on the lens, the differentials
//! are `(focal_distance / focal_length)` times `right` and `-true_up` bit
//! for bit, and they are the difference of the rays of neighbouring pixel
//! centres within the focus points' bounds.

use arbitrary::Arbitrary;
use rayhit::{
    Camera, CameraSample, PinholeCamera, Scalar, Vector,
    camera::{CameraError, FocusPoint, ThinLensCamera},
};

use super::exact::{R, abs, gamma, int, r, rv};
use super::{Check, Input, S, raw, raw_vec};
use crate::bits::vector_bits;
use crate::cases;
use crate::cases::cameras::{fov, frame, lens, lens_sample, raster};

/// The `thin_lens` target.
#[derive(Debug)]
pub struct ThinLens;

impl Check for ThinLens {
    fn run<'a, V>(input: &mut Input<'a>)
    where
        V: Vector,
        S<V>: Arbitrary<'a> + Scalar,
    {
        match input {
            Input::Raw(u) => {
                let (eye, view, up) = (raw_vec::<V>(u), raw_vec::<V>(u), raw_vec::<V>(u));
                let focal = raw::<S<V>>(u);
                let (w, h) = (raw::<u32>(u), raw::<u32>(u));
                let (radius, distance) = (raw::<S<V>>(u), raw::<S<V>>(u));
                let (x, y) = (raw::<S<V>>(u), raw::<S<V>>(u));
                let samples = [(raw::<S<V>>(u), raw::<S<V>>(u)), (raw(u), raw(u))];
                let Ok(pinhole) = PinholeCamera::new(eye, view, up, focal, w, h) else {
                    return;
                };
                let cam = ThinLensCamera::new(pinhole, radius, distance);
                check_new(&cam, &pinhole, radius, distance);
                if let Ok(cam) = cam {
                    for (s, t) in samples {
                        check_ray(&cam, x, y, s, t);
                    }
                }
            }
            Input::Structured(src) => {
                let f = frame::<V>(src);
                let fov = fov::<S<V>>(src);
                let Ok(pinhole) =
                    PinholeCamera::from_fov(f.eye, f.view, f.up, fov, f.width, f.height)
                else {
                    return;
                };
                let (radius, distance) = lens::<V>(src);
                let cam = ThinLensCamera::new(pinhole, radius, distance)
                    .expect("a valid pinhole camera, radius and focal distance");
                let (x, y) = raster::<S<V>>(src, f.width, f.height);
                check_focus(&cam, x, y);
                for _ in 0..4 {
                    let (s, t) = lens_sample::<S<V>>(src);
                    check_ray(&cam, x, y, s, t);
                    check_lens_point(&cam, s, t);
                }
                let (i, j) = cases::cameras::pixel(src, f.width, f.height);
                let (s, t) = lens_sample::<S<V>>(src);
                check_neighbours(&cam, i, j, s, t);
            }
        }
    }
}

fn check_new<V: Vector>(
    cam: &Result<ThinLensCamera<V>, CameraError>,
    pinhole: &PinholeCamera<V>,
    radius: S<V>,
    distance: S<V>,
) {
    let zero = S::<V>::ZERO;
    let radius_ok = radius >= zero && radius.is_finite();
    let distance_ok = distance > zero && distance.is_finite();
    let ctx = || format!("{pinhole:?}, radius {radius:?}, focal distance {distance:?}");
    // The documented extremes: a lens whose coordinates overflow, a ratio
    // to the focal length that under- or overflows.
    let reach_overflows = (0..3).any(|i| {
        let reach = pinhole.eye()[i].to_f64().abs()
            + radius.to_f64()
                * (pinhole.right()[i].to_f64().abs() + pinhole.up()[i].to_f64().abs());
        !(reach * (1.0 + 1e-4) < S::<V>::MAX.to_f64())
    });
    let ratio = distance / pinhole.focal_length();
    let ratio_bad = !(ratio > zero && ratio.is_finite());
    match cam {
        Ok(_) => assert!(
            radius_ok && distance_ok && !ratio_bad,
            "thin lens from {}",
            ctx()
        ),
        Err(CameraError::InvalidLensRadius) => {
            assert!(!radius_ok || reach_overflows, "radius rejected: {}", ctx())
        }
        Err(CameraError::InvalidFocalDistance) => assert!(
            radius_ok && (!distance_ok || ratio_bad),
            "focal distance rejected: {}",
            ctx()
        ),
        Err(e) => panic!("{e:?} from a valid pinhole camera: {}", ctx()),
    }
}

/// `M_i`'s upper end as the test knows it: the lens's reach, with room for
/// the camera's own rounded-up bound (below `gamma(50)` relative).
fn lens_reach<V: Vector>(cam: &ThinLensCamera<V>, i: usize) -> f64 {
    let p = cam.pinhole();
    let reach = p.eye()[i].to_f64().abs()
        + cam.lens_radius().to_f64() * (p.right()[i].to_f64().abs() + p.up()[i].to_f64().abs());
    reach * (1.0 + 1e-4)
}

/// True when the focus point's grid applies: every coordinate of the focus
/// point and the lens below `MAX / 16`.
fn on_grid<V: Vector>(cam: &ThinLensCamera<V>, focus: &FocusPoint<V>) -> bool {
    let limit = S::<V>::MAX.to_f64() / 16.0;
    (0..3).all(|i| focus.point()[i].to_f64().abs() < limit && lens_reach(cam, i) < limit)
}

fn check_ray<V: Vector>(cam: &ThinLensCamera<V>, x: S<V>, y: S<V>, s: S<V>, t: S<V>) {
    let ctx = || format!("{cam:?} at ({x:?}, {y:?}), lens ({s:?}, {t:?})");
    let focus = cam.focus(x, y);
    let ray = cam.ray_through(&focus, s, t);
    let again = cam.ray(CameraSample::new(x, y).with_lens(s, t));
    assert!(
        vector_bits(ray.origin) == vector_bits(again.origin)
            && vector_bits(ray.dir) == vector_bits(again.dir),
        "ray is not ray_through(focus): {}",
        ctx()
    );
    let diff = cam.ray_differential(CameraSample::new(x, y).with_lens(s, t));
    assert!(
        vector_bits(diff.ray.origin) == vector_bits(ray.origin)
            && vector_bits(diff.ray.dir) == vector_bits(ray.dir),
        "ray_differential's ray is not ray: {}",
        ctx()
    );
    let centre = s == S::<V>::HALF && t == S::<V>::HALF;
    let pinhole = cam.pinhole().ray(CameraSample::new(x, y));
    if centre || cam.lens_radius() == S::<V>::ZERO {
        assert!(
            vector_bits(ray.origin) == vector_bits(pinhole.origin)
                && vector_bits(ray.dir) == vector_bits(pinhole.dir),
            "lens centre is not the pinhole ray: {}",
            ctx()
        );
        return;
    }
    let in_square = |a: S<V>| a >= S::<V>::ZERO && a <= S::<V>::ONE;
    if !(x.is_finite() && y.is_finite() && focus.point().is_finite()) {
        return;
    }
    if in_square(s) && in_square(t) && on_grid(cam, &focus) {
        assert!(
            ray.origin.is_finite() && ray.dir.is_finite(),
            "non-finite ray {ray:?}: {}",
            ctx()
        );
        assert_eq!(
            vector_bits(ray.at(S::<V>::ONE)),
            vector_bits(focus.point()),
            "ray.at(1) is not the focus point: {}",
            ctx()
        );
        let (o, d, f) = (rv(ray.origin), rv(ray.dir), rv(focus.point()));
        for k in 0..3 {
            assert!(
                &o[k] + &d[k] == f[k],
                "origin + dir is not the focus point exactly: {}",
                ctx()
            );
        }
    }
}

/// The exact point `focus(x, y)` stands for, `eye + focal_distance forward
/// + k (dx right + dy up)` with `k = focal_distance / focal_length`
/// exactly and the camera's (rounded) basis and offsets, and the crate's
/// bound on the distance, `focus_error` (derived there), as rationals.
pub fn focus_bound<V: Vector>(cam: &ThinLensCamera<V>, x: S<V>, y: S<V>) -> ([R; 3], [R; 3]) {
    let p = cam.pinhole();
    let (w, h) = (p.width(), p.height());
    let half = S::<V>::HALF;
    let dx = x - S::<V>::from_u32(w) * half;
    let dy = S::<V>::from_u32(h) * half - y;
    let k = r(cam.focal_distance()) / r(p.focal_length());
    let (f, rt, up, eye) = (rv(p.forward()), rv(p.right()), rv(p.up()), rv(p.eye()));
    let (fd, dxr, dyr) = (r(cam.focal_distance()), r(dx), r(dy));
    let exact =
        core::array::from_fn(|i| &eye[i] + &fd * &f[i] + &k * (&dxr * &rt[i] + &dyr * &up[i]));
    (exact, rv(cam.focus_error(x, y)))
}

/// [`focus_bound`] held.
fn check_focus<V: Vector>(cam: &ThinLensCamera<V>, x: S<V>, y: S<V>) {
    let focus = cam.focus(x, y).point();
    assert!(focus.is_finite(), "{cam:?}: focus {focus:?}");
    let (exact, bound) = focus_bound(cam, x, y);
    let got = rv(focus);
    for i in 0..3 {
        assert!(
            abs(&(&got[i] - &exact[i])) <= bound[i],
            "focus point {focus:?} off the exact one in component {i}: {cam:?} at ({x:?}, {y:?})"
        );
    }
}

/// The lens point is on the lens: its offset from the eye has a length of
/// at most the radius (the concentric map's point in the disc within
/// `gamma(TRIG + 4)`, `gamma(28)` or `gamma(44)`, plus three roundings of
/// the sum, relative to `|eye| + radius`).
fn check_lens_point<V: Vector>(cam: &ThinLensCamera<V>, s: S<V>, t: S<V>) {
    let p = cam.pinhole();
    let l = cam.lens_point(s, t);
    let off: Vec<f64> = (0..3)
        .map(|i| l[i].to_f64() - p.eye()[i].to_f64())
        .collect();
    let len = off.iter().map(|x| x * x).sum::<f64>().sqrt();
    let g = S::<V>::gamma_n(48).to_f64();
    let eye = (0..3)
        .map(|i| p.eye()[i].to_f64().abs())
        .fold(0.0, f64::max);
    let radius = cam.lens_radius().to_f64();
    assert!(
        len <= radius * (1.0 + g) + 2.0 * g * (eye + radius),
        "lens point {l:?} is {len} from the eye, radius {radius}"
    );
}

/// The rays of neighbouring pixel centres differ by the differentials,
/// which are `k right` and `-k up` with `k` the camera's ratio, bit for
/// bit. The difference of the directions is `F(x+1) - F(x)` (exactly `k
/// right` in exact arithmetic) less the lens points' difference (the same
/// point on two grids: at most half of each grid's spacing, `4 u
/// max(|F_i|, M_i)` each): within the two focus bounds, those, and
/// `gamma(2) k |right_i|` (the differential's own rounding).
fn check_neighbours<V: Vector>(cam: &ThinLensCamera<V>, i: u32, j: u32, s: S<V>, t: S<V>) {
    let p = cam.pinhole();
    let k = cam.focal_distance() / p.focal_length();
    let half = S::<V>::HALF;
    let (x, y) = (S::<V>::from_u32(i) + half, S::<V>::from_u32(j) + half);
    let diff = cam.ray_differential(CameraSample::new(x, y).with_lens(s, t));
    let centre = s == half && t == half;
    if centre || cam.lens_radius() == S::<V>::ZERO {
        return;
    }
    assert_eq!(vector_bits(diff.dx_dir), vector_bits(p.right() * k));
    assert_eq!(vector_bits(diff.dy_dir), vector_bits(-(p.up() * k)));
    assert_eq!(vector_bits(diff.dx_origin), vector_bits(V::ZERO));
    for (step, (nx, ny), dd) in [
        ("x", (x + S::<V>::ONE, y), diff.dx_dir),
        ("y", (x, y + S::<V>::ONE), diff.dy_dir),
    ] {
        let next = cam.ray(CameraSample::new(nx, ny).with_lens(s, t));
        let (b0, b1) = (focus_bound(cam, x, y).1, focus_bound(cam, nx, ny).1);
        let (f0, f1) = (cam.focus(x, y).point(), cam.focus(nx, ny).point());
        // Half a grid spacing each: 4 u max(|F_i| before the grid, M_i).
        let u4 = int(4) * r(S::<V>::UNIT_ROUNDOFF);
        let pre = int(1) + int(8) * r(S::<V>::UNIT_ROUNDOFF);
        let exact_step = if step == "x" {
            rv(p.right())
        } else {
            rv(-p.up())
        };
        let kr = r(cam.focal_distance()) / r(p.focal_length());
        for c in 0..3 {
            let reach = R::from_float(lens_reach(cam, c)).expect("finite");
            let big = |f: S<V>| (abs(&r(f)) * &pre).max(reach.clone());
            let grids = &u4 * (big(f0[c]) + big(f1[c]));
            let bound = &b0[c] + &b1[c] + grids + gamma::<S<V>>(2) * &kr * abs(&exact_step[c]);
            let got = r(next.dir[c]) - r(diff.ray.dir[c]) - r(dd[c]);
            assert!(
                abs(&got) <= bound,
                "{step} neighbour's direction off the differential in component {c}: {cam:?} at pixel ({i}, {j}), lens ({s:?}, {t:?})"
            );
        }
    }
}
