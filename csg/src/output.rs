//! What a cut returns: the kept part as a delta against the cached target, the walls, the
//! removed piece, the contour, and the provenance of every output face.

use glam::DVec3;

use crate::mesh::Mesh;

/// Which input mesh and face an output triangle comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Provenance {
    /// Part of target face `face` (the whole face or a piece of it).
    Target(u32),
    /// Part of cutter face `face` (index into the cutter mesh given to the cut; for
    /// [`crate::boolean::subtract_many`], into the concatenation of the sub-cutters in order).
    Cutter(u32),
}

/// Where an output vertex comes from (symbolic identity: two different sources may have the same
/// rounded position in degenerate configurations).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum VertexSource {
    /// Target vertex (exact input coordinates).
    Target(u32),
    /// Cutter vertex (exact input coordinates).
    Cutter(u32),
    /// New contour vertex `k` (`CutResult::new_positions[k]`).
    New(u32),
}

/// Options of a cut. `Default` is what the CLI and the GUI use.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CutOptions {
    /// Merge output vertices whose rounded positions are bit-identical and drop the triangles
    /// that collapse (default `true`). Only degenerate configurations (tangent contact, coplanar
    /// faces) create such vertices; merging gives files without zero-length edges, but where a
    /// zero-thickness feature collapses the welded surface can be non-manifold there. With
    /// `false` every output is closed and manifold by vertex identity ([`VertexSource`]), at
    /// the price of coincident vertices.
    pub merge_coincident: bool,
}

impl Default for CutOptions {
    fn default() -> Self {
        CutOptions {
            merge_coincident: true,
        }
    }
}

impl CutOptions {
    /// Sets [`CutOptions::merge_coincident`].
    pub fn with_merge_coincident(mut self, merge: bool) -> Self {
        self.merge_coincident = merge;
        self
    }
}

/// One intersection polyline between the target surface and the cutter surface.
#[derive(Clone, Debug, PartialEq)]
pub struct Contour {
    /// Points in order (world coordinates, the same bits as the output vertices).
    pub points: Vec<DVec3>,
    /// Closed loop (the last point connects back to the first; it is not repeated).
    pub closed: bool,
    /// Sub-cutter whose surface made this polyline (0 for a single cutter).
    pub sub_cutter: u32,
}

/// A triangle mesh with one provenance and one sub-cutter id per triangle.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Part {
    /// The triangles (compacted: every vertex is used).
    pub mesh: Mesh,
    /// Same length as `mesh.triangles`.
    pub provenance: Vec<Provenance>,
    /// Sub-cutter of each triangle (0 for a single cutter). Same length as `mesh.triangles`.
    pub sub_cutter: Vec<u32>,
    /// Source of each vertex. Same length as `mesh.positions`.
    pub vertex_source: Vec<VertexSource>,
}

impl Part {
    /// The triangles of sub-cutter `k` only.
    pub fn of_sub_cutter(&self, k: u32) -> Part {
        let mut faces = Vec::new();
        let mut provenance = Vec::new();
        for (i, &s) in self.sub_cutter.iter().enumerate() {
            if s == k {
                faces.push(self.mesh.triangles[i]);
                provenance.push(self.provenance[i]);
            }
        }
        let n = faces.len();
        let mut remap = vec![u32::MAX; self.mesh.positions.len()];
        let mut positions = Vec::new();
        let mut vertex_source = Vec::new();
        let triangles = faces
            .iter()
            .map(|t| {
                t.map(|i| {
                    let r = &mut remap[i as usize];
                    if *r == u32::MAX {
                        *r = positions.len() as u32;
                        positions.push(self.mesh.positions[i as usize]);
                        vertex_source.push(self.vertex_source[i as usize]);
                    }
                    *r
                })
            })
            .collect();
        Part {
            mesh: Mesh {
                positions,
                triangles,
            },
            provenance,
            sub_cutter: vec![k; n],
            vertex_source,
        }
    }
}

/// Statistics of one cut (for benchmarks and tests).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CutStats {
    /// Target/cutter face pairs whose boxes overlap.
    pub candidate_pairs: usize,
    /// Target faces split by the contour.
    pub touched_target_faces: usize,
    /// Cutter faces split by the contour.
    pub touched_cutter_faces: usize,
    /// Exact inside tests (ray parity or winding number) performed.
    pub inside_tests: usize,
    /// Polygons whose ear clipping needed the topology-only fallback (0 when all is well).
    pub triangulation_fallbacks: usize,
    /// Face pieces whose status needed the safety net of `resolve_loops` (0 when all is well).
    pub status_fallbacks: usize,
}

/// The result of cutting a cutter out of a cached target.
///
/// Vertex ids of [`CutResult::kept_new_faces`] index the target's positions first and then
/// [`CutResult::new_positions`]: id `i < n` is target vertex `i` (exact input coordinates),
/// id `n + k` is `new_positions[k]` (a contour vertex), where `n` is the target's vertex count.
#[derive(Clone, Debug, Default)]
pub struct CutResult {
    /// Number of target vertices (`n` above).
    pub target_vertex_count: usize,
    /// Target faces that are not part of kept as they are (split, or removed), ascending.
    pub removed_faces: Vec<u32>,
    /// New contour vertices (rounded once from their exact lattice value).
    pub new_positions: Vec<DVec3>,
    /// Pieces of split target faces that are kept, in the id space described above.
    pub kept_new_faces: Vec<[u32; 3]>,
    /// Target face each of `kept_new_faces` comes from. Same length.
    pub kept_new_provenance: Vec<u32>,
    /// The cutter surface inside the target, oriented to face out of kept.
    pub walls: Part,
    /// The target surface inside the cutter, with the target's orientation.
    pub removed: Part,
    /// The intersection polylines.
    pub contours: Vec<Contour>,
    /// Counters of the work done.
    pub stats: CutStats,
}

impl CutResult {
    /// True when the cut changed nothing (cutter outside the target, or touching it only where
    /// the tie-break rule puts it outside).
    pub fn is_empty(&self) -> bool {
        self.removed_faces.is_empty() && self.walls.mesh.is_empty()
    }

    /// The full kept mesh: the target without `removed_faces`, plus the new pieces. Untouched
    /// faces keep their order and their vertex indices; the new vertices are appended.
    pub fn materialize(&self, target: &Mesh) -> Mesh {
        let (mesh, _) = self.materialize_with_provenance(target);
        mesh
    }

    /// [`CutResult::materialize`] plus the target face of every output triangle.
    pub fn materialize_with_provenance(&self, target: &Mesh) -> (Mesh, Vec<u32>) {
        debug_assert_eq!(target.positions.len(), self.target_vertex_count);
        let mut positions = Vec::with_capacity(target.positions.len() + self.new_positions.len());
        positions.extend_from_slice(&target.positions);
        positions.extend_from_slice(&self.new_positions);
        let keep = target.triangles.len() - self.removed_faces.len() + self.kept_new_faces.len();
        let mut triangles = Vec::with_capacity(keep);
        let mut provenance = Vec::with_capacity(keep);
        let mut removed = self.removed_faces.iter().peekable();
        for (t, tri) in target.triangles.iter().enumerate() {
            if removed.peek() == Some(&&(t as u32)) {
                removed.next();
                continue;
            }
            triangles.push(*tri);
            provenance.push(t as u32);
        }
        triangles.extend_from_slice(&self.kept_new_faces);
        provenance.extend_from_slice(&self.kept_new_provenance);
        (
            Mesh {
                positions,
                triangles,
            },
            provenance,
        )
    }

    /// Kept, compacted (unused vertices dropped), for writing files.
    pub fn kept_mesh(&self, target: &Mesh) -> Mesh {
        self.materialize(target).compacted()
    }
}
