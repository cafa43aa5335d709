//! The checks behind rayhit's fuzz targets: `cargo fuzz` runs them on the
//! inputs libFuzzer makes (`fuzz/fuzz_targets/`, each a one-line wrapper),
//! and `cargo test` on every checked-in seed and saved crash
//! (`tests/fuzz_replay.rs`).
//!
//! Every target reads its first byte as the mode (`byte % 4`), and the rest
//! as raw bits (`arbitrary::Unstructured`) or as the choices of a
//! [`Source`] (the case generators of [`crate::cases`]):
//!
//! | mode | precision | inputs |
//! | --- | --- | --- |
//! | 0 | `f32` | raw: every float a raw bit pattern (the crate's `arbitrary` impls) |
//! | 1 | `f64` | raw |
//! | 2 | `f32` | structured: realistic ranges, rays aimed at faces, edges and corners ([`crate::cases`]) |
//! | 3 | `f64` | structured |
//!
//! Raw inputs check what holds for any input: no panic, `None` or a finite
//! `t` in range (never NaN), invalid input rejected, and the exact-oracle
//! guarantees wherever the documented preconditions hold (checked exactly).
//! Structured inputs check the invariants in detail: exact-oracle agreement
//! within the documented bounds, hit points on the surface, slab against
//! naive, watertight against Moller-Trumbore, closed meshes that never leak,
//! spawned rays that never re-hit, shadow-ray segments that hit neither end.
//!
//! A failed check panics with the input printed as `Debug` floats (which
//! round-trip exactly), ready to paste into `tests/suite/fuzz_regressions.rs`.

use arbitrary::{Arbitrary, Unstructured};
use rayhit::glam::{DVec3, Vec3};
use rayhit::{Scalar, Vector};

use crate::source::Source;

pub mod aabb;
pub mod batch;
pub mod camera;
pub mod exact;
pub mod hit_differentials;
pub mod instance;
pub mod interval;
pub mod matrix_camera;
pub mod orthographic;
pub mod panoramic;
pub mod plane;
pub mod spawn;
pub mod spawn_to;
pub mod thin_lens;
pub mod triangle;

/// The scalar of a vector type.
pub type S<V> = <V as Vector>::Scalar;

/// A target's input after the mode byte (see the module docs).
pub enum Input<'a> {
    /// Raw bit patterns.
    Raw(Unstructured<'a>),
    /// Realistic ranges aimed at boundaries: the choices of the case
    /// generators, read from the bytes.
    Structured(Box<Source>),
}

impl Input<'_> {
    /// True for structured input.
    pub fn is_structured(&self) -> bool {
        matches!(self, Input::Structured(_))
    }
}

/// What a target does with one precision: `run::<Vec3>` or `run::<DVec3>`.
pub trait Check {
    /// Runs the checks on `input`.
    fn run<'a, V>(input: &mut Input<'a>)
    where
        V: Vector,
        S<V>: Arbitrary<'a> + Scalar;
}

/// Splits off the mode byte and runs `C` in the chosen precision and mode.
pub fn dispatch<C: Check>(data: &[u8]) {
    let Some((&mode, rest)) = data.split_first() else {
        return;
    };
    let mut input = if mode % 4 < 2 {
        Input::Raw(Unstructured::new(rest))
    } else {
        Input::Structured(Box::new(Source::from_bytes(rest)))
    };
    if mode % 2 == 0 {
        C::run::<Vec3>(&mut input);
    } else {
        C::run::<DVec3>(&mut input);
    }
}

/// The entry points of the fuzz targets, one per target.
pub mod targets {
    use super::*;

    /// `camera`: [`camera::Camera`].
    pub fn camera(data: &[u8]) {
        dispatch::<camera::Camera>(data);
    }
    /// `plane`: [`plane::PlaneCheck`].
    pub fn plane(data: &[u8]) {
        dispatch::<plane::PlaneCheck>(data);
    }
    /// `aabb`: [`aabb::Slab`].
    pub fn aabb(data: &[u8]) {
        dispatch::<aabb::Slab>(data);
    }
    /// `aabb_slab_vs_naive`: [`aabb::SlabVsNaive`].
    pub fn aabb_slab_vs_naive(data: &[u8]) {
        dispatch::<aabb::SlabVsNaive>(data);
    }
    /// `triangle`: [`triangle::Watertight`].
    pub fn triangle(data: &[u8]) {
        dispatch::<triangle::Watertight>(data);
    }
    /// `triangle_watertight_vs_mt`: [`triangle::WatertightVsMt`].
    pub fn triangle_watertight_vs_mt(data: &[u8]) {
        dispatch::<triangle::WatertightVsMt>(data);
    }
    /// `spawn`: [`spawn::Spawn`].
    pub fn spawn(data: &[u8]) {
        dispatch::<spawn::Spawn>(data);
    }
    /// `spawn_to`: [`spawn_to::SpawnTo`].
    pub fn spawn_to(data: &[u8]) {
        dispatch::<spawn_to::SpawnTo>(data);
    }
    /// `batch`: [`batch::Batch`].
    pub fn batch(data: &[u8]) {
        dispatch::<batch::Batch>(data);
    }
    /// `equirectangular`: [`panoramic::Equirectangular`].
    pub fn equirectangular(data: &[u8]) {
        dispatch::<panoramic::Equirectangular>(data);
    }
    /// `equal_area`: [`panoramic::EqualArea`].
    pub fn equal_area(data: &[u8]) {
        dispatch::<panoramic::EqualArea>(data);
    }
    /// `hit_differentials`: [`hit_differentials::HitDifferentialsCheck`].
    pub fn hit_differentials(data: &[u8]) {
        dispatch::<hit_differentials::HitDifferentialsCheck>(data);
    }
    /// `interval`: [`interval::IntervalCheck`].
    pub fn interval(data: &[u8]) {
        dispatch::<interval::IntervalCheck>(data);
    }
    /// `matrix_camera`: [`matrix_camera::MatrixCameraCheck`].
    pub fn matrix_camera(data: &[u8]) {
        dispatch::<matrix_camera::MatrixCameraCheck>(data);
    }
    /// `instance`: [`instance::InstanceCheck`].
    pub fn instance(data: &[u8]) {
        dispatch::<instance::InstanceCheck>(data);
    }
    /// `orthographic`: [`orthographic::Orthographic`].
    pub fn orthographic(data: &[u8]) {
        dispatch::<orthographic::Orthographic>(data);
    }
    /// `thin_lens`: [`thin_lens::ThinLens`].
    pub fn thin_lens(data: &[u8]) {
        dispatch::<thin_lens::ThinLens>(data);
    }
}

/// Reads one raw-bit value of `T`, or its default when the data has run out
/// (arbitrary already zero-fills; this only spares the `Result`).
pub fn raw<'a, T: Arbitrary<'a> + Default>(u: &mut Unstructured<'a>) -> T {
    T::arbitrary(u).unwrap_or_default()
}

/// Reads a vector of raw-bit components (`x`, `y`, `z`).
pub fn raw_vec<'a, V>(u: &mut Unstructured<'a>) -> V
where
    V: Vector,
    S<V>: Arbitrary<'a> + Default,
{
    let x = raw::<S<V>>(u);
    let y = raw::<S<V>>(u);
    let z = raw::<S<V>>(u);
    V::new(x, y, z)
}

/// True when `x` is zero or so far above the subnormal range that `x` times
/// any `gamma(n)` is still normal: `|x| >= MIN_POSITIVE * 2^(2p)` with `p`
/// the precision (24 or 53 bits).
///
/// The crate's error bounds are relative-error arguments; they say "no
/// intermediate overflow" but also need no intermediate underflow (see
/// tests/suite/fuzz_regressions.rs). Raw-bit inputs hold a kernel to its bounds
/// only where every product it forms passes this.
pub fn far_from_underflow<F: Scalar>(x: F) -> bool {
    let margin = F::ONE / (F::UNIT_ROUNDOFF * F::UNIT_ROUNDOFF);
    x == F::ZERO || x.abs() >= F::MIN_POSITIVE * margin
}

/// [`far_from_underflow`] for a product: exact zero (a zero factor) or
/// far from underflow.
pub fn product_far_from_underflow<F: Scalar>(a: F, b: F) -> bool {
    a == F::ZERO || b == F::ZERO || (far_from_underflow(a * b) && a * b != F::ZERO)
}

/// [`far_from_underflow`] for a quotient: an exact zero (a zero numerator)
/// or a nonzero quotient far from underflow.
pub fn quotient_far_from_underflow<F: Scalar>(a: F, b: F) -> bool {
    a == F::ZERO || (far_from_underflow(a / b) && a / b != F::ZERO)
}
