//! What a newcomer meets in the first minute, at 1280×800: the tools in a panel of their own
//! with nothing clipped, File → Open… for everything (asking to save unsaved work, starting where
//! the last file was), the first drag on a big structure just loaded making a cutter, the roller
//! under the pointer, the wheel zooming toward the pointer, the view message clearing after an
//! orbit, the first-use hint, and a single-region model keeping its name.

use super::*;
use crate::harness::apply;
use crate::input::drag_steps as drag;

use cutaway::gui::app::{Action, Purpose, UnsavedAnswer};
use cutaway::gui::viewport::view_menu::ViewCommand;
use cutaway::scene::ViewPreset;
use glam::{DVec2, DVec3};

/// Viewport pixels (physical) of a point in points.
fn to_px(h: &Harness<'_, CutawayApp>, p: egui::Pos2) -> DVec2 {
    let ppp = h.ctx.pixels_per_point() as f64;
    let r = h.state().viewport.rect;
    DVec2::new((p.x - r.left()) as f64 * ppp, (p.y - r.top()) as f64 * ppp)
}

/// Where a world point is drawn, in points.
fn on_screen(h: &Harness<'_, CutawayApp>, p: DVec3) -> egui::Pos2 {
    let app = h.state();
    let px = app.scene.camera.project(app.viewport.size_px, p).unwrap();
    let ppp = h.ctx.pixels_per_point() as f64;
    app.viewport.rect.min + egui::vec2((px.x / ppp) as f32, (px.y / ppp) as f32)
}

/// Every labelled widget drawn in `panel` lies inside it, left to right (a clipped label
/// reaches past the panel's edge); returns how many were checked.
fn assert_inside(h: &Harness<'_, CutawayApp>, panel: egui::Rect, what: &str) -> usize {
    let mut checked = 0;
    for node in h.query_all_by(|n| n.bounding_box().is_some()) {
        let label = node
            .accesskit_node()
            .label()
            .or_else(|| node.accesskit_node().value())
            .map(|l| l.to_string())
            .unwrap_or_default();
        let r = node.rect();
        let c = r.center();
        if label.is_empty() || !panel.contains(c) {
            continue;
        }
        checked += 1;
        assert!(
            r.min.x >= panel.min.x - 1.0 && r.max.x <= panel.max.x + 1.0,
            "{what}: '{label}' at {r:?} is clipped by its panel {panel:?}"
        );
    }
    checked
}

#[test]
fn the_tools_have_a_panel_of_their_own_and_nothing_in_either_panel_is_clipped() {
    if let Some(reason) = no_adapter() {
        println!("skipped: {reason}");
        return;
    }
    let dir = temp_dir("tools-panel");
    let mut h = harness(&dir, Vec::new(), false);
    settle(&mut h);
    assert!(h.state().scene.models.len() > 50, "the default scene");
    // The newcomer's state: the skin selected, a cutter painted on it.
    apply(&mut h, Action::SelectModel(Some(0)));
    apply(&mut h, Action::SetMode(Mode::Edit));
    let c = h.state().viewport.rect.center();
    drag(
        &mut h,
        c + egui::vec2(-50.0, -90.0),
        c + egui::vec2(50.0, -90.0),
        6,
    );
    settle(&mut h);
    assert_eq!(
        h.state().scene.cutters.len(),
        1,
        "{}",
        h.state().status.message
    );
    let widths = |h: &Harness<'_, CutawayApp>| {
        let layout = h.state().layout;
        (layout.models.width(), layout.tools.width())
    };
    let first = widths(&h);
    for mode in [Mode::Camera, Mode::Edit, Mode::Preview, Mode::Scalpel] {
        apply(&mut h, Action::SetMode(mode));
        settle(&mut h);
        h.run_steps(20);
        // The panels keep their width: no row pushes a panel wider frame after frame.
        let now = widths(&h);
        assert!(
            (now.0 - first.0).abs() < 0.5 && (now.1 - first.1).abs() < 0.5,
            "{mode:?}: panel widths {first:?} became {now:?}"
        );
        let (view, layout) = (h.state().viewport.rect, h.state().layout);
        // The tools are right of the view, the model list left of it.
        assert!(
            layout.tools.min.x >= view.max.x - 1.0,
            "{layout:?} {view:?}"
        );
        assert!(
            layout.models.max.x <= view.min.x + 1.0,
            "{layout:?} {view:?}"
        );
        let tools = assert_inside(&h, layout.tools, "tools");
        let models = assert_inside(&h, layout.models, "models");
        assert!(
            tools > 15 && models > 15,
            "{mode:?}: {tools} tools, {models} rows"
        );
        // The cutter's and the cut views' controls are in sight without scrolling, whatever the
        // list holds; in Scalpel mode the scalpel's too.
        let mut wanted = vec![
            "Live cut",
            "Segment spacing ω",
            "Rounded",
            "New Cutter",
            "Removed piece, transparent",
            "Slices",
            "Ribbons",
        ];
        if mode == Mode::Scalpel {
            wanted.push("Cut layers below");
        }
        for label in wanted {
            let r = h.get_by_label(label).rect();
            assert!(
                layout.tools.contains_rect(r),
                "{mode:?}: '{label}' at {r:?} is not in sight in {:?}",
                layout.tools
            );
        }
    }
    let image = h.render().expect("render");
    image.save(dir.join("tools-panel.png")).unwrap();
    println!("screenshot: {}", dir.join("tools-panel.png").display());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_removed_piece_views_are_in_the_cut_menu_and_transparency_starts_visible() {
    if let Some(reason) = no_adapter() {
        println!("skipped: {reason}");
        return;
    }
    let dir = temp_dir("cut-menu");
    let mut h = harness(&dir, Vec::new(), false);
    settle(&mut h);
    apply(&mut h, Action::SelectModel(Some(0)));
    apply(&mut h, Action::SetMode(Mode::Edit));
    let c = h.state().viewport.rect.center();
    drag(
        &mut h,
        c + egui::vec2(-50.0, -90.0),
        c + egui::vec2(50.0, -90.0),
        6,
    );
    settle(&mut h);
    assert_eq!(h.state().scene.cutters.len(), 1);
    h.get_by_label("Cut").click();
    h.run_steps(2);
    h.get_by_label("Removed Piece, Transparent").click();
    h.run_steps(3);
    let views = h.state().scene.cutters[0].views;
    let opacity = views.transparency.expect("the menu turned transparency on");
    assert!(
        opacity >= 0.45,
        "a ghost that reads at a glance, not {opacity}"
    );
    assert_eq!(
        opacity,
        cutaway::gui::panels::cutter_panel::DEFAULT_TRANSPARENCY
    );
    h.get_by_label("Slices").click();
    h.run_steps(3);
    assert!(h.state().scene.cutters[0].views.slices.is_some());
    // One undo step each, as in the panel.
    apply(&mut h, Action::Undo);
    assert!(h.state().scene.cutters[0].views.slices.is_none());
    assert!(h.state().scene.cutters[0].views.transparency.is_some());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn file_open_opens_everything_asks_to_save_first_and_starts_where_the_last_file_was() {
    if let Some(reason) = no_adapter() {
        println!("skipped: {reason}");
        return;
    }
    let dir = temp_dir("open");
    let data = dir.join("data");
    std::fs::create_dir_all(data.join("atlas")).unwrap();
    let (ball, cube) = (data.join("ball.ply"), data.join("cube.obj"));
    cutaway::io::write_mesh(&ball, &csg::testkit::geodesic_sphere(8, 20.0)).unwrap();
    let box_mesh = csg::testkit::cube(DVec3::splat(30.0), DVec3::splat(50.0));
    cutaway::io::write_mesh(&cube, &box_mesh).unwrap();
    cutaway::io::write_mesh(&data.join("atlas/part.stl"), &box_mesh).unwrap();
    std::fs::write(data.join("notes.txt"), "not for Cutaway").unwrap();
    let mut h = harness(&dir.join("state"), vec![ball.clone()], false);
    settle(&mut h);
    h.state_mut().native_dialogs = false;

    // One Open… item; the old Load Model… and Load Directory… are gone.
    h.get_by_label("File").click();
    h.run_steps(2);
    assert!(h.query_by_label_contains("Load Model").is_none());
    assert!(h.query_by_label_contains("Load Directory").is_none());
    click_menu_item(&mut h, "Open…", "Folder");
    // A new window is laid out unseen in its first frame.
    h.run_steps(2);
    let browser = h.state().browser.as_ref().expect("the in-window browser");
    assert_eq!(browser.purpose, Purpose::Open);
    // It starts in the last file's folder with that file selected, and lists what opens.
    h.get_by_label("\u{1F5CB} ball.ply");
    h.get_by_label("\u{1F5CB} cube.obj");
    h.get_by_label("\u{1F5C0} atlas");
    assert!(h.query_by_label_contains("notes.txt").is_none());
    h.get_by_label("ball.ply");
    // A folder opens whole.
    h.get_by_label("\u{1F5C0} atlas").click();
    h.run_steps(2);
    // The Open button (the window's title reads "Open" too).
    h.query_all_by_label("Open")
        .find(|n| n.accesskit_node().role() == egui::accesskit::Role::Button)
        .expect("the Open button")
        .click();
    h.run_steps(2);
    settle(&mut h);
    assert!(h.state().browser.is_none());
    let names: Vec<String> = h
        .state()
        .scene
        .models
        .iter()
        .map(|m| m.name.clone())
        .collect();
    assert_eq!(names, ["part"], "{}", h.state().status.message);

    // Unsaved work (a model added): opening over it asks first; Cancel keeps it.
    apply(&mut h, Action::Add(vec![cube.clone()]));
    settle(&mut h);
    assert_eq!(h.state().scene.models.len(), 2);
    apply(&mut h, Action::Open(vec![ball.clone()]));
    assert!(h.state().unsaved_prompt.is_some(), "no question asked");
    h.get_by_label("Save the changes first?");
    h.get_by_label("Cancel").click();
    h.run_steps(2);
    settle(&mut h);
    assert!(h.state().unsaved_prompt.is_none());
    assert_eq!(h.state().scene.models.len(), 2, "Cancel opened anyway");
    // Don't Save opens.
    apply(&mut h, Action::Open(vec![ball.clone()]));
    h.get_by_label("Don't Save").click();
    h.run_steps(2);
    settle(&mut h);
    assert_eq!(h.state().scene.models.len(), 1);
    assert_eq!(h.state().scene.models[0].name, "ball");
    // Nothing changed since: no question.
    apply(&mut h, Action::Open(vec![cube.clone()]));
    settle(&mut h);
    assert!(h.state().unsaved_prompt.is_none());
    assert_eq!(h.state().scene.models[0].name, "cube");
    // Save first: Save As is asked for (no session yet); once saved the open goes on.
    apply(&mut h, Action::Add(vec![ball.clone()]));
    settle(&mut h);
    apply(&mut h, Action::Open(vec![ball.clone()]));
    apply(&mut h, Action::Unsaved(UnsavedAnswer::Save));
    let browser = h.state().browser.as_ref().expect("Save As");
    assert_eq!(browser.purpose, Purpose::SaveSessionAs);
    h.state_mut().browser = None;
    let session = data.join("work.json");
    apply(&mut h, Action::SaveSessionTo(session.clone()));
    settle(&mut h);
    assert!(session.is_file());
    assert_eq!(h.state().scene.models.len(), 1, "the open did not go on");
    // The browser starts at the last file opened (the ball, opened once the session was
    // saved), the session saved beside it listed.
    apply(&mut h, Action::Dialog(Purpose::Open));
    h.run_steps(2);
    h.get_by_label("\u{1F5CB} work.json");
    h.get_by_label("ball.ply");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A sphere of about 180 000 triangles: above the size whose index is built on the UI thread.
fn big_sphere(path: &std::path::Path) {
    let mesh = csg::testkit::geodesic_sphere(95, 50.0);
    assert!(mesh.triangle_count() > 150_000);
    cutaway::io::write_mesh(path, &mesh).unwrap();
}

#[test]
fn the_first_drag_on_a_big_structure_just_loaded_makes_a_cutter() {
    if let Some(reason) = no_adapter() {
        println!("skipped: {reason}");
        return;
    }
    let dir = temp_dir("first-drag");
    let sphere = dir.join("organ.ply");
    big_sphere(&sphere);
    let mut h = harness(&dir.join("state"), vec![sphere], false);
    settle(&mut h);
    // Select it and press E, then drag at once: the index is still being built.
    apply(&mut h, Action::SelectModel(Some(0)));
    h.key_press(egui::Key::E);
    h.run_steps(1);
    assert_eq!(h.state().mode, Mode::Edit, "E is Edit mode");
    let c = h.state().viewport.rect.center();
    let (a, b) = (c + egui::vec2(-60.0, -20.0), c + egui::vec2(60.0, -20.0));
    drag(&mut h, a, b, 6);
    let held = h.state().viewport.held.is_some();
    println!(
        "drag {}: {}",
        if held { "held" } else { "taken at once" },
        h.state().status.message
    );
    settle(&mut h);
    h.run_steps(3);
    let app = h.state();
    assert_eq!(
        app.scene.cutters.len(),
        1,
        "the drag was lost: {}",
        app.status.message
    );
    // Where it was painted: the first plane's front edge runs from the press to the release.
    let first = app.scene.cutters[0].cutter.planes[0];
    let ends = [
        on_screen(&h, first.front_top),
        on_screen(&h, first.front_bottom),
    ];
    for p in [a, b] {
        let d = ends.iter().map(|e| e.distance(p)).fold(f32::MAX, f32::min);
        assert!(
            d < 6.0,
            "the cutter does not start where painted: {ends:?} vs {a:?}..{b:?}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_press_and_moves_in_one_slow_frame_start_the_cutter_where_pressed() {
    if let Some(reason) = no_adapter() {
        println!("skipped: {reason}");
        return;
    }
    let dir = temp_dir("slow-frame");
    let mut h = harness(&dir, Vec::new(), false);
    settle(&mut h);
    apply(&mut h, Action::SelectModel(Some(0)));
    apply(&mut h, Action::SetMode(Mode::Edit));
    let c = h.state().viewport.rect.center();
    let (a, b) = (c + egui::vec2(-60.0, -90.0), c + egui::vec2(60.0, -90.0));
    h.hover_at(a);
    h.step();
    // A software renderer's frame: the press and half the drag arrive together.
    h.event(egui::Event::PointerButton {
        pos: a,
        button: egui::PointerButton::Primary,
        pressed: true,
        modifiers: Default::default(),
    });
    for k in 1..=3 {
        h.event(egui::Event::PointerMoved(a + (b - a) * (k as f32 / 6.0)));
    }
    h.step();
    for k in 4..=6 {
        h.hover_at(a + (b - a) * (k as f32 / 6.0));
        h.step();
    }
    h.drop_at(b);
    h.run_steps(3);
    settle(&mut h);
    assert_eq!(h.state().scene.cutters.len(), 1);
    let first = h.state().scene.cutters[0].cutter.planes[0];
    let ends = [
        on_screen(&h, first.front_top),
        on_screen(&h, first.front_bottom),
    ];
    let from_press = ends.iter().map(|e| e.distance(a)).fold(f32::MAX, f32::min);
    assert!(
        from_press < 6.0,
        "the cutter starts {from_press} pt from the press: {ends:?}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_roller_stays_under_the_pointer_when_the_cursor_is_never_warped() {
    if let Some(reason) = no_adapter() {
        println!("skipped: {reason}");
        return;
    }
    let dir = temp_dir("roller");
    let mut h = harness(&dir, Vec::new(), false);
    settle(&mut h);
    apply(&mut h, Action::SelectModel(Some(0)));
    apply(&mut h, Action::SetMode(Mode::Edit));
    let c = h.state().viewport.rect.center();
    drag(
        &mut h,
        c + egui::vec2(-60.0, -110.0),
        c + egui::vec2(60.0, -110.0),
        6,
    );
    assert_eq!(h.state().scene.cutters.len(), 1);
    // Grab the handle off its middle: a third along the front edge, 6 points below it. The
    // harness, like Wayland, never moves the cursor to the handle.
    let lead = *h.state().scene.cutters[0].cutter.leading();
    let (top, bottom) = (
        on_screen(&h, lead.front_top),
        on_screen(&h, lead.front_bottom),
    );
    let grab = top + (bottom - top) * 0.38 + egui::vec2(0.0, 6.0);
    let to = grab + egui::vec2(0.0, 70.0);
    h.hover_at(grab);
    h.step();
    h.drag_at(grab);
    h.step();
    for k in 1..=7 {
        h.hover_at(grab + (to - grab) * (k as f32 / 7.0));
        h.step();
    }
    // The roller (the leading plane's front edge) is under the pointer while dragging.
    let lead = *h.state().scene.cutters[0].cutter.leading();
    let mid = on_screen(&h, lead.front_mid());
    let (top, bottom) = (
        on_screen(&h, lead.front_top),
        on_screen(&h, lead.front_bottom),
    );
    let along = (bottom - top).normalized();
    let off = to - mid;
    let across = (off - along * off.dot(along)).length();
    h.drop_at(to);
    h.run_steps(2);
    assert!(
        across < 4.0,
        "the roller is {across} pt off the pointer (edge {top:?}–{bottom:?}, pointer {to:?})"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_wheel_zooms_toward_the_pointer_in_fine_steps() {
    if let Some(reason) = no_adapter() {
        println!("skipped: {reason}");
        return;
    }
    let dir = temp_dir("zoom-at");
    let mut h = harness(&dir, Vec::new(), false);
    settle(&mut h);
    for mode in [Mode::Camera, Mode::Edit, Mode::Scalpel] {
        apply(&mut h, Action::SetMode(mode));
        apply(
            &mut h,
            Action::View(ViewCommand::Preset(ViewPreset::Anterior)),
        );
        // Over the head's right side, off the view's centre.
        let at = h.state().viewport.rect.center() + egui::vec2(70.0, -60.0);
        let px = to_px(&h, at);
        let ray = {
            let app = h.state();
            app.scene.camera.ray_through_pixel(app.viewport.size_px, px)
        };
        let scene = h.state().scene.clone();
        let hit = h
            .state_mut()
            .viewport
            .picks
            .pick(&scene, &ray)
            .map(|(_, t)| ray.at(t))
            .expect("the head is under the pointer");
        let before = h.state().scene.camera;
        h.hover_at(at);
        h.step();
        h.event(egui::Event::MouseWheel {
            unit: egui::MouseWheelUnit::Line,
            delta: egui::vec2(0.0, 1.0),
            modifiers: Default::default(),
            phase: egui::TouchPhase::Move,
            source: egui::MouseWheelSource::Wheel,
        });
        h.run_steps(2);
        let after = h.state().scene.camera;
        let ratio = after.distance() / before.distance();
        assert!(
            (0.9..0.95).contains(&ratio),
            "{mode:?}: one notch zoomed by {ratio}"
        );
        let seen = on_screen(&h, hit);
        assert!(
            seen.distance(at) < 1.5,
            "{mode:?}: the point under the pointer moved to {seen:?} from {at:?}"
        );
        assert!((after.forward() - before.forward()).length() < 1e-9);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_view_message_clears_after_an_orbit_and_the_hint_leads_to_the_first_cut() {
    if let Some(reason) = no_adapter() {
        println!("skipped: {reason}");
        return;
    }
    let dir = temp_dir("hint");
    let mut h = harness(&dir, Vec::new(), false);
    settle(&mut h);
    apply(
        &mut h,
        Action::View(ViewCommand::Preset(ViewPreset::Anterior)),
    );
    assert_eq!(h.state().status.message, "Anterior view");
    let c = h.state().viewport.rect.center();
    drag(&mut h, c, c + egui::vec2(60.0, 0.0), 4);
    assert_ne!(h.state().status.message, "Anterior view", "the view turned");
    // A message about something else stays through an orbit.
    h.state_mut().say("Saved somewhere");
    drag(&mut h, c, c + egui::vec2(-60.0, 0.0), 4);
    assert_eq!(h.state().status.message, "Saved somewhere");

    let hint = |h: &Harness<'_, CutawayApp>| cutaway::gui::viewport::first_use_hint(h.state());
    let first = hint(&h).expect("a hint in the empty view");
    assert!(
        first.contains("press E") && first.contains("drag"),
        "{first}"
    );
    apply(&mut h, Action::SelectModel(Some(0)));
    assert_eq!(
        hint(&h).as_deref(),
        Some("Press E, then drag across skin to cut into it")
    );
    h.key_press(egui::Key::E);
    h.run_steps(2);
    assert_eq!(h.state().mode, Mode::Edit);
    assert_eq!(hint(&h).as_deref(), Some("Drag across skin to cut into it"));
    apply(
        &mut h,
        Action::View(ViewCommand::Preset(ViewPreset::Anterior)),
    );
    drag(
        &mut h,
        c + egui::vec2(-50.0, -90.0),
        c + egui::vec2(50.0, -90.0),
        6,
    );
    assert_eq!(h.state().scene.cutters.len(), 1);
    assert_eq!(hint(&h), None, "the hint stays after the first cut");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_model_with_one_region_keeps_its_name_in_the_list() {
    if let Some(reason) = no_adapter() {
        println!("skipped: {reason}");
        return;
    }
    let dir = temp_dir("names");
    let organ = csg::testkit::cube(DVec3::ZERO, DVec3::splat(40.0));
    cutaway::io::write_mesh(&dir.join("organ.obj"), &organ).unwrap();
    let mut pair = csg::testkit::cube(DVec3::splat(100.0), DVec3::splat(110.0));
    pair.append(&csg::testkit::cube(
        DVec3::splat(130.0),
        DVec3::splat(140.0),
    ));
    cutaway::io::write_mesh(&dir.join("pair.obj"), &pair).unwrap();
    let session = dir.join("s.json");
    std::fs::write(
        &session,
        r#"{"format": "cutaway-session/1", "models": [{"path": "organ.obj", "name": "organ"}, {"path": "pair.obj"}]}"#,
    )
    .unwrap();
    let mut h = harness(&dir.join("state"), vec![session], false);
    settle(&mut h);
    let names: Vec<String> = h
        .state()
        .scene
        .models
        .iter()
        .map(|m| m.name.clone())
        .collect();
    assert_eq!(names, ["organ", "pair 1", "pair 2"]);
    h.get_by_label("organ");
    assert!(h.query_by_label("organ 1").is_none());
    let _ = std::fs::remove_dir_all(&dir);
}
