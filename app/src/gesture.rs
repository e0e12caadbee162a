//! The `cutaway-gesture/1` file (CONTRACT.md): a recorded mouse gesture with the camera, viewport
//! and cut settings it was made with. `cutaway extrude` replays it through [`cutter::Editor`]; the
//! GUI's "record gesture" debug action writes one, so an editing bug becomes a replayable test.
//!
//! Unknown fields are ignored; every error names the file and says what is wrong.

use std::path::Path;

use anyhow::{Context, bail};
use glam::{DVec2, DVec3};
use serde::{Deserialize, Serialize};

use cutter::{Camera, CutKind, EditorEvent, Key};

/// The format tag.
pub const FORMAT: &str = "cutaway-gesture/1";

/// Cut settings of a gesture (`cut` object).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CutSettings {
    pub kind: CutKind,
    /// Segment spacing ω (multiples of δ). Positive.
    pub spacing: f64,
    pub smooth: bool,
}

impl Default for CutSettings {
    fn default() -> Self {
        CutSettings {
            kind: CutKind::Curving,
            spacing: 20.0,
            smooth: false,
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
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("{}: cannot read", path.display()))?;
    parse_gesture(&text).with_context(|| path.display().to_string())
}

/// Parses and validates gesture JSON text.
pub fn parse_gesture(text: &str) -> anyhow::Result<Gesture> {
    let file: FileJson =
        serde_json::from_str(text).context("not a valid cutaway-gesture/1 JSON document")?;
    if file.format != FORMAT {
        bail!("format is {:?}, expected {FORMAT:?}", file.format);
    }
    let [w, h] = file.viewport;
    if !(w.is_finite() && h.is_finite() && w >= 1.0 && h >= 1.0) {
        bail!("viewport [{w}, {h}] must be two positive pixel sizes");
    }
    let c = &file.camera;
    let camera = Camera {
        eye: DVec3::from(c.eye),
        target: DVec3::from(c.target),
        up: DVec3::from(c.up),
        fov_y_deg: c.fov_y_deg,
    };
    if !(camera.eye.is_finite() && camera.target.is_finite() && camera.up.is_finite()) {
        bail!("camera has a non-finite coordinate");
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
        None => CutSettings::default(),
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
            CutSettings {
                kind,
                spacing: cut.spacing,
                smooth: cut.smooth,
            }
        }
    };
    let mut events = Vec::with_capacity(file.events.len());
    for (i, e) in file.events.iter().enumerate() {
        let event = match *e {
            EventJson::Press { x, y, shift, ctrl } => EditorEvent::Press { x, y, shift, ctrl },
            EventJson::Move { x, y, shift, ctrl } => EditorEvent::Move { x, y, shift, ctrl },
            EventJson::Release { x, y, shift, ctrl } => EditorEvent::Release { x, y, shift, ctrl },
            EventJson::Wheel { x, y, delta, ctrl } => {
                if !delta.is_finite() {
                    bail!("event {i}: wheel delta is not a finite number");
                }
                EditorEvent::Wheel { x, y, delta, ctrl }
            }
            EventJson::Key { ref key, x, y } => match Key::from_name(key) {
                Some(key) => EditorEvent::Key { key, x, y },
                None => bail!("event {i}: unknown key {key:?} (known: Delete, Escape)"),
            },
        };
        let p = event.pointer();
        if !p.is_finite() {
            bail!("event {i}: pixel position is not finite");
        }
        events.push(event);
    }
    Ok(Gesture {
        viewport: DVec2::new(w, h),
        camera,
        cut,
        events,
    })
}

/// The gesture as `cutaway-gesture/1` JSON (what the GUI's "record gesture" writes).
pub fn gesture_to_json(g: &Gesture) -> String {
    let events = g
        .events
        .iter()
        .map(|e| match *e {
            EditorEvent::Press { x, y, shift, ctrl } => EventJson::Press { x, y, shift, ctrl },
            EditorEvent::Move { x, y, shift, ctrl } => EventJson::Move { x, y, shift, ctrl },
            EditorEvent::Release { x, y, shift, ctrl } => EventJson::Release { x, y, shift, ctrl },
            EditorEvent::Wheel { x, y, delta, ctrl } => EventJson::Wheel { x, y, delta, ctrl },
            EditorEvent::Key { key, x, y } => EventJson::Key {
                key: key.name().to_owned(),
                x,
                y,
            },
        })
        .collect();
    let file = FileJson {
        format: FORMAT.to_owned(),
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
        }),
        events,
    };
    serde_json::to_string_pretty(&file).unwrap_or_default()
}

/// Writes a gesture file.
pub fn write_gesture(path: &Path, g: &Gesture) -> anyhow::Result<()> {
    std::fs::write(path, gesture_to_json(g))
        .with_context(|| format!("{}: cannot write", path.display()))
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
}
