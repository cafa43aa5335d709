//! Cameras and raster positions: the inputs of the camera checks.
//!
//! A frame (eye, view, up, image size) in realistic ranges: the eye near
//! the origin or far away (where the origins' rounding shows), view and up
//! from [`direction`] (so up is sometimes nearly parallel
//! to the view, and a camera then refuses), images from 1 to 2048 pixels
//! each way, odd and even; raster positions on pixel centres, anywhere in
//! the image, or outside it; lens samples at the centre, on the edges and
//! corners of `[0, 1)^2`, and anywhere in it.

use rayhit::{
    Camera, CameraSample, PinholeCamera, Ray, Scalar, Triangle, Vector,
    camera::{EquirectangularCamera, OrthographicCamera, RayDifferential, ThinLensCamera},
};

use super::{S, direction, point, v};
use crate::source::Source;

/// A camera's frame: where it is, where it looks, and its image.
#[derive(Clone, Copy, Debug)]
pub struct Frame<V> {
    /// The eye (or an orthographic camera's centre).
    pub eye: V,
    /// The view direction.
    pub view: V,
    /// The up vector.
    pub up: V,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
}

/// A frame: the eye in `[-64, 64]^3`, or one time in eight `10` to `10^5`
/// away; view and up from the direction strategy; sizes 1 to 2048.
pub fn frame<V: Vector>(src: &mut Source) -> Frame<V> {
    let eye = if src.one_in(8) {
        v(super::far_offset(src).map(|x| x / 100.0))
    } else {
        point::<V>(src, 64.0)
    };
    let (view, up) = (direction::<V>(src), direction::<V>(src));
    let mut size = || 1 + src.below(256) * 8 + src.below(8);
    let (width, height) = (size(), size());
    Frame {
        eye,
        view,
        up,
        width,
        height,
    }
}

/// A raster position: a pixel centre (half the time), anywhere in the
/// image, or up to one image size outside it.
pub fn raster<F: Scalar>(src: &mut Source, width: u32, height: u32) -> (F, F) {
    let (w, h) = (f64::from(width), f64::from(height));
    let (x, y) = match src.below(4) {
        0 | 1 => (
            f64::from(src.below(width)) + 0.5,
            f64::from(src.below(height)) + 0.5,
        ),
        2 => (src.range(0.0, w), src.range(0.0, h)),
        _ => (src.range(-w, 2.0 * w), src.range(-h, 2.0 * h)),
    };
    (F::from_f64(x), F::from_f64(y))
}

/// A pixel's centre `(i + 0.5, j + 0.5)` and its indices.
pub fn pixel(src: &mut Source, width: u32, height: u32) -> (u32, u32) {
    (src.below(width), src.below(height))
}

/// A lens sample in `[0, 1)^2`: the centre, a corner or edge, or uniform.
pub fn lens_sample<F: Scalar>(src: &mut Source) -> (F, F) {
    let below_one = F::ONE.next_down();
    let edge = |src: &mut Source| match src.below(3) {
        0 => F::ZERO,
        1 => below_one,
        _ => F::from_f64(src.unit()),
    };
    match src.below(8) {
        0 => (F::HALF, F::HALF),
        1 | 2 => (edge(src), edge(src)),
        _ => (F::from_f64(src.unit()), F::from_f64(src.unit())),
    }
}

/// A lens radius (zero one time in eight, else `2^-10` to `2^3`) and a
/// focal distance (`2^-3` to `2^10`).
pub fn lens<V: Vector>(src: &mut Source) -> (S<V>, S<V>) {
    let radius = if src.one_in(8) {
        0.0
    } else {
        src.log2_range(-10.0, 3.0)
    };
    (
        S::<V>::from_f64(radius),
        S::<V>::from_f64(src.log2_range(-3.0, 10.0)),
    )
}

/// A vertical field of view, 10 to 150 degrees, in radians.
pub fn fov<F: Scalar>(src: &mut Source) -> F {
    F::from_f64(src.range(10.0, 150.0).to_radians())
}

/// A camera's ray differential at a raster position in (or near) the
/// image.
pub fn differential<V: Vector>(src: &mut Source) -> Option<RayDifferential<V>> {
    let f = frame::<V>(src);
    let (x, y) = raster::<S<V>>(src, f.width, f.height);
    let pinhole = PinholeCamera::from_fov(f.eye, f.view, f.up, fov(src), f.width, f.height);
    Some(match src.below(4) {
        0 => pinhole.ok()?.ray_differential(CameraSample::new(x, y)),
        1 => {
            let (radius, distance) = lens::<V>(src);
            let cam = ThinLensCamera::new(pinhole.ok()?, radius, distance).ok()?;
            let (s, t) = lens_sample::<S<V>>(src);
            cam.ray_differential(CameraSample::new(x, y).with_lens(s, t))
        }
        2 => {
            let size = S::<V>::from_f64(src.log2_range(-8.0, 2.0));
            OrthographicCamera::new(f.eye, f.view, f.up, size, f.width, f.height)
                .ok()?
                .ray_differential(CameraSample::new(x, y))
        }
        _ => EquirectangularCamera::new(f.eye, f.view, f.up, f.width, f.height)
            .ok()?
            .ray_differential(CameraSample::new(x, y)),
    })
}

/// A triangle whose centroid is a point of the ray `1/2` to `2^7` along
/// it, its corners `2^-4` to `2^4` away in random directions.
pub fn triangle_around<V: Vector>(src: &mut Source, ray: &Ray<V>) -> Triangle<V> {
    let f = |x: S<V>| x.to_f64();
    let t = src.log2_range(-1.0, 7.0);
    let p: [f64; 3] = core::array::from_fn(|k| f(ray.origin[k]) + t * f(ray.dir[k]));
    let size = src.log2_range(-4.0, 4.0);
    let (d1, d2) = (src.direction(), src.direction());
    let a: [f64; 3] = core::array::from_fn(|k| p[k] + size * d1[k]);
    let b: [f64; 3] = core::array::from_fn(|k| p[k] + size * d2[k]);
    let c: [f64; 3] = core::array::from_fn(|k| 3.0 * p[k] - a[k] - b[k]);
    Triangle::new(v(a), v(b), v(c))
}
