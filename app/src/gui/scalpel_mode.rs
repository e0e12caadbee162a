//! Scalpel mode in the window (issue 6, "the user drags the blade over the surface"): a press on
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
//! ## Errors
//! A step the scalpel refuses (off the mesh, non-manifold region) leaves its mesh as it was; the
//! scene is then not touched and the reason goes to the status line. The stroke goes on with the
//! next move. A loop that cannot close is discarded whole.

use std::collections::HashSet;
use std::sync::Arc;

use glam::{DVec2, DVec3};

use csg::{Mesh, SpatialIndex};
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
}

impl Default for ScalpelSettings {
    fn default() -> Self {
        ScalpelSettings {
            tool: Tool::Scalpel,
            depth: 1.0,
            opening: 0.0,
            window: 0.5,
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
        let Some((model, t)) = super::viewport::pick(scene, &ray) else {
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
            if let Err(e) = session.scalpel.begin_stroke(stroke.press_point) {
                stroke.failed = true;
                return Err(e.to_string());
            }
        }
        stroke.last_px = px;
        let camera: Camera = scene.camera;
        let ray = camera.ray_through_pixel(viewport, px);
        let (rest, index) = session.rest();
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
    match app.viewport.scalpel.release(&mut app.scene) {
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
    let s = &mut app.viewport.scalpel.settings;
    ui.horizontal(|ui| {
        ui.label("Tool");
        ui.selectable_value(&mut s.tool, Tool::Scalpel, "Scalpel")
            .on_hover_text("An open cut along the path");
        ui.selectable_value(&mut s.tool, Tool::Loop, "Loop")
            .on_hover_text("A closed path that cuts through and detaches what it encloses");
    });
    ui.horizontal(|ui| {
        ui.label("Depth");
        ui.add(
            egui::DragValue::new(&mut s.depth)
                .speed(0.05)
                .range(0.0..=1000.0)
                .max_decimals(2),
        )
        .on_hover_text("Blade depth in model units; 0 cuts a slit, more cuts a groove with walls");
    });
    ui.horizontal(|ui| {
        ui.label("Opening");
        ui.add(
            egui::DragValue::new(&mut s.opening)
                .speed(0.05)
                .range(0.0..=1000.0)
                .max_decimals(2),
        )
        .on_hover_text("Width the incision opens to (DFFD), over a trailing window of the tool");
    });
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
