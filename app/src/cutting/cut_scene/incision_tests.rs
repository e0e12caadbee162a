//! A paint-roller cut of a model that has scalpel incisions: what is left of the incision walls
//! is drawn as walls in Preview and Camera (an incision part of its own) and in Edit's live cut
//! (the kept delta marks them, bit for bit what the whole kept mesh draws).

use std::sync::Arc;

use glam::DVec3;

use super::*;
use crate::cutting::delta::tests::{assert_same_corners, delta_corners, mesh_corners};
use crate::cutting::delta::{VertexFaces, of_cut};
use crate::scene::SceneModel;
use crate::test_support::{box_cutter, plain_cutter};

/// A sphere of radius 10 with a 1 deep groove across its top (x from -5 to 5 near z = 9.5),
/// its walls marked, and a box cutter removing the sphere's part with x > 0 and z > 5 (half the
/// groove). `marked` false: the same mesh without the marks.
pub(crate) fn grooved_sphere_cut(marked: bool) -> (Scene, Vec<u32>) {
    let sphere = csg::testkit::icosphere(4, 10.0);
    let options = cutter::scalpel::ScalpelOptions::default().with_depth(1.0);
    let mut scalpel = cutter::scalpel::Scalpel::new(&sphere, options).unwrap();
    let samples: Vec<DVec3> = (0..=12)
        .map(|i| {
            let a = -0.5 + i as f64 / 12.0;
            DVec3::new(10.0 * a.sin(), -3.0 * a.cos(), 9.5).normalize() * 10.0
        })
        .collect();
    scalpel.cut_stroke(&samples).unwrap();
    let walls = scalpel.wall_faces();
    assert!(walls.len() > 8, "{} walls", walls.len());
    let mut model = SceneModel::new("sphere", "sphere.obj", Arc::new(sphere), [0.8, 0.6, 0.5]);
    model.replace_mesh_with_walls(
        Arc::new(scalpel.mesh()),
        if marked { walls.clone() } else { Vec::new() },
    );
    let mut scene = Scene::default();
    scene.models.push(model);
    scene.cutters.push(plain_cutter(
        0,
        cutter::CutKind::Straight,
        box_cutter(0.0, 12.0, -12.0, 12.0, 5.0, 12.0),
    ));
    (scene, walls)
}

#[test]
fn the_preview_draws_what_is_left_of_the_incision_walls_as_walls() {
    let (scene, walls) = grooved_sphere_cut(true);
    let preview = preview_geometry_with(&scene, &mut CutCache::default());
    assert!(preview.notes.is_empty(), "{:?}", preview.notes);
    let incision: Vec<&PreviewPart> = preview
        .parts
        .iter()
        .filter(|p| p.kind == PartKind::Wall && p.cutter == usize::MAX)
        .collect();
    assert_eq!(incision.len(), 1, "one incision part");
    let mesh = &incision[0].mesh;
    assert!(mesh.triangle_count() > 2, "{}", mesh.triangle_count());
    // Pieces of the marked walls (each lies on one of them), of the half the cutter left.
    let model = &scene.models[0].model.mesh;
    let marked = select(model, |t| walls.binary_search(&(t as u32)).is_ok());
    let on_walls = csg::SpatialIndex::build(&marked);
    for t in 0..mesh.triangle_count() {
        let c = mesh.corners(t).iter().sum::<DVec3>() / 3.0;
        let off = on_walls
            .closest_point(&marked, c)
            .unwrap()
            .point
            .distance(c);
        assert!(off < 1e-9, "incision triangle {t} is {off} off the walls");
        assert!(c.x < 0.5, "incision triangle {t} at x = {}", c.x);
    }
    assert!(mesh.triangle_count() < walls.len());
    // Without the marks the same cut has no incision part: its walls are kept surface.
    let (plain, _) = grooved_sphere_cut(false);
    let preview = preview_geometry_with(&plain, &mut CutCache::default());
    assert!(
        !preview
            .parts
            .iter()
            .any(|p| p.kind == PartKind::Wall && p.cutter == usize::MAX)
    );
}

#[test]
fn the_live_cut_delta_draws_the_kept_incision_walls_bit_for_bit() {
    let (scene, walls) = grooved_sphere_cut(true);
    let target = scene.models[0].model.mesh.clone();
    let index = csg::TargetIndex::build(target.clone()).unwrap();
    let result = csg::subtract(&index, &cutter_mesh(&scene.cutters[0])).unwrap();
    let faces = VertexFaces::build(&target);
    let delta = of_cut(&target, &faces, &result, &walls);
    let (kept, provenance) = result.materialize_with_provenance(&target);
    let kept_walls: Vec<u32> = (0..kept.triangle_count() as u32)
        .filter(|&t| walls.binary_search(&provenance[t as usize]).is_ok())
        .collect();
    assert!(!kept_walls.is_empty() && kept_walls.len() < walls.len() + 8);
    assert_same_corners(
        delta_corners(&delta, &walls),
        mesh_corners(&kept, &kept_walls),
        "live delta vs kept",
    );
}
