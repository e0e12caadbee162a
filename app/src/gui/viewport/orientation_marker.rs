//! The orientation marker in the view's lower-left corner: the patient's axes as the camera sees
//! them, coloured as in 3D Slicer (R/L red, A/P green, S/I blue), with the positive ends (R, A, S)
//! drawn solid and the negative ends (L, P, I) dimmer, far axes first.

use glam::DVec2;

use crate::view::marker::marker_axes;

/// Radius of the marker in points.
const RADIUS: f32 = 38.0;

/// Draws the marker into the lower-left corner of `rect`.
pub fn orientation_marker_ui(
    painter: &egui::Painter,
    rect: egui::Rect,
    scene: &crate::scene::Scene,
) {
    // Room for the labels past the tips (see `reach` below) inside the view.
    let margin = RADIUS * 0.7 + 8.0;
    let centre = egui::pos2(
        rect.left() + RADIUS + margin,
        rect.bottom() - RADIUS - margin,
    );
    painter.circle_filled(
        centre,
        RADIUS + 14.0,
        egui::Color32::from_rgba_unmultiplied(20, 22, 26, 110),
    );
    for axis in marker_axes(&scene.camera, &scene.orientation) {
        let positive = matches!(axis.label, "R" | "A" | "S");
        let base = match axis.label {
            "R" | "L" => egui::Color32::from_rgb(230, 70, 60),
            "A" | "P" => egui::Color32::from_rgb(80, 200, 90),
            _ => egui::Color32::from_rgb(90, 140, 250),
        };
        let colour = if positive {
            base
        } else {
            base.gamma_multiply(0.55)
        };
        let tip = to_point(centre, axis.screen * RADIUS as f64);
        painter.line_segment(
            [centre, tip],
            egui::Stroke::new(if positive { 3.0 } else { 1.5 }, colour),
        );
        // The label sits just past the tip, kept off the centre when the axis points at the eye.
        let reach = axis.screen.length().max(0.35) + 0.32;
        let dir = axis.screen.try_normalize().unwrap_or(DVec2::new(0.0, 0.0));
        let at = to_point(centre, dir * (RADIUS as f64 * reach));
        painter.text(
            at,
            egui::Align2::CENTER_CENTER,
            axis.label,
            egui::FontId::proportional(if axis.depth > -0.3 { 14.0 } else { 11.0 }),
            if axis.depth >= -0.3 {
                egui::Color32::WHITE
            } else {
                egui::Color32::from_gray(150)
            },
        );
        if !positive {
            continue;
        }
        painter.circle_filled(tip, 2.5, colour);
    }
}

fn to_point(centre: egui::Pos2, offset: DVec2) -> egui::Pos2 {
    centre + egui::vec2(offset.x as f32, offset.y as f32)
}
