//! Cross cuts: a stroke meeting an existing slit.
//!
//! A slit's two lips are coincident in the rest pose (their vertices are copies of each other,
//! see [`DynMesh::copies`]). When the walk reaches a lip and the surface ends ahead, the cut
//! either crosses to the mate lip and goes on (T-cut becoming an X-cut; the junction vertex ends
//! with 4 copies) or, when the stroke meets the slit at less than the merge angle (15°, the
//! interactive cross-cutting paper), merges into it and ends there (a T-junction: 2 copies).
//! A lip edge is always split together with its mate, so lips stay vertex-for-vertex mates.

use glam::DVec3;

use super::dyn_mesh::{DynMesh, NO_TWIN, is_real, prev};
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

/// Whether half-edge `h` runs along a lip: a surface triangle's edge on the boundary or against a
/// groove wall.
pub fn is_lip(mesh: &DynMesh, h: u32) -> bool {
    let g = mesh.twin(h);
    g == NO_TWIN || (is_real(g) && mesh.is_wall(g / 3) && !mesh.is_wall(h / 3))
}

/// Acute angle (degrees) between the stroke direction `dir` and the lip at vertex `v` (a slit's
/// boundary or a groove's lip); 90 when `v` is on no lip.
pub fn angle_to_lip(mesh: &DynMesh, v: u32, dir: DVec3, scratch: &mut Vec<u32>) -> f64 {
    let pv = mesh.pos(v);
    let n = mesh.surface_normal(v, scratch);
    let mut d = dir;
    d -= n * d.dot(n);
    mesh.surface_fan_into(v, scratch);
    let (Some(&first), Some(&last)) = (scratch.first(), scratch.last()) else {
        return 90.0;
    };
    // The lip's direction at `v`: the chord between its two lip neighbours (smoother than
    // one edge where the slit zigzags along snapped vertices).
    let mut ends = Vec::with_capacity(2);
    if is_lip(mesh, first) {
        ends.push(mesh.pos(mesh.dest(first)));
    }
    if is_lip(mesh, prev(last)) {
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

/// The surface edge on the other lip of a groove coincident with lip half-edge `h` (`a → b`,
/// its twin a wall): the half-edge `b' → a'` between copies of `b` and `a`.
pub fn find_groove_mate(mesh: &DynMesh, h: u32, scratch: &mut Vec<u32>) -> Option<u32> {
    let (a, b) = (mesh.origin(h), mesh.dest(h));
    for bc in std::iter::once(b).chain(mesh.copies(b)) {
        mesh.fan_into(bc, scratch);
        for &f in scratch.iter() {
            if f != h
                && f / 3 != h / 3
                && mesh.same_point(mesh.dest(f), a)
                && is_lip(mesh, f)
                && is_real(mesh.twin(f))
            {
                return Some(f);
            }
        }
    }
    None
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
    // The copy the cut leaves most straight toward `q` (a groove's junction also leaves a copy
    // on the near side; its exits turn away from the stroke).
    let mut best: Option<(f64, u32)> = None;
    for c in copies {
        if let Some(cs) = scalpel.exit_cos(c, q)
            && best.is_none_or(|(b, _)| cs > b)
        {
            best = Some((cs, c));
        }
    }
    let (_, mate) = best?;
    let mut scratch = Vec::new();
    if angle_to_lip(&scalpel.mesh, mate, dir, &mut scratch) < scalpel.merge_angle_deg() {
        return None;
    }
    Some(mate)
}
