//! Throughput of every kernel on the test kit's fixed-seed workloads
//! (`rayhit_testkit::workloads`: see there for what each one is and its hit
//! rate, which this bench prints first).
//!
//! `cargo bench --bench kernels` runs it all in a few minutes on 2 cores;
//! `cargo bench --bench kernels -- box/` runs one group. Criterion reports
//! time per iteration and elements per second; one element is one ray/shape
//! test, so nanoseconds per test are the reciprocal of the throughput.
//! Peers (`bvh`, `parry3d`) are timed on the same data by `benches/peers`.

use std::hint::black_box;
use std::time::Duration;

use criterion::{BenchmarkGroup, Criterion, Throughput, criterion_group, criterion_main};
use rayhit::glam::{DVec3, Vec3};
use rayhit::{
    Aabb, Bounds, Camera, DAabb, DRay, DTriangle, Intersect, IntersectLanes, PreparedRay, Ray,
    Triangle,
    batch::{AabbBatch, TriangleBatch},
    ray_aabb, ray_plane, ray_triangle,
};
use rayhit_testkit::workloads::*;

type Group<'a> = BenchmarkGroup<'a, criterion::measurement::WallTime>;

const INF: f32 = f32::INFINITY;

fn prepare(rays: &[Ray]) -> Vec<PreparedRay> {
    rays.iter().map(PreparedRay::new).collect()
}

/// Prints each workload's hit rate, so the numbers below can be read.
fn hit_rates() {
    let mut lines = Vec::new();
    for w in box_workloads() {
        let hits = w.rays.iter().zip(&w.boxes);
        let r = rate(hits.map(|(r, b)| ray_aabb(r, b, INF).is_some()));
        lines.push(format!("box/{}: {:.0}% hit", w.name, 100.0 * r));
    }
    for w in triangle_workloads() {
        let pairs = || w.rays.iter().zip(&w.triangles);
        let r = rate(pairs().map(|(r, t)| ray_triangle(r, t, INF).is_some()));
        let front =
            rate(pairs().map(|(r, t)| {
                ray_triangle(r, t, INF).is_some_and(|h| h.side == rayhit::Side::Front)
            }));
        lines.push(format!(
            "triangle/{}: {:.0}% hit ({:.0}% from the front)",
            w.name,
            100.0 * r,
            100.0 * front
        ));
    }
    let g = box_groups();
    let r = rate(
        g.boxes
            .iter()
            .enumerate()
            .map(|(i, b)| ray_aabb(&g.rays[i / GROUP], b, INF).is_some()),
    );
    lines.push(format!("box groups: {:.0}% of boxes hit", 100.0 * r));
    let g = triangle_groups();
    let r = rate(
        g.triangles
            .iter()
            .enumerate()
            .map(|(i, t)| ray_triangle(&g.rays[i / GROUP], t, INF).is_some()),
    );
    lines.push(format!(
        "triangle groups: {:.0}% of triangles hit",
        100.0 * r
    ));
    let (rays, planes) = plane_pairs();
    let r = rate(
        rays.iter()
            .zip(&planes)
            .map(|(r, p)| ray_plane(r, p, INF).is_some()),
    );
    lines.push(format!("plane: {:.0}% hit", 100.0 * r));
    eprintln!("hit rates of the workloads:\n  {}", lines.join("\n  "));
}

fn camera_and_plane(c: &mut Criterion) {
    let mut g = c.benchmark_group("camera");
    g.throughput(Throughput::Elements(PAIRS as u64));
    let cam = camera();
    g.bench_function("pixel_ray 64x64", |b| {
        b.iter(|| {
            let cam = black_box(&cam);
            let mut acc = Vec3::ZERO;
            for j in 0..64 {
                for i in 0..64 {
                    acc += cam.pixel_ray(i, j).dir;
                }
            }
            acc
        })
    });
    g.finish();

    let mut g = c.benchmark_group("plane");
    g.throughput(Throughput::Elements(PAIRS as u64));
    let (rays, planes) = plane_pairs();
    g.bench_function("ray_plane", |b| {
        b.iter(|| {
            let mut acc = 0.0f32;
            for (r, p) in black_box(&rays).iter().zip(black_box(&planes)) {
                acc += ray_plane(r, p, INF).unwrap_or(0.0);
            }
            acc
        })
    });
    g.finish();
}

fn count_boxes(rays: &[Ray], boxes: &[Aabb], f: impl Fn(&Ray, &Aabb) -> bool) -> u32 {
    let mut n = 0;
    for (r, b) in rays.iter().zip(boxes) {
        n += u32::from(f(r, b));
    }
    n
}

fn boxes(c: &mut Criterion) {
    for w in box_workloads() {
        let mut g = c.benchmark_group(format!("box/{}", w.name));
        g.throughput(Throughput::Elements(w.rays.len() as u64));
        let (rays, boxes) = (&w.rays, &w.boxes);
        let prepared = prepare(rays);
        g.bench_function("slab", |b| {
            b.iter(|| {
                count_boxes(black_box(rays), black_box(boxes), |r, x| {
                    ray_aabb(r, x, INF).is_some()
                })
            })
        });
        g.bench_function("slab_prepared", |b| {
            b.iter(|| {
                let mut n = 0u32;
                for (r, x) in black_box(&prepared).iter().zip(black_box(boxes)) {
                    n += u32::from(x.clip(r, INF).is_some());
                }
                n
            })
        });
        g.bench_function("naive", |b| {
            b.iter(|| {
                count_boxes(black_box(rays), black_box(boxes), |r, x| {
                    x.clip_by_faces(r, INF).is_some()
                })
            })
        });
        g.finish();
    }
}

fn sum_t(rays: &[Ray], tris: &[Triangle], f: impl Fn(&Ray, &Triangle) -> Option<f32>) -> f32 {
    let mut acc = 0.0;
    for (r, t) in rays.iter().zip(tris) {
        acc += f(r, t).unwrap_or(0.0);
    }
    acc
}

fn triangles(c: &mut Criterion) {
    for w in triangle_workloads() {
        let mut g = c.benchmark_group(format!("triangle/{}", w.name));
        g.throughput(Throughput::Elements(w.rays.len() as u64));
        let (rays, tris) = (&w.rays, &w.triangles);
        let prepared = prepare(rays);
        g.bench_function("watertight", |b| {
            b.iter(|| {
                sum_t(black_box(rays), black_box(tris), |r, t| {
                    ray_triangle(r, t, INF).map(|h| h.t)
                })
            })
        });
        g.bench_function("watertight_prepared", |b| {
            b.iter(|| {
                let mut acc = 0.0f32;
                for (r, t) in black_box(&prepared).iter().zip(black_box(tris)) {
                    acc += t.hit(r, INF).map_or(0.0, |h| h.t);
                }
                acc
            })
        });
        g.bench_function("moller_trumbore", |b| {
            b.iter(|| {
                sum_t(black_box(rays), black_box(tris), |r, t| {
                    t.moller_trumbore(r, INF).map(|h| h.t)
                })
            })
        });
        g.finish();
    }
}

/// One ray against each group of 8: scalar per shape, and batches of 4, 8
/// and 16 (two groups per batch of 16, so that one is two rays' worth).
fn groups(c: &mut Criterion) {
    let gb = box_groups();
    let prepared = prepare(&gb.rays);
    let mut g = c.benchmark_group("groups/box");
    g.throughput(Throughput::Elements(gb.boxes.len() as u64));
    g.bench_function("slab_prepared x8", |b| {
        b.iter(|| {
            let mut n = 0u32;
            for (r, group) in black_box(&prepared).iter().zip(gb.boxes.chunks(GROUP)) {
                for x in group {
                    n += u32::from(x.clip(r, INF).is_some());
                }
            }
            n
        })
    });
    box_batches::<4>(&mut g, &prepared, &gb.boxes);
    box_batches::<8>(&mut g, &prepared, &gb.boxes);
    g.finish();

    let gt = triangle_groups();
    let prepared = prepare(&gt.rays);
    let mut g = c.benchmark_group("groups/triangle");
    g.throughput(Throughput::Elements(gt.triangles.len() as u64));
    g.bench_function("watertight x8", |b| {
        b.iter(|| {
            let mut acc = 0.0f32;
            for (r, group) in black_box(&gt.rays).iter().zip(gt.triangles.chunks(GROUP)) {
                for t in group {
                    acc += ray_triangle(r, t, INF).map_or(0.0, |h| h.t);
                }
            }
            acc
        })
    });
    g.bench_function("watertight_prepared x8", |b| {
        b.iter(|| {
            let mut acc = 0.0f32;
            for (r, group) in black_box(&prepared).iter().zip(gt.triangles.chunks(GROUP)) {
                for t in group {
                    acc += t.hit(r, INF).map_or(0.0, |h| h.t);
                }
            }
            acc
        })
    });
    triangle_batches::<4>(&mut g, &prepared, &gt.triangles);
    triangle_batches::<8>(&mut g, &prepared, &gt.triangles);
    g.finish();
}

fn box_batches<const N: usize>(g: &mut Group<'_>, rays: &[PreparedRay], boxes: &[Aabb]) {
    let batches: Vec<Vec<AabbBatch<Vec3, N>>> = boxes
        .chunks(GROUP)
        .map(|group| {
            group
                .chunks(N)
                .map(|c| AabbBatch::from_slice(c).expect("N boxes"))
                .collect()
        })
        .collect();
    g.bench_function(format!("batch{N}"), |b| {
        b.iter(|| {
            let mut n = 0u32;
            for (r, group) in black_box(rays).iter().zip(black_box(&batches)) {
                for batch in group {
                    n += batch.clip(r, INF).mask.count_ones();
                }
            }
            n
        })
    });
}

fn triangle_batches<const N: usize>(
    g: &mut Group<'_>,
    rays: &[PreparedRay],
    triangles: &[Triangle],
) {
    let batches: Vec<Vec<TriangleBatch<Vec3, N>>> = triangles
        .chunks(GROUP)
        .map(|group| {
            group
                .chunks(N)
                .map(|c| TriangleBatch::from_slice(c).expect("N triangles"))
                .collect()
        })
        .collect();
    g.bench_function(format!("batch{N}"), |b| {
        b.iter(|| {
            let mut acc = 0.0f32;
            for (r, group) in black_box(rays).iter().zip(black_box(&batches)) {
                for batch in group {
                    let hits = batch.hit(r, INF);
                    let mut bits = hits.mask;
                    while bits != 0 {
                        acc += hits.t[bits.trailing_zeros() as usize];
                        bits &= bits - 1;
                    }
                }
            }
            acc
        })
    });
}

const SWEEP: [usize; 8] = [1, 2, 4, 8, 32, 128, 512, 1024];

/// One ray against the first N boxes (a BVH node test, all children) and
/// against the first N triangles (a leaf: nearest hit, `t_max` shrinking
/// as hits are found); per-shape cost should not depend on N past 8.
fn sweep(c: &mut Criterion) {
    let (rays, boxes) = box_sweep();
    let prepared = prepare(&rays);
    let mut g = c.benchmark_group("sweep/box");
    for n in SWEEP {
        g.throughput(Throughput::Elements((rays.len() * n) as u64));
        let boxes = &boxes[..n];
        g.bench_function(format!("slab_prepared/{n}"), |b| {
            b.iter(|| {
                let mut hits = 0u32;
                for r in black_box(&prepared) {
                    for x in black_box(boxes) {
                        hits += u32::from(x.clip(r, INF).is_some());
                    }
                }
                hits
            })
        });
        let batches: Vec<AabbBatch<Vec3, 8>> = boxes
            .chunks(8)
            .map(|c| AabbBatch::from_slice(c).expect("8 boxes"))
            .collect();
        g.bench_function(format!("batch8/{n}"), |b| {
            b.iter(|| {
                let mut hits = 0u32;
                for r in black_box(&prepared) {
                    for batch in black_box(&batches) {
                        hits += batch.clip(r, INF).mask.count_ones();
                    }
                }
                hits
            })
        });
    }
    g.finish();

    let (rays, tris) = triangle_sweep();
    let prepared = prepare(&rays);
    let mut g = c.benchmark_group("sweep/triangle");
    for n in SWEEP {
        g.throughput(Throughput::Elements((rays.len() * n) as u64));
        let tris = &tris[..n];
        g.bench_function(format!("watertight_prepared/{n}"), |b| {
            b.iter(|| {
                let mut acc = 0.0f32;
                for r in black_box(&prepared) {
                    let mut t_max = INF;
                    for t in black_box(tris) {
                        if let Some(h) = t.hit(r, t_max) {
                            t_max = h.t;
                        }
                    }
                    acc += t_max.min(1e9);
                }
                acc
            })
        });
        let batches: Vec<TriangleBatch<Vec3, 8>> = tris
            .chunks(8)
            .map(|c| TriangleBatch::from_slice(c).expect("8 triangles"))
            .collect();
        g.bench_function(format!("batch8/{n}"), |b| {
            b.iter(|| {
                let mut acc = 0.0f32;
                for r in black_box(&prepared) {
                    let mut t_max = INF;
                    for batch in black_box(&batches) {
                        if let Some((_, h)) = batch.hit(r, t_max).nearest() {
                            t_max = h.t;
                        }
                    }
                    acc += t_max.min(1e9);
                }
                acc
            })
        });
    }
    g.finish();
}

/// The same kernels in `f64`, on the aimed workloads and the groups.
fn double(c: &mut Criterion) {
    let d = |v: Vec3| v.as_dvec3();
    let dray = |r: &Ray| DRay::new(d(r.origin), d(r.dir));
    let w = &box_workloads()[1];
    let rays: Vec<PreparedRay<DVec3>> = w.rays.iter().map(|r| PreparedRay::new(&dray(r))).collect();
    let boxes: Vec<DAabb> = w
        .boxes
        .iter()
        .map(|b| DAabb::new(d(b.min), d(b.max)))
        .collect();
    let mut g = c.benchmark_group("f64");
    g.throughput(Throughput::Elements(PAIRS as u64));
    g.bench_function("box/aimed/slab_prepared", |b| {
        b.iter(|| {
            let mut n = 0u32;
            for (r, x) in black_box(&rays).iter().zip(black_box(&boxes)) {
                n += u32::from(x.clip(r, f64::INFINITY).is_some());
            }
            n
        })
    });
    let w = &triangle_workloads()[1];
    let rays: Vec<DRay> = w.rays.iter().map(dray).collect();
    let tris: Vec<DTriangle> = w
        .triangles
        .iter()
        .map(|t| DTriangle::new(d(t.a), d(t.b), d(t.c)))
        .collect();
    g.bench_function("triangle/aimed/watertight", |b| {
        b.iter(|| {
            let mut acc = 0.0f64;
            for (r, t) in black_box(&rays).iter().zip(black_box(&tris)) {
                acc += ray_triangle(r, t, f64::INFINITY).map_or(0.0, |h| h.t);
            }
            acc
        })
    });
    let gb = box_groups();
    let rays: Vec<PreparedRay<DVec3>> =
        gb.rays.iter().map(|r| PreparedRay::new(&dray(r))).collect();
    let batches: Vec<AabbBatch<DVec3, 8>> = gb
        .boxes
        .chunks(GROUP)
        .map(|c| {
            let c: Vec<DAabb> = c.iter().map(|b| DAabb::new(d(b.min), d(b.max))).collect();
            AabbBatch::from_slice(&c).expect("8 boxes")
        })
        .collect();
    g.bench_function("groups/box/batch8", |b| {
        b.iter(|| {
            let mut n = 0u32;
            for (r, batch) in black_box(&rays).iter().zip(black_box(&batches)) {
                n += batch.clip(r, f64::INFINITY).mask.count_ones();
            }
            n
        })
    });
    let gt = triangle_groups();
    let rays: Vec<PreparedRay<DVec3>> =
        gt.rays.iter().map(|r| PreparedRay::new(&dray(r))).collect();
    let batches: Vec<TriangleBatch<DVec3, 8>> = gt
        .triangles
        .chunks(GROUP)
        .map(|c| {
            let c: Vec<DTriangle> = c
                .iter()
                .map(|t| DTriangle::new(d(t.a), d(t.b), d(t.c)))
                .collect();
            TriangleBatch::from_slice(&c).expect("8 triangles")
        })
        .collect();
    g.bench_function("groups/triangle/batch8", |b| {
        b.iter(|| {
            let mut acc = 0.0f64;
            for (r, batch) in black_box(&rays).iter().zip(black_box(&batches)) {
                acc += batch
                    .hit(r, f64::INFINITY)
                    .nearest()
                    .map_or(0.0, |(_, h)| h.t);
            }
            acc
        })
    });
    g.finish();
}

fn config() -> Criterion {
    hit_rates();
    Criterion::default()
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_millis(700))
        .sample_size(20)
}

criterion_group! {
    name = kernels;
    config = config();
    targets = camera_and_plane, boxes, triangles, groups, sweep, double
}
criterion_main!(kernels);
