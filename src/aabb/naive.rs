//! The reference box test, face by face.

use super::Aabb;
use crate::num::round::{max2, min2};
use crate::num::{S, Scalar, Vector};
use crate::ray::{Ray, t_max_ok};

impl<V: Vector> Aabb<V> {
    /// The reference box test, face by face: each of the six faces is treated as
    /// a plane, the crossing point is tested against the face's closed
    /// rectangle, and the interval runs from the first face crossed to the last,
    /// clipped to `[0, t_max]`.
    ///
    /// Same conventions, answer type and invalid-input behaviour as
    /// [`ray_aabb`](crate::ray_aabb).
    /// It is slower, and it is *not* conservative: a point computed a rounding
    /// outside a face rectangle is a miss, so near edges and corners it can
    /// disagree with the slab test (which is). Away from edges the two agree on
    /// hit or miss, and the distances agree within a few ulps: each face
    /// distance is `fl(fl(b - o) / d)`, two roundings, and the crossing point
    /// is tested in coordinates relative to the origin
    /// (`min - o <= t * d <= max - o`), so each test is wrong only within a
    /// relative `gamma(4)` of the face rectangle's edge, however far the origin
    /// is from the coordinate origin.
    ///
    /// ```
    /// use rayhit::{Aabb, Ray, glam::Vec3};
    /// let unit = Aabb::new(Vec3::ZERO, Vec3::ONE);
    /// let ray = Ray::new(Vec3::new(0.5, 0.5, 3.0), Vec3::new(0.0, 0.0, -1.0));
    /// assert_eq!(unit.clip_by_faces(&ray, f32::INFINITY), Some((2.0, 3.0)));
    /// assert_eq!(unit.clip_by_faces(&ray, 1.0), None);
    /// ```
    #[must_use]
    pub fn clip_by_faces(&self, ray: &Ray<V>, t_max: S<V>) -> Option<(S<V>, S<V>)> {
        ray_aabb_naive(ray, self, t_max)
    }
}

/// The face-by-face reference: see [`Aabb::clip_by_faces`].
fn ray_aabb_naive<V: Vector>(ray: &Ray<V>, aabb: &Aabb<V>, t_max: S<V>) -> Option<(S<V>, S<V>)> {
    if !(ray.is_valid() && aabb.is_valid() && t_max_ok(t_max)) {
        return None;
    }
    let mut first = S::<V>::INFINITY;
    let mut last = -S::<V>::INFINITY;
    for k in 0..3 {
        let d = ray.dir[k];
        if d == S::<V>::ZERO {
            continue;
        }
        let (j, l) = ((k + 1) % 3, (k + 2) % 3);
        for plane in [aabb.min[k], aabb.max[k]] {
            let t = (plane - ray.origin[k]) / d;
            let on_face = |m: usize| {
                let q = t * ray.dir[m];
                aabb.min[m] - ray.origin[m] <= q && q <= aabb.max[m] - ray.origin[m]
            };
            if t.is_finite() && on_face(j) && on_face(l) {
                first = min2(first, t);
                last = max2(last, t);
            }
        }
    }
    let enter = max2(first, S::<V>::ZERO);
    let exit = min2(last, t_max);
    (enter <= exit).then_some((enter, exit))
}
