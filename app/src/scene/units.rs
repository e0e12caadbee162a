//! The data's length unit and the tool defaults that follow from the target's size.
//!
//! Files carry no unit. Anatomy in millimetres (volumes always are, and the meshes exported from
//! them) measures tens to hundreds of units across; the glTF-derived reference organs are in
//! metres and measure a few units at most. So a scene whose bounding box diagonal is under
//! [`METRE_SCENE_MAX_DIAGONAL`] is taken to be in metres. Lengths are shown to the user in
//! millimetres either way ([`LengthUnit::to_mm`]), and every length a tool starts with is a
//! fraction of the target's size ([`SizeDefaults`]), so the first try looks the same on a knee in
//! millimetres and a body in metres.

use csg::Aabb;

/// Largest bounding-box diagonal (in file units) of a scene taken to be in metres: a whole body
/// is under 2.5 m; the smallest millimetre scenes (a finger bone) are over 10 mm.
pub const METRE_SCENE_MAX_DIAGONAL: f64 = 5.0;

/// What one unit of the file's coordinates is.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum LengthUnit {
    #[default]
    Millimetre,
    Metre,
}

impl LengthUnit {
    /// The unit of data with bounding box `bbox`: millimetres for volumes and for anything with
    /// a diagonal of [`METRE_SCENE_MAX_DIAGONAL`] or more, metres below.
    pub fn guess(bbox: &Aabb, from_volume: bool) -> LengthUnit {
        if from_volume || bbox.is_empty() {
            return LengthUnit::Millimetre;
        }
        let d = bbox.diagonal();
        if d.is_finite() && d > 0.0 && d < METRE_SCENE_MAX_DIAGONAL {
            LengthUnit::Metre
        } else {
            LengthUnit::Millimetre
        }
    }

    /// Millimetres per file unit.
    pub fn mm_per_unit(self) -> f64 {
        match self {
            LengthUnit::Millimetre => 1.0,
            LengthUnit::Metre => 1000.0,
        }
    }

    /// A length in file units, in millimetres.
    pub fn to_mm(self, length: f64) -> f64 {
        length * self.mm_per_unit()
    }

    /// A length in millimetres, in file units.
    pub fn from_mm(self, mm: f64) -> f64 {
        mm / self.mm_per_unit()
    }

    pub fn name(self) -> &'static str {
        match self {
            LengthUnit::Millimetre => "millimetres",
            LengthUnit::Metre => "metres",
        }
    }

    /// A length in file units written in millimetres with a sensible precision (`12.5 mm`).
    pub fn format(self, length: f64) -> String {
        let mm = self.to_mm(length);
        if mm.abs() >= 100.0 {
            format!("{mm:.0} mm")
        } else if mm.abs() >= 1.0 {
            format!("{mm:.1} mm")
        } else {
            format!("{mm:.2} mm")
        }
    }
}

/// Tool lengths (file units) a target of a given size starts with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SizeDefaults {
    /// The target's bounding-box diagonal.
    pub size: f64,
    /// Scalpel blade depth: 3 % of the target's size (6 mm on a 200 mm head).
    pub scalpel_depth: f64,
    /// Gap between the scalpel's lips once opened: 2 % of the size.
    pub scalpel_opening: f64,
    /// Closest the camera may come to its target: 0.1 % of the size.
    pub min_camera_distance: f64,
}

impl SizeDefaults {
    /// The defaults for a target with bounding box `bbox` (a unit box when it is empty).
    pub fn of(bbox: &Aabb) -> SizeDefaults {
        let d = bbox.diagonal();
        let size = if bbox.is_empty() || !d.is_finite() || d <= 0.0 {
            1.0
        } else {
            d
        };
        SizeDefaults {
            size,
            scalpel_depth: 0.03 * size,
            scalpel_opening: 0.02 * size,
            min_camera_distance: 1e-3 * size,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    fn bbox(size: DVec3) -> Aabb {
        Aabb::from_points(&[DVec3::ZERO, size])
    }

    #[test]
    fn a_body_in_metres_and_a_knee_in_millimetres_are_told_apart() {
        let body = bbox(DVec3::new(0.5, 1.6, 0.3));
        let knee = bbox(DVec3::new(95.0, 77.0, 335.0));
        assert_eq!(LengthUnit::guess(&body, false), LengthUnit::Metre);
        assert_eq!(LengthUnit::guess(&knee, false), LengthUnit::Millimetre);
        // A volume is millimetres even when tiny.
        assert_eq!(LengthUnit::guess(&body, true), LengthUnit::Millimetre);
        assert_eq!(LengthUnit::Metre.format(0.0125), "12.5 mm");
        assert_eq!(LengthUnit::Millimetre.format(250.0), "250 mm");
        assert!((LengthUnit::Metre.from_mm(5.0) - 0.005).abs() < 1e-15);
    }

    #[test]
    fn defaults_scale_with_the_target_so_both_units_look_alike() {
        let body = SizeDefaults::of(&bbox(DVec3::new(0.5, 1.6, 0.3)));
        let same_in_mm = SizeDefaults::of(&bbox(DVec3::new(500.0, 1600.0, 300.0)));
        assert!((body.scalpel_depth * 1000.0 - same_in_mm.scalpel_depth).abs() < 1e-9);
        assert!(
            body.scalpel_depth < 0.1,
            "a metre-scale depth must not be 1 unit"
        );
        let head = SizeDefaults::of(&bbox(DVec3::new(160.0, 200.0, 190.0)));
        assert!(head.scalpel_depth > 5.0 && head.scalpel_depth < 15.0);
        assert_eq!(SizeDefaults::of(&Aabb::EMPTY).size, 1.0);
    }
}
