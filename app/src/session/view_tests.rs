//! The scene orientation in sessions: written, read back, guessed for older files, refused when
//! not a pair of orthogonal unit vectors.

use std::path::Path;

use glam::DVec3;

use crate::scene::ModelUnit;
use crate::session::{self, FORMAT};

use crate::scene::{LengthUnit, Orientation};

/// Serves `body.obj`: a box 0.5 × 1.6 × 0.3 (a standing body in metres, Y up).
fn body_loader(path: &Path, _unit: ModelUnit) -> anyhow::Result<Vec<crate::io::Model>> {
    anyhow::ensure!(
        path.ends_with("body.obj"),
        "{}: no such file",
        path.display()
    );
    Ok(vec![crate::io::Model {
        name: "body".into(),
        source: path.to_path_buf(),
        index: 0,
        color: None,
        group: String::new(),
        mesh: crate::gui::app::box_mesh(DVec3::ZERO, DVec3::new(0.5, 1.6, 0.3)).into(),
    }])
}

fn file(orientation: &str) -> session::SessionFile {
    session::parse(&format!(
        r#"{{"format": "{FORMAT}", "models": [{{"path": "body.obj"}}]{orientation}}}"#
    ))
    .unwrap()
}

#[test]
fn an_old_session_is_guessed_and_a_saved_orientation_is_kept() {
    let folder = Path::new("/s");
    // No orientation field (an older file): guessed from the models, like a fresh open.
    let scene = session::scene_from_file(&file(""), folder, &mut body_loader).unwrap();
    assert_eq!(scene.orientation, Orientation::Y_UP);
    assert_eq!(scene.unit, LengthUnit::Metre);
    // The user's choice (RAS here) is written and read back as it is.
    let mut chosen = scene.clone();
    chosen.orientation = Orientation::RAS;
    let written = session::file_from_scene(&chosen, folder);
    let text = serde_json::to_string(&written).unwrap();
    assert!(text.contains("\"orientation\""), "{text}");
    let back = session::scene_from_file(&session::parse(&text).unwrap(), folder, &mut body_loader)
        .unwrap();
    assert_eq!(back.orientation, Orientation::RAS);
}

#[test]
fn a_skewed_orientation_is_refused_naming_the_field() {
    let skewed = file(r#", "orientation": {"superior": [0, 0, 1], "anterior": [0, 1, 1]}"#);
    let err = session::scene_from_file(&skewed, Path::new("/s"), &mut body_loader).unwrap_err();
    assert!(format!("{err:#}").contains("orientation"), "{err:#}");
}
