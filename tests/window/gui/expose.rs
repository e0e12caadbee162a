//! Expose in the window: selecting a structure and choosing Expose (the button under the list,
//! or the X key) adds one cutter per structure in front of it as one undo step, the status line
//! says what was opened, and the view then shows the structure where it showed the skin.

use super::*;

/// A green ball (the focus) inside a closed head, behind a plate covering its left half, with a
/// red ball beside it; seen from the front. Returns the session's path.
fn head_session(dir: &Path) -> PathBuf {
    let ball = |radius: f64, x: f64| {
        let mut m = csg::testkit::geodesic_sphere(24, radius);
        for p in &mut m.positions {
            p.x += x;
        }
        m
    };
    cutaway::io::write_mesh(&dir.join("focus.obj"), &ball(8.0, 0.0)).unwrap();
    cutaway::io::write_mesh(&dir.join("head.obj"), &ball(40.0, 0.0)).unwrap();
    cutaway::io::write_mesh(&dir.join("beside.obj"), &ball(4.0, 25.0)).unwrap();
    let plate = csg::testkit::cube(
        glam::DVec3::new(-30.0, -25.0, -15.0),
        glam::DVec3::new(-2.0, -20.0, 15.0),
    );
    cutaway::io::write_mesh(&dir.join("plate.obj"), &plate).unwrap();
    let model = |path: &str, name: &str, color: [f32; 3]| {
        serde_json::json!({"path": path, "structure": 0, "name": name, "color": color,
                           "opacity": 1.0, "style": "solid", "visible": true})
    };
    let session = serde_json::json!({
        "format": "cutaway-session/2",
        "models": [model("focus.obj", "focus", [0.1, 0.8, 0.1]),
                   model("head.obj", "head", [0.85, 0.75, 0.65]),
                   model("plate.obj", "plate", [0.3, 0.3, 0.9]),
                   model("beside.obj", "beside", [0.9, 0.2, 0.2])],
        "camera": {"eye": [0, -200, 0], "target": [0, 0, 0], "up": [0, 0, 1], "fov_y_deg": 30},
    });
    let path = dir.join("head.json");
    std::fs::write(&path, serde_json::to_string_pretty(&session).unwrap()).unwrap();
    path
}

/// The window's colour where the focus's centre projects.
fn colour_at_focus(h: &mut Harness<'_, CutawayApp>) -> [u8; 3] {
    let image = h.render().expect("render the window");
    let app = h.state();
    let px = app
        .scene
        .camera
        .project(app.viewport.size_px, glam::DVec3::ZERO)
        .expect("the focus is in view");
    let ppp = h.ctx.pixels_per_point();
    let at = app.viewport.rect.min * ppp + egui::vec2(px.x as f32, px.y as f32);
    let p = image.get_pixel(at.x as u32, at.y as u32);
    [p[0], p[1], p[2]]
}

fn greenish(c: [u8; 3]) -> bool {
    c[1] as i32 > c[0] as i32 + 40 && c[1] as i32 > c[2] as i32 + 40
}

#[test]
fn expose_adds_a_cutter_per_occluder_as_one_undo_step_and_the_view_shows_the_structure() {
    if let Some(reason) = no_adapter() {
        println!("skipped: {reason}");
        return;
    }
    let dir = temp_dir("expose");
    let session = head_session(&dir);
    let mut h = harness(&dir, vec![session], false);
    settle(&mut h);
    assert_eq!(
        h.state().scene.models.len(),
        4,
        "{}",
        h.state().status.message
    );
    let before = colour_at_focus(&mut h);
    assert!(!greenish(before), "the head hides the focus: {before:?}");

    // Select the focus in the list, then Expose under it.
    h.get_by_label("focus").click();
    h.run_steps(2);
    assert_eq!(h.state().selected_model, Some(0));
    h.get_by_role_and_label(egui::accesskit::Role::Button, "Expose")
        .click();
    h.run_steps(2);
    settle(&mut h);
    let app = h.state();
    let targets: Vec<usize> = app.scene.cutters.iter().map(|c| c.target).collect();
    assert_eq!(targets, [1, 2], "{}", app.status.message);
    let message = app.status.message.clone();
    assert!(
        message.starts_with("Exposed focus: 2 cutters through head, plate; ")
            && message.ends_with(" mm³ removed"),
        "{message}"
    );
    assert_eq!(app.history.undo_label(), Some("expose focus"));
    for c in &app.scene.cutters {
        c.cutter.validate().unwrap();
    }
    let after = colour_at_focus(&mut h);
    assert!(
        greenish(after),
        "the focus shows through the opening: {after:?}"
    );
    let shot = dir.join("expose.png");
    h.render().expect("render").save(&shot).expect("save");
    let _ = std::fs::copy(
        &shot,
        Path::new(env!("CARGO_TARGET_TMPDIR")).join("gui-expose.png"),
    );

    // One undo removes both cutters; X exposes the selection again.
    let ctx = h.ctx.clone();
    h.state_mut().apply(&ctx, cutaway::gui::app::Action::Undo);
    h.run_steps(2);
    assert!(h.state().scene.cutters.is_empty());
    h.key_press(egui::Key::X);
    h.run_steps(2);
    settle(&mut h);
    assert_eq!(
        h.state().scene.cutters.len(),
        2,
        "{}",
        h.state().status.message
    );
    let _ = std::fs::remove_dir_all(&dir);
}
