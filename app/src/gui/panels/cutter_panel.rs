//! The cutter sections of the Tools panel (thesis 3.5 E): **Cutter** — the "Live cut" toggle
//! (the cut shown while painting in Edit mode, see [`crate::gui::viewport::live_cut`]) and the
//! settings of the next cutter and the one being edited (segment spacing ω, type Freeform/Wedge,
//! rounding and its Smoothness levels, the cut direction, and the depth of the cutter being
//! edited in mm) — and **Cut views**, per cutter, what Preview shows of
//! it (Normal Cut, the removed piece transparent with its opacity, Slices, Ribbons with count and
//! width). The thesis put the two in tabs; here both stay in view, one section each.

use crate::gui::action::Action;
use crate::gui::state::AppState;
use crate::scene::SubCutterSpec;
use cutter::{CutDirection, CutKind};

/// The opacity the removed piece gets when its transparent view is turned on: on the default
/// head, a removed slab of skin at 0.25 was all but invisible against the skin and the walls
/// behind it; at 0.5 it reads at a glance as a ghost of what was cut while the cut stays clear.
pub const DEFAULT_TRANSPARENCY: f32 = 0.5;

/// The Cutter section: live cut, the cutter's settings, New Cutter.
pub fn cutter_panel_ui(ui: &mut egui::Ui, app: &mut AppState) -> Vec<Action> {
    let mut actions = Vec::new();
    ui.checkbox(&mut app.viewport.live.enabled, "Live cut")
        .on_hover_text("In Edit mode, show the cut (kept part, walls, contour) under the cutter while you paint it; the cut runs in the background");
    ui.add_space(2.0);
    initialization_ui(ui, app, &mut actions);
    actions
}

/// The Cut views section: what Preview shows of each cutter.
pub fn views_panel_ui(ui: &mut egui::Ui, app: &mut AppState) -> Vec<Action> {
    let mut actions = Vec::new();
    visualization_ui(ui, app, &mut actions);
    actions
}

fn initialization_ui(ui: &mut egui::Ui, app: &mut AppState, actions: &mut Vec<Action>) {
    let before = app.cutter_init.clone();
    // The slider takes what the label column and its value box leave, so nothing is clipped in
    // a narrow panel.
    ui.spacing_mut().slider_width = (ui.available_width() - 190.0).clamp(50.0, 200.0);
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
            ui.label("Cut along")
                .on_hover_text("Which way the cutter goes into the target");
            ui.horizontal(|ui| {
                let direction = &mut app.cutter_init.direction;
                ui.selectable_value(direction, CutDirection::View, "Your view")
                    .on_hover_text(
                        "Straight in, the way you look at the surface: the opening is what you \
                         painted, seen from where you painted it",
                    );
                ui.selectable_value(direction, CutDirection::Normal, "Normal")
                    .on_hover_text(
                        "Along the surface normal: each box goes in along the surface under it, a trench of even depth",
                    );
            });
            ui.end_row();
            depth_row(ui, app);
            ui.end_row();
            ui.label("Shape");
            ui.checkbox(&mut app.cutter_init.smooth, "Rounded")
                .on_hover_text("A rounded (subdivided) cutter instead of its boxes");
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
        .map(|m| m.model.name.clone());
    let hint = match target {
        Some(name) => format!("Target: {name}. In Edit mode, drag on it to start a cutter."),
        None => {
            "Double-click a model to make it the target, then drag on it in Edit mode.".to_string()
        }
    };
    ui.label(egui::RichText::new(hint).weak().small());
}

/// The depth of the cutter being edited, in mm (every plane gets it; the wheel over the cutter
/// changes it too), or what a new cutter's depth will be.
fn depth_row(ui: &mut egui::Ui, app: &mut AppState) {
    ui.label("Depth").on_hover_text(
        "How deep the cutter goes from its front. A new cutter reaches the first structure \
         behind its target; the wheel over the cutter changes the whole depth, Alt+wheel the \
         plane under the pointer",
    );
    let Some(depth) = app.viewport.editor.depth() else {
        ui.label(egui::RichText::new("auto: reaches what lies behind").weak());
        return;
    };
    let unit = app.scene.unit;
    let mut mm = unit.to_mm(depth);
    let speed = (mm * 0.01).max(0.05);
    let edit = egui::DragValue::new(&mut mm)
        .range(0.1..=1e5)
        .speed(speed)
        .max_decimals(1)
        .suffix(" mm");
    if ui.add(edit).changed()
        && app
            .viewport
            .editor
            .set_depth(&mut app.scene, unit.from_mm(mm))
    {
        app.cutters_changed();
        app.say_depth();
    }
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
        .map(|m| m.model.name.clone())
        .unwrap_or_default();
    ui.label(
        egui::RichText::new(format!("cuts {target_name}"))
            .weak()
            .small(),
    );
    ui.horizontal(|ui| {
        if ui
            .small_button("Edit Cutter")
            .on_hover_text("Open this cutter in the editor")
            .clicked()
        {
            actions.push(Action::EditCutter(i));
        }
        if ui.small_button("Delete Cutter").clicked() {
            actions.push(Action::RemoveCutter(i));
        }
    });
    let before = app.scene.cutters[i].views;
    let mut views = before;
    ui.checkbox(&mut views.cut, "Normal Cut");

    let mut transparency = views.transparency.is_some();
    ui.checkbox(&mut transparency, "Removed piece, transparent")
        .on_hover_text("Draw what the cut removes as a see-through ghost");
    ui.horizontal(|ui| {
        ui.add_space(18.0);
        let mut opacity = views.transparency.unwrap_or(DEFAULT_TRANSPARENCY);
        ui.spacing_mut().slider_width = (ui.available_width() - 120.0).clamp(50.0, 200.0);
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
    value: &mut Option<SubCutterSpec>,
    cut: &cutter::Cutter,
    unit: crate::scene::LengthUnit,
) {
    use cutter::subcutters::Placement;
    let mut on = value.is_some();
    let mut v = value.unwrap_or(SubCutterSpec::NEW);
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
                    SubCutterSpec::NEW.width
                } else {
                    let was = SubCutterSpec {
                        relative: true,
                        ..v
                    };
                    cutter::subcutters::absolute_width(cut, &was)
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
