//! The timed loops the rows are built from: a pair at a time, a ray
//! against its group of shapes, every ray against every shape, the
//! nearest hit through a list, a batch row under `with_simd`, and the
//! instance and camera rows' loops that store every result in a buffer.
//! Also the orders in which the pairwise rows visit their pairs, and the
//! checksums that keep the compiler from dropping the work.

use std::cell::Cell;
use std::hint::black_box;

use rayhit::batch::{AabbBatch, Simd, SimdWork, TriangleBatch, TriangleBatchHits, with_simd};
use rayhit::glam::Vec3;
use rayhit::{Bounds, IntersectLanes, PreparedRay};
use rayhit_testkit::rng::Pcg32;
use rayhit_testkit::workloads::rate;

use super::INF;

/// The share of pairs on which `a` and `b` agree.
pub fn agree(a: impl IntoIterator<Item = bool>, b: impl IntoIterator<Item = bool>) -> f64 {
    rate(a.into_iter().zip(b).map(|(x, y)| x == y))
}

fn bits(x: f32) -> u64 {
    u64::from(x.to_bits())
}

/// The timed loop of a row: ray `i` against shapes `k i .. k (i + 1)`
/// (`k = per_ray`; 1 for the pairwise rows), the sum of `f`'s checksums.
pub fn chunked<'a, R, X>(
    rays: &'a [R],
    shapes: &'a [X],
    per_ray: usize,
    f: impl Fn(&R, &X) -> u64 + 'a,
) -> impl Fn() -> u64 + 'a {
    move || {
        let mut c = 0;
        for (r, g) in rays.iter().zip(shapes.chunks(per_ray)) {
            for x in g {
                c += f(r, x);
            }
        }
        c
    }
}

/// The orders in which a pairwise row visits its workload's ray/shape
/// pairs: each call of the row's loop (one pass) takes the next, in turn.
///
/// A pass that visits the same pairs in the same order every time is a
/// sequence of branch outcomes that the CPU's branch predictor learns over
/// the passes of a round: on the aimed rays, where about half of the tests
/// hit, the textbook Moller-Trumbore then ran 2.5 times as fast as on
/// rays it had not seen, and how much of a pass the predictor held changed
/// with where the code landed in memory. A renderer's rays do not repeat like
/// that. So the triangle pairs whose order carries no meaning (`random`,
/// `aimed`, `axis`) are visited in a fresh order on each pass: one of
/// [`ORDERS`] permutations, drawn once, each shuffling the pairs within
/// consecutive blocks of [`BLOCK`] (so that the data still streams through
/// the caches block by block). Camera rays keep their scanline order: the
/// coherence of neighbouring pixels is what that workload is about.
///
/// The box pairs keep their stored order: the box tests the goals compare
/// (rayhit's, the plain slab test, `bvh`'s, which branches only on NaN)
/// do not branch on their outcome, so there is little for the predictor
/// to learn, and a shuffled order only adds the cost of fetching each
/// pair's ray from the level-2 cache (the most for a 160-byte prepared
/// ray, which a traversal reuses instead). `--shuffle-all` shuffles them
/// too, `--same-order` nothing.
pub struct Orders {
    orders: Vec<Vec<u16>>,
    next: Cell<usize>,
}

/// How many shuffled orders a workload's passes cycle through.
const ORDERS: usize = 16;

/// The pairs are shuffled within consecutive blocks of this many.
const BLOCK: usize = 64;

impl Orders {
    pub fn new(pairs: usize, shuffle: bool) -> Self {
        let stored: Vec<u16> = (0..pairs)
            .map(|i| u16::try_from(i).expect("at most 65536 pairs"))
            .collect();
        let orders = if !shuffle {
            vec![stored]
        } else {
            let mut rng = Pcg32::with_stream(31, 7);
            (0..ORDERS)
                .map(|_| {
                    let mut o = stored.clone();
                    // Fisher-Yates, within each block.
                    for block in o.chunks_mut(BLOCK) {
                        for i in (1..block.len()).rev() {
                            let j = rng.below(i as u32 + 1) as usize;
                            block.swap(i, j);
                        }
                    }
                    o
                })
                .collect()
        };
        Self {
            orders,
            next: Cell::new(0),
        }
    }

    /// The order for the next pass.
    fn take(&self) -> &[u16] {
        let k = self.next.get();
        self.next.set((k + 1) % self.orders.len());
        &self.orders[k]
    }
}

/// A pairwise row's loop: ray `i` against shape `i`, for `i` in the next
/// of `order`'s orders (a plain loop where there is only the stored
/// order); the sum of `f`'s answers.
pub fn pairwise<'a, R, X>(
    order: &'a Orders,
    rays: &'a [R],
    shapes: &'a [X],
    f: impl Fn(&R, &X) -> u64 + 'a,
) -> impl Fn() -> u64 + 'a {
    move || {
        let mut c = 0;
        if order.orders.len() == 1 {
            // The stored order: a plain loop over the pairs.
            for (r, x) in rays.iter().zip(shapes) {
                c += f(r, x);
            }
        } else {
            for &i in order.take() {
                let i = usize::from(i);
                c += f(&rays[i], &shapes[i]);
            }
        }
        c
    }
}

/// A batch row's loop as `rayhit::SimdWork`: ray `i` against batches
/// `k i .. k (i + 1)` (`k = per_ray`), or, for boxes, every ray against
/// every batch (`per_ray = 0`); the checksum of the hit masks (boxes) or
/// of the hit lanes' `t` (triangles). Written out, without closures, so that
/// `with_simd` compiles it, kernels included, for the CPU's widest SIMD.
pub struct BatchRows<'a, B> {
    pub rays: &'a [PreparedRay],
    pub batches: &'a [B],
    pub per_ray: usize,
}

impl<'a, B> Clone for BatchRows<'a, B> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<'a, B> Copy for BatchRows<'a, B> {}

impl<const N: usize> SimdWork for BatchRows<'_, AabbBatch<Vec3, N>> {
    type Output = u64;
    #[inline(always)]
    fn run<I: Simd>(self, simd: I) -> u64 {
        let mut c = 0;
        if self.per_ray == 0 {
            for r in self.rays {
                for b in self.batches {
                    c += u64::from(b.clip(&simd.ray(r), INF).mask);
                }
            }
        } else {
            for (r, group) in self
                .rays
                .iter()
                .zip(self.batches.chunks_exact(self.per_ray))
            {
                for b in group {
                    c += u64::from(b.clip(&simd.ray(r), INF).mask);
                }
            }
        }
        c
    }
}

impl<const N: usize> SimdWork for BatchRows<'_, TriangleBatch<Vec3, N>> {
    type Output = u64;
    #[inline(always)]
    fn run<I: Simd>(self, simd: I) -> u64 {
        let mut c = 0;
        for (r, group) in self
            .rays
            .iter()
            .zip(self.batches.chunks_exact(self.per_ray))
        {
            for b in group {
                c += batch_t_sum(&b.hit(&simd.ray(r), INF));
            }
        }
        c
    }
}

/// The timed loop of a `with_simd` row.
pub fn simd<'a, W: SimdWork<Output = u64> + Copy + 'a>(work: W) -> impl Fn() -> u64 + 'a {
    move || with_simd(work)
}

/// The timed loop of a sweep row: every ray against all of `shapes`.
pub fn every<'a, R, X>(
    rays: &'a [R],
    shapes: &'a [X],
    f: impl Fn(&R, &X) -> u64 + 'a,
) -> impl Fn() -> u64 + 'a {
    move || {
        let mut c = 0;
        for r in rays {
            for x in shapes {
                c += f(r, x);
            }
        }
        c
    }
}

/// The timed loop of a nearest-hit sweep row: every ray through all of
/// `shapes` in order, `f` given the nearest distance so far as its limit
/// (the way a BVH leaf culls); the checksum of each ray's nearest hit.
pub fn nearest<'a, R, X>(
    rays: &'a [R],
    shapes: &'a [X],
    f: impl Fn(&R, &X, f32) -> Option<f32> + 'a,
) -> impl Fn() -> u64 + 'a {
    move || {
        let mut c = 0;
        for r in rays {
            let mut t_max = INF;
            for x in shapes {
                if let Some(t) = f(r, x, t_max) {
                    t_max = t_max.min(t);
                }
            }
            c += bits(t_max);
        }
        c
    }
}

/// The checksum of a triangle batch's hits: every hit lane's `t`.
pub fn batch_t_sum<const N: usize>(h: &TriangleBatchHits<f32, N>) -> u64 {
    lanes_t_sum(h.mask, &h.t)
}

/// The checksum of the `t` of the lanes set in `mask`.
pub fn lanes_t_sum(mask: u32, t: &[f32]) -> u64 {
    let mut c = 0;
    let mut m = mask;
    while m != 0 {
        c += bits(t[m.trailing_zeros() as usize]);
        m &= m - 1;
    }
    c
}

/// The checksum of a hit's `t`, 0 for a miss.
pub fn t_sum(t: Option<f32>) -> u64 {
    t.map_or(0, bits)
}

/// Every (instance, item) pair through `f`, stored in a buffer; one
/// value's checksum returned.
pub fn over_pairs<'a, I: 'a, X: 'a, T: 'a>(
    instances: &'a [I],
    items: &'a [X],
    f: impl Fn(&I, &X) -> T + 'a,
    sum: fn(&T) -> u64,
) -> impl Fn() -> u64 + 'a {
    // (Cleared and refilled each pass, within its capacity: the same
    // for every row.)
    let buffer = std::cell::RefCell::new(Vec::with_capacity(instances.len() * items.len()));
    move || {
        let mut out = buffer.borrow_mut();
        out.clear();
        for i in instances {
            for x in items {
                out.push(f(i, x));
            }
        }
        black_box(&mut *out);
        sum(&out[out.len() / 2])
    }
}

/// A camera row's loop: `f` at every position of `order` (with its lens
/// sample), each result stored in a buffer, as a renderer stores the rays
/// of a tile or a wavefront before tracing them; then the buffer is handed
/// to `black_box` (so that no store is left out) and one value of it
/// returned. Generic, so that the camera's code is inlined into the loop
/// as a renderer's would be.
pub fn over<'a, T: Copy + Default + 'a>(
    order: &'a [(f32, f32)],
    lens: &'a [(f32, f32)],
    f: impl Fn(f32, f32, (f32, f32)) -> T + 'a,
    sum: fn(&T) -> u64,
) -> impl Fn() -> u64 + 'a {
    let buffer = std::cell::RefCell::new(vec![T::default(); order.len()]);
    move || {
        let mut out = buffer.borrow_mut();
        fill(order, lens, &mut out, &f);
        black_box(&mut *out);
        sum(&out[out.len() / 2])
    }
}

/// The camera rows' loop: `f` at every position, into `out`. A function
/// of its own, as a renderer's loop over a tile writes into a slice it was
/// given: `out` is then known not to overlap the camera, so the camera's
/// fields stay in registers and the compiler may compute several rays at
/// once. (Written inside the closure of [`over`], the buffer behind its
/// `RefCell` might overlap the camera in the closure as far as the
/// compiler knows.)
#[inline(never)]
fn fill<T>(
    order: &[(f32, f32)],
    lens: &[(f32, f32)],
    out: &mut [T],
    f: &impl Fn(f32, f32, (f32, f32)) -> T,
) {
    for ((p, l), slot) in order.iter().zip(lens).zip(out.iter_mut()) {
        *slot = f(p.0, p.1, *l);
    }
}
