//! # csg: the Cutaway mesh core
//!
//! Everything that every cutting mode shares: an `f64` indexed triangle mesh, its validation,
//! welding, connected regions, edge adjacency, measures, a spatial index, exact predicates and the
//! local exact boolean that cuts a closed cutter out of anatomy.
//!
//! This crate never sees a file format, egui or wgpu (see `ARCHITECTURE.md`).

pub mod adjacency;
pub mod aabb;
pub mod mesh;
pub mod regions;
pub mod spatial;
pub mod testkit;
pub mod validate;
pub mod weld;

pub use aabb::Aabb;
pub use adjacency::EdgeAdjacency;
pub use glam::DVec3;
pub use mesh::{Mesh, MeshError};
pub use spatial::{ClosestPoint, RayHit, SpatialIndex};
pub use validate::MeshReport;
