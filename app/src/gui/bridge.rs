//! Where the window meets the other parts of the application: the renderer (paint callback and
//! headless export), the session file, the embedded default scene and the mesh export. Kept in
//! one file so the panels never depend on those APIs directly. Cutting itself (the editor slot,
//! the whole-scene cut, the live cut, picks) is egui-free in [`crate::cutting`].

use std::path::Path;
use std::sync::Arc;

use glam::DVec2;

use crate::cutting::cut_scene::PreviewGeometry;
use crate::gui::state::AppState;
use crate::render::{CutterOverlay, FrameInputs, OutputTarget, Renderer, ViewMode};
use crate::scene::Scene;

/// Whether the scalpel mode exists in this build (its button is disabled otherwise).
pub const SCALPEL_AVAILABLE: bool = true;

/// Installs the renderer in egui's callback resources; false when there is no wgpu device.
pub fn install_renderer(render_state: Option<&egui_wgpu::RenderState>) -> bool {
    let Some(rs) = render_state else { return false };
    let renderer = Renderer::new(&rs.device, OutputTarget::egui(rs.target_format));
    rs.renderer.write().callback_resources.insert(renderer);
    true
}

/// The paint callback: offscreen render in `prepare`, composite in `paint`.
struct ViewCallback {
    inputs: FrameInputs,
}

impl egui_wgpu::CallbackTrait for ViewCallback {
    fn prepare(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        _screen: &egui_wgpu::ScreenDescriptor,
        encoder: &mut wgpu::CommandEncoder,
        resources: &mut egui_wgpu::CallbackResources,
    ) -> Vec<wgpu::CommandBuffer> {
        if let Some(renderer) = resources.get_mut::<Renderer>() {
            renderer.prepare(device, queue, encoder, &self.inputs);
        }
        Vec::new()
    }

    fn paint(
        &self,
        _info: egui::PaintCallbackInfo,
        pass: &mut wgpu::RenderPass<'static>,
        resources: &egui_wgpu::CallbackResources,
    ) {
        if let Some(renderer) = resources.get::<Renderer>() {
            renderer.paint(pass);
        }
    }
}

/// The cut the window draws in its current mode, with its parts and notes: Camera and Scalpel
/// draw the cut without the removed-piece views as Preview does, Preview the whole computed cut,
/// Edit the live cut (when it is on and there are cutters).
pub fn shown_cut(app: &AppState) -> Option<Arc<PreviewGeometry>> {
    use crate::gui::action::Mode;
    match app.mode {
        Mode::Camera | Mode::Scalpel => crate::gui::viewport::cut_view::cut_without_views(app),
        Mode::Preview => {
            crate::gui::viewport::cut_view::drop_derived();
            app.viewport.preview.clone()
        }
        Mode::Edit => {
            crate::gui::viewport::cut_view::drop_derived();
            let live = app.viewport.live.enabled && !app.scene.cutters.is_empty();
            live.then(|| app.viewport.live.geometry()).flatten()
        }
    }
}

/// What the renderer draws for the window's current state.
pub fn frame_inputs(app: &AppState, size: [u32; 2]) -> FrameInputs {
    use crate::gui::action::Mode;
    let cut = shown_cut(app);
    let mode = match app.mode {
        Mode::Edit => ViewMode::Edit,
        Mode::Preview => ViewMode::Preview,
        Mode::Camera | Mode::Scalpel if cut.is_some() => ViewMode::Preview,
        Mode::Camera | Mode::Scalpel => ViewMode::Camera,
    };
    let mut inputs = crate::view::frame::frame_of(&app.scene, size, mode);
    inputs.show_cut(cut);
    crate::gui::viewport::cut_view::highlight_selection(app, &mut inputs.models);
    if app.mode == Mode::Edit && app.viewport.live.enabled && !app.scene.cutters.is_empty() {
        inputs.deltas = app.viewport.live.deltas();
    }
    if app.mode == Mode::Scalpel {
        inputs.deltas.extend(app.viewport.scalpel.delta());
    }
    inputs.risk = crate::gui::risk_map::current(app);
    if app.mode == Mode::Edit {
        let active = app.viewport.editor.active_cutter();
        let hidden = |i: usize| app.cutters_hidden && i < app.hidden_cutters && Some(i) != active;
        inputs.overlays = app
            .scene
            .cutters
            .iter()
            .enumerate()
            .filter(|&(i, _)| !hidden(i))
            .map(|(i, c)| CutterOverlay {
                highlighted_plane: if Some(i) == active {
                    app.viewport.editor.highlighted_plane()
                } else {
                    None
                },
                active: Some(i) == active,
                ..crate::cutting::overlay::cutter_overlay(c)
            })
            .collect();
    }
    inputs
}

/// Draws the scene with the GPU renderer into `rect`; false when no renderer is installed.
pub fn paint_scene(ui: &mut egui::Ui, rect: egui::Rect, app: &AppState) -> bool {
    if !app.viewport.gpu {
        return false;
    }
    let ppp = ui.ctx().pixels_per_point();
    let size = [
        ((rect.width() * ppp).round() as u32).max(1),
        ((rect.height() * ppp).round() as u32).max(1),
    ];
    let inputs = frame_inputs(app, size);
    ui.painter().add(egui_wgpu::Callback::new_paint_callback(
        rect,
        ViewCallback { inputs },
    ));
    if let Some(strip) = app.viewport.editor.init_strip() {
        let viewport = DVec2::new(
            rect.width() as f64 * ppp as f64,
            rect.height() as f64 * ppp as f64,
        );
        let pts: Vec<egui::Pos2> = strip
            .iter()
            .filter_map(|p| app.scene.camera.project(viewport, *p))
            .map(|p| rect.min + egui::vec2(p.x as f32 / ppp, p.y as f32 / ppp))
            .collect();
        if pts.len() == 4 {
            ui.painter().add(egui::Shape::convex_polygon(
                pts,
                egui::Color32::from_rgba_unmultiplied(255, 160, 40, 70),
                egui::Stroke::new(1.5, egui::Color32::from_rgb(255, 160, 40)),
            ));
        }
    }
    true
}

/// Writes the window's scene as a session file (atomic).
pub fn save_session(app: &AppState, path: &Path) -> anyhow::Result<()> {
    crate::session::save(path, &app.scene)
}

/// Renders `scene` headless into a PNG at `path` (worker thread).
pub fn export_image(
    scene: &Scene,
    preview: bool,
    settings: &crate::gui::state::export_settings::ExportImageSettings,
    path: &Path,
) -> anyhow::Result<String> {
    let mut options = crate::view::RenderPngOptions::new(settings.width, settings.height);
    options.transparent_background = settings.transparent;
    options.mode = Some(if preview {
        ViewMode::Preview
    } else {
        ViewMode::Camera
    });
    let (image, _) =
        crate::annotate::picture::render_annotated(scene, &options, &settings.annotations)
            .map_err(|e| anyhow::anyhow!("{}: {e:#}", path.display()))?;
    let mut png = Vec::new();
    image
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    crate::io::write_file(path, &png)?;
    Ok(format!(
        "Exported {}×{} image to {}",
        settings.width,
        settings.height,
        path.display()
    ))
}

/// At most this many triangles are drawn by the CPU fallback.
const FALLBACK_TRIANGLES: usize = 40_000;

/// A CPU preview of the scene for when no GPU renderer is available (a window on a non-wgpu
/// backend): a subsample of the visible triangles, flat-shaded with a headlight and sorted back
/// to front.
pub fn paint_fallback(painter: &egui::Painter, rect: egui::Rect, app: &AppState) {
    let bg = app.scene.render.background;
    let to_u8 = |c: f32| (c.clamp(0.0, 1.0) * 255.0) as u8;
    painter.rect_filled(
        rect,
        0.0,
        egui::Color32::from_rgb(to_u8(bg[0]), to_u8(bg[1]), to_u8(bg[2])),
    );
    let camera = &app.scene.camera;
    let viewport = DVec2::new(rect.width() as f64, rect.height() as f64);
    let visible: Vec<&crate::scene::SceneModel> = app
        .scene
        .models
        .iter()
        .filter(|m| m.visible && m.opacity > 0.0)
        .collect();
    let total: usize = visible.iter().map(|m| m.model.mesh.triangle_count()).sum();
    if total == 0 {
        return;
    }
    let stride = total.div_ceil(FALLBACK_TRIANGLES).max(1);
    let forward = camera.forward();
    let mut tris: Vec<(f64, [egui::Pos2; 3], egui::Color32)> = Vec::new();
    for model in visible {
        let alpha = to_u8(model.opacity);
        for t in (0..model.model.mesh.triangle_count()).step_by(stride) {
            let corners = model.model.mesh.corners(t);
            let Some(n) = (corners[1] - corners[0])
                .cross(corners[2] - corners[0])
                .try_normalize()
            else {
                continue;
            };
            let projected: Vec<egui::Pos2> = corners
                .iter()
                .filter_map(|c| camera.project(viewport, *c))
                .map(|p| rect.min + egui::vec2(p.x as f32, p.y as f32))
                .collect();
            let [a, b, c] = projected[..] else { continue };
            let light = (0.25 + 0.75 * n.dot(-forward).abs()) as f32;
            let colour = egui::Color32::from_rgba_unmultiplied(
                to_u8(model.color[0] * light),
                to_u8(model.color[1] * light),
                to_u8(model.color[2] * light),
                alpha,
            );
            let depth = ((corners[0] + corners[1] + corners[2]) / 3.0 - camera.eye).dot(forward);
            if model.style == crate::scene::ModelStyle::Wireframe {
                painter.add(egui::Shape::closed_line(
                    vec![a, b, c],
                    egui::Stroke::new(0.5, colour),
                ));
            } else {
                tris.push((depth, [a, b, c], colour));
            }
        }
    }
    tris.sort_by(|a, b| b.0.total_cmp(&a.0));
    let mut mesh = egui::Mesh::default();
    for (_, pts, colour) in tris {
        let base = mesh.vertices.len() as u32;
        for p in pts {
            mesh.colored_vertex(p, colour);
        }
        mesh.add_triangle(base, base + 1, base + 2);
    }
    painter.add(egui::Shape::mesh(mesh));
    if stride > 1 {
        painter.text(
            rect.right_bottom() - egui::vec2(10.0, 10.0),
            egui::Align2::RIGHT_BOTTOM,
            format!("CPU preview: 1 of every {stride} triangles"),
            egui::FontId::proportional(12.0),
            egui::Color32::from_gray(60),
        );
    }
}

/// What the window holds now, counted ([`crate::platform::memory_census`]).
pub fn memory_census(app: &AppState) -> crate::platform::memory_census::MemoryCensus {
    crate::platform::memory_census::MemoryCensus {
        live: app.viewport.live.census(),
        preview_triangles: app.viewport.preview.as_ref().map(|p| p.triangle_count()),
        derived_cut: crate::gui::viewport::cut_view::holds_derived(),
        editor_indexes: app.viewport.editor.index_count(),
        pick_trees: app.viewport.picks.tree_count(),
        pick_bytes: app.viewport.picks.tree_bytes(),
        gpu: app.wgpu.as_ref().and_then(|rs| {
            rs.renderer
                .read()
                .callback_resources
                .get::<Renderer>()
                .map(Renderer::census)
        }),
    }
}
