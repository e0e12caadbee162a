//! # csg: the Cutaway mesh core
//!
//! Everything that every cutting mode shares: an `f64` indexed triangle mesh, its validation,
//! welding, connected regions, edge adjacency, measures, a spatial index, exact predicates and the
//! local exact boolean that cuts a closed cutter out of anatomy.
//!
//! This crate never sees a file format, egui or wgpu (see `ARCHITECTURE.md`).

pub mod aabb;
pub mod adjacency;
pub mod boolean;
pub mod cavities;
pub(crate) mod classify;
pub(crate) mod contour;
pub mod cutcheck;
pub mod exact;
pub mod fast_hash;
pub(crate) mod intersect;
pub mod labels;
pub mod lattice;
pub mod lattice_bvh;
pub mod mesh;
pub mod output;
pub(crate) mod phases;
pub mod pick;
pub(crate) mod polygon;
pub mod region_parts;
pub mod regions;
pub(crate) mod scratch;
pub(crate) mod small;
pub mod solids;
pub mod spatial;
pub(crate) mod split;
pub mod target;
pub mod testkit;
pub mod validate;
pub mod weld;
pub mod winding;

pub use aabb::Aabb;
pub use adjacency::EdgeAdjacency;
pub use boolean::{
    CutError, MAX_REACH, check_cutter, cutter_self_intersections, subtract, subtract_many,
    subtract_with,
};
pub use glam::DVec3;
pub use mesh::{Mesh, MeshError};
pub use output::{Contour, CutOptions, CutResult, Part, Provenance, Removed, VertexSource};
pub use pick::PickIndex;
pub use region_parts::RegionParts;
pub use spatial::{ClosestPoint, RayHit, SpatialIndex};
pub use target::TargetIndex;
pub use validate::MeshReport;
