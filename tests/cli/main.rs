//! End-to-end tests of the `cutaway` command line (the contract in `../shared/CONTRACT.md`):
//! each subcommand run as a process on generated scenes, recorded gestures and real anatomy, and
//! the same work done through the library where a test compares the two. One test binary, one
//! file per command or concern.

mod contract;
mod export;
mod expose;
mod extrude;
#[path = "../support/gltf_validator.rs"]
mod gltf_validator;
mod metrics;
mod scalpel;
mod scalpel_lips;
#[allow(dead_code)] // helpers shared with other test binaries
#[path = "../support/scene_files.rs"]
mod scene_files;
mod smooth_cuts;
mod subtract;
