//! Each kernel as an out-of-line function of its own, so that its machine
//! code can be read and its instructions counted (BENCHMARKS.md, "aarch64
//! (NEON)"): in the built binary (`cargo bench --no-run --bench
//! kernel_asm` prints its path), `objdump -dC` shows the code of
//! `kernel_asm::box_batch_8` and the others under those names. `main`
//! calls each once on an opaque input, which keeps them in the binary.

use std::hint::black_box;

use rayhit::glam::Vec3;
use rayhit::{
    Aabb, Bounds, Intersect, IntersectLanes, PreparedRay, Ray, Triangle, TriangleHit,
    batch::{AabbBatch, AabbBatchHits, QuantizedChildren, TriangleBatch, TriangleBatchHits},
};

/// `Aabb::clip` with a `PreparedRay`: one box, the slab test on four lanes.
#[inline(never)]
pub fn box_prepared(ray: &PreparedRay, aabb: &Aabb, t_max: f32) -> Option<(f32, f32)> {
    aabb.clip(ray, t_max)
}

/// `Triangle::hit` with a `PreparedRay`: one triangle, the watertight test.
#[inline(never)]
pub fn triangle_prepared(ray: &PreparedRay, tri: &Triangle, t_max: f32) -> Option<TriangleHit> {
    tri.hit(ray, t_max)
}

/// `AabbBatch::clip` on 8 boxes.
#[inline(never)]
pub fn box_batch_8(ray: &PreparedRay, b: &AabbBatch<Vec3, 8>, t_max: f32) -> AabbBatchHits<f32, 8> {
    b.clip(ray, t_max)
}

/// `AabbBatch::clip` on 16 boxes.
#[inline(never)]
pub fn box_batch_16(
    ray: &PreparedRay,
    b: &AabbBatch<Vec3, 16>,
    t_max: f32,
) -> AabbBatchHits<f32, 16> {
    b.clip(ray, t_max)
}

/// `TriangleBatch::hit` on 8 triangles.
#[inline(never)]
pub fn triangle_batch_8(
    ray: &PreparedRay,
    b: &TriangleBatch<Vec3, 8>,
    t_max: f32,
) -> TriangleBatchHits<f32, 8> {
    b.hit(ray, t_max)
}

/// `TriangleBatch::hit` on 16 triangles.
#[inline(never)]
pub fn triangle_batch_16(
    ray: &PreparedRay,
    b: &TriangleBatch<Vec3, 16>,
    t_max: f32,
) -> TriangleBatchHits<f32, 16> {
    b.hit(ray, t_max)
}

/// `QuantizedChildren::clip`: the eight children of a compressed node.
#[inline(never)]
pub fn quantized_children(
    ray: &PreparedRay,
    node: &QuantizedChildren<'_, Vec3>,
    t_max: f32,
) -> AabbBatchHits<f32, 8> {
    node.clip(ray, t_max)
}

fn main() {
    let ray = PreparedRay::new(&Ray::new(Vec3::splat(-1.0), Vec3::ONE));
    let ray = black_box(&ray);
    let aabb = Aabb::new(Vec3::ZERO, Vec3::ONE);
    let tri = Triangle::new(Vec3::X, Vec3::Y, Vec3::Z);
    let boxes = [aabb; 16];
    let tris = [tri; 16];
    let (lo, hi) = ([0; 8], [4; 8]);
    let node = QuantizedChildren {
        origin: Vec3::ZERO,
        exponents: [127; 3],
        min: [&lo, &lo, &lo],
        max: [&hi, &hi, &hi],
    };
    let inf = black_box(f32::INFINITY);
    let batch = |n: usize| black_box(&boxes[..n]);
    let tri_batch = |n: usize| black_box(&tris[..n]);
    let hits = [
        box_prepared(ray, black_box(&aabb), inf).is_some(),
        triangle_prepared(ray, black_box(&tri), inf).is_some(),
        box_batch_8(ray, &AabbBatch::from_slice(batch(8)).unwrap(), inf).mask == 0xff,
        box_batch_16(ray, &AabbBatch::from_slice(batch(16)).unwrap(), inf).mask == 0xffff,
        triangle_batch_8(ray, &TriangleBatch::from_slice(tri_batch(8)).unwrap(), inf).mask == 0xff,
        triangle_batch_16(ray, &TriangleBatch::from_slice(tri_batch(16)).unwrap(), inf).mask
            == 0xffff,
        quantized_children(ray, black_box(&node), inf).mask == 0xff,
    ];
    println!("{hits:?}");
}
