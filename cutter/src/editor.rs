//! The event-driven cutter editor (thesis 3.3, Edit mode): the one place that turns input events
//! into a [`Cutter`]. The GUI, `cutaway extrude` and the tests all drive it with the same
//! [`EditorEvent`]s, so the interaction metaphor is tested headless.
//!
//! ## Using it (GUI)
//! ```text
//! let settings = EditorSettings::for_scene(&all_models_bbox, camera.fov_y_deg);
//! let mut editor = Editor::new(target_mesh, target_index, camera, viewport, settings);
//! // each frame: editor.set_view(camera, viewport) if the camera moved (not while dragging),
//! // then feed pointer/wheel/key input:
//! let response = editor.handle(EditorEvent::Press { x, y, shift, ctrl });
//! if response.changed { /* re-mesh editor.cutter(), re-run the live cut */ }
//! // highlight editor.hovered_plane() / editor.selected_plane(); set the cursor from
//! // response.cursor; draw editor.init_strip() while the first drag is in progress.
//! ```
//!
//! ## What the events do (CONTRACT.md, thesis 3.3.1–3.3.3)
//! - No cutter yet: press A, drag, release B initialises one on the target ([`extrude::initialize`]);
//!   under [`Rules::Reach`] it is as deep as [`reach::default_depth`] says: it reaches the first
//!   of the [`Obstacles`] behind the target ([`Editor::set_obstacles`]; [`Editor::reach`] says
//!   why), and its boxes go along the view ([`CutDirection`]). Rolling keeps the depth.
//! - Press within [`HANDLE_PX`] of the middle third of the leading plane's projected front edge:
//!   grabs the handle; the pointer is treated as if warped to the middle of that edge (the
//!   offset is kept for the whole drag, and [`EditorResponse::warp_cursor`] tells the GUI where
//!   to put the real cursor); each move extrudes ([`extrude::extrude_move`]); Shift = straight.
//! - Press within [`VERTEX_PX`] of a plane's projected front vertex: drags that edge.
//! - Press on a plane (its quad under the pointer, or its front edge within [`HANDLE_PX`]):
//!   selects it. Press elsewhere: clears the selection.
//! - Wheel ([`Rules::Reach`], the default): over the cutter, the depth of the whole cutter
//!   (every plane × [`edits::DEPTH_FACTOR`] a notch); Alt+wheel over the cutter, the depth of the
//!   plane under the pointer (the nearest one's front edge); off the cutter nothing (the window
//!   zooms there). Under [`Rules::Delta`] (the first rules, `cutaway-gesture/1`): over the
//!   cutter, the depth of the selected (else hovered) plane; off the cutter, the depth of every
//!   plane, 2δ a notch. Ctrl+wheel rotates the selected (else hovered) plane under both.
//! - Delete with the pointer over the cutter removes the last box (down to one).
//! - Escape cancels a drag in progress.
//!
//! Every completed action (a whole drag, one wheel event, one key) is one undo step; undo and
//! redo restore whole snapshots, so an undo can never lose or corrupt a cutter. An edit that
//! would make the cutter invalid is refused and leaves it unchanged: every completed action is
//! checked with [`Cutter::validate`], the exact check the boolean makes of the very surface it
//! cuts with (smooth cutters subdivided), so the editor never hands over a cutter the exact cut
//! would refuse. Every pointer move of a drag (extrusion, wedge sweep, edge drag) is checked
//! too, before the live cut sees it: the whole cutter by [`Cutter::sanity_check`], the boxes
//! around the planes it changed by the exact check. A refused move leaves the cutter where the
//! last valid move put it and the drag goes on from there. A refusal, or smoothing that had to be
//! reduced so the smooth cutter does not fold, leaves a one-line [`Editor::note`] for the status
//! bar.

use std::sync::Arc;

use glam::{DVec2, DVec3};

use csg::{Mesh, SpatialIndex};

use crate::camera::{Camera, Ray};
use crate::cutter::{CutKind, Cutter};
use crate::edits;
use crate::events::{EditorEvent, Key};
use crate::extrude::{self, RollSettings};
use crate::geom;
use crate::reach::{Obstacles, Reach};
use crate::surface::Surface;

mod depth;
mod pick;
mod settings;

use pick::Pick;
pub use settings::{CursorHint, CutDirection, EditorResponse, EditorSettings, Rules};

/// Pick radius of the leading plane's handle (middle third of its front edge), in pixels.
pub const HANDLE_PX: f64 = 12.0;
/// Pick radius of a plane's front vertex, in pixels.
pub const VERTEX_PX: f64 = 8.0;
/// Shortest initialisation drag, in pixels.
pub const MIN_DRAG_PX: f64 = 3.0;

#[derive(Clone, Debug)]
enum Drag {
    None,
    Init {
        a: DVec2,
        b: DVec2,
    },
    Extrude {
        offset: DVec2,
        before: Cutter,
    },
    Vertex {
        plane: usize,
        top: bool,
        before: Cutter,
    },
}

/// The editor of one cutter on one target. See the module docs.
pub struct Editor {
    target: Arc<Mesh>,
    /// Built from `target`.
    index: Arc<SpatialIndex>,
    camera: Camera,
    viewport: DVec2,
    settings: EditorSettings,
    /// Always valid by [`Cutter::validate`] when present.
    cutter: Option<Cutter>,
    /// What the last completed action refused or corrected, for the status bar.
    note: Option<String>,
    /// Why a move of the drag in progress was refused (kept for the note when the drag ends).
    drag_refusal: Option<String>,
    /// Set when the last action was accepted: what smoothing gave up, worked out when
    /// [`Editor::note`] is first read (a replay that never reads it never subdivides).
    smoothing_note: Option<std::sync::OnceLock<Option<String>>>,
    undo_stack: Vec<Option<Cutter>>,
    redo_stack: Vec<Option<Cutter>>,
    drag: Drag,
    hovered: Option<usize>,
    selected: Option<usize>,
    recording: Vec<EditorEvent>,
    /// What lies behind the target (the default depth reaches the nearest of them).
    obstacles: Option<Arc<dyn Obstacles>>,
    /// Why the last cutter made here is as deep as it started.
    reach: Option<Reach>,
}

impl std::fmt::Debug for Editor {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Editor")
            .field("settings", &self.settings)
            .field("cutter", &self.cutter)
            .field("undo", &self.undo_stack.len())
            .field("redo", &self.redo_stack.len())
            .finish_non_exhaustive()
    }
}

impl Editor {
    /// An editor for `target` (the model painted on; `index` built from it), seen through
    /// `camera` in a `viewport`-pixel view.
    pub fn new(
        target: Arc<Mesh>,
        index: Arc<SpatialIndex>,
        camera: Camera,
        viewport: DVec2,
        settings: EditorSettings,
    ) -> Editor {
        Editor {
            target,
            index,
            camera,
            viewport,
            settings,
            cutter: None,
            note: None,
            drag_refusal: None,
            smoothing_note: None,
            undo_stack: Vec::new(),
            redo_stack: Vec::new(),
            drag: Drag::None,
            hovered: None,
            selected: None,
            recording: Vec::new(),
            obstacles: None,
            reach: None,
        }
    }

    /// Sets what lies behind the target: the structures a new cutter's default depth reaches
    /// for, and [`Editor::reached`] reports (none: a new cutter gets half the target's thickness).
    pub fn set_obstacles(&mut self, obstacles: Option<Arc<dyn Obstacles>>) {
        self.obstacles = obstacles;
    }

    /// Why the last cutter made by a drag started as deep as it did (under [`Rules::Reach`]).
    pub fn reach(&self) -> Option<&Reach> {
        self.reach.as_ref()
    }

    /// The current cutter, valid by [`Cutter::validate`].
    pub fn cutter(&self) -> Option<&Cutter> {
        self.cutter.as_ref()
    }

    /// What the last completed action refused or corrected (one line for the status bar), if
    /// anything.
    pub fn note(&self) -> Option<&str> {
        if self.note.is_some() {
            return self.note.as_deref();
        }
        let pending = self.smoothing_note.as_ref()?;
        pending.get_or_init(|| self.smoothing_note_now()).as_deref()
    }

    /// What smoothing the current cutter had to give up, if anything.
    fn smoothing_note_now(&self) -> Option<String> {
        self.cutter
            .as_ref()
            .and_then(|c| c.smoothing(c.levels).note())
    }

    /// Replaces the cutter (e.g. loaded from a session) as an undoable action. Refused (false)
    /// when the cutter is invalid.
    pub fn set_cutter(&mut self, cutter: Option<Cutter>) -> bool {
        if let Some(c) = &cutter
            && !self.accepts(c, "the cutter")
        {
            return false;
        }
        self.commit(cutter);
        true
    }

    /// True when `cutter` passes [`Cutter::validate`] (checked as [`Cutter::validate_boxes`],
    /// which implies it without subdividing); sets [`Editor::note`] either way (the refusal, or
    /// what smoothing had to give up, worked out when the note is first read).
    fn accepts(&mut self, cutter: &Cutter, what: &str) -> bool {
        match cutter.validate_boxes() {
            Ok(()) => {
                self.note = None;
                self.smoothing_note = Some(std::sync::OnceLock::new());
                true
            }
            Err(e) => {
                self.note = Some(format!("{what} was refused: {e}"));
                self.smoothing_note = None;
                false
            }
        }
    }

    /// The target mesh.
    pub fn target(&self) -> &Mesh {
        &self.target
    }

    /// The settings.
    pub fn settings(&self) -> &EditorSettings {
        &self.settings
    }

    /// Scene increment δ.
    pub fn delta(&self) -> f64 {
        self.settings.delta
    }

    /// The camera events are interpreted with.
    pub fn camera(&self) -> &Camera {
        &self.camera
    }

    /// The viewport size in pixels.
    pub fn viewport(&self) -> DVec2 {
        self.viewport
    }

    /// Updates camera and viewport (the GUI calls this when the view changes; a drag in progress
    /// keeps working in the new view).
    pub fn set_view(&mut self, camera: Camera, viewport: DVec2) {
        self.camera = camera;
        self.viewport = viewport;
    }

    /// Sets the cut kind. Curving/straight switch the current cutter's behaviour at once; wedge
    /// (and leaving wedge) applies from the next initialisation.
    pub fn set_kind(&mut self, kind: CutKind) {
        self.settings.kind = kind;
    }

    /// Sets the cut direction, for the current cutter (the planes it rolls from now on, and its
    /// rounding when smooth: an undoable action, checked like every edit) and the next ones.
    /// Returns true when the cutter changed.
    pub fn set_direction(&mut self, direction: CutDirection) -> bool {
        self.settings.direction = direction;
        match &self.cutter {
            Some(c) if c.direction != direction && c.kind != CutKind::Wedge => {
                let c = Cutter {
                    direction,
                    ..c.clone()
                };
                if !self.accepts(&c, "the cut direction") {
                    return false;
                }
                self.commit(Some(c));
                true
            }
            _ => false,
        }
    }

    /// Sets the segment spacing ω (clamped to at least 1).
    pub fn set_spacing(&mut self, spacing: f64) {
        if spacing.is_finite() {
            self.settings.spacing = spacing.max(1.0);
        }
    }

    /// Turns smoothing (rounded/freeform) on or off, for the current cutter (an undoable action)
    /// and the next ones. Returns true when the cutter changed.
    pub fn set_smooth(&mut self, smooth: bool) -> bool {
        self.settings.smooth = smooth;
        match &self.cutter {
            Some(c) if c.smooth != smooth => {
                let mut c = c.clone();
                c.smooth = smooth;
                if !self.accepts(&c, "smoothing") {
                    return false;
                }
                self.commit(Some(c));
                true
            }
            _ => false,
        }
    }

    /// Sets the subdivision levels of a smooth cutter ("Smoothness", clamped to
    /// [`crate::subdivision::MAX_LEVELS`]) for the current cutter (an undoable action, checked
    /// like every edit) and the next ones. Returns true when the cutter changed.
    pub fn set_levels(&mut self, levels: u32) -> bool {
        let levels = levels.min(crate::subdivision::MAX_LEVELS);
        self.settings.levels = levels;
        match &self.cutter {
            Some(c) if c.levels != levels => {
                let mut c = c.clone();
                c.levels = levels;
                if !self.accepts(&c, "the smoothness") {
                    return false;
                }
                self.commit(Some(c));
                true
            }
            _ => false,
        }
    }

    /// The plane under the pointer after the last event (for highlighting).
    pub fn hovered_plane(&self) -> Option<usize> {
        self.hovered
    }

    /// The selected plane (for highlighting; the target of wheel edits).
    pub fn selected_plane(&self) -> Option<usize> {
        self.selected
    }

    /// True while a press-drag is in progress.
    pub fn is_dragging(&self) -> bool {
        !matches!(self.drag, Drag::None)
    }

    /// The initial strip while the first drag is in progress, as world points A, D, H, E on the
    /// plane through the target's centre facing the camera (for drawing only).
    pub fn init_strip(&self) -> Option<[DVec3; 4]> {
        let Drag::Init { a, b } = self.drag else {
            return None;
        };
        let f = self.camera.forward();
        let z = (self.target.bbox().center() - self.camera.eye)
            .dot(f)
            .max(1e-9);
        let px =
            2.0 * z * (self.camera.fov_y_deg.to_radians() * 0.5).tan() / self.viewport.y.max(1.0);
        let corners =
            extrude::strip_pixels(a, b, extrude::INITIAL_WIDTH * self.settings.delta / px);
        Some(corners.map(|c| {
            let ray = self.camera.ray_through_pixel(self.viewport, c);
            ray.at(z / ray.direction.dot(f).max(1e-12))
        }))
    }

    /// True when an undo step exists.
    pub fn can_undo(&self) -> bool {
        !self.undo_stack.is_empty()
    }

    /// True when a redo step exists.
    pub fn can_redo(&self) -> bool {
        !self.redo_stack.is_empty()
    }

    /// Undoes the last action (cancelling any drag first). Returns true when something changed.
    pub fn undo(&mut self) -> bool {
        self.cancel_drag();
        let Some(previous) = self.undo_stack.pop() else {
            return false;
        };
        let current = std::mem::replace(&mut self.cutter, previous);
        self.redo_stack.push(current);
        self.clamp_selection();
        true
    }

    /// Redoes the last undone action. Returns true when something changed.
    pub fn redo(&mut self) -> bool {
        self.cancel_drag();
        let Some(next) = self.redo_stack.pop() else {
            return false;
        };
        let current = std::mem::replace(&mut self.cutter, next);
        self.undo_stack.push(current);
        self.clamp_selection();
        true
    }

    /// Every event handled so far, in order (the "record gesture" debug action saves these with
    /// the camera, viewport and settings as a `cutaway-gesture/1` file).
    pub fn recorded_events(&self) -> &[EditorEvent] {
        &self.recording
    }

    /// Forgets the recorded events (start a new recording).
    pub fn clear_recording(&mut self) {
        self.recording.clear();
    }

    /// Handles one input event.
    pub fn handle(&mut self, event: EditorEvent) -> EditorResponse {
        self.recording.push(event);
        match event {
            EditorEvent::Press { x, y, .. } => self.press(DVec2::new(x, y)),
            EditorEvent::Move { x, y, shift, .. } => self.pointer_move(DVec2::new(x, y), shift),
            EditorEvent::Release { x, y, shift, .. } => self.release(DVec2::new(x, y), shift),
            EditorEvent::Wheel {
                x,
                y,
                delta,
                ctrl,
                alt,
            } => self.wheel(DVec2::new(x, y), delta, ctrl, alt),
            EditorEvent::Key { key, x, y } => self.key(key, DVec2::new(x, y)),
        }
    }

    fn surface(&self) -> Surface<'_> {
        Surface::new(&self.target, &self.index)
    }

    fn ray(&self, px: DVec2) -> Ray {
        self.camera.ray_through_pixel(self.viewport, px)
    }

    fn commit(&mut self, cutter: Option<Cutter>) {
        let previous = std::mem::replace(&mut self.cutter, cutter);
        self.undo_stack.push(previous);
        self.redo_stack.clear();
        self.clamp_selection();
    }

    fn clamp_selection(&mut self) {
        let n = self.cutter.as_ref().map_or(0, |c| c.planes.len());
        if self.selected.is_some_and(|s| s >= n) {
            self.selected = None;
        }
        if self.hovered.is_some_and(|s| s >= n) {
            self.hovered = None;
        }
    }

    fn cancel_drag(&mut self) {
        match std::mem::replace(&mut self.drag, Drag::None) {
            Drag::Extrude { before, .. } | Drag::Vertex { before, .. } => {
                self.cutter = Some(before)
            }
            Drag::Init { .. } | Drag::None => {}
        }
    }

    fn press(&mut self, px: DVec2) -> EditorResponse {
        if self.is_dragging() {
            // A second press without release: treat the first drag as finished.
            self.release(px, false);
        }
        self.drag_refusal = None;
        let Some(cutter) = self.cutter.clone() else {
            self.drag = Drag::Init { a: px, b: px };
            return EditorResponse {
                changed: false,
                cursor: CursorHint::Crosshair,
                warp_cursor: None,
            };
        };
        let pick = self.pick(px);
        match pick {
            Pick::Handle => {
                let lead = *cutter.leading();
                let handle = self.project(lead.front_mid()).unwrap_or(px);
                self.selected = Some(cutter.planes.len() - 1);
                self.drag = Drag::Extrude {
                    offset: handle - px,
                    before: cutter,
                };
                EditorResponse {
                    changed: false,
                    cursor: CursorHint::Grabbing,
                    warp_cursor: Some(handle),
                }
            }
            Pick::Vertex { plane, top } => {
                self.selected = Some(plane);
                self.drag = Drag::Vertex {
                    plane,
                    top,
                    before: cutter,
                };
                EditorResponse {
                    changed: false,
                    cursor: CursorHint::Move,
                    warp_cursor: None,
                }
            }
            Pick::Plane(i) => {
                self.selected = Some(i);
                EditorResponse {
                    changed: false,
                    cursor: CursorHint::PointingHand,
                    warp_cursor: None,
                }
            }
            Pick::Nothing => {
                self.selected = None;
                EditorResponse::default()
            }
        }
    }

    fn pointer_move(&mut self, px: DVec2, shift: bool) -> EditorResponse {
        match &mut self.drag {
            Drag::Init { b, .. } => {
                *b = px;
                EditorResponse {
                    changed: false,
                    cursor: CursorHint::Crosshair,
                    warp_cursor: None,
                }
            }
            Drag::Extrude { offset, .. } => {
                let offset = *offset;
                let changed = self.extrude_to(px + offset, shift);
                EditorResponse {
                    changed,
                    cursor: CursorHint::Grabbing,
                    warp_cursor: None,
                }
            }
            Drag::Vertex { plane, top, .. } => {
                let (plane, top) = (*plane, *top);
                let changed = self.drag_vertex(plane, top, px);
                EditorResponse {
                    changed,
                    cursor: CursorHint::Move,
                    warp_cursor: None,
                }
            }
            Drag::None => {
                let pick = self.pick(px);
                self.hovered = match pick {
                    Pick::Handle => self.cutter.as_ref().map(|c| c.planes.len() - 1),
                    Pick::Vertex { plane, .. } | Pick::Plane(plane) => Some(plane),
                    Pick::Nothing => None,
                };
                EditorResponse {
                    changed: false,
                    cursor: self.hint(pick),
                    warp_cursor: None,
                }
            }
        }
    }

    fn extrude_to(&mut self, px: DVec2, shift: bool) -> bool {
        let ray = self.ray(px);
        let Some(mut cutter) = self.cutter.take() else {
            return false;
        };
        let settings = RollSettings {
            delta: self.settings.delta,
            spacing: self.settings.spacing,
            straight: shift || self.settings.kind == CutKind::Straight,
            keep_direction: cutter.direction == CutDirection::View,
            keep_depth: self.settings.rules == Rules::Reach,
        };
        let before = cutter.clone();
        let changed = {
            let surface = Surface::new(&self.target, &self.index);
            extrude::extrude_move(&mut cutter, &surface, &ray, &settings)
        };
        let kept = !changed || self.accepts_move(&before, &cutter, "the extrusion");
        let cutter = if kept { cutter } else { before };
        self.selected = Some(cutter.planes.len() - 1);
        self.cutter = Some(cutter);
        changed && kept
    }

    /// True when `cutter`, the result of one pointer move of a drag from `before`, passes the
    /// exact check where the move changed it; otherwise the move is refused (the cutter stays as
    /// it was, so the live cut does not get it) and the reason is kept for [`Editor::note`].
    ///
    /// The move itself ([`extrude::extrude_move`], [`edits::move_edge`]) made sure the whole
    /// cutter passes [`Cutter::sanity_check`]; here the boxes on either side of every changed
    /// plane get the exact check ([`Cutter::validate_boxes`]), which keeps a drag over a long
    /// cutter as fast as the pointer (the whole cutter is checked exactly when the drag ends).
    fn accepts_move(&mut self, before: &Cutter, cutter: &Cutter, what: &str) -> bool {
        match changed_span(before, cutter).validate_boxes() {
            Ok(()) => true,
            Err(e) => {
                let refusal = format!("{what} was stopped here: {e}");
                self.note = Some(refusal.clone());
                self.drag_refusal = Some(refusal);
                false
            }
        }
    }

    fn drag_vertex(&mut self, plane: usize, top: bool, px: DVec2) -> bool {
        let Some(cutter) = self.cutter.clone() else {
            return false;
        };
        let Some(p) = cutter.planes.get(plane) else {
            return false;
        };
        let (front, back) = if top {
            (p.front_top, p.back_top)
        } else {
            (p.front_bottom, p.back_bottom)
        };
        let ray = self.ray(px);
        let Some(t) = geom::line_plane(ray.origin, ray.direction, front, front - back) else {
            return false;
        };
        if t <= 0.0 {
            return false;
        }
        match edits::move_edge(&cutter, plane, top, ray.at(t)) {
            Some(c) => {
                if !self.accepts_move(&cutter, &c, "the edge") {
                    return false;
                }
                self.cutter = Some(c);
                true
            }
            None => {
                let refusal = "the edge cannot go there: planes would cross or fold".to_string();
                self.note = Some(refusal.clone());
                self.drag_refusal = Some(refusal);
                false
            }
        }
    }

    fn release(&mut self, px: DVec2, shift: bool) -> EditorResponse {
        let drag = std::mem::replace(&mut self.drag, Drag::None);
        let mut response = EditorResponse {
            changed: false,
            cursor: CursorHint::Default,
            warp_cursor: None,
        };
        match drag {
            Drag::Init { a, .. } => {
                if (px - a).length() >= MIN_DRAG_PX {
                    let surface = self.surface();
                    let created = extrude::initialize(
                        &surface,
                        &self.camera,
                        self.viewport,
                        a,
                        px,
                        self.settings.delta,
                        self.settings.kind,
                        self.settings.smooth,
                    );
                    let (levels, direction) = (self.settings.levels, self.settings.direction);
                    let created = created
                        .map(|c| Cutter {
                            levels,
                            direction,
                            ..c
                        })
                        .map(|c| self.at_default_depth(c));
                    if let Some(c) = created.filter(|c| self.accepts(c, "the new cutter")) {
                        self.selected = Some(c.planes.len() - 1);
                        self.commit(Some(c));
                        response.changed = true;
                    }
                }
            }
            Drag::Extrude { offset, before } => {
                let moved = self.extrude_to(px + offset, shift);
                response.changed = moved;
                self.finish_drag(before);
            }
            Drag::Vertex { plane, top, before } => {
                response.changed = self.drag_vertex(plane, top, px);
                self.finish_drag(before);
            }
            Drag::None => {}
        }
        response.cursor = self.hint(self.pick(px));
        response
    }

    /// Ends a drag that started from `before`: a valid, different result is one undo step. Every
    /// move of the drag was checked where it changed the cutter (a move that failed was refused,
    /// and [`Editor::note`] says where the drag stopped); the whole result gets the exact
    /// [`Cutter::validate`] here, and should it fail, it loses boxes from its end until it
    /// passes, else falls back to `before`, and the note says so.
    fn finish_drag(&mut self, before: Cutter) {
        let valid = match self.cutter.clone() {
            Some(c) => self.accepts(&c, "the drag"),
            None => false,
        };
        if let Some(stopped) = self.drag_refusal.take()
            && valid
        {
            self.note = Some(match self.smoothing_note_now() {
                Some(smoothing) => format!("{stopped}; {smoothing}"),
                None => stopped,
            });
        }
        if !valid {
            let refusal = self.note.clone();
            let mut trimmed = self.cutter.clone();
            let mut kept = false;
            if let Some(c) = &mut trimmed {
                while c.planes.len() > 2 && !kept {
                    c.planes.pop();
                    kept = c.validate_boxes().is_ok();
                }
            }
            if kept && let Some(c) = trimmed {
                self.accepts(&c, "the drag");
                self.note = Some(format!(
                    "{}; the last boxes were dropped",
                    refusal.unwrap_or_default()
                ));
                self.cutter = Some(c);
            } else {
                self.cutter = Some(before.clone());
                self.note = refusal;
            }
        }
        if self.cutter.as_ref() != Some(&before) {
            self.undo_stack.push(Some(before));
            self.redo_stack.clear();
        }
        self.clamp_selection();
    }

    fn key(&mut self, key: Key, px: DVec2) -> EditorResponse {
        let mut response = EditorResponse {
            cursor: self.hint(self.pick(px)),
            ..Default::default()
        };
        match key {
            Key::Escape => {
                response.changed = matches!(self.drag, Drag::Extrude { .. } | Drag::Vertex { .. });
                self.cancel_drag();
            }
            Key::Delete => {
                if self.is_dragging() || !self.over_cutter(px) {
                    return response;
                }
                if let Some(c) = self
                    .cutter
                    .as_ref()
                    .and_then(edits::remove_last_box)
                    .filter(|c| self.accepts(c, "removing the box"))
                {
                    self.commit(Some(c));
                    response.changed = true;
                }
            }
        }
        response
    }

    /// Largest distance from a plane's front-edge midpoint to the target surface.
    pub fn max_surface_gap(&self) -> Option<f64> {
        let c = self.cutter.as_ref()?;
        Some(extrude::max_surface_gap(c, &self.surface()))
    }
}

/// The planes of `after` that differ from `before`, with one unchanged plane on either side,
/// as a cutter of its own (at least one box; the whole of `after` when nothing differs).
fn changed_span(before: &Cutter, after: &Cutter) -> Cutter {
    let n = after.planes.len();
    let differs = |i: usize| before.planes.get(i) != Some(&after.planes[i]);
    let (Some(first), Some(last)) = ((0..n).find(|&i| differs(i)), (0..n).rfind(|&i| differs(i)))
    else {
        return after.clone();
    };
    let lo = first.saturating_sub(1).min(n.saturating_sub(2));
    let hi = (last + 1).min(n - 1).max(lo + 1).min(n - 1);
    Cutter {
        kind: after.kind,
        smooth: false,
        levels: 0,
        direction: after.direction,
        planes: after.planes[lo..=hi].to_vec(),
    }
}
