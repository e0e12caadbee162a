//! The cutter tabs (thesis 3.5 E): Initialization (segment spacing ω, type Freeform/Wedge,
//! smoothing and its Smoothness levels) for the next cutter and the one being edited, and Visualization per cutter (Normal Cut, Transparency with
//! its opacity, Slices, Ribbons with count and width) for Preview mode, and the "Live cut" toggle
//! (the cut shown while painting in Edit mode, see [`crate::gui::viewport::live_cut`]).

use crate::gui::action::Action;
use crate::gui::state::AppState;
use crate::scene::SubCutterView;
use cutter::CutKind;

pub use crate::gui::state::CutterTab;

pub fn cutter_panel_ui(ui: &mut egui::Ui, app: &mut AppState) -> Vec<Action> {
    let mut actions = Vec::new();
    ui.heading("Cutter");
    ui.checkbox(&mut app.viewport.live.enabled, "Live cut")
        .on_hover_text("In Edit mode, show the cut (kept part, walls, contour) under the cutter while you paint it; the cut runs in the background");
    ui.separator();
    ui.horizontal(|ui| {
        for (tab, label) in [
            (CutterTab::Initialization, "Initialization"),
            (CutterTab::Visualization, "Visualization"),
        ] {
            if ui.selectable_label(app.cutter_tab == tab, label).clicked() {
                app.cutter_tab = tab;
            }
        }
    });
    ui.add_space(4.0);
    match app.cutter_tab {
        CutterTab::Initialization => initialization_ui(ui, app, &mut actions),
        CutterTab::Visualization => visualization_ui(ui, app, &mut actions),
    }
    actions
}

fn initialization_ui(ui: &mut egui::Ui, app: &mut AppState, actions: &mut Vec<Action>) {
    let before = app.cutter_init.clone();
    egui::Grid::new("cutter-init")
        .num_columns(2)
        .spacing([10.0, 6.0])
        .show(ui, |ui| {
            ui.label("Segment spacing ω")
                .on_hover_text("A new box starts every ω·δ of extrusion (δ = scene size / 2000)");
            ui.add(
                egui::Slider::new(&mut app.cutter_init.spacing, 2.0..=200.0)
                    .logarithmic(true)
                    .fixed_decimals(0),
            );
            ui.end_row();
            ui.label("Type");
            ui.horizontal(|ui| {
                let kind = &mut app.cutter_init.kind;
                let freeform = *kind != CutKind::Wedge;
                if ui
                    .selectable_label(freeform, "Freeform")
                    .on_hover_text("Paint-roller path; hold Shift for a straight path")
                    .clicked()
                {
                    *kind = CutKind::Curving;
                }
                if ui
                    .selectable_label(!freeform, "Wedge")
                    .on_hover_text("All planes share one top edge")
                    .clicked()
                {
                    *kind = CutKind::Wedge;
                }
            });
            ui.end_row();
            ui.label("Smoothing");
            ui.checkbox(&mut app.cutter_init.smooth, "Rounded (subdivided) cutter");
            ui.end_row();
            if app.cutter_init.smooth {
                let label = ui.label("Smoothness");
                ui.add(egui::Slider::new(
                    &mut app.cutter_init.levels,
                    0..=cutter::subdivision::MAX_LEVELS,
                ))
                .labelled_by(label.id)
                .on_hover_text(
                    "Subdivision levels of the rounded cutter: 0 draws and cuts the boxes, each \
                     level splits every face in four where the path turns (straight runs stay \
                     coarser). Saved with the cutter; undoable.",
                );
                ui.end_row();
            }
        });
    if app.cutter_init != before {
        app.cutter_settings_changed();
    }
    ui.add_space(4.0);
    expose_ui(ui, app, actions);
    ui.add_space(4.0);
    if ui
        .button("New Cutter")
        .on_hover_text("Keep the current cutter; the next drag in Edit mode starts another")
        .clicked()
    {
        actions.push(Action::NewCutter);
    }
    let target = app
        .selected_model
        .and_then(|i| app.scene.models.get(i))
        .map(|m| m.name.clone());
    let hint = match target {
        Some(name) => format!("Target: {name}. In Edit mode, drag on it to start a cutter."),
        None => {
            "Double-click a model to make it the target, then drag on it in Edit mode.".to_string()
        }
    };
    ui.label(egui::RichText::new(hint).weak().small());
}

/// Expose for the selected structure, with its margin.
fn expose_ui(ui: &mut egui::Ui, app: &mut AppState, actions: &mut Vec<Action>) {
    ui.horizontal(|ui| {
        let selected = app.selected_model.is_some();
        let button = ui
            .add_enabled(selected, egui::Button::new("Expose Selected"))
            .on_hover_text(crate::gui::panels::models_panel::EXPOSE_HINT)
            .on_disabled_hover_text("Select a structure first (click it in the list)");
        if button.clicked() {
            actions.push(Action::ExposeSelected);
        }
        ui.add(
            egui::DragValue::new(&mut app.expose.margin_mm)
                .range(0.0..=crate::expose::MAX_MARGIN_MM)
                .speed(0.1)
                .fixed_decimals(1)
                .prefix("margin ")
                .suffix(" mm"),
        )
        .on_hover_text("Room left around the structure's outline by Expose");
    });
}

fn visualization_ui(ui: &mut egui::Ui, app: &mut AppState, actions: &mut Vec<Action>) {
    if app.scene.cutters.is_empty() {
        ui.label(
            egui::RichText::new(
                "No cutters yet. Switch to Edit mode and drag on the target model.",
            )
            .weak(),
        );
        return;
    }
    if app.selected_cutter >= app.scene.cutters.len() {
        app.selected_cutter = 0;
    }
    ui.horizontal_wrapped(|ui| {
        for i in 0..app.scene.cutters.len() {
            if ui
                .selectable_label(app.selected_cutter == i, format!("Cutter {}", i + 1))
                .clicked()
            {
                app.selected_cutter = i;
            }
        }
    });
    let i = app.selected_cutter;
    let target_name = app
        .scene
        .models
        .get(app.scene.cutters[i].target)
        .map(|m| m.name.clone())
        .unwrap_or_default();
    ui.horizontal(|ui| {
        ui.label(
            egui::RichText::new(format!("cuts {target_name}"))
                .weak()
                .small(),
        );
        ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
            if ui.small_button("Delete").clicked() {
                actions.push(Action::RemoveCutter(i));
            }
            if ui
                .small_button("Edit Cutter")
                .on_hover_text("Open this cutter in the editor")
                .clicked()
            {
                actions.push(Action::EditCutter(i));
            }
        });
    });
    let before = app.scene.cutters[i].views;
    let mut views = before;
    ui.checkbox(&mut views.cut, "Normal Cut");

    let mut transparency = views.transparency.is_some();
    ui.horizontal(|ui| {
        ui.checkbox(&mut transparency, "Transparency");
        let mut opacity = views.transparency.unwrap_or(0.25);
        ui.add_enabled(
            transparency,
            egui::Slider::new(&mut opacity, 0.0..=1.0)
                .text("opacity")
                .fixed_decimals(2),
        );
        views.transparency = transparency.then_some(opacity);
    });

    let (cutter, unit) = (&app.scene.cutters[i].cutter, app.scene.unit);
    sub_cutter_ui(ui, "Slices", &mut views.slices, cutter, unit);
    sub_cutter_ui(ui, "Ribbons", &mut views.ribbons, cutter, unit);

    if views != before {
        app.begin_edit("cutter view change");
        app.scene.cutters[i].views = views;
    }
}

/// A checkbox with placement, count and width (relative to the cut, or absolute in mm) for
/// ribbons or slices of the cutter `cut`.
fn sub_cutter_ui(
    ui: &mut egui::Ui,
    label: &str,
    value: &mut Option<SubCutterView>,
    cut: &cutter::Cutter,
    unit: crate::view::LengthUnit,
) {
    use cutter::subcutters::Placement;
    let mut on = value.is_some();
    let mut v = value.unwrap_or(SubCutterView::NEW);
    ui.horizontal(|ui| {
        ui.checkbox(&mut on, label);
        ui.add_enabled_ui(on, |ui| {
            egui::ComboBox::from_id_salt(label)
                .selected_text(v.placement.name())
                .show_ui(ui, |ui| {
                    for p in [Placement::Even, Placement::Planes, Placement::Horizontal] {
                        ui.selectable_value(&mut v.placement, p, p.name());
                    }
                });
            if v.placement != Placement::Planes {
                ui.add(
                    egui::DragValue::new(&mut v.count)
                        .range(1..=50)
                        .prefix("count "),
                );
            }
        });
    });
    ui.horizontal(|ui| {
        ui.add_enabled_ui(on, |ui| {
            ui.add_space(18.0);
            if ui
                .checkbox(&mut v.relative, "relative")
                .on_hover_text("width as the fraction of the spacing each one fills")
                .changed()
            {
                // Absolute starts at the size the relative width had (the target's scale).
                v.width = if v.relative {
                    SubCutterView::NEW.width
                } else {
                    let was = SubCutterView {
                        relative: true,
                        ..v
                    };
                    cutter::subcutters::absolute_width(cut, &was.spec())
                };
            }
            if v.relative {
                ui.add(
                    egui::DragValue::new(&mut v.width)
                        .range(0.01..=cutter::subcutters::MAX_RELATIVE)
                        .speed(0.005)
                        .prefix("width "),
                );
            } else {
                let mut mm = unit.to_mm(v.width);
                let speed = mm * 0.01;
                let edit = egui::DragValue::new(&mut mm)
                    .range(1e-3..=1e4)
                    .speed(speed)
                    .prefix("width ")
                    .suffix(" mm");
                if ui.add(edit).changed() {
                    v.width = unit.from_mm(mm);
                }
            }
        });
    });
    *value = on.then_some(v);
}
