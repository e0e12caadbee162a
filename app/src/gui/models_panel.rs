//! The Models list (thesis 3.5 D): one row per region (file stem + region number) with visibility
//! and colour, and for the selected model its colour picker, Solid/Wireframe, opacity and
//! visibility. Every change is undoable; a slider drag or a colour-picker drag is one step.

use super::app::{Action, CutawayApp};
use crate::scene::ModelStyle;

fn srgb_u8(c: [f32; 3]) -> [u8; 3] {
    c.map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8)
}

fn colour32(c: [f32; 3]) -> egui::Color32 {
    let [r, g, b] = srgb_u8(c);
    egui::Color32::from_rgb(r, g, b)
}

pub fn models_panel_ui(ui: &mut egui::Ui, app: &mut CutawayApp) -> Vec<Action> {
    let mut actions = Vec::new();
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
            egui::RichText::new("No models. File > Load Model, or drop files on the window.")
                .weak(),
        );
        return actions;
    }
    egui::ScrollArea::vertical()
        .id_salt("models-list")
        .max_height(220.0)
        .auto_shrink([false, true])
        .show(ui, |ui| {
            for index in 0..app.scene.models.len() {
                let model = &app.scene.models[index];
                let selected = app.selected_model == Some(index);
                let (name, visible, colour) = (model.name.clone(), model.visible, model.color);
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
                    let (rect, _) =
                        ui.allocate_exact_size(egui::vec2(14.0, 14.0), egui::Sense::hover());
                    ui.painter().rect_filled(rect, 3.0, colour32(colour));
                    let text = if visible {
                        egui::RichText::new(&name)
                    } else {
                        egui::RichText::new(&name).weak()
                    };
                    let row = ui.add(egui::Button::selectable(selected, text));
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
                        if ui.button("Centre camera on it").clicked() {
                            actions.push(Action::FocusModel(index));
                        }
                        if ui.button("Remove from scene").clicked() {
                            actions.push(Action::RemoveModel(index));
                        }
                    });
                });
            }
        });
    ui.separator();
    let Some(index) = app.selected_model.filter(|&i| i < app.scene.models.len()) else {
        ui.label(
            egui::RichText::new("Select a model (or double-click it in the view) to edit it.")
                .weak(),
        );
        return actions;
    };
    let name = app.scene.models[index].name.clone();
    ui.label(egui::RichText::new(&name).strong());
    let triangles = app.scene.models[index].mesh.triangle_count();
    ui.label(
        egui::RichText::new(format!(
            "{} triangles",
            super::status_bar::grouped(triangles)
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
    });
    actions
}
