//! The regression corpus's text format and its reader, and the embedded
//! corpus.

use std::format;
use std::string::String;
use std::vec::Vec;

use super::{Band, Case, Claim};
use crate::glam::{DVec3, Vec3};
use crate::{Aabb, Disc, Patch, Plane, Quad, Ray, Scalar, Side, Sphere, Triangle, Vector};

/// One corpus case of precision `V`: the case, its exact answer (values
/// rounded to nearest) and its band.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CorpusEntry<V: Vector> {
    /// The family: `box`, `triangle`, `plane`, `sphere`, `disc`, `quad` or
    /// `patch`.
    pub kind: &'static str,
    /// The question.
    pub case: Case<V>,
    /// The exact answer, as a claim: [`Claim::Miss`], or the hit with its
    /// exact values rounded to nearest (box: entry and exit; triangle and
    /// quad: `t`, `u`, `v`; plane: `t`; sphere and disc: `t` and the side;
    /// patch: `t`, `u`, `v` and the side).
    /// [`judge`](super::judge) finds it right, each value within half an
    /// ulp.
    pub answer: Claim<V::Scalar>,
    /// Outside (`Clear`) or inside (`Edge`) the crate's rounding band: see
    /// [`band`](super::band).
    pub band: Band,
}

/// A corpus case in either precision.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CorpusCase {
    /// Single precision.
    F32(CorpusEntry<Vec3>),
    /// Double precision.
    F64(CorpusEntry<DVec3>),
}

/// The embedded files of [`corpus`]: kind, whether single precision, text.
const FILES: [(&str, bool, &str); 14] = [
    ("box", true, include_str!("data/box_f32.txt")),
    ("box", false, include_str!("data/box_f64.txt")),
    ("triangle", true, include_str!("data/triangle_f32.txt")),
    ("triangle", false, include_str!("data/triangle_f64.txt")),
    ("plane", true, include_str!("data/plane_f32.txt")),
    ("plane", false, include_str!("data/plane_f64.txt")),
    ("sphere", true, include_str!("data/sphere_f32.txt")),
    ("sphere", false, include_str!("data/sphere_f64.txt")),
    ("disc", true, include_str!("data/disc_f32.txt")),
    ("disc", false, include_str!("data/disc_f64.txt")),
    ("quad", true, include_str!("data/quad_f32.txt")),
    ("quad", false, include_str!("data/quad_f64.txt")),
    ("patch", true, include_str!("data/patch_f32.txt")),
    ("patch", false, include_str!("data/patch_f64.txt")),
];

/// Reads a float written as its IEEE 754 bit pattern in hex, as the corpus
/// writes every float: 8 digits for an `f32`, 16 for an `f64`. Exact for
/// every finite value, the infinities and `-0.0` (a NaN pattern gives a
/// NaN); an `f32` pattern read as an `f64` is widened exactly, an `f64`
/// pattern read as an `f32` rounded to nearest. A word of another length,
/// or one that is not a number in hex, is an error naming it.
///
/// ```
/// use rayhit::exact::parse_bits;
/// assert_eq!(parse_bits::<f32>("3f800000"), Ok(1.0));
/// assert_eq!(parse_bits::<f64>("bff0000000000000"), Ok(-1.0));
/// assert_eq!(parse_bits::<f64>("3f800000"), Ok(1.0));
/// assert_eq!(parse_bits::<f32>("80000000").map(f32::to_bits), Ok(0x8000_0000));
/// assert!(parse_bits::<f32>("1.0").is_err());
/// ```
pub fn parse_bits<F: Scalar>(word: &str) -> Result<F, String> {
    let bad = || format!("not an f32 or f64 bit pattern in hex: {word}");
    Ok(match word.len() {
        8 => F::from_f64(f64::from(f32::from_bits(
            u32::from_str_radix(word, 16).map_err(|_| bad())?,
        ))),
        16 => F::from_f64(f64::from_bits(
            u64::from_str_radix(word, 16).map_err(|_| bad())?,
        )),
        _ => return Err(bad()),
    })
}

/// The case lines of a corpus file's text, each trimmed and with its line
/// number (counted from 1): every line but blank ones and comments (lines
/// whose first character other than white space is `#`).
///
/// A corpus file holds one case a line; [`CorpusLine`] splits a line into
/// its sections.
///
/// ```
/// use rayhit::exact::corpus_lines;
/// let text = "# a header\n\n  00000000 | miss | clear\n# more\n3f800000 | miss | edge\n";
/// let lines: Vec<(usize, &str)> = corpus_lines(text).collect();
/// assert_eq!(lines, [(3, "00000000 | miss | clear"), (5, "3f800000 | miss | edge")]);
/// ```
pub fn corpus_lines(text: &str) -> impl Iterator<Item = (usize, &str)> {
    text.lines()
        .enumerate()
        .map(|(i, line)| (i + 1, line.trim()))
        .filter(|(_, line)| !line.is_empty() && !line.starts_with('#'))
}

/// One line of a corpus file, split at `|` into its sections, each trimmed.
///
/// Every corpus file has the same form: sections separated by `|`, each a
/// list of words separated by white space, the floats written as their
/// IEEE 754 bit patterns in hex ([`parse_bits`]). Which sections a line has
/// depends on the file: for the files of the embedded [`corpus`] (box,
/// triangle, plane, sphere, disc, quad and patch, read by
/// [`CorpusEntry::parse`]) the inputs, the exact answer and the band; for the instance files ([`instance_corpus`], read by
/// [`InstanceCorpusEntry::parse`]) the inputs and the exact image. Each
/// file's header comments name its fields.
///
/// ```
/// use rayhit::exact::{Band, CorpusLine};
/// use rayhit::glam::Vec3;
/// let line = CorpusLine::new("3f800000 00000000 bf800000 | hit 40000000 front | clear");
/// assert_eq!(line.sections(), ["3f800000 00000000 bf800000", "hit 40000000 front", "clear"]);
/// assert_eq!(line.fields(0)?.vector::<Vec3>()?, Vec3::new(1.0, 0.0, -1.0));
/// let mut answer = line.fields(1)?;
/// assert_eq!(answer.word()?, "hit");
/// assert_eq!(answer.scalar::<f32>()?, 2.0);
/// assert_eq!(answer.word()?, "front");
/// assert_eq!(line.band(2)?, Band::Clear);
/// // A section the line does not have is an error, not a panic.
/// assert!(line.fields(3).is_err());
/// # Ok::<(), String>(())
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CorpusLine<'a> {
    sections: Vec<&'a str>,
}

impl<'a> CorpusLine<'a> {
    /// Splits `line` at `|` into its sections, each trimmed (a line without
    /// `|` is one section).
    ///
    /// ```
    /// use rayhit::exact::CorpusLine;
    /// assert_eq!(CorpusLine::new(" 3f800000 |miss| edge ").sections(), ["3f800000", "miss", "edge"]);
    /// ```
    #[must_use]
    pub fn new(line: &'a str) -> Self {
        Self {
            sections: line.split('|').map(str::trim).collect(),
        }
    }

    /// The sections, in order.
    ///
    /// ```
    /// use rayhit::exact::CorpusLine;
    /// assert_eq!(CorpusLine::new("00000000 | miss").sections().len(), 2);
    /// ```
    #[must_use]
    pub fn sections(&self) -> &[&'a str] {
        &self.sections
    }

    /// A reader of section `i` (counted from 0); an error if the line has
    /// no such section.
    ///
    /// ```
    /// use rayhit::exact::CorpusLine;
    /// let line = CorpusLine::new("3f800000 | miss");
    /// assert_eq!(line.fields(0).and_then(|mut f| f.scalar::<f32>()), Ok(1.0));
    /// assert!(line.fields(2).is_err());
    /// ```
    pub fn fields(&self, i: usize) -> Result<CorpusFields<'a>, String> {
        self.sections
            .get(i)
            .map(|section| CorpusFields::new(section))
            .ok_or_else(|| {
                format!(
                    "no section {} (the line has {})",
                    i + 1,
                    self.sections.len()
                )
            })
    }

    /// Section `i` (counted from 0) read as a band: `clear` is
    /// [`Band::Clear`], `edge` is [`Band::Edge`]; anything else, or no such
    /// section, is an error.
    ///
    /// ```
    /// use rayhit::exact::{Band, CorpusLine};
    /// let line = CorpusLine::new("00000000 | miss | edge");
    /// assert_eq!(line.band(2), Ok(Band::Edge));
    /// assert!(line.band(1).is_err());
    /// ```
    pub fn band(&self, i: usize) -> Result<Band, String> {
        let mut fields = self.fields(i)?;
        let band = match fields.word() {
            Ok("clear") => Band::Clear,
            Ok("edge") => Band::Edge,
            _ => {
                return Err(format!(
                    "the band is neither `clear` nor `edge`: {}",
                    self.sections[i]
                ));
            }
        };
        match fields.word() {
            Ok(more) => Err(format!("a word after the band: {more}")),
            Err(_) => Ok(band),
        }
    }
}

/// Reads the words of one section of a corpus line in order: floats (as
/// IEEE 754 bit patterns in hex, see [`parse_bits`]), vectors of three of
/// them, and other words (`hit`, `miss`, a box face, a side). Each read
/// that finds no word, or a word that is not a float, is an error.
///
/// ```
/// use rayhit::exact::CorpusFields;
/// use rayhit::glam::DVec3;
/// let mut f = CorpusFields::new(
///     "3ff0000000000000 0000000000000000 bff0000000000000 hit 4000000000000000",
/// );
/// assert_eq!(f.vector::<DVec3>()?, DVec3::new(1.0, 0.0, -1.0));
/// assert_eq!(f.word()?, "hit");
/// assert_eq!(f.scalar::<f64>()?, 2.0);
/// // Nothing is left.
/// assert!(f.scalar::<f64>().is_err());
/// # Ok::<(), String>(())
/// ```
#[derive(Clone, Debug)]
pub struct CorpusFields<'a> {
    words: core::str::SplitWhitespace<'a>,
}

impl<'a> CorpusFields<'a> {
    /// A reader of the words of `section` (split at white space).
    ///
    /// ```
    /// use rayhit::exact::CorpusFields;
    /// assert_eq!(CorpusFields::new("  miss ").word(), Ok("miss"));
    /// ```
    #[must_use]
    pub fn new(section: &'a str) -> Self {
        Self {
            words: section.split_whitespace(),
        }
    }

    /// The next word as it is; an error if there is none.
    ///
    /// ```
    /// use rayhit::exact::CorpusFields;
    /// let mut f = CorpusFields::new("hit 3f800000");
    /// assert_eq!(f.word(), Ok("hit"));
    /// assert_eq!(f.word(), Ok("3f800000"));
    /// assert!(f.word().is_err());
    /// ```
    pub fn word(&mut self) -> Result<&'a str, String> {
        self.words.next().ok_or_else(|| "too few words".into())
    }

    /// The next word as a float ([`parse_bits`]); an error if there is
    /// none or it is not a bit pattern.
    ///
    /// ```
    /// use rayhit::exact::CorpusFields;
    /// let mut f = CorpusFields::new("7f800000 hit");
    /// assert_eq!(f.scalar::<f32>(), Ok(f32::INFINITY));
    /// assert!(f.scalar::<f32>().is_err());
    /// ```
    pub fn scalar<F: Scalar>(&mut self) -> Result<F, String> {
        parse_bits(self.words.next().ok_or("too few numbers")?)
    }

    /// The next three words as a vector's `x`, `y` and `z`.
    ///
    /// ```
    /// use rayhit::exact::CorpusFields;
    /// use rayhit::glam::Vec3;
    /// let mut f = CorpusFields::new("00000000 3f800000 40000000");
    /// assert_eq!(f.vector::<Vec3>(), Ok(Vec3::new(0.0, 1.0, 2.0)));
    /// ```
    pub fn vector<V: Vector>(&mut self) -> Result<V, String> {
        let x = self.scalar()?;
        let y = self.scalar()?;
        let z = self.scalar()?;
        Ok(V::new(x, y, z))
    }

    /// Every word left, each as a float; an error names the first that is
    /// not a bit pattern.
    ///
    /// ```
    /// use rayhit::exact::CorpusFields;
    /// assert_eq!(CorpusFields::new("3f800000 40000000").rest::<f32>(), Ok(vec![1.0, 2.0]));
    /// assert!(CorpusFields::new("3f800000 front").rest::<f32>().is_err());
    /// ```
    pub fn rest<F: Scalar>(self) -> Result<Vec<F>, String> {
        self.words.map(parse_bits).collect()
    }
}

/// Reads a case and an answer in the corpus's text form: `kind` is `box`,
/// `triangle`, `plane`, `sphere`, `disc`, `quad` or `patch`; `inputs` the
/// case's floats as IEEE bit patterns in hex (box: origin, dir, min, max,
/// `t_max`; triangle: origin, dir, a, b, c, `t_max`; plane: origin, dir,
/// point, normal, `t_max`; sphere: origin, dir, centre, radius, `t_max`;
/// disc: origin, dir, centre, normal, radius, inner radius, `t_max`;
/// quad: origin, dir, a, b, c, d, `t_max`; patch: origin, dir, p00, p10,
/// p01, p11, `t_max`); `answer` `miss`, or `hit` and the values (box:
/// entry, exit; triangle and quad: `t`, `u`, `v`; plane: `t`; sphere and
/// disc: `t` and the side, `front` or `back`; patch: `t`, `u`, `v` and
/// the side) in hex, any further words ignored. An error says what is
/// wrong.
///
/// ```
/// use rayhit::{exact::{self, Case, Claim}, glam::Vec3};
/// let (case, claim) = exact::parse_case::<Vec3>(
///     "plane",
///     "00000000 3f800000 00000000 00000000 bf800000 00000000 \
///      00000000 00000000 00000000 00000000 3f800000 00000000 7f800000",
///     "hit 3f800000",
/// )
/// .unwrap();
/// assert!(matches!(case, Case::Plane(..)));
/// assert_eq!(claim, Claim::Plane { t: 1.0 });
/// // The unit sphere from z = -3 along z: in at t = 2.
/// let (case, claim) = exact::parse_case::<Vec3>(
///     "sphere",
///     "00000000 00000000 c0400000 00000000 00000000 3f800000 \
///      00000000 00000000 00000000 3f800000 7f800000",
///     "hit 40000000 front",
/// )
/// .unwrap();
/// assert!(matches!(case, Case::Sphere(..)));
/// assert_eq!(claim, Claim::Sphere { t: 2.0, side: rayhit::Side::Front });
/// // The unit square in the plane z = 0 as a quad and as a patch, hit
/// // straight down from z = 1 at (0.5, 0.25): t = 1, (u, v) = (0.5, 0.25).
/// let ray = "3f000000 3e800000 3f800000 00000000 00000000 bf800000";
/// let square = "00000000 00000000 00000000 3f800000 00000000 00000000 \
///               3f800000 3f800000 00000000 00000000 3f800000 00000000";
/// let (case, claim) = exact::parse_case::<Vec3>(
///     "quad",
///     &format!("{ray} {square} 7f800000"),
///     "hit 3f800000 3f000000 3e800000 front",
/// )
/// .unwrap();
/// assert!(matches!(case, Case::Quad(..)));
/// assert_eq!(claim, Claim::Quad { t: 1.0, u: 0.5, v: 0.25 });
/// // The patch's corners come in the order p00, p10, p01, p11.
/// let corners = "00000000 00000000 00000000 3f800000 00000000 00000000 \
///                00000000 3f800000 00000000 3f800000 3f800000 00000000";
/// let (case, claim) = exact::parse_case::<Vec3>(
///     "patch",
///     &format!("{ray} {corners} 7f800000"),
///     "hit 3f800000 3f000000 3e800000 front",
/// )
/// .unwrap();
/// assert!(matches!(case, Case::Patch(..)));
/// let side = rayhit::Side::Front;
/// assert_eq!(claim, Claim::Patch { t: 1.0, u: 0.5, v: 0.25, side });
/// ```
pub fn parse_case<V: Vector>(
    kind: &str,
    inputs: &str,
    answer: &str,
) -> Result<(Case<V>, Claim<V::Scalar>), String> {
    let n: Vec<V::Scalar> = CorpusFields::new(inputs).rest()?;
    let want = match kind {
        "sphere" => 11,
        "box" | "plane" => 13,
        "disc" => 15,
        "triangle" => 16,
        "quad" | "patch" => 19,
        _ => return Err(format!("unknown kind {kind}")),
    };
    if n.len() != want {
        return Err(format!("{kind} needs {want} numbers, got {}", n.len()));
    }
    let mut a = CorpusFields::new(answer);
    let hit = match a.word() {
        Ok("hit") => true,
        Ok("miss") => false,
        _ => return Err("the answer is neither `hit` nor `miss`".into()),
    };
    let words: Vec<&str> = core::iter::from_fn(|| a.word().ok()).collect();
    let x = |i: usize| -> Result<V::Scalar, String> {
        parse_bits(words.get(i).ok_or("too few numbers in the answer")?)
    };
    let v = |i: usize| V::new(n[i], n[i + 1], n[i + 2]);
    let ray = Ray::new(v(0), v(3));
    // The side after `at` numbers (sphere, disc, patch).
    let side = |at: usize| -> Result<Side, String> {
        match words.get(at) {
            Some(&"front") => Ok(Side::Front),
            Some(&"back") => Ok(Side::Back),
            _ => Err("the side is neither `front` nor `back`".into()),
        }
    };
    // `t` and the side (sphere, disc).
    let sided = || -> Result<(V::Scalar, Side), String> { Ok((x(0)?, side(1)?)) };
    Ok(match kind {
        "box" => (
            Case::Box(ray, Aabb::new(v(6), v(9)), n[12]),
            if hit {
                Claim::Box {
                    enter: x(0)?,
                    exit: x(1)?,
                }
            } else {
                Claim::Miss
            },
        ),
        "triangle" => (
            Case::Triangle(ray, Triangle::new(v(6), v(9), v(12)), n[15]),
            if hit {
                Claim::Triangle {
                    t: x(0)?,
                    u: x(1)?,
                    v: x(2)?,
                }
            } else {
                Claim::Miss
            },
        ),
        "sphere" => (
            Case::Sphere(ray, Sphere::new(v(6), n[9]), n[10]),
            if hit {
                let (t, side) = sided()?;
                Claim::Sphere { t, side }
            } else {
                Claim::Miss
            },
        ),
        "disc" => (
            Case::Disc(ray, Disc::annulus(v(6), v(9), n[12], n[13]), n[14]),
            if hit {
                let (t, side) = sided()?;
                Claim::Disc { t, side }
            } else {
                Claim::Miss
            },
        ),
        "quad" => (
            Case::Quad(ray, Quad::new(v(6), v(9), v(12), v(15)), n[18]),
            if hit {
                Claim::Quad {
                    t: x(0)?,
                    u: x(1)?,
                    v: x(2)?,
                }
            } else {
                Claim::Miss
            },
        ),
        "patch" => (
            Case::Patch(ray, Patch::new(v(6), v(9), v(12), v(15)), n[18]),
            if hit {
                Claim::Patch {
                    t: x(0)?,
                    u: x(1)?,
                    v: x(2)?,
                    side: side(3)?,
                }
            } else {
                Claim::Miss
            },
        ),
        _ => (
            Case::Plane(ray, Plane::new(v(6), v(9)), n[12]),
            if hit {
                Claim::Plane { t: x(0)? }
            } else {
                Claim::Miss
            },
        ),
    })
}

impl<V: Vector> CorpusEntry<V> {
    /// Reads a line of a box, triangle, plane, sphere, disc, quad or patch
    /// corpus file (`kind` is `box`, `triangle`, `plane`, `sphere`,
    /// `disc`, `quad` or `patch`): `INPUTS | ANSWER | BAND`, the inputs
    /// and the answer as [`parse_case`] reads them, the band `clear` or
    /// `edge`. This reads the embedded [`corpus`], and the repository's
    /// full corpus
    /// (`corpus/data/{box,triangle,plane,sphere,disc,quad,patch}_{f32,f64}.txt`)
    /// just as well. An error says what is wrong.
    ///
    /// ```
    /// use rayhit::exact::{Band, Claim, CorpusEntry};
    /// use rayhit::glam::Vec3;
    /// let e = CorpusEntry::<Vec3>::parse(
    ///     "plane",
    ///     "00000000 3f800000 00000000 00000000 bf800000 00000000 \
    ///      00000000 00000000 00000000 00000000 3f800000 00000000 7f800000 \
    ///      | hit 3f800000 | clear",
    /// )?;
    /// assert_eq!((e.kind, e.answer, e.band), ("plane", Claim::Plane { t: 1.0 }, Band::Clear));
    /// assert!(CorpusEntry::<Vec3>::parse("plane", "00000000 | miss").is_err());
    /// # Ok::<(), String>(())
    /// ```
    pub fn parse(kind: &str, line: &str) -> Result<Self, String> {
        let kind = match kind {
            "box" => "box",
            "triangle" => "triangle",
            "plane" => "plane",
            "sphere" => "sphere",
            "disc" => "disc",
            "quad" => "quad",
            "patch" => "patch",
            _ => return Err(format!("unknown kind {kind}")),
        };
        let line = CorpusLine::new(line);
        let &[inputs, answer, _] = line.sections() else {
            return Err("expected `INPUTS | ANSWER | BAND`".into());
        };
        let band = line.band(2)?;
        let (case, answer) = parse_case(kind, inputs, answer)?;
        Ok(Self {
            kind,
            case,
            answer,
            band,
        })
    }
}

/// The embedded regression corpus: about 2400 box, triangle, plane,
/// sphere, disc, quad and bilinear patch cases in both precisions (a
/// sample of the repository's corpus), each decided in exact arithmetic
/// and placed in or out of the rounding band, built around faces, edges,
/// corners, slivers, grazing rays (tangents of spheres among them), rays
/// from inside spheres, the circles of discs and their holes, quads'
/// diagonals, patches' folds and collapsed edges, and extreme scales.
/// Parsed on each call (cheap next to judging).
///
/// ```
/// use rayhit::exact::{self, Band, CorpusCase, Verdict};
/// let mut clear = 0;
/// for case in exact::corpus() {
///     if let CorpusCase::F32(e) = case {
///         // The crate's own kernels get every clear box case right.
///         if let exact::Case::Box(ray, b, t_max) = e.case {
///             let claim = match rayhit::ray_aabb(&ray, &b, t_max) {
///                 Some((enter, exit)) => exact::Claim::Box { enter, exit },
///                 None => exact::Claim::Miss,
///             };
///             let j = exact::judge(&e.case, &claim, f64::INFINITY);
///             assert!(e.band == Band::Edge || j.verdict == Verdict::Right);
///             clear += usize::from(e.band == Band::Clear);
///         }
///     }
/// }
/// assert!(clear > 50);
/// ```
pub fn corpus() -> impl Iterator<Item = CorpusCase> {
    FILES.into_iter().flat_map(|(kind, single, text)| {
        corpus_lines(text).filter_map(move |(_, line)| {
            if single {
                CorpusEntry::<Vec3>::parse(kind, line)
                    .ok()
                    .map(CorpusCase::F32)
            } else {
                CorpusEntry::<DVec3>::parse(kind, line)
                    .ok()
                    .map(CorpusCase::F64)
            }
        })
    })
}

/// One instance question of the embedded corpus, with its exact answer.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum InstanceQuestion<V: Vector> {
    /// The world box of an object box.
    Box {
        /// The object box.
        object: Aabb<V>,
        /// The exact image of `object`, rounded outward: the smallest box
        /// of floats that contains it (see
        /// [`ImageBox::outward`](super::ImageBox::outward)). A box of
        /// floats contains the exact image exactly when it contains this
        /// one.
        image: Aabb<V>,
    },
    /// The world point of an object point.
    Point {
        /// The object point.
        object: V,
        /// Its exact image `M p + T`, each component rounded to nearest.
        image: V,
    },
}

/// An instance case of the embedded corpus: the transform (the matrix's
/// columns, glam's convention, and the translation; every one builds an
/// [`Instance`](crate::Instance)) and the question with its exact answer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InstanceCorpusEntry<V: Vector> {
    /// The columns of `M`.
    pub columns: [V; 3],
    /// `T`.
    pub translation: V,
    /// The question and its exact answer.
    pub question: InstanceQuestion<V>,
}

/// An instance case in either precision.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum InstanceCorpusCase {
    /// Single precision.
    F32(InstanceCorpusEntry<Vec3>),
    /// Double precision.
    F64(InstanceCorpusEntry<DVec3>),
}

/// The embedded files of [`instance_corpus`]: kind, whether single
/// precision, text.
const INSTANCE_FILES: [(&str, bool, &str); 4] = [
    ("box", true, include_str!("data/instance_box_f32.txt")),
    ("box", false, include_str!("data/instance_box_f64.txt")),
    ("point", true, include_str!("data/instance_point_f32.txt")),
    ("point", false, include_str!("data/instance_point_f64.txt")),
];

impl<V: Vector> InstanceCorpusEntry<V> {
    /// Reads a line of an instance corpus file (`kind` is `box` or
    /// `point`): `INPUTS | IMAGE`, every float an IEEE bit pattern in hex.
    /// The inputs are the matrix's columns, the translation and the object
    /// box's `min` and `max` (18 numbers) or the object point (15); the
    /// image is the exact image's box, `min` and `max` (6), or point (3).
    /// This reads the embedded [`instance_corpus`], and the repository's
    /// full instance corpus (`corpus/data/instance_{box,point}_{f32,f64}.txt`)
    /// just as well. An error says what is wrong.
    ///
    /// ```
    /// use rayhit::exact::{InstanceCorpusEntry, InstanceQuestion};
    /// use rayhit::glam::Vec3;
    /// // The identity moved by (1, 0, 0), and the point (1, 1, 1).
    /// let e = InstanceCorpusEntry::<Vec3>::parse(
    ///     "point",
    ///     "3f800000 00000000 00000000 00000000 3f800000 00000000 \
    ///      00000000 00000000 3f800000 3f800000 00000000 00000000 \
    ///      3f800000 3f800000 3f800000 | 40000000 3f800000 3f800000",
    /// )?;
    /// assert_eq!(e.translation, Vec3::X);
    /// assert!(matches!(
    ///     e.question,
    ///     InstanceQuestion::Point { object: Vec3::ONE, image } if image == Vec3::new(2.0, 1.0, 1.0)
    /// ));
    /// assert!(InstanceCorpusEntry::<Vec3>::parse("box", "3f800000 | 3f800000").is_err());
    /// # Ok::<(), String>(())
    /// ```
    pub fn parse(kind: &str, line: &str) -> Result<Self, String> {
        let line = CorpusLine::new(line);
        let &[inputs, answer] = line.sections() else {
            return Err("expected `INPUTS | IMAGE`".into());
        };
        let n: Vec<V::Scalar> = CorpusFields::new(inputs).rest()?;
        let a: Vec<V::Scalar> = CorpusFields::new(answer).rest()?;
        let v = |x: &[V::Scalar], i: usize| V::new(x[i], x[i + 1], x[i + 2]);
        let question = match (kind, n.len(), a.len()) {
            ("box", 18, 6) => InstanceQuestion::Box {
                object: Aabb::new(v(&n, 12), v(&n, 15)),
                image: Aabb::new(v(&a, 0), v(&a, 3)),
            },
            ("point", 15, 3) => InstanceQuestion::Point {
                object: v(&n, 12),
                image: v(&a, 0),
            },
            ("box", ..) => {
                return Err(format!(
                    "an instance box needs 18 and 6 numbers, got {} and {}",
                    n.len(),
                    a.len()
                ));
            }
            ("point", ..) => {
                return Err(format!(
                    "an instance point needs 15 and 3 numbers, got {} and {}",
                    n.len(),
                    a.len()
                ));
            }
            _ => return Err(format!("unknown instance kind {kind}")),
        };
        Ok(Self {
            columns: [v(&n, 0), v(&n, 3), v(&n, 6)],
            translation: v(&n, 9),
            question,
        })
    }
}

/// The embedded instance corpus: about 340 cases in both precisions (a
/// sample of the repository's), each a transform (rotations, scales from
/// `1e-3` to `1e3`, shears, translations up to `1e5`, and exact signed
/// permutations with power-of-two scales) with an object box (ordinary,
/// flat, a point, tiny and far away, with `-0.0` corners) or an object
/// point, and its exact image: the box rounded outward, the point rounded
/// to nearest. Parsed on each call.
///
/// ```
/// use rayhit::exact::{self, InstanceCorpusCase, InstanceQuestion};
/// use rayhit::Instance;
/// let mut boxes = 0;
/// for case in exact::instance_corpus() {
///     if let InstanceCorpusCase::F32(e) = case {
///         let inst = Instance::new(e.columns, e.translation).unwrap();
///         if let InstanceQuestion::Box { object, image } = e.question {
///             // The crate's world box contains the exact image.
///             let world = inst.object_to_world_box(&object).unwrap();
///             assert!(world.min.cmple(image.min).all() && image.max.cmple(world.max).all());
///             boxes += 1;
///         }
///     }
/// }
/// assert!(boxes > 50);
/// ```
pub fn instance_corpus() -> impl Iterator<Item = InstanceCorpusCase> {
    INSTANCE_FILES.into_iter().flat_map(|(kind, single, text)| {
        corpus_lines(text).filter_map(move |(_, line)| {
            if single {
                InstanceCorpusEntry::<Vec3>::parse(kind, line)
                    .ok()
                    .map(InstanceCorpusCase::F32)
            } else {
                InstanceCorpusEntry::<DVec3>::parse(kind, line)
                    .ok()
                    .map(InstanceCorpusCase::F64)
            }
        })
    })
}
