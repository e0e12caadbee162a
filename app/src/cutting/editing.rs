//! The editor glue: one [`cutter::Editor`] at a time on the selected target, the settings the
//! next cutter starts with, and the spatial indexes the editor needs.
//!
//! The editor owns the cutter while it is edited; every accepted change is copied into
//! `Scene::cutters` so that undo, sessions, the renderer and Preview all read one truth. The
//! window maps pointer and keys to [`cutter::EditorEvent`]s and hands them to
//! [`EditorSlot::handle`]; nothing here knows egui.

use std::sync::{Arc, Weak};

use glam::DVec2;

use csg::{Mesh, SpatialIndex};
use cutter::{Camera, CutDirection, Editor, EditorEvent, EditorSettings};

use crate::cutting::obstacles::{depth_line, shared_obstacles};
use crate::cutting::pick::ScenePicks;
use crate::platform::jobs::Progress;
use crate::scene::{Scene, SceneCutter};
use cutter::CutKind;

/// Cut settings applied to the next cutter (thesis 3.5 E, Initialization tab).
#[derive(Clone, Debug, PartialEq)]
pub struct CutterInit {
    /// Segment spacing ω: a new box starts each ω·δ of extrusion.
    pub spacing: f64,
    /// Curving (freeform path) or wedge; Shift while extruding gives the straight path.
    pub kind: CutKind,
    /// Rounded (subdivided) cutter.
    pub smooth: bool,
    /// Subdivision levels of a rounded cutter ("Smoothness", 0 to
    /// [`cutter::subdivision::MAX_LEVELS`]).
    pub levels: u32,
    /// Which way the boxes go: along the view they are painted in (default) or the surface
    /// normal.
    pub direction: CutDirection,
}

impl Default for CutterInit {
    fn default() -> Self {
        CutterInit {
            spacing: 20.0,
            kind: CutKind::Curving,
            smooth: false,
            levels: cutter::subdivision::DEFAULT_LEVELS,
            direction: CutDirection::View,
        }
    }
}

impl CutterInit {
    /// These settings as the editor takes them (δ is set by [`new_editor`]).
    pub fn editor_settings(&self) -> EditorSettings {
        EditorSettings::default()
            .with_kind(self.kind)
            .with_spacing(self.spacing)
            .with_smooth(self.smooth)
            .with_levels(self.levels)
            .with_direction(self.direction)
    }
}

/// The editor of a new cutter on model `target` of `scene`, as the window and `cutaway extrude`
/// both make it: `settings` with δ sized from the target seen by `camera`
/// ([`EditorSettings::delta_for_target`]), what lies behind the target from the scene's other
/// visible structures ([`crate::cutting::obstacles`]). `index` is the target mesh's.
pub fn new_editor(
    scene: &Scene,
    target: usize,
    index: Arc<SpatialIndex>,
    camera: Camera,
    viewport: DVec2,
    settings: EditorSettings,
    picks: &mut ScenePicks,
) -> Option<Editor> {
    let model = scene.models.get(target)?;
    let delta = EditorSettings::delta_for_target(&model.model.mesh.bbox(), &scene.bbox(), &camera);
    let settings = EditorSettings { delta, ..settings };
    let mut editor = Editor::new(model.model.mesh.clone(), index, camera, viewport, settings);
    editor.set_obstacles(Some(shared_obstacles(scene, target, picks)));
    Some(editor)
}

/// The status line of an editor's cutter: its depth in the scene's unit shown as mm and what it
/// reaches ("42 mm: reaches left lateral ventricle"). None without a cutter.
pub fn depth_status(editor: &Editor, scene: &Scene) -> Option<String> {
    let depth = editor.depth()?;
    let names: Vec<String> = editor
        .reached()
        .iter()
        .filter_map(|r| editor.obstacle_name(r.structure))
        .collect();
    Some(depth_line(scene.unit.to_mm(depth), &names))
}

/// Targets up to this many triangles get their spatial index built on the UI thread (a few
/// milliseconds); bigger ones in a background job with progress.
const SYNC_INDEX_TRIANGLES: usize = 150_000;

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

    /// Spatial indexes held (the memory test prints it per step).
    pub fn index_count(&self) -> usize {
        self.indexes.len()
    }

    /// True when model `target` needs its index built in the background before a press can
    /// start a cutter on it (too big to build on the UI thread, not built yet).
    pub fn needs_background_index(&self, scene: &Scene, target: usize) -> bool {
        scene.models.get(target).is_some_and(|m| {
            m.model.mesh.triangle_count() > SYNC_INDEX_TRIANGLES
                && self.index_for(&m.model.mesh).is_none()
        })
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
        init: &CutterInit,
        picks: &mut ScenePicks,
    ) -> bool {
        if self.active.as_ref().is_some_and(|a| a.target == target) {
            return true;
        }
        let Some(model) = scene.models.get(target) else {
            return false;
        };
        let index = match self.index_for(&model.model.mesh) {
            Some(index) => index,
            None if model.model.mesh.triangle_count() <= SYNC_INDEX_TRIANGLES => {
                let index = Arc::new(SpatialIndex::build(&model.model.mesh));
                self.store_index(Arc::downgrade(&model.model.mesh), index.clone());
                index
            }
            None => return false,
        };
        self.indexes.retain(|(w, _)| {
            w.upgrade()
                .is_some_and(|m| Arc::ptr_eq(&m, &model.model.mesh))
        });
        // Sized from the target the stroke starts on, as `cutaway extrude` sizes its cutter.
        let Some(editor) = new_editor(
            scene,
            target,
            index,
            scene.camera,
            viewport,
            init.editor_settings(),
            picks,
        ) else {
            return false;
        };
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
        init: &CutterInit,
        picks: &mut ScenePicks,
    ) -> bool {
        let Some(c) = scene.cutters.get(index) else {
            return false;
        };
        self.active = None;
        if !self.ensure(scene, c.target, viewport, init, picks) {
            return false;
        }
        let cutter = c.cutter.clone();
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

    /// Renews what lies behind the active editor's target from the scene (structures that
    /// arrived or were shown or hidden since the editor was made), before a press that may start
    /// a cutter.
    pub fn refresh_obstacles(&mut self, scene: &Scene, picks: &mut ScenePicks) {
        if let Some(active) = &mut self.active
            && active.editor.cutter().is_none()
            && scene.models.get(active.target).is_some()
        {
            let obstacles = shared_obstacles(scene, active.target, picks);
            active.editor.set_obstacles(Some(obstacles));
        }
    }

    /// The active cutter's depth in file units (its leading plane's, which new planes take).
    pub fn depth(&self) -> Option<f64> {
        self.active.as_ref()?.editor.depth()
    }

    /// The depth of plane `i` of the active cutter.
    pub fn plane_depth(&self, i: usize) -> Option<f64> {
        let a = self.active.as_ref()?;
        Some(a.editor.cutter()?.planes.get(i)?.depth())
    }

    /// Gives the active cutter the depth `depth` (file units) as one undoable action; true when
    /// the scene's cutters changed.
    pub fn set_depth(&mut self, scene: &mut Scene, depth: f64) -> bool {
        let Some(active) = &mut self.active else {
            return false;
        };
        if !active.editor.set_depth(depth) {
            return false;
        }
        self.mirror_into(scene);
        true
    }

    /// The status line of the active cutter's depth ([`depth_status`]).
    pub fn depth_status(&self, scene: &Scene) -> Option<String> {
        depth_status(&self.active.as_ref()?.editor, scene)
    }

    /// True when the pixel is over the active cutter (the wheel changes its depth there).
    pub fn is_over_cutter(&self, px: DVec2) -> bool {
        self.active
            .as_ref()
            .is_some_and(|a| a.editor.is_over_cutter(px))
    }

    /// Applies Initialization-tab settings to the active editor; true when the cutter changed.
    pub fn apply_settings(&mut self, scene: &mut Scene, init: &CutterInit) -> bool {
        let Some(active) = &mut self.active else {
            return false;
        };
        active.editor.set_kind(init.kind);
        active.editor.set_spacing(init.spacing);
        // Each runs: each sets the next cutters' setting, and any may change the cutter.
        let direction = active.editor.set_direction(init.direction);
        let smooth = active.editor.set_smooth(init.smooth);
        let levels = active.editor.set_levels(init.levels);
        if smooth || levels || direction {
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
                scene.cutters[i].cutter = c.clone();
            }
            (Some(c), _) => {
                scene
                    .cutters
                    .push(SceneCutter::new(active.target, c.clone()));
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
            .is_none_or(|m| !std::ptr::eq(Arc::as_ptr(&m.model.mesh), active.editor.target()))
        {
            self.active = None;
            return;
        }
        let wanted = active
            .cutter
            .and_then(|i| scene.cutters.get(i))
            .filter(|c| c.target == active.target);
        let current = active.editor.cutter().map(|c| &c.planes);
        match wanted {
            Some(c) if current != Some(&c.cutter.planes) => {
                if !active.editor.set_cutter(Some(c.cutter.clone())) {
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
    let index = Arc::new(SpatialIndex::build(mesh));
    progress.check()?;
    Ok((Arc::downgrade(mesh), index))
}
