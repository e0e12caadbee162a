//! The depth label at the edited cutter in Edit mode: "depth 42 mm" beside the leading plane's
//! front edge (the roller), and the depth of the plane under the pointer when it differs (Alt+wheel
//! changes that one alone).

use glam::DVec2;

use crate::gui::action::Mode;
use crate::gui::state::AppState;

/// Paints the label of the edited cutter's depth, if a cutter is edited.
pub fn paint_depth_label(painter: &egui::Painter, rect: egui::Rect, app: &AppState, ppp: f32) {
    if app.mode != Mode::Edit || app.viewport.editor_dragging() {
        return;
    }
    let editor = &app.viewport.editor;
    let (Some(depth), Some(index)) = (editor.depth(), editor.active_cutter()) else {
        return;
    };
    let Some(cutter) = app.scene.cutters.get(index) else {
        return;
    };
    let unit = app.scene.unit;
    let mm = |d: f64| {
        let mm = unit.to_mm(d);
        if mm >= 10.0 {
            format!("{mm:.0} mm")
        } else {
            format!("{mm:.1} mm")
        }
    };
    let mut text = format!("depth {}", mm(depth));
    if let Some(i) = editor.hovered_plane()
        && let Some(plane) = editor.plane_depth(i)
        && (plane - depth).abs() > 0.01 * depth
    {
        text.push_str(&format!("  (plane {}: {})", i + 1, mm(plane)));
    }
    let viewport = DVec2::new(
        rect.width() as f64 * ppp as f64,
        rect.height() as f64 * ppp as f64,
    );
    let lead = cutter.cutter.leading();
    let ends = [lead.front_top, lead.front_bottom].map(|p| app.scene.camera.project(viewport, p));
    let [Some(a), Some(b)] = ends else {
        return;
    };
    // Beyond the end of the roller that is further right on screen, so the label stays off
    // the pointer that rolls it.
    let (end, other) = if a.x >= b.x { (a, b) } else { (b, a) };
    let out = (end - other).normalize_or_zero() * 14.0;
    let at = rect.min + egui::vec2((end.x + out.x) as f32 / ppp, (end.y + out.y) as f32 / ppp);
    let font = egui::FontId::proportional(14.0);
    let galley = painter.layout_no_wrap(text, font, egui::Color32::WHITE);
    let size = galley.size();
    let pos = egui::pos2(
        at.x.clamp(
            rect.left() + 4.0,
            (rect.right() - size.x - 8.0).max(rect.left() + 4.0),
        ),
        (at.y - size.y * 0.5).clamp(
            rect.top() + 4.0,
            (rect.bottom() - size.y - 8.0).max(rect.top() + 4.0),
        ),
    );
    let back = egui::Rect::from_min_size(pos, size).expand(4.0);
    painter.rect_filled(back, 4.0, egui::Color32::from_black_alpha(170));
    painter.galley(pos, galley, egui::Color32::WHITE);
}
