//! Interpolatory subdivision of a closed quad mesh (the rounded and freeform cuts, thesis 3.3.2.4).
//!
//! The thesis uses Kobbelt's interpolatory scheme for quadrilateral meshes. This is a variant of
//! it with the same structure and the two properties the editor relies on:
//!
//! - **interpolation**: every original vertex stays where it is, so dragging a plane's vertex
//!   still controls the smooth cutter;
//! - **closedness**: each level splits an `n`-gon into `n` quads around a face point, with one new
//!   point per edge shared by both faces of the edge, so a closed mesh stays closed and oriented.
//!
//! Edge points use the four-point rule `(−p₋₁ + 9p₀ + 9p₁ − p₂) / 16` along the edge. At a vertex
//! of valence 4 the outer neighbour `p₋₁` is the vertex opposite the edge (the neighbour sharing
//! no face with it), exactly as in Kobbelt's regular case; at other valences (the end-cap corners
//! of a box chain have valence 3, a wedge's axis vertices many) the outer neighbour is the
//! reflection `2p₀ − p₁`, which makes the rule fall back to a locally linear one instead of
//! Kobbelt's extraordinary-vertex stencil. Face points are the Boolean sum of the edge points,
//! `(2/n)·Σ edge points − (1/n)·Σ corners`, which reproduces the centre of any bilinear face.

use std::collections::HashMap;

use glam::DVec3;

use crate::cutter::QuadMesh;

/// `levels` rounds of interpolatory subdivision of a closed, outward polygon mesh. Level 0 returns
/// a copy. The output is all quads.
pub fn subdivide(mesh: &QuadMesh, levels: u32) -> QuadMesh {
    let mut m = mesh.clone();
    for _ in 0..levels {
        m = subdivide_once(&m);
    }
    m
}

fn subdivide_once(mesh: &QuadMesh) -> QuadMesh {
    let nv = mesh.positions.len();
    // Neighbours of each vertex, and the faces around each undirected edge.
    let mut neighbours: Vec<Vec<u32>> = vec![Vec::new(); nv];
    let mut edge_faces: HashMap<(u32, u32), Vec<usize>> = HashMap::new();
    for (fi, f) in mesh.faces.iter().enumerate() {
        for k in 0..f.len() {
            let a = f[k];
            let b = f[(k + 1) % f.len()];
            if !neighbours[a as usize].contains(&b) {
                neighbours[a as usize].push(b);
            }
            if !neighbours[b as usize].contains(&a) {
                neighbours[b as usize].push(a);
            }
            edge_faces.entry(key(a, b)).or_default().push(fi);
        }
    }
    let p = &mesh.positions;
    // The vertex across `v` from neighbour `w` (valence 4), else the reflection of `w` about `v`.
    let outer = |v: u32, w: u32| -> DVec3 {
        let ns = &neighbours[v as usize];
        if ns.len() == 4 {
            let faces = edge_faces.get(&key(v, w)).map(Vec::as_slice).unwrap_or(&[]);
            let shares_face = |x: u32| faces.iter().any(|&fi| mesh.faces[fi].contains(&x));
            let opposite: Vec<u32> = ns
                .iter()
                .copied()
                .filter(|&x| x != w && !shares_face(x))
                .collect();
            if let [o] = opposite[..] {
                return p[o as usize];
            }
        }
        p[v as usize] * 2.0 - p[w as usize]
    };
    let mut positions = p.clone();
    let mut edge_point: HashMap<(u32, u32), u32> = HashMap::new();
    let mut edges: Vec<(u32, u32)> = edge_faces.keys().copied().collect();
    edges.sort_unstable();
    for (a, b) in edges {
        let q = (-outer(a, b) + p[a as usize] * 9.0 + p[b as usize] * 9.0 - outer(b, a)) / 16.0;
        edge_point.insert((a, b), positions.len() as u32);
        positions.push(q);
    }
    let mut faces = Vec::with_capacity(mesh.faces.len() * 4);
    for f in &mesh.faces {
        let n = f.len();
        let e: Vec<u32> = (0..n)
            .map(|k| edge_point[&key(f[k], f[(k + 1) % n])])
            .collect();
        let sum_e: DVec3 = e.iter().map(|&i| positions[i as usize]).sum();
        let sum_v: DVec3 = f.iter().map(|&i| p[i as usize]).sum();
        let centre = sum_e * (2.0 / n as f64) - sum_v / n as f64;
        let c = positions.len() as u32;
        positions.push(centre);
        for k in 0..n {
            let prev = e[(k + n - 1) % n];
            faces.push(vec![f[k], e[k], c, prev]);
        }
    }
    QuadMesh { positions, faces }
}

fn key(a: u32, b: u32) -> (u32, u32) {
    if a < b { (a, b) } else { (b, a) }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cutter::{CutKind, Cutter};
    use crate::plane::BoundedPlane;

    #[test]
    fn subdivided_box_chain_interpolates_and_stays_closed() {
        let planes = (0..4)
            .map(|i| {
                let x = i as f64;
                BoundedPlane::from_front_edge(
                    DVec3::new(x, 0.1 * x * x, 1.0),
                    DVec3::new(x, 0.1 * x * x, -1.0),
                    DVec3::Y,
                    0.7,
                )
            })
            .collect();
        let c = Cutter {
            kind: CutKind::Curving,
            smooth: false,
            planes,
        };
        let q = c.quad_mesh();
        let s = subdivide(&q, 2);
        s.check_closed().unwrap();
        assert_eq!(s.faces.len(), q.faces.len() * 16);
        assert_eq!(&s.positions[..q.positions.len()], &q.positions[..]);
        assert!(s.volume() > 0.0);
        // Smoothing moves the faces: the volume changes but stays comparable.
        assert!((s.volume() / q.volume() - 1.0).abs() < 0.5);
    }

    #[test]
    fn flat_grid_stays_flat() {
        // A unit cube: every new point of a face stays on the cube's bounding box.
        let c = Cutter {
            kind: CutKind::Curving,
            smooth: false,
            planes: vec![
                BoundedPlane::from_front_edge(DVec3::new(0., 0., 1.), DVec3::ZERO, DVec3::Y, 1.0),
                BoundedPlane::from_front_edge(DVec3::new(1., 0., 1.), DVec3::X, DVec3::Y, 1.0),
            ],
        };
        let s = subdivide(&c.quad_mesh(), 1);
        s.check_closed().unwrap();
        for p in &s.positions {
            assert!(
                p.cmpge(DVec3::splat(-0.2)).all() && p.cmple(DVec3::splat(1.2)).all(),
                "{p}"
            );
        }
    }
}
