//! Is the pointer over a wall that shows the image? The window/level drag (Shift + right drag)
//! adjusts the window only when it starts on such a wall, as in a radiology viewer where the
//! drag is on the picture; anywhere else the drag keeps its navigation meaning.
//!
//! The answer is the first surface a ray meets among what the cut scene draws: kept parts and
//! uncut models hide what is behind them, a see-through removed piece does not, and the
//! surface hit must be a wall (with the image on walls) or a slice/ribbon surface (with the
//! image on slices). One ray per drag start, so every triangle is tested directly (with a box
//! test per mesh first) instead of building a tree for meshes that change with every cut.

use glam::DVec3;

use crate::cutting::cut_scene::{PartKind, PreviewGeometry};
use crate::scene::Scene;

/// True when `ray`'s first hit in the cut scene (`geometry`, the preview of `scene`) is a surface
/// that shows `scene`'s image. False without an image or a preview.
pub fn image_wall_under(
    scene: &Scene,
    geometry: Option<&PreviewGeometry>,
    ray: &cutter::Ray,
) -> bool {
    let (Some(layer), Some(geometry)) = (scene.image.as_ref(), geometry) else {
        return false;
    };
    if layer.display.image_weight() <= 0.0 {
        return false;
    }
    let visible = |model: usize| {
        scene
            .models
            .get(model)
            .is_some_and(|m| m.visible && m.opacity > 0.0)
    };
    // (ray parameter, shows the image) of the nearest opaque hit so far.
    let mut best: Option<(f64, bool)> = None;
    let mut consider = |mesh: &csg::Mesh, shows: bool| {
        let limit = best.map_or(f64::INFINITY, |(t, _)| t);
        if let Some(t) = first_hit(mesh, ray, limit) {
            best = Some((t, shows));
        }
    };
    for (i, model) in scene.models.iter().enumerate() {
        let replaced = geometry.replaced.get(i).copied().unwrap_or(false);
        if !replaced && visible(i) && model.opacity >= 1.0 {
            consider(&model.model.mesh, false);
        }
    }
    for part in &geometry.parts {
        if !visible(part.model) {
            continue;
        }
        let shows = match part.kind {
            PartKind::Wall => layer.on_walls,
            PartKind::SliceWall | PartKind::Ribbon => layer.on_slices,
            PartKind::Kept => false,
            // See-through: the wall behind it is what the user points at.
            PartKind::Removed if part.opacity < 1.0 => continue,
            PartKind::Removed => false,
        };
        if part.kind == PartKind::Kept && scene.models[part.model].opacity < 1.0 {
            continue;
        }
        consider(&part.mesh, shows);
    }
    best.is_some_and(|(_, shows)| shows)
}

/// The smallest ray parameter in `(0, limit)` at which `ray` meets a triangle of `mesh`
/// (both sides), if any.
fn first_hit(mesh: &csg::Mesh, ray: &cutter::Ray, limit: f64) -> Option<f64> {
    if mesh.triangles.is_empty() || !ray_meets_box(mesh.bbox(), ray, limit) {
        return None;
    }
    let mut best = limit;
    let mut hit = false;
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|v| mesh.positions[v as usize]);
        if let Some(s) = ray_triangle(ray.origin, ray.direction, a, b, c)
            && s > 0.0
            && s < best
        {
            best = s;
            hit = true;
        }
    }
    hit.then_some(best)
}

/// Slab test of the ray against a box, up to `limit`.
fn ray_meets_box(b: csg::Aabb, ray: &cutter::Ray, limit: f64) -> bool {
    if b.is_empty() {
        return false;
    }
    let (mut lo, mut hi) = (0.0f64, limit);
    for a in 0..3 {
        let (o, d) = (ray.origin[a], ray.direction[a]);
        let pad = 1e-9 * (b.max[a] - b.min[a]).abs().max(1.0);
        let (min, max) = (b.min[a] - pad, b.max[a] + pad);
        if d.abs() < 1e-300 {
            if o < min || o > max {
                return false;
            }
            continue;
        }
        let (t0, t1) = ((min - o) / d, (max - o) / d);
        lo = lo.max(t0.min(t1));
        hi = hi.min(t0.max(t1));
        if lo > hi {
            return false;
        }
    }
    true
}

/// Möller–Trumbore: the ray parameter of the hit with triangle (a, b, c), either side.
fn ray_triangle(origin: DVec3, dir: DVec3, a: DVec3, b: DVec3, c: DVec3) -> Option<f64> {
    let (e1, e2) = (b - a, c - a);
    let p = dir.cross(e2);
    let det = e1.dot(p);
    if det.abs() < 1e-14 * e1.length() * e2.length() {
        return None;
    }
    let inv = 1.0 / det;
    let s = origin - a;
    let u = s.dot(p) * inv;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = s.cross(e1);
    let v = dir.dot(q) * inv;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    Some(e2.dot(q) * inv)
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use glam::DVec3;

    use super::*;
    use crate::io::intensity::IntensityImage;
    use crate::scene::{CutterViews, SceneCutter, SceneModel};
    use crate::scene::{ImageLayer, WallDisplay};
    use crate::test_support::{box_cutter, cube};
    use cutter::CutKind;

    /// The cube [0, 10]³ cut by a box x, z in 2..8 from the front to y = 5, with an image.
    fn scene() -> Scene {
        let mut scene = Scene::default();
        scene.models.push(SceneModel::new(
            "cube",
            "cube.obj",
            Arc::new(cube(DVec3::ZERO, DVec3::splat(10.0))),
            [0.8, 0.3, 0.3],
        ));
        scene.cutters.push(SceneCutter {
            target: 0,
            cutter: cutter::Cutter {
                kind: CutKind::Straight,
                smooth: false,
                levels: cutter::subdivision::DEFAULT_LEVELS,
                direction: cutter::CutDirection::Normal,
                planes: box_cutter(2.0, 8.0, -5.0, 5.0, 2.0, 8.0),
            },
            views: CutterViews::default(),
        });
        let image = IntensityImage::from_fn([11, 11, 11], glam::DAffine3::IDENTITY, |p| p.x as f32);
        scene.image = Some(ImageLayer::new(Arc::new(image)));
        scene
    }

    fn ray_at(x: f64, z: f64) -> cutter::Ray {
        cutter::Ray {
            origin: DVec3::new(x, -30.0, z),
            direction: DVec3::Y,
        }
    }

    #[test]
    fn only_rays_that_first_meet_an_image_wall_count() {
        let mut scene = scene();
        let geometry = crate::cutting::cut_scene::preview_geometry(&scene);
        assert!(geometry.notes.is_empty(), "{:?}", geometry.notes);
        // Through the opening onto the back wall at y = 5.
        assert!(image_wall_under(&scene, Some(&geometry), &ray_at(5.0, 5.0)));
        // On the cube's front face beside the opening, past the cube, or without a preview.
        assert!(!image_wall_under(
            &scene,
            Some(&geometry),
            &ray_at(1.0, 5.0)
        ));
        assert!(!image_wall_under(
            &scene,
            Some(&geometry),
            &ray_at(50.0, 5.0)
        ));
        assert!(!image_wall_under(&scene, None, &ray_at(5.0, 5.0)));
        // Walls without the image (colour display, or walls unticked) do not take the drag.
        scene.image.as_mut().unwrap().display = WallDisplay::Color;
        assert!(!image_wall_under(
            &scene,
            Some(&geometry),
            &ray_at(5.0, 5.0)
        ));
        scene.image.as_mut().unwrap().display = WallDisplay::Blend;
        scene.image.as_mut().unwrap().on_walls = false;
        assert!(!image_wall_under(
            &scene,
            Some(&geometry),
            &ray_at(5.0, 5.0)
        ));
        scene.image.as_mut().unwrap().on_walls = true;
        // A hidden model's walls are not under the pointer; no image, no wall.
        scene.models[0].visible = false;
        assert!(!image_wall_under(
            &scene,
            Some(&geometry),
            &ray_at(5.0, 5.0)
        ));
        scene.models[0].visible = true;
        scene.image = None;
        assert!(!image_wall_under(
            &scene,
            Some(&geometry),
            &ray_at(5.0, 5.0)
        ));
    }

    #[test]
    fn ray_triangle_hits_inside_and_misses_outside() {
        let (a, b, c) = (DVec3::ZERO, DVec3::X, DVec3::Y);
        let down = DVec3::new(0.0, 0.0, -1.0);
        let t = ray_triangle(DVec3::new(0.2, 0.2, 3.0), down, a, b, c);
        assert!((t.unwrap() - 3.0).abs() < 1e-12);
        assert!(ray_triangle(DVec3::new(0.8, 0.8, 3.0), down, a, b, c).is_none());
    }
}
