//! The adapters to the other crates: rayhit's rays, boxes and triangles
//! as `bvh` and `parry3d` (through `nalgebra`) take them, and `bvh`'s
//! triangle test as a hit distance. (`obvhs` is reached through
//! `rayhit_peers::cwbvh`.)

use nalgebra::{Point3, Vector3};
use rayhit::glam::Vec3;
use rayhit::{Aabb, Ray, Triangle};

use crate::harness::INF;

fn np(v: Vec3) -> Point3<f32> {
    Point3::new(v.x, v.y, v.z)
}

fn nv(v: Vec3) -> Vector3<f32> {
    Vector3::new(v.x, v.y, v.z)
}

fn pv(v: Vec3) -> parry3d::math::Vector {
    parry3d::math::Vector::new(v.x, v.y, v.z)
}

pub fn bvh_ray(r: &Ray) -> bvh::ray::Ray<f32, 3> {
    bvh::ray::Ray::new(np(r.origin), nv(r.dir))
}

pub fn bvh_box(b: &Aabb) -> bvh::aabb::Aabb<f32, 3> {
    bvh::aabb::Aabb::with_bounds(np(b.min), np(b.max))
}

pub fn parry_ray(r: &Ray) -> parry3d::query::Ray {
    parry3d::query::Ray::new(pv(r.origin), pv(r.dir))
}

pub fn parry_box(b: &Aabb) -> parry3d::bounding_volume::Aabb {
    parry3d::bounding_volume::Aabb::new(pv(b.min), pv(b.max))
}

pub fn parry_tri(t: &Triangle) -> parry3d::shape::Triangle {
    parry3d::shape::Triangle::new(pv(t.a), pv(t.b), pv(t.c))
}

pub type BvhTri = [Point3<f32>; 3];

pub fn bvh_tri(t: &Triangle) -> BvhTri {
    [np(t.a), np(t.b), np(t.c)]
}

pub fn bvh_hits(r: &bvh::ray::Ray<f32, 3>, t: &BvhTri) -> Option<f32> {
    let i = r.intersects_triangle(&t[0], &t[1], &t[2]);
    (i.distance < INF).then_some(i.distance)
}
