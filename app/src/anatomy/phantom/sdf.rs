//! Implicit shapes for the phantom: signed distance *bounds* in millimetres.
//!
//! Convention: a field `f` is negative inside the shape, positive outside, and zero on its surface.
//! Every primitive here is **1-Lipschitz** (`|f(p) - f(q)| <= |p - q|`) or close to it (the
//! tapered sections are at most a few per cent steeper), so `|f(p)|` never overstates the distance
//! from `p` to the surface by more than that. Two things rely on it: the extractor skips blocks
//! whose centre value exceeds the block's half diagonal (see [`super::extract`]), and clearances
//! between parts are written as offsets (`f + 3.0` is at least 3 mm inside `f`).
//!
//! Smooth booleans use the polynomial smooth minimum (quadratic blend of width `k`): it is
//! 1-Lipschitz when its inputs are, it equals `min` wherever the inputs differ by more than `k`,
//! and it never lies above `min` by more than `k / 4`.
//!
//! There is no noise anywhere: the "bumps" are smooth ellipsoids blended in, so the phantom is a
//! pure function of the constants in the scene files.

use glam::{DVec2, DVec3};

/// A scalar field over space (mm), negative inside.
pub type Field<'a> = Box<dyn Fn(DVec3) -> f64 + Sync + Send + 'a>;

/// Sphere of radius `r` centred at `c`.
pub fn sphere(p: DVec3, c: DVec3, r: f64) -> f64 {
    (p - c).length() - r
}

/// Axis-aligned ellipsoid with semi-axes `r` centred at `c`. The field is
/// `(|q / r| - 1) * min(r)`, which is 1-Lipschitz and exact on the surface.
pub fn ellipsoid(p: DVec3, c: DVec3, r: DVec3) -> f64 {
    let q = (p - c) / r;
    (q.length() - 1.0) * r.min_element()
}

/// Capsule: the points within `r` of the segment `a`–`b`.
pub fn capsule(p: DVec3, a: DVec3, b: DVec3, r: f64) -> f64 {
    let ab = b - a;
    let t = ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0);
    (p - (a + ab * t)).length() - r
}

/// Tapered capsule ("round cone"): radius varies linearly from `ra` at `a` to `rb` at `b`. The
/// field is the distance to the segment minus the interpolated radius, which is Lipschitz with
/// constant `sqrt(1 + ((rb - ra) / |b - a|)^2)`; keep tapers gentle.
pub fn tapered_capsule(p: DVec3, a: DVec3, b: DVec3, ra: f64, rb: f64) -> f64 {
    let ab = b - a;
    let t = ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0);
    (p - (a + ab * t)).length() - (ra + (rb - ra) * t)
}

/// A smooth tube through a polyline with constant radius: the smooth union of capsules.
pub fn tube(p: DVec3, points: &[DVec3], r: f64, k: f64) -> f64 {
    let mut d = f64::INFINITY;
    for w in points.windows(2) {
        d = smin(d, capsule(p, w[0], w[1], r), k);
    }
    d
}

/// A vertical elliptic section whose semi-axes and centre vary smoothly with height: the field of
/// the cross-section ellipse at height `p.z` (scaled like [`ellipsoid`]), limited to
/// `z0 <= z <= z1` by a smooth intersection of blend width `k` (which rounds the ends).
/// `section(z)` returns (centre in xy, semi-axes in xy).
pub fn elliptic_column(
    p: DVec3,
    z0: f64,
    z1: f64,
    k: f64,
    section: impl Fn(f64) -> (DVec2, DVec2),
) -> f64 {
    let (c, r) = section(p.z.clamp(z0, z1));
    let q = (p.truncate() - c) / r;
    let radial = (q.length() - 1.0) * r.min_element();
    let half = 0.5 * (z1 - z0);
    let axial = (p.z - 0.5 * (z0 + z1)).abs() - half;
    smax(radial, axial, k)
}

/// Polynomial smooth minimum of blend width `k` (smooth union). `k = 0` is `min`.
pub fn smin(a: f64, b: f64, k: f64) -> f64 {
    if k <= 0.0 {
        return a.min(b);
    }
    let h = (k - (a - b).abs()).max(0.0) / k;
    a.min(b) - h * h * k * 0.25
}

/// Smooth maximum (smooth intersection) of blend width `k`.
pub fn smax(a: f64, b: f64, k: f64) -> f64 {
    -smin(-a, -b, k)
}

/// Smooth subtraction: `a` with `b` carved out.
pub fn ssub(a: f64, b: f64, k: f64) -> f64 {
    smax(a, -b, k)
}

/// Smooth Hermite step from 0 at `e0` to 1 at `e1`.
pub fn smoothstep(e0: f64, e1: f64, x: f64) -> f64 {
    let t = ((x - e0) / (e1 - e0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// Linear interpolation.
pub fn lerp(a: f64, b: f64, t: f64) -> f64 {
    a + (b - a) * t
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Estimates the Lipschitz constant of `f` on a lattice of points around the origin.
    fn lipschitz(f: impl Fn(DVec3) -> f64) -> f64 {
        let mut worst: f64 = 0.0;
        let step = 0.37;
        for i in -20..20 {
            for j in -20..20 {
                for k in -20..20 {
                    let p = DVec3::new(i as f64, j as f64, k as f64) * 3.1;
                    for d in [DVec3::X, DVec3::Y, DVec3::Z, DVec3::ONE.normalize()] {
                        let slope = (f(p + d * step) - f(p)).abs() / step;
                        worst = worst.max(slope);
                    }
                }
            }
        }
        worst
    }

    #[test]
    fn primitives_are_lipschitz_and_signed() {
        let c = DVec3::new(1.0, -2.0, 3.0);
        let r = DVec3::new(20.0, 10.0, 35.0);
        let e = |p| ellipsoid(p, c, r);
        assert!(lipschitz(e) <= 1.0 + 1e-9);
        assert!(e(c) < 0.0 && e(c + DVec3::new(0.0, 10.5, 0.0)) > 0.0);
        assert!(e(c + DVec3::new(19.9, 0.0, 0.0)) < 0.0);
        let a = DVec3::new(0.0, 0.0, -30.0);
        let b = DVec3::new(5.0, 3.0, 30.0);
        let t = |p| tapered_capsule(p, a, b, 12.0, 8.0);
        assert!(lipschitz(t) <= (1.0f64 + (4.0f64 / 60.0).powi(2)).sqrt() + 1e-6);
        let u = |p| smin(capsule(p, a, b, 5.0), sphere(p, c, 9.0), 6.0);
        assert!(lipschitz(u) <= 1.0 + 1e-9);
        let s = |p| ssub(sphere(p, DVec3::ZERO, 40.0), sphere(p, c, 9.0), 6.0);
        assert!(lipschitz(s) <= 1.0 + 1e-9);
        assert!(s(c) > 0.0, "the carved-out ball is outside");
    }

    #[test]
    fn smooth_min_stays_within_its_bound() {
        for (a, b) in [(0.0, 0.0), (1.0, 3.0), (-2.0, 5.0), (4.0, 4.5)] {
            let k = 2.0;
            let m = smin(a, b, k);
            assert!(m <= a.min(b) && m >= a.min(b) - k / 4.0, "{a} {b} {m}");
            assert!((smax(a, b, k) + smin(-a, -b, k)).abs() < 1e-15);
        }
        assert_eq!(smin(1.0, 5.0, 2.0), 1.0);
    }

    #[test]
    fn column_is_closed_and_rounded() {
        let f = |p: DVec3| {
            elliptic_column(p, -50.0, 50.0, 10.0, |z| {
                (DVec2::ZERO, DVec2::new(30.0 + 0.1 * z, 25.0))
            })
        };
        assert!(f(DVec3::ZERO) < 0.0);
        assert!(f(DVec3::new(0.0, 0.0, 51.0)) > 0.0);
        assert!(f(DVec3::new(0.0, 0.0, -51.0)) > 0.0);
        assert!(f(DVec3::new(33.0, 0.0, 40.0)) < 0.0 && f(DVec3::new(33.0, 0.0, -40.0)) > 0.0);
    }
}
