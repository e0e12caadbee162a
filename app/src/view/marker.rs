//! The orientation marker: the patient's six axis directions (R/L, A/P, S/I) as the camera sees
//! them, for a small axes glyph in a corner of the view.
//!
//! Only the camera's rotation matters (the marker shows directions, not positions), so the axes
//! are projected orthographically onto the camera's right and up vectors. Drawing is left to the
//! caller (egui in the window, the headless labelled export), which draws them far to near.

use glam::{DVec2, DVec3};

use cutter::Camera;

use crate::scene::Orientation;

/// One labelled direction of the marker.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MarkerAxis {
    /// `R`, `L`, `A`, `P`, `S` or `I`.
    pub label: &'static str,
    /// Screen direction of the axis, x right and y down, of length at most 1 (shorter when it
    /// points toward or away from the viewer).
    pub screen: DVec2,
    /// Positive toward the viewer, in −1..=1.
    pub depth: f64,
    /// The world direction the axis stands for.
    pub world: DVec3,
}

/// The six axes of `orientation` as `camera` sees them, farthest first (the drawing order).
pub fn marker_axes(camera: &Camera, orientation: &Orientation) -> Vec<MarkerAxis> {
    let (right, up, forward) = camera.basis();
    let o = orientation;
    let mut axes: Vec<MarkerAxis> = [
        ("R", o.right()),
        ("L", -o.right()),
        ("A", o.anterior),
        ("P", -o.anterior),
        ("S", o.superior),
        ("I", -o.superior),
    ]
    .into_iter()
    .map(|(label, world)| MarkerAxis {
        label,
        screen: DVec2::new(world.dot(right), -world.dot(up)),
        depth: -world.dot(forward),
        world,
    })
    .collect();
    axes.sort_by(|a, b| a.depth.total_cmp(&b.depth));
    axes
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::ViewPreset;

    fn axis<'a>(axes: &'a [MarkerAxis], label: &str) -> &'a MarkerAxis {
        axes.iter().find(|a| a.label == label).unwrap()
    }

    #[test]
    fn the_anterior_view_shows_superior_up_and_the_patients_right_on_the_left() {
        for o in [Orientation::RAS, Orientation::Y_UP] {
            let camera = o.preset_camera(ViewPreset::Anterior, DVec3::ZERO, 10.0, 30.0);
            let axes = marker_axes(&camera, &o);
            assert_eq!(axes.len(), 6);
            let s = axis(&axes, "S");
            assert!((s.screen - DVec2::new(0.0, -1.0)).length() < 1e-9, "{s:?}");
            let r = axis(&axes, "R");
            assert!((r.screen - DVec2::new(-1.0, 0.0)).length() < 1e-9, "{r:?}");
            // A points at the viewer and is drawn last.
            assert_eq!(axes.last().unwrap().label, "A");
            assert!((axes.last().unwrap().depth - 1.0).abs() < 1e-9);
            assert_eq!(axes.first().unwrap().label, "P");
        }
    }

    #[test]
    fn the_marker_turns_with_the_camera() {
        let o = Orientation::RAS;
        let camera = o.preset_camera(ViewPreset::Left, DVec3::ZERO, 10.0, 30.0);
        let axes = marker_axes(&camera, &o);
        // From the patient's left, anterior is on the screen's left.
        assert!(axis(&axes, "A").screen.x < -0.99);
        assert_eq!(axes.last().unwrap().label, "L");
    }
}
