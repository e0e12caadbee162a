//! What the editor is told and tells back: its settings (the thesis's "Cutter Initialization"
//! tab), the cursor it asks for and the response to one event. Plain data, kept apart from the
//! event handling so the GUI and the CLI can build and read them without the editor's state.

use csg::Aabb;
use glam::DVec2;

use crate::camera::Camera;
use crate::cutter::CutKind;

/// Editor options (the thesis's "Cutter Initialization" tab).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EditorSettings {
    /// Cut type of the next cutter. Default `Curving`. `Straight` behaves like Shift always held;
    /// `Wedge` applies from the next initialisation.
    pub kind: CutKind,
    /// Segment spacing ω: a box is locked when it reaches ω·δ wide. Default 20.
    pub spacing: f64,
    /// Rounded/freeform (subdivided) cutter. Default false.
    pub smooth: bool,
    /// Scene increment δ (see [`EditorSettings::delta_for_scene`]). Default 1.
    pub delta: f64,
}

impl Default for EditorSettings {
    fn default() -> Self {
        EditorSettings {
            kind: CutKind::Curving,
            spacing: 20.0,
            smooth: false,
            delta: 1.0,
        }
    }
}

impl EditorSettings {
    /// δ for a scene: the distance at which a camera with vertical field of view `fov_y_deg`
    /// frames the bounding sphere of every model ([`Camera::framing_distance`], our reading of
    /// the thesis's VTK camera reset), divided by 2000.
    pub fn delta_for_scene(scene: &Aabb, fov_y_deg: f64) -> f64 {
        Camera::framing_distance(scene, fov_y_deg) / 2000.0
    }

    /// Default settings with δ for `scene`.
    pub fn for_scene(scene: &Aabb, fov_y_deg: f64) -> Self {
        EditorSettings {
            delta: Self::delta_for_scene(scene, fov_y_deg),
            ..Default::default()
        }
    }

    /// Builder: the cut kind.
    pub fn with_kind(self, kind: CutKind) -> Self {
        EditorSettings { kind, ..self }
    }

    /// Builder: the segment spacing ω.
    pub fn with_spacing(self, spacing: f64) -> Self {
        EditorSettings { spacing, ..self }
    }

    /// Builder: smooth (rounded/freeform).
    pub fn with_smooth(self, smooth: bool) -> Self {
        EditorSettings { smooth, ..self }
    }
}

/// The cursor the GUI should show.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CursorHint {
    /// Nothing under the pointer.
    #[default]
    Default,
    /// No cutter yet: a press starts one.
    Crosshair,
    /// Over the leading plane's handle.
    Grab,
    /// Extruding.
    Grabbing,
    /// Over (or dragging) a plane's front vertex.
    Move,
    /// Over a plane (a press selects it).
    PointingHand,
}

/// What [`Editor::handle`] did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct EditorResponse {
    /// The cutter (or its existence) changed: re-mesh and re-cut.
    pub changed: bool,
    /// The cursor to show now.
    pub cursor: CursorHint,
    /// Where the GUI should move the real cursor (pixels), when the editor snapped it.
    pub warp_cursor: Option<DVec2>,
}
