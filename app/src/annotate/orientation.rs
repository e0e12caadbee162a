//! The orientation marker's axes for exported images: the patient's axes (where the scene's
//! orientation puts them: RAS for volumes, Y-up for such meshes), each drawn with the letter of
//! its positive end (R, A, S) and the opposite one (L, P, I) at its negative end. The geometry is the window's ([`crate::view::marker`]); this only
//! regroups it by axis for the export's drawing.

use cutter::Camera;

use crate::scene::Orientation;
use crate::view::marker::marker_axes;

/// One world axis as the camera sees it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScreenAxis {
    /// Letter at the positive end (`R`, `A` or `S`) and at the negative end (`L`, `P`, `I`).
    pub positive: char,
    pub negative: char,
    /// The axis's unit direction projected on the screen, in pixels per unit with y down:
    /// length 1 when the axis lies in the image plane, 0 when it points at the viewer.
    pub screen: [f64; 2],
    /// Toward the viewer (positive) or away (negative): the axis's component against the view
    /// direction; draw the axes farthest away first.
    pub toward_viewer: f64,
}

/// The patient's three axes (right, anterior, superior, as `orientation` places them in the
/// world) as `camera` shows them: the window's marker geometry ([`crate::view::marker`]), taken
/// by positive end, so an exported image and the window agree for Z-up and Y-up scenes alike.
pub fn screen_axes(camera: &Camera, orientation: &Orientation) -> [ScreenAxis; 3] {
    let axes = marker_axes(camera, orientation);
    let axis = |positive: char, negative: char| {
        let label = positive.to_string();
        let a = axes
            .iter()
            .find(|a| a.label == label)
            .expect("the marker has all six axes");
        ScreenAxis {
            positive,
            negative,
            screen: [a.screen.x, a.screen.y],
            toward_viewer: a.depth,
        }
    };
    [axis('R', 'L'), axis('A', 'P'), axis('S', 'I')]
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn an_anterior_view_shows_the_patient_s_right_on_the_image_left() {
        // Looking from the front (eye at +y, anterior) toward the origin, head up.
        let camera = Camera {
            eye: DVec3::new(0.0, 300.0, 0.0),
            target: DVec3::ZERO,
            up: DVec3::Z,
            fov_y_deg: 30.0,
        };
        let [x, y, z] = screen_axes(&camera, &Orientation::RAS);
        assert!(
            x.screen[0] < -0.99,
            "R points to the image left: {:?}",
            x.screen
        );
        assert!(z.screen[1] < -0.99, "S points up: {:?}", z.screen);
        assert!(y.screen[0].abs() < 1e-9 && y.screen[1].abs() < 1e-9);
        assert!(y.toward_viewer > 0.99, "A points at the viewer");
        assert_eq!((x.positive, x.negative), ('R', 'L'));
    }
}
