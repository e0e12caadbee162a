//! The View menu and its keys: radiological view presets, zoom to fit and to the selection, the
//! scene's orientation, and how a freshly opened scene is oriented, scaled and framed.
//!
//! The geometry (presets, the orientation and unit guesses, fitting) lives in [`crate::view`] so
//! headless renders agree with the window; this file only turns menu items and keys into
//! [`ViewCommand`]s and applies them to the window's camera.

use crate::scene::{LengthUnit, Orientation, ViewPreset};
use crate::view::fit;

use crate::gui::action::Action;
pub use crate::gui::action::ViewCommand;
use crate::gui::state::AppState;

/// Orients, scales and frames a scene that replaced the previous one: the default scene is RAS;
/// anything else is guessed from its size and shape ([`Orientation::guess`],
/// [`LengthUnit::guess`]). The first view is anterior, like the default scene's, and the scalpel
/// starts with lengths relative to the scene's size.
pub fn orient_new_scene(app: &mut AppState, default_scene: bool, from_volume: bool) {
    let bbox = app.scene.bbox();
    app.scene.orientation = if default_scene {
        Orientation::RAS
    } else {
        Orientation::guess(&bbox, from_volume)
    };
    app.scene.unit = LengthUnit::guess(&bbox, from_volume);
    app.scene.camera = app.scene.preset_camera(ViewPreset::Anterior);
    // From here on they follow the selected model (`crate::scalpel_session::target::ScalpelSizing`).
    let slot = &mut app.viewport.scalpel;
    slot.sizing
        .resize(&app.scene, None, &mut slot.session.settings);
}

/// Applies a view command.
pub fn apply(app: &mut AppState, command: ViewCommand) {
    let aspect = app.viewport.size_px.x / app.viewport.size_px.y.max(1.0);
    match command {
        ViewCommand::Preset(preset) => {
            let bbox = app.scene.bbox();
            let (toward_eye, up) = app.scene.orientation.preset_axes(preset);
            let turned = cutter::Camera {
                eye: app.scene.camera.target + toward_eye,
                target: app.scene.camera.target,
                up,
                fov_y_deg: app.scene.camera.fov_y_deg,
            };
            app.scene.camera = fit::fit_to_box(&turned, &bbox, aspect);
            app.say_about_view(format!("{} view", preset.label()));
        }
        ViewCommand::ZoomToFit => {
            app.scene.camera = fit::fit_to_box(&app.scene.camera, &app.scene.bbox(), aspect);
        }
        ViewCommand::ZoomToSelection => {
            let Some(model) = app.selected_model.and_then(|i| app.scene.models.get(i)) else {
                app.say("Select a model first (double-click it)");
                return;
            };
            let (bbox, name) = (model.model.mesh.bbox(), model.model.name.clone());
            app.scene.camera = fit::fit_to_box(&app.scene.camera, &bbox, aspect);
            app.say_about_view(format!("Zoomed to {name}"));
        }
        ViewCommand::Orient(orientation) => {
            app.scene.orientation = orientation;
            app.recovery.mark_dirty();
            apply(app, ViewCommand::Preset(ViewPreset::Anterior));
        }
    }
}

/// The View menu's view items (presets, zooms, up axis, the orientation marker).
pub fn view_items_ui(ui: &mut egui::Ui, app: &mut AppState) -> Vec<Action> {
    let mut actions = Vec::new();
    for preset in ViewPreset::ALL {
        let button =
            egui::Button::new(format!("{} View", preset.label())).shortcut_text(preset.key_hint());
        if ui.add(button).clicked() {
            actions.push(Action::View(ViewCommand::Preset(preset)));
        }
    }
    ui.separator();
    if ui
        .add(egui::Button::new("Zoom to Fit").shortcut_text("Home"))
        .clicked()
    {
        actions.push(Action::View(ViewCommand::ZoomToFit));
    }
    if ui
        .add_enabled(
            app.selected_model.is_some(),
            egui::Button::new("Zoom to Selection").shortcut_text("."),
        )
        .clicked()
    {
        actions.push(Action::View(ViewCommand::ZoomToSelection));
    }
    ui.menu_button("Superior Axis", |ui| {
        ui.label(
            egui::RichText::new("Which way is the patient's head (guessed when files open)")
                .small()
                .weak(),
        );
        for (label, orientation) in [
            ("+Z, anterior +Y (RAS: volumes, Slicer)", Orientation::RAS),
            ("+Y, anterior +Z (glTF, HuBMAP)", Orientation::Y_UP),
            ("−Z (upside down)", flipped(Orientation::RAS)),
            ("−Y (upside down)", flipped(Orientation::Y_UP)),
            ("+X", Orientation::with_up(glam::DVec3::X)),
        ] {
            if ui
                .radio(app.scene.orientation == orientation, label)
                .clicked()
            {
                actions.push(Action::View(ViewCommand::Orient(orientation)));
            }
        }
    });
    ui.checkbox(&mut app.viewport.show_marker, "Orientation Marker");
    ui.label(
        egui::RichText::new(format!("Units: {} (shown in mm)", app.scene.unit.name()))
            .small()
            .weak(),
    );
    actions
}

/// `o` turned upside down about its anterior axis.
fn flipped(o: Orientation) -> Orientation {
    Orientation {
        superior: -o.superior,
        anterior: o.anterior,
    }
}

/// The view keys: 1, 3, 7 (number row or keypad) for the anterior, right and superior views,
/// with Ctrl for the opposite side; Home fits everything, `.` the selection.
pub fn view_shortcuts(ctx: &egui::Context) -> Vec<Action> {
    use egui::{Key, Modifiers};
    let mut actions = Vec::new();
    if ctx.egui_wants_keyboard_input() {
        return actions;
    }
    ctx.input_mut(|i| {
        for (key, digit) in [(Key::Num1, 1), (Key::Num3, 3), (Key::Num7, 7)] {
            for ctrl in [true, false] {
                let modifiers = if ctrl {
                    Modifiers::COMMAND
                } else {
                    Modifiers::NONE
                };
                if i.consume_key(modifiers, key)
                    && let Some(preset) = ViewPreset::from_digit(digit, ctrl)
                {
                    actions.push(Action::View(ViewCommand::Preset(preset)));
                }
            }
        }
        if i.consume_key(Modifiers::NONE, Key::Home) {
            actions.push(Action::View(ViewCommand::ZoomToFit));
        }
        if i.consume_key(Modifiers::NONE, Key::Period) {
            actions.push(Action::View(ViewCommand::ZoomToSelection));
        }
    });
    actions
}
