//! # A changed mesh drawn as its uploaded original plus a small patch
//!
//! A live re-cut while painting, or a scalpel step, changes a few thousand triangles of a model
//! that may have millions. Uploading the whole changed mesh per change (24 bytes per vertex and
//! 12 per triangle, plus the smooth normals computed over all of it) costs the UI thread tens of
//! milliseconds at 2M triangles. A [`MeshDelta`] says instead: draw the **base** mesh the
//! renderer already holds on the GPU, with some of its faces **hidden**, plus a small **patch**
//! mesh. The renderer hides faces by overwriting their three indices in the base's index buffer
//! with a degenerate triangle, and puts them back when they are shown again, with one small
//! compute dispatch per change (see `renderer.rs`); only the patch and the changed indices cross
//! the bus. Every frame still draws the base with one draw call.
//!
//! ## Same pixels as the whole mesh
//! The renderer shades with area-weighted smooth normals ([`super::vertices::mesh_vertices`]):
//! a face that changes changes the normals of its corners, and those corners are shared with
//! unchanged faces. So the patch holds, besides the changed faces, the **ring**: every unchanged
//! face that uses a *dirty* vertex (a corner of a changed face, before or after the change, or a
//! vertex that moved). Those faces are hidden in the base too. Patch vertex normals are summed
//! in the order the whole mesh would sum them (its faces in ascending order, the added faces
//! last), so they are bit for bit the normals of the changed mesh: for a dirty vertex every face
//! of it is in the patch; a patch vertex that is not dirty keeps its base normal, recomputed from
//! its base faces ([`VertexFaces`]). Positions are the same `f64` values. So the base-plus-patch
//! draws the same triangles with the same vertex data as the whole changed mesh would.
//!
//! ## Cost
//! Building a delta is proportional to the change (plus one O(N) [`VertexFaces`] per base mesh,
//! built once off the UI thread for the live cut, once per stroke for the scalpel); nothing
//! scans the base.

use std::collections::HashMap;
use std::sync::Arc;

use csg::Mesh;
use glam::DVec3;

use super::vertices::Vertex;
use super::wall_split::wall_corner_normal;

/// For every vertex of a mesh, the faces that use it, ascending (a face that uses a vertex twice
/// is listed twice, as the normal sum counts it twice). Compressed rows: `faces[offsets[v] ..
/// offsets[v + 1]]`.
#[derive(Clone, Debug, Default)]
pub struct VertexFaces {
    /// `vertex_count + 1` entries, non-decreasing, last = `faces.len()`.
    offsets: Vec<u32>,
    faces: Vec<u32>,
}

impl VertexFaces {
    /// Counting sort of the corners: O(N), two passes.
    pub fn build(mesh: &Mesh) -> VertexFaces {
        let nv = mesh.positions.len();
        let mut offsets = vec![0u32; nv + 1];
        for tri in &mesh.triangles {
            for &v in tri {
                if let Some(o) = offsets.get_mut(v as usize + 1) {
                    *o += 1;
                }
            }
        }
        for v in 0..nv {
            offsets[v + 1] += offsets[v];
        }
        let mut next = offsets.clone();
        let mut faces = vec![0u32; offsets[nv] as usize];
        for (t, tri) in mesh.triangles.iter().enumerate() {
            for &v in tri {
                if let Some(slot) = next.get_mut(v as usize) {
                    faces[*slot as usize] = t as u32;
                    *slot += 1;
                }
            }
        }
        VertexFaces { offsets, faces }
    }

    /// The faces using vertex `v` (empty for an unknown vertex).
    pub fn of(&self, v: u32) -> &[u32] {
        let v = v as usize;
        match (self.offsets.get(v), self.offsets.get(v + 1)) {
            (Some(&a), Some(&b)) => &self.faces[a as usize..b as usize],
            _ => &[],
        }
    }

    pub fn vertex_count(&self) -> usize {
        self.offsets.len().saturating_sub(1)
    }
}

/// A mesh drawn as `base` minus `hidden` plus `patch` (see the module documentation).
#[derive(Debug, Default)]
pub struct MeshDelta {
    /// The model mesh the renderer holds (matched by `Arc` identity with a scene model's mesh).
    pub base: Arc<Mesh>,
    /// Base faces not drawn, ascending and unique.
    pub hidden: Vec<u32>,
    /// The changed faces, the ring of unchanged faces around them and the added faces, in the
    /// changed mesh's order, compacted.
    pub patch: Mesh,
    /// `patch`'s vertices as the GPU takes them, normals those of the whole changed mesh; the
    /// corners of wall faces follow `patch`'s vertices ([`super::wall_split`]).
    pub vertices: Vec<Vertex>,
    /// `patch`'s triangles as drawn: wall faces on corners of their own, the others as in
    /// `patch`.
    pub triangles: Vec<[u32; 3]>,
}

impl MeshDelta {
    /// The whole mesh this delta draws (tests: compare with the mesh it stands for): the base
    /// faces not hidden, in order, then the patch. Vertices are not shared between the two
    /// parts.
    pub fn compose(&self) -> Mesh {
        let mut hidden = self.hidden.iter().peekable();
        let mut out = Mesh {
            positions: self.base.positions.clone(),
            triangles: Vec::with_capacity(self.base.triangles.len()),
        };
        for (t, tri) in self.base.triangles.iter().enumerate() {
            if hidden.peek() == Some(&&(t as u32)) {
                hidden.next();
                continue;
            }
            out.triangles.push(*tri);
        }
        out.append(&self.patch);
        out
    }
}

/// A change of a base mesh, in the changed mesh's vertex numbering: base vertex `v` is still
/// `v`; vertices past the base's are new.
pub struct Change<'a> {
    pub base: &'a Arc<Mesh>,
    /// The faces using each base vertex.
    pub faces: &'a VertexFaces,
    /// Base faces that changed or are gone (the faces of `moved` vertices need not be named).
    pub touched: &'a [u32],
    /// The changed mesh's version of a touched face (`None`: gone).
    pub current: &'a dyn Fn(u32) -> Option<[u32; 3]>,
    /// Faces the change added, in order; they come after all base faces.
    pub added: &'a [[u32; 3]],
    /// Position of a vertex of the changed mesh.
    pub position: &'a dyn Fn(u32) -> DVec3,
    /// Base vertices whose position changed (any order; duplicates allowed).
    pub moved: &'a [u32],
    /// Whether a face of the changed mesh is an incision wall (a base face that did not change
    /// keeps what the base was drawn with).
    pub wall: &'a dyn Fn(u32) -> bool,
}

/// Builds the delta of `change` (cost proportional to the change and its ring).
pub fn build(change: &Change) -> MeshDelta {
    let base = change.base.as_ref();
    let nb = base.triangles.len() as u32;
    let nv = base.positions.len() as u32;
    // A moved vertex changes the shape, so the normal, of every face of it.
    let mut touched: Vec<u32> = change.touched.iter().copied().filter(|&t| t < nb).collect();
    for &v in change.moved {
        if v < nv {
            touched.extend(change.faces.of(v).iter().filter(|&&f| f < nb));
        }
    }
    touched.sort_unstable();
    touched.dedup();
    // Dirty vertices: their set of faces, or their position, changed.
    let mut dirty: Vec<u32> = Vec::with_capacity(6 * touched.len() + 3 * change.added.len());
    for &t in &touched {
        dirty.extend_from_slice(&base.triangles[t as usize]);
        if let Some(tri) = (change.current)(t) {
            dirty.extend_from_slice(&tri);
        }
    }
    for tri in change.added {
        dirty.extend_from_slice(tri);
    }
    dirty.extend(change.moved.iter().copied().filter(|&v| v < nv));
    dirty.sort_unstable();
    dirty.dedup();
    let is_dirty = |v: u32| dirty.binary_search(&v).is_ok();
    // The ring: unchanged faces with a dirty corner.
    let mut ring: Vec<u32> = Vec::new();
    for &v in dirty.iter().take_while(|&&v| v < nv) {
        for &f in change.faces.of(v) {
            if f < nb && touched.binary_search(&f).is_err() {
                ring.push(f);
            }
        }
    }
    ring.sort_unstable();
    ring.dedup();
    // Patch faces in the changed mesh's order: base ids ascending (ring and changed faces
    // interleaved), then the added faces.
    let mut hidden = Vec::with_capacity(touched.len() + ring.len());
    let mut faces: Vec<[u32; 3]> = Vec::with_capacity(touched.len() + ring.len());
    // The changed mesh's id of each patch face.
    let mut ids: Vec<u32> = Vec::with_capacity(touched.len() + ring.len() + change.added.len());
    let (mut i, mut j) = (0, 0);
    while i < touched.len() || j < ring.len() {
        let take_touched = j >= ring.len() || (i < touched.len() && touched[i] < ring[j]);
        if take_touched {
            let t = touched[i];
            i += 1;
            hidden.push(t);
            if let Some(tri) = (change.current)(t) {
                faces.push(tri);
                ids.push(t);
            }
        } else {
            let f = ring[j];
            j += 1;
            hidden.push(f);
            faces.push(base.triangles[f as usize]);
            ids.push(f);
        }
    }
    faces.extend_from_slice(change.added);
    ids.extend((0..change.added.len() as u32).map(|k| nb + k));
    // Compact the vertices.
    let mut id_of: HashMap<u32, u32> = HashMap::with_capacity(faces.len());
    let mut source: Vec<u32> = Vec::with_capacity(faces.len());
    let triangles: Vec<[u32; 3]> = faces
        .iter()
        .map(|tri| {
            tri.map(|v| {
                *id_of.entry(v).or_insert_with(|| {
                    source.push(v);
                    (source.len() - 1) as u32
                })
            })
        })
        .collect();
    let positions: Vec<DVec3> = source.iter().map(|&v| (change.position)(v)).collect();
    let patch = Mesh {
        positions,
        triangles,
    };
    let wall: Vec<bool> = ids.iter().map(|&t| (change.wall)(t)).collect();
    // Surface normals: summed over the patch's surface faces in order (complete for dirty
    // vertices), from the base's surface faces for the others.
    let mut normals = vec![DVec3::ZERO; patch.positions.len()];
    for t in 0..patch.triangles.len() {
        if wall[t] {
            continue;
        }
        let n = patch.face_normal_scaled(t);
        for &k in &patch.triangles[t] {
            normals[k as usize] += n;
        }
    }
    for (k, &v) in source.iter().enumerate() {
        if v < nv && !is_dirty(v) {
            let mut n = DVec3::ZERO;
            for &f in change.faces.of(v) {
                if !(change.wall)(f) {
                    n += base.face_normal_scaled(f as usize);
                }
            }
            normals[k] = n;
        }
    }
    let mut vertices = super::vertices::vertices_with_normals(&patch.positions, &normals);
    let triangles = patch_walls(&patch, &source, &wall, &mut vertices, &|v| {
        (v < nv && !is_dirty(v)).then(|| {
            change
                .faces
                .of(v)
                .iter()
                .filter(|&&f| (change.wall)(f))
                .map(|&f| base.face_normal_scaled(f as usize))
                .collect()
        })
    });
    MeshDelta {
        base: change.base.clone(),
        hidden,
        patch,
        vertices,
        triangles,
    }
}

/// The patch's wall faces on corners of their own (appended to `vertices`, as
/// [`super::wall_split::drawn`] draws the whole mesh): each corner's normal sums the wall faces
/// of its vertex, from the patch for a dirty vertex and from `clean_walls` (the scaled normals
/// of the base's wall faces of a clean vertex, ascending) for the others. Returns the drawn
/// triangles.
fn patch_walls(
    patch: &Mesh,
    source: &[u32],
    wall: &[bool],
    vertices: &mut Vec<Vertex>,
    clean_walls: &dyn Fn(u32) -> Option<Vec<DVec3>>,
) -> Vec<[u32; 3]> {
    let mut triangles = patch.triangles.clone();
    if !wall.contains(&true) {
        return triangles;
    }
    let normals: Vec<DVec3> = (0..patch.triangles.len())
        .map(|t| {
            if wall[t] {
                patch.face_normal_scaled(t)
            } else {
                DVec3::ZERO
            }
        })
        .collect();
    let mut around: HashMap<u32, Vec<usize>> = HashMap::new();
    for t in (0..patch.triangles.len()).filter(|&t| wall[t]) {
        for &k in &patch.triangles[t] {
            around.entry(k).or_default().push(t);
        }
    }
    let mut clean: HashMap<u32, Vec<DVec3>> = HashMap::new();
    for t in (0..patch.triangles.len()).filter(|&t| wall[t]) {
        let first = vertices.len() as u32;
        for &k in &patch.triangles[t] {
            let v = source[k as usize];
            if !clean.contains_key(&k)
                && let Some(n) = clean_walls(v)
            {
                clean.insert(k, n);
            }
            let n = match clean.get(&k) {
                Some(base) => wall_corner_normal(normals[t], base.iter().copied()),
                None => wall_corner_normal(normals[t], around[&k].iter().map(|&u| normals[u])),
            };
            vertices.push(super::wall_split::vertex(
                patch.positions[k as usize],
                n,
                true,
            ));
        }
        triangles[t] = [first, first + 1, first + 2];
    }
    triangles
}

/// The kept part of a cut as a delta against the cut's target (`result` from `csg::subtract` on
/// the index of `target`): the removed and split faces hidden, the kept pieces of split faces
/// added. Draws exactly what `result.materialize(target)` would, with the target's incision
/// walls `walls` (ascending) and the kept pieces of them as walls.
pub fn of_cut(
    target: &Arc<Mesh>,
    faces: &VertexFaces,
    result: &csg::CutResult,
    walls: &[u32],
) -> MeshDelta {
    let n = target.positions.len() as u32;
    let position = |v: u32| {
        if v < n {
            target.positions[v as usize]
        } else {
            result.new_positions[(v - n) as usize]
        }
    };
    build(&Change {
        base: target,
        faces,
        touched: &result.removed_faces,
        current: &|_| None,
        added: &result.kept_new_faces,
        position: &position,
        moved: &[],
        wall: &|t| {
            let nb = target.triangles.len() as u32;
            let from = if t < nb {
                Some(t)
            } else {
                result.kept_new_provenance.get((t - nb) as usize).copied()
            };
            from.is_some_and(|f| walls.binary_search(&f).is_ok())
        },
    })
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// One drawn triangle: (position, normal, wall flag) bits of each corner.
    pub(crate) type Corners = [[u32; 7]; 3];

    /// The vertex data of every triangle corner as the renderer draws `triangles` over
    /// `vertices`, triangles in order.
    pub(crate) fn drawn_corners(triangles: &[[u32; 3]], vertices: &[Vertex]) -> Vec<Corners> {
        triangles
            .iter()
            .map(|tri| {
                tri.map(|i| {
                    let v = vertices[i as usize];
                    let [x, y, z] = v.position_in_world.map(f32::to_bits);
                    let [a, b, c] = v.normal_in_world.map(f32::to_bits);
                    [x, y, z, a, b, c, v.wall.to_bits()]
                })
            })
            .collect()
    }

    /// What the renderer draws for the whole of `mesh` with wall faces `walls`.
    pub(crate) fn mesh_corners(mesh: &Mesh, walls: &[u32]) -> Vec<Corners> {
        let d = crate::cutting::wall_split::drawn(mesh, walls);
        drawn_corners(&d.triangles, &d.vertices)
    }

    /// Corner lists compared as multisets (the patch draws the ring after the other faces).
    pub(crate) fn sorted(mut corners: Vec<Corners>) -> Vec<Corners> {
        corners.sort_unstable();
        corners
    }

    /// Panics (with counts, not the lists) unless `a` and `b` are the same multiset.
    pub(crate) fn assert_same_corners(a: Vec<Corners>, b: Vec<Corners>, what: &str) {
        let (a, b) = (sorted(a), sorted(b));
        if a != b {
            let set_b: std::collections::HashSet<_> = b.iter().collect();
            let missing = a.iter().filter(|x| !set_b.contains(x)).count();
            panic!(
                "{what}: {} vs {} triangles drawn, {missing} of the first not in the second",
                a.len(),
                b.len()
            );
        }
    }

    /// What a delta draws, corner by corner: the base faces not hidden (with the base's vertex
    /// data, its walls `base_walls`), then the patch (with its own).
    pub(crate) fn delta_corners(delta: &MeshDelta, base_walls: &[u32]) -> Vec<Corners> {
        let base = crate::cutting::wall_split::drawn(&delta.base, base_walls);
        let mut kept = Vec::new();
        let mut hidden = delta.hidden.iter().peekable();
        for (t, tri) in base.triangles.iter().enumerate() {
            if hidden.peek() == Some(&&(t as u32)) {
                hidden.next();
            } else {
                kept.push(*tri);
            }
        }
        let mut out = drawn_corners(&kept, &base.vertices);
        out.extend(drawn_corners(&delta.triangles, &delta.vertices));
        out
    }

    #[test]
    fn vertex_faces_list_every_corner_in_ascending_order() {
        let mesh = csg::testkit::icosphere(2, 1.0);
        let vf = VertexFaces::build(&mesh);
        assert_eq!(vf.vertex_count(), mesh.positions.len());
        let mut count = 0;
        for v in 0..mesh.positions.len() as u32 {
            let f = vf.of(v);
            assert!(f.windows(2).all(|w| w[0] <= w[1]));
            for &t in f {
                assert!(mesh.triangles[t as usize].contains(&v));
            }
            count += f.len();
        }
        assert_eq!(count, 3 * mesh.triangles.len());
        assert!(vf.of(u32::MAX).is_empty());
    }

    /// A cut's delta draws exactly the materialized kept mesh: the same triangles with the same
    /// vertex positions and normals, bit for bit; and its patch is small.
    #[test]
    fn a_cut_delta_draws_the_materialized_kept_part_bit_for_bit() {
        let target = Arc::new(csg::testkit::icosphere(5, 10.0));
        let index = csg::TargetIndex::build(target.clone()).unwrap();
        let cutter = csg::testkit::cube(DVec3::new(-3.0, -4.0, 5.0), DVec3::new(4.0, 3.0, 12.0));
        let result = csg::subtract(&index, &cutter).unwrap();
        let faces = VertexFaces::build(&target);
        let delta = of_cut(&target, &faces, &result, &[]);
        let kept = result.materialize(&target);
        assert_same_corners(
            delta_corners(&delta, &[]),
            mesh_corners(&kept, &[]),
            "delta vs kept",
        );
        assert!(delta.hidden.windows(2).all(|w| w[0] < w[1]));
        assert!(delta.hidden.len() > result.removed_faces.len(), "no ring");
        assert!(
            delta.patch.triangle_count() * 4 < target.triangle_count(),
            "patch {} of {}",
            delta.patch.triangle_count(),
            target.triangle_count()
        );
        let composed = delta.compose();
        assert!((composed.area() - kept.area()).abs() < 1e-9 * kept.area());
    }

    /// An in-place change (faces rewritten, faces added, a vertex moved) draws as the whole
    /// changed mesh would.
    #[test]
    fn an_edit_delta_draws_the_edited_mesh_bit_for_bit() {
        let base = Arc::new(csg::testkit::icosphere(3, 5.0));
        let mut edited = (*base).clone();
        // Split face 10 at its centroid (rewrite it, add two), and move vertex 3 outward.
        let [a, b, c] = edited.triangles[10];
        let centroid = edited.corners(10).iter().sum::<DVec3>() / 3.0;
        let m = edited.positions.len() as u32;
        edited.positions.push(centroid * 1.05);
        edited.triangles[10] = [a, b, m];
        edited.triangles.push([b, c, m]);
        edited.triangles.push([c, a, m]);
        edited.positions[3] *= 1.1;
        let faces = VertexFaces::build(&base);
        let nb = base.triangles.len();
        let current = |t: u32| Some(edited.triangles[t as usize]);
        let position = |v: u32| edited.positions[v as usize];
        let delta = build(&Change {
            base: &base,
            faces: &faces,
            touched: &[10],
            current: &current,
            added: &edited.triangles[nb..],
            position: &position,
            moved: &[3],
            wall: &|_| false,
        });
        assert_same_corners(
            delta_corners(&delta, &[]),
            mesh_corners(&edited, &[]),
            "delta vs edited",
        );
    }

    /// On a mesh with incision walls, a change that splits a wall face and moves a lip vertex
    /// draws as the whole changed mesh would, walls split from the surface, bit for bit.
    #[test]
    fn a_delta_on_a_grooved_mesh_draws_its_split_lips_bit_for_bit() {
        let (mesh, walls) = crate::cutting::wall_split::tests::grooved_sheet();
        let base = Arc::new(mesh);
        let mut edited = (*base).clone();
        let w = walls[5];
        let [a, b, c] = edited.triangles[w as usize];
        let centroid = edited.corners(w as usize).iter().sum::<DVec3>() / 3.0;
        let m = edited.positions.len() as u32;
        edited.positions.push(centroid + DVec3::new(0.0, 0.1, 0.0));
        edited.triangles[w as usize] = [a, b, m];
        edited.triangles.push([b, c, m]);
        edited.triangles.push([c, a, m]);
        let lip = edited
            .positions
            .iter()
            .position(|&p| p == DVec3::new(0.0, -1.0, 0.0))
            .unwrap() as u32;
        edited.positions[lip as usize].z += 0.1;
        let faces = VertexFaces::build(&base);
        let nb = base.triangles.len() as u32;
        let current = |t: u32| Some(edited.triangles[t as usize]);
        let position = |v: u32| edited.positions[v as usize];
        let is_wall = |t: u32| t >= nb || walls.binary_search(&t).is_ok();
        let delta = build(&Change {
            base: &base,
            faces: &faces,
            touched: &[w],
            current: &current,
            added: &edited.triangles[nb as usize..],
            position: &position,
            moved: &[lip],
            wall: &is_wall,
        });
        let edited_walls: Vec<u32> = (0..edited.triangles.len() as u32)
            .filter(|&t| is_wall(t))
            .collect();
        let whole = mesh_corners(&edited, &edited_walls);
        assert_same_corners(
            delta_corners(&delta, &walls),
            whole.clone(),
            "delta vs edited",
        );
        // The split matters: drawn without walls, the same change draws other normals.
        assert_ne!(sorted(mesh_corners(&edited, &[])), sorted(whole));
        assert!(delta.triangles.len() < edited.triangles.len());
    }
}
