//! Leaving a surface (`SurfacePoint`): rays spawned from surface points
//! (`spawn`) and shadow-ray segments between them (`spawn_to`,
//! `spawn_to_point`).

mod fuzz_regressions;
mod properties;
mod quad;
mod spawn_to;
mod sphere;
