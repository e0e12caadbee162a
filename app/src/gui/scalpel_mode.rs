//! Scalpel mode in the window (the user drags the blade over the surface): a press on
//! a model starts a stroke, every pointer move is projected onto the surface and fed to
//! [`Scalpel::step`] so the cut front follows the tool, and the release ends the stroke.
//!
//! ## One truth for the mesh
//! The scene's model mesh is what is saved, cut in Preview and undone. The [`Scalpel`] keeps its
//! own half-edge copy in the rest pose; the scene shows that pose opened by the DFFD when an
//! opening width is set. Every mesh the scalpel puts into the scene (and every detached piece)
//! marks its model [`MeshOrigin::Edited`], so Save Session writes the cut mesh instead of naming
//! the file it was loaded from (`crate::session_meshes`).
//!
//! ## Drawing a stroke in progress (a step touches only its neighbourhood)
//! Copying a 2M-triangle mesh into the scene and uploading it after every step costs the UI
//! thread about a hundred milliseconds. So during a stroke the scene keeps the mesh from before
//! it, and each step that changed something makes a [`MeshDelta`] against that mesh instead
//! ([`ScalpelSlot::delta`], drawn by the renderer over the uploaded model): the triangles the
//! stroke has touched so far, the ones it appended, and the ring around them whose normals
//! changed. The touched triangles are found from the cut itself: every triangle a step
//! rewrites uses a vertex of one of the stroke's cut segments (the split ends, or a lip copy of
//! one), or a groove floor vertex next to them, so the fans of those vertices cover them; the
//! set only grows during a stroke (a temporary tip undone at the next step is still drawn from
//! the current mesh). The release puts the whole mesh into the scene once. A stroke on a
//! wireframe model, or with an opening width different from the one the scene's mesh was shown
//! with, replaces the scene's mesh per step as before.
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
//! Each region of a file is a model of its own, so the surfaces under the touched one (muscle
//! under skin) are other models. When a groove stroke commits, the blade below each of its
//! samples is cast against the other visible models' meshes as they were before the stroke
//! (`layer_runs`), and every model it meets within the depth is cut with strokes of its own at
//! the hit points, with the depth left there (`cut_layers`), on a scalpel of its own. They go into
//! the scene with the top cut, so the stroke stays one undo step for all of them. A model whose
//! strokes the scalpel refuses keeps its mesh (the same `Arc`) and the status line says why; the
//! top cut commits all the same. "Cut layers below" in the panel turns this off.
//!
//! ## Errors
//! A step the scalpel refuses (off the mesh, non-manifold region) leaves its mesh as it was; the
//! scene is then not touched and the reason goes to the status line. The stroke goes on with the
//! next move. A loop that cannot close is discarded whole.

use std::collections::HashSet;
use std::sync::Arc;

use glam::{DVec2, DVec3};

use csg::{Mesh, PickIndex, SpatialIndex};
use cutter::Camera;
use cutter::scalpel::{OpenOptions, Scalpel, ScalpelOptions, Tool, dffd};

use super::app::CutawayApp;
use super::camera_controls;
use crate::render::delta::{self, MeshDelta, VertexFaces};
use crate::scene::{MeshOrigin, ModelStyle, Scene, SceneModel};

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
    /// within its depth (multi-layer, see `layer_runs`); off cuts only the touched surface.
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
    fn options(&self) -> ScalpelOptions {
        ScalpelOptions::default()
            .with_depth(self.depth.max(0.0))
            .with_tool(self.tool)
    }

    fn open(&self) -> OpenOptions {
        OpenOptions {
            width: self.opening.max(0.0),
            window: self.window.max(0.0),
        }
    }
}

/// A scalpel working on one model of the scene.
struct Session {
    /// Index into `Scene::models`.
    model: usize,
    scalpel: Scalpel,
    /// The mesh the scene shows for `model`, made from the scalpel's mesh.
    shown: Arc<Mesh>,
    /// `shown` before each committed stroke of this session, oldest first, with the opening it
    /// was shown with.
    before_strokes: Vec<(Arc<Mesh>, OpenOptions)>,
    /// Bumped whenever the scalpel's rest mesh changes at a stroke boundary (commit, undo).
    revision: u64,
    /// The rest mesh and its spatial index for projecting samples, with the `revision` they were
    /// built at. Splitting keeps the surface where it was, so one index serves a whole stroke.
    rest: Option<(u64, Arc<Mesh>, Arc<SpatialIndex>)>,
    /// The rest mesh's ray-pick tree (see [`PickIndex`]), with the `revision` it was built at.
    pick: Option<(u64, Arc<Mesh>, Arc<PickIndex>)>,
    /// The opening `shown` was made with (a stroke with another one redraws the whole mesh).
    shown_open: OpenOptions,
    /// The faces of each vertex of `shown`, for the deltas of a stroke; built on a thread of its
    /// own as soon as `shown` changes, so a stroke rarely waits for it.
    faces: Option<(Arc<Mesh>, FacesJob)>,
}

/// [`VertexFaces`] of a mesh, being built or built.
enum FacesJob {
    Building(std::thread::JoinHandle<VertexFaces>),
    Built(Arc<VertexFaces>),
}

impl Session {
    fn new(model: usize, mesh: &Arc<Mesh>) -> Result<Session, String> {
        let scalpel = Scalpel::new(mesh, ScalpelOptions::default()).map_err(|e| e.to_string())?;
        let mut session = Session {
            model,
            scalpel,
            shown: mesh.clone(),
            before_strokes: Vec::new(),
            revision: 0,
            rest: None,
            pick: None,
            shown_open: OpenOptions {
                width: 0.0,
                window: 0.0,
            },
            faces: None,
        };
        session.start_faces();
        Ok(session)
    }

    /// Starts building the vertex-to-face table of `shown` (when not done for it yet).
    fn start_faces(&mut self) {
        if self
            .faces
            .as_ref()
            .is_some_and(|(m, _)| Arc::ptr_eq(m, &self.shown))
        {
            return;
        }
        let mesh = self.shown.clone();
        let job = {
            let mesh = mesh.clone();
            std::thread::Builder::new()
                .name("cutaway scalpel faces".into())
                .spawn(move || VertexFaces::build(&mesh))
        };
        self.faces = Some((
            mesh.clone(),
            match job {
                Ok(handle) => FacesJob::Building(handle),
                Err(_) => FacesJob::Built(Arc::new(VertexFaces::build(&mesh))),
            },
        ));
    }

    /// The vertex-to-face table of `shown` (waits for its thread when still building).
    fn faces(&mut self) -> Arc<VertexFaces> {
        self.start_faces();
        let Some((mesh, job)) = self.faces.take() else {
            return Arc::new(VertexFaces::build(&self.shown));
        };
        let built = match job {
            FacesJob::Built(f) => f,
            FacesJob::Building(handle) => match handle.join() {
                Ok(f) => Arc::new(f),
                Err(_) => Arc::new(VertexFaces::build(&mesh)),
            },
        };
        self.faces = Some((mesh, FacesJob::Built(built.clone())));
        built
    }

    /// The rest mesh and its index (built when the rest mesh changed since the last stroke).
    fn rest(&mut self) -> (Arc<Mesh>, Arc<SpatialIndex>) {
        if let Some((revision, mesh, index)) = &self.rest
            && *revision == self.revision
        {
            return (mesh.clone(), index.clone());
        }
        let mesh = Arc::new(self.scalpel.mesh());
        let index = Arc::new(SpatialIndex::build(&mesh));
        self.rest = Some((self.revision, mesh.clone(), index.clone()));
        (mesh, index)
    }

    /// The rest mesh and its ray-pick tree (built when the rest mesh changed since the last
    /// stroke): the pointer's ray finds the stroke's samples through it.
    fn rest_pick(&mut self) -> (Arc<Mesh>, Arc<PickIndex>) {
        if let Some((revision, mesh, pick)) = &self.pick
            && *revision == self.revision
        {
            return (mesh.clone(), pick.clone());
        }
        // The same rest mesh as [`Session::rest`]'s, taken before the stroke cuts it (the layers
        // below are found from it when the stroke ends).
        let (mesh, _) = self.rest();
        let pick = Arc::new(PickIndex::build(&mesh));
        self.pick = Some((self.revision, mesh.clone(), pick.clone()));
        (mesh, pick)
    }

    /// The delta of the stroke so far against `shown` (see the module documentation). Cost:
    /// the stroke's segments, their fans and the opening's displaced vertices; never the mesh.
    fn stroke_delta(&mut self, open: &OpenOptions, stroke: &mut Stroke) -> Arc<MeshDelta> {
        let faces = self.faces();
        let base = self.shown.clone();
        let mesh = self.scalpel.dyn_mesh();
        let nb = base.triangles.len() as u32;
        let nv = base.positions.len() as u32;
        let segments = self.scalpel.segments();
        let from = stroke.segments_before.min(segments.len());
        let mut fan = Vec::new();
        let mut visit = |v: u32, touched: &mut HashSet<u32>, floors: &mut Vec<u32>| {
            if v as usize >= mesh.vertex_count() {
                return;
            }
            let mut copies = mesh.copies(v);
            copies.push(v);
            for c in copies {
                mesh.fan_into(c, &mut fan);
                for &h in &fan {
                    let t = h / 3;
                    touched.insert(t);
                    for &w in &mesh.triangles()[t as usize] {
                        if mesh.is_floor(w) {
                            floors.push(w);
                        }
                    }
                }
            }
        };
        let mut floors = Vec::new();
        for s in &segments[from..] {
            visit(s.a, &mut stroke.touched, &mut floors);
            visit(s.b, &mut stroke.touched, &mut floors);
        }
        floors.sort_unstable();
        floors.dedup();
        let mut more = Vec::new();
        for f in floors {
            visit(f, &mut stroke.touched, &mut more);
        }
        let displaced: std::collections::HashMap<u32, DVec3> = if open.width > 0.0 {
            dffd::open_displacements(&self.scalpel, open, self.scalpel.clock())
                .into_iter()
                .collect()
        } else {
            Default::default()
        };
        let position = |v: u32| {
            displaced
                .get(&v)
                .copied()
                .unwrap_or_else(|| mesh.positions()[v as usize])
        };
        // Base vertices that moved: displaced ones, and floor vertices a deeper cut lowered.
        let mut moved: Vec<u32> = displaced
            .keys()
            .chain(&stroke.base_displaced)
            .copied()
            .filter(|&v| v < nv && position(v) != base.positions[v as usize])
            .collect();
        let mut touched: Vec<u32> = stroke.touched.iter().copied().filter(|&t| t < nb).collect();
        touched.sort_unstable();
        for &t in &touched {
            for &v in &mesh.triangles()[t as usize] {
                if v < nv && position(v) != base.positions[v as usize] {
                    moved.push(v);
                }
            }
        }
        let current = |t: u32| Some(mesh.triangles()[t as usize]);
        let added = &mesh.triangles()[(nb as usize).min(mesh.triangle_count())..];
        Arc::new(delta::build(&delta::Change {
            base: &base,
            faces: &faces,
            touched: &touched,
            current: &current,
            added,
            position: &position,
            moved: &moved,
        }))
    }

    /// The mesh to show: the rest pose, opened by the DFFD at the tool's clock.
    fn display(&self, open: &OpenOptions) -> Arc<Mesh> {
        let mut mesh = self.scalpel.mesh();
        if open.width > 0.0 {
            for (v, p) in dffd::open_displacements(&self.scalpel, open, self.scalpel.clock()) {
                mesh.positions[v as usize] = p;
            }
        }
        Arc::new(mesh)
    }

    /// What identifies the scalpel's mesh between two steps (a step that leaves it changes
    /// nothing the user can see).
    fn signature(&self) -> (usize, usize, usize, [u64; 3]) {
        let m = self.scalpel.dyn_mesh();
        let last = m
            .positions()
            .last()
            .map_or([0; 3], |p| [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()]);
        (
            m.triangle_count(),
            m.vertex_count(),
            self.scalpel.segments().len(),
            last,
        )
    }
}

/// The stroke in progress.
struct Stroke {
    /// The scene before the stroke: the undo snapshot.
    before: Scene,
    /// Pixel and surface point of the press.
    press_px: DVec2,
    press_point: DVec3,
    /// Pixel of the last sample fed to the scalpel.
    last_px: DVec2,
    /// Last surface point (misses are projected onto the view plane through it).
    last_point: DVec3,
    /// The scalpel stroke has begun (the pointer moved [`START_PIXELS`] from the press).
    begun: bool,
    /// The stroke could not begin: the rest of the drag is ignored.
    failed: bool,
    signature: (usize, usize, usize, [u64; 3]),
    /// Steps replace the scene's mesh (wireframe models, a changed opening) instead of making
    /// a delta.
    whole_mesh: bool,
    /// The scalpel's segment count before the stroke (its segments are the ones after).
    segments_before: usize,
    /// The opening the scene's mesh was shown with at the press.
    open_before: OpenOptions,
    /// Vertices that opening displaced in the scene's mesh.
    base_displaced: Vec<u32>,
    /// Triangles of the scene's mesh (and appended ones) the stroke's steps touched so far.
    touched: HashSet<u32>,
    /// What the view draws for the stroke so far (delta mode).
    delta: Option<Arc<MeshDelta>>,
    /// The samples fed to the scalpel that landed on the surface, in order; `None` marks a step
    /// off the surface (it splits the strokes on the layers below).
    samples: Vec<Option<DVec3>>,
}

/// What a camera drag in Scalpel mode does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum CameraDrag {
    Orbit,
    Pan,
}

/// What ended a stroke.
#[derive(Debug)]
pub enum Released {
    /// No stroke was in progress, or it did not change the mesh.
    Nothing,
    /// The stroke changed the scene: record it for undo with this label and say `message`.
    Committed {
        before: Box<Scene>,
        label: String,
        message: String,
    },
    /// The stroke was refused and discarded (the scene is as before it).
    Failed(String),
}

/// Scalpel mode's state in the viewport.
pub struct ScalpelSlot {
    pub settings: ScalpelSettings,
    session: Option<Session>,
    stroke: Option<Stroke>,
    camera_drag: Option<CameraDrag>,
    /// The viewport in egui points at the last frame (tests aim with it).
    pub rect: egui::Rect,
    /// Summary of the last committed stroke, for the panel.
    pub last_report: Option<String>,
    /// The last step left the surface (the blade is in the air; the cut ended there).
    pub off_surface: bool,
    /// Spatial indexes of the models cut as layers below a stroke, by mesh (weak: a replaced
    /// mesh invalidates its entry). Used when the editor has none cached for the mesh.
    layer_indexes: Vec<(std::sync::Weak<Mesh>, Arc<SpatialIndex>)>,
    /// The models' ray-pick trees: which model a press starts on.
    picks: crate::scene_pick::ScenePicks,
}

impl Default for ScalpelSlot {
    fn default() -> Self {
        ScalpelSlot {
            settings: ScalpelSettings::default(),
            session: None,
            stroke: None,
            camera_drag: None,
            rect: egui::Rect::NOTHING,
            last_report: None,
            off_surface: false,
            picks: Default::default(),
            layer_indexes: Vec::new(),
        }
    }
}

impl ScalpelSlot {
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
    fn session_for(&mut self, scene: &Scene, model: usize) -> Result<&mut Session, String> {
        let mesh = scene
            .models
            .get(model)
            .map(|m| m.mesh.clone())
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
            self.session = Some(Session::new(model, &mesh)?);
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
        let point = ray.at(t);
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
        });
        Ok(Some(model))
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
            .is_none_or(|m| !Arc::ptr_eq(&m.mesh, &session.shown))
        {
            // The scene changed under the stroke (an undo while dragging): drop the stroke.
            if stroke.begun {
                session.scalpel.undo_stroke();
                if let Some(m) = stroke.before.models.get(session.model) {
                    session.shown = m.mesh.clone();
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
            stroke.begun = true;
            match session.scalpel.begin_stroke(stroke.press_point) {
                Ok(report) => stroke
                    .samples
                    .push(report.on_mesh.then_some(stroke.press_point)),
                Err(e) => {
                    stroke.failed = true;
                    return Err(e.to_string());
                }
            }
        }
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
        if !stroke.whole_mesh {
            stroke.delta = Some(session.stroke_delta(&open, stroke));
            return Ok(true);
        }
        let shown = session.display(&open);
        session.shown = shown.clone();
        session.shown_open = open;
        if let Some(m) = scene.models.get_mut(session.model) {
            m.replace_mesh(shown);
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

    /// [`ScalpelSlot::release`], taking the spatial index of a model cut as a layer below the
    /// stroke from `cached` when it has one (the editor's cache), else from the slot's own.
    pub fn release_with(
        &mut self,
        scene: &mut Scene,
        cached: &dyn Fn(&Arc<Mesh>) -> Option<Arc<SpatialIndex>>,
    ) -> Released {
        let Some(stroke) = self.stroke.take() else {
            return Released::Nothing;
        };
        let Some(session) = self.session.as_mut() else {
            return Released::Nothing;
        };
        if !stroke.begun || stroke.failed || !session.scalpel.in_stroke() {
            return Released::Nothing;
        }
        let model = session.model;
        // The touched surface before the stroke, for the rays to the layers below it.
        let (top_mesh, top_index) = session.rest();
        let before_mesh = stroke.before.models.get(model).map(|m| m.mesh.clone());
        // What the model was before the stroke, for putting it back when nothing is kept.
        let before_origin = stroke.before.models.get(model).map(|m| m.origin);
        let report = match session.scalpel.end_stroke() {
            Ok(report) => report,
            Err(e) => {
                // Discard the whole stroke: the scalpel and the scene go back to before it.
                session.scalpel.undo_stroke();
                if let (Some(m), Some(mesh)) = (scene.models.get_mut(model), before_mesh) {
                    m.mesh = mesh.clone();
                    m.origin = before_origin.unwrap_or(m.origin);
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
                m.mesh = b.clone();
                m.origin = before_origin.unwrap_or(m.origin);
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
        session.start_faces();
        let mut message = format!(
            "Scalpel: {} triangles cut, {} created",
            report.triangles_cut, report.triangles_created
        );
        let mut label = "scalpel stroke".to_string();
        if report.detached.is_empty() {
            if let Some(m) = scene.models.get_mut(model) {
                m.replace_mesh(shown);
            }
            let settings = self.settings;
            if settings.layers && settings.tool == Tool::Scalpel && settings.depth > 0.0 {
                // Only indexes of meshes the scene shows now are worth keeping (the history
                // holds old meshes alive; their indexes would pile up).
                self.layer_indexes.retain(|(w, _)| {
                    w.upgrade()
                        .is_some_and(|m| scene.models.iter().any(|s| Arc::ptr_eq(&s.mesh, &m)))
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
                if !outcome.cut.is_empty() {
                    let created: usize = outcome.cut.iter().map(|(_, r)| r.triangles_created).sum();
                    let names: Vec<&str> = outcome
                        .cut
                        .iter()
                        .filter_map(|(m, _)| scene.models.get(*m).map(|m| m.name.as_str()))
                        .collect();
                    message.push_str(&format!(
                        "; below it {} ({created} triangles created)",
                        names.join(", ")
                    ));
                }
                for (m, e) in &outcome.refused {
                    let name = scene.models.get(*m).map_or("?", |m| m.name.as_str());
                    message.push_str(&format!("; {name} below was not cut ({e})"));
                }
            }
        } else {
            let kept = without_pieces(&shown, &report.detached);
            let Some(original) = scene.models.get(model).cloned() else {
                return Released::Nothing;
            };
            scene.models[model].replace_mesh(Arc::new(kept));
            for (k, piece) in report.detached.into_iter().enumerate() {
                let mut entry = SceneModel::new(
                    format!("{} piece {}", original.name, k + 1),
                    original.source.clone(),
                    Arc::new(piece),
                    piece_colour(original.color),
                );
                entry.region = original.region;
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
            before: Box::new(stroke.before),
            label,
            message,
        }
    }

    /// Forgets the scalpel (a new scene was loaded).
    pub fn reset(&mut self) {
        self.session = None;
        self.stroke = None;
        self.camera_drag = None;
    }
}

/// The strokes on one other model below a stroke (see [`layer_runs`]).
#[derive(Clone, Debug, PartialEq)]
struct LayerRun {
    /// Index into `Scene::models`.
    model: usize,
    /// Points on that model's surface, in stroke order (at least 2).
    samples: Vec<DVec3>,
    /// Blade depth left below that surface (mean over the samples; > 0).
    depth: f64,
}

/// Multi-layer cutting in the window ("where segmented structures lie under one
/// another, the blade cuts every surface it passes through down to its depth").
///
/// `cutter::scalpel::layers` does this for the CLI, where the stacked surfaces are regions of one
/// mesh under one scalpel. In the window every region is a model of its own, so the layers are
/// the *other* models: below each sample of the stroke on the touched model, the blade is the
/// segment from the surface point down its inward normal, `depth` long. It is cast against each
/// other model's uncut mesh; the consecutive samples whose blade meets a model become a stroke
/// on that model at the hit points, with the mean depth left below them. Computed from the
/// meshes before the stroke, so the rays never meet the new groove walls.
///
/// `top_mesh` and `top_index` are the touched model's surface before the stroke; `others` are
/// the candidate models with their meshes and indexes; a `None` sample (the blade off the
/// surface) ends every run.
fn layer_runs(
    top_mesh: &Mesh,
    top_index: &SpatialIndex,
    samples: &[Option<DVec3>],
    depth: f64,
    others: &[(usize, Arc<Mesh>, Arc<SpatialIndex>)],
) -> Vec<LayerRun> {
    if depth <= 0.0 || others.is_empty() || top_mesh.triangles.is_empty() {
        return Vec::new();
    }
    // Start the rays just below the touched surface so they never hit it where they start.
    let eps = 1e-7 * top_mesh.bbox().diagonal().max(f64::MIN_POSITIVE);
    let hits = samples.iter().map(|sample| {
        let mut below: Vec<(u32, DVec3, f64)> = Vec::new();
        if let Some(q) = sample
            && let Some(cp) = top_index.closest_point(top_mesh, *q)
        {
            let n = top_mesh
                .face_normal_scaled(cp.face as usize)
                .normalize_or_zero();
            if n != DVec3::ZERO {
                let origin = cp.point - n * eps;
                for (model, mesh, index) in others {
                    if let Some(hit) = index.ray_cast(mesh, origin, -n, depth) {
                        let left = depth - hit.t - eps;
                        if left > 0.0 {
                            below.push((*model as u32, hit.point, left));
                        }
                    }
                }
            }
        }
        below
    });
    cutter::scalpel::layers::runs(hits)
        .into_iter()
        .map(|run| LayerRun {
            model: run.region as usize,
            samples: run.samples,
            depth: run.depth,
        })
        .collect()
}

/// What [`cut_layers`] did.
#[derive(Debug, Default)]
struct LayersOutcome {
    /// Models cut, with what their strokes did (summed).
    cut: Vec<(usize, cutter::scalpel::StrokeReport)>,
    /// Models the scalpel refused to cut, with why (each left exactly as it was).
    refused: Vec<(usize, String)>,
}

/// Cuts the layers below a committed stroke on `model` (see [`layer_runs`]) into the scene: each
/// model met gets its own scalpel strokes with the depth left there, opened like the top cut,
/// and becomes [`MeshOrigin::Edited`]. All of a model's strokes are kept or none: a refused one
/// leaves that model's mesh (the same `Arc`) untouched. `index_of` gives a model mesh's spatial
/// index; it is asked only for visible models whose bounds the blade reaches.
fn cut_layers(
    scene: &mut Scene,
    model: usize,
    top_mesh: &Mesh,
    top_index: &SpatialIndex,
    samples: &[Option<DVec3>],
    settings: &ScalpelSettings,
    index_of: &mut dyn FnMut(&Arc<Mesh>) -> Arc<SpatialIndex>,
) -> LayersOutcome {
    let depth = settings.depth.max(0.0);
    let points: Vec<DVec3> = samples.iter().flatten().copied().collect();
    if depth <= 0.0 || points.len() < 2 {
        return LayersOutcome::default();
    }
    // Everything the blade can reach: the samples' box grown by the depth.
    let reach = csg::Aabb::from_points(&points).expanded(depth * 1.01 + 1e-9);
    let others: Vec<(usize, Arc<Mesh>, Arc<SpatialIndex>)> = scene
        .models
        .iter()
        .enumerate()
        .filter(|(i, m)| {
            *i != model
                && m.visible
                && m.opacity > 0.0
                && !m.mesh.triangles.is_empty()
                && m.mesh.bbox().overlaps(&reach)
        })
        .map(|(i, m)| (i, m.mesh.clone(), index_of(&m.mesh)))
        .collect();
    let runs = layer_runs(top_mesh, top_index, samples, depth, &others);
    let mut outcome = LayersOutcome::default();
    let open = settings.open();
    for (target, mesh, _) in &others {
        let mine: Vec<&LayerRun> = runs.iter().filter(|r| r.model == *target).collect();
        if mine.is_empty() {
            continue;
        }
        match cut_one_layer(mesh, &mine, settings.options(), &open) {
            Ok(Some((cut, report))) => {
                if let Some(m) = scene.models.get_mut(*target) {
                    m.replace_mesh(Arc::new(cut));
                    outcome.cut.push((*target, report));
                }
            }
            Ok(None) => {}
            Err(e) => outcome.refused.push((*target, e)),
        }
    }
    outcome
}

/// One model's layer strokes on a scalpel of its own. `Ok(None)`: they changed nothing.
fn cut_one_layer(
    mesh: &Mesh,
    runs: &[&LayerRun],
    options: ScalpelOptions,
    open: &OpenOptions,
) -> Result<Option<(Mesh, cutter::scalpel::StrokeReport)>, String> {
    let mut scalpel = Scalpel::new(mesh, options).map_err(|e| e.to_string())?;
    let mut total = cutter::scalpel::StrokeReport::default();
    for run in runs {
        scalpel.set_options(options.with_depth(run.depth));
        let mut r = scalpel.begin_stroke(run.samples[0]).map(|_| ());
        for &q in &run.samples[1..] {
            r = r.and_then(|_| scalpel.step(q).map(|_| ()));
        }
        let report = r
            .and_then(|_| scalpel.end_stroke())
            .map_err(|e| e.to_string())?;
        total.triangles_cut += report.triangles_cut;
        total.triangles_created += report.triangles_created;
    }
    let mut cut = scalpel.mesh();
    if open.width > 0.0 {
        scalpel.advance_clock(open.window);
        for (v, p) in dffd::open_displacements(&scalpel, open, scalpel.clock()) {
            cut.positions[v as usize] = p;
        }
    }
    if cut.triangles == mesh.triangles && cut.positions == mesh.positions {
        return Ok(None);
    }
    Ok(Some((cut, total)))
}

/// `mesh` without the triangles of `pieces` (matched by their corner coordinates, bit for bit:
/// the pieces were copied out of this mesh), compacted.
fn without_pieces(mesh: &Mesh, pieces: &[Mesh]) -> Mesh {
    type Key = [[u64; 3]; 3];
    let key = |corners: [DVec3; 3]| -> Key {
        corners.map(|p| [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()])
    };
    let mut remove: HashSet<Key> = HashSet::new();
    for piece in pieces {
        for t in 0..piece.triangle_count() {
            remove.insert(key(piece.corners(t)));
        }
    }
    Mesh {
        positions: mesh.positions.clone(),
        triangles: (0..mesh.triangle_count())
            .filter(|&t| !remove.contains(&key(mesh.corners(t))))
            .map(|t| mesh.triangles[t])
            .collect(),
    }
    .compacted()
}

/// A lighter shade of the model's colour for a piece cut out of it.
fn piece_colour(c: [f32; 3]) -> [f32; 3] {
    c.map(|x| (x * 0.6 + 0.4).min(1.0))
}

/// Viewport input in Scalpel mode: primary drag cuts; Alt+drag or right drag orbits,
/// Shift+drag or middle drag pans, the wheel zooms (the camera stays usable while cutting).
pub fn scalpel_input(
    ui: &egui::Ui,
    response: &egui::Response,
    app: &mut CutawayApp,
    ppp: f64,
    to_px: impl Fn(egui::Pos2) -> DVec2,
) {
    app.viewport.scalpel.rect = response.rect;
    let (shift, alt) = ui.input(|i| (i.modifiers.shift, i.modifiers.alt));
    let viewport = app.viewport.size_px;

    // Camera.
    if response.drag_started_by(egui::PointerButton::Primary) && (shift || alt) {
        app.viewport.scalpel.camera_drag = Some(if shift {
            CameraDrag::Pan
        } else {
            CameraDrag::Orbit
        });
    } else if response.drag_started_by(egui::PointerButton::Middle) {
        app.viewport.scalpel.camera_drag = Some(CameraDrag::Pan);
    } else if response.drag_started_by(egui::PointerButton::Secondary) {
        app.viewport.scalpel.camera_drag = Some(CameraDrag::Orbit);
    }
    if response.dragged()
        && let Some(drag) = app.viewport.scalpel.camera_drag
    {
        let d = response.drag_delta();
        let delta = DVec2::new(d.x as f64 * ppp, d.y as f64 * ppp);
        match drag {
            CameraDrag::Orbit => camera_controls::orbit(&mut app.scene.camera, delta),
            CameraDrag::Pan => camera_controls::pan(&mut app.scene.camera, delta, viewport),
        }
    }
    if response.drag_stopped() {
        app.viewport.scalpel.camera_drag = None;
    }
    if response.hovered() {
        let notches = ui.input(|i| i.smooth_scroll_delta.y as f64 / 50.0);
        if notches != 0.0 {
            let min = app.scene.bbox().diagonal().max(1e-6) * 1e-3;
            camera_controls::zoom(&mut app.scene.camera, notches, min);
        }
    }

    // Cutting.
    let Some(pos) = ui.input(|i| i.pointer.latest_pos()) else {
        return;
    };
    let px = to_px(pos);
    let pressed = ui.input(|i| i.pointer.primary_pressed())
        && response.rect.contains(pos)
        && response.hovered()
        && !(shift || alt);
    let released = ui.input(|i| i.pointer.primary_released());
    if pressed {
        match app.viewport.scalpel.press(&app.scene, viewport, px) {
            Ok(Some(_)) => {}
            Ok(None) => app.say("Press on a model to cut it"),
            Err(e) => app.complain(&anyhow::anyhow!(e)),
        }
    } else if app.viewport.scalpel.is_cutting() {
        match app.viewport.scalpel.drag(&mut app.scene, viewport, px) {
            Ok(_) if app.viewport.scalpel.off_surface => {
                app.say("The blade left the surface: the cut ends there until it comes back");
            }
            Ok(_) => {}
            Err(e) => app.complain(&anyhow::anyhow!("{e} (the mesh is unchanged)")),
        }
    }
    if released && app.viewport.scalpel.is_cutting() {
        finish_stroke(app);
    }
    if response.hovered() {
        ui.ctx().set_cursor_icon(egui::CursorIcon::Crosshair);
    }
}

/// Ends the stroke in progress and records it for undo.
pub fn finish_stroke(app: &mut CutawayApp) {
    let editor = &app.viewport.editor;
    let released = app
        .viewport
        .scalpel
        .release_with(&mut app.scene, &|mesh| editor.index_for(mesh));
    match released {
        Released::Nothing => {}
        Released::Committed {
            before,
            label,
            message,
        } => {
            app.record(&label, *before);
            // The cutter editor's target mesh changed: it must not keep using the old one.
            app.viewport.editor.sync_from_scene(&app.scene);
            app.say(message);
        }
        Released::Failed(e) => app.complain(&anyhow::anyhow!(e)),
    }
}

/// The Scalpel panel: tool, depth and opening width of the next strokes.
pub fn scalpel_panel_ui(ui: &mut egui::Ui, app: &mut CutawayApp) {
    ui.heading("Scalpel");
    // Lengths are edited in millimetres whatever the file's unit (metre-scale bodies too).
    let unit = app.scene.unit;
    let s = &mut app.viewport.scalpel.settings;
    let mm = |ui: &mut egui::Ui, length: &mut f64, tip: &str| {
        let mut value = unit.to_mm(*length);
        let edit = egui::DragValue::new(&mut value)
            .speed(0.1)
            .range(0.0..=1000.0)
            .suffix(" mm")
            .max_decimals(2);
        if ui.add(edit).on_hover_text(tip).changed() {
            *length = unit.from_mm(value);
        }
    };
    ui.horizontal(|ui| {
        ui.label("Tool");
        ui.selectable_value(&mut s.tool, Tool::Scalpel, "Scalpel")
            .on_hover_text("An open cut along the path");
        ui.selectable_value(&mut s.tool, Tool::Loop, "Loop")
            .on_hover_text("A closed path that cuts through and detaches what it encloses");
    });
    ui.horizontal(|ui| {
        ui.label("Depth");
        let tip = "Blade depth; 0 cuts a slit, more cuts a groove with walls";
        mm(ui, &mut s.depth, tip);
    });
    ui.horizontal(|ui| {
        ui.label("Opening");
        let tip = "Width the incision opens to (DFFD), over a trailing window of the tool";
        mm(ui, &mut s.opening, tip);
    });
    ui.checkbox(&mut s.layers, "Cut layers below").on_hover_text(
        "A groove also cuts the other models the blade meets below the surface, down to its depth",
    );
    ui.label(
        egui::RichText::new(
            "Drag on a model to cut; Alt+drag or right drag orbits, Shift+drag pans",
        )
        .small()
        .weak(),
    );
    if let Some(report) = &app.viewport.scalpel.last_report {
        ui.label(egui::RichText::new(report).small());
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sphere_scene() -> Scene {
        let mut scene = super::super::app::new_scene();
        let sphere = csg::testkit::icosphere(4, 10.0);
        scene.models.push(SceneModel::new(
            "sphere",
            "sphere.obj",
            Arc::new(sphere),
            [0.9, 0.7, 0.6],
        ));
        scene.camera = scene.framing_camera();
        scene
    }

    /// The stroke in progress as the view draws it (the scene's mesh, faces hidden, plus the
    /// patch) is the scalpel's mesh as the whole-mesh update shows it: the same triangles with
    /// the same vertex positions and normals, bit for bit. Returns the patch's share of it.
    fn assert_view_is_the_cut_mesh(slot: &ScalpelSlot) -> f64 {
        use crate::render::delta::tests::{assert_same_corners, delta_corners, drawn_corners};
        let delta = slot
            .delta()
            .expect("a stroke in progress is drawn as a delta");
        let session = slot.session.as_ref().expect("a session");
        let full = session.display(&slot.settings.open());
        let vertices = crate::render::draw_data::mesh_vertices(&full);
        assert_same_corners(
            delta_corners(&delta),
            drawn_corners(&full, &vertices),
            "the view vs the cut mesh",
        );
        delta.patch.triangle_count() as f64 / full.triangle_count() as f64
    }

    /// Grooves crossing (the deeper one lowers the other's floor) and a slit opening by the
    /// DFFD: after every step the view of the stroke in progress is the cut mesh.
    #[test]
    fn the_view_of_a_stroke_in_progress_is_the_cut_mesh_step_by_step() {
        let mut scene = sphere_scene();
        scene.models[0].replace_mesh(Arc::new(csg::testkit::icosphere(5, 10.0)));
        let viewport = DVec2::new(800.0, 600.0);
        let mut slot = ScalpelSlot::default();
        let drag = |slot: &mut ScalpelSlot, scene: &mut Scene, px: &[DVec2]| {
            assert_eq!(slot.press(scene, viewport, px[0]), Ok(Some(0)));
            let mut checked = 0;
            for &p in &px[1..] {
                if slot.drag(scene, viewport, p).expect("step") {
                    let share = assert_view_is_the_cut_mesh(slot);
                    assert!(share < 0.1, "the patch is {share} of the mesh");
                    checked += 1;
                }
            }
            assert!(checked > 3, "{checked} steps drawn");
            let before = scene.models[0].mesh.clone();
            let released = slot.release(scene);
            assert!(
                matches!(released, Released::Committed { .. }),
                "{released:?}"
            );
            assert!(!Arc::ptr_eq(&before, &scene.models[0].mesh));
            assert!(slot.delta().is_none(), "no delta after the release");
        };
        slot.settings.depth = 0.4;
        drag(&mut slot, &mut scene, &across(viewport, 0.4, 0.6, 16));
        // Down across the first groove, deeper.
        slot.settings.depth = 0.8;
        let down: Vec<DVec2> = (0..=16)
            .map(|i| DVec2::new(viewport.x * 0.5, viewport.y * (0.4 + 0.2 * i as f64 / 16.0)))
            .collect();
        drag(&mut slot, &mut scene, &down);
        // A slit that opens (the scene's mesh was shown closed: that stroke updates the whole
        // mesh), then another with the same opening, drawn as a delta.
        slot.settings.depth = 0.0;
        slot.settings.opening = 0.3;
        let slanted = |y0: f64, y1: f64| -> Vec<DVec2> {
            (0..=16)
                .map(|i| {
                    let s = i as f64 / 16.0;
                    DVec2::new(
                        viewport.x * (0.42 + 0.16 * s),
                        viewport.y * (y0 + (y1 - y0) * s),
                    )
                })
                .collect()
        };
        assert_eq!(
            slot.press(&scene, viewport, slanted(0.42, 0.47)[0]),
            Ok(Some(0))
        );
        for &p in &slanted(0.42, 0.47)[1..] {
            slot.drag(&mut scene, viewport, p).expect("step");
            assert!(
                slot.delta().is_none(),
                "a changed opening redraws the whole mesh"
            );
        }
        assert!(matches!(
            slot.release(&mut scene),
            Released::Committed { .. }
        ));
        drag(&mut slot, &mut scene, &slanted(0.55, 0.6));
        let topo = slot.validate().unwrap().expect("scalpel invariants");
        assert!(topo.manifold, "{topo:?}");
    }

    /// Pixels of a horizontal drag across the middle of the view.
    fn across(viewport: DVec2, from: f64, to: f64, steps: usize) -> Vec<DVec2> {
        (0..=steps)
            .map(|i| {
                let s = from + (to - from) * i as f64 / steps as f64;
                DVec2::new(viewport.x * s, viewport.y * 0.5)
            })
            .collect()
    }

    fn stroke(
        slot: &mut ScalpelSlot,
        scene: &mut Scene,
        viewport: DVec2,
        px: &[DVec2],
    ) -> Released {
        assert_eq!(slot.press(scene, viewport, px[0]), Ok(Some(0)));
        for &p in &px[1..] {
            if slot.drag(scene, viewport, p).expect("step") && slot.delta().is_some() {
                assert_view_is_the_cut_mesh(slot);
            }
        }
        slot.release(scene)
    }

    #[test]
    fn a_drag_across_a_sphere_cuts_a_closed_groove_step_by_step() {
        let mut scene = sphere_scene();
        let viewport = DVec2::new(800.0, 600.0);
        let original = scene.models[0].mesh.clone();
        let mut slot = ScalpelSlot::default();
        slot.settings.depth = 0.5;
        let px = across(viewport, 0.42, 0.58, 24);
        assert_eq!(slot.press(&scene, viewport, px[0]), Ok(Some(0)));
        let mut updates = 0;
        let mut counts = Vec::new();
        for &p in &px[1..] {
            if slot.drag(&mut scene, viewport, p).expect("step") {
                updates += 1;
                assert_view_is_the_cut_mesh(&slot);
            }
            counts.push(slot.delta().map_or(0, |d| d.compose().triangle_count()));
            // The scene keeps the mesh from before the stroke until the release.
            assert!(Arc::ptr_eq(&scene.models[0].mesh, &original));
        }
        // Progressive: the view's mesh grew while the pointer moved, not only at the release.
        assert!(updates > 5, "{updates} updates");
        assert!(counts[counts.len() / 2] > original.triangle_count());
        // Moving to the same pixel is no step and no update.
        let last = *px.last().unwrap();
        assert_eq!(slot.drag(&mut scene, viewport, last), Ok(false));
        let Released::Committed { before, .. } = slot.release(&mut scene) else {
            panic!("the stroke did not commit");
        };
        assert!(Arc::ptr_eq(&before.models[0].mesh, &original));
        let mesh = &scene.models[0].mesh;
        assert!(mesh.triangle_count() > original.triangle_count() + 20);
        let report = mesh.report();
        assert!(report.closed && report.manifold, "{report:?}");
        let topo = slot.validate().unwrap().expect("scalpel invariants");
        assert!(topo.closed && topo.manifold, "{topo:?}");
        // The groove is carved into the sphere: its floor lies about the depth below the surface.
        let deepest = mesh
            .positions
            .iter()
            .map(|p| p.length())
            .fold(f64::INFINITY, f64::min);
        assert!(deepest < 10.0 - 0.4, "deepest vertex at radius {deepest}");
    }

    #[test]
    fn a_drag_across_the_knee_skin_cuts_a_closed_groove() {
        let knee = crate::assets::scene("knee").expect("embedded knee");
        let models = crate::assets::load_scene(knee).expect("knee loads");
        let skin = models
            .into_iter()
            .find(|m| m.name.to_ascii_lowercase().contains("skin"))
            .expect("knee skin");
        let mut scene = super::super::app::new_scene();
        let original = Arc::new(skin.mesh);
        scene.models.push(SceneModel::new(
            skin.name,
            skin.source,
            original.clone(),
            [0.9, 0.7, 0.6],
        ));
        scene.camera = scene.framing_camera();
        let viewport = DVec2::new(800.0, 600.0);
        let mut slot = ScalpelSlot::default();
        slot.settings.depth = 2.0;
        let released = stroke(
            &mut slot,
            &mut scene,
            viewport,
            &across(viewport, 0.47, 0.53, 20),
        );
        assert!(
            matches!(released, Released::Committed { .. }),
            "{released:?}"
        );
        let mesh = &scene.models[0].mesh;
        assert!(mesh.triangle_count() > original.triangle_count());
        let report = mesh.report();
        assert!(report.closed && report.manifold, "{report:?}");
        let topo = slot.validate().unwrap().expect("scalpel invariants");
        assert!(topo.closed && topo.manifold, "{topo:?}");
    }

    #[test]
    fn undo_through_the_scene_is_followed_by_the_scalpel() {
        let mut scene = sphere_scene();
        let viewport = DVec2::new(800.0, 600.0);
        let mut slot = ScalpelSlot::default();
        slot.settings.depth = 0.0;
        let first = stroke(
            &mut slot,
            &mut scene,
            viewport,
            &across(viewport, 0.45, 0.55, 12),
        );
        let Released::Committed { before, .. } = first else {
            panic!("first stroke did not commit");
        };
        let after_first = scene.models[0].mesh.clone();
        let second = stroke(
            &mut slot,
            &mut scene,
            viewport,
            &[DVec2::new(400.0, 250.0), DVec2::new(400.0, 270.0)],
        );
        assert!(matches!(second, Released::Committed { .. }));
        // Undo the second stroke the way the window does: the scene snapshot comes back.
        scene.models[0].mesh = after_first.clone();
        // The next press follows: the scalpel undid its last stroke, so its mesh is the first
        // stroke's, bit for bit, and cutting goes on from there.
        slot.press(&scene, viewport, DVec2::new(400.0, 350.0))
            .unwrap();
        let rest = slot.session.as_ref().unwrap().scalpel.mesh();
        assert_eq!(rest.triangles, after_first.triangles);
        assert_eq!(rest.positions, after_first.positions);
        slot.release(&mut scene);
        // A scene the scalpel never made (e.g. an undo past the session): it starts over.
        scene.models[0].mesh = before.models[0].mesh.clone();
        slot.press(&scene, viewport, DVec2::new(400.0, 300.0))
            .unwrap();
        let rest = slot.session.as_ref().unwrap().scalpel.mesh();
        assert_eq!(rest.triangles, before.models[0].mesh.triangles);
    }

    #[test]
    fn a_refused_step_is_an_error_and_leaves_the_scene_alone() {
        // Two fans sharing only vertex 0 (a bow-tie): the scalpel never cuts through it.
        let mut scene = super::super::app::new_scene();
        let mesh = Arc::new(csg::testkit::bow_tie());
        scene
            .models
            .push(SceneModel::new("bowtie", "bowtie.obj", mesh, [1.0; 3]));
        scene.camera = Camera {
            eye: DVec3::new(0.0, 0.0, 20.0),
            target: DVec3::ZERO,
            up: DVec3::Y,
            fov_y_deg: 30.0,
        };
        let viewport = DVec2::new(800.0, 600.0);
        let px = |x: f64, y: f64| {
            scene
                .camera
                .project(viewport, DVec3::new(x, y, 0.0))
                .unwrap()
        };
        let (a, b, c) = (px(-2.0, 0.1), px(-1.0, 0.05), px(2.0, 0.1));
        let mut slot = ScalpelSlot::default();
        slot.settings.depth = 0.0;
        assert_eq!(slot.press(&scene, viewport, a), Ok(Some(0)));
        assert!(slot.drag(&mut scene, viewport, b).unwrap());
        let before = scene.models[0].mesh.clone();
        let shown = slot.delta().expect("the step is drawn");
        let err = slot.drag(&mut scene, viewport, c).unwrap_err();
        assert!(err.contains("non-manifold"), "{err}");
        assert!(Arc::ptr_eq(&scene.models[0].mesh, &before));
        // The view is as before the refused step, and still the scalpel's own mesh.
        assert!(Arc::ptr_eq(&slot.delta().unwrap(), &shown));
        assert_view_is_the_cut_mesh(&slot);
    }

    #[test]
    fn a_click_without_a_drag_changes_nothing() {
        let mut scene = sphere_scene();
        let viewport = DVec2::new(800.0, 600.0);
        let original = scene.models[0].mesh.clone();
        let mut slot = ScalpelSlot::default();
        slot.press(&scene, viewport, DVec2::new(400.0, 300.0))
            .unwrap();
        slot.drag(&mut scene, viewport, DVec2::new(401.0, 300.0))
            .unwrap();
        assert!(matches!(slot.release(&mut scene), Released::Nothing));
        assert!(Arc::ptr_eq(&scene.models[0].mesh, &original));
        // A press beside the model starts nothing.
        assert_eq!(slot.press(&scene, viewport, DVec2::new(3.0, 3.0)), Ok(None));
    }

    #[test]
    fn a_loop_around_a_cap_detaches_it_as_a_model() {
        let mut scene = sphere_scene();
        let viewport = DVec2::new(800.0, 600.0);
        let original = scene.models[0].mesh.clone();
        let mut slot = ScalpelSlot::default();
        slot.settings.tool = Tool::Loop;
        slot.settings.depth = 0.0;
        let centre = DVec2::new(400.0, 300.0);
        let px: Vec<DVec2> = (0..=40)
            .map(|i| {
                let a = i as f64 / 40.0 * std::f64::consts::TAU * 0.97;
                centre + DVec2::new(a.cos(), a.sin()) * 40.0
            })
            .collect();
        let released = stroke(&mut slot, &mut scene, viewport, &px);
        assert!(
            matches!(released, Released::Committed { .. }),
            "{released:?}"
        );
        assert_eq!(scene.models.len(), 2, "the piece was not added");
        let (kept, piece) = (&scene.models[0].mesh, &scene.models[1].mesh);
        assert!(piece.triangle_count() > 0);
        assert!(kept.triangle_count() > 0);
        // Nothing lost: kept + piece cover the sphere's area.
        let total = kept.area() + piece.area();
        assert!(
            (total - original.area()).abs() < 1e-6 * original.area(),
            "{total} vs {}",
            original.area()
        );
        assert!(scene.models[1].name.contains("piece"));
    }

    /// A private folder for session files.
    fn session_dir(name: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!(
            "cutaway-scalpel-session-{name}-{}",
            std::process::id()
        ));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    fn position_bits(mesh: &Mesh) -> Vec<[u64; 3]> {
        mesh.positions
            .iter()
            .map(|p| p.to_array().map(f64::to_bits))
            .collect()
    }

    #[test]
    fn a_saved_scalpel_stroke_reopens_bit_for_bit() {
        let mut scene = sphere_scene();
        let viewport = DVec2::new(800.0, 600.0);
        let mut slot = ScalpelSlot::default();
        slot.settings.depth = 0.5;
        slot.settings.opening = 0.3;
        let released = stroke(
            &mut slot,
            &mut scene,
            viewport,
            &across(viewport, 0.42, 0.58, 16),
        );
        assert!(matches!(released, Released::Committed { .. }));
        assert_eq!(scene.models[0].origin, MeshOrigin::Edited);
        // The source file does not even exist: the session must not need it.
        assert!(!scene.models[0].source.exists());
        let dir = session_dir("stroke");
        let path = dir.join("cut.json");
        crate::session::save(&path, &scene).unwrap();
        let back = crate::session::load(&path).unwrap();
        assert_eq!(back.models.len(), 1);
        let (cut, reopened) = (&scene.models[0].mesh, &back.models[0].mesh);
        assert!(reopened.triangles == cut.triangles, "triangles differ");
        assert!(
            position_bits(reopened) == position_bits(cut),
            "positions differ"
        );
        assert_eq!(back.models[0].name, scene.models[0].name);
        // A second stroke on the reopened model and a save over the same session: the new cut
        // comes back and only its mesh file is left.
        let mut scene = back;
        // A vertical drag: a cross cut.
        let down: Vec<DVec2> = (0..=12)
            .map(|i| {
                DVec2::new(
                    viewport.x * 0.47,
                    viewport.y * (0.4 + 0.2 * i as f64 / 12.0),
                )
            })
            .collect();
        let released = stroke(&mut slot, &mut scene, viewport, &down);
        assert!(matches!(released, Released::Committed { .. }));
        crate::session::save(&path, &scene).unwrap();
        let again = crate::session::load(&path).unwrap();
        let recut = &scene.models[0].mesh;
        assert!(again.models[0].mesh.triangles == recut.triangles);
        assert!(position_bits(&again.models[0].mesh) == position_bits(recut));
        assert!(recut.triangle_count() > cut.triangle_count());
        let files = std::fs::read_dir(crate::session_meshes::mesh_dir(&path))
            .unwrap()
            .count();
        assert_eq!(files, 1);
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_detached_piece_is_saved_to_its_own_file_and_reopens_as_its_own_model() {
        let mut scene = sphere_scene();
        let viewport = DVec2::new(800.0, 600.0);
        let mut slot = ScalpelSlot::default();
        slot.settings.tool = Tool::Loop;
        slot.settings.depth = 0.0;
        let centre = DVec2::new(400.0, 300.0);
        let px: Vec<DVec2> = (0..=40)
            .map(|i| {
                let a = i as f64 / 40.0 * std::f64::consts::TAU * 0.97;
                centre + DVec2::new(a.cos(), a.sin()) * 40.0
            })
            .collect();
        let released = stroke(&mut slot, &mut scene, viewport, &px);
        assert!(matches!(released, Released::Committed { .. }));
        assert_eq!(scene.models.len(), 2);
        assert_eq!(scene.models[1].origin, MeshOrigin::Edited);
        let dir = session_dir("piece");
        let path = dir.join("loop.json");
        crate::session::save(&path, &scene).unwrap();
        let file = crate::session::parse(&std::fs::read_to_string(&path).unwrap()).unwrap();
        assert!(file.models.iter().all(|m| m.exact && m.region == Some(0)));
        assert_ne!(file.models[0].path, file.models[1].path);
        let back = crate::session::load(&path).unwrap();
        assert_eq!(back.models.len(), 2);
        for (a, b) in scene.models.iter().zip(&back.models) {
            assert_eq!(a.name, b.name);
            assert!(
                a.mesh.triangles == b.mesh.triangles,
                "{}: triangles differ",
                a.name
            );
            assert!(
                position_bits(&a.mesh) == position_bits(&b.mesh),
                "{}",
                a.name
            );
        }
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// Remove All Cut Geometry in the window replaces the cut model's mesh: the model is marked
    /// edited, and Save Session writes the cut mesh, which the session then reopens.
    #[test]
    fn the_window_saves_the_mesh_left_by_remove_all_cut_geometry() {
        use egui_kittest::Harness;

        let dir = session_dir("remove-all");
        let cube = dir.join("cube.ply");
        crate::io::write_mesh(
            &cube,
            &super::super::app::box_mesh(DVec3::ZERO, DVec3::splat(2.0)),
        )
        .unwrap();
        let start = super::super::StartOptions {
            paths: vec![cube],
            state_dir: dir.join("state"),
            offer_recovery: false,
        };
        let mut h = Harness::builder()
            .with_size(egui::vec2(1024.0, 700.0))
            .with_max_steps(10_000)
            .with_accessibility_check(false)
            .build_eframe(move |cc| super::super::CutawayApp::new(cc, start));
        let settle = |h: &mut Harness<'_, super::super::CutawayApp>| {
            let deadline = std::time::Instant::now() + std::time::Duration::from_secs(60);
            while h.state().busy() {
                assert!(std::time::Instant::now() < deadline, "a job did not finish");
                h.step();
                std::thread::sleep(std::time::Duration::from_millis(5));
            }
            h.run_steps(2);
        };
        settle(&mut h);
        assert_eq!(h.state().scene.models.len(), 1);
        assert_eq!(h.state().scene.models[0].origin, MeshOrigin::Region);
        let cutter = crate::cutaway_geometry::tests::scene_with_cube_cut(Default::default())
            .cutters
            .remove(0);
        h.state_mut().scene.cutters.push(cutter);
        let ctx = h.ctx.clone();
        h.state_mut()
            .apply(&ctx, super::super::app::Action::RemoveAllCutGeometry);
        settle(&mut h);
        let state = h.state();
        assert!(state.scene.cutters.is_empty(), "{}", state.status.message);
        assert_eq!(state.scene.models[0].origin, MeshOrigin::Edited);
        let cut = state.scene.models[0].mesh.clone();
        assert!((cut.volume() - 7.0).abs() < 1e-9, "{}", cut.volume());

        let path = dir.join("applied.json");
        h.state_mut()
            .apply(&ctx, super::super::app::Action::SaveSessionTo(path.clone()));
        let back = crate::session::load(&path).unwrap();
        assert_eq!(back.models.len(), 1);
        assert!(back.models[0].mesh.triangles == cut.triangles);
        assert!(position_bits(&back.models[0].mesh) == position_bits(&cut));
        // The window reopens it the same way.
        h.state_mut().scene = super::super::app::new_scene();
        h.state_mut()
            .apply(&ctx, super::super::app::Action::Open(vec![path.clone()]));
        settle(&mut h);
        let reopened = &h.state().scene.models;
        assert_eq!(reopened.len(), 1, "{}", h.state().status.message);
        assert_eq!(reopened[0].origin, MeshOrigin::Exact);
        assert!(reopened[0].mesh.triangles == cut.triangles);
        assert!(position_bits(&reopened[0].mesh) == position_bits(&cut));
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// Two nested spheres, each a model: skin (radius 10, model 0) over muscle (radius 9.7,
    /// model 1, tessellated differently so their vertices never line up).
    fn nested_scene() -> Scene {
        let mut scene = sphere_scene();
        scene.models.push(SceneModel::new(
            "inner",
            "inner.obj",
            Arc::new(csg::testkit::icosphere(3, 9.7)),
            [0.8, 0.3, 0.3],
        ));
        scene
    }

    /// Positions of `after` that are not positions of `before` (bit for bit).
    fn new_vertices(before: &Mesh, after: &Mesh) -> Vec<DVec3> {
        let old: HashSet<[u64; 3]> = position_bits(before).into_iter().collect();
        after
            .positions
            .iter()
            .filter(|p| !old.contains(&p.to_array().map(f64::to_bits)))
            .copied()
            .collect()
    }

    /// The mesh is closed and manifold by the csg report and by the scalpel's invariants.
    fn assert_closed_and_manifold(mesh: &Mesh, what: &str) {
        let report = mesh.report();
        assert!(report.closed && report.manifold, "{what}: {report:?}");
        let scalpel = Scalpel::new(mesh, ScalpelOptions::default()).expect(what);
        let topo = cutter::scalpel::invariants::validate(scalpel.dyn_mesh())
            .unwrap_or_else(|e| panic!("{what}: {e}"));
        assert!(topo.closed && topo.manifold, "{what}: {topo:?}");
    }

    #[test]
    fn a_groove_cuts_the_model_below_within_its_depth() {
        let mut scene = nested_scene();
        let viewport = DVec2::new(800.0, 600.0);
        let (outer, inner) = (scene.models[0].mesh.clone(), scene.models[1].mesh.clone());
        let mut slot = ScalpelSlot::default();
        assert!(slot.settings.layers, "on by default");
        slot.settings.depth = 0.6;
        let released = stroke(
            &mut slot,
            &mut scene,
            viewport,
            &across(viewport, 0.42, 0.58, 24),
        );
        let Released::Committed {
            before, message, ..
        } = released
        else {
            panic!("the stroke did not commit: {released:?}");
        };
        assert!(message.contains("below it inner"), "{message}");
        assert!(Arc::ptr_eq(&before.models[1].mesh, &inner));
        let (outer_cut, inner_cut) = (&scene.models[0].mesh, &scene.models[1].mesh);
        assert!(outer_cut.triangle_count() > outer.triangle_count());
        assert!(
            inner_cut.triangle_count() > inner.triangle_count() + 10,
            "the inner sphere was not grooved: {} -> {}",
            inner.triangle_count(),
            inner_cut.triangle_count()
        );
        assert_eq!(scene.models[1].origin, MeshOrigin::Edited);
        assert_closed_and_manifold(outer_cut, "outer");
        assert_closed_and_manifold(inner_cut, "inner");
        // The inner groove lies under the outer one: every new inner vertex is, seen from the
        // centre, next to a new outer vertex; and it goes below the inner surface, but only by
        // the depth left there (0.6 - 0.3).
        let outer_new = new_vertices(&outer, outer_cut);
        let inner_new = new_vertices(&inner, inner_cut);
        assert!(!inner_new.is_empty());
        for v in &inner_new {
            let nearest = outer_new
                .iter()
                .map(|w| v.normalize().distance(w.normalize()))
                .fold(f64::INFINITY, f64::min);
            assert!(
                nearest < 0.05,
                "inner vertex {v} is {nearest} off the stroke"
            );
        }
        let deepest = inner_new
            .iter()
            .map(|p| p.length())
            .fold(f64::INFINITY, f64::min);
        assert!(
            deepest < 9.7 - 0.15 && deepest > 9.7 - 0.45,
            "inner groove floor at radius {deepest}"
        );
        // One undo step: the snapshot from before the stroke holds both models as they were.
        scene = *before;
        assert!(Arc::ptr_eq(&scene.models[0].mesh, &outer));
        assert!(Arc::ptr_eq(&scene.models[1].mesh, &inner));
    }

    #[test]
    fn a_shallow_groove_or_layers_off_leaves_the_model_below_alone() {
        let viewport = DVec2::new(800.0, 600.0);
        for (depth, layers) in [(0.2, true), (0.6, false)] {
            let mut scene = nested_scene();
            let (outer, inner) = (scene.models[0].mesh.clone(), scene.models[1].mesh.clone());
            let inner_bits = position_bits(&inner);
            let mut slot = ScalpelSlot::default();
            slot.settings.depth = depth;
            slot.settings.layers = layers;
            let released = stroke(
                &mut slot,
                &mut scene,
                viewport,
                &across(viewport, 0.42, 0.58, 24),
            );
            assert!(
                matches!(released, Released::Committed { .. }),
                "{released:?}"
            );
            assert!(scene.models[0].mesh.triangle_count() > outer.triangle_count());
            let kept = &scene.models[1];
            assert!(
                Arc::ptr_eq(&kept.mesh, &inner),
                "depth {depth}, layers {layers}: the inner sphere changed"
            );
            assert_eq!(kept.mesh.triangles, inner.triangles);
            assert_eq!(position_bits(&kept.mesh), inner_bits);
            assert_eq!(kept.origin, MeshOrigin::Region);
        }
    }

    #[test]
    fn layer_runs_follow_the_samples_whose_blade_reaches_a_model() {
        // A plate at z = 0 (top, normal +z) over a plate at z = -1: the blade reaches the
        // lower one only with depth over 1, and a sample off the surface splits the run.
        let plate = |z: f64| {
            let mut m = super::super::app::box_mesh(
                DVec3::new(-5.0, -5.0, z - 0.1),
                DVec3::new(5.0, 5.0, z),
            );
            m = m.compacted();
            Arc::new(m)
        };
        let (top, lower) = (plate(0.0), plate(-1.0));
        let top_index = SpatialIndex::build(&top);
        let others = vec![(7, lower.clone(), Arc::new(SpatialIndex::build(&lower)))];
        let at = |x: f64| Some(DVec3::new(x, 0.5, 0.0));
        let samples = [at(-2.0), at(-1.0), at(0.0), None, at(1.0), at(2.0), at(3.0)];
        assert!(layer_runs(&top, &top_index, &samples, 0.95, &others).is_empty());
        let runs = layer_runs(&top, &top_index, &samples, 1.5, &others);
        assert_eq!(runs.len(), 2, "{runs:?}");
        assert_eq!(runs[0].model, 7);
        assert_eq!(runs[0].samples.len(), 3);
        assert_eq!(runs[1].samples.len(), 3);
        for r in &runs {
            assert!((r.depth - 0.5).abs() < 1e-6, "{}", r.depth);
            assert!(r.samples.iter().all(|p| (p.z + 1.0).abs() < 1e-9));
        }
    }

    /// A layer the scalpel refuses (a bow-tie below a plate: its stroke crosses the
    /// non-manifold vertex) is left exactly as it was and reported; a sphere below it is cut.
    #[test]
    fn a_refused_layer_is_left_alone_and_reported() {
        let mut scene = super::super::app::new_scene();
        let plate = Arc::new(
            super::super::app::box_mesh(DVec3::new(-3.0, -1.0, 0.5), DVec3::new(3.0, 1.0, 1.0))
                .compacted(),
        );
        let bow_tie = Arc::new(csg::testkit::bow_tie());
        // A big sphere whose top is at z = -0.3 under the plate.
        let mut lower = csg::testkit::icosphere(4, 10.0);
        for p in &mut lower.positions {
            p.z -= 10.3;
        }
        let lower = Arc::new(lower);
        for (name, mesh) in [("plate", &plate), ("bowtie", &bow_tie), ("lower", &lower)] {
            scene
                .models
                .push(SceneModel::new(name, "x.obj", mesh.clone(), [1.0; 3]));
        }
        let index = SpatialIndex::build(&plate);
        let samples: Vec<Option<DVec3>> = (0..=16)
            .map(|i| Some(DVec3::new(-2.0 + 0.25 * i as f64, 0.1, 1.0)))
            .collect();
        let settings = ScalpelSettings {
            depth: 1.6,
            ..Default::default()
        };
        let outcome = cut_layers(
            &mut scene,
            0,
            &plate,
            &index,
            &samples,
            &settings,
            &mut |m| Arc::new(SpatialIndex::build(m)),
        );
        assert_eq!(outcome.refused.len(), 1, "{outcome:?}");
        assert_eq!(outcome.refused[0].0, 1);
        assert!(Arc::ptr_eq(&scene.models[1].mesh, &bow_tie));
        assert_eq!(scene.models[1].origin, MeshOrigin::Region);
        assert_eq!(
            outcome.cut.iter().map(|(m, _)| *m).collect::<Vec<_>>(),
            vec![2]
        );
        assert!(scene.models[2].mesh.triangle_count() > lower.triangle_count());
        assert_closed_and_manifold(&scene.models[2].mesh, "lower sphere");
        // The touched model itself is never a layer of its own stroke.
        assert!(Arc::ptr_eq(&scene.models[0].mesh, &plate));
    }

    #[test]
    fn a_session_saves_and_reopens_both_cut_layers_bit_for_bit() {
        let mut scene = nested_scene();
        let viewport = DVec2::new(800.0, 600.0);
        let inner = scene.models[1].mesh.clone();
        let mut slot = ScalpelSlot::default();
        slot.settings.depth = 0.6;
        let released = stroke(
            &mut slot,
            &mut scene,
            viewport,
            &across(viewport, 0.42, 0.58, 16),
        );
        assert!(matches!(released, Released::Committed { .. }));
        assert!(!Arc::ptr_eq(&scene.models[1].mesh, &inner), "no layer cut");
        let dir = session_dir("layers");
        let path = dir.join("layers.json");
        crate::session::save(&path, &scene).unwrap();
        let back = crate::session::load(&path).unwrap();
        assert_eq!(back.models.len(), 2);
        for (a, b) in scene.models.iter().zip(&back.models) {
            assert_eq!(a.name, b.name);
            assert!(a.mesh.triangles == b.mesh.triangles, "{}", a.name);
            assert!(
                position_bits(&a.mesh) == position_bits(&b.mesh),
                "{}",
                a.name
            );
        }
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// The real window: two files with nested spheres open as two models; a groove across
    /// the outer one cuts both, Ctrl+Z brings both back bit for bit in one step, Ctrl+Shift+Z
    /// redoes both; with "Cut layers below" unticked only the outer one is cut.
    #[test]
    fn the_window_cuts_the_layer_below_and_undoes_both_in_one_step() {
        use egui_kittest::Harness;
        use egui_kittest::kittest::Queryable;

        let dir = session_dir("layers-gui");
        let (outer_file, inner_file) = (dir.join("outer.obj"), dir.join("inner.obj"));
        crate::io::write_mesh(&outer_file, &csg::testkit::icosphere(4, 10.0)).unwrap();
        crate::io::write_mesh(&inner_file, &csg::testkit::icosphere(3, 9.7)).unwrap();
        let start = super::super::StartOptions {
            paths: vec![outer_file, inner_file],
            state_dir: dir.join("state"),
            offer_recovery: false,
        };
        let mut h = Harness::builder()
            .with_size(egui::vec2(1280.0, 800.0))
            .with_max_steps(10_000)
            .with_accessibility_check(false)
            .build_eframe(move |cc| super::super::CutawayApp::new(cc, start));
        let deadline = std::time::Instant::now() + std::time::Duration::from_secs(60);
        while h.state().busy() {
            assert!(std::time::Instant::now() < deadline, "load did not finish");
            h.step();
            std::thread::sleep(std::time::Duration::from_millis(5));
        }
        h.run_steps(3);
        let models = &h.state().scene.models;
        assert_eq!(models.len(), 2, "{}", h.state().status.message);
        let outer_i = if models[0].mesh.bbox().diagonal() > models[1].mesh.bbox().diagonal() {
            0
        } else {
            1
        };
        let inner_i = 1 - outer_i;
        let (outer, inner) = (models[outer_i].mesh.clone(), models[inner_i].mesh.clone());
        h.query_all_by_label("Scalpel")
            .find(|n| {
                use egui_kittest::kittest::NodeT;
                n.accesskit_node().toggled().is_some()
            })
            .expect("the Scalpel mode button")
            .click();
        h.run_steps(3);
        h.state_mut().viewport.scalpel.settings.depth = 0.6;
        h.run_steps(1);
        let app = h.state();
        let rect = app.viewport.scalpel.rect;
        let ppp = h.ctx.pixels_per_point() as f64;
        let centre = app
            .scene
            .camera
            .project(app.viewport.size_px, DVec3::ZERO)
            .unwrap();
        let edge = app
            .scene
            .camera
            .project(app.viewport.size_px, DVec3::new(10.0, 0.0, 0.0))
            .unwrap();
        let radius_px = (edge - centre).length();
        let at = |dx: f64, dy: f64| {
            let px = centre + DVec2::new(dx, dy) * radius_px;
            rect.min + egui::vec2((px.x / ppp) as f32, (px.y / ppp) as f32)
        };
        let drag = |h: &mut Harness<'_, super::super::CutawayApp>, dy: f64| {
            h.hover_at(at(-0.4, dy));
            h.step();
            h.drag_at(at(-0.4, dy));
            h.step();
            for k in 1..=16 {
                h.hover_at(at(-0.4 + 0.8 * k as f64 / 16.0, dy));
                h.step();
            }
            h.drop_at(at(0.4, dy));
            h.run_steps(2);
        };
        drag(&mut h, 0.0);
        let state = h.state();
        assert!(!state.status.is_error, "{}", state.status.message);
        let (outer_cut, inner_cut) = (
            state.scene.models[outer_i].mesh.clone(),
            state.scene.models[inner_i].mesh.clone(),
        );
        assert!(outer_cut.triangle_count() > outer.triangle_count());
        assert!(
            inner_cut.triangle_count() > inner.triangle_count(),
            "the inner sphere was not cut (status: {})",
            state.status.message
        );
        assert_closed_and_manifold(&inner_cut, "inner");
        assert_eq!(state.scene.models[inner_i].origin, MeshOrigin::Edited);

        // One Ctrl+Z: both models as they were, bit for bit.
        h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
        h.run_steps(2);
        for (i, original) in [(outer_i, &outer), (inner_i, &inner)] {
            let m = &h.state().scene.models[i].mesh;
            assert_eq!(m.triangles, original.triangles, "model {i}");
            assert_eq!(position_bits(m), position_bits(original), "model {i}");
        }
        // Ctrl+Shift+Z: both cuts again.
        h.key_press_modifiers(
            egui::Modifiers::COMMAND | egui::Modifiers::SHIFT,
            egui::Key::Z,
        );
        h.run_steps(2);
        assert!(Arc::ptr_eq(
            &h.state().scene.models[outer_i].mesh,
            &outer_cut
        ));
        assert!(Arc::ptr_eq(
            &h.state().scene.models[inner_i].mesh,
            &inner_cut
        ));

        // Untick "Cut layers below": a second groove cuts the outer sphere only.
        h.get_by_label("Cut layers below").click();
        h.run_steps(2);
        assert!(!h.state().viewport.scalpel.settings.layers);
        drag(&mut h, 0.3);
        let state = h.state();
        assert!(
            state.scene.models[outer_i].mesh.triangle_count() > outer_cut.triangle_count(),
            "the second groove did not cut (status: {})",
            state.status.message
        );
        assert!(Arc::ptr_eq(&state.scene.models[inner_i].mesh, &inner_cut));
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn removing_pieces_matches_triangles_by_their_corners() {
        let cube = super::super::app::box_mesh(DVec3::ZERO, DVec3::ONE);
        let piece = Mesh {
            positions: cube.positions.clone(),
            triangles: cube.triangles[..2].to_vec(),
        }
        .compacted();
        let rest = without_pieces(&cube, &[piece]);
        assert_eq!(rest.triangle_count(), 10);
    }

    /// The real window, headless (egui_kittest, no GPU needed: the viewport falls back to its
    /// CPU preview): the Scalpel button, a drag across a sphere, Ctrl+Z and Ctrl+Shift+Z.
    #[test]
    fn the_window_cuts_with_the_scalpel_and_undoes_the_stroke() {
        use egui_kittest::Harness;
        use egui_kittest::kittest::{NodeT, Queryable};

        let dir = std::env::temp_dir().join(format!("cutaway-scalpel-gui-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let sphere = dir.join("sphere.obj");
        crate::io::write_mesh(&sphere, &csg::testkit::icosphere(4, 10.0)).unwrap();
        let start = super::super::StartOptions {
            paths: vec![sphere],
            state_dir: dir.clone(),
            offer_recovery: false,
        };
        let mut h = Harness::builder()
            .with_size(egui::vec2(1280.0, 800.0))
            .with_max_steps(10_000)
            .with_accessibility_check(false)
            .build_eframe(move |cc| super::super::CutawayApp::new(cc, start));
        let deadline = std::time::Instant::now() + std::time::Duration::from_secs(60);
        while h.state().busy() {
            assert!(std::time::Instant::now() < deadline, "load did not finish");
            h.step();
            std::thread::sleep(std::time::Duration::from_millis(5));
        }
        h.run_steps(3);
        assert_eq!(
            h.state().scene.models.len(),
            1,
            "{}",
            h.state().status.message
        );
        // A cutter on the model: a scalpel stroke and its undo must never lose it.
        let cutter = crate::scene::SceneCutter {
            target: 0,
            kind: crate::scene::CutKind::Curving,
            smooth: false,
            planes: vec![
                [
                    DVec3::new(0.0, -11.0, 1.0),
                    DVec3::new(0.0, -9.0, 1.0),
                    DVec3::new(0.0, -9.0, -1.0),
                    DVec3::new(0.0, -11.0, -1.0),
                ],
                [
                    DVec3::new(1.0, -11.0, 1.0),
                    DVec3::new(1.0, -9.0, 1.0),
                    DVec3::new(1.0, -9.0, -1.0),
                    DVec3::new(1.0, -11.0, -1.0),
                ],
            ],
            views: Default::default(),
        };
        h.state_mut().scene.cutters.push(cutter.clone());

        h.query_all_by_label("Scalpel")
            .find(|n| n.accesskit_node().toggled().is_some())
            .expect("the Scalpel mode button")
            .click();
        h.run_steps(3);
        assert_eq!(h.state().mode, super::super::Mode::Scalpel);
        let original = h.state().scene.models[0].mesh.clone();

        // Aim: a horizontal drag across the middle of the sphere as the window shows it.
        let app = h.state();
        let rect = app.viewport.scalpel.rect;
        assert!(rect.width() > 100.0, "viewport {rect:?}");
        let ppp = h.ctx.pixels_per_point() as f64;
        let centre = app
            .scene
            .camera
            .project(app.viewport.size_px, DVec3::ZERO)
            .unwrap();
        let edge = app
            .scene
            .camera
            .project(app.viewport.size_px, DVec3::new(10.0, 0.0, 0.0))
            .unwrap();
        let radius_px = (edge - centre).length();
        let at = |dx: f64| {
            let px = centre + DVec2::new(dx * radius_px, 0.0);
            rect.min + egui::vec2((px.x / ppp) as f32, (px.y / ppp) as f32)
        };
        let drag = |h: &mut Harness<'_, super::super::CutawayApp>, from: f64, to: f64| {
            h.hover_at(at(from));
            h.step();
            h.drag_at(at(from));
            h.step();
            for k in 1..=16 {
                h.hover_at(at(from + (to - from) * k as f64 / 16.0));
                h.step();
            }
            h.drop_at(at(to));
            h.run_steps(2);
        };
        drag(&mut h, -0.5, 0.5);
        let cut = h.state().scene.models[0].mesh.clone();
        assert!(
            cut.triangle_count() > original.triangle_count(),
            "no cut: {} (status: {})",
            cut.triangle_count(),
            h.state().status.message
        );
        let report = cut.report();
        assert!(report.closed && report.manifold, "{report:?}");
        let topo = h
            .state()
            .viewport
            .scalpel
            .validate()
            .unwrap()
            .expect("scalpel invariants");
        assert!(topo.closed && topo.manifold, "{topo:?}");
        assert!(!h.state().status.is_error, "{}", h.state().status.message);

        // Ctrl+Z: the exact mesh comes back, the cutter is still there.
        h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
        h.run_steps(2);
        let undone = h.state().scene.models[0].mesh.clone();
        assert_eq!(undone.positions, original.positions);
        assert_eq!(undone.triangles, original.triangles);
        assert_eq!(h.state().scene.cutters, vec![cutter.clone()]);
        // Ctrl+Shift+Z: the cut again.
        h.key_press_modifiers(
            egui::Modifiers::COMMAND | egui::Modifiers::SHIFT,
            egui::Key::Z,
        );
        h.run_steps(2);
        assert!(Arc::ptr_eq(&h.state().scene.models[0].mesh, &cut));
        // Undo again and cut elsewhere: the scalpel follows the undone scene.
        h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
        h.run_steps(2);
        drag(&mut h, -0.3, 0.4);
        let again = h.state().scene.models[0].mesh.clone();
        assert!(again.triangle_count() > original.triangle_count());
        assert!(again.report().closed);
        assert_eq!(h.state().scene.cutters, vec![cutter]);
        let _ = std::fs::remove_dir_all(&dir);
    }
}

/// A stroke in progress drawn from its delta looks exactly as the whole cut mesh did, and a
/// step uploads only what changed.
#[cfg(test)]
mod view {
    use super::*;
    use crate::gui::live_cut::view::differing_pixels;
    use crate::render::{FrameInputs, HeadlessRenderer, ViewMode};

    #[test]
    fn a_stroke_drawn_from_its_delta_looks_as_the_whole_mesh_and_uploads_little() {
        let mut renderer = match HeadlessRenderer::new() {
            Ok(r) => r,
            Err(e) => {
                println!("skipped: {e}");
                return;
            }
        };
        let mut scene = super::super::app::new_scene();
        let sphere = Arc::new(csg::testkit::icosphere(6, 10.0));
        scene.models.push(SceneModel::new(
            "sphere",
            "sphere.obj",
            sphere.clone(),
            [0.9, 0.7, 0.6],
        ));
        scene.camera = scene.framing_camera();
        let viewport = DVec2::new(320.0, 240.0);
        let frame = |scene: &Scene, delta: Option<Arc<MeshDelta>>| {
            let mut f = FrameInputs::new(scene.clone(), [320, 240], ViewMode::Camera);
            f.deterministic = true;
            f.deltas.extend(delta);
            f
        };
        let uncut = renderer.render(&frame(&scene, None)).expect("render");
        let model_bytes = renderer.last_frame_uploads().bytes;
        let mut slot = ScalpelSlot::default();
        slot.settings.depth = 0.6;
        let at = |s: f64| DVec2::new(viewport.x * s, viewport.y * 0.45);
        assert_eq!(slot.press(&scene, viewport, at(0.4)), Ok(Some(0)));
        let mut drawn = 0;
        for k in 1..=10 {
            if !slot
                .drag(&mut scene, viewport, at(0.4 + 0.02 * k as f64))
                .expect("step")
            {
                continue;
            }
            let delta = slot.delta().expect("a delta");
            let got = renderer
                .render(&frame(&scene, Some(delta)))
                .expect("render");
            let uploads = renderer.last_frame_uploads();
            // The way before: the whole mesh in the scene.
            let mut whole = scene.clone();
            let session = slot.session.as_ref().unwrap();
            whole.models[0].replace_mesh(session.display(&slot.settings.open()));
            let expected = renderer.render(&frame(&whole, None)).expect("render");
            assert_ne!(differing_pixels(&got, &uncut), 0, "step {k}: nothing cut");
            assert_eq!(
                differing_pixels(&got, &expected),
                0,
                "step {k}: the view differs"
            );
            assert!(
                uploads.bytes * 10 < model_bytes,
                "step {k}: {} bytes uploaded, the model is {model_bytes}",
                uploads.bytes
            );
            drawn += 1;
            if k == 6 {
                let _ = got.save(std::env::temp_dir().join("scalpel-delta.png"));
            }
        }
        assert!(drawn > 3, "{drawn} steps drawn");
        let cut = {
            let session = slot.session.as_ref().unwrap();
            session.display(&slot.settings.open())
        };
        assert!(matches!(
            slot.release(&mut scene),
            Released::Committed { .. }
        ));
        assert_eq!(
            *scene.models[0].mesh, *cut,
            "the release puts the cut mesh in the scene"
        );
    }
}

/// The UI thread's cost of a scalpel step on a 2M-triangle model: the step itself, what the
/// scene and the view get from it, and the renderer's frame. Prints figures; no timing
/// assertion. Heavy, so it runs only with
/// `CUTAWAY_UI_TIMINGS=1 WGPU_BACKEND=vulkan cargo test -p cutaway --lib ui_thread_cost -- --nocapture`.
#[cfg(test)]
mod timings {
    use super::*;
    use crate::render::{FrameInputs, HeadlessRenderer, ViewMode};
    use std::time::Instant;

    /// Per step, the window's way (the stroke drawn as a delta over the uploaded model) and the
    /// way before it (the whole mesh copied into the scene and uploaded), each with a renderer
    /// of its own, in the same run.
    #[test]
    fn scalpel_step_ui_thread_cost_on_two_million_triangles() {
        if std::env::var_os("CUTAWAY_UI_TIMINGS").is_none() {
            println!("skipped: set CUTAWAY_UI_TIMINGS=1 to measure");
            return;
        }
        let (mut renderer, mut whole) = match (HeadlessRenderer::new(), HeadlessRenderer::new()) {
            (Ok(a), Ok(b)) => (a, b),
            (Err(e), _) | (_, Err(e)) => {
                println!("skipped: {e}");
                return;
            }
        };
        let sphere = Arc::new(csg::testkit::geodesic_sphere(316, 100.0));
        let mut scene = super::super::app::new_scene();
        scene.models.push(SceneModel::new(
            "sphere",
            "sphere.ply",
            sphere.clone(),
            [0.9, 0.7, 0.6],
        ));
        scene.camera = scene.framing_camera();
        let viewport = DVec2::new(640.0, 400.0);
        let frame_of = |scene: &Scene, delta: Option<Arc<MeshDelta>>| {
            let mut frame = FrameInputs::new(scene.clone(), [640, 400], ViewMode::Camera);
            frame.deterministic = true;
            frame.deltas.extend(delta);
            frame
        };
        let first = renderer
            .time_prepare(&frame_of(&scene, None))
            .expect("first frame");
        whole
            .time_prepare(&frame_of(&scene, None))
            .expect("first frame");
        let mut slot = ScalpelSlot::default();
        slot.settings.depth = 1.0;
        let started = Instant::now();
        let press = DVec2::new(viewport.x * 0.4, viewport.y * 0.5);
        assert_eq!(slot.press(&scene, viewport, press), Ok(Some(0)));
        let press_ms = started.elapsed().as_secs_f64() * 1000.0;
        let mut whole_scene = scene.clone();
        let (mut step_ms, mut delta_ms, mut frame_ms, mut total_ms, mut bytes) =
            (Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new());
        let (mut copy_ms, mut whole_frame_ms, mut whole_total_ms, mut whole_bytes) =
            (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        for k in 1..=40 {
            let px = DVec2::new(viewport.x * (0.4 + 0.005 * k as f64), viewport.y * 0.5);
            let started = Instant::now();
            let changed = slot.drag(&mut scene, viewport, px).expect("step");
            let step = started.elapsed().as_secs_f64() * 1000.0;
            let frame = renderer
                .time_prepare(&frame_of(&scene, slot.delta()))
                .expect("frame");
            let uploaded = renderer.last_frame_uploads().bytes as f64 / 1e6;
            // The delta's share of the step (built again: the same state gives the same delta).
            let open = slot.settings.open();
            let (Some(session), Some(stroke)) = (slot.session.as_mut(), slot.stroke.as_mut())
            else {
                panic!("no stroke");
            };
            let started = Instant::now();
            session.stroke_delta(&open, stroke);
            let delta = started.elapsed().as_secs_f64() * 1000.0;
            // The way before: the whole mesh into the scene, uploaded.
            let started = Instant::now();
            whole_scene.models[0].replace_mesh(session.display(&open));
            let copy = started.elapsed().as_secs_f64() * 1000.0;
            let whole_frame = whole
                .time_prepare(&frame_of(&whole_scene, None))
                .expect("frame");
            if changed && k > 1 {
                step_ms.push(step);
                delta_ms.push(delta);
                frame_ms.push(frame);
                total_ms.push(step + frame);
                bytes.push(uploaded);
                copy_ms.push(copy);
                whole_frame_ms.push(whole_frame);
                whole_total_ms.push(step - delta + copy + whole_frame);
                whole_bytes.push(whole.last_frame_uploads().bytes as f64 / 1e6);
            }
        }
        let started = Instant::now();
        let released = slot.release(&mut scene);
        let release_ms = started.elapsed().as_secs_f64() * 1000.0;
        assert!(
            matches!(released, Released::Committed { .. }),
            "{released:?}"
        );
        let after_release = renderer
            .time_prepare(&frame_of(&scene, None))
            .expect("frame");
        let f = |v: &[f64]| {
            let (med, max) = crate::gui::live_cut::timings::median_max(v);
            format!("median {med:.2} (max {max:.2})")
        };
        println!(
            "scalpel on {} triangles ({}): first frame {first:.1} ms, press {press_ms:.1} ms; \
             {} steps:\n  delta: step ms {} (of which the delta {}), frame ms {}, UI thread ms \
             {}, MB uploaded {}; release {release_ms:.1} ms + frame {after_release:.1} ms\n  \
             whole: copy ms {}, frame ms {}, UI thread ms {}, MB uploaded {}",
            sphere.triangle_count(),
            renderer.adapter_name(),
            step_ms.len(),
            f(&step_ms),
            f(&delta_ms),
            f(&frame_ms),
            f(&total_ms),
            f(&bytes),
            f(&copy_ms),
            f(&whole_frame_ms),
            f(&whole_total_ms),
            f(&whole_bytes),
        );
    }
}
