//! Input events of the cutter [`crate::editor::Editor`], independent of any GUI toolkit.
//!
//! The GUI translates egui input into these, the CLI parses them from a `cutaway-gesture` file,
//! and the tests build them by hand, so all three drive exactly the same code. Pixel coordinates
//! have their origin at the top-left of the viewport with y growing downward (the same convention
//! as [`crate::camera::Camera::ray_through_pixel`]).

use glam::DVec2;

/// A keyboard key the editor reacts to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Key {
    /// Removes the last box when the pointer is over the cutter (thesis 3.3.3, "Removing a Box").
    Delete,
    /// Cancels a drag in progress (restores the state before the press).
    Escape,
}

impl Key {
    /// The key's name in the gesture format (`"Delete"`, `"Escape"`).
    pub fn name(self) -> &'static str {
        match self {
            Key::Delete => "Delete",
            Key::Escape => "Escape",
        }
    }

    /// Parses a gesture-format key name (case-sensitive, as written by [`Key::name`]; `"Del"` and
    /// `"Backspace"` are accepted as aliases of Delete).
    pub fn from_name(name: &str) -> Option<Key> {
        match name {
            "Delete" | "Del" | "Backspace" => Some(Key::Delete),
            "Escape" | "Esc" => Some(Key::Escape),
            _ => None,
        }
    }
}

/// One input event in Edit mode (thesis 3.3). Only the primary mouse button is modelled: camera
/// navigation is the GUI's business and never reaches the editor.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum EditorEvent {
    /// Primary button pressed at pixel (`x`, `y`).
    Press {
        x: f64,
        y: f64,
        shift: bool,
        ctrl: bool,
    },
    /// Pointer moved (button held or not) to pixel (`x`, `y`). `shift` held during an extrusion
    /// enforces the straight-path constraint.
    Move {
        x: f64,
        y: f64,
        shift: bool,
        ctrl: bool,
    },
    /// Primary button released at pixel (`x`, `y`).
    Release {
        x: f64,
        y: f64,
        shift: bool,
        ctrl: bool,
    },
    /// Scroll wheel at pixel (`x`, `y`): `delta` notches, positive = up (deeper / clockwise).
    /// With `ctrl` it rotates the selected plane instead of changing depth; with `alt` (under
    /// [`crate::editor::Rules::Reach`]) it changes the depth of the plane under the pointer only.
    Wheel {
        x: f64,
        y: f64,
        delta: f64,
        ctrl: bool,
        alt: bool,
    },
    /// A key pressed with the pointer at pixel (`x`, `y`).
    Key { key: Key, x: f64, y: f64 },
}

impl EditorEvent {
    /// The pointer position the event carries.
    pub fn pointer(&self) -> DVec2 {
        match *self {
            EditorEvent::Press { x, y, .. }
            | EditorEvent::Move { x, y, .. }
            | EditorEvent::Release { x, y, .. }
            | EditorEvent::Wheel { x, y, .. }
            | EditorEvent::Key { x, y, .. } => DVec2::new(x, y),
        }
    }

    /// Shorthand for a press without modifiers.
    pub fn press(x: f64, y: f64) -> EditorEvent {
        EditorEvent::Press {
            x,
            y,
            shift: false,
            ctrl: false,
        }
    }

    /// Shorthand for a move without modifiers.
    pub fn move_to(x: f64, y: f64) -> EditorEvent {
        EditorEvent::Move {
            x,
            y,
            shift: false,
            ctrl: false,
        }
    }

    /// Shorthand for a move with Shift held (straight path).
    pub fn move_shift(x: f64, y: f64) -> EditorEvent {
        EditorEvent::Move {
            x,
            y,
            shift: true,
            ctrl: false,
        }
    }

    /// Shorthand for a release without modifiers.
    pub fn release(x: f64, y: f64) -> EditorEvent {
        EditorEvent::Release {
            x,
            y,
            shift: false,
            ctrl: false,
        }
    }

    /// Shorthand for a wheel event (without Alt).
    pub fn wheel(x: f64, y: f64, delta: f64, ctrl: bool) -> EditorEvent {
        EditorEvent::Wheel {
            x,
            y,
            delta,
            ctrl,
            alt: false,
        }
    }

    /// Shorthand for a wheel event with Alt held (the plane under the pointer).
    pub fn alt_wheel(x: f64, y: f64, delta: f64) -> EditorEvent {
        EditorEvent::Wheel {
            x,
            y,
            delta,
            ctrl: false,
            alt: true,
        }
    }

    /// Shorthand for a key event.
    pub fn key(key: Key, x: f64, y: f64) -> EditorEvent {
        EditorEvent::Key { key, x, y }
    }
}
