//! The menu bar (File, Edit, Cut, Rendering, View, Help; Debug only when asked for), the mode toolbar, the export dialogs and the
//! window's visual style.
//!
//! Menus describe what the user asked for as [`Action`]s; only the Rendering menu's toggles change
//! settings in place (they are view settings, not undoable scene edits).

use crate::gui::action::{Action, Mode, Purpose};
use crate::gui::panels::export_dialog::{ExportDialog, size_rows};
use crate::gui::state::AppState;
use crate::scene::Stereo;

pub use crate::gui::state::export_settings::{
    ExportImageSettings, ExportMeshSettings, MAX_EXPORT_SIDE, MeshFormat,
};

/// A calm dark theme with one accent colour and a little more room than egui's default.
pub fn apply_style(ctx: &egui::Context) {
    ctx.set_theme(egui::Theme::Dark);
    ctx.all_styles_mut(|style| {
        style.spacing.item_spacing = egui::vec2(8.0, 5.0);
        style.spacing.button_padding = egui::vec2(8.0, 3.0);
        style.spacing.interact_size.y = 22.0;
        let accent = egui::Color32::from_rgb(64, 138, 214);
        style.visuals.selection.bg_fill = accent;
        style.visuals.hyperlink_color = accent;
        style.visuals.widgets.hovered.corner_radius = egui::CornerRadius::same(4);
        style.visuals.widgets.inactive.corner_radius = egui::CornerRadius::same(4);
        style.visuals.widgets.active.corner_radius = egui::CornerRadius::same(4);
        style.visuals.widgets.noninteractive.corner_radius = egui::CornerRadius::same(4);
        style.visuals.window_corner_radius = egui::CornerRadius::same(8);
    });
}

fn item(ui: &mut egui::Ui, text: &str, shortcut: &str) -> bool {
    let button = egui::Button::new(text).shortcut_text(shortcut);
    ui.add(button).clicked()
}

/// The menu bar.
pub fn menu_bar_ui(ui: &mut egui::Ui, app: &mut AppState) -> Vec<Action> {
    let mut actions = Vec::new();
    egui::MenuBar::new().ui(ui, |ui| {
        ui.menu_button("File", |ui| {
            let open = egui::Button::new("Open…").shortcut_text("Ctrl+O");
            if ui
                .add(open)
                .on_hover_text("Mesh files, a label volume, a session, or a folder of meshes")
                .clicked()
            {
                actions.push(Action::Dialog(Purpose::Open));
            }
            if item(ui, "Open Folder…", "") {
                actions.push(Action::Dialog(Purpose::OpenFolder));
            }
            if item(ui, "Add Model…", "") {
                actions.push(Action::Dialog(Purpose::AddModel));
            }
            if item(ui, "Open Image…", "") {
                actions.push(Action::Dialog(Purpose::OpenImage));
            }
            ui.separator();
            if item(ui, "Save Session", "Ctrl+S") {
                actions.push(Action::SaveSession);
            }
            if item(ui, "Save Session As…", "") {
                actions.push(Action::Dialog(Purpose::SaveSessionAs));
            }
            ui.separator();
            if item(ui, "Export Image…", "") {
                app.export_image.open = true;
            }
            if item(ui, "Export Cut Meshes…", "") {
                app.export_meshes.open = true;
            }
            if item(ui, "Export Turntable…", "") {
                app.export_turntable.open = true;
            }
            if item(ui, "Export Web Page…", "") {
                app.export_webpage.open = true;
            }
            ui.menu_button("Open Example", |ui| {
                let atlas = crate::anatomy::default_scene::NAME;
                if ui.button(format!("{atlas} (real anatomy)")).clicked() {
                    actions.push(Action::OpenExample(atlas.to_string()));
                }
                let all = crate::anatomy::default_scene::ALL_NAME;
                if ui.button(format!("{all}, real anatomy")).clicked() {
                    actions.push(Action::OpenExample(all.to_string()));
                }
                for scene in crate::anatomy::assets::scenes() {
                    if ui.button(format!("{} (synthetic)", scene.name)).clicked() {
                        actions.push(Action::OpenExample(scene.name.to_string()));
                    }
                }
            });
            ui.separator();
            ui.menu_button("Recent Files", |ui| {
                if app.recent.paths.is_empty() {
                    ui.label(egui::RichText::new("(none)").weak());
                }
                for path in app.recent.paths.clone() {
                    let name = path
                        .file_name()
                        .map(|n| n.to_string_lossy().into_owned())
                        .unwrap_or_default();
                    if ui
                        .button(name)
                        .on_hover_text(path.display().to_string())
                        .clicked()
                    {
                        actions.push(Action::Open(vec![path]));
                    }
                }
            });
            ui.separator();
            if item(ui, "Exit", "") {
                actions.push(Action::Exit);
            }
        });
        ui.menu_button("Edit", |ui| {
            let undo = app
                .history
                .undo_label()
                .map(|l| format!("Undo {l}"))
                .unwrap_or_else(|| "Undo".into());
            if ui
                .add_enabled(
                    app.history.undo_label().is_some(),
                    egui::Button::new(undo).shortcut_text("Ctrl+Z"),
                )
                .clicked()
            {
                actions.push(Action::Undo);
            }
            let redo = app
                .history
                .redo_label()
                .map(|l| format!("Redo {l}"))
                .unwrap_or_else(|| "Redo".into());
            if ui
                .add_enabled(
                    app.history.redo_label().is_some(),
                    egui::Button::new(redo).shortcut_text("Ctrl+Shift+Z"),
                )
                .clicked()
            {
                actions.push(Action::Redo);
            }
        });
        actions.extend(crate::gui::panels::cut_menu::cut_menu_ui(ui, app));
        ui.menu_button("Rendering", |ui| {
            if ui
                .checkbox(&mut app.scene.render.antialias, "Anti-aliasing")
                .changed()
            {
                app.recovery.mark_dirty();
            }
            let mut stereo = app.scene.render.stereo == Stereo::Anaglyph;
            if ui
                .checkbox(&mut stereo, "Red/Blue Stereoscopic 3D")
                .changed()
            {
                app.scene.render.stereo = if stereo {
                    Stereo::Anaglyph
                } else {
                    Stereo::None
                };
                app.recovery.mark_dirty();
            }
            ui.separator();
            ui.horizontal(|ui| {
                ui.label("Background");
                let bg = &mut app.scene.render.background;
                let mut srgb = [to_u8(bg[0]), to_u8(bg[1]), to_u8(bg[2])];
                if ui.color_edit_button_srgb(&mut srgb).changed() {
                    for k in 0..3 {
                        bg[k] = srgb[k] as f32 / 255.0;
                    }
                    app.recovery.mark_dirty();
                }
            });
            ui.horizontal(|ui| {
                for (name, rgb) in [
                    ("White", [1.0, 1.0, 1.0]),
                    ("Grey", [0.80, 0.83, 0.87]),
                    ("Dark", [0.12, 0.13, 0.15]),
                    ("Black", [0.0, 0.0, 0.0]),
                ] {
                    if ui.small_button(name).clicked() {
                        app.scene.render.background = [rgb[0], rgb[1], rgb[2], 1.0];
                        app.recovery.mark_dirty();
                    }
                }
            });
        });
        ui.menu_button("View", |ui| {
            actions.extend(crate::gui::viewport::view_menu::view_items_ui(ui, app));
            ui.separator();
            crate::gui::panels::metrics_panel::view_menu_items(ui, app);
            ui.separator();
            let label = if app.cutters_hidden {
                "Show Current Cutters"
            } else {
                "Hide Current Cutters"
            };
            if ui.button(label).clicked() {
                actions.push(Action::ToggleCutters);
            }
            if ui.button("Remove All Cut Geometry").clicked() {
                actions.push(Action::RemoveAllCutGeometry);
            }
        });
        if crate::gui::panels::help::debug_menu_enabled() {
            debug_menu_ui(ui, app, &mut actions);
        }
        ui.menu_button("Help", |ui| {
            if ui.button("Keyboard and Mouse…").clicked() {
                crate::gui::panels::help::open(ui.ctx());
            }
            if ui.button("About Cutaway…").clicked() {
                crate::gui::panels::about::open(ui.ctx());
            }
        });
    });
    crate::gui::panels::about::about_window_ui(ui.ctx());
    crate::gui::panels::help::help_window_ui(ui.ctx());
    actions.extend(export_image_window_ui(ui.ctx(), app));
    actions.extend(export_meshes_window_ui(ui.ctx(), app));
    actions.extend(crate::gui::panels::turntable_export::window_ui(
        ui.ctx(),
        app,
    ));
    actions.extend(crate::gui::panels::webpage_export::window_ui(ui.ctx(), app));
    actions
}

/// The Debug menu (only with the debug environment variable, see [`crate::gui::panels::help::DEBUG_ENV`]).
fn debug_menu_ui(ui: &mut egui::Ui, app: &AppState, actions: &mut Vec<Action>) {
    ui.menu_button("Debug", |ui| {
        if app.viewport.recording.is_none() {
            if ui
                .button("Record Gesture")
                .on_hover_text("Record Edit-mode input as a cutaway-gesture/2 file")
                .clicked()
            {
                actions.push(Action::StartGesture);
            }
        } else if ui.button("Stop Recording and Save Gesture…").clicked() {
            actions.push(Action::StopGesture);
        }
    });
}

fn to_u8(c: f32) -> u8 {
    (c.clamp(0.0, 1.0) * 255.0).round() as u8
}

/// The mode buttons (thesis 3.5 C), undo/redo and a busy indicator.
pub fn toolbar_ui(ui: &mut egui::Ui, app: &mut AppState) -> Vec<Action> {
    let mut actions = Vec::new();
    ui.horizontal(|ui| {
        ui.add_space(2.0);
        for (mode, tip) in [
            (Mode::Camera, "Orbit, pan and zoom the camera (F1)"),
            (Mode::Edit, "Paint and edit cutters on the target (E or F2)"),
            (Mode::Preview, "Execute the cuts and show the cutaway (F3)"),
        ] {
            let button = egui::Button::selectable(
                app.mode == mode,
                egui::RichText::new(mode.label()).strong(),
            )
            .min_size(egui::vec2(78.0, 24.0));
            if ui.add(button).on_hover_text(tip).clicked() {
                actions.push(Action::SetMode(mode));
            }
        }
        let scalpel = egui::Button::selectable(
            app.mode == Mode::Scalpel,
            egui::RichText::new("Scalpel").strong(),
        )
        .min_size(egui::vec2(78.0, 24.0));
        let tip = if crate::gui::bridge::SCALPEL_AVAILABLE {
            "Progressive scalpel cut along a path (F4)"
        } else {
            "The scalpel is not part of this build"
        };
        if ui
            .add_enabled(crate::gui::bridge::SCALPEL_AVAILABLE, scalpel)
            .on_hover_text(tip)
            .on_disabled_hover_text(tip)
            .clicked()
        {
            actions.push(Action::SetMode(Mode::Scalpel));
        }
        ui.separator();
        if ui
            .add_enabled(
                app.history.undo_label().is_some(),
                egui::Button::new("Undo"),
            )
            .on_hover_text("Ctrl+Z")
            .clicked()
        {
            actions.push(Action::Undo);
        }
        if ui
            .add_enabled(
                app.history.redo_label().is_some(),
                egui::Button::new("Redo"),
            )
            .on_hover_text("Ctrl+Shift+Z")
            .clicked()
        {
            actions.push(Action::Redo);
        }
        ui.separator();
        if ui
            .button("Frame All")
            .on_hover_text("Reset the camera to show every visible model")
            .clicked()
        {
            actions.push(Action::ResetCamera);
        }
        ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
            if app.busy() {
                ui.spinner();
                if let Some(job) = app.jobs.iter().find(|j| j.is_running()) {
                    ui.label(egui::RichText::new(&job.label).weak());
                }
            }
        });
    });
    actions
}

fn export_image_window_ui(ctx: &egui::Context, app: &mut AppState) -> Vec<Action> {
    let view = app.viewport.size_px;
    let dialog = ExportDialog {
        title: "Export Image",
        button: "Export…",
        purpose: Purpose::ExportImage,
    };
    dialog.show(ctx, &mut app.export_image, |ui, s| {
        egui::Grid::new("export-image-grid")
            .num_columns(2)
            .show(ui, |ui| {
                size_rows(ui, &mut s.width, &mut s.height, MAX_EXPORT_SIDE);
            });
        ui.horizontal_wrapped(|ui| {
            let (vw, vh) = (view.x.max(1.0) as u32, view.y.max(1.0) as u32);
            for (name, w, h) in [
                ("Window".to_string(), vw, vh),
                ("2× window".to_string(), vw * 2, vh * 2),
                ("4× window".to_string(), vw * 4, vh * 4),
                ("1080p".to_string(), 1920, 1080),
                ("4k".to_string(), 3840, 2160),
                ("8k".to_string(), 7680, 4320),
            ] {
                if ui.small_button(name).clicked() {
                    let scale = (MAX_EXPORT_SIDE as f64 / w.max(h) as f64).min(1.0);
                    s.width = ((w as f64 * scale) as u32).max(1);
                    s.height = ((h as f64 * scale) as u32).max(1);
                }
            }
        });
        ui.checkbox(&mut s.transparent, "Transparent background");
        ui.separator();
        crate::gui::panels::export_labels::annotation_ui(ui, &mut s.annotations, &app.scene);
        true
    })
}

fn export_meshes_window_ui(ctx: &egui::Context, app: &mut AppState) -> Vec<Action> {
    let dialog = ExportDialog {
        title: "Export Cut Meshes",
        button: "Choose Folder…",
        purpose: Purpose::ExportMeshes,
    };
    dialog.show(ctx, &mut app.export_meshes, |ui, s| {
        ui.label("Parts of every cut, one file per cutter and part:");
        ui.checkbox(&mut s.kept, "Kept (target outside the cutter)");
        ui.checkbox(&mut s.walls, "Walls (cutter surface inside the target)");
        ui.checkbox(&mut s.removed, "Removed (target inside the cutter)");
        ui.horizontal(|ui| {
            ui.label("Format");
            for f in [MeshFormat::Obj, MeshFormat::Stl, MeshFormat::Ply] {
                ui.radio_value(&mut s.format, f, f.extension().to_uppercase());
            }
        });
        s.kept || s.walls || s.removed
    })
}
