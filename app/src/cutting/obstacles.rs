//! What lies behind a cutter's target: the scene's other visible structures, with their names
//! and ray-pick trees, as the `cutter` crate's [`cutter::reach::Obstacles`]. A new cutter's
//! default depth reaches the nearest of them, and the status line and `cutaway extrude` name
//! what a cutter reaches. The window and the CLI build it here, the same way.

use std::sync::Arc;

use cutter::reach::{MeshObstacles, Obstacle};

use crate::cutting::pick::{ScenePicks, is_pickable};
use crate::scene::Scene;

/// Every pickable model of `scene` but `target` (visible, not fully transparent, not empty: what
/// a press can hit is what a cut should reach), indexed by its model index.
pub fn scene_obstacles(scene: &Scene, target: usize, picks: &mut ScenePicks) -> MeshObstacles {
    let structures = scene
        .models
        .iter()
        .enumerate()
        .filter(|&(i, m)| i != target && is_pickable(m))
        .map(|(i, m)| Obstacle {
            structure: i,
            name: m.model.name.clone(),
            mesh: m.model.mesh.clone(),
            tree: picks.tree(&m.model.mesh),
        })
        .collect();
    MeshObstacles { structures }
}

/// [`scene_obstacles`] as the editor takes it.
pub fn shared_obstacles(
    scene: &Scene,
    target: usize,
    picks: &mut ScenePicks,
) -> Arc<dyn cutter::reach::Obstacles> {
    Arc::new(scene_obstacles(scene, target, picks))
}

/// "42 mm: reaches left lateral ventricle, left caudate nucleus": a cutter's depth in mm and the
/// structures it reaches (at most three named, then how many more), for the status line.
pub fn depth_line(depth_mm: f64, reached: &[String]) -> String {
    let depth = if depth_mm >= 10.0 {
        format!("{depth_mm:.0} mm")
    } else {
        format!("{depth_mm:.1} mm")
    };
    match reached {
        [] => format!("{depth}: reaches no other structure"),
        names if names.len() <= 3 => format!("{depth}: reaches {}", names.join(", ")),
        names => format!(
            "{depth}: reaches {} and {} more",
            names[..3].join(", "),
            names.len() - 3
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::SceneModel;
    use cutter::reach::Obstacles;
    use glam::DVec3;

    #[test]
    fn other_visible_structures_are_what_lies_behind() {
        let cube = |y: f64| {
            Arc::new(csg::testkit::cube(
                DVec3::new(-1.0, y, -1.0),
                DVec3::new(1.0, y + 2.0, 1.0),
            ))
        };
        let mut scene = Scene::default();
        for (name, y) in [("skin", 0.0), ("hidden", 4.0), ("ventricle", 8.0)] {
            scene
                .models
                .push(SceneModel::new(name, "x.obj", cube(y), [1.0; 3]));
        }
        scene.models[1].visible = false;
        let mut picks = ScenePicks::default();
        let obstacles = scene_obstacles(&scene, 0, &mut picks);
        let hits = obstacles.hits(DVec3::new(0.0, -5.0, 0.0), DVec3::Y, 100.0);
        assert_eq!(hits.len(), 1, "{hits:?}");
        assert_eq!(hits[0].structure, 2);
        assert!((hits[0].t - 13.0).abs() < 1e-9);
        assert_eq!(obstacles.name(2), "ventricle");
        assert_eq!(
            depth_line(42.4, &["left lateral ventricle".to_string()]),
            "42 mm: reaches left lateral ventricle"
        );
        assert_eq!(depth_line(4.3, &[]), "4.3 mm: reaches no other structure");
        let many: Vec<String> = (1..=5).map(|k| format!("s{k}")).collect();
        assert_eq!(
            depth_line(12.0, &many),
            "12 mm: reaches s1, s2, s3 and 2 more"
        );
    }
}
