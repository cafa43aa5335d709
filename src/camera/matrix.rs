//! The camera of a rasterizer's view and projection matrices.

use glam::{DMat4, DVec3, Mat4, Vec3};

use super::{
    Camera, CameraError, CameraSample, RayCone, RayDifferential, bound_from_f64, by_components,
    centred, dvec, linear_differential_error, zero_vector,
};
use crate::num::trig::atan2_turns;
use crate::num::{S, Scalar, Vector, unit, unit_and_inverse_length};
use crate::ray::Ray;

/// A 4x4 matrix as glam stores it: four columns of four components
/// (`Mat4::to_cols_array_2d`), acting on column vectors.
type Columns<F> = [[F; 4]; 4];

/// `projection * view` by rows in `f64`, and its magnitudes ([`product`]).
type Product = ([[f64; 4]; 4], [[f64; 4]; 4]);

/// The graphics API's clip-space convention, which the matrices alone do
/// not tell: which way normalised device `y` points, and where depth
/// starts (used only for an orthographic projection's ray origins).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ClipSpace {
    /// `y` up, depth in `[0, 1]`: Direct3D, Metal, WebGPU (wgpu); glam's
    /// `camera::{rh, lh}::proj::directx` matrices.
    Direct3D,
    /// `y` up, depth in `[-1, 1]`: OpenGL, WebGL; glam's `opengl` matrices.
    OpenGl,
    /// `y` down, depth in `[0, 1]`: Vulkan; glam's `vulkan` matrices.
    Vulkan,
}

impl ClipSpace {
    /// The near end of the depth range: `-1` for OpenGL, else `0`.
    fn near_depth(self) -> f64 {
        match self {
            Self::OpenGl => -1.0,
            Self::Direct3D | Self::Vulkan => 0.0,
        }
    }
}

/// How the rays of a [`MatrixCamera`] are made.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Projection {
    /// Every ray starts at the eye: `dir = normalize(c + dx a + dy b)`.
    Perspective,
    /// Every ray has the direction `dir`: `origin = c + dx a + dy b`.
    Orthographic,
}

/// The camera a rasterizer's view and projection matrices describe: the
/// ray through a pixel is the set of points that project to it, so a
/// hybrid renderer's traced rays match its rasterized pixels.
///
/// Built from any view matrix and any perspective or orthographic
/// projection matrix (glam's `camera::{rh, lh}::view` and
/// `camera::{rh, lh}::proj::{directx, opengl, vulkan}` functions,
/// `perspective`, `perspective_infinite`, `perspective_infinite_reverse`,
/// `orthographic`, `frustum`, jittered or off-centre ones), right- or
/// left-handed, with the [`ClipSpace`] they were made for. Raster
/// conventions as [`PinholeCamera`](crate::PinholeCamera): `(0, 0)` at the
/// top-left, `y` down, pixel `(i, j)` centred at `(i + 0.5, j + 0.5)`;
/// raster `(x, y)` is normalised device coordinates `(2x/width - 1, 1 -
/// 2y/height)` (`y` the other way for Vulkan).
///
/// **The rays.** With `m_i` the `xyz` part of row `i` of `M = projection *
/// view` and `d_i` its fourth entry, the points of NDC `(nx, ny)` lie on
/// the planes `(m_0 - nx m_3) . X + d_0 - nx d_3 = 0` and `(m_1 - ny m_3) .
/// X + d_1 - ny d_3 = 0`, and the ray is their line (the projection's depth
/// row plays no part). For a perspective projection (`m_3` not zero),
/// every ray starts at the camera centre, where `m_0`, `m_1` and `m_3`'s
/// planes meet, and has the direction of the planes' normals' cross
/// product, `m_0 x m_1 + nx (m_1 x m_3) + ny (m_3 x m_0)`, turned so that
/// the clip `w` grows along it (the visible side), normalised. For an
/// orthographic projection (`m_3` zero), every ray has the direction
/// `normalize(m_0 x m_1)`, turned so that depth grows along it, and starts
/// on the near plane of the [`ClipSpace`] (depth `0`, or `-1` for OpenGL;
/// near to far for glam's orthographic matrices). Both are linear in the
/// raster position: the camera keeps `c`, `a` and `b` (computed once, in
/// `f64`, and rounded) and makes each ray as a pinhole camera does.
///
/// **Reprojection.** The ray through raster position `(x, y)` projects
/// back to it: for a perspective projection its direction's vanishing
/// point, `(m_0 . dir / m_3 . dir, m_1 . dir / m_3 . dir)` in exact
/// arithmetic on the matrices given, is `(nx, ny)` within
///
/// `sum_k |n_k| e K_k / (|D| - sum_k |m_3k| e K_k)`
///
/// in NDC (times `width / 2` or `height / 2` for pixels), where `n = m_0 -
/// nx m_3` (or `m_1 - ny m_3` for `ny`), `D = m_0 . (m_1 x m_3)`, `e =
/// gamma(5) + gamma_64(17)` (`gamma_64` in `f64`'s unit roundoff; for an
/// `f64` camera the two are the same) and `K_k` the `k`-th component of
/// `|m_0| x |m_1| + |nx| |m_1| x |m_3| + |ny| |m_3| x |m_0|`, the cross
/// products' magnitudes, with `|m_i|` the rows of `|projection| *
/// |view|` (absolute values taken entry by entry). For a well-conditioned
/// camera (glam's perspective and a view whose up vector is well away from
/// the view direction) that is a few tens of `u` times the image size in
/// pixels: a few thousandths of a pixel for a 4K image in `f32`
/// ([`raster_error`](Self::raster_error) evaluates it). The eye is the
/// camera centre within a bound of the same kind
/// ([`eye_error`](Self::eye_error)); an orthographic ray's origin projects
/// to `(nx, ny)` within its own (Cramer's rule's magnitudes times `e (1 +
/// kappa)`, `kappa` the determinant's growth factor;
/// [`raster_error`](Self::raster_error) too), and its direction keeps it
/// there to the vanishing-point form with `m_2` in place of `m_3`, per
/// unit of depth. Each is held to in exact arithmetic by the test kit's
/// matrix camera checks.
///
/// ```
/// use rayhit::{Camera, PinholeCamera, camera::{ClipSpace, MatrixCamera}, glam::{Mat4, Vec3}};
/// use rayhit::glam::camera::rh::{proj::directx, view};
/// let (eye, dir) = (Vec3::new(1.0, 2.0, 5.0), Vec3::new(0.0, -0.3, -1.0).normalize());
/// let view = view::look_to_mat4(eye, dir, Vec3::Y);
/// let proj = directx::perspective(1.0, 640.0 / 480.0, 0.1, 100.0);
/// let cam = MatrixCamera::from_mat4(view, proj, ClipSpace::Direct3D, 640, 480).unwrap();
/// // The same rays as the pinhole camera of the same eye, view and field of view.
/// let pinhole = PinholeCamera::from_fov(eye, dir, Vec3::Y, 1.0, 640, 480).unwrap();
/// let (a, b) = (cam.pixel_ray(10, 400), pinhole.pixel_ray(10, 400));
/// assert!((a.origin - b.origin).length() < 1e-5 && (a.dir - b.dir).length() < 1e-5);
/// // The pixel's centre projects back to it.
/// let p = (proj * view).project_point3(a.at(50.0));
/// assert!((p.x - (2.0 * 10.5 / 640.0 - 1.0)).abs() < 1e-5);
/// assert!((p.y - (1.0 - 2.0 * 400.5 / 480.0)).abs() < 1e-5);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MatrixCamera<V = Vec3>
where
    V: Vector,
{
    projection: Projection,
    /// Perspective: the eye. Orthographic: the direction.
    fixed: V,
    c: V,
    a: V,
    b: V,
    width: u32,
    height: u32,
    clip: ClipSpace,
    // (The matrices are not kept: the bounds take them again. Holding
    // them, 128 more bytes, kept the benchmarks' loop of rays from
    // vectorising, a large loss in `benches/peers`' camera rows.)
}

/// `M = projection * view` by rows, in `f64` (exact products for `f32`
/// input; for `f64`, each product rounded), and its magnitudes `|projection|
/// * |view|` entry by entry, rounded up: each row of `M` is within
/// `gamma_64(5)` of the same row of the magnitudes of the exact product.
fn product<F: Scalar>(view: &Columns<F>, proj: &Columns<F>) -> Product {
    let at = |m: &Columns<F>, i: usize, j: usize| m[j][i].to_f64();
    let mut rows = [[0.0f64; 4]; 4];
    let mut mags = [[0.0f64; 4]; 4];
    for i in 0..4 {
        for j in 0..4 {
            rows[i][j] = (0..4).map(|k| at(proj, i, k) * at(view, k, j)).sum();
            let mag: f64 = (0..4)
                .map(|k| (at(proj, i, k) * at(view, k, j)).abs())
                .sum();
            mags[i][j] = mag * (1.0 + gamma64(6));
        }
    }
    (rows, mags)
}

/// `gamma(n)` in `f64`.
fn gamma64(n: u32) -> f64 {
    f64::gamma_n(n)
}

/// The cross product's magnitudes: `(a x b)_k` with every product taken in
/// absolute value and added (for non-negative `a`, `b`), rounded up.
fn cross_mag(a: DVec3, b: DVec3) -> DVec3 {
    DVec3::new(
        a.y * b.z + a.z * b.y,
        a.z * b.x + a.x * b.z,
        a.x * b.y + a.y * b.x,
    ) * (1.0 + gamma64(3))
}

/// `(x, y, z)` of a row.
fn xyz(r: [f64; 4]) -> DVec3 {
    DVec3::new(r[0], r[1], r[2])
}

impl<V: Vector> MatrixCamera<V> {
    /// The camera of the view matrix `view` and the projection matrix
    /// `projection` (each as four columns, glam's `to_cols_array_2d`), for
    /// the clip space `clip` and an image of `width x height` pixels.
    ///
    /// # Errors
    ///
    /// [`CameraError::NonFiniteMatrix`] for a NaN or infinite entry;
    /// [`CameraError::SingularMatrix`] when the matrices do not define a
    /// camera: the determinant of rows 0, 1 and 3 of `projection * view`
    /// (perspective) or 0, 1 and 2 (orthographic, row 3 being `(0, 0, 0,
    /// w)`, `w` not zero) is zero within its rounding (`gamma(16)` of the
    /// product of the rows' lengths, in the matrices' precision), or the
    /// eye, origin or directions overflow; [`CameraError::EmptyImage`] for
    /// a zero width or height.
    pub fn new(
        view: Columns<S<V>>,
        projection: Columns<S<V>>,
        clip: ClipSpace,
        width: u32,
        height: u32,
    ) -> Result<Self, CameraError> {
        let finite = |m: &Columns<S<V>>| m.iter().flatten().all(|x| x.is_finite());
        if !finite(&view) || !finite(&projection) {
            return Err(CameraError::NonFiniteMatrix);
        }
        if width == 0 || height == 0 {
            return Err(CameraError::EmptyImage);
        }
        // M = projection * view, in f64 (exact products for f32 input),
        // by rows: M[i][j] = sum_k P[i][k] V[k][j], with A[i][j] the
        // entry of row i, column j (= cols[j][i]).
        let (rows, _) = product(&view, &projection);
        if !rows.iter().flatten().all(|x| x.is_finite()) {
            return Err(CameraError::NonFiniteMatrix);
        }
        let (m0, m1, m2, m3) = (xyz(rows[0]), xyz(rows[1]), xyz(rows[2]), xyz(rows[3]));
        let (d0, d1, d2, d3) = (rows[0][3], rows[1][3], rows[2][3], rows[3][3]);
        let (kx, ky) = (2.0 / f64::from(width), 2.0 / f64::from(height));
        let ky = if clip == ClipSpace::Vulkan { -ky } else { ky };
        // "Zero within rounding": a determinant below gamma(16) of the
        // product of the rows' lengths (Hadamard's bound on it) in the
        // matrices' own precision, where rounding the entries alone can
        // move it by gamma(1) of that times a few.
        let tiny = |r: [DVec3; 3]| {
            let det = r[0].dot(r[1].cross(r[2]));
            let scale = r[0].length() * r[1].length() * r[2].length();
            (det, !(det.abs() > S::<V>::gamma_n(16).to_f64() * scale))
        };
        let (projection_kind, fixed, c, a, b) = if m3 != DVec3::ZERO {
            let (det, singular) = tiny([m0, m1, m3]);
            if singular {
                return Err(CameraError::SingularMatrix);
            }
            let (x, y, z) = (m1.cross(m3), m3.cross(m0), m0.cross(m1));
            let eye = -(x * d0 + y * d1 + z * d3) / det;
            // Turned so that clip w grows along the ray: m3 . dir = det.
            let s = det.signum();
            (
                Projection::Perspective,
                eye,
                z * s,
                x * (kx * s),
                y * (ky * s),
            )
        } else {
            if d3 == 0.0 {
                return Err(CameraError::SingularMatrix);
            }
            let (det, singular) = tiny([m0, m1, m2]);
            if singular {
                return Err(CameraError::SingularMatrix);
            }
            let (x, y, z) = (m1.cross(m2), m2.cross(m0), m0.cross(m1));
            // The point with m0.X + d0 = nx d3, m1.X + d1 = ny d3 and
            // m2.X + d2 = z0 d3 (depth z0 at the near plane), by Cramer.
            let z0 = clip.near_depth();
            let origin = (x * -d0 + y * -d1 + z * (z0 * d3 - d2)) / det;
            // Depth (m2.X + d2) / d3 grows along m0 x m1 times det d3's sign.
            let s = (det * d3).signum();
            let dir = (z * s).normalize();
            (
                Projection::Orthographic,
                dir,
                origin,
                x * (kx * d3 / det),
                y * (ky * d3 / det),
            )
        };
        let to_v = |p: DVec3| {
            V::new(
                S::<V>::from_f64(p.x),
                S::<V>::from_f64(p.y),
                S::<V>::from_f64(p.z),
            )
        };
        let (fixed, c, a, b) = (to_v(fixed), to_v(c), to_v(a), to_v(b));
        if !(fixed.is_finite() && c.is_finite() && a.is_finite() && b.is_finite()) {
            return Err(CameraError::SingularMatrix);
        }
        Ok(Self {
            projection: projection_kind,
            fixed,
            c,
            a,
            b,
            width,
            height,
            clip,
        })
    }

    /// The camera of one matrix `view_projection = projection * view`:
    /// the same as [`new`](Self::new) with the identity as the view.
    ///
    /// # Errors
    ///
    /// As [`new`](Self::new).
    pub fn from_view_projection(
        view_projection: Columns<S<V>>,
        clip: ClipSpace,
        width: u32,
        height: u32,
    ) -> Result<Self, CameraError> {
        let (zero, one) = (S::<V>::ZERO, S::<V>::ONE);
        let identity = [
            [one, zero, zero, zero],
            [zero, one, zero, zero],
            [zero, zero, one, zero],
            [zero, zero, zero, one],
        ];
        Self::new(identity, view_projection, clip, width, height)
    }

    /// `c + dx a + dy b`.
    #[inline(always)]
    fn linear(&self, x: S<V>, y: S<V>) -> V {
        let (dx, dy) = centred(x, y, self.width, self.height);
        self.c + self.a * dx + self.b * dy
    }

    /// The ray's linear form `[c, a, b]`: the direction (perspective,
    /// before normalising) or the origin (orthographic) of raster position
    /// `(x, y)` is `c + (x - width/2) a + (height/2 - y) b`, evaluated in
    /// that order, three roundings per component.
    #[inline]
    #[must_use]
    pub fn linear_form(&self) -> [V; 3] {
        [self.c, self.a, self.b]
    }

    /// The eye (perspective: where every ray starts) or the direction of
    /// every ray (orthographic).
    #[inline]
    #[must_use]
    pub fn fixed(&self) -> V {
        self.fixed
    }

    /// True for an orthographic projection (parallel rays).
    #[inline]
    #[must_use]
    pub fn is_orthographic(&self) -> bool {
        self.projection == Projection::Orthographic
    }

    /// A per-component bound on the distance of the eye (where every ray
    /// of a perspective camera starts, [`fixed`](Self::fixed)) from the
    /// exact camera centre of the matrices given, the point `e*` that
    /// every row of `M = projection * view` but the depth row maps to
    /// zero: `e* = -(d0 X + d1 Y + d3 Z) / D`, exactly (`X = m1 x m3`, `Y =
    /// m3 x m0`, `Z = m0 x m1`, `D = m0 . X`, `m_i` and `d_i` the rows'
    /// first three entries and the last). `view` and `projection` are
    /// the matrices the camera was made from, as columns (for
    /// [`from_view_projection`](Self::from_view_projection), the identity
    /// and the product; for [`from_mat4`](Self::from_mat4), each
    /// `to_cols_array_2d()`); the camera does not keep them. Infinite for
    /// other matrices (the camera is rebuilt from them and compared), for
    /// an orthographic camera, and where the matrices are too
    /// ill-conditioned for the bound (below).
    ///
    /// `(gamma_64(14) N_k / |D| + delta |eye_k|) / (1 - 2 delta) +
    /// (gamma_64(1) + u) |eye_k| (1 + u)` plus the smallest subnormal,
    /// with `N_k` the magnitudes of `d0 X + d1 Y + d3 Z` and `delta =
    /// gamma_64(14) |m0| . |X| / |D|` (magnitudes: every product in
    /// absolute value). Derivation: the rows are within `gamma_64(5)` of
    /// their magnitudes in `f64`; the cross products and the sum within
    /// `gamma_64(14)` of theirs, the determinant likewise, so `|eye_64 -
    /// e*| <= (gamma_64(14) N / |D| + delta |e*|) / (1 - delta)`, and with
    /// `|e*| <= |eye_64| + |eye_64 - e*|` that is the first term for
    /// `delta < 1/2`; rounding to the camera's precision adds the second
    /// (the quotient's rounding and the conversion's). `|D|` is taken from
    /// below (its `f64` value less `gamma_64(12) |m0| . |X|`) and the
    /// bound is infinite unless `delta < 1/4`. Evaluated in `f64` and
    /// rounded up; held to in exact arithmetic by the test kit's matrix
    /// camera checks.
    ///
    /// ```
    /// use rayhit::camera::{ClipSpace, MatrixCamera};
    /// use rayhit::glam::{Vec3, camera::rh::{proj::directx, view}};
    /// let (eye, dir) = (Vec3::new(1.0, 2.0, 5.0), Vec3::new(0.0, -0.3, -1.0).normalize());
    /// let (v, p) = (view::look_to_mat4(eye, dir, Vec3::Y), directx::perspective(1.0, 1.5, 0.1, 100.0));
    /// let cam = MatrixCamera::from_mat4(v, p, ClipSpace::Direct3D, 600, 400).unwrap();
    /// let bound = cam.eye_error(&v.to_cols_array_2d(), &p.to_cols_array_2d());
    /// assert!((cam.fixed() - eye).abs().max_element() < 1e-5);
    /// assert!(bound.max_element() < 1e-5); // a few ulps of 5
    /// ```
    #[must_use]
    pub fn eye_error(&self, view: &Columns<S<V>>, projection: &Columns<S<V>>) -> V {
        let inf = V::splat(S::<V>::INFINITY);
        let Some((m, mag)) = self.made_from(view, projection) else {
            return inf;
        };
        if self.is_orthographic() {
            return inf;
        }
        let (m0, m1, m3) = (xyz(m[0]), xyz(m[1]), xyz(m[3]));
        let (a0, a1, a3) = (xyz(mag[0]), xyz(mag[1]), xyz(mag[3]));
        let (x, y, z) = (m1.cross(m3), m3.cross(m0), m0.cross(m1));
        let (xm, ym, zm) = (cross_mag(a1, a3), cross_mag(a3, a0), cross_mag(a0, a1));
        let big = a0.dot(xm) * (1.0 + gamma64(3));
        let det = m0.dot(x).abs() - gamma64(12) * big;
        let delta = gamma64(14) * big / det;
        if !(det > 0.0 && delta < 0.25) {
            return inf;
        }
        let eye = -(x * m[0][3] + y * m[1][3] + z * m[3][3]) / m0.dot(x);
        let n = (xm * mag[0][3] + ym * mag[1][3] + zm * mag[3][3]) * (1.0 + gamma64(3));
        let u = S::<V>::UNIT_ROUNDOFF.to_f64();
        let fixed = self.fixed;
        let k = |i: usize| {
            let f64_part = (gamma64(14) * n[i] / det + delta * eye[i].abs()) / (1.0 - 2.0 * delta);
            let rounding = (gamma64(1) + u) * fixed[i].to_f64().abs() * (1.0 + u);
            bound_from_f64::<S<V>>(f64_part + rounding + S::<V>::TINY.to_f64())
        };
        V::new(k(0), k(1), k(2))
    }

    /// `projection * view` and its magnitudes ([`product`]) if this camera
    /// is the one [`new`](Self::new) makes of `view` and `projection` (and
    /// its clip space and size); `None` otherwise.
    fn made_from(&self, view: &Columns<S<V>>, projection: &Columns<S<V>>) -> Option<Product> {
        let again = Self::new(*view, *projection, self.clip, self.width, self.height);
        (again.ok() == Some(*self)).then(|| product(view, projection))
    }

    /// A bound on the length of the difference between each direction
    /// derivative of [`ray_differential`](Camera::ray_differential) at `(x,
    /// y)` (`dx_dir`, `dy_dir`) and the exact derivative of the unit
    /// direction at the camera's linear form ([`linear_form`](Self::linear_form))
    /// and the position. Perspective: with `p = c + dx a + dy b` and `K`
    /// its magnitudes `|c| + |dx| |a| + |dy| |b|`, `(|step| / |p|)
    /// (gamma(28) + 5 gamma(3) |K| / |p|)` with `|step|` the larger of
    /// `|a|` and `|b|` (the direction's error twice through `dir (dir .
    /// step)`, the dot product's, two more roundings and the factor `1 /
    /// |p|`'s). Orthographic: zero, as the origin derivatives are `a` and
    /// `-b` exactly and the direction's is zero, at any position.
    /// Evaluated in `f64` and rounded up; for a perspective camera,
    /// infinite for a NaN or infinite position, or where `|p|` is not above
    /// twice the step. Held to in exact arithmetic, against
    /// the neighbouring pixels' rays, by the test kit's matrix camera
    /// checks.
    ///
    /// ```
    /// use rayhit::camera::{ClipSpace, MatrixCamera};
    /// use rayhit::glam::{Vec3, camera::rh::{proj::directx, view}};
    /// let cam = MatrixCamera::from_mat4(view::look_to_mat4(Vec3::ZERO, -Vec3::Z, Vec3::Y),
    ///     directx::perspective(1.0, 1.5, 0.1, 100.0), ClipSpace::Direct3D, 600, 400).unwrap();
    /// // A few ulps of the derivative's length, about 1 / 350.
    /// assert!(cam.ray_differential_error(10.5, 20.5) < 1e-8);
    /// ```
    #[must_use]
    pub fn ray_differential_error(&self, x: S<V>, y: S<V>) -> S<V> {
        match self.projection {
            Projection::Orthographic => S::<V>::ZERO,
            Projection::Perspective => {
                let offsets = centred(x, y, self.width, self.height);
                linear_differential_error(dvec(self.c), [self.a, self.b], offsets, 0.0)
            }
        }
    }

    /// A bound, in pixels `(across, down)`, on how far the exact projection
    /// of the ray of raster position `(x, y)` lands from `(x, y)`, for the
    /// matrices given, in exact arithmetic: for a perspective camera the
    /// ray's vanishing point (where the projection of `origin + t dir`
    /// goes as `t` grows, which every point of the ray is on for an exact
    /// eye); for an orthographic camera the ray's origin. `view` and
    /// `projection` are the matrices the camera was made from, as for
    /// [`eye_error`](Self::eye_error). Infinite for other matrices, where
    /// the camera is too ill-conditioned for the bound (its denominator
    /// not positive) or the position not finite.
    ///
    /// Perspective: in normalised device coordinates `sum_k |n_k| (e K_k +
    /// s) / (|D| - sum_k |m_3k| (e K_k + s))`, times `width / 2` (or
    /// `height / 2`), where `n = m_0 - nx m_3` (or `m_1 - ny m_3`), `(nx,
    /// ny)` the position's device coordinates, `D = m_0 . (m_1 x m_3)`, `e
    /// = gamma(5) + gamma_64(17)` (the rays' linear form's relative error)
    /// and `K_k` the `k`-th component of `|m_0| x |m_1| + |nx| |m_1| x
    /// |m_3| + |ny| |m_3| x |m_0|` (magnitudes: every product in absolute
    /// value), `s` the subnormal slack (half the smallest subnormal per
    /// rounding that can land there: `TINY (4 + |dx| + |dy| + sum K)`).
    /// Orthographic: the origin's device coordinates `(m_i . o + d_i) /
    /// d_3` within `sum_k |m_ik| (e (1 + kappa) O_k + s) / |d_3|`, with `O`
    /// Cramer's rule's magnitudes over `|D|` (`D = m_0 . (m_1 x m_2)`) and
    /// `kappa = |m_0| . |m_1 x m_2| / |D|`. Derived in the camera's
    /// documentation ([`MatrixCamera`]); evaluated in `f64` with the rows'
    /// `f64` rounding added and the result rounded up; held to in exact
    /// arithmetic by the test kit's matrix camera checks.
    ///
    /// ```
    /// use rayhit::camera::{ClipSpace, MatrixCamera};
    /// use rayhit::glam::{Vec3, camera::rh::{proj::directx, view}};
    /// let v = view::look_to_mat4(Vec3::ZERO, -Vec3::Z, Vec3::Y);
    /// let p = directx::perspective(1.0, 16.0 / 9.0, 0.1, 100.0);
    /// let cam = MatrixCamera::from_mat4(v, p, ClipSpace::Direct3D, 3840, 2160).unwrap();
    /// let (v, p) = (v.to_cols_array_2d(), p.to_cols_array_2d());
    /// let (bx, by) = cam.raster_error(&v, &p, 100.5, 2000.5);
    /// assert!(bx < 0.01 && by < 0.01); // thousandths of a pixel for a 4K image
    /// // Matrices the camera was not made from have no bound.
    /// assert!(cam.raster_error(&v, &v, 100.5, 2000.5).0.is_infinite());
    /// ```
    #[must_use]
    pub fn raster_error(
        &self,
        view: &Columns<S<V>>,
        projection: &Columns<S<V>>,
        x: S<V>,
        y: S<V>,
    ) -> (S<V>, S<V>) {
        let inf = (S::<V>::INFINITY, S::<V>::INFINITY);
        let Some((m, mag)) = self.made_from(view, projection) else {
            return inf;
        };
        let (dx, dy) = centred(x, y, self.width, self.height);
        let (dx, dy) = (dx.to_f64(), dy.to_f64());
        if !(dx.is_finite() && dy.is_finite()) {
            return inf;
        }
        let (w, h) = (f64::from(self.width), f64::from(self.height));
        let nx = 2.0 * dx / w;
        let ny = if self.clip == ClipSpace::Vulkan {
            -2.0 * dy / h
        } else {
            2.0 * dy / h
        };
        let rows = [xyz(m[0]), xyz(m[1]), xyz(m[2]), xyz(m[3])];
        let mags = [xyz(mag[0]), xyz(mag[1]), xyz(mag[2]), xyz(mag[3])];
        let e = S::<V>::gamma_n(5).to_f64() + gamma64(17);
        let tiny = S::<V>::TINY.to_f64();
        // A row of M, or n = m_i - c m_j, in absolute value from above:
        // its f64 value's and the rows' rounding (within gamma_64(5) of
        // the magnitudes, and two more roundings for n).
        let abs_up = |v: DVec3, bound: DVec3| v.abs() + bound * gamma64(8);
        // The subnormal slack is `tiny` times `slack` per component: kept
        // apart as a multiple of `tiny` until the last step, `p + tiny q`
        // in pixels, so that for `f64` the only roundings below the normal
        // range are that product's and that sum's (half of `2^-1074` each,
        // which `bound_from_f64` covers).
        let px =
            |p: f64, q: f64, n: f64| bound_from_f64::<S<V>>(p * n / 2.0 + tiny * (q * n / 2.0));
        if !self.is_orthographic() {
            let (m0, m1, m3) = (rows[0], rows[1], rows[3]);
            let (a0, a1, a3) = (mags[0], mags[1], mags[3]);
            let k = cross_mag(a0, a1) + cross_mag(a1, a3) * nx.abs() + cross_mag(a3, a0) * ny.abs();
            let k = k * (1.0 + gamma64(3));
            let slack = 4.0 + dx.abs() + dy.abs() + k.element_sum();
            let err = k * e;
            let big = a0.dot(cross_mag(a1, a3)) * (1.0 + gamma64(3));
            let det = m0.dot(m1.cross(m3)).abs() - gamma64(12) * big;
            // (The slack's share from below: its product's rounding and one
            // more `tiny`.)
            let m3_up = abs_up(m3, a3);
            let den = det - m3_up.dot(err) - tiny * (m3_up.element_sum() * slack) - tiny;
            if !(den > 0.0) {
                return inf;
            }
            let bound = |n: DVec3, nb: DVec3, pixels: f64| {
                let n = abs_up(n, nb);
                px(n.dot(err) / den, n.element_sum() * slack / den, pixels)
            };
            (
                bound(m0 - m3 * nx, a0 + a3 * nx.abs(), w),
                bound(m1 - m3 * ny, a1 + a3 * ny.abs(), h),
            )
        } else {
            let (m0, m1, m2) = (rows[0], rows[1], rows[2]);
            let (a0, a1, a2) = (mags[0], mags[1], mags[2]);
            let d3 = m[3][3];
            let (cx, cy, cz) = (cross_mag(a1, a2), cross_mag(a2, a0), cross_mag(a0, a1));
            let big = a0.dot(cx) * (1.0 + gamma64(3));
            let det = m0.dot(m1.cross(m2)).abs() - gamma64(12) * big;
            // d3 within a rounding of its magnitude, taken from below.
            let d3_lo = d3.abs() - gamma64(5) * mag[3][3];
            if !(det > 0.0 && d3_lo > 0.0) {
                return inf;
            }
            let kappa = big / det;
            let z0 = self.clip.near_depth();
            // |c d3| + |d_i|, from above (d_i within gamma_64(5) of its
            // magnitude).
            let coeff =
                |c: f64, i: usize| (c * mag[3][3]).abs() + m[i][3].abs() + gamma64(5) * mag[i][3];
            let origin = (cx * coeff(nx, 0) + cy * coeff(ny, 1) + cz * coeff(z0, 2))
                * (1.0 + gamma64(4))
                / det;
            let eo = e * (1.0 + kappa);
            let slack = 4.0 + dx.abs() + dy.abs();
            let err = origin * eo;
            let bound = |row: DVec3, rb: DVec3, pixels: f64| {
                let row = abs_up(row, rb);
                px(
                    row.dot(err) / d3_lo,
                    row.element_sum() * slack / d3_lo,
                    pixels,
                )
            };
            (bound(m0, a0, w), bound(m1, a1, h))
        }
    }
}

impl<V: Vector> Camera<V> for MatrixCamera<V> {
    /// The ray through raster position `(x, y)`: for a perspective
    /// projection from the eye with a unit direction, for an orthographic
    /// one from the near plane with the one unit direction (see
    /// [`MatrixCamera`] for the rays and their reprojection bound).
    ///
    /// Positions outside the image give the rays of points outside the
    /// view (behind the eye's plane, a perspective ray still looks into
    /// the half-space of positive clip `w`, which is what the matrices
    /// project; a position at infinity in NDC has no ray). A NaN or
    /// infinite position gives a non-finite ray, which every kernel
    /// rejects.
    #[inline(always)]
    fn ray(&self, sample: CameraSample<S<V>>) -> Ray<V> {
        let [x, y] = sample.film;
        let p = self.linear(x, y);
        match self.projection {
            Projection::Perspective => Ray::new(by_components(self.fixed), unit(p)),
            Projection::Orthographic => Ray::new(p, by_components(self.fixed)),
        }
    }

    /// The ray through `(x, y)`, bit for bit [`ray`](Self::ray), with its
    /// differentials. Perspective: as
    /// [`PinholeCamera::ray_differential`](crate::PinholeCamera::ray_differential)
    /// with `a` and `-b` for `right` and `-true_up`, `dx_dir = (a - dir (dir
    /// . a)) / |p|`, `dy_dir = (dir (dir . b) - b) / |p|` (`p = c + dx a + dy
    /// b`; second order within `2 (|a| + |b|)^2 / |p|^2`; rounding within
    /// [`ray_differential_error`](MatrixCamera::ray_differential_error)).
    /// Orthographic: the origin moves by `a` and `-b` per pixel, exactly
    /// linearly, and the direction not at all.
    #[inline(always)]
    fn ray_differential(&self, sample: CameraSample<S<V>>) -> RayDifferential<V> {
        let [x, y] = sample.film;
        let p = self.linear(x, y);
        let (a, b) = (self.a, self.b);
        match self.projection {
            Projection::Perspective => {
                let (dir, inv) = unit_and_inverse_length(p);
                RayDifferential {
                    ray: Ray::new(by_components(self.fixed), dir),
                    dx_origin: zero_vector(),
                    dx_dir: (a - dir * dir.dot(a)) * inv,
                    dy_origin: zero_vector(),
                    dy_dir: (dir * dir.dot(b) - b) * inv,
                }
            }
            Projection::Orthographic => RayDifferential {
                ray: Ray::new(p, by_components(self.fixed)),
                dx_origin: a,
                dx_dir: zero_vector(),
                dy_origin: -b,
                dy_dir: zero_vector(),
            },
        }
    }

    /// The ray cone of every ray. Perspective: zero width, and the angle
    /// between the image centre's ray and its neighbour one pixel across,
    /// the larger of the two ways (`atan2(|c x a|, c . a)` and likewise
    /// with `b`, with the crate's arctangent). Orthographic: the larger of
    /// `|a|` and `|b|` wide, not spreading.
    #[inline]
    fn ray_cone(&self) -> RayCone<S<V>> {
        let zero = S::<V>::ZERO;
        let max = |p: S<V>, q: S<V>| if p > q { p } else { q };
        match self.projection {
            Projection::Perspective => {
                let tau = S::<V>::from_f64(core::f64::consts::TAU);
                let angle = |v: V| {
                    let next = self.c + v;
                    atan2_turns(self.c.cross(next).length(), self.c.dot(next)) * tau
                };
                RayCone {
                    width: zero,
                    spread: max(angle(self.a), angle(self.b)),
                }
            }
            Projection::Orthographic => RayCone {
                width: max(self.a.length(), self.b.length()),
                spread: zero,
            },
        }
    }

    super::film_size!();
}

impl MatrixCamera<Vec3> {
    /// [`MatrixCamera::new`] from glam's `Mat4`s. (For `Vec3A` rays, pass
    /// `to_cols_array_2d()` of each to `new`.)
    ///
    /// # Errors
    ///
    /// As [`MatrixCamera::new`].
    pub fn from_mat4(
        view: Mat4,
        projection: Mat4,
        clip: ClipSpace,
        width: u32,
        height: u32,
    ) -> Result<Self, CameraError> {
        Self::new(
            view.to_cols_array_2d(),
            projection.to_cols_array_2d(),
            clip,
            width,
            height,
        )
    }
}

impl MatrixCamera<DVec3> {
    /// [`MatrixCamera::new`] from glam's `DMat4`s.
    ///
    /// # Errors
    ///
    /// As [`MatrixCamera::new`].
    pub fn from_dmat4(
        view: DMat4,
        projection: DMat4,
        clip: ClipSpace,
        width: u32,
        height: u32,
    ) -> Result<Self, CameraError> {
        Self::new(
            view.to_cols_array_2d(),
            projection.to_cols_array_2d(),
            clip,
            width,
            height,
        )
    }
}
