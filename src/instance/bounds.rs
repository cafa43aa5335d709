//! An object box in the world, rounded outward.
//!
//! # Derivation
//!
//! The exact image of the box `[lo, hi]` under `F(x) = M x + T` is the
//! convex hull of its corners' images, and its extent on world axis `i` is
//! exactly
//!
//! ```text
//! [ T_i + sum_j min(M_ij lo_j, M_ij hi_j),  T_i + sum_j max(M_ij lo_j, M_ij hi_j) ]
//! ```
//!
//! (each term is linear in one coordinate, so its extreme over the box is
//! at one end of that coordinate's range). Evaluating the lower end with
//! every product and every partial sum stepped one float down after it is
//! rounded (`mul_down`, `add_down`), and the upper end stepped up, gives
//! floats at most and at least the exact ends: a rounding to nearest is
//! within half an ulp, and one step moves a whole ulp (in the subnormal
//! range too). So the world box contains the exact image of every point of
//! the object box; it is at most a few ulps larger than the exact extent.

use super::Instance;
use crate::Aabb;
use crate::num::round::max2;
use crate::num::round::min2;
use crate::num::round::outward::{add_down, add_up, mul_down, mul_up};
use crate::num::{S, Vector};

impl<V: Vector> Instance<V> {
    /// A world box containing the exact image of the object box `object`:
    /// a top-level BVH box for the instance that never misses what the
    /// exact transform puts inside it (derivation in the source).
    ///
    /// `None` when `object` is not valid ([`Aabb::is_valid`]) or the world
    /// box overflows.
    ///
    /// ```
    /// use rayhit::{Aabb, Instance, glam::{Affine3A, Quat, Vec3}};
    /// let place = Affine3A::from_rotation_translation(Quat::from_rotation_z(0.3), Vec3::new(1e4, 0.0, 0.0));
    /// let inst = Instance::from_affine3a(place).unwrap();
    /// let object = Aabb::new(Vec3::splat(-1.0), Vec3::splat(1.0));
    /// let world = inst.object_to_world_box(&object).unwrap();
    /// let corner = place.transform_point3(Vec3::new(1.0, -1.0, 1.0));
    /// assert!(world.min.cmple(corner).all() && corner.cmple(world.max).all());
    /// assert_eq!(inst.object_to_world_box(&Aabb::new(Vec3::ONE, Vec3::ZERO)), None);
    /// ```
    #[must_use]
    pub fn object_to_world_box(&self, object: &Aabb<V>) -> Option<Aabb<V>> {
        if !object.is_valid() {
            return None;
        }
        let (lo, hi) = (object.min, object.max);
        let (cols, t) = (self.matrix_columns(), self.translation());
        let end = |i: usize, upper: bool| -> S<V> {
            let mut acc = t[i];
            for j in 0..3 {
                let m = cols[j][i];
                acc = if upper {
                    add_up(acc, max2(mul_up(m, lo[j]), mul_up(m, hi[j])))
                } else {
                    add_down(acc, min2(mul_down(m, lo[j]), mul_down(m, hi[j])))
                };
            }
            acc
        };
        let min = V::new(end(0, false), end(1, false), end(2, false));
        let max = V::new(end(0, true), end(1, true), end(2, true));
        let world = Aabb::new(min, max);
        world.is_valid().then_some(world)
    }
}
