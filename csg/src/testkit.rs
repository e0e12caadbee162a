//! Deterministic mesh generators for tests and benchmarks across the workspace.
//!
//! Public (not `cfg(test)`) because other crates' tests and benches need the same shapes. Every
//! generator is deterministic (same arguments, same bits), closed, edge-manifold and oriented
//! outward (counter-clockwise seen from outside, positive [`Mesh::volume`]), and shares vertices
//! between neighbouring triangles (no welding needed).

use glam::DVec3;

use crate::mesh::Mesh;

pub mod resources;
pub use resources::{Resource, skip};

/// The golden ratio, for the icosahedron's corners.
const PHI: f64 = 1.618_033_988_749_895;

/// An icosphere: the icosahedron with every face split `2^subdivisions` times along each edge
/// (`20 * 4^subdivisions` triangles), all vertices on the sphere of `radius` around the origin.
///
/// `subdivisions` 7 gives 327,680 triangles, 8 gives 1,310,720. For sizes in between use
/// [`geodesic_sphere`] (`20 * frequency²` triangles).
///
/// # Panics
/// When `subdivisions > 12` (that would be over 300M triangles, beyond `u32` vertex counts in practice).
pub fn icosphere(subdivisions: u32, radius: f64) -> Mesh {
    assert!(
        subdivisions <= 12,
        "icosphere: {subdivisions} subdivisions is too many"
    );
    geodesic_sphere(1 << subdivisions, radius)
}

/// A geodesic sphere of `20 * frequency²` triangles and `10 * frequency² + 2` vertices: each
/// icosahedron face is cut into a `frequency × frequency` triangular grid and the grid points are
/// projected onto the sphere of `radius` around the origin. `frequency` 224 gives 1,003,520
/// triangles, 316 gives 1,997,120.
///
/// Vertices on an icosahedron edge are computed once from that edge alone, so the two faces
/// sharing it use the same vertex indices (the mesh is closed without welding).
///
/// # Panics
/// When `frequency` is 0 or so large that the vertex count exceeds `u32`.
pub fn geodesic_sphere(frequency: u32, radius: f64) -> Mesh {
    assert!(
        frequency >= 1,
        "geodesic_sphere: frequency must be at least 1"
    );
    let f = frequency as usize;
    let vertex_total = 10 * (f as u64) * (f as u64) + 2;
    assert!(
        vertex_total <= u32::MAX as u64,
        "geodesic_sphere: frequency {frequency} needs more than u32::MAX vertices"
    );
    let (corners, faces) = icosahedron();
    let on_sphere = |p: DVec3| p.normalize() * radius;

    let mut positions: Vec<DVec3> = Vec::with_capacity(vertex_total as usize);
    positions.extend(corners.iter().map(|&c| on_sphere(c)));

    // The interior vertices of each icosahedron edge (lo < hi), ordered from lo to hi.
    let mut edge_vertices: std::collections::BTreeMap<(u32, u32), Vec<u32>> = Default::default();
    for face in &faces {
        for k in 0..3 {
            let (a, b) = (face[k], face[(k + 1) % 3]);
            let key = (a.min(b), a.max(b));
            edge_vertices.entry(key).or_insert_with(|| {
                let (lo, hi) = (corners[key.0 as usize], corners[key.1 as usize]);
                (1..f)
                    .map(|step| {
                        let w = step as f64 / f as f64;
                        positions.push(on_sphere(lo * (1.0 - w) + hi * w));
                        (positions.len() - 1) as u32
                    })
                    .collect()
            });
        }
    }
    // Vertex `step` (0..=f) along the edge from `u` to `v`.
    let along = |u: u32, v: u32, step: usize| -> u32 {
        if step == 0 {
            u
        } else if step == f {
            v
        } else if u < v {
            edge_vertices[&(u, v)][step - 1]
        } else {
            edge_vertices[&(v, u)][f - step - 1]
        }
    };

    let mut triangles = Vec::with_capacity(20 * f * f);
    // Grid point (i, j) of face (a, b, c) has barycentric weights (f - i - j, i, j) / f.
    let mut grid = vec![0u32; (f + 1) * (f + 1)];
    for &[a, b, c] in &faces {
        let (pa, pb, pc) = (
            corners[a as usize],
            corners[b as usize],
            corners[c as usize],
        );
        for i in 0..=f {
            for j in 0..=f - i {
                grid[i * (f + 1) + j] = if j == 0 {
                    along(a, b, i)
                } else if i == 0 {
                    along(a, c, j)
                } else if i + j == f {
                    along(b, c, j)
                } else {
                    let p = pa * (f - i - j) as f64 + pb * i as f64 + pc * j as f64;
                    positions.push(on_sphere(p));
                    (positions.len() - 1) as u32
                };
            }
        }
        let g = |i: usize, j: usize| grid[i * (f + 1) + j];
        for i in 0..f {
            for j in 0..f - i {
                triangles.push([g(i, j), g(i + 1, j), g(i, j + 1)]);
                if i + j + 1 < f {
                    triangles.push([g(i + 1, j), g(i + 1, j + 1), g(i, j + 1)]);
                }
            }
        }
    }
    Mesh {
        positions,
        triangles,
    }
}

/// The 12 corners and 20 outward faces of an icosahedron with corners `(0, ±1, ±φ)` and its
/// cyclic permutations.
fn icosahedron() -> ([DVec3; 12], Vec<[u32; 3]>) {
    let v = |x, y, z| DVec3::new(x, y, z);
    let corners = [
        v(-1.0, PHI, 0.0),
        v(1.0, PHI, 0.0),
        v(-1.0, -PHI, 0.0),
        v(1.0, -PHI, 0.0),
        v(0.0, -1.0, PHI),
        v(0.0, 1.0, PHI),
        v(0.0, -1.0, -PHI),
        v(0.0, 1.0, -PHI),
        v(PHI, 0.0, -1.0),
        v(PHI, 0.0, 1.0),
        v(-PHI, 0.0, -1.0),
        v(-PHI, 0.0, 1.0),
    ];
    let mut faces: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    // Make every face outward (the solid is convex around the origin), whatever the table says.
    for face in &mut faces {
        let [a, b, c] = face.map(|i| corners[i as usize]);
        if (b - a).cross(c - a).dot(a + b + c) < 0.0 {
            face.swap(1, 2);
        }
    }
    (corners, faces)
}

/// The axis-aligned box from `min` to `max` as 12 outward triangles on 8 vertices.
///
/// Vertex `k` has x from `max` when bit 0 of `k` is set, y when bit 1 is, z when bit 2 is.
pub fn cube(min: DVec3, max: DVec3) -> Mesh {
    let positions = (0..8)
        .map(|k| {
            DVec3::new(
                if k & 1 != 0 { max.x } else { min.x },
                if k & 2 != 0 { max.y } else { min.y },
                if k & 4 != 0 { max.z } else { min.z },
            )
        })
        .collect();
    // Quads counter-clockwise seen from outside.
    let quads: [[u32; 4]; 6] = [
        [0, 4, 6, 2], // -x
        [1, 3, 7, 5], // +x
        [0, 1, 5, 4], // -y
        [2, 6, 7, 3], // +y
        [0, 2, 3, 1], // -z
        [4, 5, 7, 6], // +z
    ];
    let mut triangles = Vec::with_capacity(12);
    for [a, b, c, d] in quads {
        triangles.push([a, b, c]);
        triangles.push([a, c, d]);
    }
    Mesh {
        positions,
        triangles,
    }
}

/// A torus around the z axis: tube centre circle of radius `major`, tube radius `minor`
/// (`minor < major`), `major_segments × minor_segments` quads, each split into two triangles.
///
/// # Panics
/// When a segment count is below 3.
pub fn torus(major: f64, minor: f64, major_segments: u32, minor_segments: u32) -> Mesh {
    assert!(
        major_segments >= 3 && minor_segments >= 3,
        "torus: segment counts must be at least 3"
    );
    let (nu, nv) = (major_segments as usize, minor_segments as usize);
    let mut positions = Vec::with_capacity(nu * nv);
    for i in 0..nu {
        let u = std::f64::consts::TAU * i as f64 / nu as f64;
        for j in 0..nv {
            let v = std::f64::consts::TAU * j as f64 / nv as f64;
            let r = major + minor * v.cos();
            positions.push(DVec3::new(r * u.cos(), r * u.sin(), minor * v.sin()));
        }
    }
    let id = |i: usize, j: usize| ((i % nu) * nv + (j % nv)) as u32;
    let mut triangles = Vec::with_capacity(2 * nu * nv);
    for i in 0..nu {
        for j in 0..nv {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
    }
    Mesh {
        positions,
        triangles,
    }
}

/// A UV sphere around the origin with `rings` latitude bands (≥ 2) and `segments` longitude
/// segments (≥ 3); the poles are single vertices.
///
/// # Panics
/// When `rings < 2` or `segments < 3`.
pub fn uv_sphere(rings: u32, segments: u32, radius: f64) -> Mesh {
    assert!(
        rings >= 2 && segments >= 3,
        "uv_sphere: needs rings >= 2 and segments >= 3"
    );
    let (nr, ns) = (rings as usize, segments as usize);
    let mut positions = vec![DVec3::new(0.0, 0.0, radius)];
    for r in 1..nr {
        let theta = std::f64::consts::PI * r as f64 / nr as f64;
        for s in 0..ns {
            let phi = std::f64::consts::TAU * s as f64 / ns as f64;
            positions.push(
                DVec3::new(
                    theta.sin() * phi.cos(),
                    theta.sin() * phi.sin(),
                    theta.cos(),
                ) * radius,
            );
        }
    }
    positions.push(DVec3::new(0.0, 0.0, -radius));
    let south = (positions.len() - 1) as u32;
    let ring = |r: usize, s: usize| (1 + (r - 1) * ns + s % ns) as u32;
    let mut triangles = Vec::new();
    for s in 0..ns {
        triangles.push([0, ring(1, s), ring(1, s + 1)]);
        triangles.push([south, ring(nr - 1, s + 1), ring(nr - 1, s)]);
    }
    for r in 1..nr - 1 {
        for s in 0..ns {
            let (a, b, c, d) = (
                ring(r, s),
                ring(r + 1, s),
                ring(r + 1, s + 1),
                ring(r, s + 1),
            );
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
    }
    Mesh {
        positions,
        triangles,
    }
}

/// Two flat fans of three triangles each in the z = 0 plane, sharing only vertex 0 at the origin
/// (a bow-tie: the vertex is non-manifold), one fan at x < 0 and one at x > 0, both facing +z.
pub fn bow_tie() -> Mesh {
    let mut positions = vec![DVec3::ZERO];
    let mut triangles = Vec::new();
    for side in [-1.0, 1.0] {
        let base = positions.len() as u32;
        for i in 0..4 {
            let a = i as f64 * 0.4 - 0.6;
            positions.push(DVec3::new(side * 3.0, 3.0 * a, 0.0));
        }
        for i in 0..3 {
            if side < 0.0 {
                triangles.push([0, base + i + 1, base + i]);
            } else {
                triangles.push([0, base + i, base + i + 1]);
            }
        }
    }
    Mesh {
        positions,
        triangles,
    }
}

/// The mesh as a triangle soup: three corners per triangle, as an STL file stores it.
pub fn to_soup(mesh: &Mesh) -> Vec<DVec3> {
    mesh.triangles
        .iter()
        .flat_map(|t| t.map(|i| mesh.positions[i as usize]))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every directed edge appears exactly once and its reverse exactly once: closed, manifold
    /// edges, consistently oriented.
    fn assert_closed_oriented(mesh: &Mesh) {
        mesh.sanity_check().unwrap();
        let mut directed: Vec<(u32, u32)> = mesh
            .triangles
            .iter()
            .flat_map(|t| (0..3).map(move |k| (t[k], t[(k + 1) % 3])))
            .collect();
        directed.sort_unstable();
        let len = directed.len();
        directed.dedup();
        assert_eq!(directed.len(), len, "a directed edge is used twice");
        for &(a, b) in &directed {
            assert!(
                directed.binary_search(&(b, a)).is_ok(),
                "edge {a}-{b} has no twin"
            );
        }
    }

    #[test]
    fn icosphere_counts_closed_outward() {
        for s in 0..4 {
            let m = icosphere(s, 2.0);
            let n = 1usize << (2 * s);
            assert_eq!(m.triangle_count(), 20 * n);
            assert_eq!(m.vertex_count(), 10 * n + 2);
            assert_closed_oriented(&m);
            for p in &m.positions {
                assert!((p.length() - 2.0).abs() < 1e-12);
            }
            // Inscribed polyhedron: volume below the sphere's, approaching it.
            let sphere = 4.0 / 3.0 * std::f64::consts::PI * 8.0;
            assert!(m.volume() > 0.0 && m.volume() < sphere);
            if s == 3 {
                assert!(m.volume() > 0.97 * sphere);
            }
            // Every triangle faces away from the centre.
            for t in 0..m.triangle_count() {
                let [a, b, c] = m.corners(t);
                assert!(m.face_normal_scaled(t).dot(a + b + c) > 0.0);
            }
        }
    }

    #[test]
    fn geodesic_sphere_odd_frequency() {
        let m = geodesic_sphere(5, 1.0);
        assert_eq!(m.triangle_count(), 500);
        assert_eq!(m.vertex_count(), 252);
        assert_closed_oriented(&m);
        assert_eq!(geodesic_sphere(5, 1.0), m, "deterministic");
    }

    #[test]
    fn cube_torus_uv_sphere_closed_outward() {
        let c = cube(DVec3::new(-1.0, 0.0, 2.0), DVec3::new(1.0, 3.0, 2.5));
        assert_closed_oriented(&c);
        assert_eq!(c.volume(), 2.0 * 3.0 * 0.5);
        let t = torus(3.0, 1.0, 24, 12);
        assert_closed_oriented(&t);
        let exact = 2.0 * std::f64::consts::PI.powi(2) * 3.0;
        assert!(t.volume() > 0.8 * exact && t.volume() < exact);
        let u = uv_sphere(8, 12, 1.0);
        assert_closed_oriented(&u);
        assert!(u.volume() > 0.0);
        assert_eq!(to_soup(&c).len(), 36);
    }
}

/// A deterministic SplitMix64 stream (Steele, Lea and Flood 2014) for tests and benchmarks that
/// need reproducible random points and rays without an RNG dependency.
#[derive(Clone, Debug)]
pub struct SplitMix(pub u64);

impl SplitMix {
    /// The next value, uniform in `[0, 1)` with 53 random bits.
    pub fn next_f64(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }

    /// A point uniform in the cube `[-r, r]³`.
    pub fn in_cube(&mut self, r: f64) -> DVec3 {
        DVec3::new(self.next_f64(), self.next_f64(), self.next_f64()) * (2.0 * r) - DVec3::splat(r)
    }

    /// A uniformly random unit vector (rejection sampling in the unit ball).
    pub fn unit_vector(&mut self) -> DVec3 {
        loop {
            let v = self.in_cube(1.0);
            let l = v.length();
            if l > 0.1 && l <= 1.0 {
                return v / l;
            }
        }
    }
}
