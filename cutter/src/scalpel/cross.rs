//! Cross cuts: a stroke meeting an existing slit.
//!
//! A slit's two lips are coincident in the rest pose (their vertices are copies of each other,
//! see [`DynMesh::copies`]). When the walk reaches a lip and the surface ends ahead, the cut
//! either crosses to the mate lip and goes on (T-cut becoming an X-cut; the junction vertex ends
//! with 4 copies) or, when the stroke meets the slit at less than the merge angle (15°, the
//! interactive cross-cutting paper), merges into it and ends there (a T-junction: 2 copies).
//! A lip edge is always split together with its mate, so lips stay vertex-for-vertex mates.

use glam::DVec3;

use super::dyn_mesh::{DynMesh, NO_TWIN, prev};
use super::step::Scalpel;

/// The coincident boundary half-edge on the other lip of boundary half-edge `h` (`a → b`): the
/// boundary half-edge `b' → a'` between copies of `b` and `a`.
pub fn find_mate(mesh: &DynMesh, h: u32, scratch: &mut Vec<u32>) -> Option<u32> {
    let (a, b) = (mesh.origin(h), mesh.dest(h));
    // `b` itself counts: at a crack tip both lips share the tip vertex.
    for bc in std::iter::once(b).chain(mesh.copies(b)) {
        mesh.fan_into(bc, scratch);
        if let Some(&f) = scratch.first()
            && f != h
            && mesh.twin(f) == NO_TWIN
            && mesh.same_point(mesh.dest(f), a)
        {
            return Some(f);
        }
    }
    None
}

/// Acute angle (degrees) between the stroke direction `dir` and the lip at boundary vertex `v`;
/// 90 when `v` has no boundary edge.
pub fn angle_to_lip(mesh: &DynMesh, v: u32, dir: DVec3, scratch: &mut Vec<u32>) -> f64 {
    let pv = mesh.pos(v);
    let n = mesh.vertex_normal(v, scratch);
    let mut d = dir;
    d -= n * d.dot(n);
    mesh.fan_into(v, scratch);
    let (Some(&first), Some(&last)) = (scratch.first(), scratch.last()) else {
        return 90.0;
    };
    // The lip's direction at `v`: the chord between its two boundary neighbours (smoother than
    // one edge where the slit zigzags along snapped vertices).
    let mut ends = Vec::with_capacity(2);
    if mesh.twin(first) == NO_TWIN {
        ends.push(mesh.pos(mesh.dest(first)));
    }
    if mesh.twin(prev(last)) == NO_TWIN {
        ends.push(mesh.pos(mesh.origin(prev(last))));
    }
    let e = match ends.as_slice() {
        [a, b] if a != b => *a - *b,
        [a, ..] => *a - pv,
        [] => return 90.0,
    };
    let mut best: f64 = 90.0;
    let l = e.length() * d.length();
    if l > 0.0 {
        let c = (e.dot(d) / l).abs().min(1.0);
        best = c.acos().to_degrees();
    }
    best
}

/// The copy of boundary vertex `v` from which the walk toward `q` can go on (crossing a slit),
/// or `None` when there is none or the stroke (direction `dir`, measured over several path
/// vertices: the last edge alone zigzags along snapped vertices) meets the slit under the merge
/// angle.
pub fn crossing_mate(scalpel: &mut Scalpel, v: u32, q: DVec3, dir: DVec3) -> Option<u32> {
    let copies = scalpel.mesh.copies(v);
    if copies.is_empty() {
        return None;
    }
    // Measure the angle on the far lip: its fan is untouched by the cut arriving here, so its
    // two boundary neighbours are both lip vertices.
    let mate = copies.into_iter().find(|&c| scalpel.exit_exists(c, q))?;
    let mut scratch = Vec::new();
    if angle_to_lip(&scalpel.mesh, mate, dir, &mut scratch) < scalpel.merge_angle_deg() {
        return None;
    }
    Some(mate)
}
