//! The Cut menu: a new cutter, and what the view shows of a cutter's cut — the cut itself, the
//! removed piece as a transparent ghost, slices and ribbons of it — the same switches as the
//! Cut views section of the Tools panel, for the cutter chosen there (or here, when there are
//! several). A switch is an undoable scene edit, as in the panel.

use crate::gui::action::Action;
use crate::gui::panels::cutter_panel::DEFAULT_TRANSPARENCY;
use crate::gui::state::AppState;
use crate::scene::{CutterViews, SubCutterSpec};

/// The menu.
pub fn cut_menu_ui(ui: &mut egui::Ui, app: &mut AppState) -> Vec<Action> {
    let mut actions = Vec::new();
    ui.menu_button("Cut", |ui| {
        if ui
            .button("New Cutter")
            .on_hover_text("Keep the current cutter; the next drag in Edit mode starts another")
            .clicked()
        {
            actions.push(Action::NewCutter);
        }
        ui.separator();
        if app.scene.cutters.is_empty() {
            ui.label(
                egui::RichText::new("No cutter yet: drag across a structure in Edit mode").weak(),
            );
            return;
        }
        if app.selected_cutter >= app.scene.cutters.len() {
            app.selected_cutter = 0;
        }
        if app.scene.cutters.len() > 1 {
            for i in 0..app.scene.cutters.len() {
                let target = app
                    .scene
                    .models
                    .get(app.scene.cutters[i].target)
                    .map(|m| m.model.name.as_str())
                    .unwrap_or("");
                if ui
                    .radio(
                        app.selected_cutter == i,
                        format!("Cutter {} ({target})", i + 1),
                    )
                    .clicked()
                {
                    app.selected_cutter = i;
                }
            }
            ui.separator();
        }
        let i = app.selected_cutter;
        let target = app
            .scene
            .models
            .get(app.scene.cutters[i].target)
            .map(|m| m.model.name.as_str())
            .unwrap_or("");
        ui.label(egui::RichText::new(format!("Cutter {} ({target}) shows:", i + 1)).weak());
        let before = app.scene.cutters[i].views;
        let mut views = before;
        views_items_ui(ui, &mut views);
        if views != before {
            app.begin_edit("cutter view change");
            app.scene.cutters[i].views = views;
        }
    });
    actions
}

/// The view switches of one cutter.
fn views_items_ui(ui: &mut egui::Ui, views: &mut CutterViews) {
    ui.checkbox(&mut views.cut, "Normal Cut")
        .on_hover_text("The structure with the cut taken out, its walls and contour");
    let mut transparent = views.transparency.is_some();
    if ui
        .checkbox(&mut transparent, "Removed Piece, Transparent")
        .on_hover_text("What the cut removes, drawn as a see-through ghost")
        .changed()
    {
        views.transparency = transparent.then_some(DEFAULT_TRANSPARENCY);
    }
    for (label, value, tip) in [
        (
            "Slices",
            &mut views.slices,
            "Solid slices of the removed piece, evenly spaced along the cut",
        ),
        (
            "Ribbons",
            &mut views.ribbons,
            "Strips of the removed surface, evenly spaced along the cut",
        ),
    ] {
        let mut on = value.is_some();
        if ui.checkbox(&mut on, label).on_hover_text(tip).changed() {
            *value = on.then_some(SubCutterSpec::NEW);
        }
    }
}
