//! The watertight triangle test's per-ray part: the axis the ray mostly
//! runs along, the permutation that makes it `z`, and the shear that maps
//! the direction to `+z` (Woop, Benthin and Wald, JCGT 2013).

use crate::num::{Axis, Lanes, Scalar, Vector};

/// The per-ray part of the watertight test: which axis the ray mostly runs
/// along, and the shear that maps its direction to `+z`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Shear<F: Scalar> {
    /// The axis of the direction's largest magnitude component; `kx, ky`
    /// follow it cyclically, so the permutation keeps the handedness.
    pub(crate) kx: Axis,
    pub(crate) ky: Axis,
    pub(crate) kz: Axis,
    /// `-d_x / d_z` and `-d_y / d_z` in the permuted frame: `|s_x|, |s_y| <= 1`.
    pub(crate) sx: F,
    pub(crate) sy: F,
    /// `1 / d_z`.
    pub(crate) sz: F,
    /// `d_z` itself, for the side of a hit.
    pub(crate) dz: F,
}

impl<F: Scalar> PartialEq for Shear<F> {
    fn eq(&self, o: &Self) -> bool {
        (self.kz, self.sx, self.sy, self.sz, self.dz) == (o.kz, o.sx, o.sy, o.sz, o.dz)
    }
}

/// The index of the ray's main axis from the magnitudes of its direction's
/// components: x if `|d_x| > |d_y|` and `|d_x| > |d_z|`, else y if
/// `|d_y| > |d_z|`, else z. Written as selects rather than branches (the
/// direction of the next ray is not predictable).
#[inline(always)]
pub(crate) fn largest_axis<F: Scalar>(a: [F; 3]) -> usize {
    let x_wins = a[0] > a[1];
    let larger = if x_wins { a[0] } else { a[1] };
    if larger > a[2] {
        usize::from(!x_wins)
    } else {
        2
    }
}

impl<F: Scalar> Shear<F> {
    #[inline(always)]
    pub(crate) fn new<V: Vector<Scalar = F>>(dir: &V) -> Self {
        Self::of([dir.x(), dir.y(), dir.z()])
    }

    /// [`Shear::new`] of the direction `d`, given as its components.
    #[inline(always)]
    pub(crate) fn of(d: [F; 3]) -> Self {
        let k = largest_axis(d.map(F::abs));
        let (kz, kx, ky) = (
            Axis::from_index(k),
            Axis::from_index(if k == 2 { 0 } else { k + 1 }),
            Axis::from_index(if k == 0 { 2 } else { k - 1 }),
        );
        let (dx, dy, dz) = (d[kx as usize], d[ky as usize], d[kz as usize]);
        // Three quotients, each rounded once, in one division of lanes.
        let q = F::L4::new(-dx, -dy, F::ONE).div(F::L4::splat(dz));
        let [sx, sy, sz] = q.to_array();
        Self {
            kx,
            ky,
            kz,
            sx,
            sy,
            sz,
            dz,
        }
    }

    /// `sx`, `sy`, `sz`, each in every lane: what the lanes form of the
    /// test multiplies by.
    #[inline(always)]
    pub(crate) fn lanes(&self) -> [F::L4; 3] {
        [
            F::L4::splat(self.sx),
            F::L4::splat(self.sy),
            F::L4::splat(self.sz),
        ]
    }

    /// `(v[kx], v[ky], v[kz])`.
    #[inline(always)]
    pub(crate) fn permute<V: Vector<Scalar = F>>(&self, v: V) -> (F, F, F) {
        (v.get(self.kx), v.get(self.ky), v.get(self.kz))
    }

    /// `origin[kx]`, `origin[ky]`, `origin[kz]`, each in every lane: what
    /// the lanes form of the test subtracts from the corners.
    #[inline(always)]
    pub(crate) fn origin_lanes<V: Vector<Scalar = F>>(&self, origin: V) -> [F::L4; 3] {
        self.origin_lanes_of([origin.x(), origin.y(), origin.z()])
    }

    /// [`Shear::origin_lanes`] of the origin's components.
    #[inline(always)]
    pub(crate) fn origin_lanes_of(&self, o: [F; 3]) -> [F::L4; 3] {
        let (x, y, z) = (
            o[self.kx as usize],
            o[self.ky as usize],
            o[self.kz as usize],
        );
        [F::L4::splat(x), F::L4::splat(y), F::L4::splat(z)]
    }
}
