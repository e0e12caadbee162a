//! End-to-end tests of everything that renders headless: the renderer, sessions and `cutaway
//! render` (goldens, exports, sessions), the image on the walls, wedges on the knee, labelled
//! images and turntables (`annotate.rs`), and variant comparison (`compare.rs`).
//!
//! Golden images: full size (1280×800, the window's default 3D view), deterministic mode (no
//! supersampling), rendered on the software adapter with `WGPU_BACKEND=vulkan` (lavapipe; Vulkan
//! is used when the variable is unset). `UPDATE_GOLDEN=1 cargo test --test render` rewrites
//! `tests/golden/*.png`. The tolerances, and the noise they were set from, live in
//! `tests/support/image_compare.rs` only. On a machine with no adapter the GPU tests print "skipped: <why>" and
//! pass, or fail where `CUTAWAY_REQUIRE_GPU=1` (CI); on a hardware GPU the pictures are checked
//! for content but not compared (rasterizers differ). This file holds the scenes and helpers; the tests are in
//! `render/`, one file per concern.

use csg::testkit::{Resource, skip};
use std::path::{Path, PathBuf};
use std::sync::Arc;

use csg::Mesh;
use cutaway::render::ViewMode;
use cutaway::render::headless::HeadlessRenderer;
use cutaway::scene::{
    CutterViews, ModelStyle, Scene, SceneCutter, SceneModel, Stereo, SubCutterSpec,
};
use cutaway::view::RenderPngOptions;
use cutaway::view::render_with;
use cutter::{BoundedPlane, Camera, CutKind};
use glam::DVec3;

#[path = "../support/image_compare.rs"]
mod image_compare;

mod annotate;
mod compare;
mod depth;
mod exports;
#[path = "../support/gltf_validator.rs"]
mod gltf_validator;
mod goldens;
mod image_walls;
mod risk;
#[allow(dead_code)] // helpers shared with other test binaries
#[path = "../support/scene_files.rs"]
mod scene_files;
mod sessions;
mod webpage;
mod wedge;

const WIDTH: u32 = 1280;
const HEIGHT: u32 = 800;

fn golden_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/golden")
}

/// Where failing renders are written for inspection.
fn actual_dir() -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("render-actual");
    std::fs::create_dir_all(&dir).ok();
    dir
}

/// Compares `actual` with the golden image `name` (tolerances: [`image_compare`]).
fn compare_to_golden(name: &str, actual: &image::RgbaImage, software: bool) {
    let path = golden_dir().join(format!("{name}.png"));
    let actual_path = actual_dir().join(format!("{name}.png"));
    actual.save(&actual_path).unwrap();
    if std::env::var_os("UPDATE_GOLDEN").is_some() {
        std::fs::create_dir_all(golden_dir()).unwrap();
        actual.save(&path).unwrap();
        println!("updated {}", path.display());
        return;
    }
    if !software {
        println!(
            "{name}: hardware adapter, golden comparison skipped (written to {})",
            actual_path.display()
        );
        return;
    }
    let difference = golden_difference(name, actual);
    println!("{name}: {difference}");
    assert!(
        difference.within(&image_compare::GOLDEN),
        "{name}: {difference}; actual image at {}",
        actual_path.display()
    );
}

/// How `actual` differs from the golden image `name` (tolerance [`image_compare::GOLDEN`]).
fn golden_difference(name: &str, actual: &image::RgbaImage) -> image_compare::Difference {
    let path = golden_dir().join(format!("{name}.png"));
    let expected = image::open(&path)
        .unwrap_or_else(|e| {
            panic!(
                "{}: {e} (run with UPDATE_GOLDEN=1 to create it)",
                path.display()
            )
        })
        .to_rgba8();
    assert_eq!(
        expected.dimensions(),
        actual.dimensions(),
        "{name}: size differs"
    );
    image_compare::difference(actual, &expected, &image_compare::GOLDEN)
}

/// The headless renderer on `WGPU_BACKEND` (Vulkan when unset), or `None` with the reason printed.
fn renderer() -> Option<HeadlessRenderer> {
    let backends = wgpu::Backends::from_env().unwrap_or(wgpu::Backends::VULKAN);
    match HeadlessRenderer::with_backends(backends) {
        Ok(r) => {
            println!("adapter: {}", r.adapter_name());
            Some(r)
        }
        Err(e) => {
            skip(Resource::Gpu, format!("{e:#}"));
            None
        }
    }
}

/// An icosphere of `csg::testkit` with `levels` subdivisions, scaled and moved; outward-facing,
/// closed, convex.
fn icosphere(centre: DVec3, radius: f64, levels: u32) -> Mesh {
    let mut mesh = csg::testkit::icosphere(levels, radius);
    for p in &mut mesh.positions {
        *p += centre;
    }
    mesh
}

fn model(name: &str, mesh: Mesh, color: [f32; 3]) -> SceneModel {
    SceneModel::new(name, format!("{name}.obj"), Arc::new(mesh), color)
}

fn camera() -> Camera {
    Camera {
        eye: DVec3::new(2.2, -5.0, 2.4),
        target: DVec3::new(0.0, 0.0, 0.05),
        up: DVec3::Z,
        fov_y_deg: 30.0,
    }
}

/// A straight cutter through the front-top-right of the unit sphere: planes at x = -0.25, 0.35,
/// 0.95; front (toward the camera) at y = -1.3, back at y = 0.15; z from -0.15 to 1.2.
fn corner_planes() -> Vec<BoundedPlane> {
    let plane = |x: f64| {
        cutter::BoundedPlane::from_corners([
            DVec3::new(x, -1.3, 1.2),
            DVec3::new(x, 0.15, 1.2),
            DVec3::new(x, 0.15, -0.15),
            DVec3::new(x, -1.3, -0.15),
        ])
    };
    vec![plane(-0.25), plane(0.35), plane(0.95)]
}

/// Skin-like outer sphere around a red inner sphere, as in an anatomy cutaway.
fn layered_scene() -> Scene {
    let mut scene = Scene::default();
    scene.models.push(model(
        "skin",
        icosphere(DVec3::ZERO, 1.0, 3),
        [0.93, 0.76, 0.62],
    ));
    scene.models.push(model(
        "organ",
        icosphere(DVec3::new(0.15, 0.0, 0.2), 0.5, 3),
        [0.8, 0.22, 0.2],
    ));
    scene.camera = camera();
    scene.render.antialias = true;
    scene
}

fn with_cutter(mut scene: Scene, views: CutterViews) -> Scene {
    scene.cutters.push(SceneCutter {
        target: 0,
        cutter: cutter::Cutter {
            kind: CutKind::Straight,
            smooth: false,
            levels: cutter::subdivision::DEFAULT_LEVELS,
            direction: cutter::CutDirection::Normal,
            planes: corner_planes(),
        },
        views,
    });
    scene
}

/// `count` sub-cutters `width` model units wide, spread evenly through the cutter.
fn even_sub_cutters(count: usize, width: f64) -> SubCutterSpec {
    SubCutterSpec {
        count,
        width,
        placement: cutter::subcutters::Placement::Even,
        relative: false,
    }
}

fn render(r: &mut HeadlessRenderer, scene: &Scene, mode: Option<ViewMode>) -> image::RgbaImage {
    let mut options = RenderPngOptions::new(WIDTH, HEIGHT);
    options.deterministic = true;
    options.mode = mode;
    render_with(r, scene, &options).unwrap()
}

/// Fraction of pixels that differ from the background colour.
fn coverage(image: &image::RgbaImage, background: [u8; 3]) -> f64 {
    let n = image
        .pixels()
        .filter(|p| (0..3).any(|k| (p[k] as i32 - background[k] as i32).abs() > 8))
        .count();
    n as f64 / (image.width() * image.height()) as f64
}

/// How many pixels of two images of one size differ at all.
fn differing_pixels(a: &image::RgbaImage, b: &image::RgbaImage) -> usize {
    a.pixels().zip(b.pixels()).filter(|(p, q)| p != q).count()
}

fn pixel(image: &image::RgbaImage, x: u32, y: u32) -> [u8; 4] {
    image.get_pixel(x, y).0
}
