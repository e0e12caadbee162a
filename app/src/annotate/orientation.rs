//! The orientation marker's geometry: where the world axes point on screen. The world is RAS
//! millimetres (x toward the patient's Right, y Anterior, z Superior), so each axis is drawn
//! with the letter of its positive end (R, A, S) and the opposite one (L, P, I) at its negative
//! end. Egui-free and drawing-free, so the window's marker and the exported images' marker share
//! it.

use cutter::Camera;
use glam::DVec3;

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

/// The three world axes (x, y, z) as `camera` shows them.
pub fn screen_axes(camera: &Camera) -> [ScreenAxis; 3] {
    let (right, up, forward) = camera.basis();
    let axis = |d: DVec3, positive, negative| ScreenAxis {
        positive,
        negative,
        screen: [d.dot(right), -d.dot(up)],
        toward_viewer: -d.dot(forward),
    };
    [
        axis(DVec3::X, 'R', 'L'),
        axis(DVec3::Y, 'A', 'P'),
        axis(DVec3::Z, 'S', 'I'),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_anterior_view_shows_the_patient_s_right_on_the_image_left() {
        // Looking from the front (eye at +y, anterior) toward the origin, head up.
        let camera = Camera {
            eye: DVec3::new(0.0, 300.0, 0.0),
            target: DVec3::ZERO,
            up: DVec3::Z,
            fov_y_deg: 30.0,
        };
        let [x, y, z] = screen_axes(&camera);
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
