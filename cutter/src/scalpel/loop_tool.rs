//! Loop tool: a closed stroke that cuts through detaches what it encloses.
//!
//! The stroke's last walk aims at its own start vertex and ends on it (see
//! `Scalpel::end_stroke`); opening that last edge gives the start vertex its second slit edge,
//! so its fan falls apart and the surface inside the loop is no longer connected to the rest.
//! The detached piece is the smaller (by area) of the components found around the start vertex.

use std::collections::VecDeque;

use super::dyn_mesh::{DynMesh, is_real};

/// Triangles of the edge-connected component containing triangle `seed`.
pub fn component(mesh: &DynMesh, seed: u32) -> Vec<u32> {
    let mut seen = std::collections::HashSet::new();
    let mut queue = VecDeque::from([seed]);
    seen.insert(seed);
    let mut out = Vec::new();
    while let Some(t) = queue.pop_front() {
        out.push(t);
        for k in 0..3 {
            let g = mesh.twin(3 * t + k);
            if is_real(g) && seen.insert(g / 3) {
                queue.push_back(g / 3);
            }
        }
    }
    out
}

/// The pieces a closed loop through `start` separated, all but the largest (by area), as
/// compacted meshes. Empty when the loop did not separate the surface.
pub fn detached_pieces(mesh: &DynMesh, start: u32) -> Vec<csg::Mesh> {
    let mut ring = vec![start];
    ring.extend(mesh.copies(start));
    let mut comps: Vec<Vec<u32>> = Vec::new();
    let mut fan = Vec::new();
    for v in ring {
        mesh.fan_into(v, &mut fan);
        let Some(&h) = fan.first() else { continue };
        let t = h / 3;
        if comps.iter().any(|c| c.contains(&t)) {
            continue;
        }
        comps.push(component(mesh, t));
    }
    if comps.len() < 2 {
        return Vec::new();
    }
    let area = |c: &Vec<u32>| -> f64 {
        c.iter()
            .map(|&t| mesh.face_normal_scaled(t).length() * 0.5)
            .sum()
    };
    let largest = (0..comps.len())
        .max_by(|&a, &b| area(&comps[a]).total_cmp(&area(&comps[b])))
        .unwrap_or(0);
    comps
        .iter()
        .enumerate()
        .filter(|(i, _)| *i != largest)
        .map(|(_, c)| {
            csg::Mesh {
                positions: mesh.positions.clone(),
                triangles: c.iter().map(|&t| mesh.triangles[t as usize]).collect(),
            }
            .compacted()
        })
        .collect()
}
