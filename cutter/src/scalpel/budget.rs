//! The element budget of a cut, measured on the result: the notes' two budgets counted
//! separately (`notes/scalpel.md` §4).
//!
//! - **T1, surface pieces**: a triangle the cut crosses edge to edge leaves exactly 3 surface
//!   triangles in its place, one with an end of the cut inside at most 4. Counted per original
//!   triangle: the surface triangles of the result lying in it (each surface triangle's centroid
//!   is nearest to exactly one original triangle: the result refines the input).
//! - **T4, walls**: a V groove adds at most 4 wall triangles per path segment, 2 on each lip
//!   (a strip quad, see [`super::groove`], "Wall shape"). Counted as wall triangles over path
//!   segments (lip edges, one per side of a segment; a crack tip's segment has one wall triangle
//!   per side), and locally as the wall triangles around each floor vertex: at most 8 (the two
//!   quads on each lip on either side of it), where a floor vertex shared along the path has a
//!   fan of them. (Which lip edge a wall triangle without one belongs to is a convention in a
//!   strip of triangles, so the count per single segment is not measured.)
//!
//! Costs a spatial index of the original mesh: for tests and benches, not for steps.

use std::collections::BTreeMap;

use super::dyn_mesh::{DynMesh, is_real};

/// See the module doc.
#[derive(Clone, Debug, Default)]
pub struct ElementBudget {
    /// T1: original triangles the cut split (two or more surface pieces in them).
    pub crossed: usize,
    /// T1: mean and largest number of surface pieces in a crossed triangle.
    pub pieces_mean: f64,
    pub pieces_max: usize,
    /// T1: the original triangle with the most pieces.
    pub worst: u32,
    /// T1: pieces → number of crossed triangles.
    pub pieces_histogram: BTreeMap<usize, usize>,
    /// T4: lip edges with a wall (each path segment counts once per side).
    pub lip_edges: usize,
    /// T4: wall triangles in all.
    pub wall_triangles: usize,
    /// T4: wall triangles per path segment (both lips) on average: at most 4.
    pub walls_per_segment_mean: f64,
    /// T4: floor vertices.
    pub floor_vertices: usize,
    /// T4: the most wall triangles around one floor vertex: at most 8 for strip walls (two
    /// quads on each lip), more where a floor vertex is shared along the path (a fan).
    pub walls_per_floor_vertex_max: usize,
    /// Triangles the cut added (surface pieces beyond the originals, plus the walls).
    pub total_new: usize,
}

/// Counts the element budget of a cut of `original` (the mesh before the cut) that produced
/// `cut` (see the module doc).
pub fn element_budget(original: &csg::Mesh, cut: &DynMesh) -> ElementBudget {
    let index = csg::SpatialIndex::build(original);
    let n = original.triangles.len();
    let count = cut.triangle_count() as u32;
    let corners = |t: u32| cut.triangles()[t as usize].map(|v| cut.pos(v));
    let mut b = ElementBudget::default();

    // T1: surface pieces per original triangle.
    let mut pieces = vec![0usize; n];
    let mut surface = 0;
    for t in (0..count).filter(|&t| !cut.is_wall(t)) {
        let [p, q, r] = corners(t);
        let f = index
            .closest_point(original, (p + q + r) / 3.0)
            .map_or(0, |c| c.face);
        pieces[f as usize] += 1;
        surface += 1;
    }
    let mut sum = 0;
    for (f, &k) in pieces.iter().enumerate() {
        if k >= 2 {
            b.crossed += 1;
            sum += k;
            *b.pieces_histogram.entry(k).or_default() += 1;
            if k > b.pieces_max {
                b.pieces_max = k;
                b.worst = f as u32;
            }
        }
    }
    b.pieces_mean = sum as f64 / b.crossed.max(1) as f64;

    // T4: wall triangles per path segment, and around each floor vertex.
    let mut around = std::collections::HashMap::<u32, usize>::new();
    for t in (0..count).filter(|&t| cut.is_wall(t)) {
        b.wall_triangles += 1;
        for k in 0..3 {
            let g = cut.twin(3 * t + k);
            if is_real(g) && !cut.is_wall(g / 3) {
                b.lip_edges += 1;
            }
        }
        for v in cut.triangles()[t as usize] {
            if cut.is_floor(v) {
                *around.entry(v).or_default() += 1;
            }
        }
    }
    b.floor_vertices = around.len();
    b.walls_per_floor_vertex_max = around.values().copied().max().unwrap_or(0);
    b.walls_per_segment_mean = 2.0 * b.wall_triangles as f64 / b.lip_edges.max(1) as f64;
    b.total_new = (surface + b.wall_triangles).saturating_sub(n);
    b
}
