//! The Tools panel, right of the view: the cutter, its cut views, the scalpel and the image, one
//! collapsible section each.
//!
//! The tools sat below the model list once, so a scene of 60 structures pushed them out of
//! sight and a narrow panel clipped their labels. In a panel of their own they are always in
//! reach whatever the list holds, and the panel lays them out in its width (labels wrap, sliders
//! take what is left) so nothing is clipped at 1280×800. The section of the current mode's tool
//! opens when the mode is entered: the scalpel's in Scalpel mode, the cutter's in Edit mode.

use crate::gui::action::{Action, Mode};
use crate::gui::state::AppState;

/// The panel's default width in points (the user can resize it).
pub const DEFAULT_WIDTH: f32 = 270.0;
/// The narrowest it may become; every section is laid out to fit it.
pub const MIN_WIDTH: f32 = 240.0;

/// A section's header text.
pub fn title(text: &str) -> egui::RichText {
    egui::RichText::new(text).strong().size(15.0)
}

/// The mode the sections were last opened for (egui memory).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct OpenedFor(Mode);

/// The panel's contents.
pub fn tools_panel_ui(ui: &mut egui::Ui, app: &mut AppState) -> Vec<Action> {
    let mut actions = Vec::new();
    let memory_id = egui::Id::unique("tools-panel-mode");
    let entered = ui.data(|d| d.get_temp::<OpenedFor>(memory_id)) != Some(OpenedFor(app.mode));
    ui.data_mut(|d| d.insert_temp(memory_id, OpenedFor(app.mode)));
    egui::ScrollArea::vertical()
        .id_salt("tools-panel")
        .auto_shrink([false, false])
        .show(ui, |ui| {
            ui.set_width(ui.available_width());
            ui.add_space(4.0);
            let scalpel = |ui: &mut egui::Ui, app: &mut AppState| {
                section(
                    ui,
                    "Scalpel",
                    false,
                    entered && app.mode == Mode::Scalpel,
                    |ui| {
                        crate::gui::viewport::scalpel_mode::scalpel_panel_ui(ui, app);
                    },
                );
            };
            if app.mode == Mode::Scalpel {
                scalpel(ui, app);
            }
            section(
                ui,
                "Cutter",
                true,
                entered && app.mode == Mode::Edit,
                |ui| {
                    actions.extend(crate::gui::panels::cutter_panel::cutter_panel_ui(ui, app));
                },
            );
            section(ui, "Cut views", true, false, |ui| {
                actions.extend(crate::gui::panels::cutter_panel::views_panel_ui(ui, app));
            });
            crate::gui::panels::risk_panel::risk_panel_ui(ui, app);
            crate::gui::panels::image_panel::image_panel_ui(ui, app);
            if app.mode != Mode::Scalpel {
                scalpel(ui, app);
            }
        });
    actions
}

/// One collapsible section: open by default when `default_open`, opened now when `open_now`.
fn section(
    ui: &mut egui::Ui,
    name: &str,
    default_open: bool,
    open_now: bool,
    body: impl FnOnce(&mut egui::Ui),
) {
    let id = ui.make_persistent_id(("tools-section", name));
    let mut state = egui::collapsing_header::CollapsingState::load_with_default_open(
        ui.ctx(),
        id,
        default_open,
    );
    if open_now {
        state.set_open(true);
    }
    state
        .show_header(ui, |ui| ui.label(title(name)))
        .body(|ui| {
            body(ui);
            ui.add_space(6.0);
        });
    ui.separator();
}
