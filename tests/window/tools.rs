//! The window's measuring and comparing tools, driven headless by egui_kittest on the real wgpu
//! renderer (lavapipe without a GPU) at 1280×800: the Metrics panel against `cutaway metrics` on
//! the same session (and the closest point it draws), variants made, switched and compared side
//! by side, the Ruler on a cube of known size, Export Image with labels, and Export Turntable with
//! its progress and Cancel. Screenshots go to the
//! test's temporary folder (`CARGO_TARGET_TMPDIR`), one per state, for a person to look at.
//!
//! Skipped, with the reason printed, when no wgpu adapter exists (set `WGPU_BACKEND=vulkan` with
//! Mesa's lavapipe installed).

use csg::testkit::{Resource, skip};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

use crate::harness::{apply, harness, no_adapter, shot};
use crate::scene_files::{
    box_obj, box_planes, cut_view, cutter, model, scratch, sphere_obj, write_session,
};
use cutaway::gui::CutawayApp;
use cutaway::gui::app::Action;
use cutaway::gui::panels::variants_panel::VariantCommand;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use glam::{DVec2, DVec3};

/// Steps until no job (loads, measurements, compare pictures) runs, twice over: a finished job
/// may start the next one.
fn settle(h: &mut Harness<'_, CutawayApp>) {
    let deadline = Instant::now() + Duration::from_secs(240);
    for _ in 0..2 {
        while h.state().busy() {
            assert!(Instant::now() < deadline, "background jobs did not finish");
            h.step();
            std::thread::sleep(Duration::from_millis(5));
        }
        h.run_steps(3);
    }
}

/// Opens the View menu and clicks the switch `label` in it.
fn view_switch(h: &mut Harness<'_, CutawayApp>, label: &str) {
    h.get_by_label("View").click();
    h.run_steps(2);
    h.get_by_label(label).click();
    h.run_steps(2);
    // Close the menu.
    h.key_press(egui::Key::Escape);
    h.run_steps(2);
}

/// A primary click at `pos` (points), far enough from any other click not to be a double-click.
fn click_at(h: &mut Harness<'_, CutawayApp>, pos: egui::Pos2) {
    h.run_steps(30);
    h.hover_at(pos);
    h.step();
    h.drag_at(pos);
    h.step();
    h.drop_at(pos);
    h.run_steps(2);
}

/// Where world point `p` is drawn in the 3D view, in points.
fn screen_pos(h: &Harness<'_, CutawayApp>, p: DVec3) -> egui::Pos2 {
    let app = h.state();
    let ppp = h.ctx.pixels_per_point() as f64;
    let px: DVec2 = app
        .scene
        .camera
        .project(app.viewport.size_px, p)
        .expect("in front of the camera");
    app.viewport.rect.min + egui::vec2((px.x / ppp) as f32, (px.y / ppp) as f32)
}

/// Pixels in `rect` (points) of `image` within 40 per channel of `rgb`.
fn count_colour(h: &Harness<'_, CutawayApp>, image: &image::RgbaImage, rgb: [u8; 3]) -> usize {
    let ppp = h.ctx.pixels_per_point();
    let r = h.state().viewport.rect;
    let mut n = 0;
    for y in (r.min.y * ppp) as u32..((r.max.y * ppp) as u32).min(image.height()) {
        for x in (r.min.x * ppp) as u32..((r.max.x * ppp) as u32).min(image.width()) {
            let p = image.get_pixel(x, y);
            if (0..3).all(|k| (p[k] as i32 - rgb[k] as i32).abs() < 40) {
                n += 1;
            }
        }
    }
    n
}

/// A 10 mm cube with a corner box cutter and an overlapping slot (removing 125 and 45 mm³), and a
/// ball beside it that the walls come close to.
/// The pixel box of everything in `image` that differs from its top-left pixel (the
/// background).
fn drawn_box(image: &image::RgbaImage) -> (DVec2, DVec2) {
    let background = *image.get_pixel(0, 0);
    let (mut min, mut max) = (DVec2::splat(f64::MAX), DVec2::splat(f64::MIN));
    for (x, y, p) in image.enumerate_pixels() {
        if (0..3).any(|k| (p[k] as i32 - background[k] as i32).abs() > 12) {
            let at = DVec2::new(x as f64, y as f64);
            min = min.min(at);
            max = max.max(at);
        }
    }
    assert!(min.x <= max.x, "nothing drawn");
    (min, max)
}

fn cube_and_ball(dir: &Path) -> PathBuf {
    write_session(
        dir,
        &[
            ("cube.obj", box_obj([0.0; 3], [10.0; 3])),
            ("ball.obj", sphere_obj([15.0, 5.0, 4.0], 3.0, 24, 12)),
        ],
        vec![
            model("cube.obj", [0.8, 0.6, 0.5]),
            model("ball.obj", [0.2, 0.4, 0.9]),
        ],
        vec![
            cutter(0, box_planes(5.0, 15.0, -5.0, 5.0, 5.0, 15.0), cut_view()),
            cutter(0, box_planes(4.0, 6.0, -5.0, 3.0, -5.0, 15.0), cut_view()),
        ],
        [-10.0, -90.0, 40.0],
    )
}

fn cli_metrics(session: &Path, extra: &[&str]) -> serde_json::Value {
    let output = Command::new(env!("CARGO_BIN_EXE_cutaway"))
        .arg("metrics")
        .arg(session)
        .args(extra)
        .arg("--json")
        .output()
        .unwrap();
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    serde_json::from_slice(&output.stdout).unwrap()
}

fn close(a: &serde_json::Value, b: &serde_json::Value, what: &str) {
    let (x, y) = (a.as_f64(), b.as_f64());
    match (x, y) {
        (Some(x), Some(y)) => assert!(
            (x - y).abs() <= 1e-9 * (1.0 + y.abs()),
            "{what}: window {x} != CLI {y}"
        ),
        _ => assert_eq!(a, b, "{what}"),
    }
}

#[test]
fn the_metrics_panel_shows_what_cutaway_metrics_prints_and_draws_the_closest_point() {
    if let Some(reason) = no_adapter() {
        return skip(Resource::Gpu, reason);
    }
    let dir = scratch("window-metrics");
    let session = cube_and_ball(&dir);
    let mut h = harness(&dir, vec![session.clone()]);
    h.run_steps(2);
    settle(&mut h);
    assert_eq!(
        h.state().scene.cutters.len(),
        2,
        "{}",
        h.state().status.message
    );
    let names: Vec<String> = h
        .state()
        .scene
        .models
        .iter()
        .map(|m| m.model.name.clone())
        .collect();
    let (cube, ball) = (names[0].clone(), names[1].clone());

    view_switch(&mut h, "Metrics");
    assert!(
        h.state().metrics.open,
        "View → Metrics did not open the panel"
    );
    h.state_mut().metrics.focus = Some(cube.clone());
    h.state_mut().metrics.set_critical(&ball, true);
    h.run_steps(2);
    settle(&mut h);
    let app = h.state();
    assert!(
        app.metrics.is_current(&app.scene),
        "the panel is not up to date"
    );
    let measured = match &app.metrics.shown {
        Some(Ok(m)) => m,
        Some(Err(e)) => panic!("measuring failed: {e}"),
        None => panic!("nothing measured"),
    };
    println!(
        "metrics panel update: {:.1} ms (2 box cutters on a cube, focus and one critical)",
        measured.ms
    );
    let window = serde_json::to_value(&measured.metrics).unwrap();
    let cli = cli_metrics(&session, &["--focus", &cube, "--critical", &ball]);
    for (c, cutter) in cli["cutters"].as_array().unwrap().iter().enumerate() {
        for field in ["removed_volume", "removed_area", "wall_area", "depth"] {
            close(
                &window["cutters"][c][field],
                &cutter[field],
                &format!("cutter {c} {field}"),
            );
        }
    }
    for (s, structure) in cli["structures"].as_array().unwrap().iter().enumerate() {
        assert_eq!(window["structures"][s]["name"], structure["name"]);
        for field in ["removed_volume", "removed_area", "min_distance"] {
            close(
                &window["structures"][s][field],
                &structure[field],
                &format!("structure {s} {field}"),
            );
        }
    }
    for field in ["exposure_before", "exposure_after"] {
        close(&window["focus"][field], &cli["focus"][field], field);
    }
    // The CLI runs the same code as the panel, so the numbers are also checked against the
    // closed forms of the scene. The corner box A = [5, 10] × [0, 5] × [5, 10] of the cube
    // [0, 10]³, then the slot B = [4, 6] × [0, 3] × [0, 10] cut from what A left:
    // - A removes 125 mm³, three 5 × 5 squares of the cube's faces (75 mm²), its walls are three
    //   5 × 5 squares less what B takes of two of them (15 + 3): 57 mm²; 5 mm deep (y 0 → 5);
    // - B removes 60 − 15 (its overlap with A) = 45 mm³; of the cube's faces 20 − 5 (front),
    //   6 (bottom) and 6 − 3 (top) = 24 mm²; walls 30 (x = 4) + 15 (x = 6) + 15 (y = 3) = 60
    //   mm²; 3 mm deep;
    // - the ball (centre (15, 5, 4), radius 3, a UV sphere inside the true one by under 0.05)
    //   is nearest to the wall corner (10, 5, 5): √26 − 3 mm away, or up to 0.05 more.
    let m = &measured.metrics;
    let expect = |what: &str, got: f64, want: f64| {
        assert!(
            (got - want).abs() < 1e-6,
            "{what}: {got}, closed form {want}"
        );
    };
    for (c, (volume, area, wall, depth)) in [(125.0, 75.0, 57.0, 5.0), (45.0, 24.0, 60.0, 3.0)]
        .into_iter()
        .enumerate()
    {
        let cutter = &m.cutters[c];
        expect(
            &format!("cutter {c} volume"),
            cutter.removed_volume.unwrap(),
            volume,
        );
        expect(&format!("cutter {c} area"), cutter.removed_area, area);
        expect(&format!("cutter {c} walls"), cutter.wall_area, wall);
        expect(&format!("cutter {c} depth"), cutter.depth, depth);
    }
    expect(
        "cube volume",
        m.structures[0].removed_volume.unwrap(),
        170.0,
    );
    expect("cube area", m.structures[0].removed_area, 99.0);
    expect("cube walls", m.structures[0].wall_area, 117.0);
    let nearest = 26f64.sqrt() - 3.0;
    let distance = m.structures[1].min_distance.expect("distance");
    assert!(
        distance >= nearest - 1e-9 && distance <= nearest + 0.05,
        "distance {distance}, closed form {nearest} (+ up to 0.05)"
    );
    // The numbers are on screen.
    h.get_by_label("170.0");
    h.get_by_label(&format!("{distance:.1} mm"));

    // The closest point and the line to the wall are drawn in the viewport (magenta).
    let image = shot(&mut h, "metrics-panel");
    let marked = count_colour(&h, &image, [230, 30, 120]);
    assert!(marked > 30, "closest point marker: {marked} pixels");
    // Per cutter.
    h.get_by_label("cutter 1").click();
    h.run_steps(2);
    h.get_by_label("cut depth");
    shot(&mut h, "metrics-panel-cutter");
}

#[test]
fn variants_are_made_switched_saved_and_compared_side_by_side() {
    if let Some(reason) = no_adapter() {
        return skip(Resource::Gpu, reason);
    }
    let dir = scratch("window-variants");
    let session = cube_and_ball(&dir);
    let mut h = harness(&dir, vec![session]);
    h.run_steps(2);
    settle(&mut h);
    view_switch(&mut h, "Metrics");

    // Duplicate the cuts, then take the slot away from the copy.
    h.get_by_label("Duplicate").click();
    h.run_steps(2);
    assert_eq!(
        cutaway::scene::variants::names(&h.state().scene),
        ["current", "current 2"]
    );
    assert_eq!(h.state().scene.variants.active, 1);
    apply(&mut h, Action::RemoveCutter(1));
    assert_eq!(h.state().scene.cutters.len(), 1);
    // Rename the active variant through the name field.
    cutaway::gui::panels::variants_panel::apply(
        h.state_mut(),
        VariantCommand::Rename("corner".into()),
    );
    h.run_steps(2);
    assert_eq!(
        cutaway::scene::variants::names(&h.state().scene),
        ["current", "corner"]
    );

    // Switch back by clicking the first variant: its two cutters return.
    h.get_by_label("current  (2 cutters)").click();
    h.run_steps(2);
    assert_eq!(h.state().scene.variants.active, 0);
    assert_eq!(h.state().scene.cutters.len(), 2);
    apply(&mut h, Action::Undo);
    assert_eq!(h.state().scene.variants.active, 1, "undo of the switch");
    assert_eq!(h.state().scene.cutters.len(), 1);
    apply(&mut h, Action::Redo);
    assert_eq!(h.state().scene.cutters.len(), 2);

    // A new empty variant, then deleted.
    cutaway::gui::panels::variants_panel::apply(h.state_mut(), VariantCommand::New("empty".into()));
    assert!(h.state().scene.cutters.is_empty());
    h.run_steps(2);
    h.get_by_label("Delete").click();
    h.run_steps(2);
    assert_eq!(
        cutaway::scene::variants::names(&h.state().scene),
        ["current", "corner"]
    );

    // Saved in the session and read back.
    let saved = dir.join("variants.json");
    apply(&mut h, Action::SaveSessionTo(saved.clone()));
    let reread = cutaway::session::load(&saved).unwrap();
    assert_eq!(
        cutaway::scene::variants::names(&reread),
        ["current", "corner"]
    );
    let all = cutaway::scene::variants::all(&reread);
    assert_eq!((all[0].1.len(), all[1].1.len()), (2, 1));

    // Compare: both variants drawn from one camera with their measures under them.
    h.get_by_label("Compare side by side").click();
    h.run_steps(3);
    settle(&mut h);
    let compared = match &h.state().compare.shown {
        Some(Ok(c)) => c,
        Some(Err(e)) => panic!("compare failed: {e}"),
        None => panic!("nothing compared"),
    };
    assert_eq!(compared.images.len(), 2);
    let volume = |k: usize| {
        compared.variants[k].metrics.structures[0]
            .removed_volume
            .unwrap()
    };
    assert!((volume(0) - 170.0).abs() < 1e-9 && (volume(1) - 125.0).abs() < 1e-9);
    println!("compare view update: {:.1} ms (2 variants)", compared.ms);
    let differ = compared.images[0]
        .pixels()
        .zip(compared.images[1].pixels())
        .filter(|(a, b)| a != b)
        .count();
    assert!(
        differ > 100,
        "the two variants look the same ({differ} pixels differ)"
    );
    // The session's camera looks at the cube's corner, framed for the wide 3D view; each narrow
    // viewport frames the models instead: centred, nothing cut off at the borders.
    for image in &compared.images {
        let (w, h) = (image.width() as f64, image.height() as f64);
        let (min, max) = drawn_box(image);
        let centre = (min + max) * 0.5;
        assert!(
            (centre.x - w / 2.0).abs() < 0.08 * w && (centre.y - h / 2.0).abs() < 0.08 * h,
            "models drawn off-centre: {min:?}..{max:?} in {w}×{h}"
        );
        assert!(
            min.x > 1.0 && min.y > 1.0 && max.x < w - 2.0 && max.y < h - 2.0,
            "models cut off: {min:?}..{max:?} in {w}×{h}"
        );
    }
    let before = compared.images[0].clone();
    for shown in ["170.0 mm³", "125.0 mm³"] {
        assert!(
            h.query_all_by_label(shown).count() > 0,
            "{shown} is not shown"
        );
    }
    shot(&mut h, "compare-view");

    // Turning the camera in one viewport turns the shared camera and draws both again.
    let eye = h.state().scene.camera.eye;
    let centre = egui::pos2(400.0, 350.0);
    h.hover_at(centre);
    h.step();
    h.drag_at(centre);
    h.step();
    for k in 1..=5 {
        h.hover_at(centre + egui::vec2(12.0 * k as f32, 0.0));
        h.step();
    }
    h.drop_at(centre + egui::vec2(60.0, 0.0));
    h.run_steps(3);
    assert!(
        (h.state().scene.camera.eye - eye).length() > 1e-6,
        "the drag did not orbit"
    );
    settle(&mut h);
    let after = match &h.state().compare.shown {
        Some(Ok(c)) => c.images[0].clone(),
        _ => panic!("compare failed after turning"),
    };
    let changed = before
        .pixels()
        .zip(after.pixels())
        .filter(|(a, b)| a != b)
        .count();
    assert!(
        changed > 100,
        "the viewports were not drawn again ({changed} pixels changed)"
    );
    shot(&mut h, "compare-view-turned");
    // Closing gives the pictures and the renderer back; the 3D view returns.
    h.get_by_label("Close").click();
    h.run_steps(3);
    assert!(!h.state().compare.open && h.state().compare.shown.is_none());
    // The 3D view is framed for its own shape again: every corner of the scene inside it.
    let app = h.state();
    let (bbox, vp) = (app.scene.bbox(), app.viewport.size_px);
    for k in 0..8 {
        let corner = DVec3::new(
            if k & 1 == 0 { bbox.min.x } else { bbox.max.x },
            if k & 2 == 0 { bbox.min.y } else { bbox.max.y },
            if k & 4 == 0 { bbox.min.z } else { bbox.max.z },
        );
        let p = app.scene.camera.project(vp, corner).expect("in front");
        assert!(
            p.x >= 0.0 && p.y >= 0.0 && p.x <= vp.x && p.y <= vp.y,
            "corner {corner:?} at {p:?} outside the {vp:?} view after closing Compare"
        );
    }
}

#[test]
fn the_ruler_measures_a_cube_in_millimetres_and_is_saved() {
    if let Some(reason) = no_adapter() {
        return skip(Resource::Gpu, reason);
    }
    let dir = scratch("window-ruler");
    let session = write_session(
        &dir,
        &[("cube.obj", box_obj([0.0; 3], [10.0; 3]))],
        vec![model("cube.obj", [0.8, 0.6, 0.5])],
        Vec::new(),
        [5.0, -60.0, 5.0],
    );
    let mut h = harness(&dir, vec![session]);
    h.run_steps(2);
    settle(&mut h);
    h.state_mut().scene.camera.eye = DVec3::new(20.0, -50.0, 25.0);
    h.state_mut().scene.camera.target = DVec3::new(5.0, 5.0, 5.0);
    h.run_steps(2);
    view_switch(&mut h, "Ruler");
    assert!(h.state().ruler.active);

    // From a corner of the front face (y = 0) to a point on the top face (z = 10).
    let (a, b) = (DVec3::new(1.0, 0.0, 1.0), DVec3::new(9.0, 6.0, 10.0));
    let (pa, pb) = (screen_pos(&h, a), screen_pos(&h, b));
    click_at(&mut h, pa);
    assert!(
        h.state().ruler.first.is_some(),
        "{}",
        h.state().status.message
    );
    click_at(&mut h, pb);
    let rulers = h.state().scene.rulers.clone();
    assert_eq!(rulers.len(), 1, "{}", h.state().status.message);
    let expected = (b - a).length();
    // The ends are where the clicks hit the faces: within a hundredth of a millimetre.
    assert!((rulers[0].a - a).length() < 0.01 && (rulers[0].b - b).length() < 0.01);
    assert!((rulers[0].length() - expected).abs() < 0.02);
    let caption = format!("{expected:.1} mm");
    h.get_by_label(&caption);
    let image = shot(&mut h, "ruler");
    assert!(
        count_colour(&h, &image, [255, 200, 0]) > 50,
        "the ruler is not drawn"
    );

    // Kept in the session; a removed ruler is an undo step.
    let saved = dir.join("ruler.json");
    apply(&mut h, Action::SaveSessionTo(saved.clone()));
    let text = std::fs::read_to_string(&saved).unwrap();
    assert!(text.contains("\"rulers\""), "{text}");
    let reread = cutaway::session::load(&saved).unwrap();
    assert_eq!(reread.rulers.len(), 1);
    assert!((reread.rulers[0].length() - rulers[0].length()).abs() < 1e-12);
    // `cutaway render` draws saved rulers too.
    let png = dir.join("ruler-render.png");
    let output = Command::new(env!("CARGO_BIN_EXE_cutaway"))
        .args(["render"])
        .arg(&saved)
        .arg("--out")
        .arg(&png)
        .args(["--width", "480", "--height", "360"])
        .output()
        .unwrap();
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let rendered = image::open(&png).unwrap().to_rgba8();
    let yellow = rendered
        .pixels()
        .filter(|p| p[0] > 220 && p[1] > 170 && p[1] < 230 && p[2] < 60)
        .count();
    assert!(yellow > 50, "render drew no ruler ({yellow} pixels)");
    h.get_by_label("Remove").click();
    h.run_steps(2);
    assert!(h.state().scene.rulers.is_empty());
    apply(&mut h, Action::Undo);
    assert_eq!(h.state().scene.rulers.len(), 1);
}

#[test]
fn a_ruler_end_lands_on_the_cut_wall_seen_through_the_opening() {
    if let Some(reason) = no_adapter() {
        return skip(Resource::Gpu, reason);
    }
    let dir = scratch("window-ruler-cut");
    let session = cube_and_ball(&dir);
    let mut h = harness(&dir, vec![session]);
    h.run_steps(2);
    settle(&mut h);
    assert!(h.state().viewport.preview.is_some(), "the cut is not shown");
    view_switch(&mut h, "Ruler");
    // The corner cut opens the cube's front (y = 0) for x, z > 5: through it the camera sees the
    // notch's back wall y = 5. Without the cut the ray would stop on the front face.
    let wall = DVec3::new(8.0, 5.0, 8.0);
    let at = screen_pos(&h, wall);
    click_at(&mut h, at);
    let first = h.state().ruler.first.expect("no surface picked");
    assert!(
        (first - wall).length() < 0.01,
        "picked {first} instead of the wall {wall}"
    );
    let front = DVec3::new(2.0, 0.0, 2.0);
    let at = screen_pos(&h, front);
    click_at(&mut h, at);
    let ruler = h.state().scene.rulers[0];
    assert!((ruler.length() - (front - wall).length()).abs() < 0.02);
    shot(&mut h, "ruler-into-cut");
}

#[test]
fn export_image_with_labels_writes_the_labelled_picture() {
    if let Some(reason) = no_adapter() {
        return skip(Resource::Gpu, reason);
    }
    let dir = scratch("window-labels");
    let session = cube_and_ball(&dir);
    let mut h = harness(&dir, vec![session]);
    h.run_steps(2);
    settle(&mut h);
    let ball = h.state().scene.models[1].model.name.clone();
    {
        let app = h.state_mut();
        app.export_image.width = 640;
        app.export_image.height = 400;
    }
    let plain = dir.join("plain.png");
    apply(&mut h, Action::ExportImageTo(plain.clone()));
    settle(&mut h);

    // The dialog's switches.
    h.state_mut().export_image.open = true;
    h.run_steps(2);
    for switch in ["Structure labels", "Scale bar (mm)", "Orientation marker"] {
        h.get_by_label(switch).click();
        h.run_steps(2);
    }
    shot(&mut h, "export-dialog");
    let choice = h.state().export_image.annotations.clone();
    assert!(choice.labels && choice.extras.scale_bar && choice.extras.marker);
    let labelled = dir.join("labelled.png");
    apply(&mut h, Action::ExportImageTo(labelled.clone()));
    settle(&mut h);
    assert!(!h.state().status.is_error, "{}", h.state().status.message);
    let (a, b) = (
        image::open(&plain).unwrap().to_rgba8(),
        image::open(&labelled).unwrap().to_rgba8(),
    );
    assert_eq!(b.dimensions(), (640, 400));
    // Labels, the scale bar and the marker are drawn in the annotations' ink.
    let ink = |img: &image::RgbaImage| {
        img.pixels()
            .filter(|p| p[0] < 40 && p[1] < 40 && p[2] < 45)
            .count()
    };
    assert!(
        ink(&b) > ink(&a) + 200,
        "no annotations: {} vs {}",
        ink(&b),
        ink(&a)
    );

    // The same choice through the shared code: both structures labelled, then the ball off.
    let scene = h.state().scene.clone();
    let mut options = cutaway::view::RenderPngOptions::new(640, 400);
    options.mode = Some(cutaway::render::ViewMode::Camera);
    let (_, drawn) =
        cutaway::annotate::picture::render_annotated(&scene, &options, &choice).unwrap();
    let drawn = drawn.expect("annotations");
    assert_eq!(drawn.labels.len(), 2, "{:?}", drawn.unlabelled);
    assert!(drawn.scale_bar.is_some());
    let mut without_ball = choice.clone();
    without_ball.unlabelled.push(ball);
    let (_, drawn) =
        cutaway::annotate::picture::render_annotated(&scene, &options, &without_ball).unwrap();
    assert_eq!(drawn.expect("annotations").labels.len(), 1);
}

#[test]
fn export_turntable_shows_progress_cancels_without_output_and_writes_the_frames() {
    if let Some(reason) = no_adapter() {
        return skip(Resource::Gpu, reason);
    }
    let dir = scratch("window-turntable");
    let session = cube_and_ball(&dir);
    let mut h = harness(&dir, vec![session]);
    h.run_steps(2);
    settle(&mut h);
    h.get_by_label("File").click();
    h.run_steps(2);
    // A menu item's label ends in its (empty) shortcut text.
    h.query_all_by_label_contains("Export Turntable…")
        .next()
        .expect("no File → Export Turntable…")
        .click();
    h.run_steps(3);
    assert!(h.state().export_turntable.open, "the dialog did not open");
    h.get_by_label("Animated GIF (turntable.gif)");
    shot(&mut h, "export-turntable-dialog");
    {
        let s = &mut h.state_mut().export_turntable;
        (s.width, s.height, s.options.frames, s.options.gif) = (160, 120, 720, true);
    }

    // A long turntable, cancelled from the progress window once frames are being written.
    let cancelled = dir.join("cancelled");
    apply(&mut h, Action::ExportTurntableTo(cancelled.clone()));
    let deadline = Instant::now() + Duration::from_secs(240);
    loop {
        let started =
            h.state().jobs.iter().any(|j| {
                j.wants_progress_window() && j.progress.fraction().is_some_and(|f| f > 0.0)
            });
        if started {
            break;
        }
        assert!(
            h.state().busy(),
            "the export ended before it could be cancelled"
        );
        assert!(Instant::now() < deadline, "no frame was reported");
        h.step();
        std::thread::sleep(Duration::from_millis(5));
    }
    h.run_steps(2);
    h.get_by_label("Working…");
    shot(&mut h, "export-turntable-progress");
    h.get_by_label("Cancel").click();
    settle(&mut h);
    let status = h.state().status.message.clone();
    assert!(status.contains("cancelled"), "{status}");
    // The window lets go of a cancelled job at once; its worker stops after the frame it is
    // drawing and drops the uncommitted set, removing the folder it created.
    let gone = Instant::now() + Duration::from_secs(60);
    while cancelled.exists() && Instant::now() < gone {
        std::thread::sleep(Duration::from_millis(20));
    }
    assert!(
        !cancelled.exists(),
        "a cancelled export left {}",
        cancelled.display()
    );

    // A short one runs to the end: N frames, each another view, and the GIF.
    h.state_mut().export_turntable.options.frames = 3;
    let done = dir.join("done");
    apply(&mut h, Action::ExportTurntableTo(done.clone()));
    settle(&mut h);
    assert!(!h.state().status.is_error, "{}", h.state().status.message);
    let frames: Vec<image::RgbaImage> = (1..=3)
        .map(|k| {
            image::open(done.join(format!("frames/frame-{k:04}.png")))
                .unwrap()
                .to_rgba8()
        })
        .collect();
    assert_eq!(frames[0].dimensions(), (160, 120));
    assert_ne!(frames[0], frames[1]);
    assert_ne!(frames[1], frames[2]);
    assert!(done.join("turntable.gif").is_file());
    assert!(!done.join("frames/frame-0004.png").exists());
}

mod real_scenes;
