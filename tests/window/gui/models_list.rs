//! The Models list: structure names, groups, folders and the filter; an atlas folder as one
//! model per file; the default scene is the head atlas seen from the front.

use super::*;

/// A folder of structure files as an atlas exports them: `atlas/` with two hippocampi (one of
/// them two spheres: a structure with two regions) and `atlas/brainstem/pons`.
fn write_atlas(dir: &Path) -> PathBuf {
    let atlas = dir.join("atlas");
    std::fs::create_dir_all(atlas.join("brainstem")).unwrap();
    let sphere = |x: f64| {
        let mut m = csg::testkit::icosphere(2, 5.0);
        for p in &mut m.positions {
            p.x += x;
        }
        m
    };
    let mut two = sphere(-20.0);
    two.append(&sphere(-35.0));
    cutaway::io::write_mesh(&atlas.join("Model_17_left_hippocampus.obj"), &two).unwrap();
    cutaway::io::write_mesh(&atlas.join("Model_53_right_hippocampus.obj"), &sphere(20.0)).unwrap();
    cutaway::io::write_mesh(&atlas.join("brainstem/Model_35_pons.obj"), &sphere(0.0)).unwrap();
    atlas
}

/// Ticks or unticks the checkbox labelled exactly `label`.
fn click_checkbox(h: &mut Harness<'_, CutawayApp>, label: &str) {
    h.get_by_role_and_label(egui::accesskit::Role::CheckBox, label)
        .click();
    h.run_steps(3);
}

#[test]
fn the_models_list_names_structures_groups_folders_and_filters() {
    if let Some(reason) = no_adapter() {
        return skip(Resource::Gpu, reason);
    }
    let dir = temp_dir("models-list");
    let atlas = write_atlas(&dir);
    let mut h = harness(&dir, vec![atlas], false);
    settle(&mut h);
    let names: Vec<(String, String)> = h
        .state()
        .scene
        .models
        .iter()
        .map(|m| (m.model.name.clone(), m.model.group.clone()))
        .collect();
    let expect = |n: &str, g: &str| (n.to_string(), g.to_string());
    assert_eq!(
        names,
        [
            expect("left hippocampus", "atlas"),
            expect("right hippocampus", "atlas"),
            expect("pons", "atlas/brainstem"),
        ],
        "one model per file, named from the file, grouped by folder (status: {})",
        h.state().status.message
    );
    // The two-sphere file is one structure with both regions.
    assert_eq!(
        csg::regions::split_regions(&h.state().scene.models[0].model.mesh).len(),
        2
    );
    // Colours come from the anatomy table: both hippocampi alike, the pons different.
    let colours: Vec<[f32; 3]> = h.state().scene.models.iter().map(|m| m.color).collect();
    assert_eq!(colours[0], colours[1]);
    assert_ne!(colours[0], colours[2]);
    // Rows and group headers are in the list.
    h.get_by_label("left hippocampus");
    h.get_by_label("pons");
    h.get_by_role_and_label(egui::accesskit::Role::CheckBox, "atlas (3)");
    h.get_by_role_and_label(egui::accesskit::Role::CheckBox, "brainstem (1)");

    // A group's box hides everything in it, and one undo brings it back.
    click_checkbox(&mut h, "brainstem (1)");
    assert!(
        !h.state().scene.models[2].visible,
        "the group box hid the pons"
    );
    assert!(h.state().scene.models[0].visible);
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
    h.run_steps(2);
    assert!(
        h.state().scene.models[2].visible,
        "undo showed the pons again"
    );

    // The filter keeps the matching rows; Hide listed hides only those.
    h.get_by_role(egui::accesskit::Role::TextInput).click();
    h.run_steps(1);
    h.get_by_role(egui::accesskit::Role::TextInput)
        .type_text("hippo");
    h.run_steps(3);
    assert!(
        h.query_by_label("pons").is_none(),
        "the filter hides the pons row"
    );
    h.get_by_label("left hippocampus");
    h.get_by_label("Hide listed").click();
    h.run_steps(3);
    let visible: Vec<bool> = h.state().scene.models.iter().map(|m| m.visible).collect();
    assert_eq!(visible, [false, false, true]);

    // Cleared filter: every row is back, and Show all shows everything.
    h.get_by_label("Clear").click();
    h.run_steps(3);
    h.get_by_label("pons");
    h.get_by_label("Show all").click();
    h.run_steps(3);
    assert!(h.state().scene.models.iter().all(|m| m.visible));

    // The two-sphere hippocampus split on request: its regions become a folder of their own in
    // its place, and one undo makes it one model again.
    h.get_by_label("left hippocampus").click();
    h.run_steps(3);
    assert_eq!(h.state().selected_model, Some(0));
    h.get_by_label("Split").click();
    h.run_steps(3);
    let names: Vec<(String, String)> = h
        .state()
        .scene
        .models
        .iter()
        .map(|m| (m.model.name.clone(), m.model.group.clone()))
        .collect();
    assert_eq!(
        names,
        [
            expect("left hippocampus 1", "atlas/left hippocampus"),
            expect("right hippocampus", "atlas"),
            expect("pons", "atlas/brainstem"),
            expect("left hippocampus 2", "atlas/left hippocampus"),
        ],
        "{}",
        h.state().status.message
    );
    h.get_by_role_and_label(egui::accesskit::Role::CheckBox, "left hippocampus (2)");
    h.get_by_label("left hippocampus 2");
    let shot = Path::new(env!("CARGO_TARGET_TMPDIR")).join("gui-models-list-split.png");
    h.render().expect("render").save(&shot).expect("save");
    println!("screenshot: {}", shot.display());
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
    h.run_steps(3);
    assert_eq!(h.state().scene.models.len(), 3, "undo joined the regions");
    assert_eq!(h.state().scene.models[0].model.name, "left hippocampus");
    let shot = dir.join("models-list.png");
    h.render().expect("render").save(&shot).expect("save");
    println!("screenshot: {}", shot.display());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_brain_atlas_folder_lists_one_named_coloured_model_per_file() {
    if let Some(reason) = no_adapter() {
        return skip(Resource::Gpu, reason);
    }
    let anatomy = std::env::var_os("CUTAWAY_ANATOMY")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("../shared/anatomy"));
    let atlas = anatomy.join("head_brain_spl_atlas");
    if !atlas.is_dir() {
        return skip(
            Resource::Data,
            format!("{} not found (set CUTAWAY_ANATOMY)", atlas.display()),
        );
    }
    let dir = temp_dir("brain-atlas");
    let mut h = harness(&dir, vec![atlas], false);
    settle(&mut h);
    let app = h.state();
    assert_eq!(
        app.scene.models.len(),
        38,
        "one model per file (status: {})",
        app.status.message
    );
    let model = |name: &str| {
        app.scene
            .models
            .iter()
            .find(|m| m.model.name == name)
            .unwrap_or_else(|| panic!("no model named {name}"))
    };
    let srgb = |c: [f32; 3]| c.map(|v| (v * 255.0).round() as u8);
    assert_eq!(srgb(model("left hippocampus").color), [220, 216, 20]);
    assert_eq!(srgb(model("right lateral ventricle").color), [88, 106, 215]);
    assert_eq!(model("corpus callosum").model.group, "head_brain_spl_atlas");
    h.get_by_label("left hippocampus");
    let shot = dir.join("brain-atlas-list.png");
    h.render().expect("render").save(&shot).expect("save");
    println!("screenshot: {}", shot.display());
}

#[test]
fn the_default_scene_is_the_head_atlas_seen_from_the_front() {
    if let Some(reason) = no_adapter() {
        return skip(Resource::Gpu, reason);
    }
    let dir = temp_dir("default-head");
    let mut h = harness(&dir, Vec::new(), false);
    settle(&mut h);
    let app = h.state();
    let names: Vec<&str> = app
        .scene
        .models
        .iter()
        .map(|m| m.model.name.as_str())
        .collect();
    assert_eq!(names.first(), Some(&"skin"), "{names:?}");
    for deep in [
        "left lateral ventricle",
        "left hippocampus",
        "right putamen",
        "pons",
    ] {
        assert!(names.contains(&deep), "{deep} missing from {names:?}");
    }
    // RAS anatomy: the face looks toward +Y, so the camera stands on the +Y side, Z up.
    let camera = app.scene.camera;
    assert!(camera.eye.y > camera.target.y + 100.0, "{camera:?}");
    assert_eq!(camera.up, glam::DVec3::Z);
    let shot = dir.join("default-scene.png");
    h.render().expect("render").save(&shot).expect("save");
    println!("screenshot: {}", shot.display());
}
