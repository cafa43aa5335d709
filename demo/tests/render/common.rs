//! What the scenes' checks share: the size of their small renders and the
//! luminance their light checks compare.

use rayhit::glam::Vec3;

/// The size in pixels of the small renders most checks make.
pub const WIDTH: u32 = 64;
pub const HEIGHT: u32 = 36;

/// Rec. 709 luminance.
pub fn luminance(c: Vec3) -> f32 {
    c.dot(Vec3::new(0.2126, 0.7152, 0.0722))
}
