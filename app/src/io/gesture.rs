//! The `cutaway-gesture` file (CONTRACT.md): a recorded mouse gesture with the camera, viewport
//! and cut settings it was made with. `cutaway extrude` replays it through [`cutter::Editor`]; the
//! GUI's "record gesture" debug action writes one, so an editing bug becomes a replayable test.
//!
//! Two versions, each replayed by the rules it was recorded under ([`cutter::Rules`]):
//! `cutaway-gesture/1` by the first rules (a new cutter 5δ deep, the wheel over the cutter
//! deepening the selected plane, its boxes after the first along the surface normal), so an old
//! file makes exactly the cutter it always made; `cutaway-gesture/2` (what the window records
//! now) by the current rules (the default depth reaches the first structure behind the target,
//! the wheel over the cutter changes its whole depth and with `alt` the plane under the
//! pointer, rolling keeps the depth) with the cut direction of its `cut.direction` (`view`,
//! the default, or `normal`).
//!
//! Unknown fields are ignored; every error names the file and says what is wrong.
//!
//! # Bounds
//! A gesture is a request for work: a viewport of `[1, 2]` pixels makes every pixel of a drag
//! span a large part of the scene, and one drag then builds boxes by the thousand. Parsing
//! refuses what no window records: a viewport side outside
//! [`MIN_VIEWPORT_PX`]..=[`MAX_VIEWPORT_PX`], more than [`MAX_EVENTS`] events, a pointer more
//! than one viewport size outside the viewport, a wheel step beyond ±[`MAX_WHEEL_DELTA`], camera
//! coordinates beyond ±[`crate::io::MAX_ABS_COORDINATE`]. The replay itself stops with an error
//! once the cutter has more than [`MAX_REPLAY_BOXES`] boxes or its events used more than
//! [`MAX_REPLAY_TIME`] of the replaying thread's CPU time (see `cutaway extrude`), so every replay
//! is bounded, and a valid gesture replays the same on a loaded machine as on a quiet one.

use std::path::Path;

use anyhow::{Context, bail};
use glam::{DVec2, DVec3};
use serde::{Deserialize, Serialize};

use cutter::{Camera, CutDirection, CutKind, EditorEvent, EditorSettings, Key, Rules};

/// The format tag the window writes.
pub const FORMAT: &str = "cutaway-gesture/2";
/// The first version, still read (and written for a gesture made under the first rules).
pub const FORMAT_V1: &str = "cutaway-gesture/1";

/// Smallest viewport side, in pixels.
pub const MIN_VIEWPORT_PX: f64 = 16.0;
/// Largest viewport side, in pixels (the largest image the renderer makes).
pub const MAX_VIEWPORT_PX: f64 = 16384.0;
/// Most events in one gesture (a minute of recording at 60 Hz is 3600).
pub const MAX_EVENTS: usize = 10_000;
/// Largest wheel step of one event.
pub const MAX_WHEEL_DELTA: f64 = 1000.0;
/// Most boxes a replayed cutter may reach before the replay stops with an error. A drag across a
/// whole scene at the default spacing makes a few dozen; each new box costs more than the last
/// (the cutter is checked whole: the replay's cost grows about with the square of the box
/// count), and 100 keep a replay well within 2 s.
pub const MAX_REPLAY_BOXES: usize = 100;
/// Most CPU time a replay's events may use before it stops with an error (the replaying thread's
/// own time, [`crate::platform::thread_time`]: the machine's load does not count). The box cap alone does not
/// bound a replay: thousands of moves that each re-fit a cutter of many boxes (a 16-pixel
/// viewport, each pixel a large step) stay under the cap and took 38 s; so the replay also
/// stops at this deadline, which leaves room for reading the target, indexing it and writing
/// the cutter within 2 s. Gestures a window records replay in well under a second.
pub const MAX_REPLAY_TIME: std::time::Duration = std::time::Duration::from_millis(1500);

/// Cut settings of a gesture (`cut` object).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CutSettings {
    pub kind: CutKind,
    /// Segment spacing ω (multiples of δ). Positive.
    pub spacing: f64,
    pub smooth: bool,
    /// Which way the boxes go (a `/1` gesture always goes along the normal, the first rules'
    /// only direction).
    pub direction: CutDirection,
}

impl Default for CutSettings {
    fn default() -> Self {
        CutSettings {
            kind: CutKind::Curving,
            spacing: 20.0,
            smooth: false,
            direction: CutDirection::View,
        }
    }
}

/// A parsed, validated gesture.
#[derive(Clone, Debug, PartialEq)]
pub struct Gesture {
    /// Viewport size in pixels, both positive.
    pub viewport: DVec2,
    pub camera: Camera,
    pub cut: CutSettings,
    pub events: Vec<EditorEvent>,
    /// The rules the events were recorded under: [`Rules::Delta`] for `cutaway-gesture/1`,
    /// [`Rules::Reach`] for `/2`.
    pub rules: Rules,
}

impl Gesture {
    /// The editor settings that replay this gesture, with the scene increment `delta`.
    pub fn settings(&self, delta: f64) -> EditorSettings {
        EditorSettings {
            kind: self.cut.kind,
            spacing: self.cut.spacing,
            smooth: self.cut.smooth,
            levels: cutter::subdivision::DEFAULT_LEVELS,
            delta,
            rules: self.rules,
            direction: self.cut.direction,
        }
    }
}

#[derive(Debug, Deserialize, Serialize)]
struct FileJson {
    format: String,
    viewport: [f64; 2],
    camera: CameraJson,
    #[serde(default)]
    cut: Option<CutJson>,
    events: Vec<EventJson>,
}

#[derive(Debug, Deserialize, Serialize)]
struct CameraJson {
    eye: [f64; 3],
    target: [f64; 3],
    up: [f64; 3],
    fov_y_deg: f64,
}

#[derive(Debug, Deserialize, Serialize)]
struct CutJson {
    #[serde(default = "default_kind")]
    kind: String,
    #[serde(default = "default_spacing")]
    spacing: f64,
    #[serde(default)]
    smooth: bool,
    /// `/2` only.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    direction: Option<String>,
}

fn default_kind() -> String {
    "curving".to_owned()
}

fn default_spacing() -> f64 {
    20.0
}

#[derive(Debug, Deserialize, Serialize)]
#[serde(tag = "type", rename_all = "lowercase")]
enum EventJson {
    Press {
        x: f64,
        y: f64,
        #[serde(default)]
        shift: bool,
        #[serde(default)]
        ctrl: bool,
    },
    Move {
        x: f64,
        y: f64,
        #[serde(default)]
        shift: bool,
        #[serde(default)]
        ctrl: bool,
    },
    Release {
        x: f64,
        y: f64,
        #[serde(default)]
        shift: bool,
        #[serde(default)]
        ctrl: bool,
    },
    Wheel {
        #[serde(default)]
        x: f64,
        #[serde(default)]
        y: f64,
        delta: f64,
        #[serde(default)]
        ctrl: bool,
        /// `/2` only: the plane under the pointer.
        #[serde(default, skip_serializing_if = "std::ops::Not::not")]
        alt: bool,
    },
    Key {
        key: String,
        #[serde(default)]
        x: f64,
        #[serde(default)]
        y: f64,
    },
}

/// Reads and validates a gesture file.
pub fn read_gesture(path: &Path) -> anyhow::Result<Gesture> {
    let text = crate::io::bounded::read_text(path, crate::io::bounded::JSON_MAX_BYTES)
        .with_context(|| path.display().to_string())?;
    parse_gesture(&text).with_context(|| path.display().to_string())
}

/// Parses and validates gesture JSON text.
pub fn parse_gesture(text: &str) -> anyhow::Result<Gesture> {
    let file: FileJson =
        serde_json::from_str(text).context("not a valid cutaway-gesture JSON document")?;
    let rules = match file.format.as_str() {
        FORMAT => Rules::Reach,
        FORMAT_V1 => Rules::Delta,
        other => bail!("format is {other:?}, expected {FORMAT:?} or {FORMAT_V1:?}"),
    };
    let [w, h] = file.viewport;
    let sane = |side: f64| (MIN_VIEWPORT_PX..=MAX_VIEWPORT_PX).contains(&side);
    if !(sane(w) && sane(h)) {
        bail!(
            "viewport [{w}, {h}] must be two pixel sizes between {MIN_VIEWPORT_PX} and {MAX_VIEWPORT_PX}"
        );
    }
    if file.events.len() > MAX_EVENTS {
        bail!(
            "events: {} events, more than the limit of {MAX_EVENTS}",
            file.events.len()
        );
    }
    let c = &file.camera;
    let camera = Camera {
        eye: DVec3::from(c.eye),
        target: DVec3::from(c.target),
        up: DVec3::from(c.up),
        fov_y_deg: c.fov_y_deg,
    };
    let limit = crate::io::MAX_ABS_COORDINATE;
    if [camera.eye, camera.target, camera.up]
        .iter()
        .any(|p| !p.to_array().iter().all(|c| c.abs() <= limit))
    {
        bail!("camera has a non-finite coordinate or one beyond ±{limit:e}");
    }
    if camera.eye == camera.target {
        bail!("camera eye and target are the same point");
    }
    if !(camera.fov_y_deg > 0.0 && camera.fov_y_deg < 180.0) {
        bail!(
            "camera fov_y_deg {} must be between 0 and 180",
            camera.fov_y_deg
        );
    }
    if (camera.target - camera.eye)
        .cross(camera.up)
        .length_squared()
        == 0.0
    {
        bail!("camera up is parallel to the viewing direction");
    }
    let cut = match &file.cut {
        None => CutSettings {
            direction: match rules {
                Rules::Delta => CutDirection::Normal,
                Rules::Reach => CutDirection::View,
            },
            ..CutSettings::default()
        },
        Some(cut) => {
            let Some(kind) = CutKind::from_name(&cut.kind) else {
                bail!(
                    "cut kind {:?} is not one of curving, straight, wedge",
                    cut.kind
                );
            };
            if !(cut.spacing.is_finite() && cut.spacing > 0.0) {
                bail!("cut spacing {} must be positive", cut.spacing);
            }
            let direction = match (&cut.direction, rules) {
                (_, Rules::Delta) => CutDirection::Normal,
                (None, Rules::Reach) => CutDirection::View,
                (Some(name), Rules::Reach) => match CutDirection::from_name(name) {
                    Some(d) => d,
                    None => bail!("cut direction {name:?} is not one of view, normal"),
                },
            };
            CutSettings {
                kind,
                spacing: cut.spacing,
                smooth: cut.smooth,
                direction,
            }
        }
    };
    let mut events = Vec::with_capacity(file.events.len());
    for (i, e) in file.events.iter().enumerate() {
        let event = match *e {
            EventJson::Press { x, y, shift, ctrl } => EditorEvent::Press { x, y, shift, ctrl },
            EventJson::Move { x, y, shift, ctrl } => EditorEvent::Move { x, y, shift, ctrl },
            EventJson::Release { x, y, shift, ctrl } => EditorEvent::Release { x, y, shift, ctrl },
            EventJson::Wheel {
                x,
                y,
                delta,
                ctrl,
                alt,
            } => {
                if !(delta.is_finite() && delta.abs() <= MAX_WHEEL_DELTA) {
                    bail!(
                        "event {i}: wheel delta {delta} is not a number within ±{MAX_WHEEL_DELTA}"
                    );
                }
                // The first rules know no Alt: a `/1` file that says so means nothing by it.
                let alt = alt && rules == Rules::Reach;
                EditorEvent::Wheel {
                    x,
                    y,
                    delta,
                    ctrl,
                    alt,
                }
            }
            EventJson::Key { ref key, x, y } => match Key::from_name(key) {
                Some(key) => EditorEvent::Key { key, x, y },
                None => bail!("event {i}: unknown key {key:?} (known: Delete, Escape)"),
            },
        };
        let p = event.pointer();
        let inside = |v: f64, side: f64| (-side..=2.0 * side).contains(&v);
        if !(inside(p.x, w) && inside(p.y, h)) {
            bail!(
                "event {i}: pixel position ({}, {}) is more than one viewport size outside the {w}x{h} viewport",
                p.x,
                p.y
            );
        }
        events.push(event);
    }
    Ok(Gesture {
        viewport: DVec2::new(w, h),
        camera,
        cut,
        events,
        rules,
    })
}

/// The gesture as JSON (what the GUI's "record gesture" writes): `cutaway-gesture/2`, or `/1`
/// for a gesture made under the first rules.
pub fn gesture_to_json(g: &Gesture) -> String {
    let events = g
        .events
        .iter()
        .map(|e| match *e {
            EditorEvent::Press { x, y, shift, ctrl } => EventJson::Press { x, y, shift, ctrl },
            EditorEvent::Move { x, y, shift, ctrl } => EventJson::Move { x, y, shift, ctrl },
            EditorEvent::Release { x, y, shift, ctrl } => EventJson::Release { x, y, shift, ctrl },
            EditorEvent::Wheel {
                x,
                y,
                delta,
                ctrl,
                alt,
            } => EventJson::Wheel {
                x,
                y,
                delta,
                ctrl,
                alt: alt && g.rules == Rules::Reach,
            },
            EditorEvent::Key { key, x, y } => EventJson::Key {
                key: key.name().to_owned(),
                x,
                y,
            },
        })
        .collect();
    let first = g.rules == Rules::Delta;
    let file = FileJson {
        format: if first { FORMAT_V1 } else { FORMAT }.to_owned(),
        viewport: [g.viewport.x, g.viewport.y],
        camera: CameraJson {
            eye: g.camera.eye.to_array(),
            target: g.camera.target.to_array(),
            up: g.camera.up.to_array(),
            fov_y_deg: g.camera.fov_y_deg,
        },
        cut: Some(CutJson {
            kind: g.cut.kind.name().to_owned(),
            spacing: g.cut.spacing,
            smooth: g.cut.smooth,
            direction: (!first).then(|| g.cut.direction.name().to_owned()),
        }),
        events,
    };
    serde_json::to_string_pretty(&file).unwrap_or_default()
}

/// Writes a gesture file (atomically).
pub fn write_gesture(path: &Path, g: &Gesture) -> anyhow::Result<()> {
    crate::io::write_file(path, gesture_to_json(g).as_bytes())
}

#[cfg(test)]
mod tests {
    use super::*;

    const EXAMPLE: &str = r#"{
      "format": "cutaway-gesture/1",
      "viewport": [1280, 800],
      "camera": {"eye": [0, -300, 0], "target": [0, 0, 0], "up": [0, 0, 1], "fov_y_deg": 30},
      "cut": {"kind": "curving", "spacing": 20, "smooth": false},
      "events": [
        {"type": "press",   "x": 600, "y": 380},
        {"type": "move",    "x": 640, "y": 300, "shift": false},
        {"type": "release", "x": 660, "y": 380},
        {"type": "wheel",   "x": 100, "y": 100, "delta": 3, "ctrl": false},
        {"type": "key",     "key": "Delete", "x": 640, "y": 320}
      ]
    }"#;

    #[test]
    fn contract_example_parses_and_round_trips() {
        let g = parse_gesture(EXAMPLE).unwrap();
        assert_eq!(g.events.len(), 5);
        assert_eq!(g.viewport, DVec2::new(1280.0, 800.0));
        assert_eq!(g.events[3], EditorEvent::wheel(100.0, 100.0, 3.0, false));
        assert_eq!(g.events[4], EditorEvent::key(Key::Delete, 640.0, 320.0));
        let again = parse_gesture(&gesture_to_json(&g)).unwrap();
        assert_eq!(again, g);
    }

    /// A `/1` file keeps the first rules (and the normal direction); `/2` carries the current
    /// rules, the cut direction and Alt on the wheel, and writes itself back as `/2`.
    #[test]
    fn each_version_keeps_its_rules() {
        let first = parse_gesture(EXAMPLE).unwrap();
        assert_eq!(first.rules, Rules::Delta);
        assert_eq!(first.cut.direction, CutDirection::Normal);
        assert!(gesture_to_json(&first).contains("\"cutaway-gesture/1\""));
        let settings = first.settings(0.5);
        assert_eq!(
            (settings.rules, settings.direction, settings.delta),
            (Rules::Delta, CutDirection::Normal, 0.5)
        );

        let second = EXAMPLE
            .replace("cutaway-gesture/1", "cutaway-gesture/2")
            .replace(
                "\"smooth\": false}",
                "\"smooth\": false, \"direction\": \"normal\"}",
            )
            .replace("\"ctrl\": false}", "\"ctrl\": false, \"alt\": true}");
        let g = parse_gesture(&second).unwrap();
        assert_eq!(g.rules, Rules::Reach);
        assert_eq!(g.cut.direction, CutDirection::Normal);
        assert_eq!(g.events[3], EditorEvent::alt_wheel(100.0, 100.0, 3.0));
        let text = gesture_to_json(&g);
        assert!(text.contains("\"cutaway-gesture/2\"") && text.contains("\"alt\": true"));
        assert_eq!(parse_gesture(&text).unwrap(), g);
        let plain = second.replace(", \"direction\": \"normal\"", "");
        assert_eq!(
            parse_gesture(&plain).unwrap().cut.direction,
            CutDirection::View
        );
        let bad = second.replace("\"normal\"", "\"sideways\"");
        let e = format!("{:#}", parse_gesture(&bad).unwrap_err());
        assert!(e.contains("sideways"), "{e}");
        // Alt means nothing to the first rules.
        let alt_in_first = EXAMPLE.replace("\"ctrl\": false}", "\"ctrl\": false, \"alt\": true}");
        assert_eq!(
            parse_gesture(&alt_in_first).unwrap().events[3],
            EditorEvent::wheel(100.0, 100.0, 3.0, false)
        );
    }

    #[test]
    fn bad_files_say_what_is_wrong() {
        let wrong_format = EXAMPLE.replace("cutaway-gesture/1", "cutaway-gesture/9");
        let e = format!("{:#}", parse_gesture(&wrong_format).unwrap_err());
        assert!(e.contains("expected"), "{e}");
        let bad_kind = EXAMPLE.replace("\"curving\"", "\"spiral\"");
        let e = format!("{:#}", parse_gesture(&bad_kind).unwrap_err());
        assert!(e.contains("spiral"), "{e}");
        let bad_key = EXAMPLE.replace("Delete", "F13");
        let e = format!("{:#}", parse_gesture(&bad_key).unwrap_err());
        assert!(e.contains("F13"), "{e}");
        assert!(parse_gesture("{").is_err());
    }

    #[test]
    fn absurd_sizes_and_counts_are_refused_naming_the_field() {
        let tiny = EXAMPLE.replace("[1280, 800]", "[1, 2]");
        let e = format!("{:#}", parse_gesture(&tiny).unwrap_err());
        assert!(e.contains("viewport [1, 2]"), "{e}");
        let huge = EXAMPLE.replace("[1280, 800]", "[1280, 1e9]");
        assert!(format!("{:#}", parse_gesture(&huge).unwrap_err()).contains("viewport"));
        let far = EXAMPLE.replace("\"x\": 600", "\"x\": 1e7");
        let e = format!("{:#}", parse_gesture(&far).unwrap_err());
        assert!(e.contains("event 0: pixel position"), "{e}");
        let wheel = EXAMPLE.replace("\"delta\": 3", "\"delta\": 1e300");
        let e = format!("{:#}", parse_gesture(&wheel).unwrap_err());
        assert!(e.contains("event 3: wheel delta"), "{e}");
        let eye = EXAMPLE.replace("[0, -300, 0]", "[0, -3e38, 0]");
        assert!(format!("{:#}", parse_gesture(&eye).unwrap_err()).contains("camera"));
        let moves = vec![r#"{"type": "move", "x": 1, "y": 1}"#; MAX_EVENTS + 1].join(",");
        let many = format!(
            r#"{{"format": "cutaway-gesture/1", "viewport": [100, 100],
              "camera": {{"eye": [0, -3, 0], "target": [0, 0, 0], "up": [0, 0, 1], "fov_y_deg": 30}},
              "events": [{moves}]}}"#
        );
        let e = format!("{:#}", parse_gesture(&many).unwrap_err());
        assert!(e.contains("10001 events"), "{e}");
    }
}
