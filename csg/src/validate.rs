//! Topological validation report of a mesh: closed, manifold, oriented, degenerate faces.
//!
//! Cutaway accepts whatever anatomy files contain (open surfaces, non-manifold marching-cubes
//! output, stray degenerate faces), so validation is a report of facts rather than a pass/fail
//! gate; the boolean and `cutaway info` decide what to do with it. Structural errors that make a
//! mesh unusable (indices out of range, NaN) are [`Mesh::sanity_check`]'s job instead.
//!
//! Every count is decided exactly: edge uses and orientation are integer facts, and "collinear
//! corners" is decided with Shewchuk's exact `orient2d` (the `robust` crate) on the three
//! coordinate-plane projections: three points are collinear in space exactly when all three
//! projected orientations vanish, because those are the components of `(b - a) × (c - a)`.
//! No tolerance enters anywhere.

use crate::adjacency::{EdgeAdjacency, NO_EDGE};
use crate::mesh::Mesh;
use crate::regions::Regions;
use glam::DVec3;

/// Topological facts about a mesh. Cutaway accepts open and non-manifold meshes; this report says
/// what the mesh is so that callers can decide (and `cutaway info` can print it).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct MeshReport {
    pub vertices: usize,
    pub triangles: usize,
    /// Undirected edges (pairs of distinct vertex indices used as a triangle side).
    pub edges: usize,
    /// Edges used by exactly one face.
    pub boundary_edges: usize,
    /// Edges used by three or more faces.
    pub nonmanifold_edges: usize,
    /// Manifold edges whose two faces traverse it in the same direction (inconsistent orientation).
    pub misoriented_edges: usize,
    /// Triangles with a repeated vertex index or collinear corners (exact test).
    pub degenerate_triangles: usize,
    /// Vertices whose faces form more than one fan (non-manifold vertices). Faces around a vertex
    /// are joined through every edge at that vertex, non-manifold ones included, so a vertex on a
    /// non-manifold edge is counted only if its faces also fall apart into separate fans.
    pub nonmanifold_vertices: usize,
    /// Edge-connected components (see [`crate::regions`]).
    pub components: usize,
    /// Regions: components with their cavities joined to them (see [`crate::cavities`]).
    pub regions: usize,
    /// Every edge is used by exactly two faces (false for a mesh with no triangle).
    pub closed: bool,
    /// No non-manifold edge or vertex and consistently oriented (boundary edges are allowed).
    pub manifold: bool,
}

impl Mesh {
    /// Computes the topological report.
    ///
    /// Requires a structurally valid mesh ([`Mesh::sanity_check`]).
    pub fn report(&self) -> MeshReport {
        let adjacency = EdgeAdjacency::build(self);
        let components = Regions::components(self, &adjacency);
        let count = components.count;
        let regions = Regions::of_components(self, &adjacency, components);
        MeshReport::from_parts(self, &adjacency, count, regions.count)
    }
}

impl Mesh {
    /// Whether the mesh is closed and consistently oriented: every directed edge `a → b` of a
    /// triangle occurs exactly once and its reverse `b → a` exactly once (so every edge is used
    /// by exactly two faces, in opposite directions), and no triangle repeats a vertex. Exact
    /// (integer facts only) and linear in the mesh size: the outgoing edges are bucketed per
    /// vertex, with no sort and no spatial index, so a caller that only needs `closed` (a
    /// surface known to be closed by construction, reported per file) pays a small fraction of
    /// [`Mesh::report`]. False for a mesh with no triangle. A mesh for which this is true has
    /// `report().closed` true; the converse fails only for a closed mesh with misoriented faces.
    ///
    /// Requires a structurally valid mesh ([`Mesh::sanity_check`]).
    pub fn is_closed_oriented(&self) -> bool {
        if self.triangles.is_empty() {
            return false;
        }
        // Outgoing edges per vertex (compressed rows): start[v]..start[v + 1] in `to`.
        let mut start = vec![0u32; self.positions.len() + 1];
        for t in &self.triangles {
            if t[0] == t[1] || t[1] == t[2] || t[2] == t[0] {
                return false;
            }
            for &v in t {
                start[v as usize + 1] += 1;
            }
        }
        for v in 0..self.positions.len() {
            start[v + 1] += start[v];
        }
        let mut fill = start.clone();
        let mut to = vec![0u32; 3 * self.triangles.len()];
        for t in &self.triangles {
            for k in 0..3 {
                let (a, b) = (t[k] as usize, t[(k + 1) % 3]);
                to[fill[a] as usize] = b;
                fill[a] += 1;
            }
        }
        let out = |v: u32| &to[start[v as usize] as usize..start[v as usize + 1] as usize];
        (0..self.positions.len() as u32).all(|a| {
            let edges = out(a);
            edges.iter().enumerate().all(|(i, &b)| {
                // a → b once (no later duplicate), and b → a exactly once.
                !edges[i + 1..].contains(&b) && out(b).iter().filter(|&&c| c == a).count() == 1
            })
        })
    }
}

impl MeshReport {
    /// The report from an adjacency and the numbers of components and regions already found for
    /// `mesh` (a cached target index has all three).
    pub fn from_parts(
        mesh: &Mesh,
        adjacency: &EdgeAdjacency,
        components: usize,
        regions: usize,
    ) -> MeshReport {
        let mut boundary_edges = 0;
        let mut nonmanifold_edges = 0;
        let mut misoriented_edges = 0;
        for e in 0..adjacency.edge_count() as u32 {
            match adjacency.faces_of_edge(e) {
                [_] => boundary_edges += 1,
                &[f, g] => {
                    let [lo, hi] = adjacency.edges[e as usize];
                    let forward = |t: u32| traverses(mesh.triangles[t as usize], lo, hi);
                    let reverse = |t: u32| traverses(mesh.triangles[t as usize], hi, lo);
                    // Consistent: one face goes lo→hi and the other hi→lo.
                    let consistent = (forward(f) && reverse(g)) || (reverse(f) && forward(g));
                    if !consistent {
                        misoriented_edges += 1;
                    }
                }
                _ => nonmanifold_edges += 1,
            }
        }
        let degenerate_triangles = (0..mesh.triangles.len())
            .filter(|&t| is_degenerate(mesh, t))
            .count();
        let nonmanifold_vertices = count_nonmanifold_vertices(mesh, adjacency);
        let closed = !mesh.triangles.is_empty() && boundary_edges == 0 && nonmanifold_edges == 0;
        let manifold =
            nonmanifold_edges == 0 && nonmanifold_vertices == 0 && misoriented_edges == 0;
        MeshReport {
            vertices: mesh.positions.len(),
            triangles: mesh.triangles.len(),
            edges: adjacency.edge_count(),
            boundary_edges,
            nonmanifold_edges,
            misoriented_edges,
            degenerate_triangles,
            nonmanifold_vertices,
            components,
            regions,
            closed,
            manifold,
        }
    }
}

/// True when triangle `tri` has a side going from vertex `a` to vertex `b`.
fn traverses(tri: [u32; 3], a: u32, b: u32) -> bool {
    (0..3).any(|k| tri[k] == a && tri[(k + 1) % 3] == b)
}

/// True when triangle `t` repeats a vertex index or its corners are exactly collinear
/// (coincident corners included).
pub fn is_degenerate(mesh: &Mesh, t: usize) -> bool {
    let [a, b, c] = mesh.triangles[t];
    if a == b || b == c || c == a {
        return true;
    }
    let [a, b, c] = mesh.corners(t);
    collinear(a, b, c)
}

/// Exact test: `a`, `b`, `c` lie on one line (or coincide).
pub fn collinear(a: DVec3, b: DVec3, c: DVec3) -> bool {
    let orient = |i: usize, j: usize| {
        let p = |v: DVec3| robust::Coord { x: v[i], y: v[j] };
        robust::orient2d(p(a), p(b), p(c))
    };
    orient(0, 1) == 0.0 && orient(1, 2) == 0.0 && orient(2, 0) == 0.0
}

/// Counts vertices whose incident faces form more than one edge-connected fan.
///
/// Union-find over corners (`3 * t + k`): the corners of the faces around an edge are joined at
/// each of the edge's two vertices, and corners of one triangle that name the same vertex are
/// joined too. A vertex is non-manifold when its corners end in more than one set.
fn count_nonmanifold_vertices(mesh: &Mesh, adjacency: &EdgeAdjacency) -> usize {
    let tris = &mesh.triangles;
    let mut parent: Vec<u32> = (0..3 * tris.len() as u32).collect();
    let corner_of = |t: u32, v: u32| -> u32 {
        let tri = tris[t as usize];
        let k = if tri[0] == v {
            0
        } else if tri[1] == v {
            1
        } else {
            2
        };
        3 * t + k
    };
    for t in 0..tris.len() {
        for k in 0..3 {
            if adjacency.triangle_edges[t][k] == NO_EDGE {
                union(
                    &mut parent,
                    (3 * t + k) as u32,
                    (3 * t + (k + 1) % 3) as u32,
                );
            }
        }
    }
    for e in 0..adjacency.edge_count() as u32 {
        let faces = adjacency.faces_of_edge(e);
        let [lo, hi] = adjacency.edges[e as usize];
        if let Some((&first, rest)) = faces.split_first() {
            for &f in rest {
                union(&mut parent, corner_of(first, lo), corner_of(f, lo));
                union(&mut parent, corner_of(first, hi), corner_of(f, hi));
            }
        }
    }
    let mut fans = vec![0u8; mesh.positions.len()];
    let mut count = 0;
    for c in 0..parent.len() as u32 {
        if find(&mut parent, c) == c {
            let v = tris[(c / 3) as usize][(c % 3) as usize] as usize;
            fans[v] = fans[v].saturating_add(1);
            if fans[v] == 2 {
                count += 1;
            }
        }
    }
    count
}

fn find(parent: &mut [u32], mut x: u32) -> u32 {
    while parent[x as usize] != x {
        let grandparent = parent[parent[x as usize] as usize];
        parent[x as usize] = grandparent;
        x = grandparent;
    }
    x
}

fn union(parent: &mut [u32], a: u32, b: u32) {
    let (ra, rb) = (find(parent, a), find(parent, b));
    if ra != rb {
        parent[ra.max(rb) as usize] = ra.min(rb);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testkit;

    #[test]
    fn closed_shapes_are_closed_manifold() {
        for m in [
            testkit::cube(DVec3::ZERO, DVec3::ONE),
            testkit::icosphere(2, 3.0),
            testkit::torus(2.0, 0.5, 12, 8),
        ] {
            m.sanity_check().unwrap();
            let r = m.report();
            assert!(r.closed && r.manifold, "{r:?}");
            assert_eq!(r.edges, 3 * m.triangle_count() / 2);
            assert_eq!(r.regions, 1);
            assert_eq!(
                (r.boundary_edges, r.nonmanifold_edges, r.misoriented_edges),
                (0, 0, 0)
            );
            assert_eq!((r.degenerate_triangles, r.nonmanifold_vertices), (0, 0));
        }
    }

    #[test]
    fn closed_oriented_agrees_with_the_report() {
        let cube = || testkit::cube(DVec3::ZERO, DVec3::ONE);
        let mut open = cube();
        open.triangles.pop();
        let mut flipped = cube();
        flipped.triangles[0].swap(1, 2);
        let mut doubled = cube();
        doubled.triangles.push(doubled.triangles[0]);
        let mut degenerate = cube();
        degenerate.triangles[0][1] = degenerate.triangles[0][0];
        let mut two = cube();
        two.append(&testkit::cube(DVec3::splat(1.0), DVec3::splat(2.0)));
        let mut fin = cube();
        let [a, b, _] = fin.triangles[0];
        fin.positions.push(DVec3::new(0.5, 0.5, 3.0));
        let c = fin.positions.len() as u32 - 1;
        fin.triangles.extend([[a, b, c], [b, a, c]]);
        for (mesh, expected) in [
            (cube(), true),
            (testkit::icosphere(2, 3.0), true),
            (testkit::torus(2.0, 0.5, 12, 8), true),
            (two, true),
            (open, false),
            (flipped, false),
            (doubled, false),
            (degenerate, false),
            (fin, false),
            (Mesh::default(), false),
        ] {
            assert_eq!(mesh.is_closed_oriented(), expected, "{:?}", mesh.report());
            if expected {
                assert!(mesh.report().closed);
            }
        }
    }

    #[test]
    fn open_and_flipped() {
        let mut m = testkit::cube(DVec3::ZERO, DVec3::ONE);
        m.triangles.pop();
        let r = m.report();
        assert!(!r.closed && r.manifold);
        assert_eq!(r.boundary_edges, 3);
        let mut m = testkit::cube(DVec3::ZERO, DVec3::ONE);
        m.triangles[0].swap(1, 2);
        let r = m.report();
        assert!(r.closed && !r.manifold);
        assert_eq!(r.misoriented_edges, 3);
    }

    #[test]
    fn two_cubes_sharing_a_vertex_make_a_nonmanifold_vertex() {
        let mut m = testkit::cube(DVec3::ZERO, DVec3::ONE);
        let other = testkit::cube(DVec3::ONE, DVec3::splat(2.0));
        m.append(&other);
        let welded = crate::weld::weld_exact(&m);
        welded.sanity_check().unwrap();
        let r = welded.report();
        assert_eq!(r.vertices, 15);
        assert_eq!(r.nonmanifold_vertices, 1);
        assert_eq!(r.regions, 2);
        assert!(r.closed && !r.manifold);
    }

    #[test]
    fn two_cubes_sharing_an_edge_make_nonmanifold_edges() {
        let mut m = testkit::cube(DVec3::ZERO, DVec3::ONE);
        m.append(&testkit::cube(
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(2.0, 2.0, 1.0),
        ));
        let welded = crate::weld::weld_exact(&m);
        welded.sanity_check().unwrap();
        let r = welded.report();
        // The edge x = y = 1 is a box edge of both cubes: four faces. Its end vertices keep one
        // fan each, because faces are joined through the non-manifold edge itself.
        assert_eq!(
            (r.nonmanifold_edges, r.nonmanifold_vertices),
            (1, 0),
            "{r:?}"
        );
        assert!(!r.manifold && !r.closed);
        assert_eq!(r.regions, 1);
    }

    #[test]
    fn exact_collinearity() {
        let a = DVec3::new(0.1, 0.2, 0.3);
        let b = DVec3::new(0.7, 1.4, 2.1);
        assert!(collinear(DVec3::ZERO, DVec3::ONE, DVec3::splat(3.0)));
        assert!(collinear(a, a, b));
        assert!(!collinear(a, b, b + DVec3::new(0.0, 0.0, f64::EPSILON)));
        // Nearly collinear in floating point but not exactly: tiny offset in the last bit.
        let c = DVec3::new(1.0, 1.0, 1.0);
        let d = DVec3::new(3.0, 3.0, f64::from_bits(3.0f64.to_bits() + 1));
        assert!(!collinear(DVec3::ZERO, c, d));
        let m = Mesh::new(
            vec![DVec3::ZERO, c, d, DVec3::splat(2.0), DVec3::X],
            vec![[0, 1, 2], [0, 1, 3], [0, 0, 4], [0, 1, 4]],
        )
        .unwrap();
        assert_eq!(m.report().degenerate_triangles, 2);
    }

    #[test]
    fn empty_mesh_report() {
        let r = Mesh::default().report();
        assert_eq!(
            r,
            MeshReport {
                manifold: true,
                ..MeshReport::default()
            }
        );
    }
}
