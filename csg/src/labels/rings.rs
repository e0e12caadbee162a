//! Each vertex's smoothing neighbours, recorded while the surface is extracted.
//!
//! The smoothing needs, per vertex, the vertices it shares a polygon side with (and, for a
//! quadrilateral, a diagonal). Collecting them from the finished triangle list takes two more
//! passes over every polygon side with scattered writes, about as long as the smoothing itself; here
//! they are written as each polygon is made, while its vertices are still in cache.
//!
//! Why a fixed slot per vertex suffices: a voxel edge is shared by at most four cubes, each cube
//! puts the edge's vertex in exactly one polygon, and in that polygon the vertex has at most two
//! outgoing sides (to the next vertex of a triangle, a quadrilateral or a fan segment, plus the
//! quadrilateral's diagonal or the fan's centre). So an edge vertex has at most eight neighbours,
//! each listed once (a closed, oriented, edge-manifold mesh holds each directed side once).
//!
//! Why the rings hold only some neighbours: an edge vertex moves along its own axis only, and a
//! neighbour on a voxel edge of another axis never moves along that axis. Its coordinate there is
//! a constant, so it is added to [`Rings::fixed`] once and never read by the smoothing steps;
//! only the neighbours that can move along the axis (edge vertices of the same axis and centre
//! vertices) stay in the ring, which leaves about half the reads of a full ring per step.
//! A centre vertex (a minority) keeps its whole ring: the edge vertices of its fan.

use glam::DVec3;

use super::Constraint;

/// At most this many neighbours of an edge vertex (see the module docs).
pub const EDGE_RING: usize = 8;

/// The neighbours of one edge vertex that move along its axis, and how many neighbours it has
/// in all.
#[derive(Clone, Copy, Debug, Default)]
pub struct EdgeRing {
    /// `moving[..len]`: neighbours whose coordinate along this vertex's axis can change.
    pub moving: [u32; EDGE_RING],
    pub len: u8,
    /// All neighbours, moving or not (the Laplacian divides by this).
    pub count: u8,
}

/// The smoothing neighbourhoods of a surface under construction.
#[derive(Clone, Debug, Default)]
pub struct Rings {
    /// Per vertex (centre vertices get an empty one, unused).
    pub edge: Vec<EdgeRing>,
    /// Per vertex: the sum of the constant coordinates (along the vertex's axis) of its
    /// neighbours on edges of other axes.
    pub fixed: Vec<f64>,
    /// Centre vertex `c`'s neighbours are `centre[centre_offsets[c]..centre_offsets[c + 1]]`.
    pub centre: Vec<u32>,
    pub centre_offsets: Vec<u32>,
}

impl Rings {
    /// A new vertex with no neighbours yet.
    #[inline]
    pub fn push_vertex(&mut self) {
        self.edge.push(EdgeRing::default());
        self.fixed.push(0.0);
    }

    /// Records that edge vertex `from` has neighbour `to` (a directed polygon side).
    #[inline]
    pub fn link(&mut self, from: u32, to: u32, constraint: &[Constraint], positions: &[DVec3]) {
        let axis = constraint[from as usize].0;
        let other = constraint[to as usize].0;
        let ring = &mut self.edge[from as usize];
        ring.count += 1;
        if other < 3 && other != axis {
            self.fixed[from as usize] += positions[to as usize][axis as usize];
        } else {
            ring.moving[ring.len as usize] = to;
            ring.len += 1;
        }
    }

    /// Records the ring of the next centre vertex (the edge vertices of its fan, in order).
    pub fn push_centre(&mut self, ring: impl IntoIterator<Item = u32>) {
        if self.centre_offsets.is_empty() {
            self.centre_offsets.push(0);
        }
        self.centre.extend(ring);
        self.centre_offsets.push(self.centre.len() as u32);
    }

    /// The neighbours of centre vertex `c`.
    #[inline]
    pub fn of_centre(&self, c: usize) -> &[u32] {
        &self.centre[self.centre_offsets[c] as usize..self.centre_offsets[c + 1] as usize]
    }
}

impl super::VoxelSurface {
    /// Records the sides of a triangle or quadrilateral `v` (counter-clockwise), and for a
    /// quadrilateral both diagonals both ways (it is smoothed before it is split).
    #[inline]
    pub(crate) fn link_loop(&mut self, v: &[u32], quad: bool) {
        let n = v.len();
        for k in 0..n {
            self.rings
                .link(v[k], v[(k + 1) % n], &self.constraint, &self.positions);
        }
        if quad {
            for (a, b) in [(0, 2), (2, 0), (1, 3), (3, 1)] {
                self.rings.link(v[a], v[b], &self.constraint, &self.positions);
            }
        }
    }
}
