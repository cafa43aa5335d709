//! The textbook and floor rows of the section `camera`: the thin lens and
//! both panoramas as they are usually written, and the least arithmetic
//! each needs (`floors::camera`), with how often their rays agree with
//! rayhit's.

use rayhit::glam::Vec3;
use rayhit::{Camera, CameraSample, PinholeCamera, Ray};

use super::camera::{CameraData, Positions, ray_sum};
use crate::floors::camera as camera_refs;
use crate::harness::loops::over;
use crate::harness::{Kernel, kernel};

/// The share of the scanline positions where `reference` gives rayhit's
/// ray: directions within `1e-5` radians of each other (a few ulps of
/// `f32` trigonometry apart, far less than a pixel), origins within `1e-5`
/// of the scene's scale apart.
fn camera_agreement(
    d: &CameraData,
    rayhit: impl Fn(f32, f32, (f32, f32)) -> Ray,
    reference: impl Fn(f32, f32, (f32, f32)) -> (Vec3, Vec3),
) -> f64 {
    let same = d
        .scanline
        .iter()
        .zip(&d.lens)
        .filter(|&(&(x, y), &l)| {
            let ray = rayhit(x, y, l);
            let (o, dir) = reference(x, y, l);
            // The sine of the angle, from the cross product (the arc
            // cosine of a dot product near 1 is too coarse in f32).
            let (p, q) = (ray.dir.normalize(), dir.normalize());
            p.cross(q).length() <= 1e-5
                && p.dot(q) > 0.0
                && (ray.origin - o).length() <= 1e-5 * (1.0 + o.length())
        })
        .count();
    same as f64 / d.scanline.len() as f64
}

/// The loop of [`camera_refs::thin_lens_guarantee_floor`], with or
/// without the lens-centre ray (`CENTRE`, a constant, as the crate's
/// camera has no such switch).
fn guarantee_floor_loop<'a, const CENTRE: bool>(
    order: &'a [(f32, f32)],
    lens: &'a [(f32, f32)],
    (pin, frame, radius, focus, bound): (PinholeCamera, camera_refs::Frame, f32, f32, Vec3),
) -> impl Fn() -> u64 + 'a {
    over(
        order,
        lens,
        #[inline(always)]
        move |x, y, l| {
            let (o, dir) = camera_refs::thin_lens_guarantee_floor(
                &pin,
                (&frame, radius, focus, bound),
                CENTRE,
                (x, y),
                l,
            );
            Ray::new(Vec3::new(o.x, o.y, o.z), dir)
        },
        ray_sum,
    )
}

/// A row of the section `camera` whose rays start at `eye` and go along
/// `dir(x, y)`. (The eye as three floats: a vector captured whole and
/// stored into every ray keeps the loop scalar.)
fn eye_row<'a>(
    (name, w): (&str, &str),
    (order, lens): Positions<'a>,
    agree: f64,
    [ex, ey, ez]: [f32; 3],
    dir: impl Fn(f32, f32) -> Vec3 + 'a,
) -> Kernel<'a> {
    kernel(
        "camera",
        name,
        w,
        order.len(),
        Some(agree),
        over(
            order,
            lens,
            #[inline(always)]
            move |x, y, _| Ray::new(Vec3::new(ex, ey, ez), dir(x, y)),
            ray_sum,
        ),
    )
}

pub fn camera_reference_kernels<'a>(d: &'a CameraData, out: &mut Vec<Kernel<'a>>) {
    use camera_refs::*;
    let p = &d.pinhole;
    let frame = Frame {
        eye: p.eye(),
        forward: p.forward(),
        right: p.right(),
        up: p.up(),
        focal: p.focal_length(),
        w: p.width() as f32,
        h: p.height() as f32,
    };
    let pano = |r: Vec3, u: Vec3, f: Vec3| Frame {
        right: r,
        up: u,
        forward: f,
        ..frame
    };
    let equi = pano(d.equirect.right(), d.equirect.up(), d.equirect.forward());
    let area = pano(
        d.equal_area.right(),
        d.equal_area.up(),
        d.equal_area.forward(),
    );
    let (radius, focus) = (d.thin_lens.lens_radius(), d.thin_lens.focal_distance());
    // (The origin rebuilt from its components, as the crate's cameras do,
    // so that the loops can vectorise.)
    let as_ray = |(o, dir): (Vec3, Vec3)| Ray::new(Vec3::new(o.x, o.y, o.z), dir);
    let thin =
        move |x, y, l: (f32, f32)| d.thin_lens.ray(CameraSample::new(x, y).with_lens(l.0, l.1));
    let eye = frame.eye.to_array();
    let pin = d.pinhole;
    // A bound on the lens points' coordinates, as the camera's own.
    let bound = (frame.eye.abs() + (frame.right.abs() + frame.up.abs()) * radius) * (1.0 + 1e-5);
    let agree = [
        camera_agreement(d, thin, |x, y, l| {
            thin_lens_textbook(&frame, radius, focus, x, y, l.0, l.1)
        }),
        camera_agreement(d, thin, |x, y, l| {
            thin_lens_floor(&frame, radius, focus, x, y, l.0, l.1)
        }),
        camera_agreement(d, thin, |x, y, l| {
            thin_lens_guarantee_floor(&pin, (&frame, radius, focus, bound), false, (x, y), l)
        }),
        camera_agreement(d, thin, |x, y, l| {
            thin_lens_guarantee_floor(&pin, (&frame, radius, focus, bound), true, (x, y), l)
        }),
        camera_agreement(
            d,
            |x, y, _| d.equirect.ray(CameraSample::new(x, y)),
            |x, y, _| equirect_textbook(&equi, x, y),
        ),
        camera_agreement(
            d,
            |x, y, _| d.equal_area.ray(CameraSample::new(x, y)),
            |x, y, _| equal_area_textbook(&area, x, y),
        ),
        camera_agreement(
            d,
            |x, y, _| d.equirect.ray(CameraSample::new(x, y)),
            |x, y, _| (frame.eye, equirect_floor(&equi, x, y)),
        ),
        // (The front half only: the diamond, half the image.)
        camera_agreement(
            d,
            |x, y, _| d.equal_area.ray(CameraSample::new(x, y)),
            |x, y, _| (frame.eye, equal_area_floor(&area, x, y)),
        ),
    ];
    for (w, order) in [("scanline", &d.scanline), ("shuffled", &d.shuffled)] {
        let (n, lens) = (order.len(), &d.lens);
        let floor = (pin, frame, radius, focus, bound);
        out.extend([
            kernel(
                "camera",
                "floor thin lens + grid",
                w,
                n,
                Some(agree[2]),
                guarantee_floor_loop::<false>(order, lens, floor),
            ),
            kernel(
                "camera",
                "floor thin lens + grid + lens-centre ray",
                w,
                n,
                Some(agree[3]),
                guarantee_floor_loop::<true>(order, lens, floor),
            ),
        ]);
        out.extend([
            kernel(
                "camera",
                "textbook thin lens (pbrt-v4, std sin/cos)",
                w,
                n,
                Some(agree[0]),
                over(
                    order,
                    lens,
                    #[inline(always)]
                    move |x, y, l| {
                        as_ray(thin_lens_textbook(&frame, radius, focus, x, y, l.0, l.1))
                    },
                    ray_sum,
                ),
            ),
            kernel(
                "camera",
                "floor thin lens",
                w,
                n,
                Some(agree[1]),
                over(
                    order,
                    lens,
                    #[inline(always)]
                    move |x, y, l| as_ray(thin_lens_floor(&frame, radius, focus, x, y, l.0, l.1)),
                    ray_sum,
                ),
            ),
            kernel(
                "camera",
                "textbook equirectangular (pbrt-v4, std sin/cos)",
                w,
                n,
                Some(agree[4]),
                over(
                    order,
                    lens,
                    #[inline(always)]
                    move |x, y, _| as_ray(equirect_textbook(&equi, x, y)),
                    ray_sum,
                ),
            ),
            eye_row(
                ("floor equirectangular", w),
                (order, lens),
                agree[6],
                eye,
                #[inline(always)]
                move |x, y| equirect_floor(&equi, x, y),
            ),
            eye_row(
                ("floor equal area (front half)", w),
                (order, lens),
                agree[7],
                eye,
                #[inline(always)]
                move |x, y| equal_area_floor(&area, x, y),
            ),
            kernel(
                "camera",
                "textbook equal area (pbrt-v4, std sin/cos)",
                w,
                n,
                Some(agree[5]),
                over(
                    order,
                    lens,
                    #[inline(always)]
                    move |x, y, _| as_ray(equal_area_textbook(&area, x, y)),
                    ray_sum,
                ),
            ),
        ]);
    }
}
