//! The shared workloads of the test kit prepared in every form the rows
//! take (rayhit's rays prepared or in `Vec3A`, the peers' types, the
//! floors' rays), the groups of eight and their batches, and the hit rates
//! printed above the table.

use rayhit::batch::{AabbBatch, TriangleBatch};
use rayhit::glam::{Vec3, Vec3A};
use rayhit::{Aabb, PreparedRay, Ray, Triangle, ValidAabb, ray_aabb, ray_triangle};
use rayhit_testkit::workloads::{GROUP, box_groups, rate, triangle_groups};

#[cfg(target_arch = "x86_64")]
use crate::floors::batch as floor_batch;
#[cfg(target_arch = "x86_64")]
use crate::floors::boxes8 as floor_boxes8;
use crate::floors::{FloorRay, PlainRay};
use crate::harness::INF;
use crate::harness::loops::Orders;
use crate::peers::{BvhTri, bvh_box, bvh_ray, bvh_tri, parry_box, parry_ray, parry_tri};

/// A ray in `glam::Vec3A`.
fn ray_a(r: &Ray) -> Ray<Vec3A> {
    Ray::new(r.origin.into(), r.dir.into())
}

pub struct BoxData {
    pub name: &'static str,
    /// The orders of the pairwise rows' passes.
    pub order: Orders,
    pub rays: Vec<Ray>,
    pub boxes: Vec<Aabb>,
    pub prepared: Vec<PreparedRay>,
    /// The same boxes checked once (a BVH's node boxes as it would store
    /// them): every box of the workloads is valid.
    pub valid: Vec<ValidAabb>,
    /// The same rays and boxes in `glam::Vec3A`.
    pub prepared_a: Vec<PreparedRay<Vec3A>>,
    pub boxes_a: Vec<Aabb<Vec3A>>,
    pub plain: Vec<PlainRay>,
    pub bvh_rays: Vec<bvh::ray::Ray<f32, 3>>,
    pub bvh_boxes: Vec<bvh::aabb::Aabb<f32, 3>>,
    pub parry_rays: Vec<parry3d::query::Ray>,
    pub parry_boxes: Vec<parry3d::bounding_volume::Aabb>,
}

impl BoxData {
    pub fn new(name: &'static str, rays: Vec<Ray>, boxes: Vec<Aabb>, shuffle: bool) -> Self {
        Self {
            name,
            order: Orders::new(rays.len(), shuffle),
            prepared: rays.iter().map(PreparedRay::new).collect(),
            valid: boxes
                .iter()
                .map(|b| ValidAabb::new(*b).expect("workload boxes are valid"))
                .collect(),
            prepared_a: rays.iter().map(|r| PreparedRay::new(&ray_a(r))).collect(),
            boxes_a: boxes
                .iter()
                .map(|b| Aabb::new(b.min.into(), b.max.into()))
                .collect(),
            plain: rays.iter().map(PlainRay::new).collect(),
            bvh_rays: rays.iter().map(bvh_ray).collect(),
            bvh_boxes: boxes.iter().map(bvh_box).collect(),
            parry_rays: rays.iter().map(parry_ray).collect(),
            parry_boxes: boxes.iter().map(parry_box).collect(),
            rays,
            boxes,
        }
    }
}

pub struct TriData {
    pub name: &'static str,
    /// The orders of the pairwise rows' passes.
    pub order: Orders,
    pub rays: Vec<Ray>,
    pub tris: Vec<Triangle>,
    pub prepared: Vec<PreparedRay>,
    /// The rays as the prepared floor stores them.
    pub floor_rays: Vec<FloorRay>,
    /// The same rays and triangles in `glam::Vec3A`.
    pub prepared_a: Vec<PreparedRay<Vec3A>>,
    pub tris_a: Vec<Triangle<Vec3A>>,
    pub bvh_rays: Vec<bvh::ray::Ray<f32, 3>>,
    pub bvh_tris: Vec<BvhTri>,
    pub parry_rays: Vec<parry3d::query::Ray>,
    pub parry_tris: Vec<parry3d::shape::Triangle>,
}

impl TriData {
    pub fn new(name: &'static str, rays: Vec<Ray>, tris: Vec<Triangle>, shuffle: bool) -> Self {
        Self {
            name,
            order: Orders::new(rays.len(), shuffle),
            prepared: rays.iter().map(PreparedRay::new).collect(),
            floor_rays: rays.iter().map(FloorRay::new).collect(),
            prepared_a: rays.iter().map(|r| PreparedRay::new(&ray_a(r))).collect(),
            tris_a: tris
                .iter()
                .map(|t| Triangle::new(t.a.into(), t.b.into(), t.c.into()))
                .collect(),
            bvh_rays: rays.iter().map(bvh_ray).collect(),
            bvh_tris: tris.iter().map(bvh_tri).collect(),
            parry_rays: rays.iter().map(parry_ray).collect(),
            parry_tris: tris.iter().map(parry_tri).collect(),
            rays,
            tris,
        }
    }
}

/// The groups of eight (`box x8`, `triangle x8`): ray `i` against shapes
/// `8i..8i+8`, the shapes also in batches of four and eight, and the
/// triangles as the batch floors store them.
pub struct Groups {
    pub gb: BoxData,
    pub bb4: Vec<AabbBatch<Vec3, 4>>,
    pub bb8: Vec<AabbBatch<Vec3, 8>>,
    pub gt: TriData,
    pub tb4: Vec<TriangleBatch<Vec3, 4>>,
    pub tb8: Vec<TriangleBatch<Vec3, 8>>,
    #[cfg(target_arch = "x86_64")]
    pub fb8: Vec<floor_batch::FloorBatch>,
    /// The boxes and rays as the floor of a plain call into an eight-box
    /// batch stores them.
    #[cfg(target_arch = "x86_64")]
    pub fbox8: Vec<floor_boxes8::FloorBoxes8>,
    #[cfg(target_arch = "x86_64")]
    pub fbox_rays: Vec<floor_boxes8::FloorSlabRay>,
}

impl Groups {
    pub fn new() -> Self {
        let gb = box_groups();
        let gb = BoxData::new("groups", gb.rays, gb.boxes, false);
        let bb4: Vec<AabbBatch<Vec3, 4>> = gb
            .boxes
            .chunks(4)
            .map(|c| AabbBatch::from_slice(c).expect("4"))
            .collect();
        let bb8: Vec<AabbBatch<Vec3, 8>> = gb
            .boxes
            .chunks(8)
            .map(|c| AabbBatch::from_slice(c).expect("8"))
            .collect();
        let gt = triangle_groups();
        let gt = TriData::new("groups", gt.rays, gt.triangles, false);
        let tb4: Vec<TriangleBatch<Vec3, 4>> = gt
            .tris
            .chunks(4)
            .map(|c| TriangleBatch::from_slice(c).expect("4"))
            .collect();
        let tb8: Vec<TriangleBatch<Vec3, 8>> = gt
            .tris
            .chunks(8)
            .map(|c| TriangleBatch::from_slice(c).expect("8"))
            .collect();
        #[cfg(target_arch = "x86_64")]
        let fb8: Vec<floor_batch::FloorBatch> = gt
            .tris
            .chunks(8)
            .map(floor_batch::FloorBatch::new)
            .collect();
        #[cfg(target_arch = "x86_64")]
        let fbox8 = gb
            .boxes
            .chunks(8)
            .map(floor_boxes8::FloorBoxes8::new)
            .collect();
        #[cfg(target_arch = "x86_64")]
        let fbox_rays = gb
            .rays
            .iter()
            .map(floor_boxes8::FloorSlabRay::new)
            .collect();
        Self {
            gb,
            bb4,
            bb8,
            gt,
            tb4,
            tb8,
            #[cfg(target_arch = "x86_64")]
            fb8,
            #[cfg(target_arch = "x86_64")]
            fbox8,
            #[cfg(target_arch = "x86_64")]
            fbox_rays,
        }
    }
}

/// The line above the table: how often rayhit hits on each workload.
pub fn print_hit_rates(box_data: &[BoxData], tri_data: &[TriData], g: &Groups) {
    let (gb, gt) = (&g.gb, &g.gt);
    let mut rates = Vec::new();
    for d in box_data {
        let r = rate(
            d.rays
                .iter()
                .zip(&d.boxes)
                .map(|(r, b)| ray_aabb(r, b, INF).is_some()),
        );
        rates.push(format!("box {} {:.0}%", d.name, 100.0 * r));
    }
    for d in tri_data {
        let r = rate(
            d.rays
                .iter()
                .zip(&d.tris)
                .map(|(r, t)| ray_triangle(r, t, INF).is_some()),
        );
        rates.push(format!("triangle {} {:.0}%", d.name, 100.0 * r));
    }
    let r = rate(
        gb.boxes
            .iter()
            .enumerate()
            .map(|(i, b)| ray_aabb(&gb.rays[i / GROUP], b, INF).is_some()),
    );
    rates.push(format!("box groups {:.0}%", 100.0 * r));
    let r = rate(
        gt.tris
            .iter()
            .enumerate()
            .map(|(i, t)| ray_triangle(&gt.rays[i / GROUP], t, INF).is_some()),
    );
    rates.push(format!("triangle groups {:.0}%", 100.0 * r));
    println!("Hit rates (rayhit's answers): {}.", rates.join(", "));
    println!();
}
