//! The Image section of the side panel: what the walls show (structure colour, image, blend),
//! where (walls, slices and ribbons), the window/level with its presets, and removing the image.
//! The image itself is read on a worker (`Action::OpenImage`); [`image_loaded`] puts it in the
//! scene.

use crate::intensity::{ImageLayer, WallDisplay, WindowPreset};

use super::CutawayApp;

/// A freshly read image joins the scene, unless it lies outside the models.
pub fn image_loaded(app: &mut CutawayApp, layer: ImageLayer) {
    if let Err(e) = crate::intensity::check_overlap(&layer.image, app.scene.bbox()) {
        app.complain(&e.context(layer.image.source.display().to_string()));
        return;
    }
    let (lo, hi) = layer.image.range();
    app.say(format!(
        "Image {}: {} × {} × {} {} voxels, values {lo} to {hi}",
        layer.image.source.display(),
        layer.image.dims[0],
        layer.image.dims[1],
        layer.image.dims[2],
        layer.image.kind().name()
    ));
    app.scene.image = Some(layer);
}

fn preset_label(preset: WindowPreset) -> &'static str {
    match preset {
        WindowPreset::SoftTissue => "Soft tissue",
        WindowPreset::Lung => "Lung",
        WindowPreset::Bone => "Bone",
        WindowPreset::Brain => "Brain",
        WindowPreset::Auto => "Auto",
    }
}

/// The Image section (nothing without an image).
pub fn image_panel_ui(ui: &mut egui::Ui, app: &mut CutawayApp) {
    let Some(layer) = app.scene.image.as_mut() else {
        return;
    };
    ui.add_space(10.0);
    let mut remove = false;
    egui::CollapsingHeader::new("Image")
        .default_open(true)
        .show(ui, |ui| {
            let name = layer
                .image
                .source
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default();
            ui.label(name);
            ui.horizontal(|ui| {
                for display in WallDisplay::ALL {
                    let label = match display {
                        WallDisplay::Color => "Colour",
                        WallDisplay::Image => "Image",
                        WallDisplay::Blend => "Blend",
                    };
                    ui.selectable_value(&mut layer.display, display, label);
                }
            });
            ui.horizontal(|ui| {
                ui.checkbox(&mut layer.on_walls, "Walls");
                ui.checkbox(&mut layer.on_slices, "Slices and ribbons");
            });
            ui.horizontal_wrapped(|ui| {
                for preset in WindowPreset::ALL {
                    if ui.button(preset_label(preset)).clicked() {
                        layer.window = preset.window(&layer.image);
                    }
                }
            });
            let (lo, hi) = layer.image.range();
            let speed = ((hi - lo) / 500.0).max(0.01);
            ui.horizontal(|ui| {
                ui.label("Level");
                ui.add(egui::DragValue::new(&mut layer.window.level).speed(speed));
                ui.label("Width");
                ui.add(
                    egui::DragValue::new(&mut layer.window.width)
                        .speed(speed)
                        .range(crate::intensity::Window::MIN_WIDTH..=f64::MAX),
                );
            });
            ui.weak("Shift + right drag on the view: width ↔, level ↕");
            remove = ui.button("Remove Image").clicked();
        });
    if remove {
        app.scene.image = None;
    }
}

/// Shift + secondary-button drag anywhere on the view adjusts the window like a radiology
/// viewer: right widens, down raises the level. Returns true when it took the drag.
pub fn window_drag(app: &mut CutawayApp, response: &egui::Response, ui: &egui::Ui) -> bool {
    let Some(layer) = app.scene.image.as_mut() else {
        return false;
    };
    if !(response.dragged_by(egui::PointerButton::Secondary) && ui.input(|i| i.modifiers.shift)) {
        return false;
    }
    let delta = response.drag_delta();
    let (lo, hi) = layer.image.range();
    let scale = ((hi - lo) / 1000.0).max(1e-3);
    layer.window = layer.window.dragged(delta.x as f64, delta.y as f64, scale);
    true
}
