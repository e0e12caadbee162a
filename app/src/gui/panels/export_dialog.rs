//! The frame every export dialog shares (Export Image, Export Cut Meshes, Export Turntable,
//! Export Web Page): a fixed window while the dialog is open, the dialog's own settings, and a
//! button at the bottom that asks where to write (an [`Action::Dialog`]) and closes the dialog.

use crate::gui::action::{Action, Purpose};
use crate::gui::state::export_settings::{
    ExportImageSettings, ExportMeshSettings, TurntableSettings, WebPageSettings,
};

/// The settings of a dialog that is open or closed.
pub trait DialogSettings {
    fn open(&mut self) -> &mut bool;
}

macro_rules! dialog_settings {
    ($($settings:ty),*) => {$(
        impl DialogSettings for $settings {
            fn open(&mut self) -> &mut bool {
                &mut self.open
            }
        }
    )*};
}
dialog_settings!(
    ExportImageSettings,
    ExportMeshSettings,
    TurntableSettings,
    WebPageSettings
);

/// One export dialog: its title, its button, and what the button asks for.
pub struct ExportDialog {
    pub title: &'static str,
    pub button: &'static str,
    pub purpose: Purpose,
}

impl ExportDialog {
    /// Shows the dialog while `settings` is open; `body` draws the settings and says whether
    /// the button may be pressed.
    pub fn show<S: DialogSettings>(
        &self,
        ctx: &egui::Context,
        settings: &mut S,
        body: impl FnOnce(&mut egui::Ui, &mut S) -> bool,
    ) -> Vec<Action> {
        let mut actions = Vec::new();
        if !*settings.open() {
            return actions;
        }
        let mut open = true;
        egui::Window::new(self.title)
            .open(&mut open)
            .collapsible(false)
            .resizable(false)
            .show(ctx, |ui| {
                let ready = body(ui, settings);
                ui.add_space(6.0);
                if ui
                    .add_enabled(ready, egui::Button::new(self.button))
                    .clicked()
                {
                    actions.push(Action::Dialog(self.purpose));
                    *settings.open() = false;
                }
            });
        if !open {
            *settings.open() = false;
        }
        actions
    }
}

/// The Width and Height rows of a dialog's grid: pixels, each in `1..=max`.
pub fn size_rows(ui: &mut egui::Ui, width: &mut u32, height: &mut u32, max: u32) {
    for (label, value) in [("Width", width), ("Height", height)] {
        ui.label(label);
        ui.add(egui::DragValue::new(value).range(1..=max).suffix(" px"));
        ui.end_row();
    }
}
