//! A `no_std` user of rayhit: what a bare-metal or GPU-feeding crate does.

#![no_std]

use rayhit::glam::Vec3;
use rayhit::{Ray, Triangle, ray_triangle};

/// The `t` at which `ray` hits `tri`, if it does (rayhit's watertight test).
pub fn hit_t(ray: &Ray, tri: &Triangle) -> Option<f32> {
    ray_triangle(ray, tri, f32::INFINITY).map(|h| h.t)
}

/// The ray straight down onto `(x, y, 0)` from `z = 1`.
pub fn down_onto(x: f32, y: f32) -> Ray {
    Ray::new(Vec3::new(x, y, 1.0), Vec3::NEG_Z)
}

/// The triangles as the bytes of a vertex buffer, without copying.
#[cfg(feature = "bytemuck")]
pub fn triangle_bytes(tris: &[Triangle]) -> &[u8] {
    bytemuck::cast_slice(tris)
}

/// `ray` written into `buf` with postcard (no allocation); the bytes used.
#[cfg(feature = "serde")]
pub fn save_ray<'b>(ray: &Ray, buf: &'b mut [u8]) -> postcard::Result<&'b mut [u8]> {
    postcard::to_slice(ray, buf)
}

/// A ray read back from `save_ray`'s bytes.
#[cfg(feature = "serde")]
pub fn load_ray(bytes: &[u8]) -> postcard::Result<Ray> {
    postcard::from_bytes(bytes)
}
