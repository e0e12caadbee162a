//! # cutaway: the application
//!
//! The CLI (clap), file formats, the scene and session, the egui UI and the wgpu renderer. The
//! mesh core (`csg`) and the tools (`cutter`) never see any of these.

pub mod anatomy;
pub mod annotate;
pub mod batch;
pub mod cli;
pub mod compare;
pub mod cutting;
pub mod export;
pub mod expose;
pub mod gui;
pub mod io;
pub mod metrics;
pub mod platform;
pub mod render;
pub mod scalpel_session;
pub mod scene;
pub mod session;
#[cfg(test)]
pub(crate) mod test_support;
pub mod view;
