//! Tests of [`super`] (`meshes.rs`), kept in their own file.

use super::*;
use crate::scene::CutterViews;
use crate::test_support::scene_with_cube_cut;

#[test]
fn export_cut_meshes_writes_the_chosen_parts() {
    let scene = scene_with_cube_cut(CutterViews::default());
    let dir = std::env::temp_dir().join(format!("cutaway-export-{}", std::process::id()));
    let parts = CutMeshParts {
        kept: true,
        walls: true,
        removed: true,
    };
    let written = write_cut_meshes(&scene, parts, "obj", &dir, &Progress::default()).unwrap();
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
    let err = write_cut_meshes(&empty, parts, "obj", &dir, &Progress::default()).unwrap_err();
    assert!(format!("{err:#}").contains(&dir.display().to_string()));
}
