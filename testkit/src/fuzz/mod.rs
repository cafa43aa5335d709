//! The checks behind rayhit's fuzz targets: `cargo fuzz` runs them on the
//! inputs libFuzzer makes (`fuzz/fuzz_targets/`, each the same one line:
//! [`run`] with its binary's name), and `cargo test` on every checked-in
//! seed and saved crash (`tests/fuzz_replay.rs`). [`TARGETS`] maps each
//! target's name (its `[[bin]]` in `fuzz/Cargo.toml`, the list of targets)
//! to its check.
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
//! round-trip exactly), ready to paste into `tests/suite/<subject>/fuzz_regressions.rs`.

use arbitrary::{Arbitrary, Unstructured};
use rayhit::glam::{DVec3, Vec3};
use rayhit::{Scalar, Vector};

use crate::source::Source;

pub mod aabb;
pub mod batch;
pub mod camera;
pub mod disc;
pub mod exact;
pub mod hit_differentials;
pub mod instance;
pub mod interval;
pub mod matrix_camera;
pub mod orthographic;
pub mod panoramic;
pub mod patch;
pub mod plane;
pub mod quad;
pub mod spawn;
pub mod spawn_to;
pub mod sphere;
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

/// A fuzz target: its name and its check, which runs on one input's bytes.
pub type Target = (&'static str, fn(&[u8]));

/// Every fuzz target's check, by the target's name: the name of its
/// `[[bin]]` in `fuzz/Cargo.toml`, which lists the targets `cargo fuzz`
/// builds and CI runs. Each target's file in `fuzz/fuzz_targets/` runs the
/// check listed here under its name ([`run`]); `tests/fuzz_replay.rs` runs
/// it on the target's seeds and saved crashes, and fails when a `[[bin]]`
/// has no entry here or an entry has no `[[bin]]`. Each check's module
/// documents its input layout and what it checks.
pub const TARGETS: &[Target] = &[
    // `ray_aabb`, the prepared clip and the entry face.
    ("aabb", dispatch::<aabb::Slab>),
    // The slab test against the naive per-face one.
    ("aabb_slab_vs_naive", dispatch::<aabb::SlabVsNaive>),
    // The batch kernels against the scalar ones, lane by lane.
    ("batch", dispatch::<batch::Batch>),
    // The pinhole camera.
    ("camera", dispatch::<camera::Camera>),
    // The disc and annulus over a `t_max` and over an interval, its error
    // bound, its surface point and its box.
    ("disc", dispatch::<disc::DiscCheck>),
    // The panoramic cameras.
    ("equal_area", dispatch::<panoramic::EqualArea>),
    ("equirectangular", dispatch::<panoramic::Equirectangular>),
    // The README's example target: a user's kernel held to `rayhit::exact`
    // (its own file, compiled here as `cargo fuzz` builds it).
    ("exact_judge", exact_judge::run),
    // A camera ray's differentials transferred to a triangle hit.
    (
        "hit_differentials",
        dispatch::<hit_differentials::HitDifferentialsCheck>,
    ),
    // Instance transforms: world boxes and the ray map's bound.
    ("instance", dispatch::<instance::InstanceCheck>),
    // The interval forms over a window cut in two: every crossing reported
    // by exactly one half.
    ("interval", dispatch::<interval::IntervalCheck>),
    // The camera from a view and a projection matrix.
    (
        "matrix_camera",
        dispatch::<matrix_camera::MatrixCameraCheck>,
    ),
    // The orthographic camera.
    ("orthographic", dispatch::<orthographic::Orthographic>),
    // The bilinear patch, every ray form, rule and range, and its
    // degenerate forms against the triangle and the quad they are.
    ("patch", dispatch::<patch::PatchCheck>),
    // `ray_plane` and the plane's error bound.
    ("plane", dispatch::<plane::PlaneCheck>),
    // The quad against its two triangles, every ray form, rule and range.
    ("quad", dispatch::<quad::QuadCheck>),
    // Rays spawned off a triangle or a plane.
    ("spawn", dispatch::<spawn::Spawn>),
    // Shadow-ray segments between two surface points, or to a point light:
    // neither end's surface reported over `(0, 1]`.
    ("spawn_to", dispatch::<spawn_to::SpawnTo>),
    // The sphere over a `t_max` and over an interval, its error bound and
    // its surface point.
    ("sphere", dispatch::<sphere::SphereCheck>),
    // The thin-lens camera.
    ("thin_lens", dispatch::<thin_lens::ThinLens>),
    // The watertight ray/triangle test.
    ("triangle", dispatch::<triangle::Watertight>),
    // The watertight test against Moller-Trumbore.
    (
        "triangle_watertight_vs_mt",
        dispatch::<triangle::WatertightVsMt>,
    ),
];

/// The check of the fuzz target `name`, if [`TARGETS`] lists it.
///
/// ```
/// use rayhit_testkit::fuzz;
/// let check = fuzz::check("aabb").expect("a target");
/// check(&[0, 1, 2, 3]);
/// assert!(fuzz::check("no_such_target").is_none());
/// ```
pub fn check(name: &str) -> Option<fn(&[u8])> {
    TARGETS
        .iter()
        .find(|(target, _)| *target == name)
        .map(|&(_, check)| check)
}

/// Runs the check of the fuzz target `name` ([`TARGETS`]) on `data`: the
/// body of every file in `fuzz/fuzz_targets/` (but the README's example,
/// `exact_judge`), with its binary's name.
///
/// # Panics
///
/// When the check fails (what a fuzz target reports), and when [`TARGETS`]
/// has no target `name`.
///
/// ```
/// rayhit_testkit::fuzz::run("plane", &[2, 0x5a, 0x5a, 0x5a]);
/// ```
pub fn run(name: &str, data: &[u8]) {
    let check = check(name)
        .unwrap_or_else(|| panic!("fuzz target {name}: no entry in rayhit_testkit::fuzz::TARGETS"));
    check(data);
}

/// The README's example target (`fuzz/fuzz_targets/exact_judge.rs`) as
/// `cargo fuzz` builds it, without the two lines only `cargo fuzz` can
/// compile (see the kit's `build.rs`).
mod exact_judge {
    /// `fuzz_target!` as libfuzzer-sys expands it for a typed input: too
    /// short an input, or one `arbitrary` rejects, is skipped.
    macro_rules! fuzz_target {
        (|$input:ident: $ty:ty| $body:block) => {
            pub fn run(bytes: &[u8]) {
                use arbitrary::{Arbitrary, Unstructured};
                if bytes.len() < <$ty as Arbitrary>::size_hint(0).0 {
                    return;
                }
                if let Ok($input) =
                    <$ty as Arbitrary>::arbitrary_take_rest(Unstructured::new(bytes))
                {
                    $body
                }
            }
        };
    }
    include!(concat!(env!("OUT_DIR"), "/exact_judge.rs"));
}

/// Reads one raw-bit value of `T`, or its default when the data has run out
/// (arbitrary already zero-fills; this only spares the `Result`).
pub fn raw<'a, T: Arbitrary<'a> + Default>(u: &mut Unstructured<'a>) -> T {
    T::arbitrary(u).unwrap_or_default()
}

/// The checks every shape's target makes on both forms of its `hit`:
/// the `t_max` form and the interval form over `(lo, hi]` (where
/// `Interval::new` takes the ends) give the same answers, bit for bit, on
/// a prepared ray; a hit's `t` (from `t_of`) is finite and in range; and
/// only a `hittable` input (and a `t_max` at least zero) is hit. Returns
/// both answers.
#[allow(clippy::too_many_arguments)]
pub fn forms_in_range<V, X>(
    shape: &X,
    ray: &rayhit::Ray<V>,
    t_max: S<V>,
    (lo, hi): (S<V>, S<V>),
    hittable: bool,
    t_of: impl Fn(&X::Hit) -> S<V>,
    ctx: &dyn Fn() -> String,
) -> (Option<X::Hit>, Option<X::Hit>)
where
    V: Vector,
    X: rayhit::Intersect<V>,
    X::Hit: PartialEq + core::fmt::Debug,
{
    let zero = S::<V>::ZERO;
    let prepared = rayhit::PreparedRay::new(ray);
    let got = shape.hit(ray, t_max);
    assert_eq!(got, shape.hit(&prepared, t_max), "prepared ray: {}", ctx());
    if let Some(h) = &got {
        let t = t_of(h);
        assert!(
            t > zero && t <= t_max && t.is_finite(),
            "t_max form: {h:?} out of range: {}",
            ctx()
        );
        assert!(hittable && t_max >= zero, "hit on invalid input: {}", ctx());
    }
    let got_in = rayhit::Interval::new(lo, hi).and_then(|w| {
        let h = shape.hit(ray, w);
        assert_eq!(h, shape.hit(&prepared, w), "prepared ray: {}", ctx());
        h
    });
    if let Some(h) = &got_in {
        let t = t_of(h);
        assert!(
            lo < t && t <= hi && t.is_finite(),
            "interval form: {h:?} out of range: {}",
            ctx()
        );
        assert!(hittable, "hit on invalid input: {}", ctx());
    }
    (got, got_in)
}

/// Two interval ends drawn around a case's reported `crossings`: each
/// `0`, infinity, a crossing, a float neighbour of one, or a value up to
/// twice the farthest crossing (at least 1); in order.
pub fn ends_near<F: Scalar>(src: &mut Source, crossings: &[F]) -> (F, F) {
    let mut near = vec![F::ZERO, F::INFINITY];
    near.extend_from_slice(crossings);
    let far = crossings
        .iter()
        .fold(F::ONE, |m, &t| if t > m { t } else { m });
    let mut end = || {
        let base = near[src.index(near.len())];
        match src.index(4) {
            0 => base,
            1 => base.next_up(),
            2 => base.next_down(),
            _ => far * F::from_f64(src.range(0.0, 2.0)),
        }
    };
    let (a, b) = (end(), end());
    if b < a { (b, a) } else { (a, b) }
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
/// `tests/suite/<subject>/fuzz_regressions.rs`). Raw-bit inputs hold a
/// kernel to its bounds only where every product it forms passes this.
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
