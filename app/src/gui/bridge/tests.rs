//! Tests of [`super`] (`bridge.rs`), kept in their own file.

use super::*;
use crate::cutting::scene_cuts::apply_all_cuts;
use crate::scene::CutterViews;
use crate::test_support::scene_with_cube_cut;

#[test]
fn remove_all_cut_geometry_leaves_the_closed_kept_part() {
    // A 2-unit cube with a 1-unit corner cut away.
    let scene = scene_with_cube_cut(CutterViews::default());
    let applied = apply_all_cuts(&scene, &Progress::default()).unwrap();
    assert_eq!(applied.len(), 1);
    let (model, mesh) = &applied[0];
    assert_eq!(*model, 0);
    let report = mesh.report();
    assert!(report.closed, "{report:?}");
    assert!((mesh.volume() - 7.0).abs() < 1e-9, "{}", mesh.volume());
}

#[test]
fn export_cut_meshes_writes_the_chosen_parts() {
    let scene = scene_with_cube_cut(CutterViews::default());
    let dir = std::env::temp_dir().join(format!("cutaway-export-{}", std::process::id()));
    let settings = crate::gui::panels::menus::ExportMeshSettings {
        removed: true,
        ..Default::default()
    };
    let written = export_meshes(&scene, &settings, &dir, &Progress::default()).unwrap();
    let names: Vec<String> = written
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    assert!(
        names.iter().any(|n| n.ends_with("_removed.obj")),
        "{names:?}"
    );
    let removed = written
        .iter()
        .find(|p| p.to_string_lossy().ends_with("_removed.obj"));
    let mesh = crate::io::read_mesh(removed.unwrap()).unwrap();
    assert!((mesh.area() - 3.0).abs() < 1e-9, "{}", mesh.area());
    let _ = std::fs::remove_dir_all(&dir);
    // No cutters: a clear error naming the folder.
    let mut empty = scene.clone();
    empty.cutters.clear();
    let err = export_meshes(&empty, &settings, &dir, &Progress::default()).unwrap_err();
    assert!(format!("{err:#}").contains(&dir.display().to_string()));
}
