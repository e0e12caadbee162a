//! Edge → faces adjacency that tolerates boundary and non-manifold edges.
//!
//! Half-edge structures cannot represent an edge shared by three or more faces, and segmented
//! anatomy (marching cubes, hand-edited meshes) has such edges. So the core keeps an undirected
//! edge list with the faces around each edge in CSR form, built once per mesh and cached.
//!
//! Construction is a counting sort of the half-edges by their lower vertex followed by a tiny
//! sort inside each vertex's bucket (a handful of entries), so it is linear in the number of
//! triangles apart from those small sorts, and it allocates a few flat arrays only (no per-edge
//! hashing). A million triangles take a few tens of milliseconds (see `benches/index.rs`).
//!
//! Degenerate triangles are included as they are: a corner pair with the same vertex index on
//! both ends is not an edge (its entry in [`EdgeAdjacency::triangle_edges`] is [`NO_EDGE`]); a
//! triangle that uses an edge twice (`[a, b, a]`) is listed twice in that edge's faces.

use crate::mesh::Mesh;

/// Entry of [`EdgeAdjacency::triangle_edges`] for a corner pair whose two vertex indices are equal
/// (a degenerate triangle's collapsed edge), which is not an edge.
pub const NO_EDGE: u32 = u32::MAX;

/// Undirected edges of a mesh and the faces around each, in CSR form.
#[derive(Clone, Debug, Default)]
pub struct EdgeAdjacency {
    /// Undirected edges as `[lo, hi]` vertex indices with `lo < hi`, sorted, without duplicates.
    pub edges: Vec<[u32; 2]>,
    /// CSR offsets: the faces of edge `e` are `edge_faces[edge_face_offsets[e]..edge_face_offsets[e + 1]]`.
    /// Length is `edges.len() + 1`, starts at 0, non-decreasing, and every group is non-empty.
    pub edge_face_offsets: Vec<u32>,
    /// Face indices, grouped per edge (see `edge_face_offsets`), ascending within a group. One
    /// entry per use: a degenerate face that traverses the edge twice appears twice.
    pub edge_faces: Vec<u32>,
    /// For each triangle, its three edge ids: entry `k` is the edge from corner `k` to corner `(k + 1) % 3`,
    /// or [`NO_EDGE`] when both corners name the same vertex.
    /// Same length as `mesh.triangles`.
    pub triangle_edges: Vec<[u32; 3]>,
}

impl EdgeAdjacency {
    /// Builds the adjacency of `mesh` (degenerate triangles with repeated indices included as they are).
    ///
    /// Requires indices in range ([`Mesh::sanity_check`]).
    ///
    /// # Panics
    /// When the mesh has more than `u32::MAX / 3` triangles (half-edge ids are `u32`), or an index
    /// is out of range.
    pub fn build(mesh: &Mesh) -> EdgeAdjacency {
        Self::build_visiting(mesh, |_| {})
    }

    /// [`EdgeAdjacency::build`], also calling `visit(half_edges)` once per edge, in edge order,
    /// with the edge's half-edges (`3 * face + corner`, ascending; the edge goes from corner
    /// `corner` of `face` to the next). The target index derives face neighbours, regions and
    /// closedness in this one pass instead of re-reading the CSR arrays.
    pub(crate) fn build_visiting(mesh: &Mesh, mut visit: impl FnMut(&[u32])) -> EdgeAdjacency {
        let triangles = &mesh.triangles;
        assert!(
            triangles.len() <= (u32::MAX / 3) as usize,
            "EdgeAdjacency: {} triangles is more than u32 half-edge ids can address",
            triangles.len()
        );
        let vertex_count = mesh.positions.len();

        // Stage 1: count the half-edges by their lower vertex, then turn the counts into bucket
        // starts (exclusive prefix sums).
        let mut bucket_end = vec![0u32; vertex_count];
        for tri in triangles {
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                if a != b {
                    bucket_end[a.min(b) as usize] += 1;
                }
            }
        }
        let mut half_edge_count = 0u32;
        for c in bucket_end.iter_mut() {
            let count = *c;
            *c = half_edge_count;
            half_edge_count += count;
        }
        let half_edge_count = half_edge_count as usize;

        // Stage 2: scatter the half-edge ids into the buckets, advancing each bucket's start to
        // its end (so bucket `v` is `bucket_end[v - 1]..bucket_end[v]` afterwards). Only the ids
        // are stored (4 bytes each): on these machines first-touching memory costs more than
        // reading a half-edge's upper vertex from its (nearby) triangle again in stage 3.
        let mut slots = vec![0u32; half_edge_count];
        for (t, tri) in triangles.iter().enumerate() {
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                if a != b {
                    let c = &mut bucket_end[a.min(b) as usize];
                    slots[*c as usize] = (3 * t + k) as u32;
                    *c += 1;
                }
            }
        }

        // Stage 3: sort each bucket by (upper vertex, half-edge id) and cut it into edges. Buckets
        // are visited in vertex order, so edges come out sorted by (lo, hi); half-edge ids ascend
        // inside an edge, so its faces do too.
        let mut edges = Vec::with_capacity(half_edge_count / 2 + 1);
        let mut edge_face_offsets = Vec::with_capacity(half_edge_count / 2 + 2);
        let mut edge_faces = Vec::with_capacity(half_edge_count);
        let mut triangle_edges = vec![[NO_EDGE; 3]; triangles.len()];
        edge_face_offsets.push(0u32);
        let mut bucket: Vec<(u32, u32)> = Vec::with_capacity(16);
        let mut group: Vec<u32> = Vec::with_capacity(8);
        let mut start = 0usize;
        for (lo, &end) in bucket_end.iter().enumerate() {
            bucket.clear();
            bucket.extend(slots[start..end as usize].iter().map(|&h| {
                let (t, k) = ((h / 3) as usize, (h % 3) as usize);
                let tri = &triangles[t];
                (tri[k].max(tri[(k + 1) % 3]), h)
            }));
            start = end as usize;
            if bucket.len() > 1 {
                bucket.sort_unstable();
            }
            let mut i = 0;
            while i < bucket.len() {
                let hi = bucket[i].0;
                let edge = edges.len() as u32;
                edges.push([lo as u32, hi]);
                group.clear();
                while i < bucket.len() && bucket[i].0 == hi {
                    let half_edge = bucket[i].1;
                    group.push(half_edge);
                    let half_edge = half_edge as usize;
                    edge_faces.push((half_edge / 3) as u32);
                    triangle_edges[half_edge / 3][half_edge % 3] = edge;
                    i += 1;
                }
                edge_face_offsets.push(edge_faces.len() as u32);
                visit(&group);
            }
        }
        drop(slots);
        EdgeAdjacency {
            edges,
            edge_face_offsets,
            edge_faces,
            triangle_edges,
        }
    }

    /// Faces using edge `e`.
    pub fn faces_of_edge(&self, e: u32) -> &[u32] {
        let e = e as usize;
        &self.edge_faces[self.edge_face_offsets[e] as usize..self.edge_face_offsets[e + 1] as usize]
    }

    /// Number of edges.
    pub fn edge_count(&self) -> usize {
        self.edges.len()
    }

    /// Number of face uses of edge `e` (1 on a boundary, 2 inside a manifold, 3+ non-manifold).
    pub fn use_count(&self, e: u32) -> usize {
        let e = e as usize;
        (self.edge_face_offsets[e + 1] - self.edge_face_offsets[e]) as usize
    }

    /// The id of the undirected edge between vertices `a` and `b`, if the mesh has it
    /// (binary search over the sorted edge list).
    pub fn find_edge(&self, a: u32, b: u32) -> Option<u32> {
        let key = [a.min(b), a.max(b)];
        self.edges.binary_search(&key).ok().map(|e| e as u32)
    }

    /// Checks the invariants written on the fields against `mesh`: sorted unique edges with
    /// `lo < hi`, well-formed CSR, and every triangle's edge ids naming its own corners. Meant for
    /// tests and debug checks (linear time).
    pub fn sanity_check(&self, mesh: &Mesh) -> Result<(), AdjacencyError> {
        let EdgeAdjacency {
            edges,
            edge_face_offsets,
            edge_faces,
            triangle_edges,
        } = self;
        let fail = |what: String| Err(AdjacencyError::Invalid(what));
        if triangle_edges.len() != mesh.triangles.len() {
            return fail(format!(
                "{} triangle edge triples for {} triangles",
                triangle_edges.len(),
                mesh.triangles.len()
            ));
        }
        if edge_face_offsets.len() != edges.len() + 1
            || edge_face_offsets.first() != Some(&0)
            || edge_face_offsets.last().map(|&o| o as usize) != Some(edge_faces.len())
        {
            return fail("CSR offsets do not frame edge_faces".into());
        }
        for (e, w) in edges.windows(2).enumerate() {
            if w[0] >= w[1] {
                return fail(format!("edges {e} and {} are not strictly sorted", e + 1));
            }
        }
        for (e, &[lo, hi]) in edges.iter().enumerate() {
            if lo >= hi || hi as usize >= mesh.positions.len() {
                return fail(format!(
                    "edge {e} = [{lo}, {hi}] is not lo < hi < vertex count"
                ));
            }
            let (s, t) = (edge_face_offsets[e], edge_face_offsets[e + 1]);
            if s >= t {
                return fail(format!("edge {e} has no face"));
            }
            let faces = &edge_faces[s as usize..t as usize];
            if faces.windows(2).any(|w| w[0] > w[1]) {
                return fail(format!("faces of edge {e} are not ascending"));
            }
            for &f in faces {
                let tri = mesh.triangles.get(f as usize).copied().unwrap_or([0; 3]);
                if !(0..3).any(|k| {
                    triangle_edges[f as usize][k] == e as u32 && {
                        let (a, b) = (tri[k], tri[(k + 1) % 3]);
                        [a.min(b), a.max(b)] == [lo, hi]
                    }
                }) {
                    return fail(format!("face {f} listed on edge {e} does not use it"));
                }
            }
        }
        for (t, tri) in mesh.triangles.iter().enumerate() {
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                let e = triangle_edges[t][k];
                let ok = if a == b {
                    e == NO_EDGE
                } else {
                    edges.get(e as usize) == Some(&[a.min(b), a.max(b)])
                        && self.faces_of_edge(e).contains(&(t as u32))
                };
                if !ok {
                    return fail(format!("triangle {t} corner {k} has edge id {e}"));
                }
            }
        }
        Ok(())
    }
}

/// A broken [`EdgeAdjacency`] invariant (a bug in whoever built or edited it).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum AdjacencyError {
    /// The adjacency does not describe the mesh it was checked against; rebuild it.
    #[error("edge adjacency is inconsistent: {0}")]
    Invalid(String),
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testkit;
    use glam::DVec3;

    fn mesh(vertex_count: usize, triangles: Vec<[u32; 3]>) -> Mesh {
        let positions = (0..vertex_count).map(|i| DVec3::new(i as f64, (i * i) as f64, 0.0));
        Mesh::new(positions.collect(), triangles).unwrap()
    }

    #[test]
    fn closed_icosphere_every_edge_has_two_faces() {
        let m = testkit::icosphere(2, 1.0);
        let adj = EdgeAdjacency::build(&m);
        adj.sanity_check(&m).unwrap();
        assert_eq!(adj.edge_count(), m.triangle_count() * 3 / 2);
        assert!((0..adj.edge_count() as u32).all(|e| adj.use_count(e) == 2));
    }

    #[test]
    fn boundary_nonmanifold_and_degenerate() {
        // Three triangles on edge 0-1 (non-manifold), a boundary, and a degenerate [4, 4, 5].
        let m = mesh(
            6,
            vec![[0, 1, 2], [1, 0, 3], [0, 1, 4], [4, 4, 5], [2, 1, 2]],
        );
        let adj = EdgeAdjacency::build(&m);
        adj.sanity_check(&m).unwrap();
        let e01 = adj.find_edge(1, 0).unwrap();
        assert_eq!(adj.faces_of_edge(e01), &[0, 1, 2]);
        let e45 = adj.find_edge(4, 5).unwrap();
        // [4, 4, 5] uses 4-5 twice (4→5 and 5→4); 4→4 is no edge.
        assert_eq!(adj.faces_of_edge(e45), &[3, 3]);
        assert_eq!(adj.triangle_edges[3][0], NO_EDGE);
        let e12 = adj.find_edge(1, 2).unwrap();
        assert_eq!(adj.faces_of_edge(e12), &[0, 4, 4]);
        assert_eq!(adj.find_edge(3, 4), None);
        assert_eq!(adj.find_edge(5, 5), None);
    }

    #[test]
    fn empty_mesh() {
        let m = Mesh::default();
        let adj = EdgeAdjacency::build(&m);
        adj.sanity_check(&m).unwrap();
        assert_eq!(adj.edge_count(), 0);
        assert_eq!(adj.edge_face_offsets, vec![0]);
    }

    #[test]
    fn sanity_check_catches_corruption() {
        let m = testkit::cube(DVec3::ZERO, DVec3::ONE);
        let mut adj = EdgeAdjacency::build(&m);
        adj.triangle_edges[2][1] = 0;
        assert!(adj.sanity_check(&m).is_err());
    }
}
