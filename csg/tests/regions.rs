//! Nested shells: each region (a component with its cavities) is cut as its own solid.
//!
//! The cases of the region rule (`csg::cavities`): nested cubes both outward (two solids) and
//! outward around inward (one hollow solid), three levels, a hollow sphere, shells touching each
//! other. Every cut is computed with `merge_coincident = false` and checked with
//! `cutcheck::check_closed_cut`, which checks per region that kept + walls and removed + reversed
//! walls close up by vertex identity and that the region's volume identity holds; the figures
//! (walls areas, removed volumes) are the exact ones of the geometry.

use csg::cutcheck;
use csg::regions::{Regions, split_regions};
use csg::{CutOptions, DVec3, EdgeAdjacency, Mesh, TargetIndex, subtract_with, testkit};

fn cube(min: f64, max: f64) -> Mesh {
    testkit::cube(DVec3::splat(min), DVec3::splat(max))
}

fn join(parts: &[Mesh]) -> Mesh {
    let mut m = Mesh::default();
    for p in parts {
        m.append(p);
    }
    m.sanity_check().unwrap();
    m
}

/// The slab `lo <= x <= hi` reaching past the cube `[0, 10]³` on the other axes.
fn slab(lo: f64, hi: f64) -> Mesh {
    testkit::cube(DVec3::new(lo, -1.0, -1.0), DVec3::new(hi, 11.0, 11.0))
}

/// Cuts, checks the contract per region, and returns the result with the index.
fn cut(target: &Mesh, cutter: &Mesh) -> (TargetIndex, csg::CutResult) {
    let index = TargetIndex::build(target.clone()).unwrap();
    let options = CutOptions::default().with_merge_coincident(false);
    let result = subtract_with(&index, &[cutter], &options).unwrap();
    cutcheck::check_closed_cut(target, &result).unwrap();
    (index, result)
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * b.abs().max(1.0)
}

/// Region count from the mesh core, the index and the split agree.
fn region_count(mesh: &Mesh) -> usize {
    let regions = Regions::build(mesh, &EdgeAdjacency::build(mesh));
    regions.sanity_check(mesh).unwrap();
    let index = TargetIndex::build(mesh.clone()).unwrap();
    assert_eq!(index.regions.count, regions.count);
    assert_eq!(
        index.region_labels().region_of_triangle,
        regions.region_of_triangle
    );
    assert_eq!(split_regions(mesh).len(), regions.count);
    assert_eq!(mesh.report().regions, regions.count);
    regions.count
}

/// The volume of the removed solid of each region (removed + reversed walls).
fn removed_volumes(index: &TargetIndex, result: &csg::CutResult) -> Vec<f64> {
    result
        .region_parts(index)
        .iter()
        .map(|p| {
            let mut m = p.removed.clone();
            m.append(&p.walls.reversed());
            cutcheck::volume(&m)
        })
        .collect()
}

#[test]
fn nested_outward_cubes_are_two_solids() {
    let target = join(&[cube(0.0, 10.0), cube(3.0, 7.0)]);
    assert_eq!(region_count(&target), 2);
    let (index, result) = cut(&target, &slab(3.5, 6.5));
    // Two solids: 2 · 10² for the outer one, 2 · 4² for the inner one.
    assert!(
        close(result.walls.mesh.area(), 232.0),
        "{}",
        result.walls.mesh.area()
    );
    let parts = result.region_parts(&index);
    assert_eq!(parts.len(), 2);
    assert!(close(parts[0].walls.area(), 200.0));
    assert!(close(parts[1].walls.area(), 32.0));
    assert!(parts.iter().all(|p| p.closed));
    let v = removed_volumes(&index, &result);
    assert!(close(v[0], 300.0) && close(v[1], 48.0), "{v:?}");
    // Each region's parts close up by position too (the files the CLI writes, with coincident
    // vertices merged as the CLI's default options do).
    let merged = csg::subtract(&index, &slab(3.5, 6.5)).unwrap();
    for p in &merged.region_parts(&index) {
        let mut kw = p.kept.clone();
        kw.append(&p.walls);
        let report = csg::weld::weld_exact(&kw).report();
        assert!(report.closed && report.manifold, "{report:?}");
    }
}

#[test]
fn outward_cube_around_inward_cube_is_one_hollow_solid() {
    let target = join(&[cube(0.0, 10.0), cube(3.0, 7.0).reversed()]);
    assert_eq!(region_count(&target), 1);
    let (index, result) = cut(&target, &slab(3.5, 6.5));
    // The cavity is a hole in the walls: 200 − 32.
    assert!(
        close(result.walls.mesh.area(), 168.0),
        "{}",
        result.walls.mesh.area()
    );
    let v = removed_volumes(&index, &result);
    assert_eq!(v.len(), 1);
    assert!(close(v[0], 300.0 - 48.0), "{v:?}");
}

#[test]
fn three_levels_with_a_cavity_and_an_island() {
    // Outer outward, a cavity in it, an outward island in the cavity: two regions.
    let target = join(&[cube(0.0, 10.0), cube(2.0, 8.0).reversed(), cube(4.0, 6.0)]);
    assert_eq!(region_count(&target), 2);
    let (index, result) = cut(&target, &slab(4.5, 5.5));
    let parts = result.region_parts(&index);
    assert!(close(parts[0].walls.area(), 2.0 * (100.0 - 36.0)));
    assert!(close(parts[1].walls.area(), 2.0 * 4.0));
    let v = removed_volumes(&index, &result);
    assert!(close(v[0], 100.0 - 36.0) && close(v[1], 4.0), "{v:?}");

    // All three outward: three nested solids, each with its full walls.
    let target = join(&[cube(0.0, 10.0), cube(2.0, 8.0), cube(4.0, 6.0)]);
    assert_eq!(region_count(&target), 3);
    let (index, result) = cut(&target, &slab(4.5, 5.5));
    let areas: Vec<f64> = result
        .region_parts(&index)
        .iter()
        .map(|p| p.walls.area())
        .collect();
    assert!(
        close(areas[0], 200.0) && close(areas[1], 72.0) && close(areas[2], 8.0),
        "{areas:?}"
    );
}

#[test]
fn hollow_sphere_walls_skip_the_cavity() {
    let outer = testkit::icosphere(3, 10.0);
    let inner = testkit::icosphere(2, 5.0);
    let cutter = testkit::cube(DVec3::new(-2.0, -12.0, -12.0), DVec3::new(1.5, 12.0, 12.0));
    let hollow = join(&[outer.clone(), inner.reversed()]);
    assert_eq!(region_count(&hollow), 1);
    let (index, hollow_cut) = cut(&hollow, &cutter);
    let nested = join(&[outer, inner]);
    assert_eq!(region_count(&nested), 2);
    let (nested_index, nested_cut) = cut(&nested, &cutter);
    // Same surfaces, same contour: the hollow solid's walls are the outer disc less the inner
    // one, the nested solids' walls are the outer disc plus the inner one.
    let hollow_walls = hollow_cut.walls.mesh.area();
    let parts = nested_cut.region_parts(&nested_index);
    let (outer_walls, inner_walls) = (parts[0].walls.area(), parts[1].walls.area());
    assert!(inner_walls > 0.0);
    assert!(
        close(hollow_walls, outer_walls - inner_walls),
        "{hollow_walls} vs {outer_walls} - {inner_walls}"
    );
    assert!(close(
        nested_cut.walls.mesh.area(),
        outer_walls + inner_walls
    ));
    // Across two cuts (different wall triangulations) the volumes agree up to the rounding of
    // the new vertices off the cutter's planes (a lattice step, about 2e-7 here), not bit for bit.
    let v = removed_volumes(&index, &hollow_cut);
    let w = removed_volumes(&nested_index, &nested_cut);
    assert!((v[0] - (w[0] - w[1])).abs() < 1e-6 * v[0], "{v:?} vs {w:?}");
}

#[test]
fn touching_shells() {
    // An inward cube touching the outer cube's face x = 0 from inside: still its cavity (the
    // vertices on the outer face say nothing, the others decide).
    let outer = cube(0.0, 10.0);
    let inner = testkit::cube(DVec3::new(0.0, 3.0, 3.0), DVec3::new(4.0, 7.0, 7.0));
    let hollow = join(&[outer.clone(), inner.reversed()]);
    assert_eq!(region_count(&hollow), 1);
    let (_, result) = cut(&hollow, &slab(1.0, 2.0));
    assert!(close(result.walls.mesh.area(), 2.0 * (100.0 - 16.0)));

    // The same cube outward: a second solid, touching the first one's boundary.
    let nested = join(&[outer.clone(), inner.clone()]);
    assert_eq!(region_count(&nested), 2);
    let (_, result) = cut(&nested, &slab(1.0, 2.0));
    assert!(close(result.walls.mesh.area(), 2.0 * (100.0 + 16.0)));

    // Two outward cubes touching along a face from outside: two solids side by side.
    let beside = testkit::cube(DVec3::new(10.0, 3.0, 3.0), DVec3::new(14.0, 7.0, 7.0));
    let pair = join(&[outer, beside]);
    assert_eq!(region_count(&pair), 2);
    let cutter = testkit::cube(DVec3::new(8.0, 4.0, -1.0), DVec3::new(12.0, 6.0, 11.0));
    let (index, result) = cut(&pair, &cutter);
    let parts = result.region_parts(&index);
    assert!(parts.iter().all(|p| p.closed && !p.walls.is_empty()));
}

#[test]
fn an_inward_shell_outside_every_other_is_its_own_region() {
    let target = join(&[cube(0.0, 10.0), cube(20.0, 24.0).reversed()]);
    assert_eq!(region_count(&target), 2);
    let index = TargetIndex::build(target).unwrap();
    assert_eq!(index.regions.cavity_of, vec![None, None]);
    assert_eq!(index.regions.volume_sign, vec![1, -1]);
}
