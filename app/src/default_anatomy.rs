//! The default scene: **real anatomy** from the SPL-PNL head/brain atlas (3D Slicer licence;
//! provenance and attribution in `assets/README.md`), compiled into the binary so that `cutaway`
//! opens on a head to cut into, face forward, with the deep structures (ventricles, basal ganglia,
//! hippocampus and amygdala, brainstem, eyes and optic nerves) inside.
//!
//! The structures are the atlas's own model files, embedded byte for byte (legacy VTK) and read
//! by the same reader as any file the user opens; the skin is the atlas's skin label surface,
//! decimated once offline (`assets/spl_head/decimate_skin.py`) to keep the binary small. The
//! atlas is in RAS millimetres, so its front (anterior) is +Y: [`FRONT`] says where the camera
//! looks from.

use std::path::{Path, PathBuf};

use anyhow::Context as _;
use glam::DVec3;

use crate::io::{Format, Model};

/// The folder under `assets/` (and in the models' virtual paths).
pub const FOLDER: &str = "spl_head";

/// Menu name of the scene.
pub const NAME: &str = "head atlas";

/// Direction from the head toward a viewer who faces it (RAS: anterior is +Y).
pub const FRONT: DVec3 = DVec3::Y;

/// `(file name, group in the model list, bytes)` of `assets/spl_head/<file>`.
macro_rules! file {
    ($file:literal, $group:literal) => {
        (
            $file,
            $group,
            include_bytes!(concat!("../../assets/spl_head/", $file)) as &[u8],
        )
    };
}

/// The scene's files in list order, outer structure first.
static FILES: &[(&str, &str, &[u8])] = &[
    file!("skin.ply", ""),
    file!("Model_4_left_lateral_ventricle.vtk", "ventricles"),
    file!("Model_43_right_lateral_ventricle.vtk", "ventricles"),
    file!(
        "Model_5_temporal_horn_of_left_lateral_ventricle.vtk",
        "ventricles"
    ),
    file!(
        "Model_44_temporal_horn_of_right_lateral_ventricle.vtk",
        "ventricles"
    ),
    file!("Model_24_third_ventricle.vtk", "ventricles"),
    file!("Model_15_fourth_ventricle.vtk", "ventricles"),
    file!("Model_11_left_caudate_nucleus.vtk", "basal ganglia"),
    file!("Model_50_right_caudate_nucleus.vtk", "basal ganglia"),
    file!("Model_12_left_putamen.vtk", "basal ganglia"),
    file!("Model_51_right_putamen.vtk", "basal ganglia"),
    file!("Model_17_left_hippocampus.vtk", "limbic"),
    file!("Model_53_right_hippocampus.vtk", "limbic"),
    file!("Model_18_left_amygdala.vtk", "limbic"),
    file!("Model_54_right_amygdala.vtk", "limbic"),
    file!("Model_40_part_of_midbrain.vtk", "brainstem"),
    file!("Model_35_pons.vtk", "brainstem"),
    file!("Model_61_medulla_oblongata.vtk", "brainstem"),
    file!("Model_4027_left_eyeball.vtk", "eyes and optic nerves"),
    file!("Model_4028_right_eyeball.vtk", "eyes and optic nerves"),
    file!("Model_77_left_optic_nerve.vtk", "eyes and optic nerves"),
    file!("Model_215_right_optic_nerve.vtk", "eyes and optic nerves"),
    file!("Model_85_optic_chiasm.vtk", "eyes and optic nerves"),
];

/// The virtual path of an embedded file, as if loaded from the repository's `assets/` folder.
pub fn virtual_path(file: &str) -> PathBuf {
    PathBuf::from(format!("assets/{FOLDER}/{file}"))
}

/// Every structure of the scene, one [`Model`] per file, named from the file name
/// (`left hippocampus`), grouped as the list shows them, with no colour of its own (the anatomy
/// colour table gives it). Files are parsed in parallel.
pub fn load() -> anyhow::Result<Vec<Model>> {
    use rayon::prelude::*;
    let per_file: Vec<Vec<Model>> = FILES
        .par_iter()
        .map(|&(file, group, bytes)| parse(file, group, bytes))
        .collect::<anyhow::Result<_>>()?;
    Ok(per_file.into_iter().flatten().collect())
}

fn parse(file: &str, group: &str, bytes: &[u8]) -> anyhow::Result<Vec<Model>> {
    let path = virtual_path(file);
    let format = Format::from_path(&path)
        .ok_or_else(|| anyhow::anyhow!("{}: not a mesh file name", path.display()))?;
    let parts = crate::io::parse_bytes(format, bytes, &crate::io::file_stem(&path))
        .with_context(|| path.display().to_string())?;
    Ok(crate::io::structures_of_parts(&path, parts, group))
}

/// The embedded file a path names when the path does not exist on disk and ends in
/// `assets/spl_head/<file>` (as sessions saved from the default scene do): its structures.
/// `None` for any other path.
pub fn load_missing(path: &Path) -> Option<anyhow::Result<Vec<Model>>> {
    if path.exists() {
        return None;
    }
    let components: Vec<&str> = path.iter().filter_map(|c| c.to_str()).collect();
    let [.., assets, folder, file] = components.as_slice() else {
        return None;
    };
    if *assets != "assets" || *folder != FOLDER {
        return None;
    }
    let &(file, _, bytes) = FILES.iter().find(|(name, _, _)| name == file)?;
    // A session names the file, not the list's group: the group comes back with the entry.
    Some(parse(file, "", bytes))
}

/// True when every model comes from this scene (its virtual paths or the source tree's copies).
pub fn is_default_scene(models: &[Model]) -> bool {
    !models.is_empty()
        && models.iter().all(|m| {
            let mut parts = m.source.iter().rev().skip(1);
            parts.next().is_some_and(|f| f == FOLDER) && parts.next().is_some_and(|a| a == "assets")
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_scene_loads_named_and_grouped_with_a_closed_skin() {
        let models = load().unwrap();
        assert_eq!(models.len(), FILES.len());
        assert!(is_default_scene(&models));
        let skin = &models[0];
        assert_eq!((skin.name.as_str(), skin.group.as_str()), ("skin", ""));
        let report = skin.mesh.sanity_check();
        assert!(report.is_ok(), "{report:?}");
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
        let hippocampus = models
            .iter()
            .find(|m| m.name == "left hippocampus")
            .expect("left hippocampus");
        assert_eq!(hippocampus.group, "limbic");
        // Every deep structure lies inside the head.
        let head = skin.mesh.bbox();
        for m in &models[1..] {
            let b = m.mesh.bbox();
            assert!(
                head.contains(b.min) && head.contains(b.max),
                "{} sticks out of the head",
                m.name
            );
        }
    }

    #[test]
    fn missing_paths_of_the_scene_are_served_from_the_binary() {
        let missing = Path::new("/nonexistent/x/assets/spl_head/Model_35_pons.vtk");
        let models = load_missing(missing).expect("embedded").unwrap();
        assert_eq!(models[0].name, "pons");
        assert!(load_missing(Path::new("/nonexistent/assets/spl_head/other.vtk")).is_none());
        assert!(load_missing(Path::new("/nonexistent/assets/knee/skin.ply")).is_none());
    }
}
