//! The boolean: invariants on generic cuts, the named degenerate catalogue, invalid cutters.

mod boolean_common;

use boolean_common::*;
use csg::testkit::{cube, icosphere};
use csg::{CutError, DVec3, Mesh, TargetIndex};

fn v(x: f64, y: f64, z: f64) -> DVec3 {
    DVec3::new(x, y, z)
}

#[test]
fn box_through_sphere_makes_a_tunnel() {
    let target = icosphere(3, 10.0);
    let cutter = cube(v(-3.0, -3.0, -20.0), v(3.0, 3.0, 20.0));
    let r = cut_and_check(&target, &cutter);
    check_cut_welded(&target, &r).unwrap();
    // A tunnel: two contour loops, walls are the four sides of the box inside the sphere.
    assert_eq!(r.contours.len(), 2);
    assert!(!r.walls.mesh.is_empty());
    // The removed piece is close to the analytic volume of the box ∩ ball.
    let rw = concat(&r.removed.mesh, &r.walls.mesh.reversed());
    let vol = volume(&rw);
    assert!(
        vol > 6.0 * 6.0 * 15.0 && vol < 6.0 * 6.0 * 20.0,
        "removed volume {vol}"
    );
}

/// A cutter that runs far past a small target (a stroke painted across a small structure seen
/// from far away) reaches beyond the target's own lattice: the cut runs on a wider lattice and
/// removes the same as a short cutter with the same cross-section, checked by the full contract.
#[test]
fn a_long_cutter_through_a_small_target_is_cut_not_refused() {
    let target = icosphere(3, 1.0);
    let index = TargetIndex::build(target.clone()).unwrap();
    let long = cube(v(-0.3, -0.3, -400.0), v(0.3, 0.3, 20.0));
    let short = cube(v(-0.3, -0.3, -2.0), v(0.3, 0.3, 2.0));
    // The long cutter is far beyond the cached lattice (about 2^28 steps of 2^-26 units).
    assert!(index.lattice.quantize(v(0.0, 0.0, -400.0)).is_none());
    let far = cut_checked(&index, &target, &long).unwrap();
    let near = cut_checked(&index, &target, &short).unwrap();
    check_cut_welded(&target, &far).unwrap();
    assert_eq!(far.contours.len(), 2, "a tunnel through the ball");
    assert_eq!(far.removed_faces, near.removed_faces);
    let removed = |r: &csg::CutResult| volume(&concat(&r.removed.mesh, &r.walls.mesh.reversed()));
    let (a, b) = (removed(&far), removed(&near));
    assert!(a > 0.5 && (a - b).abs() < 1e-4 * b, "removed {a} vs {b}");
    // Beyond `MAX_REACH` target sizes the cutter is still refused, with the reason.
    let reach = csg::MAX_REACH * 2.0 + 10.0;
    let too_long = cube(v(-0.3, -0.3, -reach), v(0.3, 0.3, 2.0));
    let err = csg::subtract(&index, &too_long).unwrap_err();
    assert!(matches!(err, CutError::OutOfRange { .. }), "{err}");
    assert!(err.to_string().contains("1024 target sizes"), "{err}");
}

#[test]
fn strip_groove_on_sphere() {
    let target = icosphere(4, 50.0);
    let path: Vec<DVec3> = (0..12)
        .map(|i| {
            let a = -0.6 + 0.1 * i as f64;
            v(50.0 * a.sin(), -50.0 * a.cos() * 0.2, 50.0 * a.cos())
        })
        .collect();
    let cutter = strip(&path, v(0.0, 1.0, 0.3), 8.0, 10.0);
    let r = cut_and_check(&target, &cutter);
    check_cut_welded(&target, &r).unwrap();
    assert!(!r.contours.is_empty());
    assert!(r.removed.mesh.triangle_count() > 0);
}

#[test]
fn cutter_outside_target_changes_nothing() {
    let target = icosphere(2, 1.0);
    let cutter = cube(v(2.0, 2.0, 2.0), v(3.0, 3.0, 3.0));
    let r = cut_and_check(&target, &cutter);
    assert!(r.is_empty());
    assert!(r.removed_faces.is_empty());
    assert!(r.kept_new_faces.is_empty());
    assert!(r.contours.is_empty());
    // Boxes overlapping but the cutter still outside: also empty.
    let cutter = cube(v(0.9, 0.9, 0.9), v(3.0, 3.0, 3.0));
    let r = cut_and_check(&target, &cutter);
    assert!(r.is_empty());
}

#[test]
fn cutter_inside_target() {
    // A small cube strictly inside the sphere: walls are the whole cube (reversed), nothing of
    // the target is removed, the kept part is unchanged.
    let target = icosphere(2, 1.0);
    let cutter = cube(v(-0.2, -0.2, -0.2), v(0.2, 0.2, 0.2));
    let r = cut_and_check(&target, &cutter);
    assert!(r.removed_faces.is_empty());
    assert_eq!(r.walls.mesh.triangle_count(), 12);
    assert!(r.removed.mesh.is_empty());
    assert!((volume(&r.walls.mesh) + 0.4f64.powi(3)).abs() < 1e-12);
}

#[test]
fn target_inside_cutter_is_removed_whole() {
    let target = icosphere(1, 1.0);
    let cutter = cube(v(-2.0, -2.0, -2.0), v(2.0, 2.0, 2.0));
    let r = cut_and_check(&target, &cutter);
    assert_eq!(r.removed_faces.len(), target.triangle_count());
    assert!(r.walls.mesh.is_empty());
    assert_eq!(r.stats.inside_tests, 2);
}

#[test]
fn coplanar_faces() {
    // Two cubes sharing part of a face plane: the cutter's bottom face lies in the target's top
    // face plane, and both cubes overlap in that plane.
    let target = cube(v(0.0, 0.0, 0.0), v(2.0, 2.0, 2.0));
    // Each with the volume of the cutter box inside the target.
    for (case, (cutter, removes)) in [
        (cube(v(0.5, 0.5, 2.0), v(1.5, 1.5, 3.0)), 0.0), // touching from outside, face on face
        (cube(v(0.5, 0.5, 1.0), v(1.5, 1.5, 2.0)), 1.0), // inside, top face flush with the target's
        (cube(v(0.5, 0.5, 1.0), v(2.0, 2.0, 3.0)), 2.25), // flush on two sides, crossing the top
        (cube(v(-1.0, 0.0, 1.0), v(3.0, 2.0, 3.0)), 4.0), // shares the y faces
    ]
    .iter()
    .enumerate()
    {
        let r = cut_and_check(&target, cutter);
        assert_removes(&r, *removes, &format!("coplanar case {case}"));
    }
    // The cutter equal to the target: the tie-break translates the cutter by δ, so kept is a
    // shell of zero thickness on the −x, −y, −z sides. Symbolically it is closed; after rounding
    // its faces coincide with the walls, so only the measures are checked here (see the
    // robustness contract).
    let index = TargetIndex::build(target.clone()).unwrap();
    let r = csg::subtract(&index, &target).unwrap();
    check_measures(&target, &r).unwrap();
    let rw = concat(&r.removed.mesh, &r.walls.mesh.reversed());
    assert!((volume(&rw) - 8.0).abs() < 1e-12);
}

#[test]
fn cutter_vertex_on_target_vertex() {
    let target = cube(v(0.0, 0.0, 0.0), v(2.0, 2.0, 2.0));
    // Cutter corner exactly at the target corner (2,2,2), reaching inside: the unit cube
    // [1, 2]³ goes.
    let r = cut_and_check(&target, &cube(v(1.0, 1.0, 1.0), v(2.0, 2.0, 2.0)));
    assert_removes(&r, 1.0, "corner box inside");
    // And reaching outside from the corner: nothing goes.
    let r = cut_and_check(&target, &cube(v(2.0, 2.0, 2.0), v(3.0, 3.0, 3.0)));
    assert_removes(&r, 0.0, "corner box outside");
    // A tetrahedral cutter whose apex is a sphere vertex and whose other corners are well inside
    // the (convex) sphere: the whole tetrahedron goes.
    let sphere = icosphere(2, 1.0);
    let apex = sphere.positions[0];
    let corners = [
        apex,
        apex * 0.5 + v(0.3, 0.0, 0.0),
        apex * 0.5 + v(-0.2, 0.3, 0.0),
        apex * 0.5 + v(0.0, -0.2, 0.3),
    ];
    let tet = tetra(corners[0], corners[1], corners[2], corners[3]);
    let r = cut_and_check(&sphere, &tet);
    assert_removes(
        &r,
        tetra_volume(corners[0], corners[1], corners[2], corners[3]),
        "tetrahedron at a sphere vertex",
    );
}

#[test]
fn cutter_vertex_on_target_edge() {
    let target = cube(v(0.0, 0.0, 0.0), v(2.0, 2.0, 2.0));
    // Box with a vertex at the midpoint of the target's top edge (x from 0 to 2, y=2, z=2):
    // inside it cuts the unit cube [1, 2]³, outside it touches the edge only.
    let r = cut_and_check(&target, &cube(v(1.0, 1.0, 1.0), v(3.0, 2.0, 2.0)));
    assert_removes(&r, 1.0, "box below the edge");
    let r = cut_and_check(&target, &cube(v(1.0, 2.0, 2.0), v(3.0, 3.0, 3.0)));
    assert_removes(&r, 0.0, "box above the edge");
}

#[test]
fn cutter_vertex_on_target_face() {
    let target = cube(v(0.0, 0.0, 0.0), v(2.0, 2.0, 2.0));
    // A tetrahedron with one vertex on the top face, the others above: it only touches.
    let above = [
        v(0.7, 0.6, 2.0),
        v(0.2, 0.2, 3.0),
        v(1.5, 0.3, 3.0),
        v(0.8, 1.6, 3.0),
    ];
    let r = cut_and_check(&target, &tetra(above[0], above[1], above[2], above[3]));
    assert_removes(&r, 0.0, "tetrahedron above the face");
    // ... and the others below: all of it is inside the cube.
    let below = [
        v(0.7, 0.6, 2.0),
        v(0.2, 0.2, 1.0),
        v(1.5, 0.3, 1.0),
        v(0.8, 1.6, 1.0),
    ];
    let r = cut_and_check(&target, &tetra(below[0], below[1], below[2], below[3]));
    assert_removes(
        &r,
        tetra_volume(below[0], below[1], below[2], below[3]),
        "tetrahedron below the face",
    );
}

#[test]
fn cutter_edge_along_target_edge() {
    let target = cube(v(0.0, 0.0, 0.0), v(2.0, 2.0, 2.0));
    // Cutter edge along the target's top front edge (y=0, z=2) and along the diagonal of a
    // face's triangulation.
    let r = cut_and_check(&target, &cube(v(0.5, -1.0, 2.0), v(1.5, 0.0, 3.0)));
    assert_removes(&r, 0.0, "box outside along the edge");
    let r = cut_and_check(&target, &cube(v(0.5, 0.0, 1.0), v(1.5, 1.0, 2.0)));
    assert_removes(&r, 1.0, "box inside along the edge");
    // The tetrahedron's edge a–b lies on the top face's diagonal, c is above the face and d
    // below: the plane z = 2 through a–b meets c–d at e, and the piece a b e d below it is inside
    // the cube, |de| / |dc| = 0.5 / 1.3 of the whole.
    let (a, b, c, d) = (
        v(0.0, 0.0, 2.0),
        v(2.0, 2.0, 2.0),
        v(1.0, 0.2, 2.8),
        v(0.9, 0.5, 1.5),
    );
    let r = cut_and_check(&target, &tetra(a, b, c, d));
    assert_removes(
        &r,
        tetra_volume(a, b, c, d) * 0.5 / 1.3,
        "tetrahedron along the diagonal",
    );
}

#[test]
fn zero_area_target_triangle() {
    let flat = flat_sliver_cube();
    check_closed_oriented(&flat).unwrap();
    // Each with the volume of the box inside the cube [0, 2]³ (the sliver adds none).
    for (cutter, removes) in [
        (cube(v(0.7, -1.0, 1.5), v(1.2, 1.0, 3.0)), 0.25), // crosses the sliver's edges
        (cube(v(1.2, -1.0, 1.0), v(1.7, 1.0, 3.0)), 0.5),
        (cube(v(0.5, -0.5, 1.9), v(1.5, 0.5, 2.5)), 0.05), // contains part of the sliver
        (cube(v(1.0, -1.0, 1.0), v(2.0, 1.0, 3.0)), 1.0), // cutter face through the sliver's middle vertex
    ] {
        let r = cut_and_check(&flat, &cutter);
        assert_removes(&r, removes, &format!("box {:?}", cutter.positions[0]));
    }
}

/// A cube whose top front edge carries a vertex m = (1, 0, 2) used by a zero-area triangle
/// [4, m, 5] on the front face side: the front face is [0,1,5], [0,5,m], [0,m,4] and the zero
/// area triangle [4,m,5] fills the "gap" with its mirror on the top face.
fn flat_sliver_cube() -> Mesh {
    let mut m = cube(v(0.0, 0.0, 0.0), v(2.0, 2.0, 2.0));
    let mid = m.positions.len() as u32;
    m.positions.push(v(1.0, 0.0, 2.0));
    let tris = &mut m.triangles;
    // Front face [0,1,5],[0,5,4] → [0,1,5],[0,5,mid],[0,mid,4]: edge 5-4 is now 5-mid-4 on the
    // front side, while the top face still uses edge 4-5; the zero-area triangle [4, mid, 5]
    // closes the gap (collinear corners).
    let front = tris.iter().position(|t| *t == [0, 5, 4]).unwrap();
    tris[front] = [0, 5, mid];
    tris.push([0, mid, 4]);
    tris.push([4, mid, 5]);
    m
}

#[test]
fn cutter_touching_vertex_only() {
    let target = cube(v(0.0, 0.0, 0.0), v(2.0, 2.0, 2.0));
    // The cutter touches the target at one corner only (from outside).
    let tet = tetra(
        v(2.0, 2.0, 2.0),
        v(3.0, 2.5, 2.5),
        v(2.5, 3.0, 2.5),
        v(2.5, 2.5, 3.0),
    );
    let r = cut_and_check(&target, &tet);
    // Whatever the tie-break decides, it is a tiny or empty change.
    let removed = concat(&r.removed.mesh, &r.walls.mesh.reversed());
    assert!(volume(&removed).abs() < 1e-12);
    // Sphere vertex touched by a cutter vertex from outside.
    let sphere = icosphere(2, 1.0);
    let p = sphere.positions[5];
    let tet = tetra(
        p,
        p * 1.5 + v(0.1, 0.0, 0.0),
        p * 1.5 + v(0.0, 0.1, 0.0),
        p * 1.5 + v(0.0, 0.0, 0.1),
    );
    let r = cut_and_check(&sphere, &tet);
    let removed = concat(&r.removed.mesh, &r.walls.mesh.reversed());
    assert!(volume(&removed).abs() < 1e-12);
}

#[test]
fn many_sub_cutters_at_once() {
    let target = icosphere(3, 10.0);
    let cutters: Vec<Mesh> = (0..5)
        .map(|k| {
            let x = -8.0 + 4.0 * k as f64;
            cube(v(x, -1.0, 5.0), v(x + 1.0, 1.0, 12.0))
        })
        .collect();
    let refs: Vec<&Mesh> = cutters.iter().collect();
    let index = TargetIndex::build(target.clone()).unwrap();
    let r = csg::subtract_with(
        &index,
        &refs,
        &csg::CutOptions::default().with_merge_coincident(false),
    )
    .unwrap();
    check_cut(&target, &r).unwrap();
    for k in 0..5u32 {
        let rem = r.removed.of_sub_cutter(k);
        let walls = r.walls.of_sub_cutter(k);
        let closed = concat(&rem.mesh, &walls.mesh.reversed());
        let mut faces = part_faces(&rem, false);
        faces.extend(part_faces(&walls, true));
        check_closed_by_source(&faces).unwrap();
        // Each matches the single cut.
        let single = csg::subtract(&index, &cutters[k as usize]).unwrap();
        let v_single = volume(&concat(&single.removed.mesh, &single.walls.mesh.reversed()));
        assert!(
            (volume(&closed) - v_single).abs() < 1e-9 * v_single.abs(),
            "sub-cutter {k}"
        );
        assert!(v_single > 0.0);
    }
    // Overlapping sub-cutters are refused.
    let a = cube(v(-1.0, -1.0, 5.0), v(1.0, 1.0, 12.0));
    let b = cube(v(0.0, 0.0, 6.0), v(2.0, 2.0, 13.0));
    assert!(matches!(
        csg::subtract_many(&index, &[&a, &b]),
        Err(CutError::SelfIntersecting { .. })
    ));
}

#[test]
fn invalid_cutters_are_typed_errors() {
    let index = TargetIndex::build(icosphere(2, 1.0)).unwrap();
    let good = cube(v(0.0, 0.0, 0.0), v(2.0, 2.0, 2.0));
    // Open.
    let mut open = good.clone();
    open.triangles.pop();
    assert!(matches!(
        csg::subtract(&index, &open),
        Err(CutError::NotClosed { .. })
    ));
    // Inconsistent orientation.
    let mut flipped = good.clone();
    flipped.triangles[0] = [
        flipped.triangles[0][0],
        flipped.triangles[0][2],
        flipped.triangles[0][1],
    ];
    assert!(matches!(
        csg::subtract(&index, &flipped),
        Err(CutError::NotClosed { .. } | CutError::NotOriented { .. })
    ));
    // Inward.
    assert!(matches!(
        csg::subtract(&index, &good.reversed()),
        Err(CutError::NotPositive { .. })
    ));
    // Non-finite.
    let mut nan = good.clone();
    nan.positions[3].x = f64::NAN;
    assert!(matches!(
        csg::subtract(&index, &nan),
        Err(CutError::InvalidMesh { .. })
    ));
    // Far away.
    let far = cube(v(1e6, 0.0, 0.0), v(1e6 + 1.0, 1.0, 1.0));
    assert!(matches!(
        csg::subtract(&index, &far),
        Err(CutError::OutOfRange { .. })
    ));
    // Self-intersecting: two overlapping cubes in one mesh.
    let mut two = cube(v(0.0, 0.0, 0.0), v(1.0, 1.0, 1.0));
    two.append(&cube(v(0.5, 0.5, 0.5), v(1.5, 1.5, 1.5)));
    assert!(matches!(
        csg::subtract(&index, &two),
        Err(CutError::SelfIntersecting { .. })
    ));
    // Empty.
    assert!(matches!(
        csg::subtract(&index, &Mesh::default()),
        Err(CutError::EmptyCutter { .. })
    ));
}

/// A tetrahedron on four points, oriented outward.
pub fn tetra(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> Mesh {
    let mut m = Mesh {
        positions: vec![a, b, c, d],
        triangles: vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]],
    };
    if volume(&m) < 0.0 {
        m = m.reversed();
    }
    m
}

/// A closed cutter with a zero-area triangle (a box whose bottom edge 0–1 carries an extra
/// midpoint vertex 8, fixed up with the sliver (1, 0, 8)): vertex 8 touches the neighbouring
/// face (0, 1, 5) along its edge, and touching counts as self-intersecting, so such a cutter is
/// a typed error (never a cut with a face whose plane is undefined).
#[test]
fn zero_area_cutter_triangle_is_refused() {
    let target = icosphere(3, 10.0);
    let index = TargetIndex::build(target).unwrap();
    let mut cutter = cube(v(-3.0, -3.0, 9.5), v(3.0, 3.0, 14.0));
    cutter.positions.push(v(0.0, -3.0, 9.5));
    // -z face was (0, 2, 3), (0, 3, 1): route its edge 1 → 0 through 8.
    let k = cutter
        .triangles
        .iter()
        .position(|t| *t == [0, 3, 1])
        .unwrap();
    cutter.triangles[k] = [0, 3, 8];
    cutter.triangles.push([8, 3, 1]);
    cutter.triangles.push([1, 0, 8]);
    assert!(matches!(
        csg::subtract(&index, &cutter),
        Err(CutError::SelfIntersecting { .. })
    ));
}

/// A self-intersecting target: two interpenetrating spheres (two closed regions) cut by a slab
/// whose top and bottom faces meet both spheres in circles that cross each other. Kept and
/// removed still partition the target exactly; the crossings on the cutter faces (whose walls
/// the boolean does not resolve, see the robustness contract) are named by the diagnostic, which
/// finds none on a target that does not intersect itself.
#[test]
fn interpenetrating_regions_are_exact_on_the_target_and_reported_on_walls() {
    let mut target = icosphere(3, 5.0);
    for p in &mut target.positions {
        p.x -= 3.0;
    }
    let mut other = icosphere(3, 5.0);
    for p in &mut other.positions {
        p.x += 3.0;
    }
    target.append(&other);
    let index = TargetIndex::build(target.clone()).unwrap();
    let cutter = cube(v(-8.5, -7.5, -1.0), v(8.5, 7.5, 1.0));
    let r = csg::subtract(&index, &cutter).unwrap();
    let kept = r.materialize(&target);
    let (at, ak, ar) = (area(&target), area(&kept), area(&r.removed.mesh));
    assert!(
        (ak + ar - at).abs() <= 1e-9 * at,
        "area {ak} + {ar} != {at}"
    );
    let crossings = csg::cutcheck::crossing_cutter_faces(&index, &[&cutter]).unwrap();
    // Two circles cross twice on the top face and twice on the bottom face.
    assert_eq!(
        crossings.iter().map(|c| c.1).sum::<usize>(),
        4,
        "{crossings:?}"
    );
    // One sphere alone: no crossing anywhere.
    let single = icosphere(3, 5.0);
    let index = TargetIndex::build(single).unwrap();
    assert!(
        csg::cutcheck::crossing_cutter_faces(&index, &[&cutter])
            .unwrap()
            .is_empty()
    );
}
