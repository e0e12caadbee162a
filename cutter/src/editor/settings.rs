//! What the editor is told and tells back: its settings (the thesis's "Cutter Initialization"
//! tab), the cursor it asks for and the response to one event. Plain data, kept apart from the
//! event handling so the GUI and the CLI can build and read them without the editor's state.

use csg::Aabb;
use glam::DVec2;

use crate::camera::Camera;
pub use crate::cutter::CutDirection;
use crate::cutter::CutKind;

/// The rules the editor reads its events by. Recorded gestures name theirs, so a gesture made
/// under the first rules replays exactly as it was made.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Rules {
    /// A new cutter reaches the first structure behind its target ([`crate::reach`]); the wheel
    /// over the cutter scales every plane's depth by [`crate::edits::DEPTH_FACTOR`] a notch,
    /// Alt+wheel only the plane under the pointer, a wheel off the cutter does nothing (the
    /// window zooms); rolling keeps the leading plane's depth and new planes take it.
    #[default]
    Reach,
    /// The first rules: a new cutter is 5δ deep; the wheel changes the depth of the selected
    /// (else hovered) plane by 2δ a notch, of every plane when the pointer is off the cutter;
    /// a rolled plane takes the depth of the plane before it.
    Delta,
}

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
    /// Subdivision levels of a smooth cutter ("Smoothness", 0 to
    /// [`crate::subdivision::MAX_LEVELS`]). Default [`crate::subdivision::DEFAULT_LEVELS`].
    pub levels: u32,
    /// Scene increment δ (see [`EditorSettings::delta_for_target`]). Default 1.
    pub delta: f64,
    /// The rules events are read by. Default [`Rules::Reach`].
    pub rules: Rules,
    /// Which way the boxes go into the target. Default [`CutDirection::View`].
    pub direction: CutDirection,
}

impl Default for EditorSettings {
    fn default() -> Self {
        EditorSettings {
            kind: CutKind::Curving,
            spacing: 20.0,
            smooth: false,
            levels: crate::subdivision::DEFAULT_LEVELS,
            delta: 1.0,
            rules: Rules::Reach,
            direction: CutDirection::View,
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

    /// δ for a new cutter on a target with bounding box `target` (the model or region the
    /// stroke starts on; the `scene` box when the target's is empty or flat), seen by `camera`:
    /// the distance that frames the target ([`EditorSettings::delta_for_scene`] of its box) or,
    /// when the camera is farther from the target's centre, that distance, divided by 2000.
    ///
    /// So a cutter on a small structure is sized from the structure, not from the whole scene
    /// (a kidney in a body in metres gets a kidney's boxes), while a target seen from afar
    /// keeps the thesis's on-screen step (δ = camera distance / 2000): the roller never locks
    /// boxes narrower than a pixel or so, however small the target.
    pub fn delta_for_target(target: &Aabb, scene: &Aabb, camera: &Camera) -> f64 {
        let usable = |b: &Aabb| !b.is_empty() && b.diagonal().is_finite() && b.diagonal() > 0.0;
        let sized = if usable(target) { target } else { scene };
        let framing = Camera::framing_distance(sized, camera.fov_y_deg);
        let seen_from = if usable(sized) {
            (sized.center() - camera.eye).length()
        } else {
            0.0
        };
        framing.max(seen_from) / 2000.0
    }

    /// Default settings with δ for a new cutter on `target` ([`EditorSettings::delta_for_target`]).
    pub fn for_target(target: &Aabb, scene: &Aabb, camera: &Camera) -> Self {
        EditorSettings {
            delta: Self::delta_for_target(target, scene, camera),
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

    /// Builder: the rules events are read by.
    pub fn with_rules(self, rules: Rules) -> Self {
        EditorSettings { rules, ..self }
    }

    /// Builder: the cut direction.
    pub fn with_direction(self, direction: CutDirection) -> Self {
        EditorSettings { direction, ..self }
    }

    /// The first rules with the direction they had (the surface normal): how a
    /// `cutaway-gesture/1` file is replayed.
    pub fn first_rules(self) -> Self {
        self.with_rules(Rules::Delta)
            .with_direction(CutDirection::Normal)
    }

    /// Builder: subdivision levels of a smooth cutter (clamped to
    /// [`crate::subdivision::MAX_LEVELS`]).
    pub fn with_levels(self, levels: u32) -> Self {
        EditorSettings {
            levels: levels.min(crate::subdivision::MAX_LEVELS),
            ..self
        }
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

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    fn boxed(min: DVec3, max: DVec3) -> Aabb {
        Aabb { min, max }
    }

    /// A 20 mm structure inside a 1.8 m body in metres: framed closely, its cutter is sized from
    /// the structure (about 100 times finer than from the body); seen with the whole body, the
    /// camera's distance keeps boxes on screen; an empty target falls back to the scene.
    #[test]
    fn delta_follows_the_target_and_never_drops_below_the_view() {
        let body = boxed(DVec3::new(-0.25, 0.0, -0.15), DVec3::new(0.25, 1.8, 0.15));
        let organ = boxed(DVec3::new(0.05, 1.0, 0.0), DVec3::new(0.07, 1.02, 0.02));
        let close = Camera::framing(&organ, DVec3::Z, DVec3::Y, 30.0);
        let from_organ = EditorSettings::delta_for_target(&organ, &body, &close);
        let from_body = EditorSettings::delta_for_scene(&body, 30.0);
        assert!(
            (from_organ - EditorSettings::delta_for_scene(&organ, 30.0)).abs() < 1e-15,
            "{from_organ}"
        );
        assert!(from_organ * 50.0 < from_body, "{from_organ} vs {from_body}");
        // The first box (10δ wide, 5δ deep) is a fraction of the organ, not wider than it.
        let organ_size = organ.diagonal();
        assert!(10.0 * from_organ < 0.2 * organ_size && 5.0 * from_organ > 1e-3 * organ_size);

        let whole = Camera::framing(&body, DVec3::Z, DVec3::Y, 30.0);
        let far = EditorSettings::delta_for_target(&organ, &body, &whole);
        let seen_from = (organ.center() - whole.eye).length() / 2000.0;
        assert!((far - seen_from).abs() < 1e-15 && far > 20.0 * from_organ);

        let fallback = EditorSettings::delta_for_target(&Aabb::EMPTY, &body, &whole);
        assert!((fallback - from_body).abs() < 1e-12);
        let settings = EditorSettings::for_target(&organ, &body, &close);
        assert_eq!(settings.delta, from_organ);
        assert_eq!(settings.spacing, EditorSettings::default().spacing);
    }
}
