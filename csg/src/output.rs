//! What a cut returns: the kept part as a delta against the cached target, the walls, the
//! removed piece, the contour, and the provenance of every output face.

use std::ops::Deref;
use std::sync::{Arc, OnceLock};

use glam::DVec3;

use crate::intersect::FxMap;
use crate::mesh::Mesh;
use crate::split::Vx;

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
    /// Record each stage's wall time in [`CutResult::phases`] (default `false`; for profiling).
    pub time_phases: bool,
}

impl Default for CutOptions {
    fn default() -> Self {
        CutOptions {
            merge_coincident: true,
            time_phases: false,
        }
    }
}

impl CutOptions {
    /// Sets [`CutOptions::time_phases`].
    pub fn with_phase_times(mut self, on: bool) -> Self {
        self.time_phases = on;
        self
    }

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

/// The removed piece (the target surface inside the cutter), computed as a delta against the
/// cached target and built as a [`Part`] only when first read.
///
/// A cut does the classification (which target faces lie inside the cutter, and the inside
/// pieces of the faces the contour splits) and stops there: for a strip across a 2M-triangle
/// sphere the removed piece has ~65k triangles, and compacting them into a mesh would cost more
/// than the rest of the cut. Reading it through `Deref` (`removed.mesh`, `removed.provenance`,
/// `removed.of_sub_cutter(k)`, …) or [`Removed::part`] builds the part once (thread-safe) and
/// caches it; [`Removed::into_part`] moves it out. The part is the same, vertex for vertex and
/// triangle for triangle, whenever it is built: the pieces of split faces first (in the cut's
/// order), then the whole faces in ascending order; vertices are numbered by first use and,
/// with [`CutOptions::merge_coincident`], merged by bit-identical position.
#[derive(Clone, Default)]
pub struct Removed {
    /// Target faces entirely inside the cutter (not split by the contour), ascending.
    pub whole_faces: Vec<u32>,
    /// Sub-cutter of each of `whole_faces` (same length).
    pub whole_sub_cutter: Vec<u32>,
    /// Inside pieces of split target faces, with vertex ids as in [`CutResult::kept_new_faces`]
    /// (target vertex `i < n`, new vertex `n + k`).
    pub piece_faces: Vec<[u32; 3]>,
    /// Target face of each of `piece_faces` (same length).
    pub piece_provenance: Vec<u32>,
    /// Sub-cutter of each of `piece_faces` (same length).
    pub piece_sub_cutter: Vec<u32>,
    /// What building the part needs: the target (shared, not copied), the new vertices, and
    /// whether to merge coincident vertices. `None` for an empty result.
    source: Option<RemovedSource>,
    /// The part, once built.
    part: OnceLock<Part>,
}

#[derive(Clone)]
struct RemovedSource {
    target: Arc<Mesh>,
    new_positions: Vec<DVec3>,
    merge: bool,
}

impl std::fmt::Debug for Removed {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Removed")
            .field("whole_faces", &self.whole_faces.len())
            .field("piece_faces", &self.piece_faces.len())
            .field("built", &self.part.get().is_some())
            .finish()
    }
}

impl Removed {
    /// A removed piece over `target` (whose vertices the ids index, then `new_positions`).
    pub(crate) fn new(target: Arc<Mesh>, new_positions: Vec<DVec3>, merge: bool) -> Removed {
        Removed {
            source: Some(RemovedSource {
                target,
                new_positions,
                merge,
            }),
            ..Default::default()
        }
    }

    /// The removed piece as a mesh with provenance (built on first use, then cached).
    pub fn part(&self) -> &Part {
        self.part.get_or_init(|| self.build())
    }

    /// The removed piece as a mesh with provenance, moved out.
    pub fn into_part(mut self) -> Part {
        match self.part.take() {
            Some(p) => p,
            None => self.build(),
        }
    }

    /// Number of triangles before building: whole faces plus pieces (the built part can have
    /// fewer when merging coincident vertices collapses some).
    pub fn triangle_count_upper_bound(&self) -> usize {
        self.whole_faces.len() + self.piece_faces.len()
    }

    fn build(&self) -> Part {
        let Some(src) = &self.source else {
            return Part::default();
        };
        let n = src.target.positions.len() as u32;
        let mut b = PartBuilder::new(src.merge);
        b.reserve(self.triangle_count_upper_bound());
        let (tp, np): (&[DVec3], &[DVec3]) = (&src.target.positions, &src.new_positions);
        // Output id + 1 of each target vertex seen so far (0: not yet), so that the corners of
        // the whole faces are looked up without hashing. Zeroed memory: only the pages of the
        // vertices used are touched.
        let mut target_id = vec![0u32; n as usize];
        let mut vertex = |b: &mut PartBuilder, i: u32| {
            if i >= n {
                return b.vertex(Vx::X(i - n), tp, &[], np);
            }
            let seen = &mut target_id[i as usize];
            if *seen == 0 {
                *seen = b.new_vertex(tp[i as usize], VertexSource::Target(i)) + 1;
            }
            *seen - 1
        };
        for ((tri, &t), &k) in self
            .piece_faces
            .iter()
            .zip(&self.piece_provenance)
            .zip(&self.piece_sub_cutter)
        {
            let ids = tri.map(|i| vertex(&mut b, i));
            b.push(ids, Provenance::Target(t), k);
        }
        for (&t, &k) in self.whole_faces.iter().zip(&self.whole_sub_cutter) {
            let ids = src.target.triangles[t as usize].map(|i| vertex(&mut b, i));
            b.push(ids, Provenance::Target(t), k);
        }
        b.finish()
    }
}

impl Deref for Removed {
    type Target = Part;
    /// Builds the part on first use (see [`Removed`]).
    fn deref(&self) -> &Part {
        self.part()
    }
}

/// Accumulates a compacted output part.
///
/// With `merge`, vertices are identified by their rounded position (bit for bit), so that new
/// vertices that coincide after rounding (degenerate configurations: the tie-break keeps them
/// apart symbolically) become one vertex, and triangles that collapse are dropped. Without it,
/// by their symbolic identity.
pub(crate) struct PartBuilder {
    merge: bool,
    by_position: FxMap<PositionBits, u32>,
    by_source: FxMap<Vx, u32>,
    positions: Vec<DVec3>,
    vertex_source: Vec<VertexSource>,
    triangles: Vec<[u32; 3]>,
    provenance: Vec<Provenance>,
    sub_cutter: Vec<u32>,
}

impl PartBuilder {
    pub fn new(merge: bool) -> PartBuilder {
        PartBuilder {
            merge,
            by_position: Default::default(),
            by_source: Default::default(),
            positions: Vec::new(),
            vertex_source: Vec::new(),
            triangles: Vec::new(),
            provenance: Vec::new(),
            sub_cutter: Vec::new(),
        }
    }

    /// Room for `triangles` triangles (and about half as many vertices; the map of
    /// [`PartBuilder::vertex`] grows as needed: the removed piece gives most of its vertices
    /// through [`PartBuilder::new_vertex`]).
    pub fn reserve(&mut self, triangles: usize) {
        let vertices = triangles / 2 + 16;
        if self.merge {
            self.by_position.reserve(vertices);
        }
        self.positions.reserve(vertices);
        self.vertex_source.reserve(vertices);
        self.triangles.reserve(triangles);
        self.provenance.reserve(triangles);
        self.sub_cutter.reserve(triangles);
    }

    pub fn vertex(&mut self, v: Vx, target: &[DVec3], cutter: &[DVec3], new: &[DVec3]) -> u32 {
        if let Some(&id) = self.by_source.get(&v) {
            return id;
        }
        let (p, source) = match v {
            Vx::T(i) => (target[i as usize], VertexSource::Target(i)),
            Vx::C(i) => (cutter[i as usize], VertexSource::Cutter(i)),
            Vx::X(i) => (new[i as usize], VertexSource::New(i)),
        };
        let id = self.new_vertex(p, source);
        self.by_source.insert(v, id);
        id
    }

    /// The id of a vertex at `p` from `source` that the caller has not asked for before (the
    /// caller remembers the id; [`PartBuilder::vertex`] would look it up again): a new id, or
    /// with `merge` the id of an earlier vertex at the same position.
    pub fn new_vertex(&mut self, p: DVec3, source: VertexSource) -> u32 {
        let next = self.positions.len() as u32;
        let id = if self.merge {
            let key = position_bits(p);
            *self.by_position.entry(key).or_insert(next)
        } else {
            next
        };
        if id == next {
            self.positions.push(p);
            self.vertex_source.push(source);
        }
        id
    }

    /// Adds a triangle unless it has collapsed (a repeated vertex id); true when added.
    pub fn push(&mut self, tri: [u32; 3], provenance: Provenance, sub_cutter: u32) -> bool {
        if tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0] {
            return false;
        }
        self.triangles.push(tri);
        self.provenance.push(provenance);
        self.sub_cutter.push(sub_cutter);
        true
    }

    pub fn finish(self) -> Part {
        Part {
            mesh: Mesh {
                positions: self.positions,
                triangles: self.triangles,
            },
            provenance: self.provenance,
            sub_cutter: self.sub_cutter,
            vertex_source: self.vertex_source,
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
    /// The cutter surface inside the target, oriented to face out of kept: for every region
    /// solid, the cutter inside it (so where closed regions are nested, their walls overlap).
    pub walls: Part,
    /// The solid each wall triangle bounds: its region ([`crate::TargetIndex::regions`]), or
    /// [`crate::solids::OPEN_PART`] for the open regions together. Same length as
    /// `walls.mesh.triangles`.
    pub walls_solid: Vec<u32>,
    /// The target surface inside the cutter, with the target's orientation: a delta against the
    /// target, built into a [`Part`] on first read (see [`Removed`]).
    pub removed: Removed,
    /// The intersection polylines.
    pub contours: Vec<Contour>,
    /// Counters of the work done.
    pub stats: CutStats,
    /// Per-stage wall times in ms, `("total", ms)` first, when [`CutOptions::time_phases`]
    /// asked for them; empty otherwise.
    pub phases: Vec<(&'static str, f64)>,
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
        self.materialize_parts(target, false).0
    }

    /// [`CutResult::materialize`] plus the target face of every output triangle.
    pub fn materialize_with_provenance(&self, target: &Mesh) -> (Mesh, Vec<u32>) {
        self.materialize_parts(target, true)
    }

    /// The kept mesh, and the provenance when asked for (else empty). The untouched faces are
    /// copied run by run between the removed ones (`removed_faces` is ascending).
    fn materialize_parts(&self, target: &Mesh, with_provenance: bool) -> (Mesh, Vec<u32>) {
        debug_assert_eq!(target.positions.len(), self.target_vertex_count);
        let mut positions = Vec::with_capacity(target.positions.len() + self.new_positions.len());
        positions.extend_from_slice(&target.positions);
        positions.extend_from_slice(&self.new_positions);
        let keep = target.triangles.len() - self.removed_faces.len() + self.kept_new_faces.len();
        let mut triangles = Vec::with_capacity(keep);
        let mut provenance = Vec::with_capacity(if with_provenance { keep } else { 0 });
        let mut run_start = 0usize;
        let runs = self
            .removed_faces
            .iter()
            .map(|&t| t as usize)
            .chain(std::iter::once(target.triangles.len()));
        for end in runs {
            if end > run_start {
                triangles.extend_from_slice(&target.triangles[run_start..end]);
                if with_provenance {
                    provenance.extend(run_start as u32..end as u32);
                }
            }
            run_start = end + 1;
        }
        triangles.extend_from_slice(&self.kept_new_faces);
        if with_provenance {
            provenance.extend_from_slice(&self.kept_new_provenance);
        }
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

/// A position's bits (`-0.0` as `0.0`), as a key for "the same rounded position". A tuple, not
/// an array: arrays hash as one byte slice, which the integer hasher digests byte by byte.
pub(crate) type PositionBits = (u64, u64, u64);

/// See [`PositionBits`].
#[inline]
pub(crate) fn position_bits(p: DVec3) -> PositionBits {
    let b = p.to_array().map(|c| (c + 0.0).to_bits());
    (b[0], b[1], b[2])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{TargetIndex, testkit};

    /// The removed delta and the part built from it agree: every whole face and every piece is
    /// in the part with its provenance, whole faces keep their exact corners, and building it
    /// twice (lazily, or moved out) gives the same part.
    #[test]
    fn removed_part_is_built_from_the_delta() {
        let target = testkit::icosphere(4, 10.0);
        let index = TargetIndex::build(target.clone()).unwrap();
        let cutter = testkit::cube(DVec3::new(-3.0, -4.0, 5.0), DVec3::new(4.0, 3.0, 12.0));
        let r = crate::subtract(&index, &cutter).unwrap();
        let removed = &r.removed;
        assert!(!removed.whole_faces.is_empty() && !removed.piece_faces.is_empty());
        assert!(removed.whole_faces.windows(2).all(|w| w[0] < w[1]));
        // removed_faces = whole faces ∪ split faces.
        let split: std::collections::BTreeSet<u32> = r
            .kept_new_provenance
            .iter()
            .chain(&removed.piece_provenance)
            .copied()
            .collect();
        let mut all: Vec<u32> = removed.whole_faces.iter().chain(&split).copied().collect();
        all.sort_unstable();
        assert_eq!(all, r.removed_faces);
        assert!(removed.part.get().is_none(), "built before it was read");
        let part = removed.part().clone();
        assert_eq!(
            part.mesh.triangles.len(),
            removed.triangle_count_upper_bound()
        );
        let whole_start = removed.piece_faces.len();
        for (k, &t) in removed.whole_faces.iter().enumerate() {
            assert_eq!(part.provenance[whole_start + k], Provenance::Target(t));
            let got = part.mesh.triangles[whole_start + k].map(|i| part.mesh.positions[i as usize]);
            let want = target.triangles[t as usize].map(|i| target.positions[i as usize]);
            assert_eq!(got, want);
        }
        assert_eq!(r.removed.clone().into_part(), part);
        let fresh = crate::subtract(&index, &cutter).unwrap();
        assert_eq!(fresh.removed.into_part(), part);
    }

    /// The kept mesh is the target's faces minus `removed_faces` (first, last and consecutive
    /// ones included), in order, then the new faces; with and without provenance.
    #[test]
    fn materialize_drops_removed_faces_and_appends_new_ones() {
        let target = testkit::icosphere(1, 1.0);
        let n = target.triangles.len() as u32;
        let nv = target.positions.len() as u32;
        let r = CutResult {
            target_vertex_count: nv as usize,
            removed_faces: vec![0, 1, 2, 7, 9, 10, n - 1],
            new_positions: vec![DVec3::new(0.1, 0.2, 0.3)],
            kept_new_faces: vec![[0, 1, nv]],
            kept_new_provenance: vec![7],
            ..Default::default()
        };
        let want: Vec<u32> = (0..n).filter(|t| !r.removed_faces.contains(t)).collect();
        let (kept, provenance) = r.materialize_with_provenance(&target);
        let mut want_triangles: Vec<[u32; 3]> =
            want.iter().map(|&t| target.triangles[t as usize]).collect();
        want_triangles.push([0, 1, nv]);
        assert_eq!(kept.triangles, want_triangles);
        assert_eq!(provenance, [want, vec![7]].concat());
        assert_eq!(kept.positions.len(), nv as usize + 1);
        assert_eq!(r.materialize(&target), kept);
    }
}
