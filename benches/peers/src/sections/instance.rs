//! The section `instance`: a world ray into 64 instances and hits back
//! to the world, rayhit's mappings with their error bounds next to glam's
//! plain transforms and the floor `floors::instance::SurfaceFloor`.

use rayhit::glam::{Vec3, Vec3A};
use rayhit::{PreparedRay, Ray, Side, Triangle};
use rayhit_testkit::rng::Pcg32;

use crate::floors::instance::SurfaceFloor;
use crate::harness::loops::over_pairs;
use crate::harness::{Kernel, kernel};

/// Instances: 64 transforms (rotations, scales 0.01 to 100 per axis, shears
/// of up to 0.5, translations up to 1e4) and 64 world rays, every pair
/// once (4096 per pass), each result stored in a buffer. The crate's
/// mapping of a world ray into the instance, with its bound, prepared,
/// against glam's transforms by the stored inverse plus
/// `PreparedRay::new`; the crate's hit to world `SurfacePoint` against
/// glam's transform of the point and of the normal by the inverse
/// transpose.
pub struct InstanceData {
    instances: Vec<rayhit::Instance>,
    inverses: Vec<rayhit::glam::Affine3A>,
    normal_maps: Vec<rayhit::glam::Mat3A>,
    /// The same placements as [`SurfaceFloor`] holds them.
    surface_floors: Vec<SurfaceFloor>,
    rays: Vec<Ray>,
    hits: Vec<rayhit::SurfacePoint>,
}

impl InstanceData {
    pub fn new() -> Self {
        use rayhit::glam::{Affine3A, Mat3A, Quat};
        let mut rng = Pcg32::with_stream(24, 5);
        let mut instances = Vec::new();
        let mut inverses = Vec::new();
        let mut normal_maps = Vec::new();
        let mut surface_floors = Vec::new();
        while instances.len() < 64 {
            let q = Quat::from_axis_angle(rng.sphere(), rng.range(0.0, core::f32::consts::TAU));
            let scale = Vec3::new(
                10f32.powf(rng.range(-2.0, 2.0)),
                10f32.powf(rng.range(-2.0, 2.0)),
                10f32.powf(rng.range(-2.0, 2.0)),
            );
            let shear = Mat3A::from_cols(
                Vec3A::X,
                Vec3A::new(rng.range(-0.5, 0.5), 1.0, 0.0),
                Vec3A::new(rng.range(-0.5, 0.5), rng.range(-0.5, 0.5), 1.0),
            );
            let m = Mat3A::from_quat(q) * shear * Mat3A::from_diagonal(scale);
            let place = Affine3A::from_mat3_translation(m.into(), rng.cube(1e4));
            if let Ok(inst) = rayhit::Instance::from_affine3a(place) {
                instances.push(inst);
                inverses.push(place.inverse());
                normal_maps.push(place.matrix3.inverse().transpose());
                surface_floors.push(SurfaceFloor::new(&place));
            }
        }
        let rays = (0..64)
            .map(|_| Ray::new(rng.cube(1e4), rng.sphere()))
            .collect();
        let hits = (0..64)
            .map(|_| {
                let tri = Triangle::new(rng.cube(1.0), rng.cube(1.0), rng.cube(1.0));
                let hit = rayhit::TriangleHit {
                    t: 1.0,
                    u: 0.25,
                    v: 0.5,
                    side: Side::Front,
                };
                tri.surface_point_at(hit.u, hit.v)
            })
            .collect();
        Self {
            instances,
            inverses,
            normal_maps,
            surface_floors,
            rays,
            hits,
        }
    }
}

pub fn instance_kernels<'a>(d: &'a InstanceData, out: &mut Vec<Kernel<'a>>) {
    let n = d.instances.len() * d.rays.len();
    let prepared_sum = |p: &(PreparedRay, rayhit::instance::InstanceRayError<Vec3>)| {
        let b = |v: Vec3| {
            u64::from(v.x.to_bits() ^ v.y.to_bits().rotate_left(7) ^ v.z.to_bits().rotate_left(13))
        };
        b(p.1.at_origin) ^ b(p.1.per_t) ^ u64::from(p.0.origin().x.to_bits())
    };
    let glam_sum = |p: &PreparedRay| u64::from(p.origin().x.to_bits() ^ p.origin().y.to_bits());
    let point_sum = |p: &rayhit::SurfacePoint| {
        u64::from(p.point.x.to_bits() ^ p.normal.y.to_bits() ^ p.point_error.z.to_bits())
    };
    let plain_sum = |p: &(Vec3, Vec3)| u64::from(p.0.x.to_bits() ^ p.1.y.to_bits());
    out.extend([
        kernel(
            "instance",
            "rayhit world_to_object + world_to_object_error + PreparedRay::new",
            "pairs",
            n,
            None,
            over_pairs(
                &d.instances,
                &d.rays,
                |i, r| {
                    let object = i.world_to_object(r);
                    (PreparedRay::new(&object), i.world_to_object_error(r))
                },
                prepared_sum,
            ),
        ),
        kernel(
            "instance",
            "glam Affine3A inverse transform_point3/vector3 + PreparedRay::new",
            "pairs",
            n,
            Some(1.0),
            over_pairs(
                &d.inverses,
                &d.rays,
                |a, r| {
                    PreparedRay::new(&Ray::new(
                        a.transform_point3(r.origin),
                        a.transform_vector3(r.dir),
                    ))
                },
                glam_sum,
            ),
        ),
        kernel(
            "instance",
            "rayhit surface_to_world",
            "pairs",
            n,
            None,
            over_pairs(
                &d.instances,
                &d.hits,
                |i, h| i.surface_to_world(h),
                point_sum,
            ),
        ),
        kernel(
            "instance",
            "floor: surface_to_world's bounds with glam Mat3A",
            "pairs",
            n,
            None,
            over_pairs(
                &d.surface_floors,
                &d.hits,
                |f, h| f.surface_to_world(h),
                point_sum,
            ),
        ),
        kernel(
            "instance",
            "glam transform_point3 + inverse-transpose normal",
            "pairs",
            n,
            Some(1.0),
            over_pairs(
                &d.inverses
                    .iter()
                    .zip(&d.normal_maps)
                    .map(|(a, m)| (a.inverse(), *m))
                    .collect::<Vec<_>>()
                    .leak()[..],
                &d.hits,
                |(a, m), h| {
                    (
                        a.transform_point3(h.point),
                        Vec3::from(*m * Vec3A::from(h.normal)),
                    )
                },
                plain_sum,
            ),
        ),
    ]);
}
