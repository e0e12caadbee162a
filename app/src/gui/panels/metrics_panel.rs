//! The Metrics panel (View → Metrics): what the cuts remove from each structure, per cutter and
//! for the whole scene, the exposure of a focus structure and the distance from the cut walls to
//! the structures marked critical, whose closest points the viewport draws.
//!
//! The numbers come from [`crate::metrics::measure`], the code `cutaway metrics` prints, run on a
//! worker thread (an exact cut of the whole scene can take seconds). A new measurement starts
//! when what it depends on changed (cutters, their targets, focus, critical set, and the camera
//! when a focus is chosen) and no pointer button is held, so the panel updates on drag release;
//! one measurement runs at a time and the newest state is measured when it ends.

use std::time::Instant;

use glam::DVec2;

use crate::metrics::Metrics;

use crate::gui::jobs::Job;
use crate::gui::state::AppState;
use crate::gui::state::metrics::Request;
pub use crate::gui::state::metrics::{Measured, MetricsPanel, Scope};

/// Takes a finished measurement and starts the next one when the scene changed and no pointer
/// button is held. Call once per frame.
pub fn update(app: &mut AppState, ctx: &egui::Context) {
    let panel = &mut app.metrics;
    if let Some((request, job)) = &mut panel.job
        && let Some(result) = job.poll()
    {
        panel.shown = Some(result.map_err(|e| crate::platform::errors::error_line(&e)));
        panel.shown_request = Some(request.clone());
        panel.job = None;
    }
    if !panel.open || panel.job.is_some() {
        return;
    }
    // Names that are no longer in the scene (a model removed, another scene opened) go.
    let names: Vec<&str> = app
        .scene
        .models
        .iter()
        .map(|m| m.model.name.as_str())
        .collect();
    if panel.focus.as_deref().is_some_and(|f| !names.contains(&f)) {
        panel.focus = None;
    }
    panel.critical.retain(|c| names.contains(&c.as_str()));
    if app.scene.models.is_empty() || ctx.input(|i| i.pointer.any_down()) {
        return;
    }
    let request = Request::of(&app.scene, panel);
    if panel.shown_request.as_ref() == Some(&request) {
        return;
    }
    let scene = app.scene.clone();
    let options = panel.options();
    let repaint = ctx.clone();
    let job = Job::spawn(
        "Measuring the cuts",
        move || repaint.request_repaint(),
        move |_| {
            let started = Instant::now();
            let metrics = crate::metrics::measure(&scene, &options)?;
            Ok(Measured {
                metrics,
                ms: started.elapsed().as_secs_f64() * 1000.0,
            })
        },
    );
    panel.job = Some((request, job));
}

/// `12 345.6`: a measure with one decimal and thin grouping, or `–` when absent.
fn number(value: Option<f64>) -> String {
    match value {
        Some(v) if v.abs() >= 1000.0 => format!("{v:.0}"),
        Some(v) => format!("{v:.1}"),
        None => "–".to_string(),
    }
}

/// The panel's contents (the side panel itself is laid out by the app).
pub fn metrics_panel_ui(ui: &mut egui::Ui, app: &mut AppState) {
    ui.heading("Metrics");
    let names = app.scene.model_names();
    let panel = &mut app.metrics;
    let status = if panel.job.is_some() {
        "measuring…".to_string()
    } else {
        match &panel.shown {
            Some(Ok(m)) => format!("measured in {:.0} ms", m.ms),
            Some(Err(_)) => "failed".to_string(),
            None => String::new(),
        }
    };
    ui.label(egui::RichText::new(status).small().weak());

    // Focus structure.
    ui.horizontal(|ui| {
        ui.label("Focus");
        egui::ComboBox::from_id_salt("metrics-focus")
            .selected_text(panel.focus.as_deref().unwrap_or("none"))
            .width(170.0)
            .show_ui(ui, |ui| {
                ui.selectable_value(&mut panel.focus, None, "none");
                for name in &names {
                    ui.selectable_value(&mut panel.focus, Some(name.clone()), name);
                }
            });
    });
    // Critical structures.
    egui::CollapsingHeader::new(format!("Critical structures ({})", panel.critical.len()))
        .id_salt("metrics-critical")
        .show(ui, |ui| {
            egui::ScrollArea::vertical()
                .max_height(160.0)
                .id_salt("metrics-critical-list")
                .show(ui, |ui| {
                    for name in &names {
                        let mut on = panel.critical.contains(name);
                        if ui.checkbox(&mut on, name).changed() {
                            panel.set_critical(name, on);
                        }
                    }
                });
        });
    // Scope.
    let cutters = app.scene.cutters.len();
    if let Scope::Cutter(i) = panel.scope
        && i >= cutters
    {
        panel.scope = Scope::Scene;
    }
    ui.horizontal_wrapped(|ui| {
        ui.label("Cut");
        ui.selectable_value(&mut panel.scope, Scope::Scene, "whole scene");
        for i in 0..cutters {
            ui.selectable_value(
                &mut panel.scope,
                Scope::Cutter(i),
                format!("cutter {}", i + 1),
            );
        }
    });
    ui.separator();

    let measured = match &panel.shown {
        None => {
            ui.label("Measuring…");
            return;
        }
        Some(Err(e)) => {
            ui.colored_label(ui.visuals().error_fg_color, e);
            return;
        }
        Some(Ok(m)) => &m.metrics,
    };
    match panel.scope {
        Scope::Scene => scene_table(ui, measured),
        Scope::Cutter(i) => cutter_table(ui, measured, i),
    }
    if let Some(focus) = &measured.focus {
        ui.add_space(6.0);
        ui.strong(format!("Exposure of {}", focus.name));
        egui::Grid::new("metrics-exposure").show(ui, |ui| {
            ui.label("before the cut");
            ui.label(format!("{:.1} %", focus.exposure_before * 100.0));
            ui.end_row();
            ui.label("after the cut");
            ui.label(format!("{:.1} %", focus.exposure_after * 100.0));
            ui.end_row();
        });
        ui.label(
            egui::RichText::new(format!(
                "from the camera, {} surface samples",
                focus.samples
            ))
            .small()
            .weak(),
        );
    }
    let distances: Vec<_> = measured
        .structures
        .iter()
        .filter(|s| panel.critical.contains(&s.name))
        .collect();
    if !distances.is_empty() {
        ui.add_space(6.0);
        ui.strong("Distance from the cut walls");
        egui::Grid::new("metrics-distances").show(ui, |ui| {
            for s in distances {
                ui.label(&s.name);
                ui.label(match s.min_distance {
                    Some(d) => format!("{d:.1} mm"),
                    None => "no walls".to_string(),
                });
                ui.end_row();
            }
        });
    }
}

fn scene_table(ui: &mut egui::Ui, metrics: &Metrics) {
    let cut: Vec<_> = metrics
        .structures
        .iter()
        .filter(|s| s.removed_area > 0.0 || s.wall_area > 0.0)
        .collect();
    if cut.is_empty() {
        ui.label("The cuts remove nothing.");
        return;
    }
    egui::Grid::new("metrics-structures")
        .striped(true)
        .show(ui, |ui| {
            ui.strong("structure");
            ui.strong("volume mm³");
            ui.strong("area mm²");
            ui.strong("wall mm²");
            ui.end_row();
            for s in cut {
                ui.label(&s.name);
                ui.label(number(s.removed_volume));
                ui.label(number(Some(s.removed_area)));
                ui.label(number(Some(s.wall_area)));
                ui.end_row();
            }
        });
    let depth = metrics.cutters.iter().map(|c| c.depth).fold(0.0, f64::max);
    ui.label(format!("deepest cut {depth:.1} mm"));
}

fn cutter_table(ui: &mut egui::Ui, metrics: &Metrics, index: usize) {
    let Some(c) = metrics.cutters.iter().find(|c| c.index == index) else {
        ui.label("This cutter removes nothing.");
        return;
    };
    egui::Grid::new("metrics-cutter")
        .striped(true)
        .show(ui, |ui| {
            for (what, value) in [
                ("structure", c.target.clone()),
                (
                    "removed volume",
                    format!("{} mm³", number(c.removed_volume)),
                ),
                (
                    "removed area",
                    format!("{} mm²", number(Some(c.removed_area))),
                ),
                ("wall area", format!("{} mm²", number(Some(c.wall_area)))),
                ("cut depth", format!("{:.1} mm", c.depth)),
            ] {
                ui.label(what);
                ui.label(value);
                ui.end_row();
            }
        });
}

/// Draws, for each critical structure, its closest point and the nearest wall point joined by a
/// line, with the distance, over the 3D view.
pub fn paint_closest_points(painter: &egui::Painter, rect: egui::Rect, app: &AppState) {
    let panel = &app.metrics;
    if !panel.open {
        return;
    }
    let Some(Ok(measured)) = &panel.shown else {
        return;
    };
    let ppp = painter.ctx().pixels_per_point() as f64;
    let size = app.viewport.size_px;
    let to_screen = |p: [f64; 3]| -> Option<egui::Pos2> {
        let px: DVec2 = app.scene.camera.project(size, glam::DVec3::from_array(p))?;
        Some(rect.min + egui::vec2((px.x / ppp) as f32, (px.y / ppp) as f32))
    };
    let colour = egui::Color32::from_rgb(230, 30, 120);
    for s in &measured.metrics.structures {
        if !panel.critical.contains(&s.name) {
            continue;
        }
        let (Some(on), Some(wall), Some(d)) = (s.closest_point, s.wall_point, s.min_distance)
        else {
            continue;
        };
        let (Some(a), Some(b)) = (to_screen(on), to_screen(wall)) else {
            continue;
        };
        painter.line_segment([a, b], egui::Stroke::new(2.0, colour));
        painter.circle(a, 5.0, colour, egui::Stroke::new(1.5, egui::Color32::WHITE));
        painter.circle_filled(b, 3.5, colour);
        let galley = painter.layout_no_wrap(
            format!("{}: {d:.1} mm", s.name),
            egui::FontId::proportional(13.0),
            egui::Color32::WHITE,
        );
        let at = a + egui::vec2(8.0, -8.0 - galley.size().y);
        painter.rect_filled(
            egui::Rect::from_min_size(at, galley.size()).expand(3.0),
            3.0,
            colour,
        );
        painter.galley(at, galley, egui::Color32::WHITE);
    }
}

/// The right-hand side panel's contents: Variants, Metrics and Rulers.
pub fn side_panel_ui(ui: &mut egui::Ui, app: &mut AppState) {
    egui::ScrollArea::vertical()
        .id_salt("metrics-side")
        .show(ui, |ui| {
            crate::gui::panels::variants_panel::variants_ui(ui, app);
            ui.separator();
            if app.metrics.open {
                metrics_panel_ui(ui, app);
            } else if ui.button("Show Metrics").clicked() {
                app.metrics.open = true;
            }
            ui.separator();
            crate::gui::viewport::ruler::rulers_ui(ui, app);
        });
}

/// Whether the side panel is shown.
pub fn side_panel_open(app: &AppState) -> bool {
    app.metrics.open || app.ruler.active || app.compare.open
}

/// The View menu's Metrics, Ruler and Compare Variants switches.
pub fn view_menu_items(ui: &mut egui::Ui, app: &mut AppState) {
    ui.checkbox(&mut app.metrics.open, "Metrics");
    let mut ruler = app.ruler.active;
    if ui.checkbox(&mut ruler, "Ruler").changed() {
        app.ruler.active = ruler;
        app.ruler.first = None;
    }
    ui.checkbox(&mut app.compare.open, "Compare Variants");
}
