//! # cutter: the tools that decide what to cut
//!
//! The paint-roller cutter of the ExtrusionCutter thesis (bounded cutting planes, extrusion, cut
//! kinds, edits, subdivision, ribbons and slices), the event-driven [`editor`] that the GUI, the
//! CLI and the tests all drive with the same events, and the scalpel mode. Depends on `csg` only:
//! no egui, no wgpu, no file formats.

pub mod camera;

pub use camera::{Camera, Ray};
