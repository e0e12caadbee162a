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
    // Every label of the selection is in the atlas and named by its table, and is a model, once.
    let named = table_values().unwrap();
    for value in selection::default_labels() {
        assert!(
            named.contains(&value),
            "the table does not name label {value}"
        );
        assert!(
            volume.structures.iter().any(|s| s.value == value),
            "the atlas has no label {value}"
        );
    }
    let expected: Vec<usize> = (0..volume.structures.len())
        .filter(|&i| selection::in_default(volume.structures[i].value))
        .collect();
    assert_eq!(expected.len(), selection::default_labels().count());
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
    // The mantle and the muscles around the deep structures stay out of the default.
    for left_out in ["cerebral cortex", "white matter", "sulci", "muscles"] {
        assert!(
            !models.iter().any(|m| m.group == left_out),
            "{left_out} is in"
        );
    }
    for group in [
        "basal ganglia",
        "limbic system",
        "thalamus and hypothalamus",
        "brainstem",
        "eyes and optic pathway",
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

/// The model files an earlier default embedded; sessions saved from it name them.
const OLD_MODEL_FILES: &[&str] = &[
    "Model_4_left_lateral_ventricle.vtk",
    "Model_43_right_lateral_ventricle.vtk",
    "Model_5_temporal_horn_of_left_lateral_ventricle.vtk",
    "Model_44_temporal_horn_of_right_lateral_ventricle.vtk",
    "Model_24_third_ventricle.vtk",
    "Model_15_fourth_ventricle.vtk",
    "Model_11_left_caudate_nucleus.vtk",
    "Model_50_right_caudate_nucleus.vtk",
    "Model_12_left_putamen.vtk",
    "Model_51_right_putamen.vtk",
    "Model_17_left_hippocampus.vtk",
    "Model_53_right_hippocampus.vtk",
    "Model_18_left_amygdala.vtk",
    "Model_54_right_amygdala.vtk",
    "Model_40_part_of_midbrain.vtk",
    "Model_35_pons.vtk",
    "Model_61_medulla_oblongata.vtk",
    "Model_4027_left_eyeball.vtk",
    "Model_4028_right_eyeball.vtk",
    "Model_77_left_optic_nerve.vtk",
    "Model_215_right_optic_nerve.vtk",
    "Model_85_optic_chiasm.vtk",
];

#[test]
fn the_default_is_light_and_holds_every_structure_of_the_earlier_default() {
    let models = scene();
    let triangles: usize = models.iter().map(|m| m.mesh.triangle_count()).sum();
    println!(
        "default scene: {} structures and the skin, {triangles} triangles",
        models.len() - 1
    );
    assert!(models.len() - 1 <= 64, "{} structures", models.len() - 1);
    assert!(triangles <= 400_000, "{triangles} triangles");
    for file in OLD_MODEL_FILES {
        let value = old_model_label(file).unwrap_or_else(|| panic!("{file}: no label"));
        assert!(selection::in_default(value), "{file} is not in the default");
        // The file's name is the table's name of its label.
        let name = file
            .trim_start_matches(&format!("Model_{value}_"))
            .trim_end_matches(".vtk")
            .replace('_', " ");
        assert!(
            models.iter().any(|m| m.name == name),
            "{name} is not in the default"
        );
    }
}

#[test]
fn a_missing_model_file_of_an_earlier_default_is_its_label_surface() {
    let missing = Path::new("/nonexistent/x/assets/spl_head/Model_35_pons.vtk");
    let pons = load_missing(missing).expect("embedded").unwrap();
    assert_eq!(pons.len(), 1);
    assert_eq!((pons[0].name.as_str(), pons[0].index), ("pons", 0));
    assert_eq!(pons[0].source, virtual_path("Model_35_pons.vtk"));
    let in_default = scene().iter().find(|m| m.name == "pons").unwrap();
    assert_eq!(
        pons[0].mesh.triangle_count(),
        in_default.mesh.triangle_count()
    );
    let report = pons[0].mesh.report();
    assert!(report.closed && report.manifold, "{report:?}");
    // A label the atlas lacks is an error naming the file; other names are not ours.
    let err = load_missing(Path::new("/nonexistent/assets/spl_head/Model_9_none.vtk"))
        .expect("a model file name")
        .unwrap_err();
    assert!(format!("{err:#}").contains("Model_9_none.vtk"), "{err:#}");
    assert_eq!(old_model_label("Model_4027_left_eyeball.vtk"), Some(4027));
    assert_eq!(old_model_label("Model_x_pons.vtk"), None);
    assert_eq!(old_model_label("Model_35_.vtk"), None);
    assert_eq!(old_model_label("Model_35_pons.ply"), None);
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

#[test]
fn the_atlas_with_all_structures_adds_the_mantle_and_the_muscles() {
    let all = load_all(&|_| true).unwrap();
    assert_eq!(all[0].name, "skin");
    let named = table_values().unwrap();
    let volume = atlas_volume().unwrap();
    let present_and_named = volume
        .structures
        .iter()
        .filter(|s| named.contains(&s.value))
        .count();
    assert_eq!(all.len() - 1, present_and_named);
    assert!(all.len() > 200, "{} structures", all.len());
    for name in ["left superior frontal gyrus", "tongue", "left masseter"] {
        assert!(all.iter().any(|m| m.name == name), "{name} is missing");
    }
    // The default's structures are the same surfaces at the same label positions.
    for m in &scene()[1..] {
        let same = all.iter().find(|a| a.index == m.index).expect("in all");
        assert_eq!(same.name, m.name);
    }
    let ranks: Vec<usize> = all[1..].iter().map(|m| groups::rank(&m.group)).collect();
    assert!(ranks.windows(2).all(|w| w[0] <= w[1]), "groups interleave");
}

#[test]
fn a_session_of_the_default_scene_surfaces_only_the_structures_it_picks() {
    let atlas_path = Path::new("/nonexistent/assets/spl_head/hncma-atlas.nrrd");
    let atlas = load_missing(atlas_path).expect("embedded").unwrap();
    let dir = std::env::temp_dir().join(format!("cutaway-atlas-picks-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let session = |picks: &[usize]| {
        let models: Vec<String> = picks
            .iter()
            .map(|k| format!(r#"{{"path": "assets/spl_head/{ATLAS_FILE}", "structure": {k}}}"#))
            .collect();
        let path = dir.join("picks.cutaway.json");
        std::fs::write(
            &path,
            format!(
                r#"{{"format": "cutaway-session/2", "models": [{}], "cutters": []}}"#,
                models.join(", ")
            ),
        )
        .unwrap();
        path
    };
    let surfaced = |path: &Path| {
        let mut surfaced = 0;
        let scene = crate::session::load_with(path, |file, unit, only| {
            let models = crate::anatomy::assets::load_or_embedded_picking(file, unit, only)?;
            surfaced += models.len();
            Ok(models)
        });
        (scene, surfaced)
    };
    // Two picks: two labels surfaced, the same meshes and names as from the whole atlas.
    let (scene, count) = surfaced(&session(&[40, 3]));
    let scene = scene.unwrap();
    assert_eq!(count, 2);
    assert_eq!(scene.models.len(), 2);
    for (model, k) in scene.models.iter().zip([40, 3]) {
        assert_eq!(model.model.index, k);
        assert_eq!(model.model.name, atlas[k].name);
        assert_eq!(model.model.mesh, atlas[k].mesh);
    }
    // The session's own reader gives the same scene.
    let read = crate::session::load(&session(&[40, 3])).unwrap();
    assert_eq!(read.models[0].model.mesh, atlas[40].mesh);
    // A pick the atlas does not have: every label is read, and the error says how many there are.
    let (scene, count) = surfaced(&session(&[3, atlas.len()]));
    assert_eq!(count, atlas.len());
    let err = format!("{:#}", scene.unwrap_err());
    assert!(
        err.contains(&format!("it has {} structures", atlas.len())),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
