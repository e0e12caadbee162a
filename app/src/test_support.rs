//! Scaffolding the app's unit tests share, so each test reads as what it checks: small scenes
//! with box cutters, a headless renderer (or the printed reason the test is skipped), a scene of
//! one sphere in view, frames drawn the same on every machine, and the figures the timing tests
//! print.
//!
//! Compiled for tests only. Integration tests under `tests/` have their own scaffolding (they
//! see only the public API).

use std::sync::Arc;

use csg::Mesh;
pub use csg::testkit::cube;
use glam::DVec3;

use crate::render::{FrameInputs, HeadlessRenderer, ViewMode};
use crate::scene::{CutterViews, Scene, SceneCutter, SceneModel};

/// A headless renderer, or `None` after [`csg::testkit::skip`] (no adapter: the test is skipped,
/// or fails where `CUTAWAY_REQUIRE_GPU=1`).
pub fn renderer_or_skip() -> Option<HeadlessRenderer> {
    match HeadlessRenderer::new() {
        Ok(renderer) => Some(renderer),
        Err(e) => {
            csg::testkit::skip(csg::testkit::Resource::Gpu, e);
            None
        }
    }
}

/// Two renderers, each with uploads of its own (the way measured and the way before it), or
/// `None` after printing why the test is skipped.
pub fn two_renderers_or_skip() -> Option<(HeadlessRenderer, HeadlessRenderer)> {
    let first = renderer_or_skip()?;
    let second = renderer_or_skip()?;
    Some((first, second))
}

/// `scene` with one more model, `sphere` (read from `file`, skin-coloured), and the camera
/// framing the scene.
pub fn with_sphere(mut scene: Scene, sphere: Arc<Mesh>, file: &str) -> Scene {
    scene
        .models
        .push(SceneModel::new("sphere", file, sphere, [0.9, 0.7, 0.6]));
    scene.camera = scene.framing_camera();
    scene
}

/// A scene of unit icospheres named `names` (file `x.obj`, grey), in that order: for tests of
/// what names a user may give.
pub fn named_spheres(names: &[&str]) -> Scene {
    let mut scene = Scene::default();
    for name in names {
        scene.models.push(SceneModel::new(
            *name,
            "x.obj",
            Arc::new(csg::testkit::icosphere(1, 1.0)),
            [0.5; 3],
        ));
    }
    scene
}

/// The frame of `scene` at `size` pixels in `mode`, drawn without supersampling so that two
/// renders compare pixel for pixel.
pub fn deterministic_frame(scene: &Scene, size: [u32; 2], mode: ViewMode) -> FrameInputs {
    let mut frame = crate::view::frame::frame_of(scene, size, mode);
    frame.deterministic = true;
    frame
}

/// A straight two-plane cutter spanning x in [x0, x1], y in [y0, y1] (front at y0), z in
/// [z0, z1].
pub fn box_cutter(
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
    z0: f64,
    z1: f64,
) -> Vec<cutter::BoundedPlane> {
    let plane = |x: f64| {
        cutter::BoundedPlane::from_corners([
            DVec3::new(x, y0, z1),
            DVec3::new(x, y1, z1),
            DVec3::new(x, y1, z0),
            DVec3::new(x, y0, z0),
        ])
    };
    vec![plane(x0), plane((x0 + x1) * 0.5), plane(x1)]
}

/// A cube of side 2 at the origin with one straight box cutter through its corner, seen with
/// `views`.
pub fn scene_with_cube_cut(views: crate::scene::CutterViews) -> Scene {
    let mut scene = Scene::default();
    scene.models.push(crate::scene::SceneModel::new(
        "cube",
        "cube.obj",
        std::sync::Arc::new(cube(DVec3::ZERO, DVec3::splat(2.0))),
        [0.8, 0.6, 0.5],
    ));
    scene.cutters.push(SceneCutter {
        views,
        ..plain_cutter(
            0,
            cutter::CutKind::Straight,
            box_cutter(1.0, 3.0, -1.0, 1.0, 1.0, 3.0),
        )
    });
    scene
}

/// A cutter of `kind` on model `target` through `planes`: not smooth, the default subdivision
/// levels, the Normal Cut view.
pub fn plain_cutter(
    target: usize,
    kind: cutter::CutKind,
    planes: Vec<cutter::BoundedPlane>,
) -> SceneCutter {
    SceneCutter {
        target,
        cutter: cutter::Cutter {
            kind,
            smooth: false,
            levels: cutter::subdivision::DEFAULT_LEVELS,
            direction: cutter::CutDirection::Normal,
            planes,
        },
        views: CutterViews::default(),
    }
}

/// `n` cubes of side 2 spaced 10 apart along x, each cut at its corner by `per_model` box
/// cutters (Normal Cut view), the cutters of one model slightly apart.
pub fn cubes_each_cut(n: usize, per_model: usize) -> Scene {
    let mut scene = Scene::default();
    for m in 0..n {
        let x = 10.0 * m as f64;
        scene.models.push(crate::scene::SceneModel::new(
            format!("cube {m}"),
            format!("cube{m}.obj"),
            Arc::new(cube(DVec3::new(x, 0.0, 0.0), DVec3::new(x + 2.0, 2.0, 2.0))),
            [0.8, 0.6, 0.5],
        ));
        for k in 0..per_model {
            let z = 1.0 - 0.5 * k as f64;
            scene.cutters.push(plain_cutter(
                m,
                cutter::CutKind::Straight,
                box_cutter(x + 1.0 + 0.2 * k as f64, x + 3.0, -1.0, 1.0, z, 3.0),
            ));
        }
    }
    scene
}

/// Pixels that differ between two images of the same size.
pub fn differing_pixels(a: &image::RgbaImage, b: &image::RgbaImage) -> usize {
    assert_eq!(a.dimensions(), b.dimensions());
    a.pixels().zip(b.pixels()).filter(|(p, q)| p != q).count()
}

/// Median and maximum of `v` (not empty).
pub fn median_max(v: &[f64]) -> (f64, f64) {
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    (s[s.len() / 2], s[s.len() - 1])
}

/// `median M (max X)` of `v`, as the timing tests print their figures.
pub fn median_and_max(v: &[f64]) -> String {
    let (median, max) = median_max(v);
    format!("median {median:.2} (max {max:.2})")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_median_of_an_odd_and_an_even_count_and_the_max() {
        assert_eq!(median_max(&[3.0, 1.0, 2.0]), (2.0, 3.0));
        assert_eq!(median_max(&[4.0, 1.0, 3.0, 2.0]), (3.0, 4.0));
        assert_eq!(median_and_max(&[1.0, 5.0, 2.0]), "median 2.00 (max 5.00)");
    }

    #[test]
    fn differing_pixels_counts_only_the_changed_ones() {
        let a = image::RgbaImage::from_pixel(4, 3, image::Rgba([1, 2, 3, 255]));
        let mut b = a.clone();
        b.put_pixel(0, 0, image::Rgba([0, 2, 3, 255]));
        b.put_pixel(3, 2, image::Rgba([1, 2, 3, 0]));
        assert_eq!(differing_pixels(&a, &a), 0);
        assert_eq!(differing_pixels(&a, &b), 2);
    }
}
