//! A session saved from an earlier default scene, which embedded the atlas's model files
//! (`assets/spl_head/Model_<label>_<name>.vtk`) instead of its label map, still opens: the
//! fixture `tests/data/main_default_scene.session.json` was written by that version's own
//! `session::save` from its default scene with one cutter on the skin, run from the repository's
//! root, so it names the model files relative to `tests/data/` as a user's saved session does.
//! Those files are gone; each is served as the surface of its label.

use std::path::{Path, PathBuf};

use crate::scene::{ModelUnit, Scene};

fn fixture() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/data/main_default_scene.session.json")
}

/// The session's entries as written: (path, name, group).
fn entries() -> Vec<(String, String, String)> {
    let text = std::fs::read_to_string(fixture()).unwrap();
    let file = crate::session::parse(&text).unwrap();
    file.models
        .iter()
        .map(|m| {
            (
                m.path.to_string_lossy().into_owned(),
                m.name.clone().unwrap_or_default(),
                m.group.clone().unwrap_or_default(),
            )
        })
        .collect()
}

fn check(scene: &Scene, how: &str) {
    let entries = entries();
    assert_eq!(
        entries.len(),
        23,
        "the earlier default had the skin and 22 structures"
    );
    assert_eq!(scene.models.len(), entries.len(), "{how}");
    let head = scene.models[0].model.mesh.bbox();
    for (model, (path, name, group)) in scene.models.iter().zip(&entries) {
        assert_eq!(&model.model.name, name, "{how}");
        assert_eq!(&model.model.group, group, "{how}: {name}");
        assert_eq!(model.unit, ModelUnit::Structure, "{how}: {name}");
        let file = Path::new(path).file_name().unwrap().to_str().unwrap();
        if let Some(value) = super::old_model_label(file) {
            assert!(
                !fixture().parent().unwrap().join(path).exists(),
                "{path} exists: the test would not test the fallback"
            );
            assert!(super::selection::in_default(value), "{name}");
        }
        let report = model.model.mesh.report();
        assert!(
            report.closed && report.manifold,
            "{how}: {name}: {report:?}"
        );
        assert!(
            model.model.mesh.volume() > 0.0,
            "{how}: {name} is inside out"
        );
        let b = model.model.mesh.bbox();
        assert!(
            head.contains(b.min) && head.contains(b.max),
            "{how}: {name} sticks out of the head"
        );
    }
    assert_eq!(scene.cutters.len(), 1, "{how}");
    assert_eq!(
        scene.cutters[0].target, 0,
        "{how}: the cutter cuts the skin"
    );
}

#[test]
fn a_session_of_the_model_file_default_opens_from_the_cli_and_the_window() {
    let scene = crate::session::load(&fixture()).unwrap_or_else(|e| panic!("{e:#}"));
    check(&scene, "session::load");
    let progress = crate::platform::jobs::Progress::default();
    let scene = crate::session::load::load_with_progress(&fixture(), &progress)
        .unwrap_or_else(|e| panic!("{e:#}"));
    check(&scene, "the window's loader");
    // Saved again, it names the same files, so it opens again.
    let dir = std::env::temp_dir().join(format!("cutaway-old-session-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let again = dir.join("again.session.json");
    crate::session::save(&again, &scene).unwrap();
    let reopened = crate::session::load(&again).unwrap_or_else(|e| panic!("{e:#}"));
    assert_eq!(reopened.models.len(), scene.models.len());
    std::fs::remove_dir_all(&dir).ok();
}
