//! The exact answers for the curved and four-cornered shapes: spheres,
//! discs, quads and bilinear patches, each the nearest exact crossing in
//! range rounded to the precision asked for.

use super::*;
use crate::{Disc, DiscHit, Patch, PatchHit, Quad, Ray, Scalar, Sphere, SphereHit, Vector};

/// Exact ray/sphere: the first crossing of the ray with the sphere in `0
/// < t <= t_max` (the entry where it is in range, else the exit; a tangent
/// line's double crossing is an entry), its `t` rounded to the nearest
/// float (the crossing is a root of a quadratic, irrational in general:
/// it is placed between floats exactly, see
/// [`ExactSphere::rounded`](oracle::ExactSphere::rounded)) and its side
/// ([`Side::Front`] entering the ball); `None` for a miss or invalid
/// input (see [`Ray::is_valid`]; a NaN or infinite centre or radius, a
/// NaN `t_max`). The question [`Sphere`'s `hit`](crate::Sphere#method.hit)
/// answers with rounding; the exact comparisons themselves are
/// [`oracle::sphere`]'s.
///
/// ```
/// use rayhit::{Ray, Side, Sphere, exact, glam::Vec3};
/// let ball = Sphere::new(Vec3::ZERO, 1.0);
/// // From (0.5, 0, -2) along z: in at t = 2 - sqrt(3) / 2, out at 2 + sqrt(3) / 2.
/// let ray = Ray::new(Vec3::new(0.5, 0.0, -2.0), Vec3::Z);
/// let hit = exact::ray_sphere(&ray, &ball, f32::INFINITY).unwrap();
/// assert_eq!((hit.t, hit.side), ((2.0 - 3f64.sqrt() / 2.0) as f32, Side::Front));
/// // Up to t = 2 only the entry; from inside the exit.
/// assert!(exact::ray_sphere(&ray, &ball, 1.0).is_none());
/// let inside = Ray::new(Vec3::ZERO, Vec3::Z);
/// assert_eq!(exact::ray_sphere(&inside, &ball, f32::INFINITY).map(|h| (h.t, h.side)), Some((1.0, Side::Back)));
/// ```
#[must_use]
pub fn ray_sphere<V: Vector>(
    ray: &Ray<V>,
    sphere: &Sphere<V>,
    t_max: V::Scalar,
) -> Option<SphereHit<V::Scalar>> {
    sphere_first(ray, sphere, t_max).map(|(_, hit)| hit)
}

/// [`ray_sphere`]'s answer with the exact line it came from.
pub(crate) fn sphere_first<V: Vector>(
    ray: &Ray<V>,
    sphere: &Sphere<V>,
    t_max: V::Scalar,
) -> Option<(oracle::ExactSphere, SphereHit<V::Scalar>)> {
    if !(ray.is_valid()
        && sphere.center.is_finite()
        && sphere.radius.is_finite()
        && valid_limit(t_max))
    {
        return None;
    }
    let e = oracle::sphere(ray, sphere.center, sphere.radius)?;
    let side = e.first_in(&Rational::zero(), oracle::limit(t_max).as_ref())?;
    let t = e.rounded(side)?;
    Some((e, SphereHit { t, side }))
}

/// Exact ray/disc: the crossing with the disc's plane in `0 < t <= t_max`
/// where it lies within both closed circles (the annulus between the
/// radii, by magnitude), its `t` rounded to nearest and its side
/// ([`Side::Front`] arriving against the normal); `None` for a miss, a ray
/// parallel to the plane, or invalid input (see [`Ray::is_valid`]; a NaN
/// or infinite value of the disc, a zero normal, a NaN `t_max`). The
/// question [`Disc`'s `hit`](crate::Disc#method.hit) answers with rounding;
/// the exact crossing itself (`t` as a rational, the squared distance from
/// the centre) is [`oracle::disc`]'s.
///
/// ```
/// use rayhit::{Disc, Ray, Side, exact, glam::Vec3};
/// let ring = Disc::annulus(Vec3::ZERO, Vec3::Z, 2.0, 1.0);
/// // Down onto the inner circle at (1, 0, 0): on the rim, so hit.
/// let ray = Ray::new(Vec3::new(1.0, 0.0, 3.0), Vec3::new(0.0, 0.0, -3.0));
/// let hit = exact::ray_disc(&ray, &ring, f32::INFINITY).unwrap();
/// assert_eq!((hit.t, hit.side), (1.0, Side::Front));
/// // Through the hole.
/// let hole = Ray::new(Vec3::new(0.5, 0.0, 3.0), -Vec3::Z);
/// assert!(exact::ray_disc(&hole, &ring, f32::INFINITY).is_none());
/// ```
#[must_use]
pub fn ray_disc<V: Vector>(
    ray: &Ray<V>,
    disc: &Disc<V>,
    t_max: V::Scalar,
) -> Option<DiscHit<V::Scalar>> {
    disc_first(ray, disc, t_max).map(|(_, hit)| hit)
}

/// [`ray_disc`]'s answer with the exact crossing it came from.
pub(crate) fn disc_first<V: Vector>(
    ray: &Ray<V>,
    disc: &Disc<V>,
    t_max: V::Scalar,
) -> Option<(oracle::ExactDisc, DiscHit<V::Scalar>)> {
    if !(ray.is_valid() && valid_limit(t_max)) {
        return None;
    }
    let e = oracle::disc(ray, disc)?;
    if !(disc.radius.is_finite()
        && disc.inner_radius.is_finite()
        && e.hit_in(&Rational::zero(), oracle::limit(t_max).as_ref()))
    {
        return None;
    }
    let hit = DiscHit {
        t: round(&e.t),
        side: e.side,
    };
    Some((e, hit))
}

/// Exact ray/quad: the nearer of the exact crossings of the quad's two
/// closed triangles `a, b, c` and `a, c, d` ([`ray_triangle`]; the first
/// where they tie, as on the diagonal), with `u` and `v` placed on the
/// quad as [`Quad`'s `hit`](crate::Quad#method.hit) places them (`u = u1 +
/// v1`, `v = v1` on the first triangle, `u = u2`, `v = u2 + v2` on the
/// second, from its weights), each exact and rounded to nearest. `None`
/// for a miss (both triangles' lines parallel included) or invalid input.
///
/// ```
/// use rayhit::{Quad, Ray, exact, glam::Vec3};
/// let quad = Quad::parallelogram(Vec3::ZERO, Vec3::new(2.0, 0.0, 0.0), Vec3::Y);
/// let ray = Ray::new(Vec3::new(0.5, 0.75, 3.0), -Vec3::Z);
/// let hit = exact::ray_quad(&ray, &quad, f32::INFINITY).unwrap();
/// assert_eq!((hit.t.rounded, hit.u.rounded, hit.v.rounded), (3.0, 0.25, 0.75));
/// ```
#[must_use]
pub fn ray_quad<V: Vector>(
    ray: &Ray<V>,
    quad: &Quad<V>,
    t_max: V::Scalar,
) -> Option<TriangleAnswer<V::Scalar>> {
    let [first, second] = quad.triangles();
    let on_quad = |h: TriangleAnswer<V::Scalar>, second: bool| {
        let sum = Exact::new(&h.u.value + &h.v.value);
        let (u, v) = if second { (h.u, sum) } else { (sum, h.v) };
        TriangleAnswer { u, v, ..h }
    };
    let near = ray_triangle(ray, &first, t_max).map(|h| on_quad(h, false));
    let far = ray_triangle(ray, &second, t_max).map(|h| on_quad(h, true));
    match (near, far) {
        (Some(n), Some(f)) if f.t.value < n.t.value => Some(f),
        (None, f) => f,
        (n, _) => n,
    }
}

/// Exact ray/patch: the nearest crossing of the ray with the bilinear
/// patch in `0 < t <= t_max`, its `t`, `u` and `v` each rounded to the
/// nearest float (they are irrational in general: placed between floats
/// exactly, see [`oracle::patch`]) and its side ([`Side::Front`] where
/// `dir . (dP/du x dP/dv) <= 0`); `None` for a miss or invalid input (see
/// [`Ray::is_valid`]; a NaN or infinite corner, a NaN `t_max`). The
/// question [`Patch`'s `hit`](crate::Patch#method.hit) answers with
/// rounding.
///
/// ```
/// use rayhit::{Patch, Ray, exact, glam::Vec3};
/// let saddle = Patch::new(Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(1.0, 1.0, 1.0));
/// let ray = Ray::new(Vec3::new(0.3, 0.6, 2.0), -Vec3::Z);
/// let hit = exact::ray_patch(&ray, &saddle, f32::INFINITY).unwrap();
/// // P(0.3, 0.6) = (0.3, 0.6, 0.18), at t = 2 - 0.18 (the rounded inputs').
/// assert_eq!((hit.u, hit.v), (0.3, 0.6));
/// assert!((hit.t - 1.82).abs() < 1e-6);
/// ```
#[must_use]
pub fn ray_patch<V: Vector>(
    ray: &Ray<V>,
    patch: &Patch<V>,
    t_max: V::Scalar,
) -> Option<PatchHit<V::Scalar>> {
    patch_first(ray, patch, t_max).map(|(_, hit)| hit)
}

/// [`ray_patch`]'s answer with the exact crossing it came from.
pub(crate) fn patch_first<V: Vector>(
    ray: &Ray<V>,
    patch: &Patch<V>,
    t_max: V::Scalar,
) -> Option<(oracle::PatchCrossing, PatchHit<V::Scalar>)> {
    if !(ray.is_valid() && valid_limit(t_max)) {
        return None;
    }
    let e = oracle::patch(ray, patch)?;
    let c = e.first_in(&Rational::zero(), oracle::limit(t_max).as_ref())?;
    let round = oracle::PatchCrossing::rounded::<V::Scalar>;
    let hit = PatchHit {
        t: round(&c.t),
        u: round(&c.u),
        v: round(&c.v),
        side: c.side,
    };
    Some((c.clone(), hit))
}
