//! The window end to end: the real `CutawayApp` driven headless by egui_kittest on the real wgpu
//! renderer (lavapipe without a GPU), no display needed. One test binary, one file per concern;
//! `harness.rs` opens the window and `input.rs` holds the shared input and looking helpers.
//!
//! Skipped, with the reason printed, when no wgpu adapter exists (set `WGPU_BACKEND=vulkan` with
//! Mesa's lavapipe installed).

mod gui;
mod harness;
#[path = "../support/image_compare.rs"]
mod image_compare;
#[allow(dead_code)] // not every window test uses every helper
mod input;
mod navigation;
mod scale;
mod scalpel;
#[allow(dead_code)] // helpers shared with other test binaries
#[path = "../support/scene_files.rs"]
mod scene_files;
mod tools;
mod window;
