//! The reference corpus: checked-in inputs (exact bit patterns, in hex) with
//! the exactly decided answers, one file per kernel and precision under
//! `corpus/data/`. Every current answer is held to it:
//!
//! - hit or miss must match the exact answer wherever the case is marked
//!   `clear` (outside the documented rounding band); the slab test must hit
//!   every exact hit, `clear` or not;
//! - every reported distance must be within its documented bound of the
//!   exact one (stored rounded to nearest, so half an ulp is added):
//!   the slab entry within `gamma(3)` of it and the exit at least the exact
//!   exit and at most `1 + 16u` times it; the naive test's within `gamma(2)`
//!   where its faces are unambiguous; the watertight test's `t`, `u`, `v`
//!   within `Triangle::hit_error`; the plane's `t` within
//!   `Plane::hit_error`;
//! - spheres and discs: each line is the one the oracle writes for its
//!   inputs today (answer and band); `Sphere::hit` and `Disc::hit` with a
//!   `t_max`, judged by `exact::judge`, right with the right side on every
//!   `clear` case, and their `t` within `hit_error` of the exact crossing
//!   on the side they report; over `(0, t_max]` as an interval, hit or
//!   miss as the exact answer on every case (the side too where the bound
//!   is finite);
//! - quads and bilinear patches: each line is the one the oracle writes
//!   for its inputs today; `Quad::hit` and `Patch::hit` with a `t_max`, on
//!   a plain and a prepared ray (bit for bit the same) and over `(0,
//!   t_max]` as an interval, hit or miss as the exact answer with the
//!   exact side on every `clear` case, `t`, `u`, `v` within `hit_error` of
//!   the exact answer's there, and of some exact crossing of the shape
//!   extended on `edge` cases (where what the kernel did is tallied and
//!   printed with `--nocapture`);
//! - every transferred ray differential at a triangle hit (each component of
//!   `dp_dx`, `dp_dy` and `du_dx` ... `dv_dy`) within
//!   `Triangle::hit_differentials_error` of the exact transfer;
//! - every instance's world box (`Instance::object_to_world_box`) contains
//!   the exact image of the object box (stored rounded outward, so the
//!   comparison is exact) and is at most `16 u` of the terms' magnitudes
//!   wider; every world point of an exact object point
//!   (`Instance::surface_to_world`) within its `point_error` of the exact
//!   image (stored rounded to nearest, so half an ulp is added);
//! - over an interval `(t_min, t_max]` (ends at and around the exact
//!   crossing): `Triangle::hit` hits only where the exact plane crossing
//!   is in the interval, and as the exact answer where the inside test is
//!   clear of rounding, its prepared, batch and any-hit forms alike;
//!   `Plane::hit` hits exactly as the exact answer; each `t` in the
//!   interval and within its bound of the exact one (or of the float above
//!   `t_min`).
//!
//! Regenerate only for a deliberate change of guarantee (see CONTRIBUTING.md):
//! `RAYHIT_REGENERATE_CORPUS=1 cargo test --release -p rayhit-corpus --test corpus`
//! for every file, or `RAYHIT_REGENERATE_CORPUS=triangle_interval,plane_interval`
//! (a list of kernels) for those files alone.

use std::fmt::Write as _;
use std::path::PathBuf;

use num_traits::Signed;
use rayhit::exact::{self, CorpusLine};
use rayhit::glam::{DVec3, Vec3};
use rayhit::{
    Aabb, BoxFace, Disc, DiscHit, Instance, IntersectLanes, Plane, Ray, Scalar, Side, Sphere,
    SphereHit, SurfacePoint, Triangle, Vector, camera::RayDifferential, ray_aabb, ray_plane,
    ray_triangle,
};
use rayhit::{EdgeRule, Intersect, Surface};
use rayhit_testkit::cases::Generator;
use rayhit_testkit::cases::boxes;
use rayhit_testkit::cases::boxes::BoxCase;
use rayhit_testkit::cases::instances;
use rayhit_testkit::cases::planes;
use rayhit_testkit::cases::triangles::{self, TriCase};
use rayhit_testkit::cases::{discs, spheres};
use rayhit_testkit::cases::{patches, quads};
use rayhit_testkit::oracle;
use rayhit_testkit::oracle::{R, gamma, r, rv};
use rayhit_testkit::source::Source;
use std::cmp::Ordering;

type S<V> = <V as Vector>::Scalar;

/// Cases per kernel and precision.
const CASES: usize = 2048;

/// Whether to regenerate `kernel`'s files: `RAYHIT_REGENERATE_CORPUS` is
/// `1` or `all` for every file, or a comma-separated list of kernels
/// (`triangle_interval,plane_interval`) for those alone, so that the other
/// files, drawn by generators that may have changed since, stay as they
/// are.
fn regenerate(kernel: &str) -> bool {
    let Some(value) = std::env::var_os("RAYHIT_REGENERATE_CORPUS") else {
        return false;
    };
    let value = value.to_string_lossy();
    value == "1" || value == "all" || value.split(',').any(|k| k.trim() == kernel)
}

fn path(kernel: &str, precision: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("data")
        .join(format!("{kernel}_{precision}.txt"))
}

fn precision<V: Vector>() -> &'static str {
    if S::<V>::UNIT_ROUNDOFF.to_f64() > 1e-10 {
        "f32"
    } else {
        "f64"
    }
}

// ----------------------------------------------------------- bit patterns

/// A float as its IEEE bit pattern in hex (8 digits for f32, 16 for f64):
/// exact, `-0.0` included. (The library's corpus reader,
/// `exact::parse_bits`, reads it back.)
fn hex<F: Scalar>(x: F) -> String {
    if F::UNIT_ROUNDOFF.to_f64() > 1e-10 {
        format!("{:08x}", (x.to_f64() as f32).to_bits())
    } else {
        format!("{:016x}", x.to_f64().to_bits())
    }
}

fn hex_v<V: Vector>(v: V) -> String {
    format!("{} {} {}", hex(v.x()), hex(v.y()), hex(v.z()))
}

/// The float of precision `F` nearest to an exact value.
fn nearest<F: Scalar>(x: &R) -> F {
    let c = F::from_f64(oracle::to_f64(x));
    [c.next_down(), c, c.next_up()]
        .into_iter()
        .filter(|y| y.is_finite())
        .min_by(|a, b| (r(*a) - x).abs().cmp(&(r(*b) - x).abs()))
        .unwrap_or(c)
}

/// One ulp of `x` (the gap to the next float up), exactly.
fn ulp<F: Scalar>(x: F) -> R {
    let a = x.abs();
    r(a.next_up()) - r(a)
}

// ------------------------------------------------------------------ files

fn write(kernel: &str, precision: &str, header: &str, lines: &[String]) {
    let mut text = String::new();
    writeln!(text, "# rayhit reference corpus: {kernel}, {precision}").unwrap();
    writeln!(
        text,
        "# Generated from the exact oracle; regenerate only for a deliberate change of"
    )
    .unwrap();
    writeln!(
        text,
        "# guarantee: RAYHIT_REGENERATE_CORPUS=1 cargo test --release -p rayhit-corpus --test corpus"
    )
    .unwrap();
    writeln!(
        text,
        "# Every float is its IEEE bit pattern in hex. Fields:"
    )
    .unwrap();
    writeln!(text, "# {header}").unwrap();
    for line in lines {
        writeln!(text, "{line}").unwrap();
    }
    let p = path(kernel, precision);
    std::fs::create_dir_all(p.parent().unwrap()).unwrap();
    std::fs::write(&p, text).unwrap();
}

fn read(kernel: &str, precision: &str) -> Vec<String> {
    let p = path(kernel, precision);
    let text = std::fs::read_to_string(&p).unwrap_or_else(|e| {
        panic!("{}: {e}; generate it with RAYHIT_REGENERATE_CORPUS=1 cargo test --release -p rayhit-corpus --test corpus", p.display())
    });
    exact::corpus_lines(&text)
        .map(|(_, line)| String::from(line))
        .collect()
}

/// Draws `CASES` cases round-robin from the generators.
fn draw<C>(generators: &[Generator<C>]) -> Vec<C> {
    let mut rngs: Vec<Source> = generators
        .iter()
        .map(|(_, seed, _)| Source::seeded(seed * 1000 + 7))
        .collect();
    (0..CASES)
        .map(|i| {
            let k = i % generators.len();
            (generators[k].2)(&mut rngs[k])
        })
        .collect()
}

/// Collects failures so that one run reports all of them.
#[derive(Default)]
struct Failures(Vec<String>);

impl Failures {
    fn check(&mut self, ok: bool, line: usize, what: impl FnOnce() -> String) {
        if !ok {
            self.0.push(format!("case {line}: {}", what()));
        }
    }
    /// Checks line `i` with `check`, which reads it with the library's
    /// corpus reader (`exact::CorpusLine`); a line it cannot read is a
    /// failure too.
    fn line(&mut self, i: usize, check: impl FnOnce(&mut Self) -> Result<(), String>) {
        if let Err(e) = check(self) {
            self.0.push(format!("case {i}: unreadable: {e}"));
        }
    }
    fn assert_none(self, file: &str) {
        assert!(
            self.0.is_empty(),
            "{file}: {} failures:\n{}",
            self.0.len(),
            self.0
                .iter()
                .take(20)
                .cloned()
                .collect::<Vec<_>>()
                .join("\n")
        );
    }
}

// ------------------------------------------------------------------ boxes

const BOX_HEADER: &str = "origin dir min max t_max | exact answer: miss, or hit ENTER EXIT (rounded to nearest) FACE (the entry face: min-x .. max-z, or inside) | band: clear (hit/miss must match) or edge";

/// The corpus's name of an entry face.
fn face_name(face: Option<BoxFace>) -> &'static str {
    match face {
        None => "inside",
        Some(BoxFace::MinX) => "min-x",
        Some(BoxFace::MaxX) => "max-x",
        Some(BoxFace::MinY) => "min-y",
        Some(BoxFace::MaxY) => "max-y",
        Some(BoxFace::MinZ) => "min-z",
        Some(BoxFace::MaxZ) => "max-z",
    }
}

fn box_line<V: Vector>((b, ray, t_max): &BoxCase<V>) -> Option<String> {
    if !(ray.is_valid() && b.is_valid()) {
        return None;
    }
    let raw = oracle::box_raw(ray, b, *t_max);
    // The precondition of the slab test's guarantees (see the oracle suite).
    let half_max = r(S::<V>::MAX) / R::from_integer(2.into());
    if raw
        .as_ref()
        .is_some_and(|(e, x)| e > &half_max || x > &half_max)
    {
        return None;
    }
    let answer = match oracle::box_interval(ray, b, *t_max) {
        Some((e, x)) => format!(
            "hit {} {} {}",
            hex(nearest::<S<V>>(&e)),
            hex(nearest::<S<V>>(&x)),
            face_name(oracle::box_face(ray, b).0)
        ),
        None => "miss".into(),
    };
    // Clear: outside the slab test's rounding band (see `exact::band`).
    let clear = exact::band(&exact::Case::Box(*ray, *b, *t_max)) == exact::Band::Clear;
    let band = if clear { "clear" } else { "edge" };
    Some(format!(
        "{} {} {} {} {} | {answer} | {band}",
        hex_v(ray.origin),
        hex_v(ray.dir),
        hex_v(b.min),
        hex_v(b.max),
        hex(*t_max)
    ))
}

fn check_boxes<V: Vector>(lines: &[String]) -> Failures {
    let mut fail = Failures::default();
    let u = r(S::<V>::UNIT_ROUNDOFF);
    for (i, line) in lines.iter().enumerate() {
        fail.line(i, |fail| {
            let parts = CorpusLine::new(line);
            let mut f = parts.fields(0)?;
            let ray = Ray::new(f.vector::<V>()?, f.vector::<V>()?);
            let b = Aabb::new(f.vector::<V>()?, f.vector::<V>()?);
            let t_max: S<V> = f.scalar()?;
            let mut ans = parts.fields(1)?;
            let exact = match ans.word()? {
                "hit" => Some((ans.scalar::<S<V>>()?, ans.scalar::<S<V>>()?)),
                "miss" => None,
                w => return Err(format!("neither `hit` nor `miss`: {w}")),
            };
            // The entry face of every reported hit, exact hits or not (the
            // face is defined by the entry planes alone).
            if exact.is_some() {
                let want = ans.word()?;
                let got = b.hit(&ray, t_max).map(|h| face_name(h.face));
                fail.check(got.is_none_or(|g| g == want), i, || {
                    format!("entry face {got:?}, exact {want}")
                });
            }
            let clear = parts.band(2)? == exact::Band::Clear;
            let slab = ray_aabb(&ray, &b, t_max);
            let naive = b.clip_by_faces(&ray, t_max);
            fail.check(exact.is_none() || slab.is_some(), i, || {
                format!("slab false miss: {line}")
            });
            if clear {
                fail.check(slab.is_some() == exact.is_some(), i, || {
                    format!("slab hit/miss: {slab:?} vs {exact:?}")
                });
                fail.check(naive.is_some() == exact.is_some(), i, || {
                    format!("naive hit/miss: {naive:?} vs {exact:?}")
                });
            }
            if let (Some((e, x)), Some((ee, xx))) = (slab, exact) {
                // Entry within gamma(3) of the exact entry, which is within half
                // an ulp of the stored one; exit at least the exact exit and at
                // most (1 + 16u) times it plus two subnormals.
                let half = |y: S<V>| ulp(y) / R::from_integer(2.into());
                let entry_ok =
                    (r(e) - r(ee)).abs() <= gamma::<S<V>>(3) * (r(ee).abs() + half(ee)) + half(ee);
                let banded = !oracle::reciprocal_overflows(ray.dir);
                fail.check(!banded || entry_ok, i, || {
                    format!("slab entry {e:?} vs exact {ee:?}")
                });
                fail.check(r(x) >= r(xx) - half(xx), i, || {
                    format!("slab exit {x:?} below exact {xx:?}")
                });
                let cap = (r(xx) + half(xx))
                    * (R::from_integer(1.into()) + R::from_integer(16.into()) * &u)
                    + r(S::<V>::TINY) * R::from_integer(2.into());
                fail.check(!banded || r(x) <= cap, i, || {
                    format!("slab exit {x:?} widened beyond the band, exact {xx:?}")
                });
            }
            Ok(())
        });
    }
    fail
}

// -------------------------------------------------------------- triangles

const TRI_HEADER: &str = "origin dir a b c t_max | exact answer: miss, or hit T U V front|back (rounded to nearest) | band: clear or edge";

fn tri_line<V: Vector>((tri, ray, t_max): &TriCase<V>) -> Option<String> {
    let n = tri.normal();
    if !(ray.is_valid() && n.is_finite() && n != V::ZERO) {
        return None;
    }
    let ex = oracle::triangle(ray, tri);
    let limit = oracle::limit(*t_max);
    let answer = if ex.hits(&limit) {
        let (t, (u, v)) = (ex.t.clone().unwrap(), ex.uv.clone().unwrap());
        let (a, b, c) = (rv(tri.a), rv(tri.b), rv(tri.c));
        let nn = oracle::cross(&oracle::sub(&b, &a), &oracle::sub(&c, &a));
        let side = if oracle::dot(&rv(ray.dir), &nn).is_negative() {
            "front"
        } else {
            "back"
        };
        format!(
            "hit {} {} {} {side}",
            hex(nearest::<S<V>>(&t)),
            hex(nearest::<S<V>>(&u)),
            hex(nearest::<S<V>>(&v))
        )
    } else {
        "miss".into()
    };
    // Clear: decided outside the watertight test's rounding band widened by
    // Moller-Trumbore's (see `exact::band`).
    let clear = exact::band(&exact::Case::Triangle(*ray, *tri, *t_max)) == exact::Band::Clear;
    let band = if clear { "clear" } else { "edge" };
    Some(format!(
        "{} {} {} {} {} {} | {answer} | {band}",
        hex_v(ray.origin),
        hex_v(ray.dir),
        hex_v(tri.a),
        hex_v(tri.b),
        hex_v(tri.c),
        hex(*t_max)
    ))
}

fn check_triangles<V: Vector>(lines: &[String]) -> Failures {
    let mut fail = Failures::default();
    for (i, line) in lines.iter().enumerate() {
        fail.line(i, |fail| {
            let parts = CorpusLine::new(line);
            let mut f = parts.fields(0)?;
            let ray = Ray::new(f.vector::<V>()?, f.vector::<V>()?);
            let tri = Triangle::new(f.vector::<V>()?, f.vector::<V>()?, f.vector::<V>()?);
            let t_max: S<V> = f.scalar()?;
            let mut ans = parts.fields(1)?;
            let exact = match ans.word()? {
                "hit" => {
                    let (t, u, v) = (
                        ans.scalar::<S<V>>()?,
                        ans.scalar::<S<V>>()?,
                        ans.scalar::<S<V>>()?,
                    );
                    let side = if ans.word()? == "front" {
                        Side::Front
                    } else {
                        Side::Back
                    };
                    Some((t, u, v, side))
                }
                "miss" => None,
                w => return Err(format!("neither `hit` nor `miss`: {w}")),
            };
            let clear = parts.band(2)? == exact::Band::Clear;
            let wt = ray_triangle(&ray, &tri, t_max);
            if clear {
                let mt = tri.moller_trumbore(&ray, t_max);
                let one = tri.hit(&ray, (t_max, EdgeRule::OneHit));
                for (name, got) in [
                    ("watertight", wt.is_some()),
                    ("Moller-Trumbore", mt.is_some()),
                    ("one-hit", one.is_some()),
                ] {
                    fail.check(got == exact.is_some(), i, || {
                        format!("{name} hit/miss {got} vs exact {exact:?}")
                    });
                }
            }
            if let (Some(h), Some((t, u, v, side))) = (wt, exact) {
                let err = tri.hit_error(&ray, &h);
                let within = |got: S<V>, want: S<V>, bound: S<V>| {
                    !bound.is_finite()
                        || (r(got) - r(want)).abs()
                            <= r(bound) + ulp(want) / R::from_integer(2.into())
                };
                fail.check(within(h.t, t, err.t), i, || {
                    format!("t {:?} vs exact {t:?}, bound {:?}", h.t, err.t)
                });
                fail.check(within(h.u, u, err.u), i, || {
                    format!("u {:?} vs exact {u:?}, bound {:?}", h.u, err.u)
                });
                fail.check(within(h.v, v, err.v), i, || {
                    format!("v {:?} vs exact {v:?}, bound {:?}", h.v, err.v)
                });
                fail.check(h.side == side, i, || {
                    format!("side {:?} vs exact {side:?}", h.side)
                });
            }
            Ok(())
        });
    }
    fail
}

// ----------------------------------------------------------------- planes

const PLANE_HEADER: &str = "origin dir point normal t_max | exact answer: miss, or hit T (rounded to nearest) | band: clear or edge";

fn plane_line<V: Vector>((plane, ray, t_max): &(Plane<V>, Ray<V>, S<V>)) -> Option<String> {
    if !ray.is_valid() {
        return None;
    }
    let exact = oracle::plane_hit(ray, plane, *t_max);
    let answer = match &exact {
        Some(t) => format!("hit {}", hex(nearest::<S<V>>(t))),
        None => "miss".into(),
    };
    // Clear: not within rounding of parallel, the crossing farther than its
    // error bound from 0 and t_max (see `exact::band`).
    let clear = exact::band(&exact::Case::Plane(*ray, *plane, *t_max)) == exact::Band::Clear;
    let band = if clear { "clear" } else { "edge" };
    Some(format!(
        "{} {} {} {} {} | {answer} | {band}",
        hex_v(ray.origin),
        hex_v(ray.dir),
        hex_v(plane.point),
        hex_v(plane.normal),
        hex(*t_max)
    ))
}

fn check_planes<V: Vector>(lines: &[String]) -> Failures {
    let mut fail = Failures::default();
    for (i, line) in lines.iter().enumerate() {
        fail.line(i, |fail| {
            let parts = CorpusLine::new(line);
            let mut f = parts.fields(0)?;
            let ray = Ray::new(f.vector::<V>()?, f.vector::<V>()?);
            let plane = Plane::new(f.vector::<V>()?, f.vector::<V>()?);
            let t_max: S<V> = f.scalar()?;
            let mut ans = parts.fields(1)?;
            let exact: Option<S<V>> = match ans.word()? {
                "hit" => Some(ans.scalar()?),
                "miss" => None,
                w => return Err(format!("neither `hit` nor `miss`: {w}")),
            };
            let got = ray_plane(&ray, &plane, t_max);
            if parts.band(2)? == exact::Band::Clear {
                fail.check(got.is_some() == exact.is_some(), i, || {
                    format!("hit/miss {got:?} vs exact {exact:?}")
                });
            }
            if let (Some(t), Some(te)) = (got, exact) {
                let err = plane.hit_error(&ray, &t);
                let ok = (r(t) - r(te)).abs() <= r(err) + ulp(te) / R::from_integer(2.into());
                fail.check(ok, i, || format!("t {t:?} vs exact {te:?}, bound {err:?}"));
            }
            Ok(())
        });
    }
    fail
}

// ------------------------------------------------------ spheres and discs

const SPHERE_HEADER: &str = "origin dir center radius t_max | exact answer: miss, or hit T front|back (the first crossing in (0, t_max], the entry, else the exit; T rounded to nearest; front: entering the ball) | band: clear or edge";

const DISC_HEADER: &str = "origin dir center normal radius inner_radius t_max | exact answer: miss, or hit T front|back (T rounded to nearest; front: arriving against the normal) | band: clear or edge";

/// A shape whose answer is `t` and a side, as the corpus needs it: the
/// sphere and the disc, whose files are written and checked by one code
/// path.
trait Sided<V: Vector>: Intersect<V> + Copy + std::fmt::Debug + Sized {
    /// The kind, as the files and `exact::parse_case` name it.
    const KIND: &'static str;
    /// The files' fields.
    const HEADER: &'static str;
    /// The shape's inputs, in hex.
    fn hex(&self) -> String;
    /// The case.
    fn case(self, ray: Ray<V>, t_max: S<V>) -> exact::Case<V>;
    /// The shape of a case of this kind.
    fn of(case: &exact::Case<V>) -> Option<(Ray<V>, Self, S<V>)>;
    /// The exact answer: `t` rounded to nearest, and the side.
    fn exact(&self, ray: &Ray<V>, t_max: S<V>) -> Option<(S<V>, Side)>;
    /// A hit's `t`, side and error bound (`hit_error`).
    fn parts(&self, ray: &Ray<V>, hit: &Self::Hit) -> (S<V>, Side, S<V>);
    /// The claim of a hit.
    fn claim(t: S<V>, side: Side) -> exact::Claim<S<V>>;
    /// Whether the exact crossing on `side` (the sphere's entry or exit,
    /// the disc's one crossing with its plane) is within `err` of `t`;
    /// true where there is none (a false hit, judged by the verdict).
    fn within(&self, ray: &Ray<V>, side: Side, t: S<V>, err: S<V>) -> bool;
}

impl<V: Vector> Sided<V> for Sphere<V> {
    const KIND: &'static str = "sphere";
    const HEADER: &'static str = SPHERE_HEADER;
    fn hex(&self) -> String {
        format!("{} {}", hex_v(self.center), hex(self.radius))
    }
    fn case(self, ray: Ray<V>, t_max: S<V>) -> exact::Case<V> {
        exact::Case::Sphere(ray, self, t_max)
    }
    fn of(case: &exact::Case<V>) -> Option<(Ray<V>, Self, S<V>)> {
        match case {
            exact::Case::Sphere(ray, s, t_max) => Some((*ray, *s, *t_max)),
            _ => None,
        }
    }
    fn exact(&self, ray: &Ray<V>, t_max: S<V>) -> Option<(S<V>, Side)> {
        exact::ray_sphere(ray, self, t_max).map(|h| (h.t, h.side))
    }
    fn parts(&self, ray: &Ray<V>, hit: &SphereHit<S<V>>) -> (S<V>, Side, S<V>) {
        (hit.t, hit.side, self.hit_error(ray, hit))
    }
    fn claim(t: S<V>, side: Side) -> exact::Claim<S<V>> {
        exact::Claim::Sphere { t, side }
    }
    fn within(&self, ray: &Ray<V>, side: Side, t: S<V>, err: S<V>) -> bool {
        let Some(e) = oracle::sphere(ray, self.center, self.radius).filter(|e| e.line_hits())
        else {
            return true;
        };
        !err.is_finite()
            || (e.crossing_cmp(side, &(r(t) - r(err))) != Some(Ordering::Less)
                && e.crossing_cmp(side, &(r(t) + r(err))) != Some(Ordering::Greater))
    }
}

impl<V: Vector> Sided<V> for Disc<V> {
    const KIND: &'static str = "disc";
    const HEADER: &'static str = DISC_HEADER;
    fn hex(&self) -> String {
        format!(
            "{} {} {} {}",
            hex_v(self.center),
            hex_v(self.normal),
            hex(self.radius),
            hex(self.inner_radius)
        )
    }
    fn case(self, ray: Ray<V>, t_max: S<V>) -> exact::Case<V> {
        exact::Case::Disc(ray, self, t_max)
    }
    fn of(case: &exact::Case<V>) -> Option<(Ray<V>, Self, S<V>)> {
        match case {
            exact::Case::Disc(ray, d, t_max) => Some((*ray, *d, *t_max)),
            _ => None,
        }
    }
    fn exact(&self, ray: &Ray<V>, t_max: S<V>) -> Option<(S<V>, Side)> {
        exact::ray_disc(ray, self, t_max).map(|h| (h.t, h.side))
    }
    fn parts(&self, ray: &Ray<V>, hit: &DiscHit<S<V>>) -> (S<V>, Side, S<V>) {
        (hit.t, hit.side, self.hit_error(ray, hit))
    }
    fn claim(t: S<V>, side: Side) -> exact::Claim<S<V>> {
        exact::Claim::Disc { t, side }
    }
    fn within(&self, ray: &Ray<V>, _: Side, t: S<V>, err: S<V>) -> bool {
        oracle::disc(ray, self).is_none_or(|e| !err.is_finite() || oracle::close(t, &e.t, err))
    }
}

fn side_name(side: Side) -> &'static str {
    match side {
        Side::Front => "front",
        Side::Back => "back",
    }
}

/// A sphere or disc case's line: the inputs, the exact answer and the
/// band, all from the library (`exact::ray_sphere`, `exact::ray_disc`,
/// `exact::band`).
fn sided_line<V: Vector, T: Sided<V>>((shape, ray, t_max): &SidedCase<V, T>) -> Option<String> {
    if !ray.is_valid() {
        return None;
    }
    let answer = match shape.exact(ray, *t_max) {
        Some((t, side)) => format!("hit {} {}", hex(t), side_name(side)),
        None => "miss".into(),
    };
    let clear = exact::band(&shape.case(*ray, *t_max)) == exact::Band::Clear;
    Some(format!(
        "{} {} {} {} | {answer} | {}",
        hex_v(ray.origin),
        hex_v(ray.dir),
        shape.hex(),
        hex(*t_max),
        if clear { "clear" } else { "edge" }
    ))
}

/// A sphere or disc case: the shape, the ray and `t_max`.
type SidedCase<V, T> = (T, Ray<V>, S<V>);

/// Writes a sphere or disc file from its generators.
fn write_sided<V: Vector, T: Sided<V>>(generators: &[Generator<SidedCase<V, T>>]) {
    let lines: Vec<String> = draw(generators).iter().filter_map(sided_line).collect();
    write(T::KIND, precision::<V>(), T::HEADER, &lines);
}

/// A sphere or disc file against the oracle and the kernels. Each line,
/// read with the library's reader (`exact::CorpusEntry`), is the line the
/// oracle writes for its inputs today (answer and band unchanged). The
/// `t_max` form, judged by `exact::judge`: right, with the right side,
/// on every `clear` case; wherever it hits, its `t` within its
/// `hit_error` of the exact crossing on the side it reports (decided
/// exactly; for a sphere, where the line meets the ball). The interval
/// form over `(0, t_max]`, decided exactly: the exact answer and its side
/// on every case, `edge` ones too, its `t` within `max(hit_error, succ(0))`.
fn check_sided<V: Vector, T: Sided<V>>(lines: &[String]) -> Failures {
    use rayhit::Interval;
    let mut fail = Failures::default();
    for (i, line) in lines.iter().enumerate() {
        fail.line(i, |fail| {
            let entry = exact::CorpusEntry::<V>::parse(T::KIND, line)?;
            let (ray, shape, t_max) = T::of(&entry.case).ok_or("another kind")?;
            let again = sided_line(&(shape, ray, t_max));
            fail.check(again.as_deref() == Some(line.as_str()), i, || {
                format!("the oracle now writes {again:?} for {line}")
            });
            let got = shape.hit(&ray, t_max).map(|h| shape.parts(&ray, &h));
            let claim = got.map_or(exact::Claim::Miss, |(t, side, _)| T::claim(t, side));
            if entry.band == exact::Band::Clear {
                let j = exact::judge(&entry.case, &claim, f64::INFINITY);
                fail.check(j.verdict == exact::Verdict::Right, i, || {
                    format!(
                        "{:?} on a clear case: {got:?}, exact {:?}",
                        j.verdict, entry.answer
                    )
                });
                fail.check(j.outside.is_empty(), i, || {
                    format!(
                        "{:?} wrong on a clear case: {got:?}, exact {:?}",
                        j.outside, entry.answer
                    )
                });
            }
            if let Some((t, side, err)) = got {
                fail.check(shape.within(&ray, side, t, err), i, || {
                    format!("t {t:?} ({side:?}) beyond its bound {err:?} of the exact crossing")
                });
            }
            let exact_side = |c: &exact::Claim<S<V>>| match *c {
                exact::Claim::Sphere { side, .. } | exact::Claim::Disc { side, .. } => Some(side),
                _ => None,
            };
            let window = Interval::up_to(t_max).ok_or("no interval up to t_max")?;
            let within = shape.hit(&ray, window).map(|h| shape.parts(&ray, &h));
            fail.check(within.is_some() == entry.answer.is_hit(), i, || {
                format!("over (0, t_max]: {within:?}, exact {:?}", entry.answer)
            });
            // The side as the exact one, decided exactly by both forms.
            if let Some((_, side, _)) = within {
                fail.check(Some(side) == exact_side(&entry.answer), i, || {
                    format!("over (0, t_max]: {within:?}, exact {:?}", entry.answer)
                });
            }
            if let Some((t, side, err)) = within {
                let tiny = S::<V>::ZERO.next_up();
                let err = if err > tiny { err } else { tiny };
                fail.check(shape.within(&ray, side, t, err), i, || {
                    format!("over (0, t_max]: t {t:?} beyond its bound {err:?}")
                });
            }
            Ok(())
        });
    }
    fail
}

// ------------------------------------------------------ quads and patches

const QUAD_HEADER: &str = "origin dir a b c d t_max | exact answer: miss, or hit T U V front|back (the nearer crossing of the closed triangles a b c and a c d, the first where they tie; T, U, V rounded to nearest; U along a->b, V along a->d) | band: clear or edge";

const PATCH_HEADER: &str = "origin dir p00 p10 p01 p11 t_max | exact answer: miss, or hit T U V front|back (the nearest crossing in (0, t_max]; T, U, V rounded to nearest; front: dir . (dP/du x dP/dv) <= 0) | band: clear or edge";

/// A shape whose answer is `t`, a place `(u, v)` and a side, as the
/// corpus needs it: the quad and the patch, whose files are written and
/// checked by one code path.
trait Placed<V: Vector>: Intersect<V> + Copy + std::fmt::Debug + Sized {
    /// The kind, as the files and `exact::parse_case` name it.
    const KIND: &'static str;
    /// The files' fields.
    const HEADER: &'static str;
    /// The shape's corners, in the files' order.
    fn corners(&self) -> [V; 4];
    /// The case.
    fn case(self, ray: Ray<V>, t_max: S<V>) -> exact::Case<V>;
    /// The shape of a case of this kind.
    fn of(case: &exact::Case<V>) -> Option<(Ray<V>, Self, S<V>)>;
    /// The exact answer: `t`, `u`, `v` rounded to nearest, and the side.
    fn exact(&self, ray: &Ray<V>, t_max: S<V>) -> Option<([S<V>; 3], Side)>;
    /// A hit's `t`, `u`, `v`, side, and their bounds (`hit_error`).
    fn parts(&self, ray: &Ray<V>, hit: &Self::Hit) -> Parts<V>;
    /// Whether the interval form over `(0, t_max]` answers as the `t_max`
    /// form, bit for bit.
    fn same_over_interval(&self) -> bool;
    /// Whether an exact crossing of the ray's line with the shape
    /// extended (the quad: either triangle's plane, `(u, v)` summed as
    /// the quad sums them; the patch: its surface past its edges,
    /// `oracle::patch_extended`) is within `bounds` of `values`.
    fn near_exact(&self, ray: &Ray<V>, values: [S<V>; 3], bounds: [S<V>; 3]) -> bool;
}

impl<V: Vector> Placed<V> for rayhit::Quad<V> {
    const KIND: &'static str = "quad";
    const HEADER: &'static str = QUAD_HEADER;
    fn corners(&self) -> [V; 4] {
        [self.a, self.b, self.c, self.d]
    }
    fn case(self, ray: Ray<V>, t_max: S<V>) -> exact::Case<V> {
        exact::Case::Quad(ray, self, t_max)
    }
    fn of(case: &exact::Case<V>) -> Option<(Ray<V>, Self, S<V>)> {
        match case {
            exact::Case::Quad(ray, q, t_max) => Some((*ray, *q, *t_max)),
            _ => None,
        }
    }
    fn exact(&self, ray: &Ray<V>, t_max: S<V>) -> Option<([S<V>; 3], Side)> {
        exact::ray_quad(ray, self, t_max).map(|h| ([h.t.rounded, h.u.rounded, h.v.rounded], h.side))
    }
    fn parts(&self, ray: &Ray<V>, hit: &rayhit::QuadHit<S<V>>) -> ([S<V>; 3], Side, [S<V>; 3]) {
        let e = self.hit_error(ray, hit);
        ([hit.t, hit.u, hit.v], hit.side, [e.t, e.u, e.v])
    }
    fn same_over_interval(&self) -> bool {
        // (The interval form decides the ends exactly, the t_max form
        // `t > 0` conservatively.)
        false
    }
    fn near_exact(&self, ray: &Ray<V>, values: [S<V>; 3], bounds: [S<V>; 3]) -> bool {
        self.triangles().iter().enumerate().any(|(k, tri)| {
            let e = oracle::triangle(ray, tri);
            let (Some(t), Some((b, c))) = (e.t, e.uv) else {
                return false;
            };
            let (u, v) = if k == 0 {
                (&b + &c, c)
            } else {
                (b.clone(), b + c)
            };
            [t, u, v]
                .iter()
                .zip(values.iter().zip(bounds))
                .all(|(x, (&got, bound))| (r(got) - x).abs() <= r(bound))
        })
    }
}

impl<V: Vector> Placed<V> for rayhit::Patch<V> {
    const KIND: &'static str = "patch";
    const HEADER: &'static str = PATCH_HEADER;
    fn corners(&self) -> [V; 4] {
        [self.p00, self.p10, self.p01, self.p11]
    }
    fn case(self, ray: Ray<V>, t_max: S<V>) -> exact::Case<V> {
        exact::Case::Patch(ray, self, t_max)
    }
    fn of(case: &exact::Case<V>) -> Option<(Ray<V>, Self, S<V>)> {
        match case {
            exact::Case::Patch(ray, p, t_max) => Some((*ray, *p, *t_max)),
            _ => None,
        }
    }
    fn exact(&self, ray: &Ray<V>, t_max: S<V>) -> Option<([S<V>; 3], Side)> {
        exact::ray_patch(ray, self, t_max).map(|h| ([h.t, h.u, h.v], h.side))
    }
    fn parts(&self, ray: &Ray<V>, hit: &rayhit::PatchHit<S<V>>) -> ([S<V>; 3], Side, [S<V>; 3]) {
        let e = self.hit_error(ray, hit);
        ([hit.t, hit.u, hit.v], hit.side, [e.t, e.u, e.v])
    }
    fn same_over_interval(&self) -> bool {
        // (A collapsed edge is its triangle, whose interval form decides
        // the ends exactly.)
        oracle::collapsed_triangle(self).is_none()
    }
    fn near_exact(&self, ray: &Ray<V>, values: [S<V>; 3], bounds: [S<V>; 3]) -> bool {
        oracle::patch_extended(ray, self).is_some_and(|e| {
            e.crossings.iter().any(|c| {
                [&c.t, &c.u, &c.v]
                    .into_iter()
                    .zip(values.iter().zip(bounds))
                    .all(|(x, (&got, bound))| near(x, got, bound))
            })
        })
    }
}

/// Whether an exact value known by comparisons is within `bound` of `x`.
fn near<F: Scalar>(exact: &oracle::Surd, x: F, bound: F) -> bool {
    let (x, b) = (r(x), r(bound));
    exact.cmp_rational(&(&x - &b)) != Ordering::Less
        && exact.cmp_rational(&(&x + &b)) != Ordering::Greater
}

/// A quad or patch hit's `t`, `u`, `v`, side, and their bounds.
type Parts<V> = ([S<V>; 3], Side, [S<V>; 3]);

/// A quad or patch case: the shape, the ray and `t_max`.
type PlacedCase<V, T> = (T, Ray<V>, S<V>);

/// A quad or patch case's line: the inputs, the exact answer
/// (`exact::ray_quad`, `exact::ray_patch`) and the band (`exact::band`).
fn placed_line<V: Vector, T: Placed<V>>((shape, ray, t_max): &PlacedCase<V, T>) -> Option<String> {
    if !ray.is_valid() {
        return None;
    }
    let answer = match shape.exact(ray, *t_max) {
        Some(([t, u, v], side)) => {
            format!("hit {} {} {} {}", hex(t), hex(u), hex(v), side_name(side))
        }
        None => "miss".into(),
    };
    let clear = exact::band(&shape.case(*ray, *t_max)) == exact::Band::Clear;
    let [c0, c1, c2, c3] = shape.corners().map(hex_v);
    Some(format!(
        "{} {} {c0} {c1} {c2} {c3} {} | {answer} | {}",
        hex_v(ray.origin),
        hex_v(ray.dir),
        hex(*t_max),
        if clear { "clear" } else { "edge" }
    ))
}

/// Writes a quad or patch file from its generators.
fn write_placed<V: Vector, T: Placed<V>>(generators: &[Generator<PlacedCase<V, T>>]) {
    let lines: Vec<String> = draw(generators).iter().filter_map(placed_line).collect();
    write(T::KIND, precision::<V>(), T::HEADER, &lines);
}

/// What a file's kernel did on its `edge` cases, where hit or miss is
/// measured and not held: printed with `--nocapture`.
#[derive(Default)]
struct EdgeTally {
    cases: usize,
    edge: usize,
    false_hits: usize,
    false_misses: usize,
    /// Hits away from the exact answer's crossing (another triangle of a
    /// quad, a fold's other crossing) or on its other side.
    elsewhere: usize,
}

impl EdgeTally {
    fn print(&self, file: &str) {
        println!(
            "{file}: {} cases, {} edge; on edge cases the t_max form's false hits {}, \
             false misses {}, hits elsewhere than the exact crossing {}",
            self.cases, self.edge, self.false_hits, self.false_misses, self.elsewhere
        );
    }
}

/// A quad or patch file against the oracle and the kernel. Each line,
/// read with the library's reader (`exact::CorpusEntry`), is the line the
/// oracle writes for its inputs today (answer and band unchanged). The
/// kernel's `hit` with a `t_max` on a plain and a prepared ray (the same
/// answer, bit for bit), and over `Interval::up_to(t_max)` (for a patch
/// without a collapsed edge the same answer, bit for bit): on every
/// `clear` case hit or miss as the exact answer, with the exact side, and
/// `t`, `u`, `v` within their `hit_error` of the exact answer's (stored
/// rounded to nearest, so half an ulp is added); on `edge` cases, wherever
/// it hits, within their bounds of an exact crossing of the shape
/// extended (where the kernel may report another: the quad's other
/// triangle, a fold's other crossing, a crossing just past an edge).
/// Infinite bounds hold nothing; over the interval `t` may be brought up
/// to the float above 0.
fn check_placed<V: Vector, T: Placed<V>>(lines: &[String]) -> (Failures, EdgeTally) {
    use rayhit::{Interval, PreparedRay};
    let mut fail = Failures::default();
    let mut tally = EdgeTally::default();
    for (i, line) in lines.iter().enumerate() {
        fail.line(i, |fail| {
            let entry = exact::CorpusEntry::<V>::parse(T::KIND, line)?;
            let (ray, shape, t_max) = T::of(&entry.case).ok_or("another kind")?;
            let again = placed_line(&(shape, ray, t_max));
            fail.check(again.as_deref() == Some(line.as_str()), i, || {
                format!("the oracle now writes {again:?} for {line}")
            });
            // The exact answer, as the line gives it.
            let mut answer = CorpusLine::new(line).fields(1)?;
            let exact = match answer.word()? {
                "hit" => {
                    let values: [S<V>; 3] = [answer.scalar()?, answer.scalar()?, answer.scalar()?];
                    let side = if answer.word()? == "front" {
                        Side::Front
                    } else {
                        Side::Back
                    };
                    Some((values, side))
                }
                _ => None,
            };
            let clear = entry.band == exact::Band::Clear;
            tally.cases += 1;
            tally.edge += usize::from(!clear);
            // Each form's `t`, `u`, `v`, side and bounds, and its bits.
            let parts = |h: Option<T::Hit>| h.map(|h| shape.parts(&ray, &h));
            let bits = |h: &Option<Parts<V>>| {
                h.map(|(x, side, _)| (x.map(|x| x.to_f64().to_bits()), side))
            };
            let got = parts(shape.hit(&ray, t_max));
            let prepared = parts(shape.hit(&PreparedRay::new(&ray), t_max));
            fail.check(bits(&got) == bits(&prepared), i, || {
                format!("plain {got:?}, prepared {prepared:?}")
            });
            let window = Interval::up_to(t_max).ok_or("no interval up to t_max")?;
            let over = parts(shape.hit(&ray, window));
            fail.check(
                !shape.same_over_interval() || bits(&got) == bits(&over),
                i,
                || format!("over t_max {got:?}, over (0, t_max] {over:?}"),
            );
            for (form, h) in [("t_max", got), ("(0, t_max]", over)] {
                if clear {
                    fail.check(h.is_some() == exact.is_some(), i, || {
                        format!("{form}: {h:?} on a clear case, exact {exact:?}")
                    });
                } else if form == "t_max" {
                    tally.false_hits += usize::from(h.is_some() && exact.is_none());
                    tally.false_misses += usize::from(h.is_none() && exact.is_some());
                }
                let Some((values, side, bounds)) = h else {
                    continue;
                };
                // Where the exact answer's crossing is within the bounds:
                // the stored values are within half an ulp of it.
                let at_answer = |bounds: [S<V>; 3]| {
                    exact.is_some_and(|(want, exact_side)| {
                        side == exact_side
                            && (0..3).all(|k| {
                                (r(values[k]) - r(want[k])).abs()
                                    <= r(bounds[k]) + ulp(want[k]) / R::from_integer(2.into())
                            })
                    })
                };
                if !bounds.iter().all(|b| b.is_finite()) {
                    fail.check(!clear || exact.is_some_and(|(_, s)| s == side), i, || {
                        format!("{form}: the side of {h:?}, exact {exact:?}")
                    });
                    continue;
                }
                let tiny = S::<V>::ZERO.next_up();
                let bounds = [if bounds[0] > tiny { bounds[0] } else { tiny }, bounds[1], bounds[2]];
                if clear {
                    fail.check(at_answer(bounds), i, || {
                        format!("{form}: {h:?} beyond its bounds of the exact {exact:?}, or on another side")
                    });
                } else {
                    if form == "t_max" && exact.is_some() && !at_answer(bounds) {
                        tally.elsewhere += 1;
                    }
                    fail.check(shape.near_exact(&ray, values, bounds), i, || {
                        format!("{form}: {h:?} beyond its bounds of every exact crossing")
                    });
                }
            }
            Ok(())
        });
    }
    (fail, tally)
}

// -------------------------------------------------------------- intervals

const TRI_IN_HEADER: &str = "origin dir a b c t_min t_max | exact answer over (t_min, t_max]: miss, or hit T U V front|back (rounded to nearest) | the exact plane crossing t* against the ends: below (t* <= t_min), inside, above (t* > t_max) or none (parallel) | band: clear or edge";

const PLANE_IN_HEADER: &str = "origin dir point normal t_min t_max | exact answer over (t_min, t_max]: miss, or hit T (rounded to nearest)";

/// `x` stepped `k` floats up (down for negative `k`).
fn step<F: Scalar>(x: F, k: i32) -> F {
    (0..k.unsigned_abs()).fold(x, |x, _| if k > 0 { x.next_up() } else { x.next_down() })
}

/// Interval ends around an exact crossing `t*` (line `i` picks the kind):
/// the float nearest `t*` and its neighbours up to two floats away as
/// `t_min` (to infinity), as `t_max` (from zero), a window a float or two
/// wide either side, and a wide window from half of it to twice it.
/// `None` where the ends are not `0 <= t_min <= t_max`.
fn ends<F: Scalar>(t: &R, i: usize) -> Option<(F, F)> {
    let t0: F = nearest(t);
    let k = (i / 4 % 5) as i32 - 2;
    let (lo, hi) = match i % 4 {
        0 => (step(t0, k), F::INFINITY),
        1 => (F::ZERO, step(t0, k)),
        2 => (step(t0, -1 - k.abs()), step(t0, k)),
        _ => (t0 * F::HALF, t0 * F::TWO),
    };
    (F::ZERO <= lo && lo <= hi).then_some((lo, hi))
}

/// An interval form's `t` against the exact answer `te` (stored rounded
/// to nearest, so half an ulp is added): within the larger of its error
/// bound `err` (finite) and one float above `t_min`, as the kernels'
/// docs state for a `t` brought into the interval.
fn within_or_above_lo<F: Scalar>(t: F, te: F, err: F, lo: F) -> bool {
    let step_up = r(lo.next_up()) - r(lo);
    let bound = if r(err) > step_up { r(err) } else { step_up };
    (r(t) - r(te)).abs() <= bound + ulp(te) / R::from_integer(2.into())
}

/// Where the exact `t*` lies against the ends.
fn place<F: Scalar>(t: Option<&R>, lo: F, hi: F) -> &'static str {
    match t {
        None => "none",
        Some(t) if *t <= r(lo) => "below",
        Some(t) if hi.is_finite() && *t > r(hi) => "above",
        Some(_) => "inside",
    }
}

fn tri_in_line<V: Vector>(i: usize, (tri, ray, _): &TriCase<V>) -> Option<String> {
    if !(ray.is_valid() && tri.normal().is_finite()) {
        return None;
    }
    let t_star = oracle::triangle(ray, tri).t?;
    if !t_star.is_positive() {
        return None;
    }
    let (lo, hi) = ends::<S<V>>(&t_star, i)?;
    let answer = match exact::ray_triangle_in(ray, tri, lo, hi) {
        Some(h) => format!(
            "hit {} {} {} {}",
            hex(h.t.rounded),
            hex(h.u.rounded),
            hex(h.v.rounded),
            if h.side == Side::Front {
                "front"
            } else {
                "back"
            }
        ),
        None => "miss".into(),
    };
    // Clear: the inside test's answer is not within rounding (the range is
    // decided exactly whatever the band).
    let clear = oracle::triangle_clear(ray, tri, S::<V>::INFINITY);
    Some(format!(
        "{} {} {} {} {} {} {} | {answer} | {} | {}",
        hex_v(ray.origin),
        hex_v(ray.dir),
        hex_v(tri.a),
        hex_v(tri.b),
        hex_v(tri.c),
        hex(lo),
        hex(hi),
        place(Some(&t_star), lo, hi),
        if clear { "clear" } else { "edge" }
    ))
}

/// The interval forms of the watertight test against the corpus: the
/// per-call, prepared and batch forms bit for bit alike, the any-hit forms
/// exactly whether they hit; a hit only where the exact plane crossing is
/// in the interval, with its `t` in the interval and within its error
/// bound of the exact `T` (or of one float above `t_min`, where `T` lies
/// between `t_min` and that float); and, where the inside test is clear
/// of rounding, hit or miss as the exact answer.
fn check_triangle_intervals<V: Vector>(lines: &[String]) -> Failures {
    use rayhit::{Interval, PreparedRay, batch::TriangleBatch};
    let mut fail = Failures::default();
    for (i, line) in lines.iter().enumerate() {
        fail.line(i, |fail| {
            let parts = CorpusLine::new(line);
            let mut f = parts.fields(0)?;
            let ray = Ray::new(f.vector::<V>()?, f.vector::<V>()?);
            let tri = Triangle::new(f.vector::<V>()?, f.vector::<V>()?, f.vector::<V>()?);
            let (lo, hi): (S<V>, S<V>) = (f.scalar()?, f.scalar()?);
            let mut ans = parts.fields(1)?;
            let exact: Option<S<V>> = match ans.word()? {
                "hit" => Some(ans.scalar()?),
                "miss" => None,
                w => return Err(format!("neither `hit` nor `miss`: {w}")),
            };
            let (place, clear) = (
                parts.fields(2)?.word()?,
                parts.band(3)? == exact::Band::Clear,
            );
            let Some(window) = Interval::new(lo, hi) else {
                fail.check(false, i, || "not an interval".into());
                return Ok(());
            };
            let got = tri.hit(&ray, window);
            let prepared = PreparedRay::new(&ray);
            let batch = TriangleBatch::<V, 8>::from_slice(&[tri]).expect("one triangle");
            let bits = |h: Option<rayhit::TriangleHit<S<V>>>| {
                h.map(|h| (hex(h.t), hex(h.u), hex(h.v), h.side))
            };
            fail.check(
                bits(tri.hit(&prepared, window)) == bits(got)
                    && bits(batch.hit(&prepared, window).get(0)) == bits(got),
                i,
                || "the prepared or batch form differs".into(),
            );
            fail.check(
                tri.occluded(&ray, window) == got.is_some()
                    && batch.occluded(&prepared, window) == got.is_some(),
                i,
                || "an any-hit form differs".into(),
            );
            if clear {
                fail.check(got.is_some() == exact.is_some(), i, || {
                    format!("hit/miss {got:?} vs exact {exact:?}")
                });
            }
            if let Some(h) = got {
                fail.check(place == "inside" && window.contains(h.t), i, || {
                    format!("hit {h:?} with t* {place} the interval")
                });
                if let Some(te) = exact {
                    let err = tri.hit_error(&ray, &h).t;
                    let ok = !err.is_finite() || within_or_above_lo(h.t, te, err, lo);
                    fail.check(ok, i, || {
                        format!("t {:?} vs exact {te:?}, bound {err:?}", h.t)
                    });
                }
            }
            Ok(())
        });
    }
    fail
}

fn plane_in_line<V: Vector>(
    i: usize,
    (plane, ray, _): &(Plane<V>, Ray<V>, S<V>),
) -> Option<String> {
    if !ray.is_valid() {
        return None;
    }
    let t_star = oracle::plane_hit(ray, plane, S::<V>::INFINITY)?;
    let (lo, hi) = ends::<S<V>>(&t_star, i)?;
    let answer = match exact::ray_plane_in(ray, plane, lo, hi) {
        Some(t) => format!("hit {}", hex(t.rounded)),
        None => "miss".into(),
    };
    Some(format!(
        "{} {} {} {} {} {} | {answer}",
        hex_v(ray.origin),
        hex_v(ray.dir),
        hex_v(plane.point),
        hex_v(plane.normal),
        hex(lo),
        hex(hi),
    ))
}

/// `Plane::hit` over an interval against the corpus: hit or miss as the
/// exact answer (decided exactly, no band), `t` in the interval and within
/// `Plane::hit_error` of the exact `T` (or of one float above `t_min`).
fn check_plane_intervals<V: Vector>(lines: &[String]) -> Failures {
    use rayhit::Interval;
    let mut fail = Failures::default();
    for (i, line) in lines.iter().enumerate() {
        fail.line(i, |fail| {
            let parts = CorpusLine::new(line);
            let mut f = parts.fields(0)?;
            let ray = Ray::new(f.vector::<V>()?, f.vector::<V>()?);
            let plane = Plane::new(f.vector::<V>()?, f.vector::<V>()?);
            let (lo, hi): (S<V>, S<V>) = (f.scalar()?, f.scalar()?);
            let mut ans = parts.fields(1)?;
            let exact: Option<S<V>> = match ans.word()? {
                "hit" => Some(ans.scalar()?),
                "miss" => None,
                w => return Err(format!("neither `hit` nor `miss`: {w}")),
            };
            let Some(window) = Interval::new(lo, hi) else {
                fail.check(false, i, || "not an interval".into());
                return Ok(());
            };
            let got = plane.hit(&ray, window);
            fail.check(got.is_some() == exact.is_some(), i, || {
                format!("hit/miss {got:?} vs exact {exact:?}")
            });
            if let (Some(t), Some(te)) = (got, exact) {
                let err = plane.hit_error(&ray, &t);
                let ok =
                    window.contains(t) && (!err.is_finite() || within_or_above_lo(t, te, err, lo));
                fail.check(ok, i, || format!("t {t:?} vs exact {te:?}, bound {err:?}"));
            }
            Ok(())
        });
    }
    fail
}

// ---------------------------------------------------- hit differentials

const DIFF_HEADER: &str = "dir dx_origin dx_dir dy_origin dy_dir a b c t | exact transfer (rounded to nearest): dp_dx du_dx dv_dx dp_dy du_dy dv_dy";

/// A camera ray's differentials at a triangle it hits (the test kit's
/// cameras and triangles), with the exact transfer at the hit's `t`.
fn diff_line<V: Vector>(src: &mut Source) -> Option<String> {
    let diff = rayhit_testkit::cases::cameras::differential::<V>(src)?;
    let tri = rayhit_testkit::cases::cameras::triangle_around::<V>(src, &diff.ray);
    let t = ray_triangle(&diff.ray, &tri, S::<V>::INFINITY)?.t;
    let mut answer = Vec::new();
    for (o, d) in [(diff.dx_origin, diff.dx_dir), (diff.dy_origin, diff.dy_dir)] {
        let (dp, du, dv) = oracle::hit_differential(diff.ray.dir, o, d, &tri, t)?;
        for x in dp.iter().chain([&du, &dv]) {
            answer.push(hex(nearest::<S<V>>(x)));
        }
    }
    Some(format!(
        "{} {} {} {} {} {} {} {} {} | {}",
        hex_v(diff.ray.dir),
        hex_v(diff.dx_origin),
        hex_v(diff.dx_dir),
        hex_v(diff.dy_origin),
        hex_v(diff.dy_dir),
        hex_v(tri.a),
        hex_v(tri.b),
        hex_v(tri.c),
        hex(t),
        answer.join(" ")
    ))
}

fn check_differentials<V: Vector>(lines: &[String]) -> Failures {
    let mut fail = Failures::default();
    for (i, line) in lines.iter().enumerate() {
        fail.line(i, |fail| {
            let parts = CorpusLine::new(line);
            let mut f = parts.fields(0)?;
            let dir = f.vector::<V>()?;
            let diff = RayDifferential {
                ray: Ray::new(V::ZERO, dir),
                dx_origin: f.vector()?,
                dx_dir: f.vector()?,
                dy_origin: f.vector()?,
                dy_dir: f.vector()?,
            };
            let tri = Triangle::new(f.vector::<V>()?, f.vector::<V>()?, f.vector::<V>()?);
            let t: S<V> = f.scalar()?;
            let mut ans = parts.fields(1)?;
            let exact: Vec<S<V>> = (0..10).map(|_| ans.scalar()).collect::<Result<_, _>>()?;
            let Some(got) = tri.hit_differentials(&diff, t) else {
                fail.check(false, i, || "no transfer".into());
                return Ok(());
            };
            let err = tri.hit_differentials_error(&diff, t);
            let values = [
                (got.dp_dx.x(), err.dp_dx.x()),
                (got.dp_dx.y(), err.dp_dx.y()),
                (got.dp_dx.z(), err.dp_dx.z()),
                (got.du_dx, err.du_dx),
                (got.dv_dx, err.dv_dx),
                (got.dp_dy.x(), err.dp_dy.x()),
                (got.dp_dy.y(), err.dp_dy.y()),
                (got.dp_dy.z(), err.dp_dy.z()),
                (got.du_dy, err.du_dy),
                (got.dv_dy, err.dv_dy),
            ];
            for (k, ((value, bound), e)) in values.iter().zip(&exact).enumerate() {
                let ok =
                    (r(*value) - r(*e)).abs() <= r(*bound) + ulp(*e) / R::from_integer(2.into());
                fail.check(ok, i, || {
                    format!("value {k}: {value:?} vs exact {e:?}, bound {bound:?}")
                });
            }
            Ok(())
        });
    }
    fail
}

// -------------------------------------------------------------- instances

const INSTANCE_BOX_HEADER: &str = "columns of M (x_axis y_axis z_axis) T object_min object_max | the exact image of the object box under x -> M x + T, rounded outward (the smallest float box containing it): MIN MAX";

/// Reads a transform: the matrix's three columns and the translation.
fn transform<V: Vector>(f: &mut exact::CorpusFields) -> Result<([V; 3], V), String> {
    Ok((
        [f.vector::<V>()?, f.vector::<V>()?, f.vector::<V>()?],
        f.vector::<V>()?,
    ))
}

fn hex_transform<V: Vector>((cols, t): &([V; 3], V)) -> String {
    format!(
        "{} {} {} {}",
        hex_v(cols[0]),
        hex_v(cols[1]),
        hex_v(cols[2]),
        hex_v(*t)
    )
}

/// A transform the crate builds an instance of (the inputs of a line, not
/// its answer) and an object box, with the exact image's box rounded
/// outward.
fn instance_box_line<V: Vector>(src: &mut Source) -> Option<String> {
    let (cols, t) = instances::transform::<V>(src)?;
    let object = instances::object_box::<V>(src)?;
    Instance::new(cols, t).ok()?;
    let map = exact::AffineMap::new(cols, t)?;
    let image: Aabb<V> = exact::instance_box(&map, &object)?.outward();
    if !(image.min.is_finite() && image.max.is_finite()) {
        return None;
    }
    Some(format!(
        "{} {} {} | {} {}",
        hex_transform(&(cols, t)),
        hex_v(object.min),
        hex_v(object.max),
        hex_v(image.min),
        hex_v(image.max)
    ))
}

/// `object_to_world_box` contains the exact image (it contains the stored
/// outward rounding, which is the same question for a box of floats) and
/// is at most `16 u S + 16 TINY` wider on each side, with `S = |T_i| +
/// sum_j max(|M_ij lo_j|, |M_ij hi_j|)`: each end is six operations
/// (three products, three sums), each rounded to nearest and stepped one
/// float outward, so off by at most `1.5` ulps (`3u` relative, or `1.5
/// TINY` below the normal range) of a value of magnitude at most `S (1 +
/// 6u)`: `6 * 3u S (1 + 6u) + 9 TINY`, below the bound.
fn check_instance_boxes<V: Vector>(lines: &[String]) -> Failures {
    let mut fail = Failures::default();
    let (u, tiny) = (r(S::<V>::UNIT_ROUNDOFF), r(S::<V>::TINY));
    let sixteen = R::from_integer(16.into());
    for (i, line) in lines.iter().enumerate() {
        fail.line(i, |fail| {
            let parts = CorpusLine::new(line);
            let mut f = parts.fields(0)?;
            let (cols, t) = transform::<V>(&mut f)?;
            let object = Aabb::new(f.vector::<V>()?, f.vector::<V>()?);
            let mut ans = parts.fields(1)?;
            let (lo, hi) = (ans.vector::<V>()?, ans.vector::<V>()?);
            let Ok(inst) = Instance::new(cols, t) else {
                fail.check(false, i, || format!("no instance: {line}"));
                return Ok(());
            };
            let Some(world) = inst.object_to_world_box(&object) else {
                fail.check(false, i, || format!("no world box: {line}"));
                return Ok(());
            };
            for k in 0..3 {
                fail.check(world.min[k] <= lo[k] && hi[k] <= world.max[k], i, || {
                    format!("axis {k}: {world:?} does not contain the exact image [{lo:?}, {hi:?}]")
                });
                let s: R = (0..3)
                    .map(|j| {
                        let m = r(cols[j][k]);
                        let (a, b) = ((&m * r(object.min[j])).abs(), (m * r(object.max[j])).abs());
                        if a > b { a } else { b }
                    })
                    .fold(r(t[k]).abs(), |acc, x| acc + x);
                let allowed = &sixteen * &u * s + &sixteen * &tiny;
                fail.check(
                    r(lo[k]) - r(world.min[k]) <= allowed && r(world.max[k]) - r(hi[k]) <= allowed,
                    i,
                    || format!("axis {k}: {world:?} wider than its bound around [{lo:?}, {hi:?}]"),
                );
            }
            Ok(())
        });
    }
    fail
}

const INSTANCE_POINT_HEADER: &str = "columns of M (x_axis y_axis z_axis) T object_point | the exact image M p + T, rounded to nearest";

fn instance_point_line<V: Vector>(src: &mut Source) -> Option<String> {
    let (cols, t) = instances::transform::<V>(src)?;
    let p = instances::object_point::<V>(src)?;
    Instance::new(cols, t).ok()?;
    let image = exact::instance_point(&exact::AffineMap::new(cols, t)?, p)?;
    let image = V::new(image[0].rounded, image[1].rounded, image[2].rounded);
    if !image.is_finite() {
        return None;
    }
    Some(format!(
        "{} {} | {}",
        hex_transform(&(cols, t)),
        hex_v(p),
        hex_v(image)
    ))
}

/// `surface_to_world` of an exact object point (error zero) is within its
/// `point_error` of the exact image, stored rounded to nearest (so half an
/// ulp is added).
fn check_instance_points<V: Vector>(lines: &[String]) -> Failures {
    let mut fail = Failures::default();
    for (i, line) in lines.iter().enumerate() {
        fail.line(i, |fail| {
            let parts = CorpusLine::new(line);
            let mut f = parts.fields(0)?;
            let (cols, t) = transform::<V>(&mut f)?;
            let p = f.vector::<V>()?;
            let image = parts.fields(1)?.vector::<V>()?;
            let Ok(inst) = Instance::new(cols, t) else {
                fail.check(false, i, || format!("no instance: {line}"));
                return Ok(());
            };
            let one = S::<V>::ONE;
            let zero = S::<V>::ZERO;
            let world = inst.surface_to_world(&SurfacePoint {
                point: p,
                point_error: V::ZERO,
                normal: V::new(zero, zero, one),
                normal_error: V::ZERO,
            });
            for k in 0..3 {
                let (got, want, bound) = (world.point[k], image[k], world.point_error[k]);
                let ok = bound.is_finite()
                    && (r(got) - r(want)).abs() <= r(bound) + ulp(want) / R::from_integer(2.into());
                fail.check(ok, i, || {
                    format!("axis {k}: {got:?} vs exact {want:?}, bound {bound:?}")
                });
            }
            Ok(())
        });
    }
    fail
}

// ------------------------------------------------------------------ tests

fn corpus<V: Vector>() {
    let p = precision::<V>();
    if regenerate("box") {
        let boxes: Vec<String> = draw(&boxes::generators::<V>())
            .iter()
            .filter_map(box_line)
            .collect();
        write("box", p, BOX_HEADER, &boxes);
    }
    if regenerate("triangle") {
        let tris: Vec<String> = draw(&triangles::generators::<V>())
            .iter()
            .filter_map(tri_line)
            .collect();
        write("triangle", p, TRI_HEADER, &tris);
    }
    if regenerate("plane") {
        let planes: Vec<String> =
            draw::<(Plane<V>, Ray<V>, S<V>)>(&[("plane", 21, planes::plane::<V>)])
                .iter()
                .filter_map(plane_line)
                .collect();
        write("plane", p, PLANE_HEADER, &planes);
    }
    if regenerate("sphere") {
        write_sided(&spheres::generators::<V>());
    }
    if regenerate("disc") {
        write_sided(&discs::generators::<V>());
    }
    if regenerate("quad") {
        write_placed(&quads::generators::<V>());
    }
    if regenerate("patch") {
        write_placed(&patches::generators::<V>());
    }
    if regenerate("hit_differentials") {
        let mut src = Source::seeded(0xd1ff_c0de);
        let diffs: Vec<String> = (0..4 * CASES)
            .filter_map(|_| diff_line::<V>(&mut src))
            .take(CASES / 2)
            .collect();
        write("hit_differentials", p, DIFF_HEADER, &diffs);
    }
    if regenerate("instance_box") {
        let mut src = Source::seeded(0x1257_b0c5);
        let lines: Vec<String> = (0..2 * CASES)
            .filter_map(|_| instance_box_line::<V>(&mut src))
            .take(CASES / 2)
            .collect();
        write("instance_box", p, INSTANCE_BOX_HEADER, &lines);
    }
    if regenerate("instance_point") {
        let mut src = Source::seeded(0x1257_901e);
        let lines: Vec<String> = (0..2 * CASES)
            .filter_map(|_| instance_point_line::<V>(&mut src))
            .take(CASES / 2)
            .collect();
        write("instance_point", p, INSTANCE_POINT_HEADER, &lines);
    }
    if regenerate("triangle_interval") {
        let tris: Vec<String> = draw(&triangles::generators::<V>())
            .iter()
            .enumerate()
            .filter_map(|(i, c)| tri_in_line(i, c))
            .collect();
        write("triangle_interval", p, TRI_IN_HEADER, &tris);
    }
    if regenerate("plane_interval") {
        let planes: Vec<String> =
            draw::<(Plane<V>, Ray<V>, S<V>)>(&[("plane", 22, planes::plane::<V>)])
                .iter()
                .enumerate()
                .filter_map(|(i, c)| plane_in_line(i, c))
                .collect();
        write("plane_interval", p, PLANE_IN_HEADER, &planes);
    }
    let files = [
        ("box", check_boxes::<V> as fn(&[String]) -> Failures),
        ("triangle", check_triangles::<V>),
        ("plane", check_planes::<V>),
        ("sphere", check_sided::<V, Sphere<V>>),
        ("disc", check_sided::<V, Disc<V>>),
        ("hit_differentials", check_differentials::<V>),
        ("instance_box", check_instance_boxes::<V>),
        ("instance_point", check_instance_points::<V>),
        ("triangle_interval", check_triangle_intervals::<V>),
        ("plane_interval", check_plane_intervals::<V>),
    ];
    for (kernel, check) in files {
        let lines = read(kernel, p);
        assert!(
            lines.len() >= CASES / 2,
            "{kernel}_{p}: only {} cases",
            lines.len()
        );
        check(&lines).assert_none(&format!("{kernel}_{p}.txt"));
    }
    let tallied = [
        (
            "quad",
            check_placed::<V, rayhit::Quad<V>> as fn(&[String]) -> (Failures, EdgeTally),
        ),
        ("patch", check_placed::<V, rayhit::Patch<V>>),
    ];
    for (kernel, check) in tallied {
        let lines = read(kernel, p);
        assert!(
            lines.len() >= CASES / 2,
            "{kernel}_{p}: only {} cases",
            lines.len()
        );
        let (fail, tally) = check(&lines);
        let file = format!("{kernel}_{p}.txt");
        tally.print(&file);
        fail.assert_none(&file);
    }
}

#[test]
fn corpus_f32() {
    corpus::<Vec3>();
}

#[test]
fn corpus_f64() {
    corpus::<DVec3>();
}

/// The hex encoding is exact both ways, `-0.0` and NaN payloads included.
#[test]
fn hex_round_trips() {
    for x in [
        0.0f32,
        -0.0,
        1.0,
        f32::MIN_POSITIVE,
        f32::from_bits(1),
        f32::MAX,
        -3.5e-20,
    ] {
        assert_eq!(
            exact::parse_bits::<f32>(&hex(x)).map(f32::to_bits),
            Ok(x.to_bits())
        );
    }
    for x in [
        0.0f64,
        -0.0,
        1.0,
        f64::MIN_POSITIVE,
        f64::from_bits(1),
        f64::MAX,
        1e300,
    ] {
        assert_eq!(
            exact::parse_bits::<f64>(&hex(x)).map(f64::to_bits),
            Ok(x.to_bits())
        );
    }
    assert_eq!(hex(-0.0f32), "80000000");
    assert_eq!(hex(1.0f64), "3ff0000000000000");
}

/// Checks that every line of the embedded files `names` (in
/// `src/exact/data`) is a line of the repository's file of the same name
/// (in `corpus/data`), unchanged; returns how many there are.
fn embedded_lines_in_data(names: &[&str]) -> usize {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/data");
    let embedded_dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../src/exact/data");
    let mut lines = 0;
    for name in names {
        let full = std::fs::read_to_string(format!("{dir}/{name}.txt")).unwrap();
        let all: std::collections::HashSet<&str> = full.lines().collect();
        let small = std::fs::read_to_string(format!("{embedded_dir}/{name}.txt")).unwrap();
        for l in small.lines().filter(|l| !l.starts_with('#')) {
            assert!(all.contains(l), "{name}: not in corpus/data: {l}");
            lines += 1;
        }
    }
    lines
}

/// The corpus embedded in `rayhit::exact` (`exact::corpus()`): about 2400
/// cases, each a line of `corpus/data` as it is, judged right with
/// every value within half an ulp of the exact one and the same band.
#[test]
fn embedded_corpus_agrees_with_tests_data() {
    let lines = embedded_lines_in_data(&[
        "box_f32",
        "box_f64",
        "triangle_f32",
        "triangle_f64",
        "plane_f32",
        "plane_f64",
        "sphere_f32",
        "sphere_f64",
        "disc_f32",
        "disc_f64",
        "quad_f32",
        "quad_f64",
        "patch_f32",
        "patch_f64",
    ]);
    let mut count = 0;
    fn check<V: Vector>(e: &exact::CorpusEntry<V>) {
        let j = exact::judge(&e.case, &e.answer, 0.5);
        assert_eq!(j.verdict, exact::Verdict::Right, "{e:?}");
        assert!(j.outside.is_empty(), "{e:?}: {j:?}");
        assert_eq!(j.band, e.band, "{e:?}");
    }
    for case in exact::corpus() {
        match case {
            exact::CorpusCase::F32(e) => check(&e),
            exact::CorpusCase::F64(e) => check(&e),
        }
        count += 1;
    }
    assert_eq!(count, lines);
    // Every 12th of the fourteen files' 2048 or so cases.
    assert!((2300..=2500).contains(&count), "{count}");
}

/// The instance corpus embedded in `rayhit::exact`
/// (`exact::instance_corpus()`): each line of `corpus/data` as it is, and
/// each answer the exact image (boxes rounded outward, points to
/// nearest), recomputed by the `exact` module.
#[test]
fn embedded_instance_corpus_agrees_with_tests_data() {
    let lines = embedded_lines_in_data(&[
        "instance_box_f32",
        "instance_box_f64",
        "instance_point_f32",
        "instance_point_f64",
    ]);
    fn check<V: Vector>(e: &exact::InstanceCorpusEntry<V>) {
        assert!(Instance::new(e.columns, e.translation).is_ok(), "{e:?}");
        let map = exact::AffineMap::new(e.columns, e.translation).expect("finite");
        match e.question {
            exact::InstanceQuestion::Box { object, image } => {
                let exact = exact::instance_box(&map, &object).expect("a valid box");
                assert_eq!(exact.outward::<V>(), image, "{e:?}");
            }
            exact::InstanceQuestion::Point { object, image } => {
                let exact = exact::instance_point(&map, object).expect("finite");
                let rounded = V::new(exact[0].rounded, exact[1].rounded, exact[2].rounded);
                assert_eq!(rounded, image, "{e:?}");
            }
            _ => panic!("a question this test does not know: {e:?}"),
        }
    }
    let mut count = 0;
    for case in exact::instance_corpus() {
        match case {
            exact::InstanceCorpusCase::F32(e) => check(&e),
            exact::InstanceCorpusCase::F64(e) => check(&e),
            _ => panic!("a precision this test does not know"),
        }
        count += 1;
    }
    assert_eq!(count, lines);
    assert!((300..=400).contains(&count), "{count}");
}
