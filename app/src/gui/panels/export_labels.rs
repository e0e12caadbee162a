//! The annotation part of the Export Image dialog: structure labels with leader lines (each
//! structure can be switched off), the scale bar and the orientation marker, drawn by
//! [`crate::annotate::picture`], the same code as `cutaway render --labels`.

use crate::annotate::picture::AnnotationChoice;
use crate::annotate::visible::is_opaque;
use crate::scene::Scene;

/// The dialog's annotation controls.
pub fn annotation_ui(ui: &mut egui::Ui, choice: &mut AnnotationChoice, scene: &Scene) {
    ui.checkbox(&mut choice.labels, "Structure labels");
    if choice.labels {
        egui::CollapsingHeader::new("Labelled structures")
            .id_salt("export-labelled-structures")
            .show(ui, |ui| {
                egui::ScrollArea::vertical()
                    .max_height(180.0)
                    .id_salt("export-labelled-list")
                    .show(ui, |ui| {
                        for m in (0..scene.models.len()).filter(|&m| is_opaque(scene, m)) {
                            let name = &scene.models[m].model.name;
                            let mut on = !choice.unlabelled.contains(name);
                            if ui.checkbox(&mut on, name).changed() {
                                choice.unlabelled.retain(|n| n != name);
                                if !on {
                                    choice.unlabelled.push(name.clone());
                                }
                            }
                        }
                    });
            });
    }
    ui.checkbox(&mut choice.extras.scale_bar, "Scale bar (mm)");
    ui.checkbox(&mut choice.extras.marker, "Orientation marker");
}
