//! [`Walk`]: the windows of a walk along a ray, every crossing in order.

use super::Interval;
use crate::num::Scalar;
use crate::num::round::{min2, outward::add_up};

/// Every hit along a ray, in order, from the caller's own traversal: the
/// arithmetic of the windows, for transparency, volumes and crossing
/// counts.
///
/// The walk cuts its range into consecutive windows `(t0, t1]`, `(t1,
/// t2]`, ... A window starts from the nearest hit of what is left of the
/// range ([`rest`](Walk::rest)): [`window`](Walk::window) takes that
/// hit's `t` and its error bound and gives `(t0, t + error]`, the end
/// rounded up (or the rest's end, where the bound is infinite, as it is
/// for a ray within rounding of parallel to the surface). The caller
/// collects every hit of the window with an interval form, and
/// [`advance`](Walk::advance) sorts them by `t` and moves the walk past
/// the window.
///
/// **What it guarantees.** The interval forms decide both ends of a
/// window exactly against each exact crossing, so every crossing lands in
/// exactly one window: no hit is skipped or repeated, whatever the
/// windows' ends (they decide only how many hits each window holds), and
/// the windows are in exact order. Within a window, hits are in order of
/// their computed `t`, which is exact order except between hits within
/// each other's error bounds. With [`EdgeRule::OneHit`](crate::EdgeRule)
/// for triangles, each crossing of the surface the triangles form is
/// reported once, at an edge or a corner too (see [`Triangle`'s
/// `hit`](crate::Triangle#method.hit)); with the closed rule, a crossing
/// through a shared edge is reported by every triangle that has it.
///
/// The traversal stays the caller's: cull nodes with
/// [`Bounds::clip`](crate::Bounds::clip) over the same intervals (a
/// conservative test: it never culls a box the ray crosses within them).
/// A traversal that collects every hit of the rest in one pass (a small
/// mesh) can skip `window` and call `advance` directly.
///
/// ```
/// use rayhit::{EdgeRule, Intersect, Interval, Ray, Surface, Triangle, Walk, glam::Vec3};
/// // Four parallel squares at z = 1, 2, 3, 4, each of two triangles
/// // sharing a diagonal, and a ray along that diagonal's line.
/// let square = |z: f32| {
///     let p = |x: f32, y: f32| Vec3::new(x, y, z);
///     [Triangle::new(p(0.0, 0.0), p(1.0, 0.0), p(0.0, 1.0)),
///      Triangle::new(p(1.0, 0.0), p(1.0, 1.0), p(0.0, 1.0))]
/// };
/// let mesh: Vec<Triangle<Vec3>> = [4.0, 2.0, 3.0, 1.0].into_iter().flat_map(square).collect();
/// let ray = Ray::new(Vec3::new(0.5, 0.5, 0.0), Vec3::Z);
/// let search = |i: Interval<f32>| (i, EdgeRule::OneHit);
///
/// let mut walk = Walk::new(Interval::up_to(f32::INFINITY).unwrap());
/// let mut order = Vec::new();
/// while let Some(rest) = walk.rest() {
///     // The nearest hit of the rest (the caller's closest-hit traversal).
///     let Some((tri, hit)) = mesh
///         .iter()
///         .filter_map(|tri| Some((tri, tri.hit(&ray, search(rest))?)))
///         .min_by(|a, b| a.1.t.total_cmp(&b.1.t))
///     else {
///         break;
///     };
///     let window = walk.window(hit.t, tri.hit_error(&ray, &hit).t).unwrap();
///     // Every hit of the window (the caller's any-hit traversal, collecting).
///     let mut hits: Vec<_> = mesh.iter().filter_map(|tri| tri.hit(&ray, search(window))).collect();
///     order.extend(walk.advance(&mut hits, |h| h.t).iter().map(|h| h.t));
/// }
/// // Each square once, though the ray runs through the shared diagonals.
/// assert_eq!(order, [1.0, 2.0, 3.0, 4.0]);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Walk<F> {
    /// What is left of the range, `None` once the walk is done.
    rest: Option<Interval<F>>,
    /// The end of the window last given by [`Walk::window`], if any.
    window_end: Option<F>,
}

impl<F: Scalar> Walk<F> {
    /// A walk over `range`, starting at its lower end.
    #[inline]
    #[must_use]
    pub fn new(range: Interval<F>) -> Self {
        Self {
            rest: Some(range),
            window_end: None,
        }
    }

    /// What is left of the range: the interval to search for the next
    /// nearest hit; `None` once the walk has passed the range's end.
    #[inline]
    #[must_use]
    pub fn rest(&self) -> Option<Interval<F>> {
        self.rest
    }

    /// The window that holds the nearest hit of the rest, at `t` with the
    /// error bound `t_error` (from [`Surface::hit_error`](crate::Surface)):
    /// `(rest.min, t + t_error]`, its end rounded up to a float at least
    /// the exact sum, and no farther than the rest's end (the whole rest
    /// where the sum overflows, or a value is infinite or NaN). Every hit
    /// whose exact crossing might precede the nearest one's is in it.
    /// `None` once the walk is done.
    #[inline]
    #[must_use]
    pub fn window(&mut self, t: F, t_error: F) -> Option<Interval<F>> {
        let rest = self.rest?;
        // A NaN or negative bound, or a NaN sum, fails `>=`: the rest.
        let end = if t_error >= F::ZERO {
            add_up(t, t_error)
        } else {
            F::INFINITY
        };
        let end = if end >= rest.min() {
            min2(end, rest.max())
        } else {
            rest.max()
        };
        self.window_end = Some(end);
        Interval::new(rest.min(), end)
    }

    /// Sorts `hits`, every hit collected over the last
    /// [`window`](Walk::window) (or over the whole [`rest`](Walk::rest),
    /// where no window was asked for), by their `t` as `t_of` gives it,
    /// and moves the walk past that window. Returns the sorted hits (hits
    /// of equal `t` in no particular order).
    #[inline]
    pub fn advance<'h, H>(&mut self, hits: &'h mut [H], t_of: impl Fn(&H) -> F) -> &'h mut [H] {
        hits.sort_unstable_by(|a, b| {
            t_of(a)
                .partial_cmp(&t_of(b))
                .unwrap_or(core::cmp::Ordering::Equal)
        });
        if let Some(rest) = self.rest {
            let end = self.window_end.take().unwrap_or(rest.max());
            self.rest = if end < rest.max() {
                Interval::new(end, rest.max())
            } else {
                None
            };
        }
        hits
    }
}
