//! The drawn samples' feet on the surface, kept between steps by the live opening.
//!
//! The path corrections ([`super::drawn::corrections`]) put each tool sample onto the surface
//! first: the nearest point of the triangles searched outward from the cut vertex its step
//! reached ([`closest_face_near`]). Every step recomputed the corrections of the whole incision,
//! so every sample's foot: a search of [`FOOT_SEARCH`] triangles each, which made a third of
//! a step's opening on a long stroke and grew with it. A foot only changes when the mesh
//! changes where its search went, and a step edits the mesh around its own cut only.
//!
//! [`Feet`] keeps each foot, by its start vertex and sample, with the vertices its search
//! depended on: those of the triangles it examined, of their neighbours over twins (the ones
//! it could have examined next: their distances decided the order and the stop) and of the
//! start vertex's triangles and its copies'. Every change of the mesh logs the vertices of the
//! triangles it touches ([`DynMesh::edits_since`]): [`Feet::forget`] drops the feet watching
//! one of them, so a kept foot is the one a new search would give, bit for bit.

use glam::DVec3;

use super::cut_point::closest_face_near_examining;
use super::dyn_mesh::{DynMesh, is_real};
use csg::fast_hash::FastMap;

/// Triangles examined to put a sample onto the surface (searched outward from the cut vertex
/// its step reached).
pub const FOOT_SEARCH: usize = 64;

/// A foot's start vertex and sample (its coordinates' bits).
type Key = (u32, [u64; 3]);

/// The feet kept between steps (see the module doc).
#[derive(Default)]
pub struct Feet {
    /// The feet by slot: the foot kept there (`None` when free) and the slot's generation
    /// (counted up as its foot is dropped, so a watch left on another vertex knows it is old).
    feet: Vec<(Option<(Key, DVec3)>, u32)>,
    free_feet: Vec<u32>,
    /// The feet kept, by key: their slot.
    known: FastMap<Key, u32>,
    /// Per watched vertex, its last watch in `watches`. A foot watches a hundred vertices and
    /// more; a list of its own for each of them was a hundred allocations per foot.
    watch: FastMap<u32, u32>,
    /// The watches of all vertices, each a foot's slot and generation and the vertex's watch
    /// before ([`NONE`] for its first); a forgotten vertex's watches are reused.
    watches: Vec<Watch>,
    free_watches: Vec<u32>,
}

#[derive(Clone, Copy)]
struct Watch {
    slot: u32,
    generation: u32,
    before: u32,
}

/// The end of a vertex's watch list.
const NONE: u32 = u32::MAX;

impl Feet {
    /// Drops every foot.
    pub fn clear(&mut self) {
        *self = Feet::default();
    }

    /// Drops the feet whose search depended on one of the vertices `edited`.
    pub fn forget(&mut self, edited: &[u32]) {
        for v in edited {
            let Some(mut at) = self.watch.remove(v) else {
                continue;
            };
            while at != NONE {
                let w = self.watches[at as usize];
                let (foot, generation) = &mut self.feet[w.slot as usize];
                if *generation == w.generation
                    && let Some((key, _)) = foot.take()
                {
                    self.known.remove(&key);
                    *generation = generation.wrapping_add(1);
                    self.free_feet.push(w.slot);
                }
                self.free_watches.push(at);
                at = w.before;
            }
        }
        // Watches of dropped feet pile up on the vertices never edited; start over once they
        // outnumber the feet by far.
        if self.watch.len() > 64 * self.known.len() + 65_536 {
            self.clear();
        }
    }

    /// The foot of sample `q` searched from vertex `v` ([`foot`]), kept or searched now.
    pub fn foot(&mut self, mesh: &DynMesh, v: u32, q: DVec3) -> DVec3 {
        let key = (v, q.to_array().map(f64::to_bits));
        if let Some(&slot) = self.known.get(&key) {
            return self.feet[slot as usize].0.expect("a known foot is kept").1;
        }
        let mut examined = Vec::new();
        let p = search(mesh, v, q, &mut examined);
        // The triangles, then their vertices, each once (sorted lists: a few hundred entries,
        // cheaper than sets).
        let mut seen: Vec<u32> = Vec::with_capacity(4 * examined.len() + 16);
        let mut fan = Vec::new();
        for s in std::iter::once(v).chain(mesh.copies(v)) {
            mesh.fan_into(s, &mut fan);
            seen.extend(fan.iter().map(|h| h / 3));
        }
        for &t in &examined {
            seen.push(t);
            for k in 0..3 {
                let g = mesh.twin(3 * t + k);
                if is_real(g) {
                    seen.push(g / 3);
                }
            }
        }
        seen.sort_unstable();
        seen.dedup();
        let mut watched: Vec<u32> = seen
            .iter()
            .flat_map(|&t| mesh.triangles()[t as usize])
            .collect();
        watched.sort_unstable();
        watched.dedup();
        let slot = self.free_feet.pop().unwrap_or_else(|| {
            self.feet.push((None, 0));
            (self.feet.len() - 1) as u32
        });
        let generation = self.feet[slot as usize].1;
        self.feet[slot as usize].0 = Some((key, p));
        self.known.insert(key, slot);
        for v in watched {
            let at = self.free_watches.pop().unwrap_or_else(|| {
                self.watches.push(Watch {
                    slot,
                    generation,
                    before: NONE,
                });
                (self.watches.len() - 1) as u32
            });
            let before = self.watch.insert(v, at).unwrap_or(NONE);
            self.watches[at as usize] = Watch {
                slot,
                generation,
                before,
            };
        }
        p
    }
}

/// The foot of sample `q` on the surface, searched from cut vertex `v`: the nearest point of
/// the triangles [`closest_face_near`] finds, or `q` itself when it finds none.
pub fn foot(mesh: &DynMesh, v: u32, q: DVec3) -> DVec3 {
    search(mesh, v, q, &mut Vec::new())
}

fn search(mesh: &DynMesh, v: u32, q: DVec3, examined: &mut Vec<u32>) -> DVec3 {
    closest_face_near_examining(mesh, v, q, FOOT_SEARCH, examined).map_or(q, |(t, b, _)| {
        let [x, y, z] = mesh.triangles()[t as usize].map(|u| mesh.pos(u));
        x * b.x + y * b.y + z * b.z
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalpel::cut_point::closest_face_near;

    #[test]
    fn a_kept_foot_is_searched_again_once_the_mesh_changes_under_it_and_only_then() {
        let mut mesh = DynMesh::from_mesh(&csg::testkit::icosphere(4, 10.0));
        let v = 0;
        let q = mesh.pos(v) * 1.02 + DVec3::new(0.3, -0.2, 0.1);
        let far = (0..mesh.vertex_count() as u32)
            .max_by(|&a, &b| {
                let d = |x: u32| mesh.pos(x).distance_squared(mesh.pos(v));
                d(a).total_cmp(&d(b))
            })
            .unwrap();
        let mut feet = Feet::default();
        let first = feet.foot(&mesh, v, q);
        assert_eq!(first, foot(&mesh, v, q));
        // A change on the far side of the sphere keeps the foot.
        let cursor = mesh.edit_cursor();
        mesh.set_pos(far, mesh.pos(far) * 1.01);
        feet.forget(mesh.edits_since(cursor).unwrap());
        assert_eq!(feet.known.len(), 1);
        // Moving the corners of the triangle under the sample drops it; the kept foot is then
        // the new one.
        let cursor = mesh.edit_cursor();
        let mut examined = Vec::new();
        closest_face_near_examining(&mesh, v, q, FOOT_SEARCH, &mut examined);
        let (t, _, _) = closest_face_near(&mesh, v, q, FOOT_SEARCH).unwrap();
        assert!(examined.contains(&t));
        for c in mesh.triangles()[t as usize] {
            mesh.set_pos(c, mesh.pos(c) * 1.05);
        }
        feet.forget(mesh.edits_since(cursor).unwrap());
        assert!(feet.known.is_empty());
        let again = feet.foot(&mesh, v, q);
        assert_eq!(again, foot(&mesh, v, q));
        assert_ne!(again, first);
    }

    #[test]
    fn a_watch_left_by_a_dropped_foot_drops_no_later_foot_in_its_slot() {
        let mesh = DynMesh::from_mesh(&csg::testkit::icosphere(4, 10.0));
        let mut feet = Feet::default();
        let near = |v: u32| mesh.pos(v) * 1.02;
        feet.foot(&mesh, 0, near(0));
        // The vertices the first foot watches (all its watches are in slot 0).
        let watched: Vec<u32> = feet.watch.keys().copied().collect();
        assert!(watched.len() > 2);
        feet.forget(&watched[..1]);
        assert!(feet.known.is_empty());
        // A foot on the far side takes the freed slot and watches none of those vertices.
        let far = (0..mesh.vertex_count() as u32)
            .max_by(|&a, &b| {
                let d = |x: u32| mesh.pos(x).distance_squared(mesh.pos(0));
                d(a).total_cmp(&d(b))
            })
            .unwrap();
        feet.foot(&mesh, far, near(far));
        assert_eq!(feet.known.values().copied().collect::<Vec<_>>(), vec![0]);
        assert!(
            watched
                .iter()
                .all(|w| !feet.watch.get(w).is_some_and(|&at| {
                    let w = feet.watches[at as usize];
                    w.generation == feet.feet[0].1
                }))
        );
        // The first foot's other watches are old: forgetting them keeps the new foot.
        feet.forget(&watched[1..]);
        assert_eq!(feet.known.len(), 1);
        assert_eq!(
            feet.foot(&mesh, far, near(far)),
            foot(&mesh, far, near(far))
        );
    }
}
