use std::sync::OnceLock;

use super::*;

/// The scene, surfaced once for all tests of this module.
fn scene() -> &'static [Model] {
    static SCENE: OnceLock<Vec<Model>> = OnceLock::new();
    SCENE.get_or_init(|| load().expect("the default scene loads"))
}

#[test]
fn the_skin_comes_first_closed_and_the_labels_follow_named_from_the_table() {
    let models = scene();
    assert!(is_default_scene(models));
    let skin = &models[0];
    assert_eq!((skin.name.as_str(), skin.group.as_str()), ("skin", ""));
    let report = skin.mesh.report();
    assert!(
        report.closed && report.manifold && report.regions == 1,
        "the decimated skin must stay one closed manifold surface: {report:?}"
    );
    assert!(
        skin.mesh.volume() > 1.0e6,
        "skin volume {}",
        skin.mesh.volume()
    );
    let volume = atlas_volume().unwrap();
    // Every label present in the atlas that the table names is a model, once, but the brain's
    // mantle; the one the table does not name (label 1, a single voxel) is not.
    let named = table_values().unwrap();
    let kept = |s: &crate::io::volume::Structure| {
        named.contains(&s.value) && !groups::LEFT_OUT.contains(&groups::group_of(s.value, &s.name))
    };
    let expected: Vec<usize> = (0..volume.structures.len())
        .filter(|&i| kept(&volume.structures[i]))
        .collect();
    assert!(expected.len() > 200, "{} structures kept", expected.len());
    assert!(
        volume.structures.iter().any(|s| !named.contains(&s.value)),
        "label 1 is unnamed"
    );
    let mut indices: Vec<usize> = models[1..].iter().map(|m| m.index).collect();
    indices.sort_unstable();
    assert_eq!(indices, expected);
    for m in &models[1..] {
        let label = &volume.structures[m.index];
        assert_eq!(m.name, crate::io::structure_name(&label.name));
        assert_eq!(
            m.color,
            Some(label.color.map(|c| c as f32 / 255.0)),
            "{}",
            m.name
        );
        assert_eq!(m.group, groups::group_of(label.value, &label.name));
        assert!(!m.mesh.triangles.is_empty(), "{} has no surface", m.name);
    }
    // The table's names and colours, not "label 17".
    let hippocampus = models
        .iter()
        .find(|m| m.name == "left hippocampus")
        .expect("left hippocampus");
    assert_eq!(hippocampus.group, "limbic system");
    assert_eq!(
        hippocampus.color,
        Some([220.0 / 255.0, 215.0 / 255.0, 20.0 / 255.0])
    );
    assert!(models.iter().all(|m| !m.name.starts_with("label ")));
}

#[test]
fn the_list_runs_group_by_group_deep_structures_first() {
    let models = &scene()[1..];
    let ranks: Vec<usize> = models.iter().map(|m| groups::rank(&m.group)).collect();
    assert!(ranks.windows(2).all(|w| w[0] <= w[1]), "groups interleave");
    assert_eq!(models[0].group, "ventricles");
    for left_out in groups::LEFT_OUT {
        assert!(
            !models.iter().any(|m| m.group == *left_out),
            "{left_out} is in"
        );
    }
    for group in [
        "basal ganglia",
        "brainstem",
        "eyes and optic pathway",
        "muscles",
    ] {
        assert!(
            models.iter().any(|m| m.group == group),
            "no structure in {group}"
        );
    }
}

#[test]
fn the_deep_structures_lie_inside_the_skin_and_every_surface_is_closed() {
    let models = scene();
    let head = models[0].mesh.bbox();
    for name in [
        "left lateral ventricle",
        "third ventricle",
        "left caudate nucleus",
        "right putamen",
        "right hippocampus",
        "pons",
        "left eyeball",
        "optic chiasm",
    ] {
        let m = models
            .iter()
            .find(|m| m.name == name)
            .unwrap_or_else(|| panic!("{name} is missing"));
        let b = m.mesh.bbox();
        assert!(
            head.contains(b.min) && head.contains(b.max),
            "{name} sticks out of the head"
        );
    }
    for m in &models[1..] {
        let report = m.mesh.report();
        assert!(report.closed && report.manifold, "{}: {report:?}", m.name);
        assert!(m.mesh.volume() > 0.0, "{} is inside out", m.name);
    }
}

#[test]
fn missing_paths_of_the_scene_are_served_from_the_binary() {
    let skin = load_missing(Path::new("/nonexistent/x/assets/spl_head/skin.ply"))
        .expect("embedded")
        .unwrap();
    assert_eq!(skin[0].name, "skin");
    assert!(load_missing(Path::new("/nonexistent/assets/spl_head/other.vtk")).is_none());
    assert!(load_missing(Path::new("/nonexistent/assets/knee/skin.ply")).is_none());
}

#[test]
fn a_missing_atlas_is_served_in_label_order_as_a_session_picks_it() {
    let atlas = load_missing(Path::new("/nonexistent/assets/spl_head/hncma-atlas.nrrd"))
        .expect("embedded")
        .unwrap();
    // Every label, the unnamed one included, at the position opening the file gives it, and
    // the default scene's models carry that position.
    assert!(atlas.iter().enumerate().all(|(i, m)| m.index == i));
    let volume = atlas_volume().unwrap();
    assert_eq!(atlas.len(), volume.structures.len());
    for m in &scene()[1..] {
        assert_eq!(atlas[m.index].name, m.name);
        assert_eq!(
            atlas[m.index].mesh.triangle_count(),
            m.mesh.triangle_count()
        );
    }
}

#[test]
fn a_cancelled_surfacing_ends_with_an_error_and_no_models() {
    let err = load_structures(&|_| false).unwrap_err();
    assert!(format!("{err:#}").contains("cancelled"), "{err:#}");
}
