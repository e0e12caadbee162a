//! The 3D viewport's state across frames: the drag in progress, the cutter editor, the scalpel,
//! the cut shown, the gesture recorder and the pick trees. The input that changes it is in
//! `gui/viewport.rs`, `gui/navigation.rs` and `gui/scalpel_mode.rs`.

use std::ops::{Deref, DerefMut};
use std::path::Path;
use std::sync::Arc;

use glam::DVec2;

use cutter::Camera;
use cutter::events::EditorEvent;

use crate::cutting::editing::CutterInit;
use crate::scalpel_session::ScalpelSession;

/// What the primary-button drag in progress does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(in crate::gui) enum Drag {
    Orbit,
    Pan,
    /// The press went to the editor; the release must too.
    Editor,
}

/// The cursor warp of a handle press (thesis 3.3: the cursor snaps to the middle of the handle's
/// front edge). The editor treats the pointer as moved there for the whole drag (it adds the
/// press-to-handle offset to every position it is given), so the window takes that offset off
/// every position it sends: the roller is then where the real pointer is, whether the platform
/// moved the cursor to the handle (the roller starts on it and follows) or ignored the request
/// (Wayland, a remote desktop, test harnesses: the roller comes to the pointer on the first
/// move), and however late the warp arrives. Sending plain positions until the warp arrived left
/// the roller the whole offset away from the pointer when it never did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CursorWarp {
    /// Handle minus press, taken off every pointer position of the drag.
    offset: DVec2,
}

impl CursorWarp {
    /// The cursor was asked to move from `press` to `handle`.
    pub fn requested(&mut self, handle: DVec2, press: DVec2) {
        self.offset = handle - press;
    }

    /// The position to send to the editor for the real pointer position `raw` during the drag.
    pub fn observe(&mut self, raw: DVec2) -> DVec2 {
        raw - self.offset
    }
}

/// A drag that started on a target whose spatial index was still being built (a big structure
/// just loaded or selected): its editor events, in viewport pixels, kept until the index is
/// there and then replayed, so the first drag on a fresh scene is never lost.
#[derive(Clone, Debug, PartialEq)]
pub struct HeldGesture {
    /// The model the press chose.
    pub target: usize,
    /// The camera the pixels were taken with (a replay under another view would cut elsewhere).
    pub camera: Camera,
    /// Press first, then moves, then the release once it came.
    pub events: Vec<EditorEvent>,
}

impl HeldGesture {
    /// True once the drag's release is among the events.
    pub fn released(&self) -> bool {
        matches!(self.events.last(), Some(EditorEvent::Release { .. }))
    }

    /// The pixels the drag went through (to draw it while it waits).
    pub fn path(&self) -> Vec<DVec2> {
        self.events
            .iter()
            .filter_map(|e| match *e {
                EditorEvent::Press { x, y, .. }
                | EditorEvent::Move { x, y, .. }
                | EditorEvent::Release { x, y, .. } => Some(DVec2::new(x, y)),
                _ => None,
            })
            .collect()
    }
}

/// A gesture being recorded (the "record gesture" debug action).
#[derive(Clone, Debug)]
pub struct Recording {
    /// Camera when recording started (Edit mode never moves the camera).
    pub camera: Camera,
    /// Viewport size in pixels when recording started.
    pub viewport: DVec2,
    pub init: CutterInit,
    pub events: Vec<EditorEvent>,
}

/// Viewport state that lives across frames.
pub struct ViewportState {
    pub(in crate::gui) drag: Option<Drag>,
    /// The cursor warp of the extrusion drag in progress.
    pub(in crate::gui) warp: CursorWarp,
    /// Size of the viewport in physical pixels at the last frame.
    pub size_px: DVec2,
    /// The viewport's rectangle in points at the last frame.
    pub rect: egui::Rect,
    /// Pointer position of the last editor event (to send moves only when it changes).
    pub(in crate::gui) last_pointer: Option<DVec2>,
    pub recording: Option<Recording>,
    /// The cutter editor and its spatial-index cache.
    pub editor: crate::cutting::editing::EditorSlot,
    /// Scalpel mode's blade settings, session and stroke.
    pub scalpel: ScalpelSlot,
    /// Cut parts shown in Preview, with the scene state they were computed for.
    pub preview: Option<Arc<crate::cutting::cut_scene::PreviewGeometry>>,
    pub preview_key: Option<crate::cutting::scene_cuts::PreviewKey>,
    /// The live re-cut shown in Edit mode while the cutter is painted.
    pub live: crate::cutting::live_cut::LiveCut,
    /// The renderer is installed in egui's callback resources.
    pub gpu: bool,
    /// The navigation drag (right or middle button, Alt+drag in Edit) in progress.
    pub nav: Option<NavDrag>,
    /// View → Orientation Marker (a window overlay: exports do not draw it).
    pub show_marker: bool,
    /// The models' ray-pick trees (double-click focus, the first press of a cutter).
    pub picks: crate::cutting::pick::ScenePicks,
    /// The walls' distances to the critical structures, mapped on a worker.
    pub risk: crate::cutting::risk_worker::RiskMap,
    /// A drag waiting for its target's index (see [`HeldGesture`]).
    pub held: Option<HeldGesture>,
    /// The mesh whose index Edit mode last started building ahead of a press (once per mesh,
    /// so a cancelled build is not started again at once).
    pub(in crate::gui) index_ahead: Option<std::sync::Weak<csg::Mesh>>,
    /// The frame whose pointer events the Edit mode input already handled: egui may lay out a
    /// frame twice (a discarded sizing pass) with the same events, which must reach the editor
    /// once.
    pub(in crate::gui) input_frame: Option<u64>,
}

impl ViewportState {
    /// `gpu`: the renderer is installed in egui's callback resources.
    pub fn new(gpu: bool) -> ViewportState {
        ViewportState {
            drag: None,
            warp: CursorWarp::default(),
            size_px: DVec2::new(1280.0, 800.0),
            rect: egui::Rect::NOTHING,
            last_pointer: None,
            recording: None,
            editor: crate::cutting::editing::EditorSlot::default(),
            scalpel: Default::default(),
            preview: None,
            preview_key: None,
            live: Default::default(),
            gpu,
            nav: None,
            show_marker: true,
            picks: Default::default(),
            risk: Default::default(),
            held: None,
            index_ahead: None,
            input_frame: None,
        }
    }

    pub fn cancel_drag(&mut self) {
        self.drag = None;
        self.nav = None;
    }

    /// True while a press went to the cutter editor and is not released yet.
    pub fn editor_dragging(&self) -> bool {
        self.drag == Some(Drag::Editor)
    }

    pub fn reset_editor(&mut self) {
        self.editor = crate::cutting::editing::EditorSlot::default();
        self.held = None;
        self.scalpel.reset();
        self.drag = None;
        self.preview = None;
        self.preview_key = None;
        self.live.clear();
    }

    pub fn start_recording(&mut self, camera: &Camera, init: &CutterInit) {
        self.recording = Some(Recording {
            camera: *camera,
            viewport: self.size_px,
            init: init.clone(),
            events: Vec::new(),
        });
    }

    /// Writes the recording as a `cutaway-gesture/2` file and stops recording; returns the number
    /// of events written.
    pub fn save_recording(&mut self, path: &Path) -> anyhow::Result<usize> {
        let Some(recording) = self.recording.take() else {
            anyhow::bail!("{}: no gesture is being recorded", path.display());
        };
        let gesture = recording.gesture();
        crate::io::gesture::write_gesture(path, &gesture)?;
        Ok(gesture.events.len())
    }

    /// Sends one event to the editor (and the recorder). True when the scene's cutters changed.
    pub(in crate::gui) fn editor_event(
        &mut self,
        scene: &mut crate::scene::Scene,
        event: EditorEvent,
    ) -> bool {
        if let Some(r) = &mut self.recording {
            r.events.push(event);
        }
        self.editor.handle(scene, self.size_px, event)
    }
}

impl Recording {
    /// The recording as a gesture (the format `cutaway extrude` replays).
    pub fn gesture(&self) -> crate::io::gesture::Gesture {
        crate::io::gesture::Gesture {
            viewport: self.viewport,
            camera: self.camera,
            cut: crate::io::gesture::CutSettings {
                kind: self.init.kind,
                spacing: self.init.spacing,
                smooth: self.init.smooth,
                direction: self.init.direction,
            },
            events: self.events.clone(),
            rules: cutter::Rules::Reach,
        }
    }
}

/// What the navigation drag in progress does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NavDrag {
    Orbit,
    Pan,
}

/// Scalpel mode's state in the viewport: the session plus what the pointer is doing.
pub struct ScalpelSlot {
    pub session: ScalpelSession,
    pub(in crate::gui) camera_drag: Option<CameraDrag>,
    /// The viewport in egui points at the last frame (tests aim with it).
    pub rect: egui::Rect,
    /// The target the depth and opening were sized for (they follow the selected model).
    pub sizing: crate::scalpel_session::target::ScalpelSizing,
}

impl Default for ScalpelSlot {
    fn default() -> Self {
        ScalpelSlot {
            session: ScalpelSession::default(),
            camera_drag: None,
            rect: egui::Rect::NOTHING,
            sizing: Default::default(),
        }
    }
}

impl Deref for ScalpelSlot {
    type Target = ScalpelSession;
    fn deref(&self) -> &ScalpelSession {
        &self.session
    }
}

impl DerefMut for ScalpelSlot {
    fn deref_mut(&mut self) -> &mut ScalpelSession {
        &mut self.session
    }
}

impl ScalpelSlot {
    /// Forgets the scalpel and the pointer's drag (a new scene was loaded).
    pub fn reset(&mut self) {
        self.session.reset();
        self.camera_drag = None;
    }
}

/// What a camera drag in Scalpel mode does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(in crate::gui) enum CameraDrag {
    Orbit,
    Pan,
}

#[cfg(test)]
mod tests {
    use super::*;
    use cutter::events::Key;
    use glam::DVec3;

    #[test]
    fn a_recorded_gesture_reads_back_as_the_same_gesture() {
        let recording = Recording {
            camera: Camera {
                eye: DVec3::new(0.0, -300.0, 0.0),
                target: DVec3::ZERO,
                up: DVec3::Z,
                fov_y_deg: 30.0,
            },
            viewport: DVec2::new(1280.0, 800.0),
            init: CutterInit::default(),
            events: vec![
                EditorEvent::press(600.0, 380.0),
                EditorEvent::move_shift(660.0, 380.0),
                EditorEvent::release(660.0, 380.0),
                EditorEvent::wheel(100.0, 100.0, 3.0, true),
                EditorEvent::key(Key::Delete, 640.0, 320.0),
            ],
        };
        let mut state = ViewportState::new(false);
        state.recording = Some(recording.clone());
        let path =
            std::env::temp_dir().join(format!("cutaway-gesture-{}.json", std::process::id()));
        assert_eq!(state.save_recording(&path).unwrap(), 5);
        assert!(state.recording.is_none());
        let back = crate::io::gesture::read_gesture(&path).unwrap();
        assert_eq!(back, recording.gesture());
        let text = std::fs::read_to_string(&path).unwrap();
        // The window records under the current rules.
        assert!(text.contains("cutaway-gesture/2"));
        let _ = std::fs::remove_file(&path);
    }

    #[test]
    fn the_roller_is_where_the_pointer_is_whether_the_cursor_warp_arrives_or_not() {
        let (press, handle) = (DVec2::new(100.0, 200.0), DVec2::new(110.0, 195.0));
        // The editor puts the roller at the position it is sent plus the press-to-handle offset.
        let roller = |sent: DVec2| sent + (handle - press);
        let mut warp = CursorWarp::default();
        warp.requested(handle, press);
        // The platform ignores the warp: the pointer moves on from the press.
        for pointer in [DVec2::new(101.0, 200.0), DVec2::new(100.0, 260.0)] {
            assert_eq!(roller(warp.observe(pointer)), pointer);
        }
        // The warp arrives late: the pointer jumps to the handle and moves on from there.
        for pointer in [handle, handle + DVec2::new(3.0, 40.0)] {
            assert_eq!(roller(warp.observe(pointer)), pointer);
        }
    }
}
