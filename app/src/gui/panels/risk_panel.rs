//! The Risk map section of the tools panel: colour the cut walls by their distance to the
//! structures marked critical (red within the near distance, graded to the far one), pick those
//! structures from the model list, and set both distances. What it edits is the scene's
//! [`crate::scene::risk::RiskSettings`], saved with the session and undoable; the map itself is
//! computed on a worker ([`crate::gui::risk_map`]) and its legend drawn in the view.

use crate::gui::state::AppState;

/// The Risk map section.
pub fn risk_panel_ui(ui: &mut egui::Ui, app: &mut AppState) {
    let before = app.scene.risk.clone();
    let mut risk = before.clone();
    let names = app.scene.model_names();
    let selected = app
        .selected_model
        .and_then(|i| app.scene.models.get(i))
        .map(|m| m.model.name.clone());
    egui::CollapsingHeader::new(crate::gui::panels::tools_panel::title("Risk map"))
        .id_salt("risk-map")
        .default_open(!risk.critical.is_empty())
        .show(ui, |ui| {
            ui.checkbox(&mut risk.shown, "Colour walls by distance")
                .on_hover_text(
                    "Cut walls within the near distance of a critical structure are red, graded \
                     orange to yellow up to the far distance; beyond it they keep their colour \
                     (or the image). Computed exactly per wall vertex, refined where the colour \
                     changes so a wall never looks safer than it is.",
                );
            ui.horizontal(|ui| {
                ui.label("Red within");
                ui.add(
                    egui::DragValue::new(&mut risk.near_mm)
                        .range(0.0..=(risk.far_mm - 0.1).max(0.0))
                        .speed(0.05)
                        .suffix(" mm"),
                );
                ui.label("graded to");
                ui.add(
                    egui::DragValue::new(&mut risk.far_mm)
                        .range(risk.near_mm + 0.1..=crate::scene::risk::RiskSettings::MAX_MM)
                        .speed(0.1)
                        .suffix(" mm"),
                );
            });
            ui.label("Critical structures");
            let mut remove = None;
            for (k, name) in risk.critical.iter().enumerate() {
                ui.horizontal(|ui| {
                    if ui
                        .small_button("Remove")
                        .on_hover_text("No longer critical")
                        .clicked()
                    {
                        remove = Some(k);
                    }
                    if names.contains(name) {
                        ui.label(name);
                    } else {
                        ui.label(egui::RichText::new(format!("{name} (not in the scene)")).weak());
                    }
                });
            }
            if let Some(k) = remove {
                risk.critical.remove(k);
            }
            ui.horizontal_wrapped(|ui| {
                if let Some(name) = selected.as_ref().filter(|n| !risk.critical.contains(n))
                    && ui
                        .button("Add selected")
                        .on_hover_text(format!("Mark {name} critical"))
                        .clicked()
                {
                    risk.critical.push(name.clone());
                    risk.shown = true;
                }
                egui::ComboBox::from_id_salt("risk-add")
                    .selected_text("Add…")
                    .width(120.0)
                    .show_ui(ui, |ui| {
                        let candidates: Vec<&String> = names
                            .iter()
                            .filter(|n| !risk.critical.contains(n))
                            .collect();
                        for name in candidates {
                            if ui.selectable_label(false, name).clicked() {
                                risk.critical.push(name.clone());
                                risk.shown = true;
                            }
                        }
                    });
            });
            status_ui(ui, app);
        });
    if risk != before && risk.check().is_ok() {
        app.begin_edit("risk map change");
        app.scene.risk = risk;
    }
}

/// One line on what the map shows now.
fn status_ui(ui: &mut egui::Ui, app: &AppState) {
    let risk = &app.scene.risk;
    let text = if risk.critical.is_empty() {
        "Mark a structure critical to colour the walls near it.".to_string()
    } else if !risk.shown {
        "Off.".to_string()
    } else if app.scene.cutters.is_empty() {
        "No cut walls yet: cut in Edit mode.".to_string()
    } else if let Some(failed) = &app.viewport.risk.failed {
        failed.clone()
    } else if let Some(map) = crate::gui::risk_map::current(app) {
        match &map.nearest {
            Some(n) => format!(
                "Closest wall {:.1} mm from {} (the colours err toward red by at most {:.2} mm).",
                n.distance_mm, n.structure, map.margin_mm
            ),
            None => "No cut walls shown.".to_string(),
        }
    } else if app.viewport.risk.busy() {
        "Measuring the walls' distances…".to_string()
    } else {
        "Shown where the cut is shown (Camera, Preview; Edit once the cutter is released)."
            .to_string()
    };
    ui.label(egui::RichText::new(text).weak().small());
}
