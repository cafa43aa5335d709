//! A box batch's hit lanes get the entry face of their box: the face
//! `Aabb::hit` reports on the lane's box, with the same hit or miss as the
//! scalar test (see `aabb::face` for the faces against exact arithmetic).

use crate::common::props::config;
use proptest::prelude::*;
use rayhit::glam::Vec3;
use rayhit::strategies as strat;
use rayhit::{Bounds, Intersect, PreparedRay, batch::AabbBatch};

proptest! {
    #![proptest_config(config())]

    /// A batch's hit lanes get the face of their box.
    #[test]
    fn batch_lanes_get_their_faces((aabb, ray) in strat::aabb_and_ray::<Vec3>()) {
        let batch = AabbBatch::<Vec3, 8>::from_slice(&[aabb; 3]).expect("3 <= 8");
        let prepared = PreparedRay::new(&ray);
        let hits = batch.clip(&prepared, f32::INFINITY);
        for lane in 0..3 {
            let expected = aabb.hit(&prepared, f32::INFINITY);
            prop_assert_eq!(hits.get(lane).is_some(), expected.is_some());
            if let (Some(_), Some(b)) = (hits.get(lane), batch.get(lane)) {
                prop_assert_eq!(b.hit(&prepared, f32::INFINITY).and_then(|h| h.face), expected.and_then(|h| h.face));
            }
        }
        prop_assert_eq!(aabb.clip(&prepared, f32::INFINITY).is_some(), hits.mask & 1 == 1);
    }
}
