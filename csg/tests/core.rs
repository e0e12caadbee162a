//! Integration tests of the mesh core against brute-force oracles: adjacency, regions, welding,
//! the validation report and the spatial index, on random meshes (proptest) and on the testkit
//! shapes. Every mesh is passed through `Mesh::sanity_check` right after it is built.

use std::collections::{BTreeMap, BTreeSet};

use csg::adjacency::{EdgeAdjacency, NO_EDGE};
use csg::regions::{Regions, split_regions};
use csg::spatial::{WatertightRay, closest_on_triangle};
use csg::weld::{weld_exact, weld_soup};
use csg::{Aabb, DVec3, Mesh, SpatialIndex, testkit};
use proptest::prelude::*;

fn checked(mesh: Mesh) -> Mesh {
    mesh.sanity_check()
        .expect("generated mesh is structurally valid");
    mesh
}

/// A random mesh on a small integer grid: many coincident vertices, repeated indices, shared and
/// non-manifold edges, collinear corners. Integer coordinates keep the oracles' arithmetic exact.
fn grid_mesh() -> impl Strategy<Value = Mesh> {
    (1usize..24).prop_flat_map(|n| {
        (
            prop::collection::vec((0i32..4, 0i32..4, 0i32..3), n),
            prop::collection::vec((0..n as u32, 0..n as u32, 0..n as u32), 0..60),
        )
            .prop_map(|(points, tris)| {
                checked(Mesh {
                    positions: points
                        .into_iter()
                        .map(|(x, y, z)| DVec3::new(x as f64, y as f64, z as f64))
                        .collect(),
                    triangles: tris.into_iter().map(|(a, b, c)| [a, b, c]).collect(),
                })
            })
    })
}

/// A random mesh with arbitrary coordinates (for the spatial index).
fn float_mesh() -> impl Strategy<Value = Mesh> {
    (3usize..40).prop_flat_map(|n| {
        (
            prop::collection::vec(prop::array::uniform3(-10.0f64..10.0), n),
            prop::collection::vec(prop::array::uniform3(0..n as u32), 1..80),
        )
            .prop_map(|(points, triangles)| {
                checked(Mesh {
                    positions: points.into_iter().map(DVec3::from_array).collect(),
                    triangles,
                })
            })
    })
}

fn vec3(range: std::ops::Range<f64>) -> impl Strategy<Value = DVec3> {
    prop::array::uniform3(range).prop_map(DVec3::from_array)
}

/// Directions including axis-aligned ones with exact zero components.
fn direction() -> impl Strategy<Value = DVec3> {
    prop_oneof![
        vec3(-1.0..1.0),
        (0usize..3, prop::bool::ANY).prop_map(|(axis, neg)| {
            let mut d = DVec3::ZERO;
            d[axis] = if neg { -1.0 } else { 1.0 };
            d
        }),
    ]
}

/// Edge → faces by a map, the obvious way.
fn naive_edges(mesh: &Mesh) -> BTreeMap<[u32; 2], Vec<u32>> {
    let mut map: BTreeMap<[u32; 2], Vec<u32>> = BTreeMap::new();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            if a != b {
                map.entry([a.min(b), a.max(b)]).or_default().push(t as u32);
            }
        }
    }
    map
}

/// Components by repeated flood fill over the naive edge map, labelled by first triangle.
fn naive_regions(mesh: &Mesh) -> Vec<u32> {
    let edges = naive_edges(mesh);
    let n = mesh.triangles.len();
    let mut label = vec![u32::MAX; n];
    let mut next = 0;
    for seed in 0..n {
        if label[seed] != u32::MAX {
            continue;
        }
        label[seed] = next;
        let mut todo = vec![seed];
        while let Some(t) = todo.pop() {
            let tri = mesh.triangles[t];
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                if a == b {
                    continue;
                }
                for &f in &edges[&[a.min(b), a.max(b)]] {
                    if label[f as usize] == u32::MAX {
                        label[f as usize] = next;
                        todo.push(f as usize);
                    }
                }
            }
        }
        next += 1;
    }
    label
}

fn bits(p: DVec3) -> [u64; 3] {
    (p + DVec3::ZERO).to_array().map(f64::to_bits)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, ..ProptestConfig::default() })]

    #[test]
    fn adjacency_matches_naive_map(mesh in grid_mesh()) {
        let adj = EdgeAdjacency::build(&mesh);
        adj.sanity_check(&mesh).unwrap();
        let naive = naive_edges(&mesh);
        prop_assert_eq!(adj.edges.clone(), naive.keys().copied().collect::<Vec<_>>());
        for (e, faces) in naive.values().enumerate() {
            prop_assert_eq!(adj.faces_of_edge(e as u32), faces.as_slice());
        }
        for (t, tri) in mesh.triangles.iter().enumerate() {
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                let expected = if a == b { NO_EDGE } else { adj.find_edge(a, b).unwrap() };
                prop_assert_eq!(adj.triangle_edges[t][k], expected);
            }
        }
    }

    #[test]
    fn regions_match_flood_fill_and_split_keeps_triangles(mesh in grid_mesh()) {
        let adj = EdgeAdjacency::build(&mesh);
        let components = Regions::components(&mesh, &adj);
        components.sanity_check(&mesh).unwrap();
        prop_assert_eq!(&components.region_of_triangle, &naive_regions(&mesh));
        let regions = Regions::build(&mesh, &adj);
        regions.sanity_check(&mesh).unwrap();
        let pieces = split_regions(&mesh);
        prop_assert_eq!(pieces.len(), regions.count);
        let mut next_in_piece = vec![0usize; pieces.len()];
        for (t, &r) in regions.region_of_triangle.iter().enumerate() {
            let piece = &pieces[r as usize];
            piece.sanity_check().unwrap();
            let tri = piece.triangles[next_in_piece[r as usize]];
            next_in_piece[r as usize] += 1;
            let got = tri.map(|i| piece.positions[i as usize].to_array().map(f64::to_bits));
            let want = mesh.corners(t).map(|p| p.to_array().map(f64::to_bits));
            prop_assert_eq!(got, want);
        }
        for (piece, used) in pieces.iter().zip(next_in_piece) {
            prop_assert_eq!(piece.triangles.len(), used);
            prop_assert_eq!(piece.compacted().positions.len(), piece.positions.len());
        }
    }

    #[test]
    fn report_matches_naive_counts(mesh in grid_mesh()) {
        let report = mesh.report();
        let naive = naive_edges(&mesh);
        let uses = |n: usize| naive.values().filter(|f| f.len() == n).count();
        prop_assert_eq!(report.edges, naive.len());
        prop_assert_eq!(report.boundary_edges, uses(1));
        prop_assert_eq!(report.nonmanifold_edges, naive.values().filter(|f| f.len() >= 3).count());
        prop_assert_eq!(report.components, naive_regions(&mesh).iter().copied().max().map_or(0, |m| m as usize + 1));
        // Degenerate by exact integer cross product.
        let degenerate = (0..mesh.triangles.len())
            .filter(|&t| {
                let [a, b, c] = mesh.corners(t);
                let [i, j, k] = mesh.triangles[t];
                i == j || j == k || k == i || (b - a).cross(c - a) == DVec3::ZERO
            })
            .count();
        prop_assert_eq!(report.degenerate_triangles, degenerate);
        prop_assert_eq!(report.closed, !mesh.triangles.is_empty() && naive.values().all(|f| f.len() == 2));
        if report.manifold {
            prop_assert_eq!(report.nonmanifold_edges + report.misoriented_edges + report.nonmanifold_vertices, 0);
        }
    }

    #[test]
    fn weld_matches_bit_map(mesh in grid_mesh(), flip in prop::collection::vec(prop::bool::ANY, 24)) {
        // Sprinkle -0.0 in place of 0.0: it must weld with 0.0.
        let mut mesh = mesh;
        for (p, f) in mesh.positions.iter_mut().zip(&flip) {
            if *f && p.x == 0.0 {
                p.x = -0.0;
            }
        }
        let welded = weld_exact(&mesh);
        welded.sanity_check().unwrap();
        let mut first: BTreeMap<[u64; 3], u32> = BTreeMap::new();
        let mut order = Vec::new();
        for p in &mesh.positions {
            let n = first.len() as u32;
            if *first.entry(bits(*p)).or_insert(n) == n {
                order.push(*p);
            }
        }
        prop_assert_eq!(welded.positions.iter().map(|p| p.to_array().map(f64::to_bits)).collect::<Vec<_>>(),
                        order.iter().map(|p| p.to_array().map(f64::to_bits)).collect::<Vec<_>>());
        for (t, tri) in welded.triangles.iter().enumerate() {
            prop_assert_eq!(tri.map(|i| bits(welded.positions[i as usize])), mesh.triangles[t].map(|i| bits(mesh.positions[i as usize])));
        }
        let soup = weld_soup(&testkit::to_soup(&mesh));
        soup.sanity_check().unwrap();
        prop_assert_eq!(soup.triangles.len(), mesh.triangles.len());
        prop_assert!(soup.positions.len() <= first.len());
    }

    #[test]
    fn ray_cast_matches_brute_force(mesh in float_mesh(), origin in vec3(-12.0..12.0), dir in direction(), t_max in prop_oneof![Just(f64::INFINITY), 0.0f64..30.0]) {
        let index = SpatialIndex::build(&mesh);
        index.sanity_check(&mesh).unwrap();
        let got = index.ray_cast(&mesh, origin, dir, t_max);
        let brute = WatertightRay::new(origin, dir).and_then(|ray| {
            (0..mesh.triangles.len() as u32)
                .filter_map(|f| ray.intersect(&mesh, f, t_max))
                .min_by(|a, b| a.t.total_cmp(&b.t).then(a.face.cmp(&b.face)))
        });
        prop_assert_eq!(got, brute);
    }

    #[test]
    fn ray_aimed_at_a_triangle_hits_at_or_before_it(mesh in float_mesh(), origin in vec3(-12.0..12.0), pick in any::<prop::sample::Index>(), w in prop::array::uniform3(0.01f64..1.0)) {
        let index = SpatialIndex::build(&mesh);
        let face = pick.index(mesh.triangles.len());
        let [a, b, c] = mesh.corners(face);
        let target = (a * w[0] + b * w[1] + c * w[2]) / (w[0] + w[1] + w[2]);
        let dir = target - origin;
        // Well-shaped triangle, not hit at a grazing angle (rounding of `target` stays harmless).
        let n = (b - a).cross(c - a);
        prop_assume!(n.length() > 1e-2 * (b - a).length() * (c - a).length());
        prop_assume!(dir.length() > 1e-3 && n.normalize().dot(dir.normalize()).abs() > 1e-2);
        let hit = index.ray_cast(&mesh, origin, dir, 2.0);
        prop_assert!(hit.is_some());
        let hit = hit.unwrap();
        prop_assert!(hit.t <= 1.0 + 1e-9, "hit at t = {} beyond the aimed point", hit.t);
        prop_assert!((hit.bary.x + hit.bary.y + hit.bary.z - 1.0).abs() < 1e-9);
    }

    #[test]
    fn closest_point_matches_brute_force(mesh in float_mesh(), p in vec3(-15.0..15.0), max_distance in prop_oneof![Just(f64::INFINITY), 0.0f64..8.0]) {
        let index = SpatialIndex::build(&mesh);
        let got = index.closest_point_within(&mesh, p, max_distance);
        let brute = (0..mesh.triangles.len())
            .map(|f| {
                let [a, b, c] = mesh.corners(f);
                let (q, bary) = closest_on_triangle(p, a, b, c);
                ((p - q).length_squared(), f as u32, q, bary)
            })
            .min_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)))
            .filter(|x| x.0 <= max_distance * max_distance);
        match (got, brute) {
            (None, None) => {}
            (Some(g), Some((d2, face, q, bary))) => {
                prop_assert_eq!((g.face, g.point, g.bary), (face, q, bary));
                prop_assert_eq!(g.distance, d2.sqrt());
                prop_assert!((g.bary.x + g.bary.y + g.bary.z - 1.0).abs() < 1e-12);
            }
            (g, b) => prop_assert!(false, "index {:?} vs brute force {:?}", g, b),
        }
    }

    #[test]
    fn faces_in_box_matches_brute_force(mesh in float_mesh(), c in vec3(-12.0..12.0), half in vec3(0.0..6.0)) {
        let index = SpatialIndex::build(&mesh);
        let query = Aabb { min: c - half, max: c + half };
        let mut got = Vec::new();
        index.faces_in_box(&query, &mut got);
        let set: BTreeSet<u32> = got.iter().copied().collect();
        prop_assert_eq!(set.len(), got.len(), "no face twice");
        for f in 0..mesh.triangles.len() {
            let b = Aabb::from_points(&mesh.corners(f));
            if b.overlaps(&query) {
                prop_assert!(set.contains(&(f as u32)), "face {} missing", f);
            } else if set.contains(&(f as u32)) {
                // Only an f32 rounding of the box may let a face in.
                prop_assert!(b.expanded(1e-5).overlaps(&query), "face {} far from the box", f);
            }
        }
    }
}

#[test]
fn watertight_rays_from_the_centre_through_every_vertex_and_edge_hit() {
    let sphere = checked(testkit::icosphere(3, 1.5));
    let index = SpatialIndex::build(&sphere);
    index.sanity_check(&sphere).unwrap();
    let adj = EdgeAdjacency::build(&sphere);
    let centre = DVec3::new(1e-3, -2e-3, 0.5e-3);
    let mut targets: Vec<DVec3> = sphere.positions.clone();
    targets.extend(
        adj.edges
            .iter()
            .map(|&[a, b]| (sphere.positions[a as usize] + sphere.positions[b as usize]) * 0.5),
    );
    for target in targets {
        let hit = index.ray_cast(&sphere, centre, target - centre, f64::INFINITY);
        assert!(
            hit.is_some(),
            "ray towards {target} escaped the closed sphere"
        );
    }
}

#[test]
fn testkit_shapes_index_consistently() {
    for (mesh, inside) in [
        (testkit::icosphere(4, 1.0), DVec3::ZERO),
        (testkit::geodesic_sphere(7, 3.0), DVec3::new(0.5, 1.0, -1.0)),
        (testkit::torus(2.0, 0.5, 32, 12), DVec3::new(0.0, 2.0, 0.1)),
        (testkit::uv_sphere(10, 16, 2.0), DVec3::ZERO),
        (
            testkit::cube(DVec3::splat(-2.0), DVec3::new(1.0, 2.0, 3.0)),
            DVec3::ZERO,
        ),
    ] {
        let mesh = checked(mesh);
        let report = mesh.report();
        assert!(
            report.closed && report.manifold && report.regions == 1,
            "{report:?}"
        );
        assert_eq!(report.degenerate_triangles, 0);
        assert!(mesh.volume() > 0.0);
        let index = SpatialIndex::build(&mesh);
        index.sanity_check(&mesh).unwrap();
        // From a point inside, the closest point is on the surface and every ray hits.
        let cp = index.closest_point(&mesh, inside).unwrap();
        assert!(cp.distance > 0.0);
        assert!(
            index
                .ray_cast(&mesh, inside, DVec3::new(0.3, 0.2, 1.0), f64::INFINITY)
                .is_some()
        );
        let welded = checked(weld_soup(&testkit::to_soup(&mesh)));
        assert_eq!(welded.report(), report);
    }
}

#[test]
fn geodesic_sphere_has_the_expected_edges_and_one_region() {
    let mesh = checked(testkit::geodesic_sphere(64, 1.0));
    let adj = EdgeAdjacency::build(&mesh);
    assert_eq!(adj.edge_count(), 30 * 64 * 64);
    assert_eq!(Regions::build(&mesh, &adj).count, 1);
}
