//! The risk map's legend in the view, bottom centre: the structures and the closest wall, the
//! colour bar (red to the near distance, graded to the far one, then the wall colour) and its
//! distances, drawn from the same [`crate::scene::risk::RiskSettings`] helpers as the legend of
//! exported pictures (`crate::annotate::risk_legend`). Shown while the walls on screen carry a
//! map.

use crate::gui::state::AppState;

/// Paints the legend when the view shows a risk map.
pub fn paint_risk_legend(painter: &egui::Painter, rect: egui::Rect, app: &AppState) {
    let Some(map) = crate::gui::risk_map::current(app) else {
        return;
    };
    let title = map.caption();
    let ink = egui::Color32::from_rgb(20, 22, 26);
    let font = egui::FontId::proportional(13.0);
    let small = egui::FontId::proportional(11.5);
    let galley = painter.layout_no_wrap(title, font, ink);
    let bar_w = (rect.width() * 0.28).clamp(180.0, 360.0);
    let bar_h = 12.0;
    let pad = 7.0;
    let box_w = galley.size().x.max(bar_w) + 2.0 * pad;
    let box_h = pad + galley.size().y + 5.0 + bar_h + 4.0 + 14.0 + pad;
    let bottom = rect.bottom() - 12.0;
    let frame = egui::Rect::from_min_size(
        egui::pos2(rect.center().x - box_w / 2.0, bottom - box_h),
        egui::vec2(box_w, box_h),
    );
    painter.rect_filled(frame, 4.0, egui::Color32::from_white_alpha(225));
    painter.galley(
        egui::pos2(frame.center().x - galley.size().x / 2.0, frame.top() + pad),
        galley,
        ink,
    );
    let bar = egui::Rect::from_min_size(
        egui::pos2(
            frame.center().x - bar_w / 2.0,
            frame.top() + pad + 13.0 + 8.0,
        ),
        egui::vec2(bar_w, bar_h),
    );
    let columns = bar_w.round() as usize;
    for c in 0..columns {
        let x = (c as f64 + 0.5) / columns as f64;
        let [r, g, b] = map
            .settings
            .legend_color(x)
            .map(|v| (v * 255.0).round() as u8);
        let left = bar.left() + c as f32 * bar_w / columns as f32;
        painter.rect_filled(
            egui::Rect::from_min_max(
                egui::pos2(left, bar.top()),
                egui::pos2(left + bar_w / columns as f32 + 0.5, bar.bottom()),
            ),
            0.0,
            egui::Color32::from_rgb(r, g, b),
        );
    }
    painter.rect_stroke(
        bar,
        0.0,
        egui::Stroke::new(1.0, ink),
        egui::StrokeKind::Outside,
    );
    for (at, caption) in map.settings.legend_marks() {
        let x = bar.left() + at as f32 * bar_w;
        painter.line_segment(
            [
                egui::pos2(x, bar.center().y),
                egui::pos2(x, bar.bottom() + 3.0),
            ],
            egui::Stroke::new(1.5, ink),
        );
        painter.text(
            egui::pos2(x, bar.bottom() + 3.0),
            egui::Align2::CENTER_TOP,
            caption,
            small.clone(),
            ink,
        );
    }
}
