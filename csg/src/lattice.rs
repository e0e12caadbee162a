//! The integer lattice on which the boolean decides topology.
//!
//! Every predicate of [`crate::exact`] takes lattice points. A target's lattice is fixed when its
//! [`crate::target::TargetIndex`] is built: the origin is the centre of its bounding box and the
//! step a power of two chosen so that the box spans `±2^(LATTICE_BITS − 2)` steps. Cutter points
//! may lie up to four times farther out (`±2^LATTICE_BITS`); farther is an error.
//!
//! Quantizing is the only place where input coordinates are rounded, and it affects decisions
//! only: output keeps every input vertex's exact `f64` coordinates, and only the new contour
//! vertices (computed on the lattice) are rounded back to `f64`. For a 100 mm model the step is
//! about 0.75 nm.

use glam::DVec3;

use crate::aabb::Aabb;
use crate::exact::LPoint;

/// Bits of a lattice coordinate (absolute value at most `2^LATTICE_BITS`). The bit budgets in
/// [`crate::exact`] assume at most 28.
pub const LATTICE_BITS: u32 = 28;

/// Largest allowed absolute lattice coordinate.
pub const LATTICE_MAX: i64 = 1 << LATTICE_BITS;

/// World ↔ lattice mapping: `lattice = round((world − origin) · scale)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lattice {
    /// World point mapped to lattice 0.
    pub origin: DVec3,
    /// Lattice steps per world unit; a power of two.
    pub scale: f64,
}

impl Lattice {
    /// The lattice of a target with bounding box `bbox` (any finite box; an empty or flat box gets
    /// a unit-size lattice around its centre).
    pub fn for_box(bbox: &Aabb) -> Lattice {
        let origin = if bbox.is_empty() {
            DVec3::ZERO
        } else {
            bbox.center()
        };
        let half = if bbox.is_empty() {
            1.0
        } else {
            (bbox.size().max_element() * 0.5).max(f64::MIN_POSITIVE * 1e10)
        };
        // Largest power of two with half · scale <= 2^(BITS − 2).
        let target = (1u64 << (LATTICE_BITS - 2)) as f64;
        let exp = (target / half).log2().floor();
        let scale = 2f64.powi(exp.clamp(-1000.0, 1000.0) as i32);
        Lattice { origin, scale }
    }

    /// Quantizes a world point, or `None` when it falls outside `±LATTICE_MAX` (or is not finite).
    #[inline]
    pub fn quantize(&self, p: DVec3) -> Option<LPoint> {
        let v = (p - self.origin) * self.scale;
        // Beyond `LATTICE_MAX + 1` the rounded value is out of range (and `round_half_away`
        // needs `|v| <= 2^53`).
        if !v.is_finite() || v.abs().max_element() > (LATTICE_MAX + 1) as f64 {
            return None;
        }
        let q = [
            round_half_away(v.x),
            round_half_away(v.y),
            round_half_away(v.z),
        ];
        q.iter().all(|c| c.abs() <= LATTICE_MAX).then_some(q)
    }

    /// Maps lattice coordinates (possibly fractional) back to world.
    #[inline]
    pub fn to_world(&self, l: [f64; 3]) -> DVec3 {
        DVec3::from_array(l) / self.scale + self.origin
    }

    /// Length of one lattice step in world units.
    pub fn step(&self) -> f64 {
        1.0 / self.scale
    }
}

/// `x.round()` (halves away from zero) as an integer, for `|x| <= 2^53`: the same value as
/// `f64::round`, without its library call (the baseline x86-64 target has no rounding
/// instruction), which made quantizing a 1M-vertex target take tens of milliseconds.
#[inline]
fn round_half_away(x: f64) -> i64 {
    let t = x as i64; // truncated toward zero; exact below 2^53
    let frac = x - t as f64; // exact: both are within one unit of each other
    if frac >= 0.5 {
        t + 1
    } else if frac <= -0.5 {
        t - 1
    } else {
        t
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn box_fits_with_room_for_cutters() {
        let b = Aabb {
            min: DVec3::new(-50.0, -50.0, -50.0),
            max: DVec3::new(50.0, 50.0, 50.0),
        };
        let l = Lattice::for_box(&b);
        let q = l.quantize(b.max).unwrap();
        assert!(q[0] <= 1 << (LATTICE_BITS - 2));
        assert!(q[0] > 1 << (LATTICE_BITS - 3));
        assert!(l.quantize(DVec3::splat(150.0)).is_some());
        assert!(l.quantize(DVec3::splat(1000.0)).is_none());
        assert!(l.quantize(DVec3::splat(f64::NAN)).is_none());
        let back = l.to_world([q[0] as f64, q[1] as f64, q[2] as f64]);
        assert!((back - b.max).length() < l.step());
        // Exactly `f64::round` (halves away from zero), halves and large values included.
        for x in [
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.5,
            -1.5,
            2.5,
            -2.5,
            0.49999999999999994,
            -0.49999999999999994,
            1e15 + 0.5,
            -1e15 - 0.5,
            4503599627370495.5,
            -4503599627370495.5,
            9007199254740992.0,
            123.456,
            -987.654,
        ] {
            assert_eq!(round_half_away(x), x.round() as i64, "{x}");
        }
        let edge = LATTICE_MAX as f64;
        let on_lattice = Lattice {
            origin: DVec3::ZERO,
            scale: 1.0,
        };
        assert!(on_lattice.quantize(DVec3::splat(edge + 0.49)).is_some());
        assert!(on_lattice.quantize(DVec3::splat(-edge - 0.49)).is_some());
        assert!(on_lattice.quantize(DVec3::splat(edge + 0.5)).is_none());
        assert!(on_lattice.quantize(DVec3::splat(f64::INFINITY)).is_none());
        assert!(
            on_lattice
                .quantize(DVec3::new(1.0, f64::NAN, 2.0))
                .is_none()
        );
        assert!(
            on_lattice
                .quantize(DVec3::new(1.0, 2.0, f64::NEG_INFINITY))
                .is_none()
        );
    }
}
