//! The window opens the default scene, switches modes, saves a session, undoes and redoes,
//! offers a crash autosave, and refuses a missing file before any window opens.

use super::*;

#[test]
fn window_loads_the_default_scene_switches_modes_and_saves_a_session() {
    if let Some(reason) = no_adapter() {
        return skip(Resource::Gpu, reason);
    }
    let dir = temp_dir("smoke");
    let mut h = harness(&dir, Vec::new(), false);
    settle(&mut h);

    // The default scene is loaded, framed, and shown.
    let app = h.state();
    assert!(
        !app.scene.models.is_empty(),
        "default scene not loaded: {}",
        app.status.message
    );
    assert!(!app.status.is_error, "status: {}", app.status.message);
    let triangles: usize = app
        .scene
        .models
        .iter()
        .map(|m| m.model.mesh.triangle_count())
        .sum();
    assert!(
        triangles > 1000,
        "default scene has only {triangles} triangles"
    );
    assert_eq!(app.mode, Mode::Camera);

    // Camera mode: a drag in the viewport orbits the camera.
    let eye_before = h.state().scene.camera.eye;
    h.drag_at(egui::pos2(800.0, 400.0));
    h.step();
    h.hover_at(egui::pos2(900.0, 430.0));
    h.step();
    h.drop_at(egui::pos2(900.0, 430.0));
    h.run_steps(2);
    let eye_after = h.state().scene.camera.eye;
    assert!(
        (eye_after - eye_before).length() > 1e-6,
        "drag did not orbit the camera"
    );
    let distance_before = h.state().scene.camera.distance();

    // The modes switch through their buttons.
    click_mode(&mut h, "Edit");
    assert_eq!(h.state().mode, Mode::Edit);
    h.get_by_label("extrude (Shift: straight)");
    click_mode(&mut h, "Preview");
    assert_eq!(h.state().mode, Mode::Preview);
    click_mode(&mut h, "Camera");
    assert_eq!(h.state().mode, Mode::Camera);
    assert!(
        (h.state().scene.camera.distance() - distance_before).abs() < 1e-9,
        "mode switches moved the camera"
    );

    // The rendered frame is not blank: the 3D view drew something other than the background.
    let image = h.render().expect("render the window");
    let shot = dir.join("gui-smoke.png");
    image.save(&shot).expect("save screenshot");
    let centre = image
        .get_pixel(image.width() * 6 / 10, image.height() / 2)
        .0;
    let corner = image.get_pixel(image.width() - 5, image.height() - 40).0;
    println!(
        "screenshot: {} (centre {centre:?}, corner {corner:?})",
        shot.display()
    );
    assert_ne!(
        centre, corner,
        "the viewport shows only background where the head should be"
    );

    // Save Session through the File menu writes a cutaway-session/2 file (models are structures).
    let session = dir.join("smoke-session.json");
    h.state_mut().session_path = Some(session.clone());
    h.get_by_label("File").click();
    h.run_steps(2);
    click_menu_item(&mut h, "Save Session", "As");
    let text = std::fs::read_to_string(&session).unwrap_or_else(|e| {
        panic!(
            "{}: {e} (status: {})",
            session.display(),
            h.state().status.message
        )
    });
    let json: serde_json::Value = serde_json::from_str(&text).expect("session is JSON");
    assert_eq!(json["format"], "cutaway-session/2");
    assert_eq!(
        json["models"].as_array().map(Vec::len),
        Some(h.state().scene.models.len()),
        "every model is in the session"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn hiding_a_model_is_undone_and_redone_with_the_keyboard() {
    if let Some(reason) = no_adapter() {
        return skip(Resource::Gpu, reason);
    }
    let dir = temp_dir("undo");
    let mut h = harness(&dir, Vec::new(), false);
    settle(&mut h);
    assert!(
        !h.state().scene.models.is_empty(),
        "default scene not loaded: {}",
        h.state().status.message
    );
    let name = h.state().scene.models[0].model.name.clone();

    // Select the first model in the Models list, then untick Visible in its properties.
    h.get_by_label(&name).click();
    h.run_steps(2);
    assert_eq!(h.state().selected_model, Some(0));
    h.get_by_role_and_label(egui::accesskit::Role::CheckBox, "Visible")
        .click();
    h.run_steps(3);
    assert!(
        !h.state().scene.models[0].visible,
        "Visible checkbox did not hide the model"
    );

    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
    h.run_steps(2);
    assert!(
        h.state().scene.models[0].visible,
        "Ctrl+Z did not undo the hide"
    );
    h.key_press_modifiers(
        egui::Modifiers::COMMAND | egui::Modifiers::SHIFT,
        egui::Key::Z,
    );
    h.run_steps(2);
    assert!(
        !h.state().scene.models[0].visible,
        "Ctrl+Shift+Z did not redo the hide"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_crash_autosave_is_offered_and_can_be_discarded() {
    if let Some(reason) = no_adapter() {
        return skip(Resource::Gpu, reason);
    }
    let dir = temp_dir("recovery");
    std::fs::write(dir.join("recovery-session.json"), "{}").unwrap();
    let mut h = harness(&dir, Vec::new(), true);
    h.run_steps(2);
    h.get_by_label("Restore the previous session?");
    h.get_by_label("Discard").click();
    h.run_steps(2);
    assert!(h.state().pending_recovery.is_none());
    assert!(
        !dir.join("recovery-session.json").exists(),
        "discard keeps the autosave"
    );
    settle(&mut h);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_missing_file_is_one_line_error_before_any_window() {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_cutaway"))
        .args(["open", "/nonexistent/knee.obj"])
        .output()
        .expect("run cutaway");
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.starts_with("error: /nonexistent/knee.obj"),
        "{stderr}"
    );
}
