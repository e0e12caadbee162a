//! Keeping the opened surface from folding over.
//!
//! The opening ([`super::dffd`]) moves each vertex by a field evaluated on its own (nearest cut
//! segment, side, taper). Where the path bends sharply, or two vertices of one surface triangle
//! take their frame from different cut segments, the three moved corners can land so that the
//! triangle turns over: a bright shard or a dark crack on the opened lip. So after the field is
//! evaluated, every surface triangle with a moved corner is compared with its rest pose; one
//! whose normal turned more than [`MAX_TURN_DEG`] has its corners' displacements replaced by
//! the mean over them and their moved neighbours (the lips stay open, the kink goes; a few
//! passes), then, if it still folds, halved, and the check repeats (at most [`PASSES`] times,
//! after which such corners stay where they rest).
//!
//! The opening also moves the lips sideways onto the drawn path ([`super::drawn`]): where that
//! correction is larger than the triangles around it allow, [`unfold_correction`] shrinks the
//! correction (shrinking it step by step at the corners of each triangle it folds, and at their coincident
//! copies, so that the two lips keep their gap), not the opening.
//! Groove walls are not checked: they tilt by design as the lips open over a fixed floor.
//! Deterministic and proportional to the moved vertices, so the window and `cutaway scalpel`
//! still show the same positions bit for bit.

use glam::DVec3;

use super::dyn_mesh::{DynMesh, prev};

/// A surface triangle may turn at most this far (degrees) from its rest pose when opened.
pub const MAX_TURN_DEG: f64 = 60.0;

/// Passes that smooth a folding triangle's corners' displacements before halving them.
const SMOOTHING: usize = 4;

/// Passes in all (smoothing, then halving) before a folding triangle's corners are put back
/// at rest.
const PASSES: usize = 10;

/// Passes that shrink a folding triangle's corners' corrections (to [`CORRECTION_KEEP`] of
/// themselves) before they are dropped.
const CORRECTION_PASSES: usize = 16;

/// What a pass keeps of a folding correction (small steps keep as much of it as the triangles
/// allow).
const CORRECTION_KEEP: f64 = 0.75;

/// The surface triangles with a moved corner, and where each moved vertex is in the list.
/// It depends on which vertices move, not where to: [`unfold_correction`] and [`unfold`] of
/// the same moved vertices share one, made by whichever needs it first.
pub struct Moved {
    /// The tables by vertex and by triangle (see [`MovedTables`]).
    tables: MovedTables,
    /// The moved vertices, in the moved list's order.
    vertices: Vec<u32>,
    /// Surface triangles with a moved corner, by their three corners (each once), and their ids.
    triangles: Vec<[u32; 3]>,
    triangle_ids: Vec<u32>,
    /// Per triangle, where its corners are in the moved list (the checks of every pass look
    /// them up here), their rest positions, its rest normal and that normal's length (computed
    /// once, not at every check).
    slots: Vec<[Option<usize>; 3]>,
    rest: Vec<([DVec3; 3], DVec3, f64)>,
    /// Per moved vertex `i`, the triangles it is a corner of:
    /// `corner_of[corner_start[i]..corner_start[i + 1]]`.
    corner_start: Vec<usize>,
    corner_of: Vec<usize>,
}

/// Where each vertex is in a moved list, by vertex id, and which triangles are listed, by
/// triangle id: the unfolding looks a vertex up for every corner of every triangle around the
/// moved vertices, and hash maps of them were most of making a [`Moved`] (thousands of moved
/// vertices on a step of the live opening). The tables span the mesh; a [`Moved`] sets only the
/// entries of its own vertices and triangles and [`Moved::into_tables`] clears them again, so
/// tables kept between steps cost what is moved, not the mesh.
#[derive(Default)]
pub struct MovedTables {
    /// Per vertex, its index in the moved list, [`NOT_MOVED`] when it does not move.
    at: Vec<u32>,
    /// Per triangle, whether it is listed (bits).
    listed: Vec<u64>,
}

/// The index of a vertex that does not move, in [`MovedTables`].
const NOT_MOVED: u32 = u32::MAX;

impl Moved {
    pub(crate) fn new(mesh: &DynMesh, moved: &[(u32, DVec3)]) -> Moved {
        Moved::with_tables(mesh, moved, MovedTables::default())
    }

    /// [`Moved::new`], in `tables` (cleared, of any size: they grow to the mesh's).
    pub(crate) fn with_tables(
        mesh: &DynMesh,
        moved: &[(u32, DVec3)],
        mut tables: MovedTables,
    ) -> Moved {
        if tables.at.len() < mesh.vertex_count() {
            tables.at.resize(mesh.vertex_count(), NOT_MOVED);
        }
        let words = mesh.triangle_count().div_ceil(64);
        if tables.listed.len() < words {
            tables.listed.resize(words, 0);
        }
        let vertices: Vec<u32> = moved.iter().map(|m| m.0).collect();
        for (i, &v) in vertices.iter().enumerate() {
            tables.at[v as usize] = i as u32;
        }
        // About two surface triangles per moved vertex, more along the edge of the moved patch.
        let mut triangles: Vec<[u32; 3]> = Vec::with_capacity(3 * moved.len());
        let mut triangle_ids: Vec<u32> = Vec::with_capacity(3 * moved.len());
        let mut fan = Vec::new();
        for &v in &vertices {
            mesh.fan_into(v, &mut fan);
            for &h in &fan {
                let t = h / 3;
                let (word, bit) = ((t / 64) as usize, 1u64 << (t % 64));
                if mesh.is_wall(t) || tables.listed[word] & bit != 0 {
                    continue;
                }
                tables.listed[word] |= bit;
                triangles.push([mesh.origin(h), mesh.dest(h), mesh.origin(prev(h))]);
                triangle_ids.push(t);
            }
        }
        let at = &tables.at;
        let slot = |v: u32| Some(at[v as usize] as usize).filter(|&i| i != NOT_MOVED as usize);
        let slots: Vec<[Option<usize>; 3]> = triangles.iter().map(|t| t.map(slot)).collect();
        let rest = triangles
            .iter()
            .map(|t| {
                let p = t.map(|v| mesh.pos(v));
                let n0 = (p[1] - p[0]).cross(p[2] - p[0]);
                (p, n0, n0.length())
            })
            .collect();
        let mut corner_start = vec![0; moved.len() + 1];
        for &i in slots.iter().flatten().flatten() {
            corner_start[i + 1] += 1;
        }
        for i in 0..moved.len() {
            corner_start[i + 1] += corner_start[i];
        }
        let mut corner_of = vec![0; corner_start[moved.len()]];
        let mut fill = corner_start.clone();
        for (k, s) in slots.iter().enumerate() {
            for &i in s.iter().flatten() {
                corner_of[fill[i]] = k;
                fill[i] += 1;
            }
        }
        Moved {
            tables,
            vertices,
            triangles,
            triangle_ids,
            slots,
            rest,
            corner_start,
            corner_of,
        }
    }

    /// The tables, cleared for the next [`Moved::with_tables`].
    pub(crate) fn into_tables(self) -> MovedTables {
        let mut tables = self.tables;
        for v in self.vertices {
            tables.at[v as usize] = NOT_MOVED;
        }
        for t in self.triangle_ids {
            tables.listed[(t / 64) as usize] = 0;
        }
        tables
    }

    /// Where vertex `v` is in the moved list, `None` when it does not move.
    #[inline]
    pub(crate) fn slot(&self, v: u32) -> Option<usize> {
        let i = *self.tables.at.get(v as usize)?;
        (i != NOT_MOVED).then_some(i as usize)
    }

    /// Brings `folding` (per triangle, whether `test` holds) up to date: every triangle on the
    /// first pass (`changed` is `None`), afterwards only those with a corner among `changed`
    /// (indices into the moved list: the only ones whose shown corners moved since, so the
    /// others' answers stand). A pass costs what it changed, not the whole region.
    fn refold(
        &self,
        folding: &mut Vec<bool>,
        changed: Option<&[usize]>,
        test: impl Fn(usize) -> bool,
    ) {
        match changed {
            None => {
                folding.clear();
                folding.extend((0..self.triangles.len()).map(&test));
            }
            Some(changed) => {
                for &i in changed {
                    for &k in &self.corner_of[self.corner_start[i]..self.corner_start[i + 1]] {
                        folding[k] = test(k);
                    }
                }
            }
        }
    }

    /// Whether triangle `k` turns more than [`MAX_TURN_DEG`] from its rest pose when its moved
    /// corners are shown at `shown(index in moved)`.
    fn folds(&self, k: usize, shown: impl Fn(usize) -> DVec3) -> bool {
        let cos_max = MAX_TURN_DEG.to_radians().cos();
        let (p, n0, l0) = self.rest[k];
        let s = self.slots[k];
        let q: [DVec3; 3] = std::array::from_fn(|c| s[c].map_or(p[c], &shown));
        let n1 = (q[1] - q[0]).cross(q[2] - q[0]);
        let l1 = n1.length();
        l0 != 0.0 && (l1 == 0.0 || n0.dot(n1) < cos_max * l0 * l1)
    }
}

/// Shrinks the path corrections in `correction` (parallel to `moved`: the part of each
/// displacement that moves the lips onto the drawn path, see [`super::drawn`]) where they fold
/// a surface triangle that the rest of the displacement does not fold: shrunk at its corners
/// and their coincident copies, up to [`CORRECTION_PASSES`] times, then dropped. `moved` is
/// updated with them. `around`: the [`Moved`] of these moved vertices, made here if `None`.
/// Returns which triangles fold at `moved` when it left `moved` as it was (the first check
/// of [`unfold`] after it, already made here), `None` when it changed it or checked nothing.
pub fn unfold_correction(
    mesh: &DynMesh,
    moved: &mut [(u32, DVec3)],
    correction: &mut [DVec3],
    around: &mut Option<Moved>,
) -> Option<Vec<bool>> {
    if moved.is_empty() || correction.iter().all(|c| *c == DVec3::ZERO) {
        return None;
    }
    let m = &*around.get_or_insert_with(|| Moved::new(mesh, moved));
    // Which triangles fold as the displacements are: those the correction may be folding.
    let mut plain = Vec::new();
    m.refold(&mut plain, None, |k| m.folds(k, |i| moved[i].1));
    let mut folding = Vec::new();
    let mut shrink: Vec<usize> = Vec::new();
    for pass in 0..=CORRECTION_PASSES {
        m.refold(&mut folding, (pass > 0).then_some(&shrink[..]), |k| {
            (if pass == 0 {
                plain[k]
            } else {
                m.folds(k, |i| moved[i].1)
            }) && !m.folds(k, |i| moved[i].1 - correction[i])
        });
        shrink.clear();
        for (tri, _) in m.triangles.iter().zip(&folding).filter(|f| *f.1) {
            for &v in tri {
                if m.slot(v).is_some() {
                    for c in std::iter::once(v).chain(mesh.copies(v)) {
                        if let Some(i) = m.slot(c) {
                            shrink.push(i);
                        }
                    }
                }
            }
        }
        if shrink.is_empty() {
            return (pass == 0).then_some(plain);
        }
        shrink.sort_unstable();
        shrink.dedup();
        for &i in &shrink {
            let keep = if pass == CORRECTION_PASSES {
                0.0
            } else {
                CORRECTION_KEEP
            };
            let c = correction[i];
            correction[i] = c * keep;
            moved[i].1 -= c * (1.0 - keep);
        }
    }
    None
}

/// Shrinks the displacements in `moved` (vertex, opened position) until no surface triangle
/// with a moved corner turns more than [`MAX_TURN_DEG`] from its rest normal (see the module
/// doc). Entries that end at rest are dropped. `around`: the [`Moved`] of these moved
/// vertices, made here if `None`. `folding`: which of its triangles fold at `moved` now, when
/// known ([`unfold_correction`] gives it).
pub fn unfold(
    mesh: &DynMesh,
    moved: &mut Vec<(u32, DVec3)>,
    around: &mut Option<Moved>,
    folding: Option<Vec<bool>>,
) {
    if moved.is_empty() {
        return;
    }
    let known = folding.is_some();
    let m = &*around.get_or_insert_with(|| Moved::new(mesh, moved));
    let triangles = &m.triangles;
    let rest = |v: u32| mesh.pos(v);
    let mut fan = Vec::new();
    let mut folding = folding.unwrap_or_default();
    let mut changed: Vec<usize> = Vec::new();
    for pass in 0..=PASSES {
        if pass > 0 || !known {
            m.refold(&mut folding, (pass > 0).then_some(&changed[..]), |k| {
                m.folds(k, |i| moved[i].1)
            });
        }
        let mut shrink: Vec<u32> = Vec::new();
        for (tri, _) in triangles.iter().zip(&folding).filter(|f| *f.1) {
            shrink.extend(tri.iter().copied().filter(|&v| m.slot(v).is_some()));
        }
        if shrink.is_empty() {
            break;
        }
        shrink.sort_unstable();
        shrink.dedup();
        changed.clear();
        changed.extend(shrink.iter().filter_map(|&v| m.slot(v)));
        if pass < SMOOTHING {
            // The corners take the mean displacement of themselves and their moved neighbours
            // over surface triangles (all on their side of the cut: a lip's surface fan never
            // crosses it): the opening stays, its kink goes.
            let mut next = Vec::with_capacity(shrink.len());
            for &v in &shrink {
                let mut sum = moved[m.slot(v).expect("moved")].1 - rest(v);
                let mut count = 1.0;
                mesh.surface_fan_into(v, &mut fan);
                for &h in &fan {
                    for n in [mesh.dest(h), mesh.origin(prev(h))] {
                        if let Some(i) = m.slot(n) {
                            sum += moved[i].1 - rest(n);
                            count += 1.0;
                        }
                    }
                }
                next.push(rest(v) + sum / count);
            }
            for (&v, p) in shrink.iter().zip(next) {
                moved[m.slot(v).expect("moved")].1 = p;
            }
            continue;
        }
        for v in shrink {
            let i = m.slot(v).expect("moved");
            moved[i].1 = if pass == PASSES {
                rest(v)
            } else {
                rest(v) + (moved[i].1 - rest(v)) * 0.5
            };
        }
    }
    moved.retain(|&(v, p)| p != mesh.pos(v));
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 6 × 6 grid of unit squares on z = 0 as a scalpel mesh, and the id of vertex (i, j).
    fn grid() -> (DynMesh, impl Fn(u32, u32) -> u32) {
        let n = 6;
        let id = move |i: u32, j: u32| j * (n + 1) + i;
        let mut positions = Vec::new();
        for j in 0..=n {
            for i in 0..=n {
                positions.push(DVec3::new(i as f64, j as f64, 0.0));
            }
        }
        let mut triangles = Vec::new();
        for j in 0..n {
            for i in 0..n {
                let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
                triangles.push([a, b, c]);
                triangles.push([a, c, d]);
            }
        }
        let mesh = csg::Mesh::new(positions, triangles).unwrap();
        (DynMesh::from_mesh(&mesh), id)
    }

    /// The largest turn (degrees) of any triangle of `mesh` with `moved` applied.
    fn largest_turn(mesh: &DynMesh, moved: &[(u32, DVec3)]) -> f64 {
        let at = |v: u32| moved.iter().find(|m| m.0 == v).map_or(mesh.pos(v), |m| m.1);
        let mut worst = 0.0f64;
        for t in 0..mesh.triangle_count() {
            let [a, b, c] = mesh.triangles()[t];
            let n0 = (mesh.pos(b) - mesh.pos(a)).cross(mesh.pos(c) - mesh.pos(a));
            let n1 = (at(b) - at(a)).cross(at(c) - at(a));
            let turn = if n1.length() == 0.0 {
                180.0
            } else {
                n0.angle_between(n1).to_degrees()
            };
            worst = worst.max(turn);
        }
        worst
    }

    #[test]
    fn refolding_only_around_the_changed_corners_gives_the_full_answer() {
        let (mesh, id) = grid();
        let mut moved: Vec<(u32, DVec3)> = (0..=6)
            .flat_map(|j| (0..=3).map(move |i| (i, j)))
            .map(|(i, j)| (id(i, j), mesh.pos(id(i, j)) + DVec3::new(0.3, 0.0, 0.0)))
            .collect();
        let m = Moved::new(&mesh, &moved);
        let mut folding = Vec::new();
        m.refold(&mut folding, None, |k| m.folds(k, |i| moved[i].1));
        assert!(!folding.iter().any(|&f| f));
        // Push two vertices past their neighbours: the triangles around them fold.
        let changed: Vec<usize> = [id(3, 2), id(1, 5)]
            .iter()
            .map(|&v| m.slot(v).unwrap())
            .collect();
        for &i in &changed {
            moved[i].1 += DVec3::new(1.5, 0.4, 0.0);
        }
        let mut full = Vec::new();
        m.refold(&mut full, None, |k| m.folds(k, |i| moved[i].1));
        assert!(full.iter().any(|&f| f));
        m.refold(&mut folding, Some(&changed), |k| m.folds(k, |i| moved[i].1));
        assert_eq!(folding, full);
        // Told nothing changed, it keeps its answers (so the pass costs only what changed).
        let stale = folding.clone();
        for &i in &changed {
            moved[i].1 -= DVec3::new(1.5, 0.4, 0.0);
        }
        m.refold(&mut folding, Some(&[]), |k| m.folds(k, |i| moved[i].1));
        assert_eq!(folding, stale);
    }

    #[test]
    fn a_vertex_moved_past_its_neighbour_is_pulled_back_until_nothing_folds() {
        let (mesh, id) = grid();
        let v = id(3, 3);
        let mut moved = vec![(v, mesh.pos(v) + DVec3::new(1.6, 0.0, 0.0))];
        assert!(largest_turn(&mesh, &moved) > 90.0, "the input folds");
        unfold(&mesh, &mut moved, &mut None, None);
        let turn = largest_turn(&mesh, &moved);
        assert!(turn <= MAX_TURN_DEG, "still turned {turn}°");
        // Pulled back only as far as needed: it still moves along +x.
        assert_eq!(moved.len(), 1);
        assert!(moved[0].1.x > mesh.pos(v).x + 0.5, "{:?}", moved[0].1);
    }

    #[test]
    fn a_kink_in_a_moved_patch_is_smoothed_and_the_rest_kept_bit_for_bit() {
        let (mesh, id) = grid();
        // Columns 0..=2 move by 0.4 along +x (no fold), except (2, 3), which moves by 1.6 and
        // passes its neighbour (3, 3).
        let mut moved = Vec::new();
        for j in 0..=6 {
            for i in 0..=2 {
                let v = id(i, j);
                let dx = if (i, j) == (2, 3) { 1.6 } else { 0.4 };
                moved.push((v, mesh.pos(v) + DVec3::new(dx, 0.0, 0.0)));
            }
        }
        let before = moved.clone();
        assert!(largest_turn(&mesh, &before) > 90.0, "the input folds");
        unfold(&mesh, &mut moved, &mut None, None);
        assert!(largest_turn(&mesh, &moved) <= MAX_TURN_DEG);
        let kink = moved.iter().find(|m| m.0 == id(2, 3)).unwrap().1;
        assert!(
            kink.x > mesh.pos(id(2, 3)).x + 0.4,
            "the kinked vertex keeps at least its neighbours' opening: {kink:?}"
        );
        // Vertices of no folding triangle (two rings away from the kink) are untouched.
        for (v, p) in before {
            let q = mesh.pos(v);
            if (q - mesh.pos(id(2, 3))).length() > 2.5 {
                let now = moved.iter().find(|m| m.0 == v).unwrap().1;
                assert_eq!(now, p, "vertex {v} changed");
            }
        }
    }
}
