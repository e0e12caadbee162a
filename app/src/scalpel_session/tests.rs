//! Scalpel sessions on scenes, driven as the window drives them (pixels through the camera)
//! and as the command line does (surface points): the view of a stroke in progress, undo,
//! loops, sessions saved and reopened, the layers below.

use super::*;
use cutter::scalpel::Scalpel;

fn sphere_scene() -> Scene {
    let mut scene = Scene::default();
    let sphere = csg::testkit::icosphere(4, 10.0);
    scene.models.push(SceneModel::new(
        "sphere",
        "sphere.obj",
        Arc::new(sphere),
        [0.9, 0.7, 0.6],
    ));
    scene.camera = scene.framing_camera();
    scene
}

/// The stroke in progress as the view draws it (the scene's mesh, faces hidden, plus the
/// patch) is the scalpel's mesh as the whole-mesh update shows it: the same triangles with
/// the same vertex positions and normals, bit for bit. Returns the patch's share of it.
fn assert_view_is_the_cut_mesh(slot: &ScalpelSession) -> f64 {
    use crate::cutting::delta::tests::{assert_same_corners, delta_corners, mesh_corners};
    let delta = slot
        .delta()
        .expect("a stroke in progress is drawn as a delta");
    let session = slot.session.as_ref().expect("a session");
    let full = session.display(&slot.settings.open());
    // The base is the scene's model at the press, drawn with its walls.
    let before = &slot.stroke.as_ref().expect("a stroke").before.models[session.model];
    assert!(Arc::ptr_eq(&before.model.mesh, &delta.base));
    assert_same_corners(
        delta_corners(&delta, before.wall_faces()),
        mesh_corners(&full, &session.scalpel.wall_faces()),
        "the view vs the cut mesh",
    );
    delta.patch.triangle_count() as f64 / full.triangle_count() as f64
}

/// Grooves crossing (the deeper one lowers the other's floor) and a slit opening by the
/// DFFD: after every step the view of the stroke in progress is the cut mesh.
#[test]
fn the_view_of_a_stroke_in_progress_is_the_cut_mesh_step_by_step() {
    let mut scene = sphere_scene();
    scene.models[0].replace_mesh(Arc::new(csg::testkit::icosphere(5, 10.0)));
    let viewport = DVec2::new(800.0, 600.0);
    let mut slot = ScalpelSession::default();
    let drag = |slot: &mut ScalpelSession, scene: &mut Scene, px: &[DVec2]| {
        assert_eq!(slot.press(scene, viewport, px[0]), Ok(Some(0)));
        let mut checked = 0;
        for &p in &px[1..] {
            if slot.drag(scene, viewport, p).expect("step") {
                let share = assert_view_is_the_cut_mesh(slot);
                assert!(share < 0.1, "the patch is {share} of the mesh");
                checked += 1;
            }
        }
        assert!(checked > 3, "{checked} steps drawn");
        let before = scene.models[0].model.mesh.clone();
        let released = slot.release(scene);
        assert!(
            matches!(released, Released::Committed { .. }),
            "{released:?}"
        );
        assert!(!Arc::ptr_eq(&before, &scene.models[0].model.mesh));
        assert!(slot.delta().is_none(), "no delta after the release");
    };
    slot.settings.depth = 0.4;
    drag(&mut slot, &mut scene, &across(viewport, 0.4, 0.6, 16));
    // Down across the first groove, deeper.
    slot.settings.depth = 0.8;
    let down: Vec<DVec2> = (0..=16)
        .map(|i| DVec2::new(viewport.x * 0.5, viewport.y * (0.4 + 0.2 * i as f64 / 16.0)))
        .collect();
    drag(&mut slot, &mut scene, &down);
    // A slit that opens (the scene's mesh was shown closed: that stroke updates the whole
    // mesh), then another with the same opening, drawn as a delta.
    slot.settings.depth = 0.0;
    slot.settings.opening = 0.3;
    let slanted = |y0: f64, y1: f64| -> Vec<DVec2> {
        (0..=16)
            .map(|i| {
                let s = i as f64 / 16.0;
                DVec2::new(
                    viewport.x * (0.42 + 0.16 * s),
                    viewport.y * (y0 + (y1 - y0) * s),
                )
            })
            .collect()
    };
    assert_eq!(
        slot.press(&scene, viewport, slanted(0.42, 0.47)[0]),
        Ok(Some(0))
    );
    for &p in &slanted(0.42, 0.47)[1..] {
        slot.drag(&mut scene, viewport, p).expect("step");
        assert!(
            slot.delta().is_none(),
            "a changed opening redraws the whole mesh"
        );
    }
    assert!(matches!(
        slot.release(&mut scene),
        Released::Committed { .. }
    ));
    drag(&mut slot, &mut scene, &slanted(0.55, 0.6));
    let topo = slot.validate().unwrap().expect("scalpel invariants");
    assert!(topo.manifold, "{topo:?}");
}

/// Pixels of a horizontal drag across the middle of the view.
fn across(viewport: DVec2, from: f64, to: f64, steps: usize) -> Vec<DVec2> {
    (0..=steps)
        .map(|i| {
            let s = from + (to - from) * i as f64 / steps as f64;
            DVec2::new(viewport.x * s, viewport.y * 0.5)
        })
        .collect()
}

fn stroke(slot: &mut ScalpelSession, scene: &mut Scene, viewport: DVec2, px: &[DVec2]) -> Released {
    assert_eq!(slot.press(scene, viewport, px[0]), Ok(Some(0)));
    for &p in &px[1..] {
        if slot.drag(scene, viewport, p).expect("step") && slot.delta().is_some() {
            assert_view_is_the_cut_mesh(slot);
        }
    }
    slot.release(scene)
}

#[test]
fn a_drag_across_a_sphere_cuts_a_closed_groove_step_by_step() {
    let mut scene = sphere_scene();
    let viewport = DVec2::new(800.0, 600.0);
    let original = scene.models[0].model.mesh.clone();
    let mut slot = ScalpelSession::default();
    slot.settings.depth = 0.5;
    let px = across(viewport, 0.42, 0.58, 24);
    assert_eq!(slot.press(&scene, viewport, px[0]), Ok(Some(0)));
    let mut updates = 0;
    let mut counts = Vec::new();
    for &p in &px[1..] {
        if slot.drag(&mut scene, viewport, p).expect("step") {
            updates += 1;
            assert_view_is_the_cut_mesh(&slot);
        }
        counts.push(slot.delta().map_or(0, |d| d.compose().triangle_count()));
        // The scene keeps the mesh from before the stroke until the release.
        assert!(Arc::ptr_eq(&scene.models[0].model.mesh, &original));
    }
    // Progressive: the view's mesh grew while the pointer moved, not only at the release.
    assert!(updates > 5, "{updates} updates");
    assert!(counts[counts.len() / 2] > original.triangle_count());
    // Moving to the same pixel is no step and no update.
    let last = *px.last().unwrap();
    assert_eq!(slot.drag(&mut scene, viewport, last), Ok(false));
    let Released::Committed { before, .. } = slot.release(&mut scene) else {
        panic!("the stroke did not commit");
    };
    assert!(Arc::ptr_eq(&before.models[0].model.mesh, &original));
    let mesh = &scene.models[0].model.mesh;
    assert!(mesh.triangle_count() > original.triangle_count() + 20);
    let report = mesh.report();
    assert!(report.closed && report.manifold, "{report:?}");
    let topo = slot.validate().unwrap().expect("scalpel invariants");
    assert!(topo.closed && topo.manifold, "{topo:?}");
    // The groove is carved into the sphere: its floor lies about the depth below the surface.
    let deepest = mesh
        .positions
        .iter()
        .map(|p| p.length())
        .fold(f64::INFINITY, f64::min);
    assert!(deepest < 10.0 - 0.4, "deepest vertex at radius {deepest}");
}

#[test]
fn a_drag_across_the_knee_skin_cuts_a_closed_groove() {
    let knee = crate::anatomy::assets::scene("knee").expect("embedded knee");
    let models = crate::anatomy::assets::load_scene(knee).expect("knee loads");
    let skin = models
        .into_iter()
        .find(|m| m.name.to_ascii_lowercase().contains("skin"))
        .expect("knee skin");
    let mut scene = Scene::default();
    let original = skin.mesh;
    scene.models.push(SceneModel::new(
        skin.name,
        skin.source,
        original.clone(),
        [0.9, 0.7, 0.6],
    ));
    scene.camera = scene.framing_camera();
    let viewport = DVec2::new(800.0, 600.0);
    let mut slot = ScalpelSession::default();
    slot.settings.depth = 2.0;
    let released = stroke(
        &mut slot,
        &mut scene,
        viewport,
        &across(viewport, 0.47, 0.53, 20),
    );
    assert!(
        matches!(released, Released::Committed { .. }),
        "{released:?}"
    );
    let mesh = &scene.models[0].model.mesh;
    assert!(mesh.triangle_count() > original.triangle_count());
    let report = mesh.report();
    assert!(report.closed && report.manifold, "{report:?}");
    let topo = slot.validate().unwrap().expect("scalpel invariants");
    assert!(topo.closed && topo.manifold, "{topo:?}");
}

#[test]
fn undo_through_the_scene_is_followed_by_the_scalpel() {
    let mut scene = sphere_scene();
    let viewport = DVec2::new(800.0, 600.0);
    let mut slot = ScalpelSession::default();
    slot.settings.depth = 0.0;
    let first = stroke(
        &mut slot,
        &mut scene,
        viewport,
        &across(viewport, 0.45, 0.55, 12),
    );
    let Released::Committed { before, .. } = first else {
        panic!("first stroke did not commit");
    };
    let after_first = scene.models[0].model.mesh.clone();
    let second = stroke(
        &mut slot,
        &mut scene,
        viewport,
        &[DVec2::new(400.0, 250.0), DVec2::new(400.0, 270.0)],
    );
    assert!(matches!(second, Released::Committed { .. }));
    // Undo the second stroke the way the window does: the scene snapshot comes back.
    scene.models[0].model.mesh = after_first.clone();
    // The next press follows: the scalpel undid its last stroke, so its mesh is the first
    // stroke's, bit for bit, and cutting goes on from there.
    slot.press(&scene, viewport, DVec2::new(400.0, 350.0))
        .unwrap();
    let rest = slot.session.as_ref().unwrap().scalpel.mesh();
    assert_eq!(rest.triangles, after_first.triangles);
    assert_eq!(rest.positions, after_first.positions);
    slot.release(&mut scene);
    // A scene the scalpel never made (e.g. an undo past the session): it starts over.
    scene.models[0].model.mesh = before.models[0].model.mesh.clone();
    slot.press(&scene, viewport, DVec2::new(400.0, 300.0))
        .unwrap();
    let rest = slot.session.as_ref().unwrap().scalpel.mesh();
    assert_eq!(rest.triangles, before.models[0].model.mesh.triangles);
}

#[test]
fn a_refused_step_is_an_error_and_leaves_the_scene_alone() {
    // Two fans sharing only vertex 0 (a bow-tie): the scalpel never cuts through it.
    let mut scene = Scene::default();
    let mesh = Arc::new(csg::testkit::bow_tie());
    scene
        .models
        .push(SceneModel::new("bowtie", "bowtie.obj", mesh, [1.0; 3]));
    scene.camera = Camera {
        eye: DVec3::new(0.0, 0.0, 20.0),
        target: DVec3::ZERO,
        up: DVec3::Y,
        fov_y_deg: 30.0,
    };
    let viewport = DVec2::new(800.0, 600.0);
    let px = |x: f64, y: f64| {
        scene
            .camera
            .project(viewport, DVec3::new(x, y, 0.0))
            .unwrap()
    };
    let (a, b, c) = (px(-2.0, 0.1), px(-1.0, 0.05), px(2.0, 0.1));
    let mut slot = ScalpelSession::default();
    slot.settings.depth = 0.0;
    assert_eq!(slot.press(&scene, viewport, a), Ok(Some(0)));
    assert!(slot.drag(&mut scene, viewport, b).unwrap());
    let before = scene.models[0].model.mesh.clone();
    let shown = slot.delta().expect("the step is drawn");
    let err = slot.drag(&mut scene, viewport, c).unwrap_err();
    assert!(err.contains("non-manifold"), "{err}");
    assert!(Arc::ptr_eq(&scene.models[0].model.mesh, &before));
    // The view is as before the refused step, and still the scalpel's own mesh.
    assert!(Arc::ptr_eq(&slot.delta().unwrap(), &shown));
    assert_view_is_the_cut_mesh(&slot);
}

#[test]
fn a_click_without_a_drag_changes_nothing() {
    let mut scene = sphere_scene();
    let viewport = DVec2::new(800.0, 600.0);
    let original = scene.models[0].model.mesh.clone();
    let mut slot = ScalpelSession::default();
    slot.press(&scene, viewport, DVec2::new(400.0, 300.0))
        .unwrap();
    slot.drag(&mut scene, viewport, DVec2::new(401.0, 300.0))
        .unwrap();
    assert!(matches!(slot.release(&mut scene), Released::Nothing));
    assert!(Arc::ptr_eq(&scene.models[0].model.mesh, &original));
    // A press beside the model starts nothing.
    assert_eq!(slot.press(&scene, viewport, DVec2::new(3.0, 3.0)), Ok(None));
}

#[test]
fn a_loop_around_a_cap_detaches_it_as_a_model() {
    let mut scene = sphere_scene();
    let viewport = DVec2::new(800.0, 600.0);
    let original = scene.models[0].model.mesh.clone();
    let mut slot = ScalpelSession::default();
    slot.settings.tool = Tool::Loop;
    slot.settings.depth = 0.0;
    let centre = DVec2::new(400.0, 300.0);
    let px: Vec<DVec2> = (0..=40)
        .map(|i| {
            let a = i as f64 / 40.0 * std::f64::consts::TAU * 0.97;
            centre + DVec2::new(a.cos(), a.sin()) * 40.0
        })
        .collect();
    let released = stroke(&mut slot, &mut scene, viewport, &px);
    assert!(
        matches!(released, Released::Committed { .. }),
        "{released:?}"
    );
    assert_eq!(scene.models.len(), 2, "the piece was not added");
    let (kept, piece) = (&scene.models[0].model.mesh, &scene.models[1].model.mesh);
    assert!(piece.triangle_count() > 0);
    assert!(kept.triangle_count() > 0);
    // Nothing lost: kept + piece cover the sphere's area (to within what moving the vertices the
    // cut passes near onto the cut changes on a curved surface: second order in the move, about
    // 1e-6 of the area here; one lost triangle would be 2e-4).
    let total = kept.area() + piece.area();
    assert!(
        (total - original.area()).abs() < 1e-5 * original.area(),
        "{total} vs {}",
        original.area()
    );
    assert!(scene.models[1].model.name.contains("piece"));
}

/// A private folder for session files.
fn session_dir(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "cutaway-scalpel-session-{name}-{}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

pub(crate) fn position_bits(mesh: &Mesh) -> Vec<[u64; 3]> {
    mesh.positions
        .iter()
        .map(|p| p.to_array().map(f64::to_bits))
        .collect()
}

#[test]
fn a_saved_scalpel_stroke_reopens_bit_for_bit() {
    let mut scene = sphere_scene();
    let viewport = DVec2::new(800.0, 600.0);
    let mut slot = ScalpelSession::default();
    slot.settings.depth = 0.5;
    slot.settings.opening = 0.3;
    let released = stroke(
        &mut slot,
        &mut scene,
        viewport,
        &across(viewport, 0.42, 0.58, 16),
    );
    assert!(matches!(released, Released::Committed { .. }));
    assert_eq!(scene.models[0].origin, MeshOrigin::Edited);
    // The source file does not even exist: the session must not need it.
    assert!(!scene.models[0].model.source.exists());
    let dir = session_dir("stroke");
    let path = dir.join("cut.json");
    crate::session::save(&path, &scene).unwrap();
    let back = crate::session::load(&path).unwrap();
    assert_eq!(back.models.len(), 1);
    let (cut, reopened) = (&scene.models[0].model.mesh, &back.models[0].model.mesh);
    assert!(reopened.triangles == cut.triangles, "triangles differ");
    assert!(
        position_bits(reopened) == position_bits(cut),
        "positions differ"
    );
    assert_eq!(back.models[0].model.name, scene.models[0].model.name);
    // The incision walls come back with the mesh (the PLY's wall marks).
    let walls = scene.models[0].wall_faces().to_vec();
    assert!(walls.len() > 10, "{} walls", walls.len());
    assert_eq!(back.models[0].wall_faces(), walls);
    let first = back.models[0].model.mesh.clone();
    // A second stroke on the reopened model and a save over the same session: the new cut
    // comes back and only its mesh file is left.
    let mut scene = back;
    // A vertical drag: a cross cut.
    let down: Vec<DVec2> = (0..=12)
        .map(|i| {
            DVec2::new(
                viewport.x * 0.47,
                viewport.y * (0.4 + 0.2 * i as f64 / 12.0),
            )
        })
        .collect();
    let released = stroke(&mut slot, &mut scene, viewport, &down);
    assert!(matches!(released, Released::Committed { .. }));
    crate::session::save(&path, &scene).unwrap();
    let again = crate::session::load(&path).unwrap();
    let recut = &scene.models[0].model.mesh;
    assert!(again.models[0].model.mesh.triangles == recut.triangles);
    // The scalpel made from the reopened mesh kept its walls walls: every first wall the cross
    // cut left as it was is still one, and the saved marks come back again.
    let recut_walls = scene.models[0].wall_faces();
    for &f in &walls {
        let f = f as usize;
        if recut.triangles[f] == first.triangles[f] {
            assert!(
                recut_walls.binary_search(&(f as u32)).is_ok(),
                "wall {f} lost"
            );
        }
    }
    assert!(recut_walls.len() > walls.len());
    assert_eq!(again.models[0].wall_faces(), recut_walls);
    assert!(position_bits(&again.models[0].model.mesh) == position_bits(recut));
    assert!(recut.triangle_count() > cut.triangle_count());
    let files = std::fs::read_dir(crate::session::meshes::mesh_dir(&path))
        .unwrap()
        .count();
    assert_eq!(files, 1);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_detached_piece_is_saved_to_its_own_file_and_reopens_as_its_own_model() {
    let mut scene = sphere_scene();
    let viewport = DVec2::new(800.0, 600.0);
    let mut slot = ScalpelSession::default();
    slot.settings.tool = Tool::Loop;
    slot.settings.depth = 0.0;
    let centre = DVec2::new(400.0, 300.0);
    let px: Vec<DVec2> = (0..=40)
        .map(|i| {
            let a = i as f64 / 40.0 * std::f64::consts::TAU * 0.97;
            centre + DVec2::new(a.cos(), a.sin()) * 40.0
        })
        .collect();
    let released = stroke(&mut slot, &mut scene, viewport, &px);
    assert!(matches!(released, Released::Committed { .. }));
    assert_eq!(scene.models.len(), 2);
    assert_eq!(scene.models[1].origin, MeshOrigin::Edited);
    let dir = session_dir("piece");
    let path = dir.join("loop.json");
    crate::session::save(&path, &scene).unwrap();
    let file = crate::session::parse(&std::fs::read_to_string(&path).unwrap()).unwrap();
    assert!(file.models.iter().all(|m| m.exact && m.region == Some(0)));
    assert_ne!(file.models[0].path, file.models[1].path);
    let back = crate::session::load(&path).unwrap();
    assert_eq!(back.models.len(), 2);
    for (a, b) in scene.models.iter().zip(&back.models) {
        assert_eq!(a.model.name, b.model.name);
        assert!(
            a.model.mesh.triangles == b.model.mesh.triangles,
            "{}: triangles differ",
            a.model.name
        );
        assert!(
            position_bits(&a.model.mesh) == position_bits(&b.model.mesh),
            "{}",
            a.model.name
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Two nested spheres, each a model: skin (radius 10, model 0) over muscle (radius 9.7,
/// model 1, tessellated differently so their vertices never line up).
fn nested_scene() -> Scene {
    let mut scene = sphere_scene();
    scene.models.push(SceneModel::new(
        "inner",
        "inner.obj",
        Arc::new(csg::testkit::icosphere(3, 9.7)),
        [0.8, 0.3, 0.3],
    ));
    scene
}

/// Positions of `after` that are not positions of `before` (bit for bit).
fn new_vertices(before: &Mesh, after: &Mesh) -> Vec<DVec3> {
    let old: HashSet<[u64; 3]> = position_bits(before).into_iter().collect();
    after
        .positions
        .iter()
        .filter(|p| !old.contains(&p.to_array().map(f64::to_bits)))
        .copied()
        .collect()
}

/// The mesh is closed and manifold by the csg report and by the scalpel's invariants.
pub(crate) fn assert_closed_and_manifold(mesh: &Mesh, what: &str) {
    let report = mesh.report();
    assert!(report.closed && report.manifold, "{what}: {report:?}");
    let scalpel = Scalpel::new(mesh, ScalpelOptions::default()).expect(what);
    let topo = cutter::scalpel::invariants::validate(scalpel.dyn_mesh())
        .unwrap_or_else(|e| panic!("{what}: {e}"));
    assert!(topo.closed && topo.manifold, "{what}: {topo:?}");
}

#[test]
fn a_groove_cuts_the_model_below_within_its_depth() {
    let mut scene = nested_scene();
    let viewport = DVec2::new(800.0, 600.0);
    let (outer, inner) = (
        scene.models[0].model.mesh.clone(),
        scene.models[1].model.mesh.clone(),
    );
    let mut slot = ScalpelSession::default();
    assert!(slot.settings.layers, "on by default");
    slot.settings.depth = 0.6;
    let released = stroke(
        &mut slot,
        &mut scene,
        viewport,
        &across(viewport, 0.42, 0.58, 24),
    );
    let Released::Committed {
        before, message, ..
    } = released
    else {
        panic!("the stroke did not commit: {released:?}");
    };
    assert!(message.contains("below it inner"), "{message}");
    assert!(Arc::ptr_eq(&before.models[1].model.mesh, &inner));
    let (outer_cut, inner_cut) = (&scene.models[0].model.mesh, &scene.models[1].model.mesh);
    assert!(outer_cut.triangle_count() > outer.triangle_count());
    assert!(
        inner_cut.triangle_count() > inner.triangle_count() + 10,
        "the inner sphere was not grooved: {} -> {}",
        inner.triangle_count(),
        inner_cut.triangle_count()
    );
    assert_eq!(scene.models[1].origin, MeshOrigin::Edited);
    assert_closed_and_manifold(outer_cut, "outer");
    assert_closed_and_manifold(inner_cut, "inner");
    // The inner groove lies under the outer one: every new inner vertex is, seen from the
    // centre, next to a new outer vertex; and it goes below the inner surface, but only by
    // the depth left there (0.6 - 0.3).
    let outer_new = new_vertices(&outer, outer_cut);
    let inner_new = new_vertices(&inner, inner_cut);
    assert!(!inner_new.is_empty());
    for v in &inner_new {
        let nearest = outer_new
            .iter()
            .map(|w| v.normalize().distance(w.normalize()))
            .fold(f64::INFINITY, f64::min);
        assert!(
            nearest < 0.05,
            "inner vertex {v} is {nearest} off the stroke"
        );
    }
    let deepest = inner_new
        .iter()
        .map(|p| p.length())
        .fold(f64::INFINITY, f64::min);
    assert!(
        deepest < 9.7 - 0.15 && deepest > 9.7 - 0.45,
        "inner groove floor at radius {deepest}"
    );
    // One undo step: the snapshot from before the stroke holds both models as they were.
    scene = *before;
    assert!(Arc::ptr_eq(&scene.models[0].model.mesh, &outer));
    assert!(Arc::ptr_eq(&scene.models[1].model.mesh, &inner));
}

#[test]
fn a_shallow_groove_or_layers_off_leaves_the_model_below_alone() {
    let viewport = DVec2::new(800.0, 600.0);
    for (depth, layers) in [(0.2, true), (0.6, false)] {
        let mut scene = nested_scene();
        let (outer, inner) = (
            scene.models[0].model.mesh.clone(),
            scene.models[1].model.mesh.clone(),
        );
        let inner_bits = position_bits(&inner);
        let mut slot = ScalpelSession::default();
        slot.settings.depth = depth;
        slot.settings.layers = layers;
        let released = stroke(
            &mut slot,
            &mut scene,
            viewport,
            &across(viewport, 0.42, 0.58, 24),
        );
        assert!(
            matches!(released, Released::Committed { .. }),
            "{released:?}"
        );
        assert!(scene.models[0].model.mesh.triangle_count() > outer.triangle_count());
        let kept = &scene.models[1];
        assert!(
            Arc::ptr_eq(&kept.model.mesh, &inner),
            "depth {depth}, layers {layers}: the inner sphere changed"
        );
        assert_eq!(kept.model.mesh.triangles, inner.triangles);
        assert_eq!(position_bits(&kept.model.mesh), inner_bits);
        assert_eq!(kept.origin, MeshOrigin::Region);
    }
}

#[test]
fn layers_below_follow_the_samples_whose_blade_reaches_a_model() {
    use cutter::scalpel::layers::{Surface, strokes_below};
    // A plate at z = 0 (top, normal +z) over a plate at z = -1: the blade reaches the
    // lower one only with depth over 1, and a sample off the surface splits the run.
    let plate = |z: f64| {
        csg::testkit::cube(DVec3::new(-5.0, -5.0, z - 0.1), DVec3::new(5.0, 5.0, z)).compacted()
    };
    let (top, lower) = (plate(0.0), plate(-1.0));
    let top_index = SpatialIndex::build(&top);
    let lower_index = SpatialIndex::build(&lower);
    let others = [Surface {
        id: 7,
        mesh: &lower,
        index: &lower_index,
    }];
    let at = |x: f64| Some(DVec3::new(x, 0.5, 0.0));
    let samples = [at(-2.0), at(-1.0), at(0.0), None, at(1.0), at(2.0), at(3.0)];
    assert!(strokes_below(&top, &top_index, &samples, 0.95, &others).is_empty());
    let runs = strokes_below(&top, &top_index, &samples, 1.5, &others);
    assert_eq!(runs.len(), 2, "{runs:?}");
    assert_eq!(runs[0].region, 7);
    assert_eq!(runs[0].samples.len(), 3);
    assert_eq!(runs[1].samples.len(), 3);
    for r in &runs {
        assert!((r.depth - 0.5).abs() < 1e-6, "{}", r.depth);
        assert!(r.samples.iter().all(|p| (p.z + 1.0).abs() < 1e-9));
    }
}

/// A layer the scalpel refuses (a bow-tie below a plate: its stroke crosses the
/// non-manifold vertex) is left exactly as it was and reported; a sphere below it is cut.
#[test]
fn a_refused_layer_is_left_alone_and_reported() {
    let mut scene = Scene::default();
    let plate = Arc::new(
        csg::testkit::cube(DVec3::new(-3.0, -1.0, 0.5), DVec3::new(3.0, 1.0, 1.0)).compacted(),
    );
    let bow_tie = Arc::new(csg::testkit::bow_tie());
    // A big sphere whose top is at z = -0.3 under the plate.
    let mut lower = csg::testkit::icosphere(4, 10.0);
    for p in &mut lower.positions {
        p.z -= 10.3;
    }
    let lower = Arc::new(lower);
    for (name, mesh) in [("plate", &plate), ("bowtie", &bow_tie), ("lower", &lower)] {
        scene
            .models
            .push(SceneModel::new(name, "x.obj", mesh.clone(), [1.0; 3]));
    }
    let index = SpatialIndex::build(&plate);
    let samples: Vec<Option<DVec3>> = (0..=16)
        .map(|i| Some(DVec3::new(-2.0 + 0.25 * i as f64, 0.1, 1.0)))
        .collect();
    let settings = ScalpelSettings {
        depth: 1.6,
        ..Default::default()
    };
    let outcome = cut_layers(
        &mut scene,
        0,
        &plate,
        &index,
        &samples,
        &settings,
        &mut |m| Arc::new(SpatialIndex::build(m)),
    );
    assert_eq!(outcome.refused.len(), 1, "{outcome:?}");
    assert_eq!(outcome.refused[0].0, 1);
    assert!(Arc::ptr_eq(&scene.models[1].model.mesh, &bow_tie));
    assert_eq!(scene.models[1].origin, MeshOrigin::Region);
    assert_eq!(
        outcome.cut.iter().map(|(m, _)| *m).collect::<Vec<_>>(),
        vec![2]
    );
    assert!(scene.models[2].model.mesh.triangle_count() > lower.triangle_count());
    assert_closed_and_manifold(&scene.models[2].model.mesh, "lower sphere");
    // The touched model itself is never a layer of its own stroke.
    assert!(Arc::ptr_eq(&scene.models[0].model.mesh, &plate));
}

#[test]
fn a_session_saves_and_reopens_both_cut_layers_bit_for_bit() {
    let mut scene = nested_scene();
    let viewport = DVec2::new(800.0, 600.0);
    let inner = scene.models[1].model.mesh.clone();
    let mut slot = ScalpelSession::default();
    slot.settings.depth = 0.6;
    let released = stroke(
        &mut slot,
        &mut scene,
        viewport,
        &across(viewport, 0.42, 0.58, 16),
    );
    assert!(matches!(released, Released::Committed { .. }));
    assert!(
        !Arc::ptr_eq(&scene.models[1].model.mesh, &inner),
        "no layer cut"
    );
    let dir = session_dir("layers");
    let path = dir.join("layers.json");
    crate::session::save(&path, &scene).unwrap();
    let back = crate::session::load(&path).unwrap();
    assert_eq!(back.models.len(), 2);
    for (a, b) in scene.models.iter().zip(&back.models) {
        assert_eq!(a.model.name, b.model.name);
        assert!(
            a.model.mesh.triangles == b.model.mesh.triangles,
            "{}",
            a.model.name
        );
        assert!(
            position_bits(&a.model.mesh) == position_bits(&b.model.mesh),
            "{}",
            a.model.name
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn removing_pieces_matches_triangles_by_their_corners() {
    let cube = csg::testkit::cube(DVec3::ZERO, DVec3::ONE);
    let piece = Mesh {
        positions: cube.positions.clone(),
        triangles: cube.triangles[..2].to_vec(),
    }
    .compacted();
    let (rest, walls) = without_pieces_walls(&cube, &[piece], &[1, 3, 5]);
    assert_eq!(rest.triangle_count(), 10);
    // Triangles 3 and 5 of the cube are the 2nd and 4th kept.
    assert_eq!(walls, vec![1, 3]);
    assert_eq!(rest.corners(1), cube.corners(3));
}
