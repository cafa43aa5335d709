//! Instances (`Instance`): world boxes, rays, surface points, spawned rays
//! and segments against exact arithmetic (`exact`), and closed meshes
//! placed by instances (`meshes`).

mod exact;
mod meshes;
