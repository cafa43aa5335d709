//! A BVH-node form: the children of a compressed wide BVH node, stored
//! quantized, and the conservative ray test that reads them where the node
//! keeps them (the box batch's slab test on boxes decoded rounded outward).

use core::marker::PhantomData;

use glam::{Vec3, Vec3A};

use crate::aabb::{Aabb, AabbBatch, AabbBatchHits, MaskOf, Slab8, batch_query};
use crate::num::{Lanes8, Vector};
use crate::query::{Bounds, RayForm, Search};
use crate::ray::PreparedRay;
use crate::simd::{Isa, Kernel};

/// The eight child boxes of a compressed wide BVH node, read in place:
/// the quantized format of Ylitie, Karras and Laine ("Efficient Incoherent
/// Ray Traversal on GPUs Through Compressed Wide BVHs", HPG 2017), which
/// obvhs and other CPU and GPU BVHs store.
///
/// Per axis `k`, a child's box runs from `origin[k] + s[k] * min[k][child]`
/// to `origin[k] + s[k] * max[k][child]`, where the grid step
/// `s[k] = 2^(exponents[k] - 127)` is the `f32` whose bits are
/// `exponents[k] << 23`, and the bounds are bytes. The struct holds
/// references to the node's own byte arrays, so the node is not copied: build
/// one per node visit from the fields of whatever node type the BVH uses.
///
/// The boxes the ray test uses, [`QuantizedChildren::child_box`], contain
/// these exact boxes: every coordinate is rounded outward by at least the
/// rounding error of computing it (see `widening`). A node whose origin is
/// not finite or whose exponent is 255 (a step of infinity) is invalid and
/// none of its children is hit; a child with `min > max` on some axis is
/// empty and never hit. Empty child slots are tested like any other: mask
/// the answer with the node's occupied slots.
///
/// ```
/// use rayhit::{batch::QuantizedChildren, glam::Vec3};
/// // Step 2^(125 - 127) = 0.25 on every axis, children measured from (1, 2, 3).
/// let (lo, hi) = ([0, 4, 0, 0, 0, 0, 0, 0], [4, 8, 0, 0, 0, 0, 0, 0]);
/// let node = QuantizedChildren {
///     origin: Vec3::new(1.0, 2.0, 3.0),
///     exponents: [125; 3],
///     min: [&lo, &lo, &lo],
///     max: [&hi, &hi, &hi],
/// };
/// assert_eq!(node.step(), Vec3::splat(0.25));
/// // Child 1 spans [2, 3] x [3, 4] x [4, 5], widened by a few ulps of the
/// // node's largest coordinate (3 + 255 * 0.25 = 66.75, ulp 2^-17).
/// let b = node.child_box(1).unwrap();
/// assert!(b.min.x <= 2.0 && b.min.x > 2.0 - 1e-4 && b.max.z >= 5.0 && b.max.z < 5.0 + 1e-4);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct QuantizedChildren<'a, V = Vec3> {
    /// The corner the children's bounds are measured from (any `f32`
    /// [`Vector`](crate::Vector)).
    pub origin: V,
    /// Per axis, the biased exponent of the grid step.
    pub exponents: [u8; 3],
    /// Per axis, the eight children's lower bounds, in grid steps.
    pub min: [&'a [u8; 8]; 3],
    /// Per axis, the eight children's upper bounds, in grid steps.
    pub max: [&'a [u8; 8]; 3],
}

/// The grid step `2^(e - 127)` of a biased exponent `e` (`0` for `e = 0`,
/// `+inf` for `e = 255`).
#[inline(always)]
fn step_of(e: u8) -> f32 {
    f32::from_bits(u32::from(e) << 23)
}

/// The outward rounding of the decoded coordinates of an axis (of each
/// lane's): a float `w` such that for every byte `q`, `fl(r - w) <= p + s q <= fl(r + w)`
/// exactly, where `r = fl(fl(s q) + p)` is the coordinate computed.
///
/// Derivation. `s q` is exact (a byte times a power of two, for steps from
/// `2^-126` up; below, `s = 0` or a subnormal step, whose products are also
/// exact as long as they stay subnormal or `q s` is a multiple of the
/// smallest subnormal, which it is). So `r` is one rounding of the exact
/// `x = p + s q`: `|r - x| <= ulp(r) / 2 <= 2^-24 |r|` for a normal `r`,
/// and `<= TINY / 2` below. Rounding is monotone in `q`, so `|r| <= M =
/// max(|p|, |fl(p + 255 s)|)`. With `w = fl(2^-22 M) + 2 TINY` (at least
/// `2^-22 M + TINY`), the difference `r - w` is at most
/// `x - 3 * 2^-24 M - TINY/2`, and rounding it adds at most
/// `2^-24 |r - w| <= 2^-24 (M + w)` for a normal result, less than that
/// margin (a subnormal result of a subtraction is exact). The same holds
/// for `r + w` upward. So the decoded box contains the exact one, wider by
/// about four ulps of the node's largest coordinate on each side.
///
/// Computed for the three axes at once, lane by lane (`Vec3A::max` keeps
/// the first operand where it is greater; only a NaN origin, which makes
/// the node invalid, could tell the backends' maxima apart).
#[inline(always)]
fn widening(p: Vec3A, s: Vec3A) -> Vec3A {
    let far = p + s * 255.0;
    p.abs().max(far.abs()) * f32::from_bits(0x3480_0000) + 2.0 * f32::from_bits(1)
}

impl<V: Vector<Scalar = f32>> QuantizedChildren<'_, V> {
    /// The grid step `2^(e - 127)` of each axis.
    #[inline]
    #[must_use]
    pub fn step(&self) -> V {
        let [x, y, z] = self.exponents.map(step_of);
        V::new(x, y, z)
    }

    /// True when the origin is finite, no exponent is 255, and every
    /// decoded coordinate is finite (an origin within a few ulps of
    /// `f32::MAX`, or a step so large that `origin + 255 step` overflows,
    /// makes the node invalid).
    #[inline]
    #[must_use]
    pub fn is_valid(&self) -> bool {
        axes_of(self).1
    }

    /// The box the ray test uses for `child` (0 to 7): the quantized box
    /// rounded outward, so that it contains the exact one; `None` for an
    /// invalid node, an empty child (`min > max` on an axis) or `child >= 8`.
    #[must_use]
    pub fn child_box(&self, child: usize) -> Option<Aabb<V>> {
        let (axes, finite) = axes_of(self);
        if child >= 8 || !finite {
            return None;
        }
        let mut lo = [0.0; 3];
        let mut hi = [0.0; 3];
        for (k, &Axis { p, s, w }) in axes.iter().enumerate() {
            let (a, b) = (self.min[k][child], self.max[k][child]);
            if a > b {
                return None;
            }
            lo[k] = (s * f32::from(a) + p) - w;
            hi[k] = (s * f32::from(b) + p) + w;
        }
        Some(Aabb::new(
            V::new(lo[0], lo[1], lo[2]),
            V::new(hi[0], hi[1], hi[2]),
        ))
    }

    /// The eight boxes of [`QuantizedChildren::child_box`] as a batch
    /// (empty children and invalid nodes give empty lanes): its
    /// [`clip`](Bounds::clip) gives, bit for bit, what the node's gives.
    #[must_use]
    pub fn boxes(&self) -> AabbBatch<V, 8> {
        let mut batch = AabbBatch::empty();
        for child in 0..8 {
            if let Some(b) = self.child_box(child) {
                batch.set(child, &b);
            }
        }
        batch
    }
}

impl QuantizedChildren<'_, Vec3> {
    /// Quantizes one axis of a child's bounds for a node with origin `origin`
    /// and biased exponent `exponent` on that axis, conservatively: the bytes
    /// `(lo, hi)` with the tightest box whose decoded form
    /// ([`QuantizedChildren::child_box`]) contains `[min, max]`, or `None`
    /// when no byte pair does (the node's box does not contain the child's, or
    /// its step is too small) or the input is not finite or inverted.
    ///
    /// A BVH builder that quantizes with this (or checks its own bytes against
    /// `child_box`) gets nodes whose test never misses a child the ray meets.
    ///
    /// ```
    /// use rayhit::batch::QuantizedChildren;
    /// // Origin 1, step 0.25 (exponent 125): [1.6, 2.2] needs [1.5, 2.25].
    /// assert_eq!(QuantizedChildren::quantize(1.0, 125, 1.6, 2.2), Some((2, 5)));
    /// // Below the origin: no byte reaches it.
    /// assert_eq!(QuantizedChildren::quantize(1.0, 125, 0.5, 2.0), None);
    /// ```
    #[must_use]
    pub fn quantize(origin: f32, exponent: u8, min: f32, max: f32) -> Option<(u8, u8)> {
        if !(origin.is_finite()
            && exponent < 255
            && min.is_finite()
            && max.is_finite()
            && min <= max)
        {
            return None;
        }
        let s = step_of(exponent);
        let w = widening(Vec3A::splat(origin), Vec3A::splat(s)).x;
        let lo_of = |q: u8| (s * f32::from(q) + origin) - w;
        let hi_of = |q: u8| (s * f32::from(q) + origin) + w;
        // A first guess from the quotient, then the exact decode decides (the
        // decoded coordinates grow with the byte).
        let guess = |x: f32| {
            let q = if s > 0.0 { (x - origin) / s } else { 0.0 };
            if q.is_nan() { 0.0 } else { q.clamp(0.0, 255.0) }
        };
        // (`as u8` truncates, which the loops below correct either way; no
        // `floor` or `ceil` without `std`.)
        let mut lo = guess(min) as u8;
        while lo_of(lo) > min {
            lo = lo.checked_sub(1)?;
        }
        while lo < 255 && lo_of(lo + 1) <= min {
            lo += 1;
        }
        let mut hi = guess(max) as u8;
        while hi_of(hi) < max {
            hi = hi.checked_add(1)?;
        }
        while hi > lo && hi_of(hi - 1) >= max {
            hi -= 1;
        }
        // For bounds thinner than the widening, `lo` can pass `hi`; then every
        // byte between them decodes to a box containing the bounds (the decoded
        // coordinates grow with the byte), `hi` among them.
        Some(if lo > hi { (hi, hi) } else { (lo, hi) })
    }
}

/// The node test, conservative, on the children as stored.
impl<V: Vector<Scalar = f32>> Bounds<V> for QuantizedChildren<'_, V> {
    /// The children hit, and each one's entry.
    type Clip = AabbBatchHits<f32, 8>;
    /// The children hit.
    type Meets = u32;

    /// The slab test of one ray against the eight children of a compressed
    /// wide BVH node, read from the node itself: which children the ray meets
    /// within `search` (a `t_max` or an [`Interval`](crate::Interval)), and where it enters
    /// each.
    ///
    /// Each child's box is decoded with outward rounding
    /// ([`QuantizedChildren::child_box`]), so it contains the exact quantized
    /// box, and tested with the conservative slab test: the answer is, bit for
    /// bit, the [`clip`](Bounds::clip) of [`QuantizedChildren::boxes`], so
    /// every guarantee of [`Aabb`]'s [`clip`](Bounds::clip) holds per child. In
    /// particular: no false miss against exact arithmetic on the quantized
    /// boxes. With a builder whose quantized boxes contain the children's
    /// geometry (see [`QuantizedChildren::quantize`]), a traversal with this node test and
    /// [`ray_triangle`](crate::ray_triangle) in the leaves is watertight. False
    /// hits only within a few ulps of a decoded box (about four ulps of the
    /// node's largest coordinate, from the outward rounding, plus the slab
    /// test's band).
    ///
    /// With an [`Interval`](crate::Interval) `(t_min, t_max]`, each child is culled as
    /// [`Aabb`]'s [`clip`](Bounds::clip) culls it over the interval: never a
    /// false miss of a child whose box the exact ray crosses within it.
    ///
    /// An invalid node, an invalid ray and a NaN or negative `t_max` give no
    /// hits; empty children are never hit. Never panics. On x86-64 with `std`
    /// it runs the AVX-512 or AVX2 copy where the CPU has one, like the
    /// batches (a prepared ray on an instruction set,
    /// [`SimdRay`](crate::batch::SimdRay), chooses once per traversal).
    ///
    /// ```
    /// use rayhit::{Bounds, Interval, PreparedRay, Ray, glam::Vec3};
    /// use rayhit::batch::QuantizedChildren;
    /// let (lo, hi) = ([0, 4, 0, 0, 0, 0, 0, 0], [4, 8, 0, 0, 0, 0, 0, 0]);
    /// let node = QuantizedChildren {
    ///     origin: Vec3::ZERO,
    ///     exponents: [127; 3], // step 1
    ///     min: [&lo, &lo, &lo],
    ///     max: [&hi, &hi, &hi],
    /// };
    /// // Along the diagonal: child 0 is [0, 4]^3, child 1 is [4, 8]^3.
    /// let ray = PreparedRay::new(&Ray::new(Vec3::splat(-1.0), Vec3::ONE));
    /// let hits = node.clip(&ray, f32::INFINITY);
    /// assert_eq!(hits.mask & 0b11, 0b11);
    /// assert!(hits.enter[1] <= 5.0 && hits.enter[1] > 4.99);
    /// // Past t = 6, only child 1.
    /// let later = node.clip(&ray, Interval::new(6.0, f32::INFINITY).unwrap());
    /// assert_eq!(later.mask & 0b11, 0b10);
    /// assert_eq!(later.enter[1], 6.0);
    /// ```
    #[inline(always)]
    fn clip(&self, ray: &impl RayForm<V>, search: impl Into<Search<f32>>) -> Self::Clip {
        node_clip(ray, self, search.into())
    }

    /// [`clip`](Bounds::clip)`.mask`, returned in a register: the node
    /// test of a traversal that visits the children in an order of its
    /// own (by the ray's octant, as Ylitie et al. do) or asks for any hit.
    ///
    /// ```
    /// use rayhit::{Bounds, PreparedRay, Ray, glam::Vec3};
    /// use rayhit::batch::QuantizedChildren;
    /// let (lo, hi) = ([0, 4, 0, 0, 0, 0, 0, 0], [4, 8, 0, 0, 0, 0, 0, 0]);
    /// let node = QuantizedChildren {
    ///     origin: Vec3::ZERO,
    ///     exponents: [127; 3], // step 1: child 0 is [0, 4]^3, child 1 [4, 8]^3
    ///     min: [&lo, &lo, &lo],
    ///     max: [&hi, &hi, &hi],
    /// };
    /// let ray = PreparedRay::new(&Ray::new(Vec3::splat(-1.0), Vec3::ONE));
    /// assert_eq!(node.meets(&ray, f32::INFINITY) & 0b11, 0b11);
    /// assert_eq!(node.meets(&ray, 2.0) & 0b11, 0b01);
    /// ```
    #[inline(always)]
    fn meets(&self, ray: &impl RayForm<V>, search: impl Into<Search<f32>>) -> u32 {
        node_meets(ray, self, search.into())
    }
}

/// A compressed wide BVH node read where it is stored: `F` makes its
/// [`QuantizedChildren`] view, and the node test calls it inside its SIMD
/// copy, so that the node's bytes are loaded there, straight from the
/// node.
///
/// The same answers as the view's, bit for bit: [`Bounds`] here is
/// [`QuantizedChildren`]'s. What differs is the cost of a plain call on a
/// [`PreparedRay`]: with the view built in the traversal and passed to the
/// call, the test reads the node through the view the caller has just
/// written to the stack (the origin, the exponents and six row
/// references), a round trip through memory on every node; with
/// `InPlace`, the call carries one reference to the closure. In a
/// traversal by plain calls that is the faster form (see BENCHMARKS.md);
/// inside [`with_simd`](crate::batch::with_simd), where the test is
/// inlined, both compile alike.
///
/// ```
/// use rayhit::{Bounds, PreparedRay, Ray, glam::Vec3};
/// use rayhit::batch::{InPlace, QuantizedChildren};
/// /// A node as a BVH stores it.
/// struct Node {
///     origin: Vec3,
///     exponents: [u8; 3],
///     rows: [[u8; 8]; 6], // min x, max x, min y, max y, min z, max z
/// }
/// let mut rows = [[0; 8]; 6];
/// for k in 0..3 {
///     rows[2 * k] = [0, 4, 0, 0, 0, 0, 0, 0];
///     rows[2 * k + 1] = [4, 8, 0, 0, 0, 0, 0, 0];
/// }
/// let node = Node { origin: Vec3::ZERO, exponents: [127; 3], rows };
/// fn view(n: &Node) -> QuantizedChildren<'_> {
///     QuantizedChildren {
///         origin: n.origin,
///         exponents: n.exponents,
///         min: [&n.rows[0], &n.rows[2], &n.rows[4]],
///         max: [&n.rows[1], &n.rows[3], &n.rows[5]],
///     }
/// }
/// let ray = PreparedRay::new(&Ray::new(Vec3::splat(-1.0), Vec3::ONE));
/// let hits = InPlace(|| view(&node)).meets(&ray, f32::INFINITY);
/// assert_eq!(hits & 0b11, 0b11);
/// assert_eq!(hits, view(&node).meets(&ray, f32::INFINITY));
/// ```
#[derive(Clone, Copy, Debug)]
pub struct InPlace<F>(pub F);

/// [`QuantizedChildren`]'s node test on the view `F` makes, bit for bit.
impl<'n, V: Vector<Scalar = f32>, F: Fn() -> QuantizedChildren<'n, V>> Bounds<V> for InPlace<F> {
    /// As [`QuantizedChildren`]'s.
    type Clip = AabbBatchHits<f32, 8>;
    /// As [`QuantizedChildren`]'s.
    type Meets = u32;

    /// [`QuantizedChildren`]'s [`clip`](Bounds::clip) of the view, with
    /// the view made inside the test.
    #[inline(always)]
    fn clip(&self, ray: &impl RayForm<V>, search: impl Into<Search<f32>>) -> Self::Clip {
        node_clip(ray, self, search.into())
    }

    /// [`QuantizedChildren`]'s [`meets`](Bounds::meets) of the view, with
    /// the view made inside the test.
    #[inline(always)]
    fn meets(&self, ray: &impl RayForm<V>, search: impl Into<Search<f32>>) -> u32 {
        node_meets(ray, self, search.into())
    }
}

/// What the node test reads a node from: its view, or a closure that makes
/// the view ([`InPlace`]), called inside the kernel.
pub(crate) trait Source<'n, V> {
    fn view(&self) -> QuantizedChildren<'n, V>;
}

impl<'n, V: Copy> Source<'n, V> for QuantizedChildren<'n, V> {
    #[inline(always)]
    fn view(&self) -> QuantizedChildren<'n, V> {
        *self
    }
}

impl<'n, V, F: Fn() -> QuantizedChildren<'n, V>> Source<'n, V> for InPlace<F> {
    #[inline(always)]
    fn view(&self) -> QuantizedChildren<'n, V> {
        (self.0)()
    }
}

/// The node test's [`clip`](Bounds::clip) on the node `source` reads,
/// for every form of it.
#[inline(always)]
fn node_clip<'n, V: Vector<Scalar = f32>, S: Source<'n, V>>(
    ray: &impl RayForm<V>,
    source: &S,
    search: Search<f32>,
) -> AabbBatchHits<f32, 8> {
    batch_query::<V, QuantizedKernel<'n, V, S>>(ray, source, search, AabbBatchHits::none())
}

/// The node test's [`meets`](Bounds::meets) on the node `source` reads.
#[inline(always)]
fn node_meets<'n, V: Vector<Scalar = f32>, S: Source<'n, V>>(
    ray: &impl RayForm<V>,
    source: &S,
    search: Search<f32>,
) -> u32 {
    batch_query::<V, MaskOf<QuantizedKernel<'n, V, S>>>(ray, source, search, 0)
}

/// [`QuantizedChildren`]'s `clip` as a kernel on a node read from `S`, for
/// any instruction set (see `crate::simd`).
pub(crate) struct QuantizedKernel<'n, V, S>(PhantomData<(&'n V, S)>);

impl<'n, V: Vector<Scalar = f32>, S: Source<'n, V>> Kernel for QuantizedKernel<'n, V, S> {
    type Ray = PreparedRay<V>;
    type Shapes = S;
    /// `(t_min, t_max)`, as the box batch's.
    type Limit = (f32, f32);
    type Output = AabbBatchHits<f32, 8>;

    #[inline(always)]
    fn run<I: Isa>(_: I, ray: &PreparedRay<V>, node: &S, ends: (f32, f32)) -> Self::Output {
        quantized_body::<I::W<f32>, V>(ray, &node.view(), ends)
    }
}

/// One axis of a node: its origin `p`, step `s` and widening `w`.
#[derive(Clone, Copy)]
struct Axis {
    p: f32,
    s: f32,
    w: f32,
}

/// The three axes of `node`, computed side by side in the lanes of a
/// `Vec3A` once for the validity test and the decoding, and whether every
/// coordinate they decode is finite (the node is valid).
#[inline(always)]
fn axes_of<V: Vector<Scalar = f32>>(node: &QuantizedChildren<'_, V>) -> ([Axis; 3], bool) {
    let o = node.origin;
    let p = Vec3A::new(o.x(), o.y(), o.z());
    let [sx, sy, sz] = node.exponents.map(step_of);
    let s = Vec3A::new(sx, sy, sz);
    let w = widening(p, s);
    let max = Vec3A::splat(f32::MAX);
    let finite = ((p - w).abs().cmple(max) & ((p + s * 255.0) + w).cmple(max)).all();
    let axis = |k: usize| Axis {
        p: p[k],
        s: s[k],
        w: w[k],
    };
    ([axis(0), axis(1), axis(2)], finite)
}

/// Axis `k` of the eight children, decoded as `child_box` does: the lower
/// and upper planes, and which children are not empty on that axis.
/// (A function, not a closure: the AVX2 copy must be inlined whole.)
#[inline(always)]
fn decode<W: Lanes8<F = f32>, V: Vector<Scalar = f32>>(
    node: &QuantizedChildren<'_, V>,
    k: usize,
    axis: Axis,
) -> (W, W, W::Mask) {
    let (a, b) = (W::from_bytes(node.min[k]), W::from_bytes(node.max[k]));
    let (s, p, w) = (W::splat(axis.s), W::splat(axis.p), W::splat(axis.w));
    (a.mul(s).add(p).sub(w), b.mul(s).add(p).add(w), a.le(b))
}

/// The body of [`QuantizedChildren`]'s `clip` with the eight-lane type `W`.
#[inline(always)]
fn quantized_body<W: Lanes8<F = f32>, V: Vector<Scalar = f32>>(
    ray: &PreparedRay<V>,
    node: &QuantizedChildren<'_, V>,
    ends: (f32, f32),
) -> AabbBatchHits<f32, 8> {
    let mut enter = [f32::INFINITY; 8];
    let (axes, finite) = axes_of(node);
    // (One branch for the node's validity; the search's `t_max` was
    // checked at the call, `batch_query`.)
    if !finite {
        return AabbBatchHits::none();
    }
    let (x0, x1, ox) = decode::<W, V>(node, 0, axes[0]);
    let (y0, y1, oy) = decode::<W, V>(node, 1, axes[1]);
    let (z0, z1, oz) = decode::<W, V>(node, 2, axes[2]);
    let slab = Slab8::<W>::new(ray, ends);
    let (hit, e) = slab.test([x0, y0, z0], [x1, y1, z1]);
    let hit = W::and(hit, W::and(ox, W::and(oy, oz)));
    W::select(hit, e, W::splat(f32::INFINITY)).store(&mut enter);
    AabbBatchHits {
        mask: W::bits(hit),
        enter,
    }
}
