//! The patient's axes in world coordinates and the six radiological view presets.
//!
//! Data come in two conventions: medical volumes and the meshes exported from them are RAS
//! (+X right, +Y anterior, +Z superior, millimetres), while glTF-derived body models such as the
//! HuBMAP reference organs are Y-up with the body facing +Z (metres). A scene stores which world
//! directions are superior and anterior ([`Orientation`]); the patient's right follows
//! (anterior × superior, which gives +X for RAS). The guess ([`Orientation::guess`]) is made once
//! when files are opened and saved in the session, so the user can correct it for good.
//!
//! Presets name the side the viewer looks from, as in 3D Slicer: Anterior looks at the face,
//! Left at the patient's left side. Superior and inferior views keep anterior up on screen, so the
//! inferior view shows the patient's right on the screen's left, as an axial radiograph does.

use glam::DVec3;

use csg::Aabb;
use cutter::Camera;

/// Which world directions are the patient's superior and anterior (unit, orthogonal).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Orientation {
    pub superior: DVec3,
    pub anterior: DVec3,
}

impl Default for Orientation {
    fn default() -> Orientation {
        Orientation::RAS
    }
}

/// How a scene's orientation was decided (shown in the View menu).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Convention {
    /// RAS: +Z superior, +Y anterior (volumes, 3D Slicer models, the default scene).
    Ras,
    /// +Y superior, +Z anterior (glTF and the HuBMAP reference organs).
    YUp,
}

impl Orientation {
    /// RAS: superior +Z, anterior +Y (patient's right +X).
    pub const RAS: Orientation = Orientation {
        superior: DVec3::Z,
        anterior: DVec3::Y,
    };
    /// glTF convention: superior +Y, anterior +Z (patient's right −X).
    pub const Y_UP: Orientation = Orientation {
        superior: DVec3::Y,
        anterior: DVec3::Z,
    };

    /// The orientation with superior along `up` (a signed world axis), anterior along the
    /// convention's front for that axis: +Y for a Z up, +Z for a Y up, +Y for an X up.
    pub fn with_up(up: DVec3) -> Orientation {
        let up = up.normalize_or(DVec3::Z);
        let front = if up.z.abs() > 0.5 { DVec3::Y } else { DVec3::Z };
        let front = if up.x.abs() > 0.5 { DVec3::Y } else { front };
        Orientation {
            superior: up,
            anterior: front,
        }
    }

    /// The named conventions this orientation is, if any.
    pub fn convention(&self) -> Option<Convention> {
        if *self == Orientation::RAS {
            Some(Convention::Ras)
        } else if *self == Orientation::Y_UP {
            Some(Convention::YUp)
        } else {
            None
        }
    }

    /// The patient's right: anterior × superior.
    pub fn right(&self) -> DVec3 {
        self.anterior.cross(self.superior)
    }

    /// `Some` when both axes are finite, of unit length and orthogonal (what a session may hold).
    pub fn checked(superior: DVec3, anterior: DVec3) -> Option<Orientation> {
        let ok = superior.is_finite()
            && anterior.is_finite()
            && (superior.length() - 1.0).abs() < 1e-6
            && (anterior.length() - 1.0).abs() < 1e-6
            && superior.dot(anterior).abs() < 1e-6;
        ok.then_some(Orientation { superior, anterior })
    }

    /// The orientation of data whose bounding box is `bbox`: volumes are RAS; a mesh whose
    /// largest extent is along Y and at least 1.6 times the next (a body standing in a Y-up
    /// file) is Y-up; any other mesh keeps the medical file convention, RAS (a limb tall along
    /// Z already is). Only the two conventions files use are guessed: a scene longest along X is
    /// parts laid side by side or a body lying down, not one whose head points along X, so it
    /// stays RAS (View → Superior Axis offers +X for the rare file that means it).
    pub fn guess(bbox: &Aabb, from_volume: bool) -> Orientation {
        if from_volume || bbox.is_empty() {
            return Orientation::RAS;
        }
        let size = bbox.max - bbox.min;
        if !size.is_finite() {
            return Orientation::RAS;
        }
        if size.y >= 1.6 * size.x.max(size.z) {
            Orientation::Y_UP
        } else {
            Orientation::RAS
        }
    }

    /// A camera looking from `preset`'s side at `target` from `distance`, superior (or, for the
    /// superior and inferior views, anterior) up on screen.
    pub fn preset_camera(
        &self,
        preset: ViewPreset,
        target: DVec3,
        distance: f64,
        fov_y_deg: f64,
    ) -> Camera {
        let (toward_eye, up) = self.preset_axes(preset);
        Camera {
            eye: target + toward_eye * distance,
            target,
            up,
            fov_y_deg,
        }
    }

    /// (direction from the target toward the eye, up on screen) of `preset`.
    pub fn preset_axes(&self, preset: ViewPreset) -> (DVec3, DVec3) {
        let (s, a, r) = (self.superior, self.anterior, self.right());
        match preset {
            ViewPreset::Anterior => (a, s),
            ViewPreset::Posterior => (-a, s),
            ViewPreset::Left => (-r, s),
            ViewPreset::Right => (r, s),
            ViewPreset::Superior => (s, a),
            ViewPreset::Inferior => (-s, a),
        }
    }
}

/// The six standard views, named by the side the viewer looks from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ViewPreset {
    Anterior,
    Posterior,
    Left,
    Right,
    Superior,
    Inferior,
}

impl ViewPreset {
    pub const ALL: [ViewPreset; 6] = [
        ViewPreset::Anterior,
        ViewPreset::Posterior,
        ViewPreset::Left,
        ViewPreset::Right,
        ViewPreset::Superior,
        ViewPreset::Inferior,
    ];

    pub fn label(self) -> &'static str {
        match self {
            ViewPreset::Anterior => "Anterior",
            ViewPreset::Posterior => "Posterior",
            ViewPreset::Left => "Left",
            ViewPreset::Right => "Right",
            ViewPreset::Superior => "Superior",
            ViewPreset::Inferior => "Inferior",
        }
    }

    /// The key that selects the preset (the number row or the keypad; Ctrl gives the opposite
    /// side, as in Blender: 1 anterior, 3 right, 7 superior).
    pub fn key_hint(self) -> &'static str {
        match self {
            ViewPreset::Anterior => "1",
            ViewPreset::Posterior => "Ctrl+1",
            ViewPreset::Right => "3",
            ViewPreset::Left => "Ctrl+3",
            ViewPreset::Superior => "7",
            ViewPreset::Inferior => "Ctrl+7",
        }
    }

    /// The preset of digit `digit` (1, 3 or 7), the opposite side with `ctrl`.
    pub fn from_digit(digit: u8, ctrl: bool) -> Option<ViewPreset> {
        Some(match (digit, ctrl) {
            (1, false) => ViewPreset::Anterior,
            (1, true) => ViewPreset::Posterior,
            (3, false) => ViewPreset::Right,
            (3, true) => ViewPreset::Left,
            (7, false) => ViewPreset::Superior,
            (7, true) => ViewPreset::Inferior,
            _ => return None,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec2;

    fn bbox(size: DVec3) -> Aabb {
        Aabb::from_points(&[DVec3::ZERO, size])
    }

    #[test]
    fn ras_right_is_plus_x_and_y_up_right_is_minus_x() {
        assert_eq!(Orientation::RAS.right(), DVec3::X);
        assert_eq!(Orientation::Y_UP.right(), DVec3::NEG_X);
    }

    #[test]
    fn a_standing_y_up_body_is_guessed_y_up_and_a_round_head_stays_ras() {
        // HuBMAP female body: about 0.5 × 1.6 × 0.3 m.
        let body = Orientation::guess(&bbox(DVec3::new(0.5, 1.6, 0.3)), false);
        assert_eq!(body, Orientation::Y_UP);
        // A knee in RAS mm: tall along Z.
        let knee = Orientation::guess(&bbox(DVec3::new(95.0, 77.0, 335.0)), false);
        assert_eq!(knee, Orientation::RAS);
        // A head: no dominant axis, file convention.
        let head = Orientation::guess(&bbox(DVec3::new(160.0, 200.0, 190.0)), false);
        assert_eq!(head, Orientation::RAS);
        // Parts side by side along X (or a body lying along X): RAS, not X up.
        let row = Orientation::guess(&bbox(DVec3::new(30.0, 10.0, 10.0)), false);
        assert_eq!(row, Orientation::RAS);
        // A volume is RAS whatever its shape.
        let slab = Orientation::guess(&bbox(DVec3::new(10.0, 300.0, 10.0)), true);
        assert_eq!(slab, Orientation::RAS);
    }

    #[test]
    fn presets_show_the_named_side_with_superior_up() {
        let o = Orientation::Y_UP;
        let vp = DVec2::new(1280.0, 800.0);
        let right_hand = o.right() * 10.0;
        let head = o.superior * 10.0;
        // Anterior view: the patient faces the viewer, so their right is on the screen's left
        // and the head is above the centre.
        let c = o.preset_camera(ViewPreset::Anterior, DVec3::ZERO, 100.0, 30.0);
        assert!(c.eye.dot(o.anterior) > 0.0);
        let centre = c.project(vp, DVec3::ZERO).unwrap();
        assert!(c.project(vp, right_hand).unwrap().x < centre.x);
        assert!(c.project(vp, head).unwrap().y < centre.y);
        // Posterior: the right hand is on the screen's right.
        let c = o.preset_camera(ViewPreset::Posterior, DVec3::ZERO, 100.0, 30.0);
        assert!(c.project(vp, right_hand).unwrap().x > centre.x);
        // Inferior (from the feet, anterior up): patient's right on the screen's left, the
        // front above the centre.
        let c = o.preset_camera(ViewPreset::Inferior, DVec3::ZERO, 100.0, 30.0);
        assert!(c.project(vp, right_hand).unwrap().x < centre.x);
        assert!(c.project(vp, o.anterior * 10.0).unwrap().y < centre.y);
        // Left: the eye is on the patient's left.
        let c = o.preset_camera(ViewPreset::Left, DVec3::ZERO, 100.0, 30.0);
        assert!(c.eye.dot(o.right()) < 0.0);
    }

    #[test]
    fn digits_name_opposite_sides_with_ctrl() {
        for preset in ViewPreset::ALL {
            let hint = preset.key_hint();
            let ctrl = hint.starts_with("Ctrl+");
            let digit = hint.trim_start_matches("Ctrl+").parse::<u8>().unwrap();
            assert_eq!(ViewPreset::from_digit(digit, ctrl), Some(preset));
        }
        assert_eq!(ViewPreset::from_digit(5, false), None);
    }

    #[test]
    fn checked_rejects_non_orthogonal_axes() {
        assert!(Orientation::checked(DVec3::Z, DVec3::Y).is_some());
        assert!(Orientation::checked(DVec3::Z, DVec3::new(0.0, 1.0, 1.0).normalize()).is_none());
        assert!(Orientation::checked(DVec3::Z * 2.0, DVec3::Y).is_none());
    }
}
