//! The floor for `Instance::surface_to_world`, written with glam alone.

use rayhit::glam::Vec3A;

/// The floor for `Instance::surface_to_world`: the same point, normal and
/// error bounds (the point's `|M| (e + g(4)|p|) + c`, the normal's `|A^T|
/// (g(3)|n| + eta)`, the largest of `|A^T n| + s` times a residual),
/// written with glam's `Mat3A` and `Vec3A` and nothing else: the plain
/// transform's two matrix products and the bounds' two more, a maximum and
/// a few products and sums. The constants stand in for the instance's
/// (same shapes, plausible values), so it is timed, not compared.
pub struct SurfaceFloor {
    m: rayhit::glam::Mat3A,
    m_abs: rayhit::glam::Mat3A,
    t: Vec3A,
    c_point: Vec3A,
    a_t: rayhit::glam::Mat3A,
    a_t_abs: rayhit::glam::Mat3A,
    residual: Vec3A,
    tiny: Vec3A,
}

impl SurfaceFloor {
    pub fn new(place: &rayhit::glam::Affine3A) -> Self {
        use rayhit::glam::Mat3A;
        let abs = |m: Mat3A| Mat3A::from_cols(m.x_axis.abs(), m.y_axis.abs(), m.z_axis.abs());
        let a_t = place.matrix3.inverse().transpose();
        let u = f32::EPSILON / 2.0;
        Self {
            m: place.matrix3,
            m_abs: abs(place.matrix3),
            t: place.translation,
            c_point: place.translation.abs() * (5.0 * u),
            a_t,
            a_t_abs: abs(a_t),
            residual: Vec3A::splat(8.0 * u),
            tiny: Vec3A::splat(f32::MIN_POSITIVE),
        }
    }

    #[inline(always)]
    pub fn surface_to_world(&self, h: &rayhit::SurfacePoint) -> rayhit::SurfacePoint {
        let u = f32::EPSILON / 2.0;
        let (g3, g4) = (3.0 * u / (1.0 - 3.0 * u), 4.0 * u / (1.0 - 4.0 * u));
        let (up6, up7) = (1.0 + 7.0 * u, 1.0 + 8.0 * u);
        let (p, n) = (Vec3A::from(h.point), Vec3A::from(h.normal));
        let (e, eta) = (
            Vec3A::from(h.point_error).abs(),
            Vec3A::from(h.normal_error).abs(),
        );
        let point = self.m * p + self.t;
        let point_error = (self.m_abs * (p.abs() * g4 + e) + self.c_point) * up6;
        let normal = self.a_t * n;
        let s = self.a_t_abs * (n.abs() * g3 + eta);
        let w = (normal.abs() + s) * up6;
        let normal_error = (s + self.residual * w.max_element() + self.tiny) * up7;
        rayhit::SurfacePoint {
            point: point.into(),
            point_error: point_error.into(),
            normal: normal.into(),
            normal_error: normal_error.into(),
        }
    }
}
