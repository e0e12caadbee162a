//! Where the window meets the other parts of the application: the renderer, the session file, the
//! embedded default scene, the cutter editor and the boolean. Kept in one file so the panels never
//! depend on those APIs directly.

use std::path::Path;

use glam::{DVec2, DVec3};

use cutter::events::EditorEvent;

use super::app::CutawayApp;
use crate::scene::{ModelStyle, Scene};

/// Whether the scalpel mode exists in this build (its button is disabled otherwise).
pub const SCALPEL_AVAILABLE: bool = false;

/// The cutter editor of the window (placeholder until `cutter::Editor` lands: counts events).
#[derive(Default)]
pub struct EditorSlot {
    events: usize,
}

impl EditorSlot {
    /// Feeds one event; returns true when the cutters changed (an undoable edit happened).
    pub fn handle(&mut self, scene: &mut Scene, target: Option<usize>, viewport: DVec2, event: EditorEvent) -> bool {
        let _ = (scene, target, viewport, event);
        self.events += 1;
        false
    }

    pub fn undo(&mut self) {}

    pub fn redo(&mut self) {}

    pub fn cutter_count(&self) -> usize {
        0
    }
}

/// Installs the renderer in egui's callback resources; false when there is no wgpu device.
pub fn install_renderer(render_state: Option<&egui_wgpu::RenderState>) -> bool {
    let _ = render_state;
    false
}

/// Draws the scene with the GPU renderer into `rect`; false when no renderer is installed.
pub fn paint_scene(ui: &mut egui::Ui, rect: egui::Rect, app: &CutawayApp) -> bool {
    let _ = (ui, rect, app);
    false
}

/// At most this many triangles are drawn by the CPU fallback.
const FALLBACK_TRIANGLES: usize = 40_000;

/// A CPU preview of the scene for when no GPU renderer is available: a subsample of the visible
/// triangles, flat-shaded with a headlight and sorted back to front.
pub fn paint_fallback(painter: &egui::Painter, rect: egui::Rect, app: &CutawayApp) {
    let bg = app.scene.render.background;
    let top = egui::Color32::from_rgb((bg[0] * 255.0) as u8, (bg[1] * 255.0) as u8, (bg[2] * 255.0) as u8);
    painter.rect_filled(rect, 0.0, top);
    let camera = &app.scene.camera;
    let viewport = DVec2::new(rect.width() as f64, rect.height() as f64);
    let visible: Vec<&crate::scene::SceneModel> = app.scene.models.iter().filter(|m| m.visible && m.opacity > 0.0).collect();
    let total: usize = visible.iter().map(|m| m.mesh.triangle_count()).sum();
    if total == 0 {
        return;
    }
    let stride = total.div_ceil(FALLBACK_TRIANGLES).max(1);
    let forward = camera.forward();
    let mut tris: Vec<(f64, [egui::Pos2; 3], egui::Color32)> = Vec::new();
    for model in visible {
        let alpha = (model.opacity.clamp(0.0, 1.0) * 255.0) as u8;
        for t in (0..model.mesh.triangle_count()).step_by(stride) {
            let corners = model.mesh.corners(t);
            let normal = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
            let Some(n) = normal.try_normalize() else { continue };
            let mut pts = [egui::Pos2::ZERO; 3];
            let mut ok = true;
            for (k, c) in corners.iter().enumerate() {
                match camera.project(viewport, *c) {
                    Some(p) => pts[k] = rect.min + egui::vec2(p.x as f32, p.y as f32),
                    None => ok = false,
                }
            }
            if !ok {
                continue;
            }
            let light = (0.25 + 0.75 * n.dot(-forward).abs()) as f32;
            let shade = |c: f32| (c * light * 255.0).clamp(0.0, 255.0) as u8;
            let colour = egui::Color32::from_rgba_unmultiplied(
                shade(model.color[0]),
                shade(model.color[1]),
                shade(model.color[2]),
                alpha,
            );
            let depth = ((corners[0] + corners[1] + corners[2]) / 3.0 - camera.eye).dot(forward);
            if model.style == ModelStyle::Wireframe {
                tris.push((depth, pts, egui::Color32::TRANSPARENT));
                painter.add(egui::Shape::closed_line(pts.to_vec(), egui::Stroke::new(0.5, colour)));
            } else {
                tris.push((depth, pts, colour));
            }
        }
    }
    tris.sort_by(|a, b| b.0.total_cmp(&a.0));
    let mut mesh = egui::Mesh::default();
    for (_, pts, colour) in tris {
        if colour == egui::Color32::TRANSPARENT {
            continue;
        }
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

/// The embedded default scene (the knee).
pub fn default_scene_models() -> anyhow::Result<Vec<crate::io::Model>> {
    anyhow::bail!("this build has no embedded default scene yet; use File ▸ Load Model")
}

/// Writes the window's scene as a session file.
pub fn save_session(app: &CutawayApp, path: &Path) -> anyhow::Result<()> {
    let _ = app;
    anyhow::bail!("{}: saving sessions is not available in this build", path.display())
}

/// Replaces the window's scene with a session file.
pub fn load_session(app: &mut CutawayApp, path: &Path) -> anyhow::Result<()> {
    let _ = app;
    anyhow::bail!("{}: opening sessions is not available in this build", path.display())
}

/// Renders the viewport's picture into a PNG.
pub fn export_image(app: &CutawayApp, path: &Path) -> anyhow::Result<()> {
    let _ = app;
    anyhow::bail!("{}: image export is not available in this build", path.display())
}

/// Writes the cut parts of every cutter into `dir`; returns the number of files written.
pub fn export_meshes(app: &CutawayApp, dir: &Path) -> anyhow::Result<usize> {
    let _ = app;
    anyhow::bail!("{}: there are no cut results to export (cut in Edit mode, then Preview)", dir.display())
}

/// Centre of the scene, for tools that need one.
pub fn scene_centre(scene: &Scene) -> DVec3 {
    let b = scene.bbox();
    if b.is_empty() { DVec3::ZERO } else { b.center() }
}
