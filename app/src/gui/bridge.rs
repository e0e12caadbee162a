//! Where the window meets the other parts of the application: the renderer (paint callback and
//! headless export), the session file, the embedded default scene, the cutter editor and the cut
//! geometry. Kept in one file so the panels never depend on those APIs directly.

use std::path::{Path, PathBuf};
use std::sync::{Arc, Weak};
use std::time::Instant;

use glam::DVec2;

use csg::{Mesh, SpatialIndex};
use cutter::{BoundedPlane, Cutter, Editor, EditorEvent, EditorSettings};

use super::app::CutawayApp;
use super::jobs::Progress;
use crate::cutaway_geometry::{self, PreviewGeometry};
use crate::render::{CutterOverlay, FrameInputs, OutputTarget, Renderer, ViewMode};
use crate::scene::{CutKind, Scene, SceneCutter, SceneModel};

/// Whether the scalpel mode exists in this build (its button is disabled otherwise).
pub const SCALPEL_AVAILABLE: bool = true;

/// Targets up to this many triangles get their spatial index built on the UI thread (a few
/// milliseconds); bigger ones in a background job with progress.
const SYNC_INDEX_TRIANGLES: usize = 150_000;

/// Scene cut kind → editor cut kind.
pub fn editor_kind(kind: CutKind) -> cutter::CutKind {
    match kind {
        CutKind::Curving => cutter::CutKind::Curving,
        CutKind::Straight => cutter::CutKind::Straight,
        CutKind::Wedge => cutter::CutKind::Wedge,
    }
}

/// Editor cut kind → scene cut kind.
pub fn scene_kind(kind: cutter::CutKind) -> CutKind {
    match kind {
        cutter::CutKind::Curving => CutKind::Curving,
        cutter::CutKind::Straight => CutKind::Straight,
        cutter::CutKind::Wedge => CutKind::Wedge,
    }
}

/// The editor working on one cutter of the scene.
struct Active {
    editor: Editor,
    /// Index into `Scene::models` of the target.
    target: usize,
    /// Index into `Scene::cutters` of the cutter being edited; `None` until the first drag made one.
    cutter: Option<usize>,
}

/// The window's cutter editing: at most one active [`Editor`] (on the selected target), a cache of
/// spatial indexes per target mesh, and the glue that mirrors the editor's cutter into
/// `Scene::cutters` so that undo, sessions, the renderer and Preview all see one truth.
#[derive(Default)]
pub struct EditorSlot {
    active: Option<Active>,
    /// Spatial indexes by target mesh (weak: a replaced mesh invalidates its entry). Only the
    /// index of the target being edited is kept (see [`EditorSlot::ensure`]), and one built in
    /// the background for the next target: an index per model ever edited would add up to
    /// several times the scene.
    indexes: Vec<(Weak<Mesh>, Arc<SpatialIndex>)>,
    /// The cursor the editor asked for at the last event.
    pub cursor: cutter::CursorHint,
    /// Where the editor asked the real cursor to be put at the last event (viewport pixels).
    pub warp: Option<DVec2>,
}

impl EditorSlot {
    /// What the active editor's last action refused or corrected (see [`Editor::note`]).
    pub fn note(&self) -> Option<&str> {
        self.active.as_ref().and_then(|a| a.editor.note())
    }

    /// The cached index of `mesh`, if built.
    pub fn index_for(&self, mesh: &Arc<Mesh>) -> Option<Arc<SpatialIndex>> {
        self.indexes
            .iter()
            .find(|(w, _)| w.upgrade().is_some_and(|m| Arc::ptr_eq(&m, mesh)))
            .map(|(_, i)| i.clone())
    }

    /// Stores an index built by a background job.
    pub fn store_index(&mut self, mesh: Weak<Mesh>, index: Arc<SpatialIndex>) {
        self.indexes.retain(|(w, _)| w.strong_count() > 0);
        self.indexes.push((mesh, index));
    }

    /// The model the active editor works on.
    pub fn target(&self) -> Option<usize> {
        self.active.as_ref().map(|a| a.target)
    }

    /// Index into `Scene::cutters` of the cutter being edited.
    pub fn active_cutter(&self) -> Option<usize> {
        self.active.as_ref().and_then(|a| a.cutter)
    }

    /// Highlighted plane of the active cutter (selected, else hovered).
    pub fn highlighted_plane(&self) -> Option<usize> {
        let a = self.active.as_ref()?;
        a.editor.selected_plane().or(a.editor.hovered_plane())
    }

    /// The active cutter's plane under the pointer after the last event (none: off the cutter).
    pub fn hovered_plane(&self) -> Option<usize> {
        let a = self.active.as_ref()?;
        a.editor.cutter().and(a.editor.hovered_plane())
    }

    /// The initial strip while the first drag is in progress.
    pub fn init_strip(&self) -> Option<[glam::DVec3; 4]> {
        self.active.as_ref()?.editor.init_strip()
    }

    /// Stops editing the current cutter (it stays in the scene); the next drag starts a new one.
    pub fn finish(&mut self) {
        self.active = None;
    }

    /// Makes an editor for `target` ready when its index exists. Returns `false` when it is not
    /// ready: the model does not exist, or its index must first be built in the background (the
    /// caller starts that job).
    pub fn ensure(
        &mut self,
        scene: &Scene,
        target: usize,
        viewport: DVec2,
        init: &super::app::CutterInit,
    ) -> bool {
        if self.active.as_ref().is_some_and(|a| a.target == target) {
            return true;
        }
        let Some(model) = scene.models.get(target) else {
            return false;
        };
        let index = match self.index_for(&model.mesh) {
            Some(index) => index,
            None if model.mesh.triangle_count() <= SYNC_INDEX_TRIANGLES => {
                let index = Arc::new(SpatialIndex::build(&model.mesh));
                self.store_index(Arc::downgrade(&model.mesh), index.clone());
                index
            }
            None => return false,
        };
        self.indexes
            .retain(|(w, _)| w.upgrade().is_some_and(|m| Arc::ptr_eq(&m, &model.mesh)));
        let settings = EditorSettings::for_scene(&scene.bbox(), scene.camera.fov_y_deg)
            .with_kind(editor_kind(init.kind))
            .with_spacing(init.spacing)
            .with_smooth(init.smooth);
        let editor = Editor::new(model.mesh.clone(), index, scene.camera, viewport, settings);
        self.active = Some(Active {
            editor,
            target,
            cutter: None,
        });
        true
    }

    /// Opens scene cutter `index` for editing (its target's index must exist or be cheap).
    pub fn edit_existing(
        &mut self,
        scene: &Scene,
        index: usize,
        viewport: DVec2,
        init: &super::app::CutterInit,
    ) -> bool {
        let Some(c) = scene.cutters.get(index) else {
            return false;
        };
        self.active = None;
        if !self.ensure(scene, c.target, viewport, init) {
            return false;
        }
        let cutter = Cutter {
            kind: editor_kind(c.kind),
            smooth: c.smooth,
            planes: c
                .planes
                .iter()
                .map(|p| BoundedPlane::from_corners(*p))
                .collect(),
        };
        let Some(active) = &mut self.active else {
            return false;
        };
        if !active.editor.set_cutter(Some(cutter)) {
            self.active = None;
            return false;
        }
        active.cutter = Some(index);
        true
    }

    /// Feeds one event to the active editor. Returns true when the scene's cutters changed.
    pub fn handle(&mut self, scene: &mut Scene, viewport: DVec2, event: EditorEvent) -> bool {
        let Some(active) = &mut self.active else {
            return false;
        };
        if !active.editor.is_dragging() {
            active.editor.set_view(scene.camera, viewport);
        }
        let response = active.editor.handle(event);
        self.cursor = response.cursor;
        self.warp = response.warp_cursor;
        if !response.changed {
            return false;
        }
        self.mirror_into(scene);
        true
    }

    /// Applies Initialization-tab settings to the active editor; true when the cutter changed.
    pub fn apply_settings(&mut self, scene: &mut Scene, init: &super::app::CutterInit) -> bool {
        let Some(active) = &mut self.active else {
            return false;
        };
        active.editor.set_kind(editor_kind(init.kind));
        active.editor.set_spacing(init.spacing);
        if active.editor.set_smooth(init.smooth) {
            self.mirror_into(scene);
            return true;
        }
        false
    }

    /// Copies the editor's cutter into `scene.cutters` (adding, updating or removing the entry).
    fn mirror_into(&mut self, scene: &mut Scene) {
        let Some(active) = &mut self.active else {
            return;
        };
        match (active.editor.cutter(), active.cutter) {
            (Some(c), Some(i)) if i < scene.cutters.len() => {
                let entry = &mut scene.cutters[i];
                entry.kind = scene_kind(c.kind);
                entry.smooth = c.smooth;
                entry.planes = c.planes.iter().map(BoundedPlane::corners).collect();
            }
            (Some(c), _) => {
                scene.cutters.push(SceneCutter {
                    target: active.target,
                    kind: scene_kind(c.kind),
                    smooth: c.smooth,
                    planes: c.planes.iter().map(BoundedPlane::corners).collect(),
                    views: Default::default(),
                });
                active.cutter = Some(scene.cutters.len() - 1);
            }
            (None, Some(i)) if i < scene.cutters.len() => {
                scene.cutters.remove(i);
                active.cutter = None;
            }
            (None, _) => active.cutter = None,
        }
    }

    /// After an undo/redo replaced the scene: make the editor show what the scene now holds.
    pub fn sync_from_scene(&mut self, scene: &Scene) {
        let Some(active) = &mut self.active else {
            return;
        };
        if scene
            .models
            .get(active.target)
            .is_none_or(|m| !std::ptr::eq(Arc::as_ptr(&m.mesh), active.editor.target()))
        {
            self.active = None;
            return;
        }
        let wanted = active
            .cutter
            .and_then(|i| scene.cutters.get(i))
            .filter(|c| c.target == active.target);
        let current: Option<Vec<[glam::DVec3; 4]>> = active
            .editor
            .cutter()
            .map(|c| c.planes.iter().map(BoundedPlane::corners).collect());
        match wanted {
            Some(c) if current.as_ref() != Some(&c.planes) => {
                let cutter = Cutter {
                    kind: editor_kind(c.kind),
                    smooth: c.smooth,
                    planes: c
                        .planes
                        .iter()
                        .map(|p| BoundedPlane::from_corners(*p))
                        .collect(),
                };
                if !active.editor.set_cutter(Some(cutter)) {
                    self.active = None;
                }
            }
            Some(_) => {}
            None => {
                // The cutter is gone (its creation was undone): a fresh start on the same target.
                active.editor.set_cutter(None);
                active.cutter = None;
            }
        }
    }

    /// Number of cutters the editor has made or opened (for the status line, see `Scene::cutters`).
    pub fn is_active(&self) -> bool {
        self.active.is_some()
    }

    /// The events the active editor has handled (for gesture recording).
    pub fn editor_settings(&self) -> Option<EditorSettings> {
        self.active.as_ref().map(|a| *a.editor.settings())
    }
}

/// Builds the spatial index of a target mesh in a worker.
pub fn build_index(
    mesh: &Arc<Mesh>,
    progress: &Progress,
) -> anyhow::Result<(Weak<Mesh>, Arc<SpatialIndex>)> {
    progress.set_message(format!(
        "{} triangles",
        super::status_bar::grouped(mesh.triangle_count())
    ));
    let index = Arc::new(SpatialIndex::build(mesh));
    progress.check()?;
    Ok((Arc::downgrade(mesh), index))
}

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

/// What the renderer draws for the window's current state.
pub fn frame_inputs(app: &CutawayApp, size: [u32; 2]) -> FrameInputs {
    use super::app::Mode;
    // Camera and Scalpel draw the cut (without the removed-piece views) as Preview does.
    let cut = match app.mode {
        Mode::Camera | Mode::Scalpel => super::cut_view::cut_without_views(app),
        Mode::Preview => app.viewport.preview.clone(),
        Mode::Edit => None,
    };
    let mode = match app.mode {
        Mode::Edit => ViewMode::Edit,
        Mode::Preview => ViewMode::Preview,
        Mode::Camera | Mode::Scalpel if cut.is_some() => ViewMode::Preview,
        Mode::Camera | Mode::Scalpel => ViewMode::Camera,
    };
    let mut inputs = FrameInputs::new(app.scene.clone(), size, mode);
    inputs.preview = cut;
    super::cut_view::highlight_selection(app, &mut inputs.scene);
    if app.mode == Mode::Edit && app.viewport.live.enabled && !app.scene.cutters.is_empty() {
        inputs.preview = app.viewport.live.geometry();
        inputs.deltas = app.viewport.live.deltas();
    }
    if app.mode == Mode::Scalpel {
        inputs.deltas.extend(app.viewport.scalpel.delta());
    }
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
                planes: c.planes.clone(),
                surface: overlay_surface(c),
                highlighted_plane: if Some(i) == active {
                    app.viewport.editor.highlighted_plane()
                } else {
                    None
                },
                active: Some(i) == active,
            })
            .collect();
    }
    inputs
}

/// The cutter surface the overlay draws: the very mesh the boolean cuts with
/// ([`cutaway_geometry::cutter_mesh`]). A smooth cutter's surface costs a subdivision and its
/// exact check, so the surfaces of the last few cutters drawn are kept between frames.
fn overlay_surface(cutter: &SceneCutter) -> Arc<Mesh> {
    type Key = (crate::scene::CutKind, bool, Vec<crate::scene::CutterPlane>);
    thread_local! {
        static SURFACES: std::cell::RefCell<std::collections::VecDeque<(Key, Arc<Mesh>)>> =
            Default::default();
    }
    let key: Key = (cutter.kind, cutter.smooth, cutter.planes.clone());
    SURFACES.with(|cache| {
        let mut cache = cache.borrow_mut();
        if let Some((_, mesh)) = cache.iter().find(|(k, _)| *k == key) {
            return mesh.clone();
        }
        let mesh = Arc::new(cutaway_geometry::cutter_mesh(cutter));
        if cache.len() >= 8 {
            cache.pop_front();
        }
        cache.push_back((key, mesh.clone()));
        mesh
    })
}

/// Draws the scene with the GPU renderer into `rect`; false when no renderer is installed.
pub fn paint_scene(ui: &mut egui::Ui, rect: egui::Rect, app: &CutawayApp) -> bool {
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

/// An embedded example scene by name. Models keep the virtual `assets/<scene>/<part>.ply`
/// source unless the source tree's copy exists, whose absolute path is used instead so that a
/// session saved from the example opens anywhere on this machine.
pub fn example_scene_models(
    name: &str,
    progress: &Progress,
) -> anyhow::Result<Vec<crate::io::Model>> {
    progress.set_message(name.to_string());
    let mut models = if name == crate::default_anatomy::NAME {
        crate::default_anatomy::load()?
    } else {
        let scene = crate::assets::scene(name)
            .ok_or_else(|| anyhow::anyhow!("{name}: no such example scene"))?;
        crate::assets::load_scene_structures(scene)?
    };
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    for model in &mut models {
        let on_disk = root.join(&model.source);
        if on_disk.is_file()
            && let Ok(absolute) = std::fs::canonicalize(&on_disk)
        {
            model.source = absolute;
        }
    }
    Ok(models)
}

/// Writes the window's scene as a session file (atomic).
pub fn save_session(app: &CutawayApp, path: &Path) -> anyhow::Result<()> {
    crate::session::save(path, &app.scene)
}

/// Reads a session (models included) in a worker.
pub fn load_session(path: &Path, progress: &Progress) -> anyhow::Result<Scene> {
    progress.set_message(
        path.file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default(),
    );
    let mut files = 0u64;
    let scene = crate::session::load_with(path, |file, unit| {
        progress.check()?;
        files += 1;
        progress.set_message(
            file.file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default(),
        );
        match unit {
            crate::scene::ModelUnit::Region => crate::io::load_models(file),
            crate::scene::ModelUnit::Structure => crate::session_volumes::structures(file, &|f| {
                progress.set((f.clamp(0.0, 1.0) * 1000.0) as u64, 1000);
                !progress.is_cancelled()
            }),
        }
    })?;
    scene
        .sanity_check()
        .map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    Ok(scene)
}

/// Renders `scene` headless into a PNG at `path` (worker thread).
pub fn export_image(
    scene: &Scene,
    preview: bool,
    settings: &super::menus::ExportImageSettings,
    path: &Path,
) -> anyhow::Result<String> {
    let mut options = crate::render::RenderPngOptions::new(settings.width, settings.height);
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

/// Cuts every cutter out of its target (cutters on one model one after another, as Preview does)
/// and writes the chosen parts into `dir`; returns the files written.
pub fn export_meshes(
    scene: &Scene,
    settings: &super::menus::ExportMeshSettings,
    dir: &Path,
    progress: &Progress,
) -> anyhow::Result<Vec<PathBuf>> {
    if scene.cutters.is_empty() {
        anyhow::bail!(
            "{}: there are no cutters to export (make one in Edit mode first)",
            dir.display()
        );
    }
    std::fs::create_dir_all(dir).map_err(|e| anyhow::anyhow!("{}: {e}", dir.display()))?;
    let ext = settings.format.extension();
    let mut written = Vec::new();
    cut_each_in_turn(scene, progress, |step, model| {
        use cutaway_geometry::{SURFACE, select};
        let stem = sanitize(&format!("cutter{}_{}", step.cutter + 1, model.name));
        let tags = step.after_tags;
        for (wanted, part) in [
            (settings.kept, "kept"),
            (settings.walls, "walls"),
            (settings.removed, "removed"),
        ] {
            if !wanted {
                continue;
            }
            let mesh = match part {
                "kept" => select(step.after, |t| tags[t] == SURFACE),
                "walls" => select(step.after, |t| tags[t] != SURFACE),
                _ => step.removed.clone(),
            };
            if !mesh.triangles.is_empty() {
                let path = dir.join(format!("{stem}_{part}.{ext}"));
                crate::io::write_mesh(&path, &mesh)?;
                written.push(path);
            }
        }
        Ok(())
    })?;
    Ok(written)
}

/// Cuts every model by its cutters in turn ([`cutaway_geometry::cut_in_turn`]: each cutter cuts
/// the closed result of the ones before it, so overlapping cutters give T ∖ (K1 ∪ … ∪ Kn), with
/// no wall of one cutter left inside another). `visit(step, model)` sees every cutter's step
/// (its `after` is kept part and walls so far, closed). Returns per model the closed result (None
/// when no cutter targets it). Each cutter's kind and smoothing are honoured.
fn cut_each_in_turn(
    scene: &Scene,
    progress: &Progress,
    mut visit: impl FnMut(&cutaway_geometry::Step, &SceneModel) -> anyhow::Result<()>,
) -> anyhow::Result<Vec<Option<Arc<Mesh>>>> {
    let mut out = vec![None; scene.models.len()];
    let mut cache = cutaway_geometry::CutCache::default();
    let total = scene.cutters.len() as u64;
    let mut done = 0u64;
    for (m, model) in scene.models.iter().enumerate() {
        let cutters: Vec<(usize, &SceneCutter)> = scene
            .cutters
            .iter()
            .enumerate()
            .filter(|(_, c)| c.target == m)
            .collect();
        if cutters.is_empty() {
            continue;
        }
        progress.check()?;
        let mut failure = None;
        let sequence = cutaway_geometry::cut_in_turn(
            &mut cache,
            &model.mesh,
            &cutters,
            |_| false,
            |step| {
                if failure.is_some() {
                    return;
                }
                done += 1;
                progress.set(done, total);
                if let Err(e) = progress.check().and_then(|()| visit(step, model)) {
                    failure = Some(e);
                }
            },
        );
        if let Some(e) = failure {
            return Err(e);
        }
        out[m] = Some(sequence.closed);
    }
    Ok(out)
}

/// File-name-safe version of a model name.
fn sanitize(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// The cut parts Preview shows, computed in a worker; returns them with the wall time in ms.
pub fn compute_preview(scene: &Scene) -> (Arc<PreviewGeometry>, f64) {
    let started = Instant::now();
    let geometry = cutaway_geometry::preview_geometry(scene);
    (Arc::new(geometry), started.elapsed().as_secs_f64() * 1000.0)
}

/// "Remove All Cut Geometry": each cut model replaced by its kept part closed by the walls, so
/// later cuts reach the structures behind. Returns (model index, new mesh) pairs.
pub fn apply_all_cuts(
    scene: &Scene,
    progress: &Progress,
) -> anyhow::Result<Vec<(usize, Arc<Mesh>)>> {
    let current = cut_each_in_turn(scene, progress, |_, _| Ok(()))?;
    Ok(current
        .into_iter()
        .enumerate()
        .filter_map(|(i, m)| m.map(|m| (i, m)))
        .collect())
}

/// Preview's dependency on the scene: the cutters and their targets' meshes. When this changes,
/// the preview is recomputed.
#[derive(Clone, Debug, PartialEq)]
pub struct PreviewKey {
    cutters: Vec<SceneCutter>,
    targets: Vec<usize>,
}

impl PreviewKey {
    pub fn of(scene: &Scene) -> PreviewKey {
        PreviewKey {
            cutters: scene.cutters.clone(),
            targets: scene
                .cutters
                .iter()
                .filter_map(|c| scene.models.get(c.target))
                .map(|m| Arc::as_ptr(&m.mesh) as usize)
                .collect(),
        }
    }
}

/// At most this many triangles are drawn by the CPU fallback.
const FALLBACK_TRIANGLES: usize = 40_000;

/// A CPU preview of the scene for when no GPU renderer is available (a window on a non-wgpu
/// backend): a subsample of the visible triangles, flat-shaded with a headlight and sorted back
/// to front.
pub fn paint_fallback(painter: &egui::Painter, rect: egui::Rect, app: &CutawayApp) {
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
    let total: usize = visible.iter().map(|m| m.mesh.triangle_count()).sum();
    if total == 0 {
        return;
    }
    let stride = total.div_ceil(FALLBACK_TRIANGLES).max(1);
    let forward = camera.forward();
    let mut tris: Vec<(f64, [egui::Pos2; 3], egui::Color32)> = Vec::new();
    for model in visible {
        let alpha = to_u8(model.opacity);
        for t in (0..model.mesh.triangle_count()).step_by(stride) {
            let corners = model.mesh.corners(t);
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

#[cfg(test)]
#[path = "bridge_tests.rs"]
mod tests;
