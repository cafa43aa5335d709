//! The camera rows' references, each written the way it is usually
//! written (pbrt-v4's cameras, with `std`'s sines and cosines: "textbook")
//! and with nothing but the arithmetic a camera cannot do without
//! (the thin lens's "floor": the same formula with the quarter-turn
//! polynomials inlined, no grid, no select of the lens centre's ray, no
//! normalisation). The floor shows what the thin lens costs at least, next
//! to the pinhole ray; the textbook rows what the crate's cameras replace.

use rayhit::glam::Vec3;
use rayhit::{Camera, CameraSample};

/// `(sin(pi r / 2), cos(pi r / 2))` for `|r| <= 1/2`: the crate's
/// quarter-turn polynomials, by Horner's rule in `f32`.
#[inline(always)]
fn quarter(r: f32) -> (f32, f32) {
    const S: [f32; 5] = [
        1.570_796_4,
        -0.645_964_1,
        0.079_692_63,
        -0.004_681_754,
        0.000_160_441_18,
    ];
    const C: [f32; 6] = [
        1.0,
        -1.233_700_5,
        0.253_669_5,
        -0.020_863_48,
        0.000_919_260_26,
        -2.520_204_2e-5,
    ];
    let z = r * r;
    let s = (((S[4] * z + S[3]) * z + S[2]) * z + S[1]) * z + S[0];
    let c = ((((C[5] * z + C[4]) * z + C[3]) * z + C[2]) * z + C[1]) * z + C[0];
    (r * s, c)
}

/// A camera frame and film, as the references take them.
#[derive(Clone, Copy)]
pub struct Frame {
    pub eye: Vec3,
    pub forward: Vec3,
    pub right: Vec3,
    pub up: Vec3,
    pub focal: f32,
    pub w: f32,
    pub h: f32,
}

/// pbrt-v4's `PerspectiveCamera` with a lens: the normalised film
/// direction, Shirley and Chiu's concentric disc with `std`'s sine and
/// cosine, the focus point at `focal_distance / dir.z`, the normalised
/// direction from the lens point.
#[inline(always)]
pub fn thin_lens_textbook(
    f: &Frame,
    radius: f32,
    focus: f32,
    x: f32,
    y: f32,
    s: f32,
    t: f32,
) -> (Vec3, Vec3) {
    let dir =
        (f.forward * f.focal + f.right * (x - f.w * 0.5) + f.up * (f.h * 0.5 - y)).normalize();
    let (a, b) = (2.0 * s - 1.0, 2.0 * t - 1.0);
    let (la, lb) = if a == 0.0 && b == 0.0 {
        (0.0, 0.0)
    } else {
        let (r, theta) = if a.abs() > b.abs() {
            (a, core::f32::consts::FRAC_PI_4 * (b / a))
        } else {
            (
                b,
                core::f32::consts::FRAC_PI_2 - core::f32::consts::FRAC_PI_4 * (a / b),
            )
        };
        let (sin, cos) = theta.sin_cos();
        (r * cos, r * sin)
    };
    let origin = f.eye + f.right * (radius * la) + f.up * (radius * lb);
    let p_focus = f.eye + dir * (focus / dir.dot(f.forward));
    (origin, (p_focus - origin).normalize())
}

/// The thin lens's floor: the focus point on the plane of focus (two
/// products and sums), the concentric disc with one division and the
/// polynomials, the lens point, their difference.
#[inline(always)]
pub fn thin_lens_floor(
    f: &Frame,
    radius: f32,
    focus: f32,
    x: f32,
    y: f32,
    s: f32,
    t: f32,
) -> (Vec3, Vec3) {
    let (p_focus, origin, _) = focus_and_lens(f, radius, focus, (x, y), (s, t));
    (origin, p_focus - origin)
}

/// The floor's focus point and lens point, and whether the sample is
/// at the lens centre.
#[inline(always)]
fn focus_and_lens(
    f: &Frame,
    radius: f32,
    focus: f32,
    (x, y): (f32, f32),
    (s, t): (f32, f32),
) -> (Vec3, Vec3, bool) {
    let k = focus / f.focal;
    let centre = f.eye + f.forward * focus;
    let p_focus = centre + f.right * ((x - f.w * 0.5) * k) + f.up * ((f.h * 0.5 - y) * k);
    let (a, b) = (2.0 * s - 1.0, 2.0 * t - 1.0);
    let wide = a.abs() > b.abs();
    let (r, n) = if wide { (a, b) } else { (b, a) };
    // (The division guarded at the centre, so that its NaN does not
    // reach the rays of the lens-centre form.)
    let (sin, cos) = quarter(n / if r == 0.0 { 1.0 } else { r } * 0.5);
    let (la, lb) = if wide {
        (r * cos, r * sin)
    } else {
        (r * sin, r * cos)
    };
    let origin = f.eye + f.right * (radius * la) + f.up * (radius * lb);
    (p_focus, origin, (a == 0.0) & (b == 0.0))
}

/// The thin lens's floor with what its guarantees need, written
/// directly: the floor above, plus per component the grid of the focus
/// point (`6` times the binade of `max(|F_i|, M_i)`, `M` a bound on the
/// lens points, zero above `MAX / 8`) with the focus point and the lens
/// point rounded to it, so that `F - L` is exact; and, with `centre`,
/// the pinhole camera's ray for the sample at the lens centre (both
/// rays computed, one selected per component: no branch).
#[inline(always)]
pub fn thin_lens_guarantee_floor(
    pin: &rayhit::PinholeCamera,
    (f, radius, focus, lens_bound): (&Frame, f32, f32, Vec3),
    centre: bool,
    position: (f32, f32),
    sample: (f32, f32),
) -> (Vec3, Vec3) {
    let (p_focus, lens, at_centre) = focus_and_lens(f, radius, focus, position, sample);
    // (Zero above MAX / 8, where the sum would overflow.)
    let grid_of = |v: f32| {
        let b = f32::from_bits(v.to_bits() & 0x7f80_0000);
        if b <= f32::MAX * 0.125 { b * 6.0 } else { 0.0 }
    };
    let m = p_focus.abs().max(lens_bound);
    let grid = Vec3::new(grid_of(m.x), grid_of(m.y), grid_of(m.z));
    let snap = |v: Vec3| (v + grid) - grid;
    let (p_focus, origin) = (snap(p_focus), snap(lens));
    let ray = (origin, p_focus - origin);
    let pr = pin.ray(CameraSample::new(position.0, position.1));
    let sel = centre & ((radius == 0.0) | at_centre);
    let pick = |p: Vec3, q: Vec3| {
        Vec3::new(
            if sel { p.x } else { q.x },
            if sel { p.y } else { q.y },
            if sel { p.z } else { q.z },
        )
    };
    (pick(pr.origin, ray.0), pick(pr.dir, ray.1))
}

/// pbrt-v4's equirectangular `SphericalCamera`: the two angles in
/// radians, `std`'s sines and cosines, the direction in the frame.
#[inline(always)]
pub fn equirect_textbook(f: &Frame, x: f32, y: f32) -> (Vec3, Vec3) {
    let lon = core::f32::consts::TAU * (x / f.w - 0.5);
    let lat = core::f32::consts::PI * (0.5 - y / f.h);
    let (sl, cl) = lon.sin_cos();
    let (sa, ca) = lat.sin_cos();
    (
        f.eye,
        f.right * (ca * sl) + f.up * sa + f.forward * (ca * cl),
    )
}

/// `(sin, cos)` of `q` quarter turns for `|q|` below `2^22`: `k =
/// round(q)` by the sum with `1.5 * 2^23`, the quarter-turn polynomials
/// at `q - k`, and the quarter turns `k` brings as a swap by masks and
/// two sign flips from the sum's low bits. (The crate's own reduction
/// first takes out whole turns, for a range four times as wide.)
#[inline(always)]
fn sin_cos_quarters(q: f32) -> (f32, f32) {
    const C: f32 = 12_582_912.0;
    let kc = q + C;
    let (sin, cos) = quarter(q - (kc - C));
    let k = kc.to_bits();
    let swap = 0u32.wrapping_sub(k & 1);
    let (s, c) = (sin.to_bits(), cos.to_bits());
    let (a, b) = ((s & !swap) | (c & swap), (c & !swap) | (s & swap));
    // sin(x + k pi/2) is negative for k = 2, 3 modulo 4, cos for 1, 2.
    let sa = (k & 2) << 30;
    let sb = (k.wrapping_add(1) & 2) << 30;
    (f32::from_bits(a ^ sa), f32::from_bits(b ^ sb))
}

/// The equirectangular direction with the least arithmetic its
/// guarantees need, a lower bound on any such camera: each angle's
/// sine and cosine to a few ulps for positions well outside the image
/// too ([`sin_cos_quarters`]), the direction in the frame, and one
/// Newton step to unit length (the frame's rounding leaves it a few
/// tens of ulps off).
#[inline(always)]
pub fn equirect_floor(f: &Frame, x: f32, y: f32) -> Vec3 {
    let (lon, lat) = ((x - f.w * 0.5) * (4.0 / f.w), (f.h * 0.5 - y) * (2.0 / f.h));
    let (sl, cl) = sin_cos_quarters(lon);
    let (sa, ca) = sin_cos_quarters(lat);
    let d = f.right * (ca * sl) + f.up * sa + f.forward * (ca * cl);
    d * (1.5 - 0.5 * d.dot(d))
}

/// The equal-area direction with the least arithmetic its guarantees
/// need, a lower bound: the front half's map only (no fold to the back
/// half, no clamp outside the image): the square's coordinates, the
/// radius, the angle's division, its sine and cosine within a quarter
/// turn (one comparison, a subtraction and a swap), the ring's square
/// root, the direction in the frame and one Newton step.
#[inline(always)]
pub fn equal_area_floor(f: &Frame, x: f32, y: f32) -> Vec3 {
    let (u, v) = ((x - f.w * 0.5) * (2.0 / f.w), (f.h * 0.5 - y) * (2.0 / f.h));
    let (au, av) = (u.abs(), v.abs());
    let r = au + av;
    let q = av / if r == 0.0 { 1.0 } else { r };
    let turned = q > 0.5;
    let (s, c) = quarter(if turned { q - 1.0 } else { q });
    let (sin, cos) = if turned { (c, -s) } else { (s, c) };
    let ring = r * (2.0 - r * r).sqrt();
    let (lx, ly) = (cos.copysign(u) * ring, sin.copysign(v) * ring);
    let d = f.right * lx + f.up * ly + f.forward * (1.0 - r * r);
    d * (1.5 - 0.5 * d.dot(d))
}

/// pbrt-v4's `EqualAreaSquareToSphere` with `std`'s sine and cosine,
/// the square's `v` up, the direction in the frame.
#[inline(always)]
pub fn equal_area_textbook(f: &Frame, x: f32, y: f32) -> (Vec3, Vec3) {
    let (u, v) = (2.0 * x / f.w - 1.0, 1.0 - 2.0 * y / f.h);
    let (au, av) = (u.abs(), v.abs());
    let signed = 1.0 - (au + av);
    let r = 1.0 - signed.abs();
    let phi = (if r == 0.0 { 1.0 } else { (av - au) / r + 1.0 }) * core::f32::consts::FRAC_PI_4;
    let z = (1.0 - r * r).copysign(signed);
    let (sin, cos) = phi.sin_cos();
    let ring = r * (2.0 - r * r).max(0.0).sqrt();
    let (lx, ly) = (cos.copysign(u) * ring, sin.copysign(v) * ring);
    (f.eye, f.right * lx + f.up * ly + f.forward * z)
}
