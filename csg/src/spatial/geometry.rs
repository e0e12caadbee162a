//! Per-triangle geometry of the queries: the watertight ray/triangle test (Woop, Benthin and
//! Wald, JCGT 2013) and the closest point on a triangle (Ericson, Real-Time Collision Detection,
//! 5.1.5), safe for degenerate triangles.

use glam::DVec3;

use super::RayHit;
use crate::mesh::Mesh;

/// A ray prepared for the watertight test: the axis of largest direction becomes "z" and the
/// ray is sheared to run along it, so each triangle edge is tested by a 2D edge function that is
/// computed identically (up to sign) for both triangles sharing it.
#[derive(Clone, Copy, Debug)]
pub struct WatertightRay {
    origin: DVec3,
    direction: DVec3,
    /// Permuted axes: `kz` is the dominant direction axis; `kx`, `ky` keep the winding.
    kx: usize,
    ky: usize,
    kz: usize,
    /// Shear constants.
    shear: DVec3,
}

impl WatertightRay {
    /// Prepares the ray; None for a zero or non-finite direction or a non-finite origin.
    pub fn new(origin: DVec3, direction: DVec3) -> Option<WatertightRay> {
        if !origin.is_finite() || !direction.is_finite() || direction == DVec3::ZERO {
            return None;
        }
        let abs = direction.abs();
        let kz = if abs.x >= abs.y && abs.x >= abs.z {
            0
        } else if abs.y >= abs.z {
            1
        } else {
            2
        };
        let mut kx = (kz + 1) % 3;
        let mut ky = (kx + 1) % 3;
        if direction[kz] < 0.0 {
            std::mem::swap(&mut kx, &mut ky);
        }
        let shear = DVec3::new(
            direction[kx] / direction[kz],
            direction[ky] / direction[kz],
            1.0 / direction[kz],
        );
        Some(WatertightRay {
            origin,
            direction,
            kx,
            ky,
            kz,
            shear,
        })
    }

    /// Hit of triangle `face` of `mesh` with `0 <= t <= t_max`, either side.
    pub fn intersect(&self, mesh: &Mesh, face: u32, t_max: f64) -> Option<RayHit> {
        let corners = mesh.corners(face as usize);
        let [a, b, c] = corners.map(|v| v - self.origin);
        let (kx, ky, kz, s) = (self.kx, self.ky, self.kz, self.shear);
        let ax = a[kx] - s.x * a[kz];
        let ay = a[ky] - s.y * a[kz];
        let bx = b[kx] - s.x * b[kz];
        let by = b[ky] - s.y * b[kz];
        let cx = c[kx] - s.x * c[kz];
        let cy = c[ky] - s.y * c[kz];
        // Edge functions; u belongs to corner 0 (edge b-c), v to corner 1, w to corner 2.
        let u = cx * by - cy * bx;
        let v = ax * cy - ay * cx;
        let w = bx * ay - by * ax;
        if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
            return None;
        }
        let det = u + v + w;
        if det == 0.0 {
            return None;
        }
        let (az, bz, cz) = (s.z * a[kz], s.z * b[kz], s.z * c[kz]);
        let t_scaled = u * az + v * bz + w * cz;
        // t = t_scaled / det must lie in [0, t_max]; compare without dividing.
        let (t_scaled, det_abs) = if det < 0.0 {
            (-t_scaled, -det)
        } else {
            (t_scaled, det)
        };
        if t_scaled < 0.0 || t_scaled > t_max * det_abs {
            return None;
        }
        let inv = 1.0 / det;
        let bary = DVec3::new(u * inv, v * inv, w * inv);
        let t = (t_scaled / det_abs).min(t_max);
        Some(RayHit {
            face,
            t,
            bary,
            point: self.origin + self.direction * t,
        })
    }
}

/// Closest point to `p` on triangle `abc` and its barycentric weights. Safe for degenerate
/// triangles (collinear or coincident corners): they fall back to the nearest of their sides.
pub fn closest_on_triangle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> (DVec3, DVec3) {
    let ab = b - a;
    let ac = c - a;
    let ap = p - a;
    let d1 = ab.dot(ap);
    let d2 = ac.dot(ap);
    if d1 <= 0.0 && d2 <= 0.0 {
        return (a, DVec3::X);
    }
    let bp = p - b;
    let d3 = ab.dot(bp);
    let d4 = ac.dot(bp);
    if d3 >= 0.0 && d4 <= d3 {
        return (b, DVec3::Y);
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = ratio(d1, d1 - d3);
        return (a + ab * v, DVec3::new(1.0 - v, v, 0.0));
    }
    let cp = p - c;
    let d5 = ab.dot(cp);
    let d6 = ac.dot(cp);
    if d6 >= 0.0 && d5 <= d6 {
        return (c, DVec3::Z);
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = ratio(d2, d2 - d6);
        return (a + ac * w, DVec3::new(1.0 - w, 0.0, w));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = ratio(d4 - d3, (d4 - d3) + (d5 - d6));
        return (b + (c - b) * w, DVec3::new(0.0, 1.0 - w, w));
    }
    let denom = va + vb + vc;
    if denom > 0.0 {
        let v = vb / denom;
        let w = vc / denom;
        let q = a + ab * v + ac * w;
        if q.is_finite() && v >= 0.0 && w >= 0.0 && v + w <= 1.0 {
            return (q, DVec3::new(1.0 - v - w, v, w));
        }
    }
    // Degenerate (or rounding put us nowhere): the nearest point on the three sides.
    let sides = [
        closest_on_segment(p, a, b),
        closest_on_segment(p, b, c),
        closest_on_segment(p, c, a),
    ];
    let mut best = 0;
    for k in 1..3 {
        if (p - sides[k].0).length_squared() < (p - sides[best].0).length_squared() {
            best = k;
        }
    }
    let (q, s) = sides[best];
    let mut bary = DVec3::ZERO;
    bary[best] = 1.0 - s;
    bary[(best + 1) % 3] += s;
    (q, bary)
}

/// `n / d` clamped to `0..=1`, 0 when `d` is not positive.
fn ratio(n: f64, d: f64) -> f64 {
    if d > 0.0 {
        (n / d).clamp(0.0, 1.0)
    } else {
        0.0
    }
}

/// Closest point on segment `ab` to `p` and its parameter in `0..=1`.
fn closest_on_segment(p: DVec3, a: DVec3, b: DVec3) -> (DVec3, f64) {
    let ab = b - a;
    let s = ratio((p - a).dot(ab), ab.length_squared());
    (a + ab * s, s)
}
