//! The Ruler tool: while it is on, a click on a surface sets a ruler's first end and the next
//! click its second; the distance is shown in millimetres ([`crate::scene::ruler`]), the ruler is drawn
//! over the 3D view, listed in the Metrics panel (removable there) and saved in the session.
//! Drags keep turning the camera, so both ends can be picked from the best side. Adding and
//! removing rulers are undo steps.
//!
//! Points are picked on the scene as the view draws it ([`crate::cutting::drawn_hit::first_hit`]): where the
//! cut is shown, on its walls and kept parts, so a ruler can measure into the opening.

use glam::{DVec2, DVec3};

use crate::scene::ruler::Ruler;

use crate::gui::state::AppState;

pub use crate::gui::state::RulerTool;

/// The surface point under pixel `px` of the 3D view as drawn (the cut's walls and kept parts
/// where the view shows the cut), if any.
pub fn surface_point(app: &mut AppState, px: DVec2) -> Option<DVec3> {
    let ray = app.scene.camera.ray_through_pixel(app.viewport.size_px, px);
    let current = app.viewport.preview_key.as_ref()
        == Some(&crate::cutting::scene_cuts::PreviewKey::of(&app.scene));
    let preview = (crate::gui::viewport::cut_view::shows_cut(app.mode)
        && current
        && !app.scene.cutters.is_empty())
    .then(|| app.viewport.preview.clone())
    .flatten();
    crate::cutting::drawn_hit::first_hit(
        &mut app.viewport.picks,
        &app.scene,
        preview.as_deref(),
        &ray,
    )
}

/// Places a ruler end at the clicked pixel `px`: the first click starts a ruler, the second
/// finishes it (one undo step). Says what happened in the status bar.
pub fn click(app: &mut AppState, px: DVec2) {
    let Some(point) = surface_point(app, px) else {
        app.say("Ruler: no surface under the pointer");
        return;
    };
    match app.ruler.first.take() {
        None => {
            app.ruler.first = Some(point);
            app.say("Ruler: click the second point");
        }
        Some(first) => {
            let before = app.scene.clone();
            let ruler = Ruler { a: first, b: point };
            app.scene.rulers.push(ruler);
            app.record("add ruler", before);
            app.say(format!("Ruler: {}", ruler.caption(app.scene.unit)));
        }
    }
}

/// The 3D view's input while the tool is on: a primary click places an end. Returns true when
/// the click was taken.
pub fn ruler_input(
    response: &egui::Response,
    app: &mut AppState,
    to_px: impl Fn(egui::Pos2) -> DVec2,
) -> bool {
    if !response.clicked_by(egui::PointerButton::Primary) {
        return false;
    }
    let Some(pos) = response.interact_pointer_pos() else {
        return false;
    };
    click(app, to_px(pos));
    true
}

/// Draws the scene's rulers (and the first end of one being placed) over the 3D view.
pub fn paint_rulers(painter: &egui::Painter, rect: egui::Rect, app: &AppState) {
    let ppp = painter.ctx().pixels_per_point() as f64;
    let size = app.viewport.size_px;
    let camera = app.scene.camera;
    let to_screen = |p: DVec3| -> Option<egui::Pos2> {
        let px = camera.project(size, p)?;
        Some(rect.min + egui::vec2((px.x / ppp) as f32, (px.y / ppp) as f32))
    };
    let ink = egui::Color32::from_rgb(255, 200, 0);
    let outline = egui::Stroke::new(1.5, egui::Color32::BLACK);
    for ruler in &app.scene.rulers {
        let (Some(a), Some(b)) = (to_screen(ruler.a), to_screen(ruler.b)) else {
            continue;
        };
        painter.line_segment([a, b], egui::Stroke::new(4.0, egui::Color32::BLACK));
        painter.line_segment([a, b], egui::Stroke::new(2.0, ink));
        painter.circle(a, 4.0, ink, outline);
        painter.circle(b, 4.0, ink, outline);
        let middle = a + (b - a) * 0.5;
        let text = ruler.caption(app.scene.unit);
        let galley =
            painter.layout_no_wrap(text, egui::FontId::proportional(14.0), egui::Color32::BLACK);
        let at = middle + egui::vec2(6.0, -6.0 - galley.size().y);
        let back = egui::Rect::from_min_size(at, galley.size()).expand(3.0);
        painter.rect_filled(back, 3.0, ink);
        painter.galley(at, galley, egui::Color32::BLACK);
    }
    if app.ruler.active
        && let Some(first) = app.ruler.first
        && let Some(a) = to_screen(first)
    {
        painter.circle(a, 5.0, ink, outline);
    }
}

/// The Rulers section of the Metrics panel: the tool switch and every ruler with its length and a
/// remove button.
pub fn rulers_ui(ui: &mut egui::Ui, app: &mut AppState) {
    ui.heading("Rulers");
    let mut active = app.ruler.active;
    if ui
        .toggle_value(&mut active, "Ruler tool")
        .on_hover_text("Click two points on surfaces to measure the distance between them")
        .changed()
    {
        app.ruler.active = active;
        app.ruler.first = None;
        app.say(if active {
            "Ruler: click the first point on a surface"
        } else {
            "Ruler tool off"
        });
    }
    let mut remove = None;
    for (i, ruler) in app.scene.rulers.iter().enumerate() {
        ui.horizontal(|ui| {
            ui.label(format!("{}.", i + 1));
            ui.label(ruler.caption(app.scene.unit));
            if ui
                .small_button("Remove")
                .on_hover_text("Remove this ruler")
                .clicked()
            {
                remove = Some(i);
            }
        });
    }
    if app.scene.rulers.is_empty() {
        ui.label(egui::RichText::new("No rulers").weak());
    }
    if let Some(i) = remove {
        let before = app.scene.clone();
        app.scene.rulers.remove(i);
        app.record(&format!("remove ruler {}", i + 1), before);
    }
}
