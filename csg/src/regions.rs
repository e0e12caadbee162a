//! Regions of a mesh: its connected components, with each cavity joined to the component
//! around it.
//!
//! A segmentation file often stores several structures in one mesh (two vertebrae, a bone with
//! its marrow cavity, a brain inside the skin); the Models list shows each region as its own
//! model and the boolean cuts each region as its own solid. Components are joined through edges
//! only: surfaces that merely touch at a vertex stay separate, which matches how segmentations
//! are built (marching cubes joins voxels through faces). Non-manifold edges join all their
//! faces. A region is a component together with its cavities: closed inward components inside
//! it ([`crate::cavities`] states the rule and how it is decided exactly). So
//! [`Regions::components`] labels components and [`Regions::build`] regions; both have the same
//! type and numbering (in order of the first triangle).
//!
//! Labelling is a union-find over triangles in which the smaller triangle index always becomes the
//! root, so every root is the first triangle of its region and numbering "in order of the first
//! triangle" falls out of one forward pass.

use crate::adjacency::EdgeAdjacency;
use crate::mesh::Mesh;

/// The region (or component) of every triangle.
#[derive(Clone, Debug, Default)]
pub struct Regions {
    /// Region id of each triangle, in `0..count`. Regions are numbered in order of their first
    /// triangle. Same length as `mesh.triangles`.
    pub region_of_triangle: Vec<u32>,
    /// Number of regions.
    pub count: usize,
}

impl Regions {
    /// Labels edge-connected components of `mesh` (non-manifold edges connect all their faces).
    ///
    /// `adjacency` must be [`EdgeAdjacency::build`] of `mesh`.
    pub fn components(mesh: &Mesh, adjacency: &EdgeAdjacency) -> Regions {
        let n = mesh.triangles.len();
        debug_assert_eq!(
            adjacency.triangle_edges.len(),
            n,
            "adjacency of another mesh"
        );
        // parent[t] <= t always; a root is the smallest triangle of its set.
        let mut parent: Vec<u32> = (0..n as u32).collect();
        for e in 0..adjacency.edge_count() as u32 {
            let faces = adjacency.faces_of_edge(e);
            if let Some((&first, rest)) = faces.split_first() {
                for &f in rest {
                    union(&mut parent, first, f);
                }
            }
        }
        Self::from_parents(parent)
    }

    /// Labels the sets of a union-find forest over triangles built with [`union`] (`parent[t] <=
    /// t`, starting from `parent[t] == t`): the regions of [`Regions::build`] when every edge's
    /// faces were joined.
    pub(crate) fn from_parents(mut parent: Vec<u32>) -> Regions {
        // One forward pass, in place: `parent[t] < t` lies in t's region and was relabelled
        // already, so its entry is t's region id; a root (`parent[t] == t`) opens a new region.
        let mut count = 0u32;
        for t in 0..parent.len() {
            let p = parent[t] as usize;
            parent[t] = if p == t {
                count += 1;
                count - 1
            } else {
                parent[p]
            };
        }
        Regions {
            region_of_triangle: parent,
            count: count as usize,
        }
    }

    /// Number of triangles in each region, indexed by region id.
    pub fn triangle_counts(&self) -> Vec<usize> {
        let mut counts = vec![0usize; self.count];
        for &r in &self.region_of_triangle {
            counts[r as usize] += 1;
        }
        counts
    }

    /// Checks the invariants written on the fields against `mesh`: one label per triangle, labels
    /// in `0..count`, and regions numbered in order of their first triangle (so every id is used).
    pub fn sanity_check(&self, mesh: &Mesh) -> Result<(), String> {
        let Regions {
            region_of_triangle,
            count,
        } = self;
        if region_of_triangle.len() != mesh.triangles.len() {
            return Err(format!(
                "{} region labels for {} triangles",
                region_of_triangle.len(),
                mesh.triangles.len()
            ));
        }
        let mut next = 0u32;
        for (t, &r) in region_of_triangle.iter().enumerate() {
            if r > next || r as usize >= *count {
                return Err(format!(
                    "triangle {t} has region {r}, expected at most {next}"
                ));
            }
            if r == next {
                next += 1;
            }
        }
        if next as usize != *count {
            return Err(format!("{count} regions claimed, {next} used"));
        }
        Ok(())
    }
}

/// Root of `x`, halving the path on the way.
fn find(parent: &mut [u32], mut x: u32) -> u32 {
    while parent[x as usize] != x {
        let grandparent = parent[parent[x as usize] as usize];
        parent[x as usize] = grandparent;
        x = grandparent;
    }
    x
}

/// Joins the sets of `a` and `b`; the smaller root wins.
pub(crate) fn union(parent: &mut [u32], a: u32, b: u32) {
    let (ra, rb) = (find(parent, a), find(parent, b));
    if ra < rb {
        parent[rb as usize] = ra;
    } else if rb < ra {
        parent[ra as usize] = rb;
    }
}

/// Splits `mesh` into one compacted mesh per region ([`Regions::build`]: a cavity stays with the
/// component around it), in region order. Vertex coordinates are kept bit-exact.
///
/// Inside each piece, triangles keep their relative order and vertices are numbered in order of
/// first use (as [`Mesh::compacted`] does). A vertex shared by two regions (surfaces touching at a
/// point) is copied into both.
pub fn split_regions(mesh: &Mesh) -> Vec<Mesh> {
    let adjacency = EdgeAdjacency::build(mesh);
    let regions = Regions::build(mesh, &adjacency);
    split_by_regions(mesh, &regions)
}

/// [`split_regions`] with regions already computed (they must belong to `mesh`).
pub fn split_by_regions(mesh: &Mesh, regions: &Regions) -> Vec<Mesh> {
    let mut pieces: Vec<Mesh> = regions
        .triangle_counts()
        .into_iter()
        .map(|n| Mesh {
            positions: Vec::new(),
            triangles: Vec::with_capacity(n),
        })
        .collect();
    // Group triangle ids by region (stable), so each region is processed contiguously and one
    // stamp per vertex says whether it already has an index in the current piece.
    let mut start = vec![0usize; regions.count + 1];
    for &r in &regions.region_of_triangle {
        start[r as usize + 1] += 1;
    }
    for r in 0..regions.count {
        start[r + 1] += start[r];
    }
    let mut order = vec![0u32; regions.region_of_triangle.len()];
    for (t, &r) in regions.region_of_triangle.iter().enumerate() {
        order[start[r as usize]] = t as u32;
        start[r as usize] += 1;
    }
    let mut stamp = vec![u32::MAX; mesh.positions.len()];
    let mut local = vec![0u32; mesh.positions.len()];
    for &t in &order {
        let r = regions.region_of_triangle[t as usize];
        let piece = &mut pieces[r as usize];
        let tri = mesh.triangles[t as usize].map(|v| {
            let v = v as usize;
            if stamp[v] != r {
                stamp[v] = r;
                local[v] = piece.positions.len() as u32;
                piece.positions.push(mesh.positions[v]);
            }
            local[v]
        });
        piece.triangles.push(tri);
    }
    pieces
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testkit;
    use glam::DVec3;

    #[test]
    fn three_shapes_in_first_triangle_order() {
        let mut m = testkit::cube(DVec3::ZERO, DVec3::ONE);
        let sphere = testkit::icosphere(1, 0.5);
        let torus = testkit::torus(3.0, 1.0, 8, 6);
        m.append(&torus);
        m.append(&sphere);
        // Interleave: move the sphere's last triangle to the front.
        let last = m.triangles.pop().unwrap();
        m.triangles.insert(0, last);
        m.sanity_check().unwrap();
        let adj = EdgeAdjacency::build(&m);
        let regions = Regions::build(&m, &adj);
        regions.sanity_check(&m).unwrap();
        assert_eq!(regions.count, 3);
        assert_eq!(regions.triangle_counts(), vec![80, 12, 96]);
        let pieces = split_regions(&m);
        assert_eq!(pieces.len(), 3);
        for p in &pieces {
            p.sanity_check().unwrap();
        }
        assert_eq!(
            pieces[1],
            testkit::cube(DVec3::ZERO, DVec3::ONE).compacted()
        );
        assert_eq!(pieces[2].triangle_count(), 96);
        assert_eq!(pieces[0].vertex_count(), sphere.vertex_count());
        let mut a: Vec<[u64; 3]> = pieces[0]
            .positions
            .iter()
            .map(|p| p.to_array().map(f64::to_bits))
            .collect();
        let mut b: Vec<[u64; 3]> = sphere
            .positions
            .iter()
            .map(|p| p.to_array().map(f64::to_bits))
            .collect();
        a.sort_unstable();
        b.sort_unstable();
        assert_eq!(a, b, "coordinates are bit-exact");
    }

    #[test]
    fn vertex_touching_surfaces_are_two_regions() {
        // Two triangles sharing only vertex 0, plus a non-manifold fin joining 3 faces.
        let p = |x: f64, y: f64| DVec3::new(x, y, 0.0);
        let m = Mesh::new(
            vec![
                p(0., 0.),
                p(1., 0.),
                p(0., 1.),
                p(-1., 0.),
                p(0., -1.),
                p(0.5, 0.5),
            ],
            vec![[0, 1, 2], [0, 3, 4], [1, 2, 5], [0, 1, 5]],
        )
        .unwrap();
        let regions = Regions::build(&m, &EdgeAdjacency::build(&m));
        regions.sanity_check(&m).unwrap();
        assert_eq!(regions.region_of_triangle, vec![0, 1, 0, 0]);
        let pieces = split_regions(&m);
        assert_eq!(pieces[1].positions, vec![p(0., 0.), p(-1., 0.), p(0., -1.)]);
        assert_eq!(pieces[1].triangles, vec![[0, 1, 2]]);
        assert_eq!(pieces[0].positions.len(), 4);
    }

    #[test]
    fn degenerate_point_triangle_is_its_own_region() {
        let m = Mesh::new(
            vec![DVec3::ZERO, DVec3::X, DVec3::Y],
            vec![[0, 1, 2], [1, 1, 1]],
        )
        .unwrap();
        let regions = Regions::build(&m, &EdgeAdjacency::build(&m));
        assert_eq!(regions.count, 2);
        assert!(split_regions(&Mesh::default()).is_empty());
    }
}
