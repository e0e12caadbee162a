//! Tests of [`super`] (`cut_scene.rs`), kept in their own file.

use super::*;
use crate::test_support::{box_cutter, cube, cubes_each_cut, plain_cutter, scene_with_cube_cut};

#[test]
fn exact_cut_of_a_cube_corner_removes_three_squares() {
    let scene = scene_with_cube_cut(crate::scene::CutterViews::default());
    let index = TargetIndex::build(cube(DVec3::ZERO, DVec3::splat(2.0))).unwrap();
    let parts = cut_exact(&index, &scene.cutters[0]).unwrap();
    assert!(
        (parts.removed.area() - 3.0).abs() < 1e-9,
        "{}",
        parts.removed.area()
    );
    assert!(
        (parts.walls.area() - 3.0).abs() < 1e-9,
        "{}",
        parts.walls.area()
    );
    let mut closed = parts.kept.clone();
    closed.append(&parts.walls);
    assert!((closed.volume() - 7.0).abs() < 1e-9, "{}", closed.volume());
    assert_eq!(parts.contour.len(), 1);
    assert_eq!(parts.contour[0].first(), parts.contour[0].last());
}

#[test]
fn preview_has_every_requested_view() {
    let views = crate::scene::CutterViews {
        cut: true,
        transparency: Some(0.3),
        ribbons: Some(crate::scene::SubCutterSpec {
            count: 2,
            width: 0.2,
            placement: cutter::subcutters::Placement::Even,
            relative: false,
        }),
        slices: Some(crate::scene::SubCutterSpec {
            count: 2,
            width: 0.2,
            placement: cutter::subcutters::Placement::Even,
            relative: false,
        }),
    };
    let preview = preview_geometry(&scene_with_cube_cut(views));
    assert!(preview.notes.is_empty(), "{:?}", preview.notes);
    assert_eq!(preview.replaced, vec![true]);
    for kind in [
        PartKind::Kept,
        PartKind::Wall,
        PartKind::Removed,
        PartKind::Ribbon,
        PartKind::SliceWall,
    ] {
        assert!(
            preview.parts.iter().any(|p| p.kind == kind),
            "{kind:?} missing"
        );
    }
    assert_eq!(preview.contours.len(), 1);
    // A cutter with no view leaves the model alone.
    let none = crate::scene::CutterViews {
        cut: false,
        ..crate::scene::CutterViews::default()
    };
    let preview = preview_geometry(&scene_with_cube_cut(none));
    assert_eq!(preview.replaced, vec![false]);
    assert!(preview.parts.is_empty());
}

/// Every cutter cut in turn out of `mesh`, each cut exact and the result closed and manifold.
fn cut_closed(
    cache: &mut CutCache,
    mesh: &Arc<Mesh>,
    cutters: &[(usize, &SceneCutter)],
) -> SequenceResult {
    let sequence = cut_in_turn(cache, mesh, cutters, |_| true, |_| {});
    assert!(sequence.notes.is_empty(), "{:?}", sequence.notes);
    let report = sequence.closed.report();
    assert!(report.closed && report.manifold, "{report:?}");
    sequence
}

/// A sphere with one cutter per box, each cutter straight and aimed at model 0.
fn sphere_scene(boxes: &[[f64; 6]]) -> Scene {
    let mut scene = Scene::default();
    scene.models.push(crate::scene::SceneModel::new(
        "sphere",
        "sphere.obj",
        Arc::new(csg::testkit::icosphere(3, 1.0)),
        [0.8, 0.6, 0.5],
    ));
    for b in boxes {
        scene.cutters.push(plain_cutter(
            0,
            cutter::CutKind::Straight,
            box_cutter(b[0], b[1], b[2], b[3], b[4], b[5]),
        ));
    }
    scene
}

/// Nested structures in one model are each cut closed, and a cavity stays a cavity: two
/// cutters in turn on a cube of side 10 with a cube of side 4 inside (both outward: two
/// solids; the inner one inward: one hollow solid).
#[test]
fn nested_shells_are_each_cut_closed_and_a_cavity_stays_hollow() {
    let outer = cube(DVec3::ZERO, DVec3::splat(10.0));
    let inner = cube(DVec3::splat(3.0), DVec3::splat(7.0));
    let cutter = |planes| SceneCutter {
        target: 0,
        cutter: cutter::Cutter {
            kind: cutter::CutKind::Straight,
            smooth: false,
            levels: cutter::subdivision::DEFAULT_LEVELS,
            direction: cutter::CutDirection::Normal,
            planes,
        },
        views: crate::scene::CutterViews::default(),
    };
    let k1 = cutter(box_cutter(3.5, 6.5, -1.0, 11.0, -1.0, 11.0));
    let k2 = cutter(box_cutter(-1.0, 11.0, 4.5, 5.5, -1.0, 11.0));
    let cutters: Vec<(usize, &SceneCutter)> = vec![(0, &k1), (1, &k2)];
    // Removed: slab 1 (3 thick) and slab 2 (1 thick) overlap in a 3 × 1 bar.
    for (inner, expected) in [
        (inner.clone(), (1000.0 - 370.0) + (64.0 - 52.0)),
        (inner.reversed(), (1000.0 - 64.0) - (370.0 - 52.0)),
    ] {
        let mut model = outer.clone();
        model.append(&inner);
        let sequence = cut_closed(&mut CutCache::default(), &Arc::new(model), &cutters);
        assert!(
            (sequence.closed.volume() - expected).abs() < 1e-9,
            "{} vs {expected}",
            sequence.closed.volume()
        );
    }
}

/// Volume of the sphere minus one box, by a single exact cut (kept + walls).
fn volume_minus(b: [f64; 6]) -> f64 {
    let scene = sphere_scene(&[b]);
    let index = TargetIndex::build(scene.models[0].model.mesh.clone()).unwrap();
    let parts = cut_exact(&index, &scene.cutters[0]).unwrap();
    let mut closed = parts.kept;
    closed.append(&parts.walls);
    closed.volume()
}

#[test]
fn overlapping_cutters_remove_the_union_and_no_wall_survives_inside_the_other() {
    let k1 = [0.0, 2.0, -2.0, 0.2, 0.0, 2.0];
    let k2 = [-2.0, 0.4, -2.0, 2.0, 0.3, 2.0];
    let k12 = [0.0, 0.4, -2.0, 0.2, 0.3, 2.0];
    let scene = sphere_scene(&[k1, k2]);
    let t = scene.models[0].model.mesh.volume();
    // Inclusion–exclusion from single cuts: vol(T ∖ (K1 ∪ K2)).
    let (v1, v2, v12) = (volume_minus(k1), volume_minus(k2), volume_minus(k12));
    let expected = t - (t - v1) - (t - v2) + (t - v12);
    let cutters: Vec<(usize, &SceneCutter)> = scene.cutters.iter().enumerate().collect();
    let mut cache = CutCache::default();
    let sequence = cut_closed(&mut cache, &scene.models[0].model.mesh, &cutters);
    // New contour vertices are rounded once from the lattice (steps of ~1e-8 here).
    assert!(
        (sequence.closed.volume() - expected).abs() < 1e-6,
        "{} vs {expected}",
        sequence.closed.volume()
    );
    // No wall of cutter 1 is left inside cutter 2 (x < 0.4 and z > 0.3), and cutter 2 has
    // walls only outside cutter 1.
    let tags = &sequence.tags;
    for (t, tri) in sequence.closed.triangles.iter().enumerate() {
        let c = tri
            .map(|i| sequence.closed.positions[i as usize])
            .iter()
            .sum::<DVec3>()
            / 3.0;
        let inside = |b: [f64; 6]| {
            c.x > b[0] && c.x < b[1] && c.y > b[2] && c.y < b[3] && c.z > b[4] && c.z < b[5]
        };
        match tags[t] {
            0 => assert!(!inside(k2), "wall of cutter 1 inside cutter 2 at {c}"),
            1 => assert!(!inside(k1), "wall of cutter 2 inside cutter 1 at {c}"),
            _ => {}
        }
    }
    assert!(tags.contains(&0) && tags.contains(&1) && tags.contains(&SURFACE));
    // Preview shows the same: kept + walls of both cutters is the closed result, and the
    // contour is closed loops on the kept surface.
    let preview = preview_geometry(&scene);
    let mut shown = Mesh::default();
    for p in &preview.parts {
        shown.append(&p.mesh);
    }
    assert!(
        (shown.volume() - expected).abs() < 1e-6,
        "{}",
        shown.volume()
    );
    assert!(!preview.contours.is_empty());
    for (_, line) in &preview.contours {
        assert_eq!(line.first(), line.last(), "open contour");
    }
    // A second preview of a moved second cutter reuses the first cutter's cached result.
    let mut moved = scene.clone();
    moved.cutters[1].cutter.planes = box_cutter(-2.0, 0.5, -2.0, 2.0, 0.3, 2.0);
    let again = preview_geometry_with(&moved, &mut cache);
    assert!(again.notes.is_empty(), "{:?}", again.notes);
    assert_eq!(cache.prefixes.len(), 1);
}

#[test]
fn cutter_outside_the_target_removes_nothing() {
    let target = cube(DVec3::ZERO, DVec3::ONE);
    let mut scene = scene_with_cube_cut(crate::scene::CutterViews::default());
    scene.cutters[0].cutter.planes = box_cutter(1.5, 2.5, 1.5, 2.5, 1.5, 2.5);
    let index = TargetIndex::build(target).unwrap();
    let parts = cut_exact(&index, &scene.cutters[0]).unwrap();
    assert!(parts.removed.is_empty() && parts.walls.is_empty() && parts.contour.is_empty());
    assert_eq!(parts.kept.triangle_count(), 12);
}

#[test]
fn cutter_mesh_is_closed_and_outward() {
    let mut scene = scene_with_cube_cut(crate::scene::CutterViews::default());
    scene.cutters[0].cutter.planes = box_cutter(0.0, 2.0, 0.0, 1.0, 0.0, 1.0);
    let surface = cutter_mesh(&scene.cutters[0]);
    assert!(
        (surface.volume() - 2.0).abs() < 1e-9,
        "{}",
        surface.volume()
    );
    csg::check_cutter(&surface).unwrap();
    scene.cutters[0].cutter.smooth = true;
    let smooth = cutter_mesh(&scene.cutters[0]);
    csg::check_cutter(&smooth).unwrap();
    assert!(smooth.triangle_count() > surface.triangle_count());
}

#[test]
fn a_refused_cutter_cuts_nothing_and_says_why() {
    let mut scene = scene_with_cube_cut(crate::scene::CutterViews::default());
    // The middle plane folds back past the last one: the boxes overlap.
    let mut planes = box_cutter(1.0, 3.0, -1.0, 1.0, 1.0, 3.0);
    planes[1] = cutter::BoundedPlane::from_corners(planes[1].corners().map(|p| p + DVec3::X * 3.0));
    scene.cutters[0].cutter.planes = planes;
    let preview = preview_geometry(&scene);
    assert_eq!(preview.notes.len(), 1, "{:?}", preview.notes);
    assert!(
        preview.notes[0].contains("cutter 1 cannot cut"),
        "{}",
        preview.notes[0]
    );
    assert_eq!(preview.reports.len(), 1);
    assert!(!preview.reports[0].1.exact);
    // Nothing in place of the cut: the model is whole and there is no wall.
    assert!(preview.parts.iter().all(|p| p.kind == PartKind::Kept));
    let kept: f64 = preview.parts.iter().map(|p| p.mesh.volume()).sum();
    assert!((kept - 8.0).abs() < 1e-9, "{kept}");
}

#[test]
fn ribbons_of_a_smooth_cutter_lie_inside_its_surface() {
    use cutter::subcutters::Placement;
    let sphere = Arc::new(csg::testkit::icosphere(4, 1.0));
    for placement in [Placement::Even, Placement::Planes, Placement::Horizontal] {
        let mut scene = Scene::default();
        scene.models.push(crate::scene::SceneModel::new(
            "sphere",
            "sphere.obj",
            sphere.clone(),
            [0.8, 0.6, 0.5],
        ));
        let view = crate::scene::SubCutterSpec {
            count: 3,
            width: 0.4,
            placement,
            relative: true,
        };
        scene.cutters.push(SceneCutter {
            target: 0,
            cutter: cutter::Cutter {
                kind: cutter::CutKind::Curving,
                smooth: true,
                levels: cutter::subdivision::DEFAULT_LEVELS,
                direction: cutter::CutDirection::Normal,
                planes: box_cutter(-0.6, 0.6, -0.5, 0.5, 0.3, 1.5),
            },
            views: crate::scene::CutterViews {
                cut: false,
                transparency: None,
                ribbons: Some(view),
                slices: Some(view),
            },
        });
        let preview = preview_geometry(&scene);
        assert!(
            preview.notes.is_empty(),
            "{placement:?}: {:?}",
            preview.notes
        );
        assert!(preview.reports[0].1.exact);
        let smooth = cutter_mesh(&scene.cutters[0]);
        let smooth_index = csg::SpatialIndex::build(&smooth);
        let mut ribbon_area = 0.0;
        for part in &preview.parts {
            if !matches!(part.kind, PartKind::Ribbon | PartKind::SliceWall) {
                continue;
            }
            ribbon_area += part.mesh.area();
            // Every piece lies inside the smooth cutter (up to the rounding of new vertices).
            for t in 0..part.mesh.triangle_count() {
                let c = part.mesh.corners(t).iter().sum::<DVec3>() / 3.0;
                let near = smooth_index.closest_point(&smooth, c).unwrap();
                let outward = (c - near.point).dot(smooth.face_normal_scaled(near.face as usize));
                assert!(
                    outward <= 0.0 || near.distance < 1e-6,
                    "{placement:?}: piece outside at {c}"
                );
            }
        }
        assert!(ribbon_area > 0.0, "{placement:?}: no ribbons");
    }
}

#[test]
fn a_long_lived_cache_keeps_one_preview_per_model_and_only_the_edited_models_index() {
    // More cut models than any fixed bound: editing one cutter must not re-cut the others (and
    // so keep their indexes) because their previews were pushed out.
    let mut scene = cubes_each_cut(6, 2);
    let mut cache = CutCache::default();
    let first = preview_geometry_with(&scene, &mut cache);
    assert!(first.notes.is_empty(), "{:?}", first.notes);
    cache.forget_unused();
    assert_eq!(cache.census().previews, 6);
    // Move the last cutter of model 0, as a drag does, twice.
    for step in 1..=2 {
        let last = &mut scene.cutters[1].cutter.planes;
        *last = box_cutter(1.2 + 0.1 * step as f64, 3.0, -1.0, 1.0, 0.5, 3.0);
        let again = preview_geometry_with(&scene, &mut cache);
        assert!(again.notes.is_empty(), "{:?}", again.notes);
        cache.forget_unused();
        let census = cache.census();
        assert_eq!(census.previews, 6, "step {step}: {census:?}");
        // Only model 0 was cut again: at most its own index and its first cutter's prefix.
        assert!(census.indexes <= 1, "step {step}: {census:?}");
        assert!(census.prefixes <= 1, "step {step}: {census:?}");
        assert_eq!(
            again.triangle_count(),
            first.triangle_count() - first_model_triangles(&first) + first_model_triangles(&again)
        );
    }
}

/// Triangles of model 0's parts.
fn first_model_triangles(g: &PreviewGeometry) -> usize {
    g.parts
        .iter()
        .filter(|p| p.model == 0)
        .map(|p| p.mesh.triangle_count())
        .sum()
}
