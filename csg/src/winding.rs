//! Fast generalized winding numbers (Barill, Dickson, Schmidt, Levin, Jacobson 2018, "Fast
//! winding numbers for soups and clouds").
//!
//! The generalized winding number of a triangle mesh at `q` (Jacobson, Kavan, Sorkine-Hornung
//! 2013) is the sum of the signed solid angles its triangles subtend at `q`, over 4π: an integer
//! for a closed surface (1 inside, 0 outside), harmonic, and about ½ across holes, so
//! thresholding it at ½ classifies points against open or non-manifold surfaces. The boolean
//! uses it only where no exact test exists: the status of cutter components against an *open*
//! target (see `boolean.rs`).
//!
//! Summing all N solid angles costs O(N) per query. The tree here groups the triangles in a
//! bounding-volume hierarchy and stores per node its area vector `A` (Σ area × unit normal, i.e.
//! the sum of the half cross products), its area-weighted centre `p̃`, the radius of a ball
//! around `p̃` containing all its triangles, and the second-order moment `M = Σ A_t ⊗ (c_t − p̃)`
//! (`c_t`: triangle centroids). The solid angle of a surface is `∫ n(x) · K(x − q) dA` with
//! `K(y) = y / |y|³`; far from a node (distance > β × radius) the node's triangles contribute its
//! Taylor expansion about `p̃`: `A · K(d) + Σ_ij ∂_j K_i(d) M_ij` with `d = p̃ − q` (the paper's
//! expansion to second order; for flat triangles the moment is exact because the integrand's
//! offset is linear). Near a node the children are visited, down to the exact solid angles of
//! the leaf triangles. Queries cost O(log N) away from the surface.
//!
//! Accuracy: the error of a node's expansion is of the order of (radius / distance)² of its
//! contribution. With β = [`WindingTree::BETA`] = 4 the tests find the tree within 1e-2 of the
//! exact sum at random points around an open sphere, and within 2e-2 at the centre of a closed
//! sphere (there every far-field term errs the same way); β = 2.5 gave 4e-2 there. It is a classifier, not an exact predicate: the
//! boolean uses it only for open targets, and says so in its contract.

use glam::{DMat3, DVec3};

use crate::mesh::Mesh;

/// A node: a leaf when `count > 0` (faces `order[start..start + count]`), otherwise an inner
/// node with children `start` and `start + 1` (always at higher indices than the node).
#[derive(Clone, Copy, Debug)]
struct Node {
    /// Σ over the node's triangles of ½ (b − a) × (c − a).
    area_vector: DVec3,
    /// Second-order moment: Σ over the triangles of `area_vector_t ⊗ (centroid_t − centre)`
    /// (row i, column j: component i of the area vector times component j of the offset).
    moment: DMat3,
    /// Area-weighted centre of the node's triangles (mean of their corners when they have no
    /// area).
    centre: DVec3,
    /// Every corner of every triangle of the node is within `radius` of `centre`.
    radius: f64,
    /// Total area of the node's triangles (for combining children).
    area: f64,
    start: u32,
    count: u32,
}

/// Fast winding-number tree over one mesh (see the module doc). Built once per target.
#[derive(Clone, Debug, Default)]
pub struct WindingTree {
    /// Node 0 is the root (no node for a mesh without triangles).
    nodes: Vec<Node>,
    /// Face ids grouped by leaf.
    order: Vec<u32>,
    /// Number of triangles of the mesh the tree was built from.
    triangle_count: usize,
}

const LEAF_SIZE: usize = 8;

/// Signed solid angle of triangle `a b c` seen from the origin (van Oosterom and Strackee 1983),
/// positive when the origin lies behind the triangle (on the side opposite to its
/// counter-clockwise normal), as it does inside an outward-oriented closed surface.
#[inline]
fn solid_angle(a: DVec3, b: DVec3, c: DVec3) -> f64 {
    let (la, lb, lc) = (a.length(), b.length(), c.length());
    let num = a.dot(b.cross(c));
    let den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    2.0 * num.atan2(den)
}

/// `a ⊗ b`: the matrix with entry (i, j) = a_i b_j (glam matrices are stored by columns:
/// column j is `a * b_j`).
#[inline]
fn outer(a: DVec3, b: DVec3) -> DMat3 {
    DMat3::from_cols(a * b.x, a * b.y, a * b.z)
}

/// Exact generalized winding number of `mesh` at `q` (O(N)): the reference the tree is tested
/// against.
pub fn winding_number_exact(mesh: &Mesh, q: DVec3) -> f64 {
    let mut sum = 0.0;
    for t in 0..mesh.triangles.len() {
        let [a, b, c] = mesh.corners(t);
        sum += solid_angle(a - q, b - q, c - q);
    }
    sum / (4.0 * std::f64::consts::PI)
}

impl WindingTree {
    /// Far-field threshold β: a node is replaced by its dipole when the query is farther than
    /// β × its radius from its centre.
    pub const BETA: f64 = 4.0;

    /// Builds the tree of `mesh` (indices must be in range: [`Mesh::sanity_check`]).
    pub fn build(mesh: &Mesh) -> WindingTree {
        let n = mesh.triangles.len();
        if n == 0 {
            return WindingTree::default();
        }
        let centroid: Vec<DVec3> = (0..n)
            .map(|t| {
                let [a, b, c] = mesh.corners(t);
                (a + b + c) / 3.0
            })
            .collect();
        let mut order: Vec<u32> = (0..n as u32).collect();
        let empty = Node {
            area_vector: DVec3::ZERO,
            moment: DMat3::ZERO,
            centre: DVec3::ZERO,
            radius: 0.0,
            area: 0.0,
            start: 0,
            count: 0,
        };
        let mut nodes = vec![empty];
        // Top-down: median split of the centroids on the longest axis of their box.
        let mut stack = vec![(0usize, 0usize, n)];
        while let Some((node, lo, hi)) = stack.pop() {
            let slice = &mut order[lo..hi];
            if slice.len() <= LEAF_SIZE {
                nodes[node].start = lo as u32;
                nodes[node].count = slice.len() as u32;
                continue;
            }
            let (mut min, mut max) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
            for &t in slice.iter() {
                min = min.min(centroid[t as usize]);
                max = max.max(centroid[t as usize]);
            }
            let extent = max - min;
            let axis = if extent.x >= extent.y && extent.x >= extent.z {
                0
            } else if extent.y >= extent.z {
                1
            } else {
                2
            };
            let mid = slice.len() / 2;
            slice.select_nth_unstable_by(mid, |&p, &q| {
                centroid[p as usize][axis].total_cmp(&centroid[q as usize][axis])
            });
            let first_child = nodes.len();
            nodes.push(empty);
            nodes.push(empty);
            nodes[node].start = first_child as u32;
            stack.push((first_child, lo, lo + mid));
            stack.push((first_child + 1, lo + mid, hi));
        }
        // Bottom-up: children have higher indices than their parent.
        for i in (0..nodes.len()).rev() {
            let node = nodes[i];
            if node.count > 0 {
                let faces = &order[node.start as usize..(node.start + node.count) as usize];
                let mut area_vector = DVec3::ZERO;
                let mut area = 0.0;
                let mut weighted = DVec3::ZERO;
                let mut mean = DVec3::ZERO;
                for &t in faces {
                    let [a, b, c] = mesh.corners(t as usize);
                    let v = 0.5 * (b - a).cross(c - a);
                    let w = v.length();
                    area_vector += v;
                    area += w;
                    weighted += w * centroid[t as usize];
                    mean += centroid[t as usize];
                }
                let centre = if area > 0.0 {
                    weighted / area
                } else {
                    mean / faces.len() as f64
                };
                let mut radius = 0.0f64;
                let mut moment = DMat3::ZERO;
                for &t in faces {
                    let [a, b, c] = mesh.corners(t as usize);
                    for p in [a, b, c] {
                        radius = radius.max(p.distance(centre));
                    }
                    moment += outer(0.5 * (b - a).cross(c - a), centroid[t as usize] - centre);
                }
                nodes[i] = Node {
                    area_vector,
                    moment,
                    centre,
                    radius,
                    area,
                    ..node
                };
            } else {
                let (l, r) = (nodes[node.start as usize], nodes[node.start as usize + 1]);
                let area = l.area + r.area;
                let centre = if area > 0.0 {
                    (l.area * l.centre + r.area * r.centre) / area
                } else {
                    0.5 * (l.centre + r.centre)
                };
                let radius = (centre.distance(l.centre) + l.radius)
                    .max(centre.distance(r.centre) + r.radius);
                let moment = l.moment
                    + r.moment
                    + outer(l.area_vector, l.centre - centre)
                    + outer(r.area_vector, r.centre - centre);
                nodes[i] = Node {
                    area_vector: l.area_vector + r.area_vector,
                    moment,
                    centre,
                    radius,
                    area,
                    ..node
                };
            }
        }
        WindingTree {
            nodes,
            order,
            triangle_count: n,
        }
    }

    /// Generalized winding number of `mesh` (the mesh the tree was built from) at `q`:
    /// approximately [`winding_number_exact`], exact sums near `q`, dipoles far from it.
    pub fn winding_number(&self, mesh: &Mesh, q: DVec3) -> f64 {
        self.evaluate(mesh, q).0
    }

    /// The winding number and the number of nodes visited.
    fn evaluate(&self, mesh: &Mesh, q: DVec3) -> (f64, usize) {
        debug_assert_eq!(
            mesh.triangles.len(),
            self.triangle_count,
            "tree of another mesh"
        );
        if self.nodes.is_empty() {
            return (0.0, 0);
        }
        let mut visited = 0;
        let mut sum = 0.0;
        let mut stack: Vec<u32> = Vec::with_capacity(64);
        stack.push(0);
        while let Some(i) = stack.pop() {
            let node = &self.nodes[i as usize];
            visited += 1;
            let d = node.centre - q;
            let dist = d.length();
            if dist > Self::BETA * node.radius {
                // Ω ≈ A · K(d) + Σ_ij ∂_j K_i(d) M_ij with K(y) = y / |y|³, whose Jacobian is
                // I / |y|³ − 3 y yᵀ / |y|⁵.
                let d3 = dist * dist * dist;
                let m = &node.moment;
                let trace = m.x_axis.x + m.y_axis.y + m.z_axis.z;
                // yᵀ M y with M stored as columns (column j holds M_·j).
                let quad = d.dot(*m * d);
                sum += node.area_vector.dot(d) / d3 + trace / d3 - 3.0 * quad / (d3 * dist * dist);
            } else if node.count > 0 {
                for &t in &self.order[node.start as usize..(node.start + node.count) as usize] {
                    let [a, b, c] = mesh.corners(t as usize);
                    sum += solid_angle(a - q, b - q, c - q);
                }
            } else {
                stack.push(node.start);
                stack.push(node.start + 1);
            }
        }
        (sum / (4.0 * std::f64::consts::PI), visited)
    }

    /// Checks the invariants written on the fields (every face in exactly one leaf, children
    /// after parents, radii covering the corners).
    pub fn sanity_check(&self, mesh: &Mesh) -> Result<(), String> {
        if self.triangle_count != mesh.triangles.len() {
            return Err("tree of another mesh".into());
        }
        let mut seen = vec![false; self.triangle_count];
        for (i, node) in self.nodes.iter().enumerate() {
            if node.count > 0 {
                for &t in &self.order[node.start as usize..(node.start + node.count) as usize] {
                    if std::mem::replace(&mut seen[t as usize], true) {
                        return Err(format!("face {t} in two leaves"));
                    }
                    for p in mesh.corners(t as usize) {
                        // The radius is a sum of rounded distances: allow for their rounding.
                        if p.distance(node.centre) > node.radius * (1.0 + 1e-12) + 1e-300 {
                            return Err(format!("node {i}: corner of face {t} outside its ball"));
                        }
                    }
                }
            } else if (node.start as usize) <= i || node.start as usize + 1 >= self.nodes.len() {
                return Err(format!("node {i}: children {} out of order", node.start));
            }
        }
        match seen.iter().position(|&s| !s) {
            Some(t) => Err(format!("face {t} in no leaf")),
            None => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testkit;

    /// An icosphere with a cap of faces removed (an open surface), and a torus.
    fn open_sphere() -> Mesh {
        let mut m = testkit::icosphere(4, 10.0);
        m.triangles.retain(|t| {
            let c = (m.positions[t[0] as usize] + m.positions[t[1] as usize]) * 0.5;
            c.z < 7.0
        });
        m
    }

    /// Deterministic pseudo-random points in a box (xorshift).
    fn points(n: usize, half: f64) -> Vec<DVec3> {
        let mut s = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        (0..n)
            .map(|_| DVec3::new(next(), next(), next()) * half)
            .collect()
    }

    #[test]
    fn tree_matches_the_exact_sum_on_an_open_surface() {
        let mesh = open_sphere();
        let tree = WindingTree::build(&mesh);
        tree.sanity_check(&mesh).unwrap();
        let mut worst = 0.0f64;
        let mut inside = 0;
        for q in points(300, 15.0) {
            let exact = winding_number_exact(&mesh, q);
            let fast = tree.winding_number(&mesh, q);
            worst = worst.max((exact - fast).abs());
            inside += usize::from(exact >= 0.5);
            // Away from the ½ level set, the classification agrees.
            if (exact - 0.5).abs() > 0.05 {
                assert_eq!(
                    exact >= 0.5,
                    fast >= 0.5,
                    "at {q}: exact {exact}, tree {fast}"
                );
            }
        }
        assert!(worst < 1e-2, "largest difference {worst}");
        // The sample sees both sides (the sphere fills ~1/7 of the box).
        assert!(inside > 10 && inside < 250, "{inside} points inside");
    }

    #[test]
    fn closed_surfaces_give_integers() {
        let mut mesh = testkit::torus(10.0, 3.0, 48, 24);
        mesh.append(&testkit::icosphere(3, 2.0));
        let tree = WindingTree::build(&mesh);
        tree.sanity_check(&mesh).unwrap();
        // In the tube of the torus, inside the small sphere (at the centre), far outside.
        let cases = [
            (DVec3::new(10.0, 0.0, 0.0), 1.0),
            (DVec3::new(0.0, 0.0, 0.0), 1.0),
            (DVec3::new(0.0, 0.0, 8.0), 0.0),
            (DVec3::new(40.0, 30.0, -20.0), 0.0),
        ];
        for (q, want) in cases {
            let fast = tree.winding_number(&mesh, q);
            let exact = winding_number_exact(&mesh, q);
            assert!((exact - want).abs() < 1e-9, "exact {exact} at {q}");
            // At the centre of a sphere every far-field term errs the same way (curvature):
            // the largest difference of the tests, about 1.2e-2.
            assert!((fast - want).abs() < 2e-2, "tree {fast} at {q}");
        }
    }

    #[test]
    fn queries_visit_few_nodes() {
        // Not a timing: the far field must prune. A query far away is answered at the root; one
        // near the surface visits a small part of the tree.
        let mesh = testkit::icosphere(5, 1.0);
        let tree = WindingTree::build(&mesh);
        let (far, visited) = tree.evaluate(&mesh, DVec3::new(100.0, 0.0, 0.0));
        assert!(far.abs() < 1e-6, "{far}");
        assert_eq!(visited, 1);
        let q = DVec3::new(0.0, 0.0, 0.9);
        let (near, visited) = tree.evaluate(&mesh, q);
        assert!((near - winding_number_exact(&mesh, q)).abs() < 1e-2);
        assert!(
            visited * 10 < tree.nodes.len(),
            "{visited} of {}",
            tree.nodes.len()
        );
        let (empty, _) = WindingTree::build(&Mesh::default()).evaluate(&Mesh::default(), q);
        assert_eq!(empty, 0.0);
    }
}
