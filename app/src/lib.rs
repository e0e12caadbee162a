//! # cutaway: the application
//!
//! The CLI (clap), file formats, the scene and session, the egui UI and the wgpu renderer. The
//! mesh core (`csg`) and the tools (`cutter`) never see any of these.

pub mod anatomy_colors;
pub mod annotate;
pub mod assets;
pub mod cli;
pub mod compare;
pub mod cutting;
pub mod default_anatomy;
pub mod dropped;
pub mod errors;
pub mod export;
pub mod free_pages;
pub mod gesture;
pub mod gui;
pub mod intensity;
pub mod io;
pub mod jobs;
pub mod large_blocks;
pub mod memory_census;
pub mod metrics;
pub mod path_file;
pub mod phantom;
pub mod render;
pub mod ruler;
pub mod scalpel_session;
pub mod scene;
pub mod scene_regions;
pub mod session;
pub mod session_cutters;
pub mod session_format;
pub mod session_image;
pub mod session_limits;
pub mod session_meshes;
pub mod session_paths;
pub mod session_picks;
pub mod session_rulers;
pub mod session_variants;
pub mod session_volumes;
#[cfg(test)]
pub(crate) mod test_support;
pub mod thread_time;
pub mod variants;
pub mod view;
pub mod wall_faces;
