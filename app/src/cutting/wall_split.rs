//! # Incision walls drawn as walls: a hard edge at the lips
//!
//! A scalpel groove's walls meet the surface at its lips at a steep angle. Smooth normals
//! averaged over every face of a lip vertex blend the wall into the surface, which draws bright
//! smeared shards along the lips, and in the model's colour the opened incision does not read as
//! two lips and the inside of the tissue. So a mesh with wall faces
//! ([`crate::scene::wall_faces::WallFaces`]) is drawn with its lip vertices split:
//!
//! - vertex `v` of the mesh stays vertex `v` of the draw data with the **surface** normal: the
//!   area-weighted sum over its non-wall faces only (zero for a floor vertex, which no surface
//!   face uses and no drawn triangle then names);
//! - every wall face gets three vertices of its own, appended after the mesh's (wall face of
//!   rank `k` among the walls: `n + 3k .. n + 3k + 3`), flagged as wall (drawn in the wall
//!   colour) with the **wall** normal of each corner: the sum over the wall faces of that vertex
//!   whose normals are within [`CREASE_DEG`] of this face's. So a wall is smooth along the lip,
//!   while the two walls of a V groove keep their crease at the floor.
//!
//! The faces keep their order and ids, so the renderer's hidden faces
//! ([`super::delta`]) address the same index words; [`drawn_triangle`] gives a face's indices
//! back. A mesh without walls is drawn exactly as [`super::vertices::mesh_vertices`] draws it.
//!
//! Sums run over faces in ascending order, as the delta's patch sums them, so a patch draws bit
//! for bit what the whole mesh would (see [`super::delta`], "Same pixels as the whole mesh").

use std::collections::HashMap;

use csg::Mesh;
use glam::DVec3;

use super::vertices::Vertex;

/// Wall faces meeting at a vertex at less than this angle share a smooth normal there; more,
/// and the edge between them stays hard (the two walls at a groove's floor).
pub const CREASE_DEG: f64 = 45.0;

/// The draw data of a mesh with wall faces: vertices and the triangles indexing them, face for
/// face in the mesh's order.
#[derive(Clone, Debug, Default)]
pub struct DrawnMesh {
    pub vertices: Vec<Vertex>,
    pub triangles: Vec<[u32; 3]>,
}

/// Whether a wall face with scaled normal `a` is smoothed with one with scaled normal `b`.
fn same_wall(a: DVec3, b: DVec3) -> bool {
    a.dot(b) >= CREASE_DEG.to_radians().cos() * a.length() * b.length()
}

/// The wall normal (unnormalized) of a corner of a wall face with scaled normal `own`: the sum of
/// the scaled normals `around` (every wall face of the corner's vertex, ascending, this one
/// included) that [`same_wall`] keeps.
pub(crate) fn wall_corner_normal(own: DVec3, around: impl Iterator<Item = DVec3>) -> DVec3 {
    let mut sum = DVec3::ZERO;
    for n in around {
        if same_wall(own, n) {
            sum += n;
        }
    }
    sum
}

/// A GPU vertex at `p` with the unnormalized normal `n`.
pub(crate) fn vertex(p: DVec3, n: DVec3, wall: bool) -> Vertex {
    Vertex {
        position_in_world: p.as_vec3().to_array(),
        normal_in_world: n
            .try_normalize()
            .unwrap_or(DVec3::ZERO)
            .as_vec3()
            .to_array(),
        wall: if wall { 1.0 } else { 0.0 },
    }
}

/// Draw data of `mesh` whose faces `walls` (ascending, unique, in range) are incision walls.
/// Cost: one pass over the faces plus the walls.
pub fn drawn(mesh: &Mesh, walls: &[u32]) -> DrawnMesh {
    let nv = mesh.positions.len();
    let mut sums = vec![DVec3::ZERO; nv];
    let mut next_wall = walls.iter().peekable();
    for t in 0..mesh.triangles.len() {
        if next_wall.next_if(|&&w| w as usize == t).is_some() {
            continue;
        }
        let n = mesh.face_normal_scaled(t);
        for &i in &mesh.triangles[t] {
            sums[i as usize] += n;
        }
    }
    let mut vertices: Vec<Vertex> = Vec::with_capacity(nv + 3 * walls.len());
    vertices.extend(
        mesh.positions
            .iter()
            .zip(&sums)
            .map(|(&p, &n)| vertex(p, n, false)),
    );
    drop(sums);
    let normals: Vec<DVec3> = walls
        .iter()
        .map(|&f| mesh.face_normal_scaled(f as usize))
        .collect();
    let mut around: HashMap<u32, Vec<usize>> = HashMap::with_capacity(2 * walls.len());
    for (k, &f) in walls.iter().enumerate() {
        for &v in &mesh.triangles[f as usize] {
            around.entry(v).or_default().push(k);
        }
    }
    let mut triangles = mesh.triangles.clone();
    for (k, &f) in walls.iter().enumerate() {
        let tri = mesh.triangles[f as usize];
        for &v in &tri {
            let n = wall_corner_normal(normals[k], around[&v].iter().map(|&j| normals[j]));
            vertices.push(vertex(mesh.positions[v as usize], n, true));
        }
        triangles[f as usize] = wall_triangle(nv, k);
    }
    DrawnMesh {
        vertices,
        triangles,
    }
}

/// The drawn indices of the wall face of rank `k` in a mesh of `vertex_count` vertices.
pub(crate) fn wall_triangle(vertex_count: usize, k: usize) -> [u32; 3] {
    let first = (vertex_count + 3 * k) as u32;
    [first, first + 1, first + 2]
}

/// The indices face `f` of `mesh` is drawn with when its walls are `walls` (what [`drawn`]
/// made of it); `None` for a face `mesh` does not have.
pub fn drawn_triangle(mesh: &Mesh, walls: &[u32], f: u32) -> Option<[u32; 3]> {
    let tri = *mesh.triangles.get(f as usize)?;
    Some(match walls.binary_search(&f) {
        Ok(k) => wall_triangle(mesh.positions.len(), k),
        Err(_) => tri,
    })
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::cutting::vertices::mesh_vertices;

    /// A sheet in z = 0 (normals up) with a V groove along x: the sheet is split into two lips
    /// at y = ±1, the groove's walls go down to a floor line at depth 2. Returns the mesh and its
    /// wall faces.
    pub(crate) fn grooved_sheet() -> (Mesh, Vec<u32>) {
        let mut mesh = Mesh::default();
        let top = |mesh: &mut Mesh, x: f64, y: f64, z: f64| -> u32 {
            let p = DVec3::new(x, y, z);
            if let Some(i) = mesh.positions.iter().position(|&q| q == p) {
                return i as u32;
            }
            mesh.positions.push(p);
            (mesh.positions.len() - 1) as u32
        };
        let xs = [-4.0, -2.0, 0.0, 2.0, 4.0];
        let mut walls = Vec::new();
        for w in xs.windows(2) {
            let (x0, x1) = (w[0], w[1]);
            let a0 = top(&mut mesh, x0, -4.0, 0.0);
            let a1 = top(&mut mesh, x1, -4.0, 0.0);
            let l0 = top(&mut mesh, x0, -1.0, 0.0);
            let l1 = top(&mut mesh, x1, -1.0, 0.0);
            let f0 = top(&mut mesh, x0, 0.0, -2.0);
            let f1 = top(&mut mesh, x1, 0.0, -2.0);
            let r0 = top(&mut mesh, x0, 1.0, 0.0);
            let r1 = top(&mut mesh, x1, 1.0, 0.0);
            let b0 = top(&mut mesh, x0, 4.0, 0.0);
            let b1 = top(&mut mesh, x1, 4.0, 0.0);
            let quad = |m: &mut Mesh, a: u32, b: u32, c: u32, d: u32| {
                m.triangles.push([a, b, c]);
                m.triangles.push([a, c, d]);
            };
            quad(&mut mesh, a0, a1, l1, l0);
            let n = mesh.triangles.len() as u32;
            quad(&mut mesh, l0, l1, f1, f0);
            quad(&mut mesh, f0, f1, r1, r0);
            walls.extend(n..n + 4);
            quad(&mut mesh, r0, r1, b1, b0);
        }
        (mesh, walls)
    }

    fn normal(v: &Vertex) -> DVec3 {
        DVec3::from(v.normal_in_world.map(f64::from))
    }

    #[test]
    fn the_grooved_sheet_faces_up_and_into_the_groove() {
        let (mesh, walls) = grooved_sheet();
        mesh.sanity_check().unwrap();
        assert_eq!(walls.len(), 16);
        for f in 0..mesh.triangles.len() {
            let n = mesh.face_normal_scaled(f);
            assert!(n.z > 0.0, "face {f}: {n}");
        }
    }

    /// No drawn vertex is shared between a wall face and a surface face; lip vertices get a
    /// surface copy (up) and a wall copy (along the wall, far from up); the two walls keep their
    /// crease at the floor; wall corners carry the wall flag, others not.
    #[test]
    fn lip_vertices_are_split_into_a_surface_and_a_wall_copy() {
        let (mesh, walls) = grooved_sheet();
        let d = drawn(&mesh, &walls);
        assert_eq!(d.triangles.len(), mesh.triangles.len());
        let is_wall = |f: usize| walls.binary_search(&(f as u32)).is_ok();
        let mut wall_vertices = std::collections::HashSet::new();
        let mut surface_vertices = std::collections::HashSet::new();
        for (f, tri) in d.triangles.iter().enumerate() {
            for (k, &i) in tri.iter().enumerate() {
                let v = d.vertices[i as usize];
                // Same position as the mesh's corner.
                let p = mesh.positions[mesh.triangles[f][k] as usize]
                    .as_vec3()
                    .to_array();
                assert_eq!(v.position_in_world, p);
                assert_eq!(v.wall, if is_wall(f) { 1.0 } else { 0.0 }, "face {f}");
                if is_wall(f) {
                    wall_vertices.insert(i);
                } else {
                    surface_vertices.insert(i);
                }
            }
        }
        assert!(wall_vertices.is_disjoint(&surface_vertices));
        // A lip vertex in the middle: (0, -1, 0).
        let lip = mesh
            .positions
            .iter()
            .position(|&p| p == DVec3::new(0.0, -1.0, 0.0))
            .unwrap() as u32;
        let surface = normal(&d.vertices[lip as usize]);
        assert!(surface.dot(DVec3::Z) > 0.999, "surface normal {surface}");
        let wall_left = DVec3::new(0.0, 2.0, 1.0).normalize();
        for (f, tri) in mesh.triangles.iter().enumerate() {
            for k in 0..3 {
                if !is_wall(f) {
                    continue;
                }
                let n = normal(&d.vertices[d.triangles[f][k] as usize]);
                let face = mesh.face_normal_scaled(f).normalize();
                // Smooth along its own wall, hard against the other wall and the surface.
                assert!(n.dot(face) > 0.99, "face {f} corner {k}: {n} vs {face}");
                if tri[k] == lip {
                    assert!((n - wall_left).length() < 1e-6, "{n}");
                    assert!(n.dot(surface) < 0.5);
                }
            }
        }
    }

    #[test]
    fn without_walls_the_draw_data_is_the_smooth_mesh() {
        let (mesh, walls) = grooved_sheet();
        let d = drawn(&mesh, &[]);
        assert_eq!(d.vertices, mesh_vertices(&mesh));
        assert_eq!(d.triangles, mesh.triangles);
        for f in 0..mesh.triangles.len() as u32 {
            assert_eq!(
                drawn_triangle(&mesh, &[], f),
                Some(mesh.triangles[f as usize])
            );
        }
        let d = drawn(&mesh, &walls);
        for f in 0..mesh.triangles.len() as u32 {
            assert_eq!(
                drawn_triangle(&mesh, &walls, f),
                Some(d.triangles[f as usize])
            );
        }
        assert_eq!(
            drawn_triangle(&mesh, &walls, mesh.triangles.len() as u32),
            None
        );
    }
}
