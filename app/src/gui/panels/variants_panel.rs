//! The Variants section of the Metrics panel: the scene's named cutter sets
//! ([`crate::scene::variants`]), the active one highlighted. Click a variant to switch to it; New starts
//! an empty cutter set, Duplicate copies the active one, Rename and Delete act on the active one.
//! Every change is an undo step, and the variants are saved in the session.

use crate::gui::state::AppState;
use crate::scene::variants;

/// A change to the scene's variants.
#[derive(Clone, Debug, PartialEq)]
pub enum VariantCommand {
    /// Make variant `k` the active one.
    Switch(usize),
    /// A new variant without cutters, named so, made active.
    New(String),
    /// A copy of the active variant named so, made active.
    Duplicate(String),
    /// Rename the active variant.
    Rename(String),
    /// Delete the active variant.
    Delete,
}

/// Applies `command` to the app's scene as one undo step; refusals go to the status bar.
pub fn apply(app: &mut AppState, command: VariantCommand) {
    let before = app.scene.clone();
    let active = app.scene.variants.active;
    let result = match &command {
        VariantCommand::Switch(k) => {
            variants::switch(&mut app.scene, *k).map(|()| "switch variant")
        }
        VariantCommand::New(name) => variants::create(&mut app.scene, name).map(|_| {
            app.scene.cutters.clear();
            "new variant"
        }),
        VariantCommand::Duplicate(name) => {
            variants::create(&mut app.scene, name).map(|_| "duplicate variant")
        }
        VariantCommand::Rename(name) => {
            variants::rename(&mut app.scene, active, name).map(|()| "rename variant")
        }
        VariantCommand::Delete => {
            variants::remove(&mut app.scene, active).map(|()| "delete variant")
        }
    };
    match result {
        Ok(label) => {
            if app.scene.cutters != before.cutters {
                // The editor's cutter, the hidden cutters and the cutter shown in the Cutter
                // panel belong to the variant left.
                app.viewport.editor.finish();
                app.cutters_hidden = false;
                app.hidden_cutters = 0;
                app.selected_cutter = 0;
            }
            app.record(label, before);
            let name = variants::names(&app.scene)
                .get(app.scene.variants.active)
                .cloned()
                .unwrap_or_default();
            app.say(format!("Variant '{name}' ({label})"));
        }
        Err(e) => {
            app.scene = before;
            app.complain(&anyhow::anyhow!(e));
        }
    }
}

/// A free name `stem 2`, `stem 3`, … for a new variant.
fn free_name(app: &AppState, stem: &str) -> String {
    let names = variants::names(&app.scene);
    (2..)
        .map(|n| format!("{stem} {n}"))
        .find(|n| !names.contains(n))
        .expect("a free name")
}

/// The section's contents.
pub fn variants_ui(ui: &mut egui::Ui, app: &mut AppState) {
    ui.heading("Variants");
    let names = variants::names(&app.scene);
    let active = app.scene.variants.active;
    let mut commands = Vec::new();
    for (k, name) in names.iter().enumerate() {
        let cutters = variants::all(&app.scene).get(k).map_or(0, |(_, c)| c.len());
        if ui
            .selectable_label(k == active, format!("{name}  ({cutters} cutters)"))
            .on_hover_text("Click to work on this variant")
            .clicked()
            && k != active
        {
            commands.push(VariantCommand::Switch(k));
        }
    }
    let id = egui::Id::unique("variant-name");
    let mut name: String = ui.data_mut(|d| d.get_temp(id)).unwrap_or_default();
    ui.horizontal(|ui| {
        ui.label("Name");
        ui.add(egui::TextEdit::singleline(&mut name).desired_width(140.0));
    });
    let typed = |stem: &str| {
        if name.trim().is_empty() {
            free_name(app, stem)
        } else {
            name.trim().to_string()
        }
    };
    ui.horizontal_wrapped(|ui| {
        if ui
            .button("New")
            .on_hover_text("A new variant without cutters")
            .clicked()
        {
            commands.push(VariantCommand::New(typed("variant")));
        }
        if ui
            .button("Duplicate")
            .on_hover_text("A copy of the active variant's cutters")
            .clicked()
        {
            let stem = names.get(active).cloned().unwrap_or_default();
            commands.push(VariantCommand::Duplicate(typed(&stem)));
        }
        if ui
            .add_enabled(!name.trim().is_empty(), egui::Button::new("Rename"))
            .on_hover_text("Give the active variant the name typed above")
            .clicked()
        {
            commands.push(VariantCommand::Rename(name.trim().to_string()));
        }
        if ui
            .add_enabled(names.len() > 1, egui::Button::new("Delete"))
            .on_hover_text("Delete the active variant")
            .clicked()
        {
            commands.push(VariantCommand::Delete);
        }
    });
    let mut compare = app.compare.open;
    if ui
        .add_enabled(
            names.len() > 1,
            egui::Checkbox::new(&mut compare, "Compare side by side"),
        )
        .changed()
    {
        app.compare.open = compare;
    }
    if !commands.is_empty() {
        name.clear();
    }
    ui.data_mut(|d| d.insert_temp(id, name));
    for command in commands {
        apply(app, command);
    }
}
