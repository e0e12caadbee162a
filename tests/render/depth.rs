//! The first cut a newcomer makes, replayed as the window makes it, and the size of the window it
//! opens on the default head, the knee (the phantom and the real one) and a sphere.
//!
//! The newcomer selects the skin of the default head, presses E, drags about 70 mm across the
//! forehead and rolls the handle about 50 mm down, without the wheel. The cutter must then reach
//! the ventricles, show the left lateral ventricle through the forehead from where it was painted
//! (at least 0.3 of what is seen of it with nothing else in the way) and open the whole painted
//! region (opened / painted ≥ 0.9; a rounded cutter neither lumpy nor more than 10 % wider). The
//! same gesture under the first rules (`cutaway-gesture/1`) makes the cut this replaces, a few
//! millimetres deep, which shows nothing.
//!
//! The golden image `tests/golden/newcomer_forehead.png` is the cut scene of that state at
//! 1280×800, as `cutaway render` draws it; `UPDATE_GOLDEN=1` rewrites it.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::{DVec2, DVec3};

use cutaway::cli::extrude_session::{SceneReplay, replay_on_scene};
use cutaway::io::gesture::{CutSettings, Gesture};
use cutaway::scene::{Scene, SceneModel};
use cutter::{Camera, CutDirection, CutKind, EditorEvent, EditorSettings, Rules};

const VIEWPORT: DVec2 = DVec2::new(1280.0, 800.0);

/// The default head as the window shows it: the skin first, framed from the front on its own (the
/// structures arrive after the first frame and the camera stays), then the deep structures.
fn head() -> Scene {
    let mut scene = Scene::default();
    for (i, model) in cutaway::anatomy::default_scene::load()
        .expect("the default scene")
        .into_iter()
        .enumerate()
    {
        let color = cutaway::anatomy::colors::structure_color(&model.name, model.color, i);
        scene.models.push(SceneModel::structure(model, color));
    }
    scene.orientation = cutaway::scene::Orientation::RAS;
    let mut skin_only = scene.clone();
    skin_only.models.truncate(1);
    scene.camera = skin_only.preset_camera(cutaway::scene::ViewPreset::Anterior);
    scene
}

/// Where the view ray through the image point of `p` first meets `scene`'s model `target`.
fn on_surface(scene: &Scene, target: usize, camera: &Camera, p: DVec3) -> DVec3 {
    let px = camera.project(VIEWPORT, p).expect("in front of the camera");
    let ray = camera.ray_through_pixel(VIEWPORT, px);
    let mesh = &scene.models[target].model.mesh;
    let index = csg::SpatialIndex::build(mesh);
    index
        .ray_cast(mesh, ray.origin, ray.direction, f64::INFINITY)
        .expect("the point is on the target as seen")
        .point
}

/// A stroke `width` long across the surface point `centre` (screen-left to screen-right, so the
/// strip hangs below it), then the handle rolled `roll` down the screen: lengths in world units
/// at the depth of `centre`, as a hand measures them on the screen.
fn paint_and_roll(
    scene: &Scene,
    target: usize,
    camera: Camera,
    centre: DVec3,
    width: f64,
    roll: f64,
    rules: Rules,
    smooth: bool,
) -> Gesture {
    let (right, up, _) = camera.basis();
    let project = |p: DVec3| camera.project(VIEWPORT, p).expect("in view");
    let a = project(centre - right * (width * 0.5));
    let b = project(centre + right * (width * 0.5));
    let px_size = width / (b - a).length();
    let mut events = vec![EditorEvent::press(a.x, a.y)];
    for k in 1..=12 {
        let p = a.lerp(b, k as f64 / 12.0);
        events.push(EditorEvent::move_to(p.x, p.y));
    }
    events.push(EditorEvent::release(b.x, b.y));
    // The handle: the middle of the leading plane, 10δ below the stroke.
    let delta = EditorSettings::delta_for_target(
        &scene.models[target].model.mesh.bbox(),
        &scene.bbox(),
        &camera,
    );
    let down = (project(centre - up * roll) - project(centre)).normalize();
    let handle = (a + b) * 0.5 + down * (10.0 * delta / px_size);
    events.push(EditorEvent::press(handle.x, handle.y));
    let steps = 60;
    let mut p = handle;
    for k in 1..=steps {
        p = handle + down * (roll / px_size) * (k as f64 / steps as f64);
        events.push(EditorEvent::move_to(p.x, p.y));
    }
    events.push(EditorEvent::release(p.x, p.y));
    Gesture {
        viewport: VIEWPORT,
        camera,
        cut: CutSettings {
            kind: CutKind::Curving,
            spacing: 20.0,
            smooth,
            direction: match rules {
                Rules::Reach => CutDirection::View,
                Rules::Delta => CutDirection::Normal,
            },
        },
        events,
        rules,
    }
}

/// The newcomer's stroke on the head: 70 mm across the forehead 50 mm above the eyes' centres
/// (z = 50 in the atlas, below the hairline), rolled 50 mm down to the brows.
fn newcomer(scene: &Scene, rules: Rules, smooth: bool) -> Gesture {
    let skin = 0;
    assert_eq!(scene.models[skin].model.name, "skin");
    let forehead = on_surface(scene, skin, &scene.camera, DVec3::new(0.0, 0.0, 50.0));
    paint_and_roll(
        scene,
        skin,
        scene.camera,
        forehead,
        70.0,
        50.0,
        rules,
        smooth,
    )
}

/// Exposure of `focus` from the scene's camera after the cuts, and with nothing else in the way.
fn exposure(scene: &Scene, focus: &str) -> (f64, f64) {
    let options = cutaway::metrics::MetricsOptions {
        focus: Some(focus.to_string()),
        critical: Vec::new(),
        samples: 20_000,
    };
    let after = cutaway::metrics::measure(scene, &options)
        .expect("exact cuts")
        .focus
        .expect("the focus")
        .exposure_after;
    let model = scene.models.iter().find(|m| m.model.name == focus).unwrap();
    let camera = scene.camera;
    let alone = cutaway::metrics::exposure::exposure(
        &model.model.mesh,
        &[],
        camera.eye,
        camera.forward(),
        20_000,
    )
    .unwrap();
    (after, alone)
}

fn names(replay: &SceneReplay) -> Vec<String> {
    replay
        .reached
        .iter()
        .map(|r| replay.scene.models[r.structure].model.name.clone())
        .collect()
}

#[test]
fn the_newcomers_first_cut_shows_the_ventricles_through_the_forehead() {
    let scene = head();
    let replay = replay_on_scene(&scene, &newcomer(&scene, Rules::Reach, false)).unwrap();
    assert_eq!(replay.target, 0, "the skin is painted");
    let c = &replay.cutter;
    assert!(c.planes.len() >= 8, "{} planes", c.planes.len());
    let reaches = names(&replay);
    let depth = c.depth();
    println!(
        "newcomer: {} planes, {depth:.1} mm ({:?}), reaches {reaches:?}",
        c.planes.len(),
        replay.reach
    );
    assert!(depth > 40.0, "{depth} mm");
    for v in ["left lateral ventricle", "right lateral ventricle"] {
        assert!(reaches.iter().any(|n| n == v), "{v} not in {reaches:?}");
    }
    assert!(reaches.iter().any(|n| n.contains("caudate")), "{reaches:?}");
    // Rolling kept the depth: every plane has it.
    for p in &c.planes {
        assert!((p.depth() - depth).abs() < 1e-6 * depth);
    }
    let (after, alone) = exposure(&replay.scene, "left lateral ventricle");
    println!("left lateral ventricle: exposure {after:.3} of {alone:.3} unoccluded");
    assert!(after >= 0.3 * alone, "{after} < 0.3 × {alone}");
    let opening = replay.opening.expect("the opening");
    println!("opening: {opening:?}, ratio {:.3}", opening.ratio());
    assert!(opening.ratio() >= 0.9, "{opening:?}");
    assert!(
        opening.covered() >= 0.9 && opening.outside() <= 0.1,
        "{opening:?}"
    );

    // The same hand under the first rules: a few millimetres deep, a slit, nothing seen.
    let first = replay_on_scene(&scene, &newcomer(&scene, Rules::Delta, false)).unwrap();
    let shallow = first.cutter.depth();
    let (before, _) = exposure(&first.scene, "left lateral ventricle");
    let slit = first.opening.expect("an opening").ratio();
    println!("first rules: {shallow:.1} mm, exposure {before:.3}, opening {slit:.3}");
    assert!(shallow < 5.0 && before < 0.05 * alone && slit < 0.7);

    render_golden("newcomer_forehead", &replay.scene);
}

/// `cutaway extrude SESSION.json --gesture G.json --out OUT.json --json` does the newcomer's cut
/// as the window does: the skin is the target, the cutter reaches the ventricles, and the written
/// session holds the new cutter along the view. A mesh-less output is refused in one line.
#[test]
fn extrude_on_a_session_writes_the_newcomers_cutter() {
    let scene = head();
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("depth_extrude_session");
    std::fs::create_dir_all(&dir).unwrap();
    let session = dir.join("head.json");
    let gesture = dir.join("newcomer.json");
    let out = dir.join("cut.json");
    let _ = std::fs::remove_file(&out);
    cutaway::session::save(&session, &scene).unwrap();
    cutaway::io::gesture::write_gesture(&gesture, &newcomer(&scene, Rules::Reach, false)).unwrap();
    let run = |out: &Path| {
        std::process::Command::new(env!("CARGO_BIN_EXE_cutaway"))
            .args([
                "extrude".as_ref(),
                session.as_os_str(),
                "--gesture".as_ref(),
            ])
            .arg(&gesture)
            .arg("--out")
            .arg(out)
            .arg("--json")
            .output()
            .unwrap()
    };
    let output = run(&out);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    println!("{json}");
    assert_eq!(json["target"], "skin");
    assert_eq!(json["direction"], "view");
    assert!(json["depth_mm"].as_f64().unwrap() > 40.0, "{json}");
    let reaches: Vec<&str> = json["reaches"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_str().unwrap())
        .collect();
    assert!(reaches.contains(&"left lateral ventricle"), "{reaches:?}");
    assert!(json["opening"]["ratio"].as_f64().unwrap() >= 0.9, "{json}");
    let written = cutaway::session::load(&out).unwrap();
    assert_eq!(written.cutters.len(), 1);
    assert_eq!(written.cutters[0].target, 0);
    assert_eq!(written.cutters[0].cutter.direction, CutDirection::View);
    let depth_mm = written.unit.to_mm(written.cutters[0].cutter.depth());
    assert!((depth_mm - json["depth_mm"].as_f64().unwrap()).abs() < 1e-6);

    let refused = run(&dir.join("cut.obj"));
    assert!(!refused.status.success());
    let err = String::from_utf8_lossy(&refused.stderr);
    assert!(err.contains("cut.obj") && err.lines().count() == 1, "{err}");
}

/// The rounded cutter of the same stroke opens the painted region without spilling over it.
#[test]
fn the_rounded_newcomer_cut_is_as_wide_as_painted() {
    let scene = head();
    let replay = replay_on_scene(&scene, &newcomer(&scene, Rules::Reach, true)).unwrap();
    assert!(replay.cutter.smooth);
    let opening = replay.opening.expect("the opening");
    println!(
        "rounded on the head: {opening:?}, ratio {:.3}",
        opening.ratio()
    );
    assert!(opening.covered() >= 0.9, "{opening:?}");
    assert!(opening.outside() <= 0.1, "{opening:?}");
}

/// A sphere of radius 50 with a ball of radius 8 whose front is 30 behind the sphere's front.
fn sphere_scene() -> Scene {
    let mut scene = Scene::default();
    let sphere = csg::testkit::icosphere(5, 50.0);
    scene.models.push(SceneModel::new(
        "sphere",
        "sphere.obj",
        Arc::new(sphere),
        [0.9, 0.7, 0.6],
    ));
    let mut ball = csg::testkit::icosphere(3, 8.0);
    for p in &mut ball.positions {
        p.y -= 12.0;
    }
    scene.models.push(SceneModel::new(
        "ball",
        "ball.obj",
        Arc::new(ball),
        [0.3, 0.3, 0.9],
    ));
    scene.camera = Camera {
        eye: DVec3::new(0.0, -300.0, 0.0),
        target: DVec3::ZERO,
        up: DVec3::Z,
        fov_y_deg: 30.0,
    };
    scene
}

#[test]
fn the_opening_on_a_sphere_is_what_was_painted() {
    let scene = sphere_scene();
    let centre = on_surface(&scene, 0, &scene.camera, DVec3::new(0.0, 0.0, 20.0));
    for smooth in [false, true] {
        let gesture = paint_and_roll(
            &scene,
            0,
            scene.camera,
            centre,
            50.0,
            40.0,
            Rules::Reach,
            smooth,
        );
        let replay = replay_on_scene(&scene, &gesture).unwrap();
        let opening = replay.opening.expect("the opening");
        println!(
            "sphere (smooth {smooth}): {:.1} deep, reaches {:?}, {opening:?}, ratio {:.3}",
            replay.cutter.depth(),
            names(&replay),
            opening.ratio()
        );
        assert_eq!(names(&replay), ["ball"]);
        assert!(opening.covered() >= 0.9, "{opening:?}");
        assert!(opening.outside() <= 0.1, "{opening:?}");
        assert!(opening.ratio() >= 0.9, "{opening:?}");
    }
}

/// The anatomy folder: `CUTAWAY_ANATOMY`, else `../shared/anatomy` beside the workspace.
fn anatomy() -> Option<PathBuf> {
    if let Ok(dir) = std::env::var("CUTAWAY_ANATOMY") {
        let p = PathBuf::from(dir);
        return p.is_dir().then_some(p);
    }
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/anatomy");
    p.is_dir().then_some(p)
}

/// The width of `target` as `camera` sees it along the screen-horizontal line through `p`:
/// how far either way the view rays through that line still meet it.
fn seen_width(scene: &Scene, target: usize, camera: &Camera, p: DVec3) -> f64 {
    let (right, _, _) = camera.basis();
    let mesh = &scene.models[target].model.mesh;
    let index = csg::SpatialIndex::build(mesh);
    let meets = |q: DVec3| {
        let px = camera.project(VIEWPORT, q).expect("in view");
        let ray = camera.ray_through_pixel(VIEWPORT, px);
        index
            .ray_cast(mesh, ray.origin, ray.direction, f64::INFINITY)
            .is_some()
    };
    let step = 0.25;
    let reach = |sign: f64| {
        let mut d = 0.0;
        while meets(p + right * (sign * (d + step))) {
            d += step;
        }
        d
    };
    reach(-1.0) + reach(1.0)
}

/// Paints across `target` of `scene` from the side `toward_eye` points to (a stroke across 60 %
/// of the structure's width as seen, above its middle, rolled a fifth of its height down, as a
/// hand paints within what it sees) and checks that the window opens what was painted, sharp and
/// rounded.
fn check_opening(scene: &Scene, target: usize, toward_eye: DVec3, what: &str) {
    let bbox = scene.models[target].model.mesh.bbox();
    let camera = Camera::framing(&bbox, toward_eye, DVec3::Z, 30.0);
    let (_, up, _) = camera.basis();
    let extent = bbox.max - bbox.min;
    let roll = 0.2 * extent.dot(up.abs());
    let centre = on_surface(
        scene,
        target,
        &camera,
        bbox.center() + up * (0.15 * extent.z),
    );
    let width = 0.6 * seen_width(scene, target, &camera, centre);
    for smooth in [false, true] {
        let gesture = paint_and_roll(
            scene,
            target,
            camera,
            centre,
            width,
            roll,
            Rules::Reach,
            smooth,
        );
        let replay = replay_on_scene(scene, &gesture).unwrap();
        assert_eq!(replay.target, target, "{what}");
        let opening = replay.opening.expect("the opening");
        println!(
            "{what} (smooth {smooth}): {} planes, {:.1} mm deep ({:?}), reaches {:?}, ratio {:.3}, covered {:.3}, outside {:.3}",
            replay.cutter.planes.len(),
            replay.cutter.depth(),
            replay.reach.map(|r| r.rule),
            names(&replay),
            opening.ratio(),
            opening.covered(),
            opening.outside()
        );
        assert!(replay.cutter.planes.len() >= 4, "{what}: the roller moved");
        assert!(opening.covered() >= 0.9, "{what}: {opening:?}");
        assert!(opening.outside() <= 0.1, "{what}: {opening:?}");
    }
}

#[test]
fn the_opening_on_the_knee_is_what_was_painted() {
    // The knee phantom: its skin, painted from the front over the kneecap.
    let knee = cutaway::anatomy::assets::scene("knee").expect("the knee phantom");
    let mut scene = Scene::default();
    for (i, model) in cutaway::anatomy::assets::load_scene_structures(knee)
        .unwrap()
        .into_iter()
        .enumerate()
    {
        let color = cutaway::anatomy::colors::structure_color(&model.name, model.color, i);
        scene.models.push(SceneModel::structure(model, color));
    }
    let skin = scene
        .models
        .iter()
        .position(|m| m.model.name == "skin")
        .unwrap();
    let patella = scene
        .models
        .iter()
        .position(|m| m.model.name == "patella")
        .unwrap();
    let front = front_of(&scene, skin, patella);
    check_opening(&scene, skin, front, "knee phantom");

    // The real knee: the tibia from the front (the side the kneecap is on).
    let Some(dir) = anatomy() else {
        return csg::testkit::skip(
            csg::testkit::Resource::Data,
            "the real knee: no anatomy folder (set CUTAWAY_ANATOMY)",
        );
    };
    let folder = dir.join("knee_vhf_left_denver");
    let mut real = Scene::default();
    for file in [
        "VHF_Left_Bone_Tibia_smooth.stl",
        "VHF_Left_Bone_Fibula_smooth.stl",
        "VHF_Left_Bone_Patella_smooth.stl",
        "VHF_Left_Ligament_ACL_smooth.stl",
        "VHF_Left_Ligament_PCL_smooth.stl",
    ] {
        let path = folder.join(file);
        if !path.exists() {
            eprintln!("skipped the real knee: {file} is missing");
            return;
        }
        let mesh = cutaway::io::read_mesh(&path).unwrap();
        real.models.push(SceneModel::new(
            file,
            &path,
            Arc::new(mesh),
            [0.9, 0.85, 0.7],
        ));
    }
    let front = front_of(&real, 0, 2);
    check_opening(&real, 0, front, "real tibia");
}

/// The horizontal direction from model `target`'s centre toward model `toward`'s (the front of
/// a knee: the kneecap's side).
fn front_of(scene: &Scene, target: usize, toward: usize) -> DVec3 {
    let d = scene.models[toward].model.mesh.bbox().center()
        - scene.models[target].model.mesh.bbox().center();
    DVec3::new(d.x, d.y, 0.0).normalize()
}

/// Renders `scene` at 1280×800 as `cutaway render` does and compares it with the golden image
/// `name` (written with `UPDATE_GOLDEN=1`; tolerance [`crate::image_compare::GOLDEN`]).
fn render_golden(name: &str, scene: &Scene) {
    let Some(mut renderer) = crate::renderer() else {
        return;
    };
    let mut options = cutaway::view::RenderPngOptions::new(1280, 800);
    options.deterministic = true;
    let image = cutaway::view::headless::render_with(&mut renderer, scene, &options).unwrap();
    crate::compare_to_golden(name, &image, renderer.is_software());
}
