//! TEMPORARY: the previous private oracle (a verbatim copy of the old
//! tests/support/mod.rs oracle) against `rayhit::exact`, on every corpus
//! case and on the generators' cases. Removed once the switch is done.
#![allow(dead_code)]

mod old_oracle;
use old_oracle as old;
use old_oracle::generators;

use rayhit::exact::{self, Band, Case};
use rayhit::glam::{DVec3, Vec3};
use rayhit::{Aabb, Plane, Ray, Scalar, Triangle, Vector};

fn val<F: Scalar>(s: &str) -> F {
    if s.len() == 8 {
        F::from_f64(f64::from(f32::from_bits(
            u32::from_str_radix(s, 16).unwrap(),
        )))
    } else {
        F::from_f64(f64::from_bits(u64::from_str_radix(s, 16).unwrap()))
    }
}
fn vec3<V: Vector>(w: &[&str]) -> V {
    V::new(val(w[0]), val(w[1]), val(w[2]))
}
fn bits<F: Scalar>(x: F) -> u64 {
    x.to_f64().to_bits()
}

#[derive(Default, Debug)]
struct Counts {
    cases: usize,
    ties: usize,
}

fn corpus<V: Vector>(file: &str, counts: &mut Counts) {
    let text = std::fs::read_to_string(format!("{}/tests/data/{file}", env!("CARGO_MANIFEST_DIR")))
        .unwrap();
    for line in text
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
    {
        let parts: Vec<&str> = line.split('|').map(str::trim).collect();
        let w: Vec<&str> = parts[0].split_whitespace().collect();
        let ans: Vec<&str> = parts[1].split_whitespace().collect();
        let band = if parts[2] == "clear" {
            Band::Clear
        } else {
            Band::Edge
        };
        let ray = Ray::new(vec3::<V>(&w[0..3]), vec3::<V>(&w[3..6]));
        let mut check_round = |exact: &exact::Rational, rounded: V::Scalar, file_hex: &str| {
            let from_file: V::Scalar = val(file_hex);
            if bits(rounded) != bits(from_file) {
                // The corpus rounds ties down; `exact` ties to even.
                let lo = old::r(from_file);
                let hi = old::r(from_file.next_up());
                assert_eq!(exact - &lo, &hi - exact, "not a tie: {line}");
                counts.ties += 1;
            }
        };
        counts.cases += 1;
        if file.starts_with("box") {
            let b = Aabb::new(vec3::<V>(&w[6..9]), vec3::<V>(&w[9..12]));
            let t_max: V::Scalar = val(w[12]);
            let got = exact::ray_aabb(&ray, &b, t_max);
            assert_eq!(got.is_some(), ans[0] == "hit", "{line}");
            if let Some(h) = got {
                check_round(&h.enter.value, h.enter.rounded, ans[1]);
                check_round(&h.exit.value, h.exit.rounded, ans[2]);
                let old_face = old::box_face(&ray, &b).0;
                let new_face = if h.enter.value > old::int(0) {
                    h.entry_faces.first().copied()
                } else {
                    None
                };
                assert_eq!(old_face, new_face, "{line}");
            }
            assert_eq!(exact::band(&Case::Box(ray, b, t_max)), band, "{line}");
        } else if file.starts_with("triangle") {
            let tri = Triangle::new(
                vec3::<V>(&w[6..9]),
                vec3::<V>(&w[9..12]),
                vec3::<V>(&w[12..15]),
            );
            let t_max: V::Scalar = val(w[15]);
            let got = exact::ray_triangle(&ray, &tri, t_max);
            assert_eq!(got.is_some(), ans[0] == "hit", "{line}");
            if let Some(h) = got {
                check_round(&h.t.value, h.t.rounded, ans[1]);
                check_round(&h.u.value, h.u.rounded, ans[2]);
                check_round(&h.v.value, h.v.rounded, ans[3]);
                let side = if h.side == rayhit::Side::Front {
                    "front"
                } else {
                    "back"
                };
                assert_eq!(side, ans[4], "{line}");
            }
            assert_eq!(
                exact::band(&Case::Triangle(ray, tri, t_max)),
                band,
                "{line}"
            );
        } else {
            let p = Plane::new(vec3::<V>(&w[6..9]), vec3::<V>(&w[9..12]));
            let t_max: V::Scalar = val(w[12]);
            let got = exact::ray_plane(&ray, &p, t_max);
            assert_eq!(got.is_some(), ans[0] == "hit", "{line}");
            if let Some(t) = got {
                check_round(&t.value, t.rounded, ans[1]);
            }
            assert_eq!(exact::band(&Case::Plane(ray, p, t_max)), band, "{line}");
        }
    }
}

fn generated<V: Vector>(n: usize) -> usize {
    let mut count = 0;
    for (name, seed, g) in generators::box_generators::<V>() {
        let mut rng = old::Pcg32::new(seed);
        for _ in 0..n {
            let (b, ray, t_max) = g(&mut rng);
            count += 1;
            let valid = ray.is_valid() && b.is_valid();
            let old_i = if valid {
                old::box_interval(&ray, &b, t_max)
            } else {
                None
            };
            let new = exact::ray_aabb(&ray, &b, t_max);
            assert_eq!(
                old_i,
                new.as_ref()
                    .map(|h| (h.enter.value.clone(), h.exit.value.clone())),
                "{name}"
            );
            if let Some(h) = new {
                let new_face = if h.enter.value > old::int(0) {
                    h.entry_faces.first().copied()
                } else {
                    None
                };
                assert_eq!(old::box_face(&ray, &b).0, new_face, "{name}");
            }
        }
    }
    for (name, seed, g) in generators::triangle_generators::<V>() {
        let mut rng = old::Pcg32::new(seed);
        for _ in 0..n {
            let (tri, ray, t_max) = g(&mut rng);
            count += 1;
            let ex = old::triangle(&ray, &tri);
            let new = exact::ray_triangle(&ray, &tri, t_max);
            assert_eq!(ex.hits(&old::limit(t_max)), new.is_some(), "{name}");
            if let Some(h) = new {
                assert_eq!(ex.t.unwrap(), h.t.value);
                assert_eq!(ex.uv.unwrap(), (h.u.value, h.v.value));
            }
        }
    }
    let mut rng = old::Pcg32::new(7);
    for _ in 0..n {
        let (p, ray, t_max) = generators::gen_plane::<V>(&mut rng);
        count += 1;
        let old_t = if ray.is_valid() {
            old::plane_hit(&ray, &p, t_max)
        } else {
            None
        };
        assert_eq!(old_t, exact::ray_plane(&ray, &p, t_max).map(|t| t.value));
    }
    count
}

#[test]
fn old_and_new_oracles_agree() {
    let mut counts = Counts::default();
    corpus::<Vec3>("box_f32.txt", &mut counts);
    corpus::<DVec3>("box_f64.txt", &mut counts);
    corpus::<Vec3>("triangle_f32.txt", &mut counts);
    corpus::<DVec3>("triangle_f64.txt", &mut counts);
    corpus::<Vec3>("plane_f32.txt", &mut counts);
    corpus::<DVec3>("plane_f64.txt", &mut counts);
    let generated = generated::<Vec3>(2000) + generated::<DVec3>(2000);
    println!(
        "corpus cases {} (rounding ties that differ: {}), generated cases {generated}",
        counts.cases, counts.ties
    );
}
