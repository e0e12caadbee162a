//! A cut's output split by region: for each region of the target, its kept part, its walls and
//! its removed part, as separate meshes.
//!
//! The boolean cuts every region as its own solid ([`crate::cavities`], [`crate::solids`]), so
//! each region's parts are meaningful on their own: for a closed region, kept + walls and
//! removed + reversed walls are closed. Callers that write or show structures one by one (the
//! CLI's per-region files, per-structure measures) read them here.
//!
//! Kept and removed faces belong to the region of the target face they come from. Walls carry
//! their solid ([`crate::CutResult::walls_solid`]); the walls of the open regions taken together
//! ([`crate::solids::OPEN_PART`]) go to the open region when there is exactly one, and to none
//! when there are several (an open surface bounds no solid of its own, so there is nothing to
//! attribute them by).

use crate::mesh::Mesh;
use crate::output::{CutResult, Provenance};
use crate::solids::OPEN_PART;
use crate::target::TargetIndex;

/// One region's share of a cut (compacted meshes; vertex coordinates are the cut's, bit for bit).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RegionParts {
    /// The region's surface outside the cutter.
    pub kept: Mesh,
    /// The cutter surface inside the region's solid, facing out of `kept`.
    pub walls: Mesh,
    /// The region's surface inside the cutter.
    pub removed: Mesh,
    /// The region is closed (then `kept` + `walls` and `removed` + reversed `walls` are closed).
    pub closed: bool,
}

impl CutResult {
    /// The cut's parts per region of `target` (the index the cut ran on), in region order.
    pub fn region_parts(&self, target: &TargetIndex) -> Vec<RegionParts> {
        let count = target.regions.count;
        let (kept, kept_faces) = self.materialize_with_provenance(&target.mesh);
        let kept_region: Vec<u32> = kept_faces
            .iter()
            .map(|&t| target.region_of_face(t))
            .collect();
        let removed = self.removed.part();
        let region_of_part_face = |p: &Provenance| match *p {
            Provenance::Target(t) => target.region_of_face(t),
            Provenance::Cutter(_) => u32::MAX,
        };
        let removed_region: Vec<u32> = removed.provenance.iter().map(region_of_part_face).collect();
        let closed = target.regions_closed();
        let open: Vec<u32> = (0..count as u32).filter(|&r| !closed[r as usize]).collect();
        let walls_region: Vec<u32> = self
            .walls_solid
            .iter()
            .map(|&s| match (s, open.as_slice()) {
                (OPEN_PART, [only]) => *only,
                (OPEN_PART, _) => u32::MAX,
                (r, _) => r,
            })
            .collect();
        (0..count as u32)
            .map(|r| RegionParts {
                kept: select(&kept, &kept_region, r),
                walls: select(&self.walls.mesh, &walls_region, r),
                removed: select(&removed.mesh, &removed_region, r),
                closed: closed[r as usize],
            })
            .collect()
    }
}

/// The triangles of `mesh` whose label is `r`, compacted.
fn select(mesh: &Mesh, labels: &[u32], r: u32) -> Mesh {
    Mesh {
        positions: mesh.positions.clone(),
        triangles: mesh
            .triangles
            .iter()
            .zip(labels)
            .filter(|&(_, &l)| l == r)
            .map(|(t, _)| *t)
            .collect(),
    }
    .compacted()
}
