//! The Models list (thesis 3.5 D): one row per model (a structure: a mesh file or a volume label)
//! with visibility and colour, grouped by folder (each a collapsible header with its own
//! show/hide box), a filter box and Show all / Hide all for what the filter leaves; for the
//! selected model its colour picker, Solid/Wireframe, opacity and visibility. Every change is
//! undoable; a slider drag or a colour-picker drag is one step. When the selection changes (a
//! double-click in the view), the list opens the model's groups and scrolls to its row.

use crate::gui::action::Action;
use crate::gui::state::AppState;
use crate::scene::ModelStyle;
use crate::scene::model_groups::GroupNode;

fn srgb_u8(c: [f32; 3]) -> [u8; 3] {
    c.map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8)
}

fn colour32(c: [f32; 3]) -> egui::Color32 {
    let [r, g, b] = srgb_u8(c);
    egui::Color32::from_rgb(r, g, b)
}

/// What the list remembers between frames (in egui's memory, not in the scene).
#[derive(Clone, Debug, Default)]
struct ListState {
    filter: String,
    /// The selection the list last saw.
    shown_selection: Option<usize>,
    /// Frames left to keep scrolling to the selection (groups open with an animation, so the
    /// row's place settles over a few frames).
    reveal_frames: u8,
}

/// How many frames the list keeps scrolling to a newly selected model.
const REVEAL_FRAMES: u8 = 12;

/// What Expose does, on its button and menu entry.
pub const EXPOSE_HINT: &str = "Cut open everything in front of this structure from the current \
     view: one cutter per structure in the way, sized to its outline plus a margin (X)";

pub fn models_panel_ui(ui: &mut egui::Ui, app: &mut AppState) -> Vec<Action> {
    let mut actions = Vec::new();
    let state_id = egui::Id::unique("models-list-state");
    let mut state: ListState = ui.data(|d| d.get_temp(state_id)).unwrap_or_default();
    ui.add_space(4.0);
    ui.horizontal(|ui| {
        ui.heading("Models");
        ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
            ui.label(egui::RichText::new(format!("{}", app.scene.models.len())).weak());
        });
    });
    ui.separator();
    if app.scene.models.is_empty() {
        ui.label(
            egui::RichText::new("No models. File > Open…, or drop files on the window.").weak(),
        );
        return actions;
    }
    // Right to left, so the box takes exactly what the button leaves: a row wider than the
    // panel would widen it frame after frame.
    let row = egui::vec2(ui.available_width(), ui.spacing().interact_size.y);
    let right_to_left = egui::Layout::right_to_left(egui::Align::Center);
    ui.allocate_ui_with_layout(row, right_to_left, |ui| {
        if ui
            .add_enabled(!state.filter.is_empty(), egui::Button::new("Clear"))
            .on_hover_text("Clear the filter")
            .clicked()
        {
            state.filter.clear();
        }
        ui.add(
            egui::TextEdit::singleline(&mut state.filter)
                .hint_text("Filter by name or group")
                .desired_width(ui.available_width()),
        )
        .on_hover_text("Shows only the models whose name or group contains every word typed");
    });
    let tree = GroupNode::build(&app.scene.models, &state.filter);
    let listed = tree.all_models();
    ui.horizontal(|ui| {
        let what = if state.filter.is_empty() {
            "all"
        } else {
            "listed"
        };
        for (show, label) in [(true, "Show"), (false, "Hide")] {
            if ui
                .add_enabled(
                    !listed.is_empty(),
                    egui::Button::new(format!("{label} {what}")),
                )
                .clicked()
            {
                set_visible(
                    app,
                    &listed,
                    show,
                    if show { "show models" } else { "hide models" },
                );
            }
        }
        if !state.filter.is_empty() {
            ui.label(egui::RichText::new(format!("{} listed", listed.len())).weak());
        }
    });
    let selected = app.selected_model.filter(|&i| i < app.scene.models.len());
    if selected != state.shown_selection {
        state.shown_selection = selected;
        state.reveal_frames = if selected.is_some() { REVEAL_FRAMES } else { 0 };
    }
    let reveal = selected.filter(|_| state.reveal_frames > 0);
    if reveal.is_some() {
        state.reveal_frames -= 1;
        ui.ctx().request_repaint();
    }
    // The list takes the panel's height but what the selected model's properties need below
    // it (the tools have a panel of their own).
    let below = if selected.is_some() { 215.0 } else { 45.0 };
    let list_height = (ui.available_height() - below).max(160.0);
    egui::ScrollArea::vertical()
        .id_salt("models-list")
        .max_height(list_height)
        .auto_shrink([false, true])
        .show(ui, |ui| {
            let filtering = !state.filter.is_empty();
            group_body_ui(ui, app, &tree, filtering, reveal, &mut actions);
            if listed.is_empty() {
                ui.label(egui::RichText::new("No model matches the filter.").weak());
            }
        });
    ui.data_mut(|d| d.insert_temp(state_id, state));
    ui.separator();
    let Some(index) = app.selected_model.filter(|&i| i < app.scene.models.len()) else {
        ui.label(
            egui::RichText::new("Select a model (or double-click it in the view) to edit it.")
                .weak(),
        );
        return actions;
    };
    let name = app.scene.models[index].model.name.clone();
    ui.label(egui::RichText::new(&name).strong());
    let triangles = app.scene.models[index].model.mesh.triangle_count();
    ui.label(
        egui::RichText::new(format!(
            "{} triangles",
            crate::gui::panels::status_bar::grouped(triangles)
        ))
        .weak()
        .small(),
    );
    egui::Grid::new("model-properties")
        .num_columns(2)
        .spacing([10.0, 6.0])
        .show(ui, |ui| {
            ui.label("Colour");
            let mut srgb = srgb_u8(app.scene.models[index].color);
            if ui.color_edit_button_srgb(&mut srgb).changed() {
                app.begin_edit("colour change");
                app.scene.models[index].color = srgb.map(|c| c as f32 / 255.0);
            }
            ui.end_row();

            ui.label("Render");
            ui.horizontal(|ui| {
                let style = app.scene.models[index].style;
                for (s, label) in [
                    (ModelStyle::Solid, "Solid"),
                    (ModelStyle::Wireframe, "Wireframe"),
                ] {
                    if ui.selectable_label(style == s, label).clicked() && style != s {
                        app.begin_edit(if s == ModelStyle::Solid {
                            "solid style"
                        } else {
                            "wireframe style"
                        });
                        app.scene.models[index].style = s;
                    }
                }
            });
            ui.end_row();

            ui.label("Opacity");
            let mut opacity = app.scene.models[index].opacity;
            if ui
                .add(egui::Slider::new(&mut opacity, 0.0..=1.0).fixed_decimals(2))
                .changed()
            {
                app.begin_edit("opacity change");
                app.scene.models[index].opacity = opacity;
            }
            ui.end_row();

            ui.label("");
            let mut visible = app.scene.models[index].visible;
            if ui.checkbox(&mut visible, "Visible").changed() {
                app.begin_edit(if visible { "show model" } else { "hide model" });
                app.scene.models[index].visible = visible;
            }
            ui.end_row();
        });
    ui.horizontal(|ui| {
        if ui.button("Expose").on_hover_text(EXPOSE_HINT).clicked() {
            actions.push(Action::Expose(index));
        }
        if ui
            .button("Centre")
            .on_hover_text("Centre the camera on this model")
            .clicked()
        {
            actions.push(Action::FocusModel(index));
        }
        if ui.button("Remove").clicked() {
            actions.push(Action::RemoveModel(index));
        }
        if ui
            .button("Split")
            .on_hover_text("One model per connected region of this structure")
            .clicked()
        {
            actions.push(Action::SplitRegions(index));
        }
    });
    actions
}

/// Sets the visibility of `models` as one undo step (nothing when none changes).
fn set_visible(app: &mut AppState, models: &[usize], visible: bool, label: &str) {
    if models
        .iter()
        .all(|&i| app.scene.models[i].visible == visible)
    {
        return;
    }
    app.begin_edit(label);
    for &i in models {
        app.scene.models[i].visible = visible;
    }
}

/// The rows of a group's own models, then its sub-groups as collapsible headers. Groups stay
/// open while filtering and open up to reveal the model `reveal`.
fn group_body_ui(
    ui: &mut egui::Ui,
    app: &mut AppState,
    node: &GroupNode,
    filtering: bool,
    reveal: Option<usize>,
    actions: &mut Vec<Action>,
) {
    for &index in &node.models {
        model_row_ui(ui, app, index, reveal == Some(index), actions);
    }
    for group in &node.groups {
        let id = ui.make_persistent_id(("models-group", &group.path));
        let mut header =
            egui::collapsing_header::CollapsingState::load_with_default_open(ui.ctx(), id, true);
        if filtering || reveal.is_some_and(|i| group.contains(i)) {
            header.set_open(true);
        }
        header
            .show_header(ui, |ui| {
                let members = group.all_models();
                let shown = members
                    .iter()
                    .filter(|&&i| app.scene.models[i].visible)
                    .count();
                let mut all = shown == members.len();
                let some = shown > 0 && !all;
                let label = format!("{} ({})", group.name, members.len());
                if ui
                    .add(egui::Checkbox::new(&mut all, label).indeterminate(some))
                    .on_hover_text(format!("Show or hide everything in {}", group.path))
                    .changed()
                {
                    set_visible(
                        app,
                        &members,
                        all,
                        if all { "show group" } else { "hide group" },
                    );
                }
            })
            .body(|ui| group_body_ui(ui, app, group, filtering, reveal, actions));
    }
}

/// One model's row: visibility box, colour swatch, name (click selects, double-click centres).
fn model_row_ui(
    ui: &mut egui::Ui,
    app: &mut AppState,
    index: usize,
    reveal: bool,
    actions: &mut Vec<Action>,
) {
    let model = &app.scene.models[index];
    let selected = app.selected_model == Some(index);
    let (name, visible, colour) = (model.model.name.clone(), model.visible, model.color);
    ui.horizontal(|ui| {
        let mut v = visible;
        if ui
            .checkbox(&mut v, "")
            .on_hover_text(format!("Show or hide {name}"))
            .changed()
        {
            app.begin_edit(if v { "show model" } else { "hide model" });
            app.scene.models[index].visible = v;
        }
        let (rect, _) = ui.allocate_exact_size(egui::vec2(14.0, 14.0), egui::Sense::hover());
        ui.painter().rect_filled(rect, 3.0, colour32(colour));
        let text = if visible {
            egui::RichText::new(&name)
        } else {
            egui::RichText::new(&name).weak()
        };
        // Long structure names end in "…" at the panel's edge (widen the panel to read them);
        // the whole name shows on hover.
        let row = ui
            .add(egui::Button::selectable(selected, text).truncate())
            .on_hover_text(&name);
        if reveal {
            row.scroll_to_me(None);
        }
        if row.clicked() {
            actions.push(Action::SelectModel(if selected {
                None
            } else {
                Some(index)
            }));
        }
        if row.double_clicked() {
            actions.push(Action::FocusModel(index));
        }
        row.context_menu(|ui| {
            if ui.button("Expose (X)").on_hover_text(EXPOSE_HINT).clicked() {
                actions.push(Action::Expose(index));
            }
            if ui.button("Centre camera on it").clicked() {
                actions.push(Action::FocusModel(index));
            }
            if ui.button("Remove from scene").clicked() {
                actions.push(Action::RemoveModel(index));
            }
        });
    });
}
