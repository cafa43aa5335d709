//! A batch's rows (one coordinate of `N` shapes, structure-of-arrays) read
//! and written eight lanes at a time.
//!
//! The kernels on eight lanes call only functions marked
//! `#[inline(always)]`, never closures: an instruction set's copy of a
//! kernel must be inlined, whole, into the function compiled for it.

use crate::num::{Lanes8, Scalar};

/// Checks `1 <= N <= 32` at compile time (the hit masks are `u32`).
pub(crate) const fn check_lanes<const N: usize>() {
    assert!(N >= 1 && N <= 32, "a batch has 1 to 32 lanes");
}

/// Lanes `8 c .. 8 c + 8` of `row`, lanes past its end NaN.
#[inline(always)]
pub(crate) fn lanes_at<W: Lanes8, const N: usize>(row: &[W::F; N], c: usize) -> W
where
    W::F: Scalar,
{
    match row.get(8 * c..8 * c + 8) {
        Some(full) => W::load(full.try_into().expect("8 lanes")),
        None => W::load(&core::array::from_fn(|l| {
            row.get(8 * c + l).copied().unwrap_or(W::F::NAN)
        })),
    }
}

/// Stores lanes `8 c .. 8 c + 8` of `row` from `lanes` (those that exist).
#[inline(always)]
pub(crate) fn put<W: Lanes8, const N: usize>(row: &mut [W::F; N], c: usize, lanes: W)
where
    W::F: Scalar,
{
    if let Some(full) = row.get_mut(8 * c..8 * c + 8) {
        lanes.store(full.try_into().expect("8 lanes"));
    } else {
        let mut a = [W::F::ZERO; 8];
        lanes.store(&mut a);
        for (l, x) in a.into_iter().enumerate() {
            if let Some(slot) = row.get_mut(8 * c + l) {
                *slot = x;
            }
        }
    }
}
