//! The scalpel on a scene, without a window: what Scalpel mode does with the pointer and what
//! `cutaway scalpel` does with a path file, through the same code. A press on a model starts a
//! stroke, every pointer move is projected onto the surface and fed to [`Scalpel::step`] so
//! the cut front follows the tool, and the release ends the stroke (commits it, cuts the layers
//! below, detaches a loop's pieces). The window maps input to [`ScalpelSession::press`],
//! [`ScalpelSession::drag`] and [`ScalpelSession::release`] and draws; the command line replays
//! a path's samples through [`ScalpelSession::press_at`], [`ScalpelSession::step_to`] and the
//! same release ([`replay`]), so a stroke gives the same meshes in both, bit for bit.
//!
//! ## No stall on the first step
//! Making a scalpel for a model (its half-edge mesh, the index that finds where strokes start,
//! the rest mesh's indexes) costs time proportional to the mesh: about a second on two million
//! triangles. [`ScalpelSession::prepare`] does it on a thread of its own when a model is
//! selected in Scalpel mode; a press on a large model whose scalpel is not ready yet says so
//! instead of freezing the window. After a stroke the rest mesh's indexes are rebuilt on a
//! thread too ([`model_cut::ModelCut::index_rest`]). So every step, the first included, costs
//! only the cut itself (`cutter::scalpel::locate`).
//!
//! ## One truth for the mesh
//! The scene's model mesh is what is saved, cut in Preview and undone. The [`Scalpel`] keeps its
//! own half-edge copy in the rest pose; the scene shows that pose opened by the DFFD when an
//! opening width is set. Every mesh the scalpel puts into the scene (and every detached piece)
//! marks its model [`MeshOrigin::Edited`], so Save Session writes the cut mesh instead of naming
//! the file it was loaded from (`crate::session::meshes`).
//!
//! ## Drawing a stroke in progress (a step touches only its neighbourhood)
//! Copying a 2M-triangle mesh into the scene and uploading it after every step costs the UI
//! thread about a hundred milliseconds. So during a stroke the scene keeps the mesh from before
//! it, and each step that changed something makes a [`MeshDelta`] against that mesh instead
//! ([`ScalpelSession::delta`], drawn by the renderer over the uploaded model): the triangles the
//! stroke has touched so far, the ones it appended, and the ring around them whose normals
//! changed. The touched triangles are found from the cut itself: every triangle a step
//! rewrites uses a vertex of one of the stroke's cut segments (the split ends, or a lip copy of
//! one), or a groove floor vertex next to them, so the fans of those vertices cover them; the
//! set only grows during a stroke (a temporary tip undone at the next step is still drawn from
//! the current mesh). The release puts the whole mesh into the scene once. A stroke on a
//! wireframe model, or with an opening width different from the one the scene's mesh was shown
//! with, replaces the scene's mesh per step as before.
//!
//! ## Walls
//! Every mesh the scalpel puts into the scene carries its wall faces (groove and through-cut
//! walls, `Scalpel::wall_faces`), so the view draws them as the inside of the tissue
//! (`crate::cutting::wall_split`); a stroke's delta marks them from the scalpel's mesh the same
//! way, and a scalpel made for a mesh with marks (a reopened session) marks them walls again
//! before its first stroke. The layers below are cut with their walls kept likewise.
//!
//! ## Undo
//! A stroke is one step of the window's history: the scene before the stroke and after it
//! (meshes are shared `Arc`s, so the snapshots are cheap and cutters are never lost). Undo puts
//! the old `Arc` back, bit for bit. The scalpel follows lazily at the next press: when the scene
//! shows the mesh from before its last stroke it undoes that stroke ([`Scalpel::undo_stroke`],
//! keeping earlier openings), and when the scene shows anything else it starts again from the
//! scene's mesh.
//!
//! ## Layers below (multi-layer)
//! The other models the blade reaches below a groove are cut with it ([`below`], the one
//! strategy of `cutter::scalpel::layers`), in the same undo step. A model whose strokes the
//! scalpel refuses keeps its mesh and the status line says why; the top cut commits all the
//! same. "Cut layers below" in the panel turns this off.
//!
//! ## Errors
//! A step the scalpel refuses (off the mesh, non-manifold region) leaves its mesh as it was; the
//! scene is then not touched and the reason goes to the status line. The stroke goes on with the
//! next move. A loop that cannot close is discarded whole.

pub mod below;
pub mod model_cut;
#[cfg(test)]
mod parity_tests;
pub mod prepare;
pub mod replay;
pub mod target;
#[cfg(test)]
pub(crate) mod tests;

use std::collections::HashSet;
use std::sync::Arc;

use glam::{DVec2, DVec3};

use csg::{Mesh, SpatialIndex};
use cutter::Camera;
use cutter::scalpel::{OpenOptions, ScalpelOptions, Tool, dffd};

use crate::cutting::delta::MeshDelta;
use crate::scene::{MeshOrigin, ModelStyle, Scene, SceneModel};
use below::{cut_layers, piece_colour, without_pieces_walls};
use model_cut::{ModelCut, Stroke};
pub use prepare::Prepared;

/// A press must move this many pixels before it cuts (a click does nothing).
const START_PIXELS: f64 = 3.0;

/// The blade the next stroke uses (the panel's controls).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScalpelSettings {
    /// Open cut or closed loop that detaches what it encloses.
    pub tool: Tool,
    /// Blade depth below the surface in model units; `0` cuts a slit (the surface opens), more
    /// cuts a groove whose walls keep a closed surface closed.
    pub depth: f64,
    /// Final gap between the lips (model units) of the DFFD opening; `0` leaves the cut closed.
    pub opening: f64,
    /// Seconds of tool time over which a fresh cut opens to its full width (the trailing window).
    pub window: f64,
    /// A groove stroke also cuts the other visible models the blade meets below the surface
    /// within its depth (multi-layer, see [`below`]); off cuts only the touched surface.
    pub layers: bool,
}

impl Default for ScalpelSettings {
    fn default() -> Self {
        ScalpelSettings {
            tool: Tool::Scalpel,
            depth: 1.0,
            opening: 0.0,
            window: 0.5,
            layers: true,
        }
    }
}

impl ScalpelSettings {
    pub fn options(&self) -> ScalpelOptions {
        ScalpelOptions::default()
            .with_depth(self.depth.max(0.0))
            .with_tool(self.tool)
    }

    pub fn open(&self) -> OpenOptions {
        OpenOptions {
            width: self.opening.max(0.0),
            window: self.window.max(0.0),
        }
    }
}

#[derive(Debug)]
pub enum Released {
    /// No stroke was in progress, or it did not change the mesh.
    Nothing,
    /// The stroke changed the scene: record it for undo with this label and say `message`.
    Committed {
        before: Box<Scene>,
        label: String,
        message: String,
        /// Layers below that the scalpel refused to cut, each as "name: why" (they are left as
        /// they were; `message` says so too).
        refused: Vec<String>,
    },
    /// The stroke was refused and discarded (the scene is as before it).
    Failed(String),
}

/// The scalpel's state on a scene: the model under the knife and the stroke in progress.
pub struct ScalpelSession {
    pub settings: ScalpelSettings,
    pub(crate) session: Option<ModelCut>,
    pub(crate) stroke: Option<Stroke>,
    /// Scalpels being made off the UI thread for the models about to be cut.
    prepared: Prepared,
    /// Whether a stroke in progress is shown (the window): steps then make the delta the view
    /// draws. The command line shows nothing until the release.
    view: bool,
    /// Summary of the last committed stroke, for the panel.
    pub last_report: Option<String>,
    /// The points the last released stroke fed to the scalpel (its press point first): what a
    /// `cutaway-path/1` file replays.
    pub last_points: Vec<DVec3>,
    /// What the last committed stroke did (on the touched model and the layers below).
    pub last_stroke: Option<cutter::scalpel::StrokeReport>,
    /// The last step left the surface (the blade is in the air; the cut ended there).
    pub off_surface: bool,
    /// Spatial indexes of the models cut as layers below a stroke, by mesh (weak: a replaced
    /// mesh invalidates its entry). Used when the editor has none cached for the mesh.
    layer_indexes: Vec<(std::sync::Weak<Mesh>, Arc<SpatialIndex>)>,
    /// The models' ray-pick trees: which model a press starts on.
    picks: crate::cutting::pick::ScenePicks,
}

impl Default for ScalpelSession {
    fn default() -> Self {
        ScalpelSession {
            settings: ScalpelSettings::default(),
            session: None,
            stroke: None,
            prepared: Prepared::default(),
            view: true,
            last_report: None,
            last_stroke: None,
            last_points: Vec::new(),
            off_surface: false,
            picks: Default::default(),
            layer_indexes: Vec::new(),
        }
    }
}

impl ScalpelSession {
    /// A session with no view and no UI thread to keep free (the command line): it waits for
    /// the scalpels it makes and shows a stroke only when it is released.
    pub fn headless(settings: ScalpelSettings) -> ScalpelSession {
        ScalpelSession {
            settings,
            prepared: Prepared::waiting(),
            view: false,
            ..ScalpelSession::default()
        }
    }

    /// Starts making the scalpel for `model` off the UI thread (the window calls this for the
    /// selected model in Scalpel mode), so that pressing on it does not wait. Nothing to do
    /// while a stroke is in progress or when the scalpel for what the scene shows exists.
    pub fn prepare(&mut self, scene: &Scene, model: Option<usize>) {
        let Some((model, mesh)) =
            model.and_then(|m| scene.models.get(m).map(|s| (m, &s.model.mesh)))
        else {
            return;
        };
        if self.stroke.is_some()
            || self
                .session
                .as_ref()
                .is_some_and(|s| s.model == model && Arc::ptr_eq(&s.shown, mesh))
        {
            return;
        }
        self.prepared.start(model, mesh);
    }

    /// Makes (or waits for) the scalpel for what the scene shows of `model` now, with its rest
    /// mesh's indexes (the command line, so that no step shares the machine with their build).
    pub fn ready(&mut self, scene: &Scene, model: usize) -> Result<(), String> {
        self.session_for(scene, model)?.rest_indexes();
        Ok(())
    }

    /// Whether the scalpel for `model` is still being made (the window says so).
    pub fn preparing(&self, scene: &Scene, model: usize) -> bool {
        scene
            .models
            .get(model)
            .is_some_and(|m| self.prepared.pending(model, &m.model.mesh))
    }

    /// True while a stroke is in progress.
    pub fn is_cutting(&self) -> bool {
        self.stroke.is_some()
    }

    /// The model the scalpel works on.
    pub fn model(&self) -> Option<usize> {
        self.session.as_ref().map(|s| s.model)
    }

    /// Validates the scalpel's own mesh with its invariants (tests, debugging).
    pub fn validate(&self) -> Option<Result<cutter::scalpel::TopologyReport, String>> {
        let s = self.session.as_ref()?;
        Some(cutter::scalpel::invariants::validate(s.scalpel.dyn_mesh()).map_err(|e| e.to_string()))
    }

    /// A session on `model` whose scalpel matches what the scene shows: follows undo/redo (see
    /// the module docs), else starts over from the scene's mesh.
    fn session_for(&mut self, scene: &Scene, model: usize) -> Result<&mut ModelCut, String> {
        let mesh = scene
            .models
            .get(model)
            .map(|m| m.model.mesh.clone())
            .ok_or_else(|| format!("model {} does not exist", model + 1))?;
        let keep = match &mut self.session {
            Some(s) if s.model == model => loop {
                if Arc::ptr_eq(&s.shown, &mesh) {
                    break true;
                }
                match s.before_strokes.last() {
                    Some((previous, open)) if Arc::ptr_eq(previous, &mesh) => {
                        s.shown_open = *open;
                        s.scalpel.undo_stroke();
                        s.shown = mesh.clone();
                        s.before_strokes.pop();
                        s.revision += 1;
                    }
                    _ => break false,
                }
            },
            _ => false,
        };
        if !keep {
            self.session = None;
            let mut made = self.prepared.take(model, &mesh)?;
            // A mesh saved with its incision walls keeps them walls for the strokes to come.
            made.scalpel.mark_walls(scene.models[model].wall_faces());
            if self.view {
                made.start_faces();
            }
            self.session = Some(made);
        }
        self.session
            .as_mut()
            .ok_or_else(|| "no scalpel session".to_string())
    }

    /// Primary press at pixel `px`: picks the model under it and prepares a stroke (the cut
    /// begins once the pointer moves). Err: nothing under the pointer or the model cannot be cut.
    pub fn press(
        &mut self,
        scene: &Scene,
        viewport: DVec2,
        px: DVec2,
    ) -> Result<Option<usize>, String> {
        self.stroke = None;
        let ray = scene.camera.ray_through_pixel(viewport, px);
        let Some((model, t)) = self.picks.pick(scene, &ray) else {
            return Ok(None);
        };
        self.press_at(scene, model, ray.at(t), px)?;
        Ok(Some(model))
    }

    /// A press on `model` at its surface point `point` (at pixel `px`; the command line's
    /// presses have no pixel): prepares a stroke there, which [`ScalpelSession::begin`] starts.
    pub fn press_at(
        &mut self,
        scene: &Scene,
        model: usize,
        point: DVec3,
        px: DVec2,
    ) -> Result<(), String> {
        self.stroke = None;
        let settings = self.settings;
        let wireframe = scene.models[model].style != ModelStyle::Solid;
        let session = self.session_for(scene, model)?;
        session.scalpel.set_options(settings.options());
        let signature = session.signature();
        let open = settings.open();
        let whole_mesh = wireframe
            || ((open.width > 0.0 || session.shown_open.width > 0.0) && open != session.shown_open);
        let segments_before = session.scalpel.segments().len();
        let open_before = session.shown_open;
        // The vertices the opening displaces in the scene's mesh: a step may move them back.
        let base_displaced = if open.width > 0.0 && !whole_mesh {
            dffd::open_displacements(&session.scalpel, &open, session.scalpel.clock())
                .into_iter()
                .map(|(v, _)| v)
                .collect()
        } else {
            Vec::new()
        };
        self.stroke = Some(Stroke {
            before: scene.clone(),
            press_px: px,
            press_point: point,
            last_px: px,
            last_point: point,
            begun: false,
            failed: false,
            signature,
            whole_mesh,
            segments_before,
            open_before,
            base_displaced,
            touched: HashSet::new(),
            delta: None,
            samples: Vec::new(),
            points: Vec::new(),
        });
        Ok(())
    }

    /// Starts the stroke prepared by the press: the scalpel's first step, at the press point.
    /// Err (the rest of the drag is ignored): the scalpel refused to start there.
    pub fn begin(&mut self) -> Result<(), String> {
        let (Some(stroke), Some(session)) = (self.stroke.as_mut(), self.session.as_mut()) else {
            return Ok(());
        };
        if stroke.begun {
            return Ok(());
        }
        stroke.begun = true;
        stroke.points.push(stroke.press_point);
        match session.scalpel.begin_stroke(stroke.press_point) {
            Ok(report) => {
                stroke
                    .samples
                    .push(report.on_mesh.then_some(stroke.press_point));
                Ok(())
            }
            Err(e) => {
                stroke.failed = true;
                Err(e.to_string())
            }
        }
    }

    /// Pointer at `px` while the button is held: one scalpel step toward the surface point under
    /// it. `Ok(true)` when the scene's mesh changed; `Err` (scene untouched) when the scalpel
    /// refused the step.
    pub fn drag(&mut self, scene: &mut Scene, viewport: DVec2, px: DVec2) -> Result<bool, String> {
        let (Some(stroke), Some(session)) = (self.stroke.as_mut(), self.session.as_mut()) else {
            return Ok(false);
        };
        if stroke.failed || px == stroke.last_px {
            return Ok(false);
        }
        if scene
            .models
            .get(session.model)
            .is_none_or(|m| !Arc::ptr_eq(&m.model.mesh, &session.shown))
        {
            // The scene changed under the stroke (an undo while dragging): drop the stroke.
            if stroke.begun {
                session.scalpel.undo_stroke();
                if let Some(m) = stroke.before.models.get(session.model) {
                    session.shown = m.model.mesh.clone();
                    session.shown_open = stroke.open_before;
                }
            }
            self.stroke = None;
            return Ok(false);
        }
        if !stroke.begun {
            if px.distance(stroke.press_px) < START_PIXELS {
                return Ok(false);
            }
            self.begin()?;
        }
        let (Some(stroke), Some(session)) = (self.stroke.as_mut(), self.session.as_mut()) else {
            return Ok(false);
        };
        stroke.last_px = px;
        let camera: Camera = scene.camera;
        let ray = camera.ray_through_pixel(viewport, px);
        let (rest, index) = session.rest_pick();
        let q = match index.ray_cast(&rest, ray.origin, ray.direction, f64::INFINITY) {
            Some(hit) => hit.point,
            // Off the model: the view plane through the last point, so that the scalpel decides
            // (it reports a sample too far from the surface as off the mesh).
            None => {
                let n = camera.forward();
                let denom = ray.direction.dot(n);
                if denom.abs() < 1e-12 {
                    return Ok(false);
                }
                ray.at((stroke.last_point - ray.origin).dot(n) / denom)
            }
        };
        self.step_to(scene, q)
    }

    /// One scalpel step of the stroke in progress toward `q` (a point on or near the model's
    /// surface). `Ok(true)` when what the scene shows changed; `Err` (scene untouched) when the
    /// scalpel refused the step.
    pub fn step_to(&mut self, scene: &mut Scene, q: DVec3) -> Result<bool, String> {
        let (Some(stroke), Some(session)) = (self.stroke.as_mut(), self.session.as_mut()) else {
            return Ok(false);
        };
        if stroke.failed || !stroke.begun {
            return Ok(false);
        }
        stroke.points.push(q);
        let report = session.scalpel.step(q).map_err(|e| e.to_string())?;
        self.off_surface = !report.on_mesh;
        stroke.samples.push(report.on_mesh.then_some(q));
        stroke.last_point = q;
        let open = self.settings.open();
        let signature = session.signature();
        if signature == stroke.signature && open.width <= 0.0 {
            return Ok(false);
        }
        stroke.signature = signature;
        if !self.view {
            return Ok(true);
        }
        if !stroke.whole_mesh {
            stroke.delta = Some(session.stroke_delta(&open, stroke));
            return Ok(true);
        }
        let shown = session.display(&open);
        session.shown = shown.clone();
        session.shown_open = open;
        if let Some(m) = scene.models.get_mut(session.model) {
            m.replace_mesh_with_walls(shown, session.scalpel.wall_faces());
        }
        Ok(true)
    }

    /// What the view draws over the scene's mesh for the stroke in progress (see the module
    /// documentation); `None` outside a stroke or when its steps replace the scene's mesh.
    pub fn delta(&self) -> Option<Arc<MeshDelta>> {
        self.stroke.as_ref()?.delta.clone()
    }

    /// Release: ends the stroke. A loop's detached pieces become models of their own.
    pub fn release(&mut self, scene: &mut Scene) -> Released {
        self.release_with(scene, &|_| None)
    }

    /// [`ScalpelSession::release`], taking the spatial index of a model cut as a layer below the
    /// stroke from `cached` when it has one (the editor's cache), else from the slot's own.
    pub fn release_with(
        &mut self,
        scene: &mut Scene,
        cached: &dyn Fn(&Arc<Mesh>) -> Option<Arc<SpatialIndex>>,
    ) -> Released {
        let Some(stroke) = self.stroke.take() else {
            return Released::Nothing;
        };
        self.last_points = stroke.points.clone();
        let Some(session) = self.session.as_mut() else {
            return Released::Nothing;
        };
        if !stroke.begun || stroke.failed || !session.scalpel.in_stroke() {
            return Released::Nothing;
        }
        let model = session.model;
        // The touched surface before the stroke, for the rays to the layers below it.
        let (top_mesh, top_index) = session.rest();
        let before_mesh = stroke
            .before
            .models
            .get(model)
            .map(|m| m.model.mesh.clone());
        // What the model was before the stroke, for putting it back when nothing is kept.
        let before_origin = stroke.before.models.get(model).map(|m| m.origin);
        let before_walls = stroke
            .before
            .models
            .get(model)
            .and_then(|m| m.walls.clone());
        let report = match session.scalpel.end_stroke() {
            Ok(report) => report,
            Err(e) => {
                // Discard the whole stroke: the scalpel and the scene go back to before it.
                session.scalpel.undo_stroke();
                if let (Some(m), Some(mesh)) = (scene.models.get_mut(model), before_mesh) {
                    m.model.mesh = mesh.clone();
                    m.origin = before_origin.unwrap_or(m.origin);
                    m.walls = before_walls;
                    session.shown = mesh;
                    session.shown_open = stroke.open_before;
                }
                return Released::Failed(format!("{e}; the stroke was discarded"));
            }
        };
        let open = self.settings.open();
        if open.width > 0.0 {
            // Let the trailing window run out so the whole cut shows open.
            session.scalpel.advance_clock(open.window);
        }
        let shown = session.display(&open);
        let unchanged = before_mesh
            .as_ref()
            .is_some_and(|b| b.triangles == shown.triangles && b.positions == shown.positions);
        if unchanged {
            session.scalpel.undo_stroke();
            if let (Some(m), Some(b)) = (scene.models.get_mut(model), before_mesh) {
                m.model.mesh = b.clone();
                m.origin = before_origin.unwrap_or(m.origin);
                m.walls = before_walls;
                session.shown = b;
                session.shown_open = stroke.open_before;
            }
            return Released::Nothing;
        }
        if let Some(b) = &before_mesh {
            session.before_strokes.push((b.clone(), stroke.open_before));
        }
        session.shown = shown.clone();
        session.shown_open = open;
        session.revision += 1;
        // The next stroke projects onto the new rest mesh: index it now, off this thread.
        let rest = if open.width > 0.0 {
            Arc::new(session.scalpel.mesh())
        } else {
            shown.clone()
        };
        session.index_rest(rest);
        if self.view {
            session.start_faces();
        }
        let mut message = format!(
            "Scalpel: {} triangles cut, {} created",
            report.triangles_cut, report.triangles_created
        );
        let mut label = "scalpel stroke".to_string();
        let mut refused = Vec::new();
        self.last_stroke = Some(cutter::scalpel::StrokeReport {
            triangles_cut: report.triangles_cut,
            triangles_created: report.triangles_created,
            detached: Vec::new(),
        });
        if report.detached.is_empty() {
            if let Some(m) = scene.models.get_mut(model) {
                m.replace_mesh_with_walls(shown, session.scalpel.wall_faces());
            }
            let settings = self.settings;
            if settings.layers && settings.tool == Tool::Scalpel && settings.depth > 0.0 {
                // Only indexes of meshes the scene shows now are worth keeping (the history
                // holds old meshes alive; their indexes would pile up).
                self.layer_indexes.retain(|(w, _)| {
                    w.upgrade().is_some_and(|m| {
                        scene.models.iter().any(|s| Arc::ptr_eq(&s.model.mesh, &m))
                    })
                });
                let indexes = &mut self.layer_indexes;
                let mut index_of = |mesh: &Arc<Mesh>| -> Arc<SpatialIndex> {
                    if let Some(index) = cached(mesh) {
                        return index;
                    }
                    if let Some((_, index)) = indexes
                        .iter()
                        .find(|(w, _)| w.upgrade().is_some_and(|m| Arc::ptr_eq(&m, mesh)))
                    {
                        return index.clone();
                    }
                    let index = Arc::new(SpatialIndex::build(mesh));
                    indexes.push((Arc::downgrade(mesh), index.clone()));
                    index
                };
                let outcome = cut_layers(
                    scene,
                    model,
                    &top_mesh,
                    &top_index,
                    &stroke.samples,
                    &settings,
                    &mut index_of,
                );
                if let Some(r) = self.last_stroke.as_mut() {
                    for (_, layer) in &outcome.cut {
                        r.triangles_cut += layer.triangles_cut;
                        r.triangles_created += layer.triangles_created;
                    }
                }
                if !outcome.cut.is_empty() {
                    let created: usize = outcome.cut.iter().map(|(_, r)| r.triangles_created).sum();
                    let names: Vec<&str> = outcome
                        .cut
                        .iter()
                        .filter_map(|(m, _)| scene.models.get(*m).map(|m| m.model.name.as_str()))
                        .collect();
                    message.push_str(&format!(
                        "; below it {} ({created} triangles created)",
                        names.join(", ")
                    ));
                }
                for (m, e) in &outcome.refused {
                    let name = scene.models.get(*m).map_or("?", |m| m.model.name.as_str());
                    message.push_str(&format!("; {name} below was not cut ({e})"));
                    refused.push(format!("{name}: {e}"));
                }
            }
        } else {
            let (kept, walls) =
                without_pieces_walls(&shown, &report.detached, &session.scalpel.wall_faces());
            let Some(original) = scene.models.get(model).cloned() else {
                return Released::Nothing;
            };
            scene.models[model].replace_mesh_with_walls(Arc::new(kept), walls);
            for (k, piece) in report.detached.into_iter().enumerate() {
                let mut entry = SceneModel::new(
                    format!("{} piece {}", original.model.name, k + 1),
                    original.model.source.clone(),
                    Arc::new(piece),
                    piece_colour(original.color),
                );
                entry.model.index = original.model.index;
                // Not a region of the source file: a session saves the piece as a file of its own.
                entry.origin = MeshOrigin::Edited;
                scene.models.push(entry);
            }
            // The scalpel still holds the pieces: the next stroke starts from the scene's mesh.
            self.session = None;
            label = "scalpel loop".to_string();
            message.push_str("; the detached piece is a model of its own");
        }
        self.last_report = Some(message.clone());
        Released::Committed {
            refused,
            before: Box::new(stroke.before),
            label,
            message,
        }
    }

    /// Forgets the scalpel (a new scene was loaded).
    pub fn reset(&mut self) {
        self.session = None;
        self.stroke = None;
        self.prepared = Prepared::default();
    }
}
