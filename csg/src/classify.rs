//! Stage 4 of the boolean: inside tests for what the contour does not classify locally.
//!
//! Most statuses come from the exact crossing signs (see `boolean.rs`). What is left:
//! - a cutter component: the region solids one of its vertices lies in (ray parity per closed
//!   region, the generalized winding number for the open regions together);
//! - a target region the cutter does not cross but whose box overlaps it, or a touched face
//!   crossed only by contour loops: one ray-parity test of one vertex against the cutter.
//!
//! Rays run along +x from the point to beyond the other mesh's box; they are segments, so the
//! same exact EF/FE predicates (and the same tie-break) decide every crossing.

use crate::exact::{self, LPoint};
use crate::intersect::PreparedCutter;
use crate::solids::{OPEN_PART, solid_of_face};
use crate::split::OUT;
use crate::target::{IBox, TargetIndex};

/// Status of target point `p` relative to the cutter: `OUT`, or `1 + sub-cutter id`.
pub(crate) fn target_point_status(cutter: &PreparedCutter, p: &LPoint) -> u32 {
    if p[0] > cutter.bounds.max[0] {
        return OUT;
    }
    let far = [cutter.bounds.max[0] + 1, p[1], p[2]];
    let mut parity = vec![false; cutter.components as usize];
    for f in 0..cutter.triangles.len() as u32 {
        let b = &cutter.face_boxes[f as usize];
        if b.max[0] < p[0]
            || b.min[1] > p[1]
            || b.max[1] < p[1]
            || b.min[2] > p[2]
            || b.max[2] < p[2]
        {
            continue;
        }
        let [a, bb, c] = cutter.face_points(f);
        if exact::segment_crosses_cutter_face(p, &far, a, bb, c) {
            let k = cutter.face_component[f as usize] as usize;
            parity[k] = !parity[k];
        }
    }
    parity
        .iter()
        .position(|&odd| odd)
        .map_or(OUT, |k| k as u32 + 1)
}

/// The region solids that perturbed cutter point `a'` lies in, ascending (see
/// [`crate::solids`]): for the closed regions, exact ray parity per region (a region's
/// cavities are its own faces, so parity is its non-zero winding); for the open regions
/// together ([`OPEN_PART`]), the generalized winding number (≥ 1/2) at the point's rounded
/// position from the target's fast winding-number tree ([`crate::winding`]), less the winding
/// of the closed regions that contain it.
pub(crate) fn cutter_point_solids(
    target: &TargetIndex,
    a: &LPoint,
    a_world: glam::DVec3,
) -> Vec<u32> {
    let mut hits: Vec<u32> = Vec::new();
    let any_closed = target.component_closed.iter().any(|&c| c);
    if any_closed && a[0] <= target.bounds.max[0] {
        let far = [target.bounds.max[0] + 1, a[1], a[2]];
        let query = IBox {
            min: [a[0], a[1], a[2]],
            max: [far[0], a[1], a[2]],
        };
        let tris = &target.mesh.triangles;
        target.faces_in_box(&query, |t| {
            let tri = tris[t as usize];
            if tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0] {
                return;
            }
            let solid = solid_of_face(target, t);
            if solid == OPEN_PART {
                return;
            }
            let [u, v, w] = target.face_points(t);
            if exact::cutter_edge_crosses_target_face(a, &far, u, v, w).is_some() {
                hits.push(solid);
            }
        });
    }
    hits.sort_unstable();
    let mut inside: Vec<u32> = hits
        .chunk_by(|x, y| x == y)
        .filter(|run| run.len() % 2 == 1)
        .map(|run| run[0])
        .collect();
    if !target.is_closed() {
        let w = match &target.winding {
            Some(tree) => tree.winding_number(&target.mesh, a_world),
            None => crate::winding::winding_number_exact(&target.mesh, a_world),
        };
        let closed_winding: f64 = inside
            .iter()
            .map(|&r| f64::from(target.regions.volume_sign[r as usize]))
            .sum();
        if w - closed_winding >= 0.5 {
            inside.push(OPEN_PART);
        }
    }
    inside
}
