//! The scalpel mesh validator, run after every step in tests (and by the CLI at the end).
//!
//! Checks (notes §4 I1–I5): array lengths, indices, twin symmetry with reversed endpoints (so every
//! split edge is split in both faces: no T-junction in the connectivity), one outgoing half-edge
//! per used vertex, every vertex one fan (no bow-tie, except the input's own), no duplicate
//! directed edge (edge-manifold, consistently oriented), copy rings of coincident vertices. It
//! also reports the topology the scenario corpus compares: components, boundary loops, Euler
//! characteristic. [`t_junction_near`] is the geometric I4 check and [`min_angle_deg`] the Q0 one.

use std::collections::HashSet;

use glam::DVec3;

use super::dyn_mesh::{DynMesh, NO_TWIN, NONMANIFOLD, is_real, next, prev};

/// Topology of the surface.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TopologyReport {
    /// Vertices used by a triangle.
    pub vertices: usize,
    pub edges: usize,
    pub faces: usize,
    pub boundary_edges: usize,
    pub boundary_loops: usize,
    /// Edge-connected components.
    pub components: usize,
    /// V - E + F.
    pub euler: i64,
    /// No boundary edge.
    pub closed: bool,
    /// No non-manifold edge or vertex, consistently oriented.
    pub manifold: bool,
}

/// A broken invariant (a bug in the scalpel, never the user's input).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ValidationError {
    #[error("array lengths disagree: {0}")]
    Lengths(String),
    #[error("triangle {0} has a bad or repeated vertex index")]
    BadTriangle(u32),
    #[error("half-edge {0} and its twin are not mutual or not reversed")]
    Twin(u32),
    #[error("vertex {0} has no valid outgoing half-edge")]
    VertexHalfEdge(u32),
    #[error("vertex {0}'s triangles form more than one fan")]
    BowTie(u32),
    #[error("directed edge {0} -> {1} is used twice")]
    DuplicateEdge(u32, u32),
    #[error("copy ring of vertex {0} is broken or not coincident")]
    CopyRing(u32),
}

/// Validates `mesh` and reports its topology.
pub fn validate(mesh: &DynMesh) -> Result<TopologyReport, ValidationError> {
    let DynMesh {
        positions,
        triangles,
        twin,
        vert_he,
        next_copy,
        singular,
        floor,
        wall_tri,
        ..
    } = mesh;
    let nv = positions.len();
    let nt = triangles.len();
    if twin.len() != 3 * nt
        || vert_he.len() != nv
        || next_copy.len() != nv
        || singular.len() != nv
        || floor.len() != nv
        || wall_tri.len() != nt
    {
        return Err(ValidationError::Lengths(format!(
            "{nv} positions, {nt} triangles, {} twins, {} vertex half-edges, {} copy links",
            twin.len(),
            vert_he.len(),
            next_copy.len()
        )));
    }
    let mut corners = vec![0u32; nv];
    for (t, tri) in triangles.iter().enumerate() {
        if tri.iter().any(|&i| i as usize >= nv) {
            return Err(ValidationError::BadTriangle(t as u32));
        }
        if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2])
            && !(0..3).all(|k| twin[3 * t + k] == NONMANIFOLD)
        {
            return Err(ValidationError::BadTriangle(t as u32));
        }
        for &i in tri {
            corners[i as usize] += 1;
        }
    }
    let mut nonmanifold_edges = 0usize;
    let mut boundary_edges = 0usize;
    let mut interior_half = 0usize;
    for h in 0..(3 * nt) as u32 {
        let g = twin[h as usize];
        if g == NO_TWIN {
            boundary_edges += 1;
        } else if g == NONMANIFOLD {
            nonmanifold_edges += 1;
        } else {
            if g as usize >= 3 * nt
                || twin[g as usize] != h
                || mesh.origin(g) != mesh.dest(h)
                || mesh.dest(g) != mesh.origin(h)
            {
                return Err(ValidationError::Twin(h));
            }
            interior_half += 1;
        }
    }
    let mut directed: Vec<(u32, u32)> = Vec::with_capacity(3 * nt);
    for h in 0..(3 * nt) as u32 {
        if twin[h as usize] != NONMANIFOLD {
            directed.push((mesh.origin(h), mesh.dest(h)));
        }
    }
    directed.sort_unstable();
    if let Some(w) = directed.windows(2).find(|w| w[0] == w[1]) {
        return Err(ValidationError::DuplicateEdge(w[0].0, w[0].1));
    }
    let mut fan = Vec::new();
    let mut used = 0usize;
    let mut nonmanifold_vertices = 0usize;
    for v in 0..nv as u32 {
        if corners[v as usize] == 0 {
            continue;
        }
        used += 1;
        let h = vert_he[v as usize];
        if h == NO_TWIN || h as usize >= 3 * nt || mesh.origin(h) != v {
            return Err(ValidationError::VertexHalfEdge(v));
        }
        mesh.fan_from(h, &mut fan);
        if fan.len() != corners[v as usize] as usize {
            if singular[v as usize]
                || fan.iter().any(|&x| {
                    twin[x as usize] == NONMANIFOLD || twin[prev(x) as usize] == NONMANIFOLD
                })
            {
                nonmanifold_vertices += 1;
            } else {
                return Err(ValidationError::BowTie(v));
            }
        }
        // Copy ring: a cycle of coincident vertices.
        let mut c = next_copy[v as usize];
        let mut steps = 0;
        while c != v {
            if c as usize >= nv || positions[c as usize] != positions[v as usize] || steps > 64 {
                return Err(ValidationError::CopyRing(v));
            }
            c = next_copy[c as usize];
            steps += 1;
        }
    }
    // Boundary loops: follow boundary half-edges; at each destination take its outgoing boundary
    // half-edge (the first of its open fan).
    let mut seen = vec![false; 3 * nt];
    let mut loops = 0usize;
    for h in 0..(3 * nt) as u32 {
        if twin[h as usize] != NO_TWIN || seen[h as usize] {
            continue;
        }
        loops += 1;
        let mut x = h;
        let mut guard = 0usize;
        while !seen[x as usize] && guard <= 3 * nt {
            seen[x as usize] = true;
            guard += 1;
            // Rotate clockwise around dest(x) from next(x) until the boundary.
            let mut y = next(x);
            loop {
                let g = twin[y as usize];
                if !is_real(g) {
                    break;
                }
                y = next(g);
            }
            if twin[y as usize] != NO_TWIN {
                break;
            }
            x = y;
        }
    }
    // Components by union-find over twins.
    let mut parent: Vec<u32> = (0..nt as u32).collect();
    fn find(p: &mut [u32], mut x: u32) -> u32 {
        while p[x as usize] != x {
            p[x as usize] = p[p[x as usize] as usize];
            x = p[x as usize];
        }
        x
    }
    for h in 0..(3 * nt) as u32 {
        let g = twin[h as usize];
        if is_real(g) {
            let (a, b) = (find(&mut parent, h / 3), find(&mut parent, g / 3));
            if a != b {
                parent[a as usize] = b;
            }
        }
    }
    let components = (0..nt as u32)
        .filter(|&t| find(&mut parent, t) == t)
        .count();
    let edges = interior_half / 2 + boundary_edges + nonmanifold_edges;
    Ok(TopologyReport {
        vertices: used,
        edges,
        faces: nt,
        boundary_edges,
        boundary_loops: loops,
        components,
        euler: used as i64 - edges as i64 + nt as i64,
        closed: boundary_edges == 0 && nonmanifold_edges == 0,
        manifold: nonmanifold_edges == 0 && nonmanifold_vertices == 0,
    })
}

/// Smallest corner angle of triangle `t`, in degrees.
pub fn min_angle_deg(mesh: &DynMesh, t: u32) -> f64 {
    let [a, b, c] = mesh.triangles[t as usize].map(|v| mesh.pos(v));
    let angle = |p: DVec3, q: DVec3, r: DVec3| {
        let (u, v) = (q - p, r - p);
        let l = u.length() * v.length();
        if l == 0.0 {
            0.0
        } else {
            (u.dot(v) / l).clamp(-1.0, 1.0).acos().to_degrees()
        }
    };
    angle(a, b, c).min(angle(b, c, a)).min(angle(c, a, b))
}

/// Whether vertex `v` lies (within `1e-9` of the edge's length) inside an edge of its 2-ring it
/// is not an end of (a geometric T-junction). Lip edges (both ends copied) are skipped: a groove's
/// two lips coincide in the rest pose but are separate sheets joined through the walls.
pub fn t_junction_near(mesh: &DynMesh, v: u32) -> bool {
    let pv = mesh.pos(v);
    let mut fan = Vec::new();
    let mut fan2 = Vec::new();
    let mut tris = HashSet::new();
    mesh.fan_into(v, &mut fan);
    for &h in &fan {
        for w in [mesh.dest(h), mesh.origin(prev(h))] {
            mesh.fan_into(w, &mut fan2);
            tris.extend(fan2.iter().map(|&x| x / 3));
        }
    }
    for t in tris {
        let tri = mesh.triangles[t as usize];
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            let (pa, pb) = (mesh.pos(a), mesh.pos(b));
            if pa == pv || pb == pv {
                continue;
            }
            // A lip edge of a groove: its coincident mate lip is another sheet of the surface
            // (walls between them), split on its own; both lips coincide only in the rest pose.
            if !mesh.copies(a).is_empty() && !mesh.copies(b).is_empty() {
                continue;
            }
            let ab = pb - pa;
            let l2 = ab.length_squared();
            if l2 == 0.0 {
                continue;
            }
            let s = (pv - pa).dot(ab) / l2;
            if s > 1e-9 && s < 1.0 - 1e-9 && (pa + ab * s).distance(pv) <= 1e-9 * l2.sqrt() {
                return true;
            }
        }
    }
    false
}
