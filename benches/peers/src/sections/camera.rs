//! The sections `camera` and `camera differentials`, and the same two
//! `, by reference`: every camera's ray, and its ray with differentials,
//! over the pixel centres of a 64x64 image in scanline and shuffled order,
//! each result stored in a buffer; and the differentials' floors.

use std::hint::black_box;

use rayhit::camera::{
    ClipSpace, EqualAreaCamera, EquirectangularCamera, MatrixCamera, OrthographicCamera,
    RayDifferential, ThinLensCamera,
};
use rayhit::glam::Vec3;
use rayhit::{Camera, CameraSample, PinholeCamera, Ray};
use rayhit_testkit::rng::Pcg32;

use crate::harness::loops::over;
use crate::harness::{Kernel, kernel};

/// The cameras: every camera's ray, and its ray with differentials, over
/// the 4096 pixel centres of a 64x64 image, in scanline order (coherent:
/// neighbouring pixels one after the other, as a renderer's tiles visit
/// them) and in one fixed shuffled order (each pixel's position read from
/// a permutation: the same arithmetic, no coherence between one ray and the
/// next). The thin lens takes one lens sample per pixel, drawn once.
pub struct CameraData {
    pub pinhole: PinholeCamera,
    pub thin_lens: ThinLensCamera,
    pub ortho: OrthographicCamera,
    pub matrix: MatrixCamera,
    pub equirect: EquirectangularCamera,
    pub equal_area: EqualAreaCamera,
    /// Raster positions, scanline order and shuffled.
    pub scanline: Vec<(f32, f32)>,
    pub shuffled: Vec<(f32, f32)>,
    /// A lens sample per position.
    pub lens: Vec<(f32, f32)>,
}

impl CameraData {
    pub fn new() -> Self {
        let (w, h) = (64u32, 64u32);
        let (eye, dir, up) = (
            Vec3::new(1.0, 2.0, 5.0),
            Vec3::new(0.1, -0.3, -1.0).normalize(),
            Vec3::Y,
        );
        let fov = 60f32.to_radians();
        let pinhole = PinholeCamera::from_fov(eye, dir, up, fov, w, h).expect("a camera");
        let view = rayhit::glam::camera::rh::view::look_to_mat4(eye, dir, up);
        let proj = rayhit::glam::camera::rh::proj::directx::perspective(fov, 1.0, 0.1, 100.0);
        let scanline: Vec<(f32, f32)> = (0..h)
            .flat_map(|j| (0..w).map(move |i| (i as f32 + 0.5, j as f32 + 0.5)))
            .collect();
        let mut rng = Pcg32::with_stream(25, 3);
        let mut shuffled = scanline.clone();
        for i in (1..shuffled.len()).rev() {
            let j = rng.below(i as u32 + 1) as usize;
            shuffled.swap(i, j);
        }
        let lens = (0..scanline.len())
            .map(|_| {
                (
                    rng.below(1 << 24) as f32 / 16_777_216.0,
                    rng.below(1 << 24) as f32 / 16_777_216.0,
                )
            })
            .collect();
        Self {
            pinhole,
            thin_lens: ThinLensCamera::new(pinhole, 0.1, 5.0).expect("a lens"),
            ortho: OrthographicCamera::new(eye, dir, up, 0.05, w, h).expect("a camera"),
            matrix: MatrixCamera::from_mat4(view, proj, ClipSpace::Direct3D, w, h)
                .expect("a camera"),
            equirect: EquirectangularCamera::new(eye, dir, up, w, h).expect("a camera"),
            equal_area: EqualAreaCamera::new(eye, dir, up, w, h).expect("a camera"),
            scanline,
            shuffled,
            lens,
        }
    }
}

/// A checksum of a ray: its direction's and origin's bits.
pub fn ray_sum(r: &Ray) -> u64 {
    let b = |v: Vec3| {
        u64::from(v.x.to_bits() ^ v.y.to_bits().rotate_left(7) ^ v.z.to_bits().rotate_left(13))
    };
    b(r.dir).wrapping_add(b(r.origin))
}

/// A checksum of a ray and its differentials.
pub fn diff_sum(d: &RayDifferential) -> u64 {
    let b = |v: Vec3| {
        u64::from(v.x.to_bits() ^ v.y.to_bits().rotate_left(7) ^ v.z.to_bits().rotate_left(13))
    };
    ray_sum(&d.ray)
        .wrapping_add(b(d.dx_dir) ^ b(d.dy_dir))
        .wrapping_add(b(d.dx_origin) ^ b(d.dy_origin))
}

/// The camera rows' names, in the table and the targets.
pub const CAMERAS: [&str; 6] = [
    "PinholeCamera",
    "ThinLensCamera",
    "OrthographicCamera",
    "MatrixCamera",
    "EquirectangularCamera",
    "EqualAreaCamera",
];

/// The six cameras, by value.
#[derive(Clone, Copy)]
pub struct Cameras {
    pub pinhole: PinholeCamera,
    pub thin_lens: ThinLensCamera,
    pub ortho: OrthographicCamera,
    pub matrix: MatrixCamera,
    pub equirect: EquirectangularCamera,
    pub equal_area: EqualAreaCamera,
}

impl Cameras {
    /// The cameras of `d`, copied.
    pub fn of(d: &CameraData) -> Self {
        Self {
            pinhole: d.pinhole,
            thin_lens: d.thin_lens,
            ortho: d.ortho,
            matrix: d.matrix,
            equirect: d.equirect,
            equal_area: d.equal_area,
        }
    }
}

/// How a row's closure reaches its camera: a copy it owns ([`Owned`]), as
/// a renderer's `self.camera` belongs to the renderer, so that the compiler
/// knows the camera does not change while rays are stored and may compute
/// several rays at once; or a reference it captures ([`Borrowed`]), as a
/// renderer's `camera: &'a ThinLensCamera` field, which the compiler must
/// reload for every ray, keeping every such loop scalar.
trait Access<C>: Copy {
    fn get(&self) -> &C;
}

/// A camera the row's closure owns.
#[derive(Clone, Copy)]
struct Owned<C>(C);

/// A camera the row's closure reaches through a reference.
struct Borrowed<'a, C>(&'a C);

impl<C> Clone for Borrowed<'_, C> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<C> Copy for Borrowed<'_, C> {}

impl<C: Copy> Access<C> for Owned<C> {
    #[inline(always)]
    fn get(&self) -> &C {
        &self.0
    }
}

impl<C> Access<C> for Borrowed<'_, C> {
    #[inline(always)]
    fn get(&self) -> &C {
        self.0
    }
}

/// Raster positions and their lens samples.
pub type Positions<'a> = (&'a [(f32, f32)], &'a [(f32, f32)]);

/// One row: `f` at every position of `order` through [`over`].
fn camera_row<'a, T: Copy + Default + 'a>(
    (section, name, w): (&'static str, String, &str),
    (order, lens): Positions<'a>,
    f: impl Fn(f32, f32, (f32, f32)) -> T + 'a,
    sum: fn(&T) -> u64,
) -> Kernel<'a> {
    kernel(
        section,
        &name,
        w,
        order.len(),
        None,
        over(order, lens, f, sum),
    )
}

/// The camera sample of a position and a lens sample (cameras without a
/// lens ignore it).
#[inline(always)]
fn sample(x: f32, y: f32, (s, t): (f32, f32)) -> CameraSample {
    CameraSample::new(x, y).with_lens(s, t)
}

/// One camera's ray (section `sections.0`) and ray with differentials
/// (`sections.1`), through the [`Camera`] trait, the closures reaching the
/// camera through `c`.
fn camera_rows<'a, C: Camera + 'a>(
    c: impl Access<C> + 'a,
    name: &str,
    d: &'a CameraData,
    (rs, ds): (&'static str, &'static str),
    out: &mut Vec<Kernel<'a>>,
) {
    for (w, order) in [("scanline", &d.scanline), ("shuffled", &d.shuffled)] {
        let ol = (&order[..], &d.lens[..]);
        out.push(camera_row(
            (rs, format!("rayhit {name}::ray"), w),
            ol,
            #[inline(always)]
            move |x, y, s| c.get().ray(sample(x, y, s)),
            ray_sum,
        ));
        out.push(camera_row(
            (ds, format!("rayhit {name}::ray_differential"), w),
            ol,
            #[inline(always)]
            move |x, y, s| c.get().ray_differential(sample(x, y, s)),
            diff_sum,
        ));
    }
}

/// Every camera's rows ([`camera_rows`]), each camera owned by its
/// closures or, with `by_reference`, borrowed from `c`.
pub fn camera_kernels<'a>(
    c: &'a Cameras,
    by_reference: bool,
    d: &'a CameraData,
    sections: (&'static str, &'static str),
    out: &mut Vec<Kernel<'a>>,
) {
    let [p, t, o, m, e, a] = CAMERAS;
    macro_rules! rows {
        ($($field:ident $name:ident),*) => {$(
            if by_reference {
                camera_rows(Borrowed(&c.$field), $name, d, sections, out);
            } else {
                camera_rows(Owned(c.$field), $name, d, sections, out);
            }
        )*};
    }
    rows!(pinhole p, thin_lens t, ortho o, matrix m, equirect e, equal_area a);
}

/// The differentials' floor of one camera: its ray alone, stored as a ray
/// with differentials whose four derivatives are zero (see
/// [`differential_floor_kernels`]).
fn zero_differential_rows<'a, C: Camera + Copy + 'a>(
    c: C,
    name: &str,
    d: &'a CameraData,
    out: &mut Vec<Kernel<'a>>,
) {
    // (A zero the compiler cannot see through: the constant `Vec3::ZERO`,
    // or one written with literals, is stored by a call to `memset`, which
    // keeps the loop scalar. The crate's cameras, generic over the vector
    // type, build theirs from three zeros after the fact, which the
    // compiler stores as floats.)
    let z: f32 = black_box(0.0);
    for (w, order) in [("scanline", &d.scanline), ("shuffled", &d.shuffled)] {
        out.push(camera_row(
            (
                "camera differentials",
                format!("floor: {name}::ray with zero differentials"),
                w,
            ),
            (&order[..], &d.lens[..]),
            #[inline(always)]
            move |x, y, s| RayDifferential {
                ray: c.ray(sample(x, y, s)),
                dx_origin: Vec3::new(z, z, z),
                dx_dir: Vec3::new(z, z, z),
                dy_origin: Vec3::new(z, z, z),
                dy_dir: Vec3::new(z, z, z),
            },
            diff_sum,
        ));
    }
}

/// The differentials' floors: each camera's ray alone, stored as a ray
/// with differentials whose four derivatives are zero. No ray with
/// differentials can cost less than computing its ray and writing its 72
/// bytes, so these rows bound from below what any camera's
/// `ray_differential` costs in this loop.
pub fn differential_floor_kernels<'a>(c: Cameras, d: &'a CameraData, out: &mut Vec<Kernel<'a>>) {
    // (A zero the compiler cannot see through: see `zero_differential_rows`.)
    let z: f32 = black_box(0.0);
    // The pinhole camera's ray with differentials written directly with
    // glam: the film direction, its length's reciprocal (no rescaling of a
    // squared length that over- or underflows), and the two derivatives
    // as the crate forms them.
    let pin = &c.pinhole;
    let (eye, fwd, right, up) = (
        pin.eye(),
        pin.forward() * pin.focal_length(),
        pin.right(),
        pin.up(),
    );
    let (hw, hh) = (pin.width() as f32 * 0.5, pin.height() as f32 * 0.5);
    let pinhole_floor = move |x: f32, y: f32| {
        let (dx, dy) = (x - hw, hh - y);
        let p = fwd + right * dx + up * dy;
        let inv = 1.0 / p.dot(p).sqrt();
        let dir = p * inv;
        RayDifferential {
            ray: Ray::new(Vec3::new(eye.x, eye.y, eye.z), dir),
            dx_origin: Vec3::new(z, z, z),
            dx_dir: (right - dir * (dx * inv)) * inv,
            dy_origin: Vec3::new(z, z, z),
            dy_dir: (dir * (dy * inv) - up) * inv,
        }
    };
    for (w, order) in [("scanline", &d.scanline), ("shuffled", &d.shuffled)] {
        let ol = (&order[..], &d.lens[..]);
        out.push(camera_row(
            (
                "camera differentials",
                "floor: pinhole ray with differentials (glam, no rescaling)".to_string(),
                w,
            ),
            ol,
            #[inline(always)]
            move |x, y, _| pinhole_floor(x, y),
            diff_sum,
        ));
    }
    let [p, t, o, m, e, a] = CAMERAS;
    zero_differential_rows(c.pinhole, p, d, out);
    zero_differential_rows(c.thin_lens, t, d, out);
    zero_differential_rows(c.ortho, o, d, out);
    zero_differential_rows(c.matrix, m, d, out);
    zero_differential_rows(c.equirect, e, d, out);
    zero_differential_rows(c.equal_area, a, d, out);
}
