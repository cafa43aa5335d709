//! `orthographic`: [`OrthographicCamera`]: its construction, rays and
//! differentials.
//!
//! Input: raw mode, the centre, view and up as raw-bit vectors, the pixel
//! size, width and height, and a raster position; structured mode, a frame
//! from [`cases::cameras`](crate::cases::cameras), a pixel size of `2^-10` to `2^4` and three
//! raster positions.
//!
//! Checks, any input: no panic; a camera only from valid input, each error
//! naming an input bad that way; every ray's direction is `forward`, bit
//! for bit, whatever the position; the differential's ray is the ray, its
//! origin offsets `pixel_size right` and `-pixel_size true_up` bit for bit
//! and its direction offsets zero; a finite position whose offsets do not
//! overflow gives a finite origin. Structured inputs also: `forward` has
//! unit length within `2 gamma(6) + gamma(6)^2` (squared); each origin is
//! within `gamma(4) (|centre_i| + |dx s right_i| + |dy s up_i|)` of the
//! exact point of the plane (`s` the pixel size); and the origins of
//! neighbouring pixels differ by the differential within the two origins'
//! bounds and its own rounding.

use arbitrary::Arbitrary;
use rayhit::{
    Camera, CameraSample, Scalar, Vector,
    camera::{CameraError, OrthographicCamera},
};

use super::exact::{R, abs, dot, gamma, int, r, rv};
use super::{Check, Input, S, raw, raw_vec};
use crate::bits::vector_bits;
use crate::cases::cameras::{frame, raster};

/// The `orthographic` target.
#[derive(Debug)]
pub struct Orthographic;

impl Check for Orthographic {
    fn run<'a, V>(input: &mut Input<'a>)
    where
        V: Vector,
        S<V>: Arbitrary<'a> + Scalar,
    {
        match input {
            Input::Raw(u) => {
                let (centre, view, up) = (raw_vec::<V>(u), raw_vec::<V>(u), raw_vec::<V>(u));
                let size = raw::<S<V>>(u);
                let (w, h) = (raw::<u32>(u), raw::<u32>(u));
                let (x, y) = (raw::<S<V>>(u), raw::<S<V>>(u));
                let cam = OrthographicCamera::new(centre, view, up, size, w, h);
                if let Err(e) = cam {
                    check_error(e, centre, view, up, size, w, h);
                    return;
                }
                let cam = cam.expect("checked");
                check_ray(&cam, x, y, false);
            }
            Input::Structured(src) => {
                let f = frame::<V>(src);
                let size = S::<V>::from_f64(src.log2_range(-10.0, 4.0));
                let Ok(cam) = OrthographicCamera::new(f.eye, f.view, f.up, size, f.width, f.height)
                else {
                    return;
                };
                let fw = rv(cam.forward());
                let len2 = dot(&fw, &fw);
                let g = gamma::<S<V>>(6);
                assert!(abs(&(len2 - int(1))) <= int(2) * &g + &g * &g, "{cam:?}");
                for _ in 0..3 {
                    let (x, y) = raster::<S<V>>(src, f.width, f.height);
                    check_ray(&cam, x, y, true);
                }
            }
        }
    }
}

fn check_error<V: Vector>(e: CameraError, centre: V, view: V, up: V, size: S<V>, w: u32, h: u32) {
    let ok = match e {
        CameraError::NonFiniteEye => !centre.is_finite(),
        CameraError::InvalidViewDir => !view.is_finite() || view == V::ZERO,
        CameraError::InvalidUp => !up.is_finite() || up == V::ZERO,
        CameraError::UpParallelToView => true,
        CameraError::InvalidPixelSize => !(size > S::<V>::ZERO && size.is_finite()),
        CameraError::EmptyImage => w == 0 || h == 0,
        _ => false,
    };
    assert!(
        ok,
        "{e:?} for centre {centre:?}, view {view:?}, up {up:?}, pixel size {size:?}, {w}x{h}"
    );
}

/// The exact origin of `(x, y)` for the camera's basis and the computed
/// offsets, and the crate's bound on its distance, `origin_error`, which
/// is checked to be at least the derivation's.
fn origin_bound<V: Vector>(cam: &OrthographicCamera<V>, x: S<V>, y: S<V>) -> ([R; 3], [R; 3]) {
    let half = S::<V>::HALF;
    let dx = x - S::<V>::from_u32(cam.width()) * half;
    let dy = S::<V>::from_u32(cam.height()) * half - y;
    let (c, rt, up) = (rv(cam.centre()), rv(cam.right()), rv(cam.up()));
    let s = r(cam.pixel_size());
    let (a, b) = (r(dx) * &s, r(dy) * &s);
    let exact = core::array::from_fn(|i| &c[i] + &a * &rt[i] + &b * &up[i]);
    let derived: [R; 3] = core::array::from_fn(|i| {
        gamma::<S<V>>(4) * (abs(&c[i]) + abs(&(&a * &rt[i])) + abs(&(&b * &up[i])))
    });
    let bound = rv(cam.origin_error(x, y));
    for i in 0..3 {
        assert!(
            derived[i] <= bound[i],
            "origin_error below its derivation in component {i}: {cam:?} at ({x:?}, {y:?})"
        );
    }
    (exact, bound)
}

fn check_ray<V: Vector>(cam: &OrthographicCamera<V>, x: S<V>, y: S<V>, bounded: bool) {
    let ctx = || format!("{cam:?} at ({x:?}, {y:?})");
    let ray = cam.ray(CameraSample::new(x, y));
    assert_eq!(
        vector_bits(ray.dir),
        vector_bits(cam.forward()),
        "not parallel: {}",
        ctx()
    );
    let diff = cam.ray_differential(CameraSample::new(x, y));
    assert!(
        vector_bits(diff.ray.origin) == vector_bits(ray.origin)
            && vector_bits(diff.ray.dir) == vector_bits(ray.dir),
        "{}",
        ctx()
    );
    let s = cam.pixel_size();
    assert_eq!(vector_bits(diff.dx_origin), vector_bits(cam.right() * s));
    assert_eq!(vector_bits(diff.dy_origin), vector_bits(-(cam.up() * s)));
    assert_eq!(vector_bits(diff.dx_dir), vector_bits(V::ZERO));
    assert_eq!(vector_bits(diff.dy_dir), vector_bits(V::ZERO));
    if !(x.is_finite() && y.is_finite()) {
        return;
    }
    // Finite wherever the offsets and their sum with the centre are.
    let half = S::<V>::HALF;
    let dx = (x - S::<V>::from_u32(cam.width()) * half).to_f64() * s.to_f64();
    let dy = (S::<V>::from_u32(cam.height()) * half - y).to_f64() * s.to_f64();
    let reach = (0..3)
        .map(|i| cam.centre()[i].to_f64().abs() + dx.abs() + dy.abs())
        .fold(0.0, f64::max);
    if reach < S::<V>::MAX.to_f64() / 4.0 {
        assert!(ray.origin.is_finite(), "non-finite origin: {}", ctx());
    }
    if !bounded {
        return;
    }
    let (exact, bound) = origin_bound(cam, x, y);
    let got = rv(ray.origin);
    for i in 0..3 {
        assert!(
            abs(&(&got[i] - &exact[i])) <= bound[i],
            "origin off the plane's point in component {i}: {}",
            ctx()
        );
    }
    // Neighbours: o(x + 1) - o(x) - dx_origin, with dx_origin within
    // gamma(1) s |right_i| of s right_i.
    for (nx, ny, d, e) in [
        (x + S::<V>::ONE, y, diff.dx_origin, rv(cam.right())),
        (x, y + S::<V>::ONE, diff.dy_origin, rv(-cam.up())),
    ] {
        let (exact1, b1) = origin_bound(cam, nx, ny);
        let next = rv(cam.ray(CameraSample::new(nx, ny)).origin);
        let (dv, sr) = (rv(d), r(s));
        // The exact origins are a pixel apart where the computed offsets
        // are (always on the half-pixel grid).
        if (0..3).any(|i| &exact1[i] - &exact[i] != &sr * &e[i]) {
            continue;
        }
        for i in 0..3 {
            let moved = &next[i] - &got[i] - &dv[i];
            let own = gamma::<S<V>>(1) * &sr * abs(&e[i]);
            assert!(
                abs(&moved) <= &bound[i] + &b1[i] + own,
                "neighbour's origin off the differential in component {i}: {}",
                ctx()
            );
        }
    }
}
