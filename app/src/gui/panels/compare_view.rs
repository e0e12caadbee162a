//! The Compare view: the scene's cut variants ([`crate::scene::variants`]) side by side in 2 to 4
//! viewports that share one camera (the scene's), each variant's metrics under it — what
//! `cutaway compare` writes as a sheet, live in the window.
//!
//! Each viewport is the variant drawn with its cuts executed by the headless renderer, as
//! `cutaway compare` draws it ([`crate::compare`]), on a worker thread. Dragging in any viewport
//! turns the shared camera (Shift pans, the wheel zooms); the pictures are drawn again when the
//! pointer is released. The cut geometry and the measures of a variant are kept until its
//! cutters change, so turning the camera only re-renders (and re-measures exposure when a focus
//! structure is chosen in the Metrics panel).

use std::sync::Arc;
use std::time::Instant;

use glam::DVec2;

use crate::cutting::cut_scene::preview_geometry;
use crate::metrics::MetricsOptions;
use crate::metrics::variants::VariantMetrics;
use crate::render::HeadlessRenderer;
use crate::scene::Scene;
use crate::view::RenderPngOptions;

use crate::gui::jobs::Job;
use crate::gui::state::AppState;
use crate::gui::state::compare::{Cached, Request, Worker};
pub use crate::gui::state::compare::{CompareView, Compared, MAX_SHOWN};

/// Draws and measures variant `k` of `scene` with the worker's renderer and cache.
fn compare_one(
    worker: &mut Worker,
    scene: &Scene,
    k: usize,
    name: &str,
    tile: [u32; 2],
    options: &MetricsOptions,
    camera: [f64; 9],
) -> anyhow::Result<(image::RgbaImage, VariantMetrics)> {
    let shown = crate::scene::variants::variant_scene(scene, k).expect("k < variant count");
    let key = (
        shown.cutters.clone(),
        shown
            .models
            .iter()
            .map(|m| Arc::as_ptr(&m.model.mesh) as usize)
            .collect::<Vec<_>>(),
    );
    let at = match worker.cache.iter().position(|c| c.key == key) {
        Some(at) => at,
        None => {
            let geometry = Arc::new(preview_geometry(&shown));
            if let Some(note) = geometry.notes.first() {
                anyhow::bail!("variant '{name}': {note}");
            }
            worker.cache.push(Cached {
                key,
                geometry,
                metrics: None,
            });
            worker.cache.len() - 1
        }
    };
    // Exposure is seen from the camera; the rest does not depend on it.
    let camera_matters = options.focus.is_some();
    let fresh = worker.cache[at].metrics.as_ref().is_some_and(|(o, c, _)| {
        o.focus == options.focus
            && o.critical == options.critical
            && (!camera_matters || *c == camera)
    });
    if !fresh {
        let metrics = crate::metrics::measure(&shown, options)
            .map_err(|e| anyhow::anyhow!("variant '{name}': {e}"))?;
        worker.cache[at].metrics = Some((options.clone(), camera, metrics));
    }
    let geometry = worker.cache[at].geometry.clone();
    let metrics = worker.cache[at]
        .metrics
        .as_ref()
        .expect("measured")
        .2
        .clone();
    if worker.renderer.is_none() {
        worker.renderer = Some(HeadlessRenderer::new()?);
    }
    let renderer = worker.renderer.as_mut().expect("renderer");
    let render_options = RenderPngOptions::new(tile[0], tile[1]);
    let image = crate::annotate::risk_legend::render_with_legend(
        renderer,
        &shown,
        &render_options,
        Some(geometry),
    )
    .map_err(|e| anyhow::anyhow!("variant '{name}': {e}"))?;
    Ok((
        image,
        VariantMetrics {
            name: name.to_string(),
            metrics,
        },
    ))
}

/// Takes finished pictures and starts new ones when the variants, the camera or the viewport
/// size changed and no pointer button is held. Call once per frame.
pub fn update(app: &mut AppState, ctx: &egui::Context) {
    if !app.compare.open && app.compare.framed_for.take().is_some() {
        crate::gui::viewport::view_menu::apply(
            app,
            crate::gui::viewport::view_menu::ViewCommand::ZoomToFit,
        );
    }
    let view = &mut app.compare;
    if let Some((request, job)) = &mut view.job
        && let Some(result) = job.poll()
    {
        view.textures.clear();
        if let Ok(compared) = &result {
            for (k, image) in compared.images.iter().enumerate() {
                let size = [image.width() as usize, image.height() as usize];
                let pixels = egui::ColorImage::from_rgba_unmultiplied(size, image.as_raw());
                view.textures.push(ctx.load_texture(
                    format!("compare-{k}"),
                    pixels,
                    egui::TextureOptions::LINEAR,
                ));
            }
        }
        view.shown = Some(result.map_err(|e| crate::platform::errors::error_line(&e)));
        view.shown_request = Some(request.clone());
        view.job = None;
    }
    if !view.open && view.job.is_none() && view.shown.is_some() {
        // Closed: give back the renderer's device, the cached cuts and the pictures.
        if let Ok(mut worker) = view.worker.try_lock() {
            *worker = Worker::default();
        }
        view.textures.clear();
        view.shown = None;
        view.shown_request = None;
    }
    if !view.open
        || view.job.is_some()
        || view.tile[0] < 16
        || view.tile[1] < 16
        || app.scene.models.is_empty()
        || ctx.input(|i| i.pointer.any_down())
    {
        return;
    }
    let options = app.metrics.options();
    let request = Request::of(&app.scene, view.tile, &options);
    if view.shown_request.as_ref() == Some(&request) {
        return;
    }
    let scene = app.scene.clone();
    let worker = view.worker.clone();
    let repaint = ctx.clone();
    let (tile, camera) = (request.tile, request.camera);
    let names: Vec<String> = request.variants.iter().map(|(n, _)| n.clone()).collect();
    let job = Job::spawn(
        "Drawing the variants",
        move || repaint.request_repaint(),
        move |progress| {
            let started = Instant::now();
            let mut worker = worker
                .lock()
                .map_err(|_| anyhow::anyhow!("compare worker"))?;
            let mut images = Vec::new();
            let mut variants = Vec::new();
            for (k, name) in names.iter().enumerate() {
                progress.check()?;
                progress.set(k as u64, names.len() as u64);
                let (image, metrics) =
                    compare_one(&mut worker, &scene, k, name, tile, &options, camera)?;
                images.push(image);
                variants.push(metrics);
            }
            // Keep only what the variants shown now use.
            let keep = worker.cache.len().saturating_sub(2 * MAX_SHOWN);
            worker.cache.drain(..keep);
            Ok(Compared {
                images,
                variants,
                ms: started.elapsed().as_secs_f64() * 1000.0,
            })
        },
    );
    view.job = Some((request, job));
}

/// The view, in place of the 3D view: the viewports in a row, each with its name and its column
/// of the metrics table under it.
pub fn compare_ui(ui: &mut egui::Ui, app: &mut AppState) {
    egui::Frame::NONE
        .fill(ui.visuals().panel_fill)
        .inner_margin(egui::Margin::same(8))
        .show(ui, |ui| {
            ui.set_min_size(ui.available_size());
            compare_contents(ui, app);
        });
}

fn compare_contents(ui: &mut egui::Ui, app: &mut AppState) {
    let names = crate::scene::variants::names(&app.scene);
    let shown = names.len().min(MAX_SHOWN);
    ui.horizontal(|ui| {
        ui.heading("Compare variants");
        if names.len() > MAX_SHOWN {
            ui.label(format!("(the first {MAX_SHOWN} of {})", names.len()));
        }
        if let Some((_, job)) = &app.compare.job
            && job.started.elapsed().as_millis() > 150
        {
            ui.spinner();
        } else if let Some(Ok(c)) = &app.compare.shown {
            ui.label(egui::RichText::new(format!("drawn in {:.0} ms", c.ms)).weak());
        }
        if ui.button("Close").clicked() {
            app.compare.open = false;
        }
    });
    if shown < 2 {
        ui.label("Make a second variant in the Metrics panel (View → Metrics) to compare.");
        return;
    }
    let ppp = ui.ctx().pixels_per_point();
    let gap = 8.0;
    let rows = match &app.compare.shown {
        Some(Ok(c)) => crate::metrics::table::rows(&c.variants),
        _ => Vec::new(),
    };
    let table_height = 22.0 * rows.len().max(5) as f32 + 16.0;
    let width = ((ui.available_width() - gap * (shown as f32 - 1.0)) / shown as f32).max(32.0);
    let height = (ui.available_height() - table_height - 24.0).max(32.0);
    app.compare.tile = [(width * ppp).round() as u32, (height * ppp).round() as u32];
    if app.compare.framed_for != Some(shown) {
        app.compare.framed_for = Some(shown);
        let aspect = f64::from(width) / f64::from(height);
        app.scene.camera =
            crate::view::fit::fit_to_box(&app.scene.camera, &app.scene.bbox(), aspect);
    }
    if let Some(Err(e)) = &app.compare.shown {
        ui.colored_label(ui.visuals().error_fg_color, e.clone());
    }
    ui.horizontal_top(|ui| {
        ui.spacing_mut().item_spacing.x = gap;
        for (k, name) in names.iter().take(shown).enumerate() {
            ui.vertical(|ui| {
                ui.set_width(width);
                let label = if k == app.scene.variants.active {
                    format!("{name} (active)")
                } else {
                    name.clone()
                };
                ui.strong(label);
                let (rect, response) =
                    ui.allocate_exact_size(egui::vec2(width, height), egui::Sense::drag());
                match app.compare.textures.get(k) {
                    Some(texture) => {
                        ui.painter().image(
                            texture.id(),
                            rect,
                            egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0)),
                            egui::Color32::WHITE,
                        );
                    }
                    None => {
                        ui.painter()
                            .rect_filled(rect, 0.0, egui::Color32::from_gray(60));
                    }
                }
                ui.painter().rect_stroke(
                    rect,
                    0.0,
                    ui.visuals().widgets.noninteractive.bg_stroke,
                    egui::StrokeKind::Outside,
                );
                camera_input(ui, &response, app, ppp as f64);
                egui::Grid::new(("compare-metrics", k))
                    .striped(true)
                    .show(ui, |ui| {
                        for row in &rows {
                            ui.label(row.label.trim());
                            ui.label(row.cells.get(k).cloned().unwrap_or_default());
                            ui.end_row();
                        }
                    });
            });
        }
    });
}

/// Drag turns (Shift: pans) the shared camera; the wheel zooms.
fn camera_input(ui: &egui::Ui, response: &egui::Response, app: &mut AppState, ppp: f64) {
    if response.dragged() {
        let delta = response.drag_delta();
        let delta_px = DVec2::new(delta.x as f64 * ppp, delta.y as f64 * ppp);
        if ui.input(|i| i.modifiers.shift) {
            let size = DVec2::new(app.compare.tile[0] as f64, app.compare.tile[1] as f64);
            crate::view::camera_controls::pan(&mut app.scene.camera, delta_px, size);
        } else {
            crate::view::camera_controls::orbit(&mut app.scene.camera, delta_px);
        }
    }
    if response.hovered() {
        let (notches, _) = crate::gui::viewport::navigation::wheel_notches(ui);
        if notches != 0.0 {
            let min = app.scene.bbox().diagonal().max(1e-6) * 1e-3;
            crate::view::camera_controls::zoom(&mut app.scene.camera, notches, min);
        }
    }
}
