//! Rulers: straight distances between two points the user picked on surfaces, kept with the
//! scene so a saved session shows the same measurements again. Lengths are in file units and
//! shown in millimetres through the scene's unit guess ([`crate::scene::LengthUnit`]), so a body
//! in metres and a knee in millimetres both read in mm.
//!
//! Egui-free: the window picks the points and draws the rulers, `cutaway render` draws saved ones
//! over its image, and the session stores them ([`crate::session::rulers`]).

use glam::DVec3;

use crate::scene::LengthUnit;

/// One measured distance: from `a` to `b`, both points on a surface (file units).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ruler {
    pub a: DVec3,
    pub b: DVec3,
}

impl Ruler {
    /// Straight distance in file units.
    pub fn length(&self) -> f64 {
        (self.b - self.a).length()
    }

    /// Straight distance in millimetres.
    pub fn length_mm(&self, unit: LengthUnit) -> f64 {
        unit.to_mm(self.length())
    }

    /// The ruler's caption (`42.0 mm`).
    pub fn caption(&self, unit: LengthUnit) -> String {
        unit.format(self.length())
    }

    /// The point halfway between the ends, where the caption sits.
    pub fn middle(&self) -> DVec3 {
        (self.a + self.b) * 0.5
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ruler_reads_in_millimetres_whatever_the_file_unit() {
        let r = Ruler {
            a: DVec3::new(0.0, 0.0, 0.0),
            b: DVec3::new(3.0, 4.0, 0.0),
        };
        assert_eq!(r.length(), 5.0);
        assert_eq!(r.length_mm(LengthUnit::Millimetre), 5.0);
        assert_eq!(r.length_mm(LengthUnit::Metre), 5000.0);
        assert_eq!(r.caption(LengthUnit::Millimetre), "5.0 mm");
        assert_eq!(r.middle(), DVec3::new(1.5, 2.0, 0.0));
    }
}
