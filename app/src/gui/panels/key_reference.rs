//! The reference key of mouse and keyboard commands shown above the viewport (thesis 3.5 F: "the
//! mouse/keyboard commands used in the editing of a cutaway region are displayed above the
//! viewport"). It follows the mode, so it always tells what the mouse does right now.

use crate::gui::action::Mode;

/// The (keys, action) pairs for `mode`, in the order shown.
pub fn commands(mode: Mode) -> &'static [(&'static str, &'static str)] {
    match mode {
        Mode::Camera | Mode::Preview => &[
            ("Drag", "orbit"),
            ("Shift/Middle-drag", "pan"),
            ("Wheel", "zoom"),
            ("Double-click", "select & centre"),
            ("E", "Edit mode: cut"),
            ("X", "expose selection"),
            ("1 3 7 (Ctrl)", "views"),
            ("Right-click", "menu"),
        ],
        Mode::Edit => &[
            ("Drag on model", "new cutter"),
            ("Drag handle", "extrude (Shift: straight)"),
            ("Drag front vertex", "move edge"),
            ("Wheel on cutter", "depth"),
            ("Alt+Wheel", "plane depth"),
            ("Wheel elsewhere", "zoom"),
            ("Right/Alt+Drag", "orbit"),
            ("Ctrl+Wheel", "rotate plane"),
            ("Del", "remove last box"),
            ("Ctrl+Z", "undo"),
        ],
        Mode::Scalpel => &[
            ("Drag on model", "cut along the path"),
            ("Alt+Drag / Right-drag", "orbit"),
            ("Shift+Drag / Middle-drag", "pan"),
            ("Wheel", "zoom"),
            ("Ctrl+Z", "undo"),
            ("F4", "Scalpel mode"),
        ],
    }
}

/// One line of key chips; wraps on narrow windows.
pub fn key_reference_ui(ui: &mut egui::Ui, mode: Mode) {
    ui.horizontal_wrapped(|ui| {
        ui.spacing_mut().item_spacing.x = 4.0;
        ui.label(egui::RichText::new(format!("{} mode", mode.label())).strong());
        ui.add_space(8.0);
        for (keys, action) in commands(mode) {
            ui.label(
                egui::RichText::new(*keys)
                    .monospace()
                    .small()
                    .background_color(ui.visuals().faint_bg_color)
                    .strong(),
            );
            ui.label(egui::RichText::new(*action).small().weak());
            ui.add_space(10.0);
        }
    });
}
