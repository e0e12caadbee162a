//! A structure's disconnected pieces as models of their own, when the user asks for them.
//!
//! A structure file opens as one model however many pieces it has (a hippocampus exported with
//! a stray island, twelve phalanges in one file), so the model list names structures, not
//! fragments. The user may still want one piece alone (hide it, cut it, colour it): splitting
//! the model turns each connected region into a model, listed in a sub-group named after the
//! structure (a folder of the list that opens like any other), in the structure's place.
//!
//! The pieces are new geometry as far as sessions go ([`crate::scene::MeshOrigin::Edited`]):
//! saving writes each one to a file of its own, so the session reopens exactly what was split.
//! A model a cutter of any variant aims at is not split (the cutter would have to choose a
//! piece); the caller says so instead.

use std::sync::Arc;

use crate::scene::Scene;

/// Why a model was not split.
#[derive(Debug, PartialEq, Eq)]
pub enum SplitRefused {
    /// No model at that index.
    NoModel,
    /// The model is one connected region already.
    OneRegion,
    /// A cutter (of this or another variant) cuts the model.
    Cut,
}

impl std::fmt::Display for SplitRefused {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            SplitRefused::NoModel => "no such model",
            SplitRefused::OneRegion => "it is one connected region",
            SplitRefused::Cut => "a cutter cuts it (remove its cutters first)",
        })
    }
}

/// Splits model `index` of `scene` into one model per connected region: the largest region
/// stays at `index`, the others are appended; all are named `"<name> <k>"` (k from 1, largest
/// first), keep the model's colour, opacity, style and visibility, and sit in the sub-group
/// `<group>/<name>`. Returns how many models the structure became.
pub fn split_into_regions(scene: &mut Scene, index: usize) -> Result<usize, SplitRefused> {
    let model = scene.models.get(index).ok_or(SplitRefused::NoModel)?;
    let cut = crate::scene::variants::all(scene)
        .iter()
        .any(|(_, cutters)| cutters.iter().any(|c| c.target == index));
    if cut {
        return Err(SplitRefused::Cut);
    }
    let mut pieces = csg::regions::split_regions(&model.model.mesh);
    if pieces.len() < 2 {
        return Err(SplitRefused::OneRegion);
    }
    // Largest first, so "1" is the structure's main body.
    pieces.sort_by_key(|p| std::cmp::Reverse(p.triangle_count()));
    let folder = model.model.name.replace('/', "-");
    let group = if model.model.group.is_empty() {
        folder
    } else {
        format!("{}/{folder}", model.model.group)
    };
    let template = model.clone();
    let count = pieces.len();
    for (k, piece) in pieces.into_iter().enumerate() {
        let mut part = template.clone();
        part.model.name = format!("{} {}", template.model.name, k + 1);
        part.model.group = group.clone();
        // A structure of its own, so a session keeps its name and group whatever the model was.
        part.unit = crate::scene::ModelUnit::Structure;
        part.replace_mesh(Arc::new(piece));
        if k == 0 {
            scene.models[index] = part;
        } else {
            scene.models.push(part);
        }
    }
    Ok(count)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{MeshOrigin, SceneModel};

    fn sphere(x: f64, subdivisions: u32) -> csg::Mesh {
        let mut m = csg::testkit::icosphere(subdivisions, 5.0);
        for p in &mut m.positions {
            p.x += x;
        }
        m
    }

    fn scene() -> Scene {
        let mut two = sphere(0.0, 1);
        two.append(&sphere(30.0, 2));
        let mut scene = Scene::default();
        let mut hippo =
            SceneModel::new("left hippocampus", "a.vtk", Arc::new(two), [0.9, 0.8, 0.1]);
        hippo.model.group = "atlas".into();
        hippo.opacity = 0.5;
        scene.models.push(hippo);
        scene.models.push(SceneModel::new(
            "pons",
            "b.vtk",
            Arc::new(sphere(60.0, 1)),
            [0.2, 0.3, 0.4],
        ));
        scene
    }

    #[test]
    fn each_region_becomes_a_model_in_a_sub_group_named_after_the_structure() {
        let mut scene = scene();
        let before = scene.models[0].model.mesh.triangle_count();
        assert_eq!(split_into_regions(&mut scene, 0), Ok(2));
        let names: Vec<(&str, &str)> = scene
            .models
            .iter()
            .map(|m| (m.model.name.as_str(), m.model.group.as_str()))
            .collect();
        assert_eq!(
            names,
            [
                ("left hippocampus 1", "atlas/left hippocampus"),
                ("pons", ""),
                ("left hippocampus 2", "atlas/left hippocampus"),
            ]
        );
        // The larger sphere (more subdivisions) is piece 1; together they are the whole.
        let (a, b) = (&scene.models[0], &scene.models[2]);
        assert!(a.model.mesh.triangle_count() > b.model.mesh.triangle_count());
        assert_eq!(
            a.model.mesh.triangle_count() + b.model.mesh.triangle_count(),
            before
        );
        assert!(
            a.model.mesh.bbox().min.x > 20.0,
            "piece 1 is the sphere at x = 30"
        );
        for m in [a, b] {
            assert_eq!(m.color, [0.9, 0.8, 0.1]);
            assert_eq!(m.opacity, 0.5);
            assert_eq!(m.origin, MeshOrigin::Edited, "saved as meshes of their own");
        }
    }

    #[test]
    fn a_session_saved_after_a_split_reopens_the_pieces() {
        let dir = std::env::temp_dir().join(format!("cutaway-split-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let mut scene = scene();
        // The test's models are regions of files (as a `cutaway-session/1` file gives them); the
        // pons names no real file, so it is saved as a mesh of its own too.
        scene.models[1].origin = MeshOrigin::Edited;
        split_into_regions(&mut scene, 0).unwrap();
        let path = dir.join("split.json");
        crate::session::save(&path, &scene).unwrap();
        let reopened = crate::session::load(&path).unwrap();
        let summary = |s: &Scene| -> Vec<(String, String, usize)> {
            s.models
                .iter()
                .map(|m| {
                    (
                        m.model.name.clone(),
                        m.model.group.clone(),
                        m.model.mesh.triangle_count(),
                    )
                })
                .collect()
        };
        assert_eq!(summary(&reopened), summary(&scene));
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn one_region_and_cut_models_are_refused() {
        let mut scene = scene();
        assert_eq!(
            split_into_regions(&mut scene, 1),
            Err(SplitRefused::OneRegion)
        );
        assert_eq!(
            split_into_regions(&mut scene, 7),
            Err(SplitRefused::NoModel)
        );
        let plane = cutter::BoundedPlane::from_corners([
            glam::DVec3::ZERO,
            glam::DVec3::X,
            glam::DVec3::Y,
            glam::DVec3::Z,
        ]);
        scene.cutters.push(crate::scene::SceneCutter::new(
            0,
            cutter::Cutter {
                kind: cutter::CutKind::Curving,
                smooth: false,
                levels: cutter::subdivision::DEFAULT_LEVELS,
                direction: cutter::CutDirection::Normal,
                planes: vec![plane],
            },
        ));
        assert_eq!(split_into_regions(&mut scene, 0), Err(SplitRefused::Cut));
        assert_eq!(scene.models.len(), 2, "nothing changed");
    }
}
