//! Help → Keyboard and Mouse: the whole reference of every mode in one window (the line above the
//! view shows only the current mode's), the view keys, and the Debug menu's switch.

use crate::gui::action::Mode;

/// The environment variable that shows the Debug menu (gesture recording).
pub const DEBUG_ENV: &str = "CUTAWAY_DEBUG";

/// True when the Debug menu is shown: only with [`DEBUG_ENV`] set, so users never meet it.
pub fn debug_menu_enabled() -> bool {
    std::env::var_os(DEBUG_ENV).is_some_and(|v| !v.is_empty() && v != "0")
}

/// Navigation that works in every mode ([`crate::gui::viewport::navigation`]).
pub const EVERY_MODE: &[(&str, &str)] = &[
    ("Right-drag", "orbit"),
    ("Middle-drag", "pan"),
    ("Wheel", "zoom (in Edit: off the cutter)"),
    ("Double-click", "select a model (clears on empty space)"),
    ("1 / Ctrl+1", "anterior / posterior view"),
    ("3 / Ctrl+3", "right / left view"),
    ("7 / Ctrl+7", "superior / inferior view"),
    (
        "X",
        "expose the selected structure (cut open what hides it)",
    ),
    ("Home", "zoom to fit"),
    (".", "zoom to the selection"),
    ("F1–F4", "Camera, Edit, Preview, Scalpel mode"),
    ("Ctrl+Z / Ctrl+Shift+Z", "undo / redo"),
];

fn open_id() -> egui::Id {
    egui::Id::unique("help-keys-window-open")
}

/// Opens the Keyboard and Mouse window.
pub fn open(ctx: &egui::Context) {
    ctx.data_mut(|d| d.insert_temp(open_id(), true));
}

/// The Keyboard and Mouse window, when open.
pub fn help_window_ui(ctx: &egui::Context) {
    let mut open = ctx.data(|d| d.get_temp::<bool>(open_id())).unwrap_or(false);
    if !open {
        return;
    }
    // Below the menu bar and the mode bar, centred over the window, as tall as the window
    // allows (the reference is long; it scrolls).
    let screen = ctx.content_rect();
    egui::Window::new("Keyboard and Mouse")
        .open(&mut open)
        .collapsible(false)
        .default_width(520.0)
        .default_height((screen.height() - 140.0).max(240.0))
        .pivot(egui::Align2::CENTER_TOP)
        .default_pos(screen.center_top() + egui::vec2(0.0, 72.0))
        .show(ctx, |ui| {
            egui::ScrollArea::vertical()
                .max_height((screen.height() - 180.0).max(200.0))
                .auto_shrink([false, false])
                .show(ui, |ui| {
                    section_ui(ui, "Every mode", EVERY_MODE);
                    for mode in [Mode::Camera, Mode::Edit, Mode::Preview, Mode::Scalpel] {
                        section_ui(
                            ui,
                            &format!("{} mode", mode.label()),
                            crate::gui::panels::key_reference::commands(mode),
                        );
                    }
                    ui.label(
                        egui::RichText::new(format!(
                            "The Debug menu (gesture recording) shows when {DEBUG_ENV}=1 is set."
                        ))
                        .small()
                        .weak(),
                    );
                });
        });
    ctx.data_mut(|d| d.insert_temp(open_id(), open));
}

fn section_ui(ui: &mut egui::Ui, title: &str, rows: &[(&str, &str)]) {
    ui.strong(title);
    egui::Grid::new(("help-keys", title))
        .num_columns(2)
        .striped(true)
        .show(ui, |ui| {
            for (keys, action) in rows {
                ui.label(egui::RichText::new(*keys).monospace());
                ui.label(*action);
                ui.end_row();
            }
        });
    ui.add_space(6.0);
}
