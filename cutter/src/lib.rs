//! # cutter: the tools that decide what to cut
//!
//! The paint-roller cutter of the ExtrusionCutter thesis (bounded cutting planes, extrusion, cut
//! kinds, edits, subdivision, ribbons and slices), the event-driven [`editor`] that the GUI, the
//! CLI and the tests all drive with the same events, and the scalpel mode. Depends on `csg` only:
//! no egui, no wgpu, no file formats.

pub mod adaptive;
pub mod camera;
pub mod cutter;
pub mod editor;
pub mod edits;
pub mod events;
pub mod expose;
pub mod extrude;
mod geom;
pub mod opening;
pub mod plane;
pub mod quad_mesh;
pub mod reach;
pub mod roll;
pub mod scalpel;
pub mod subcutters;
pub mod subdivision;
pub mod surface;
pub mod wedge;

pub use camera::{Camera, Ray};
pub use cutter::{CutKind, Cutter, CutterError};
pub use editor::{CursorHint, CutDirection, Editor, EditorResponse, EditorSettings, Rules};
pub use events::{EditorEvent, Key};
pub use plane::BoundedPlane;
pub use quad_mesh::QuadMesh;
