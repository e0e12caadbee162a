//! End-to-end tests of the renderer, sessions and `cutaway render`.
//!
//! Golden images: small (160×120), deterministic mode (no supersampling), rendered on the software
//! adapter with `WGPU_BACKEND=vulkan` (lavapipe; Vulkan is used when the variable is unset).
//! `UPDATE_GOLDEN=1 cargo test --test render` rewrites `tests/golden/*.png`. The tolerances live
//! in `image_compare.rs` only. On a machine with no adapter the GPU tests print
//! "skipped: <why>" and pass; on a hardware GPU the pictures are checked for content but not
//! compared (rasterizers differ).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use csg::Mesh;
use cutaway::render::headless::{HeadlessRenderer, render_with};
use cutaway::render::{RenderPngOptions, ViewMode};
use cutaway::scene::{
    CutterViews, ModelStyle, Scene, SceneCutter, SceneModel, Stereo, SubCutterView,
};
use cutter::{BoundedPlane, Camera, CutKind};
use glam::DVec3;

#[path = "image_compare.rs"]
mod image_compare;

const WIDTH: u32 = 160;
const HEIGHT: u32 = 120;

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
    let difference = image_compare::difference(actual, &expected);
    assert!(
        difference.within_tolerance(),
        "{name}: {difference}; actual image at {}",
        actual_path.display()
    );
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
            println!("skipped: {e:#}");
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
            planes: corner_planes(),
        },
        views,
    });
    scene
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

fn pixel(image: &image::RgbaImage, x: u32, y: u32) -> [u8; 4] {
    image.get_pixel(x, y).0
}

#[test]
fn golden_plain_scene() {
    let Some(mut r) = renderer() else { return };
    let mut scene = layered_scene();
    scene.models.push(model(
        "wire",
        icosphere(DVec3::new(-1.3, 0.6, -0.5), 0.45, 1),
        [0.2, 0.35, 0.8],
    ));
    scene.models[2].style = ModelStyle::Wireframe;
    let image = render(&mut r, &scene, None);
    // The skin hides the organ; the picture is neither empty nor all model.
    let c = coverage(&image, [255, 255, 255]);
    assert!(c > 0.15 && c < 0.8, "coverage {c}");
    let centre = pixel(&image, WIDTH / 2, HEIGHT / 2);
    assert!(
        centre[0] > centre[2],
        "skin colour expected at the centre, got {centre:?}"
    );
    compare_to_golden("plain", &image, r.is_software());
}

#[test]
fn golden_normal_cut_with_walls_and_contour() {
    let Some(mut r) = renderer() else { return };
    let uncut = render(&mut r, &layered_scene(), None);
    let scene = with_cutter(layered_scene(), CutterViews::default());
    let image = render(&mut r, &scene, None);
    // The cut reveals the red organ where the skin was.
    let red = |img: &image::RgbaImage| {
        img.pixels()
            .filter(|p| p[0] as i32 > p[1] as i32 + 80 && p[0] as i32 > p[2] as i32 + 80)
            .count()
    };
    assert!(
        red(&image) > red(&uncut) + 100,
        "{} vs {}",
        red(&image),
        red(&uncut)
    );
    // A dark contour line exists.
    let dark = image
        .pixels()
        .filter(|p| p[0] < 60 && p[1] < 60 && p[2] < 60)
        .count();
    assert!(dark > 40, "contour pixels: {dark}");
    compare_to_golden("normal_cut", &image, r.is_software());
}

#[test]
fn golden_transparency_over_two_layers() {
    let Some(mut r) = renderer() else { return };
    let views = CutterViews {
        transparency: Some(0.35),
        ..CutterViews::default()
    };
    let mut scene = with_cutter(layered_scene(), views);
    // A second transparent layer in front of part of the removed piece.
    let mut veil = model(
        "veil",
        icosphere(DVec3::new(0.75, -1.6, 0.55), 0.45, 2),
        [0.25, 0.5, 0.95],
    );
    veil.opacity = 0.45;
    scene.models.push(veil);
    let image = render(&mut r, &scene, None);
    let opaque_cut = render(
        &mut r,
        &with_cutter(layered_scene(), CutterViews::default()),
        None,
    );
    // The removed piece shows as a tint over the hole: the image differs from the plain cut in
    // many pixels, and blue appears where the veil is.
    let changed = image
        .pixels()
        .zip(opaque_cut.pixels())
        .filter(|(a, b)| (0..3).any(|k| (a[k] as i32 - b[k] as i32).abs() > 10))
        .count();
    assert!(changed > 300, "{changed} pixels changed");
    let blue = image
        .pixels()
        .filter(|p| p[2] as i32 > p[0] as i32 + 20)
        .count();
    assert!(blue > 30, "{blue} bluish pixels");
    compare_to_golden("transparency", &image, r.is_software());
}

#[test]
fn golden_ribbons() {
    let Some(mut r) = renderer() else { return };
    let views = CutterViews {
        cut: true,
        ribbons: Some(SubCutterView {
            count: 3,
            width: 0.12,
            placement: cutter::subcutters::Placement::Even,
            relative: false,
        }),
        ..CutterViews::default()
    };
    let scene = with_cutter(layered_scene(), views);
    let image = render(&mut r, &scene, None);
    let plain_cut = render(
        &mut r,
        &with_cutter(layered_scene(), CutterViews::default()),
        None,
    );
    let changed = image
        .pixels()
        .zip(plain_cut.pixels())
        .filter(|(a, b)| a != b)
        .count();
    assert!(changed > 60, "ribbons changed only {changed} pixels");
    compare_to_golden("ribbons", &image, r.is_software());
}

#[test]
fn golden_slices() {
    let Some(mut r) = renderer() else { return };
    let views = CutterViews {
        cut: true,
        slices: Some(SubCutterView {
            count: 3,
            width: 0.12,
            placement: cutter::subcutters::Placement::Even,
            relative: false,
        }),
        ..CutterViews::default()
    };
    let scene = with_cutter(layered_scene(), views);
    let image = render(&mut r, &scene, None);
    let ribbons = CutterViews {
        cut: true,
        ribbons: Some(SubCutterView {
            count: 3,
            width: 0.12,
            placement: cutter::subcutters::Placement::Even,
            relative: false,
        }),
        ..CutterViews::default()
    };
    let ribbon_image = render(&mut r, &with_cutter(layered_scene(), ribbons), None);
    // Slices add walls to the ribbons.
    let changed = image
        .pixels()
        .zip(ribbon_image.pixels())
        .filter(|(a, b)| a != b)
        .count();
    assert!(
        changed > 30,
        "slices look like ribbons ({changed} pixels differ)"
    );
    compare_to_golden("slices", &image, r.is_software());
}

#[test]
fn golden_anaglyph() {
    let Some(mut r) = renderer() else { return };
    let mut scene = layered_scene();
    // Something well in front of the convergence plane (the camera target), so the eyes disagree.
    scene.models.push(model(
        "near",
        icosphere(DVec3::new(-1.0, -2.0, -0.7), 0.3, 2),
        [0.3, 0.8, 0.4],
    ));
    scene.render.stereo = Stereo::Anaglyph;
    let image = render(&mut r, &scene, None);
    // Red/blue only: no green anywhere, and both eyes' images present (red-only and blue-only
    // fringes at the silhouette).
    assert!(image.pixels().all(|p| p[1] == 0), "green in an anaglyph");
    let red_only = image
        .pixels()
        .filter(|p| p[0] as i32 > p[2] as i32 + 60)
        .count();
    let blue_only = image
        .pixels()
        .filter(|p| p[2] as i32 > p[0] as i32 + 60)
        .count();
    assert!(
        red_only > 10 && blue_only > 10,
        "fringes: red {red_only}, blue {blue_only}"
    );
    compare_to_golden("anaglyph", &image, r.is_software());
}

#[test]
fn golden_edit_mode_cutter_overlay() {
    let Some(mut r) = renderer() else { return };
    let scene = with_cutter(layered_scene(), CutterViews::default());
    let image = render(&mut r, &scene, Some(ViewMode::Edit));
    let camera_mode = render(&mut r, &scene, Some(ViewMode::Camera));
    let changed = image
        .pixels()
        .zip(camera_mode.pixels())
        .filter(|(a, b)| a != b)
        .count();
    assert!(
        changed > 200,
        "the cutter overlay changed only {changed} pixels"
    );
    compare_to_golden("edit_mode", &image, r.is_software());
}

/// A rounded (smooth) cutter across the front of the embedded knee phantom: a wavy path of
/// seven planes at the height of the joint, from just outside the skin 45 mm deep.
fn rounded_knee_scene() -> Scene {
    let knee = cutaway::assets::scene("knee").expect("embedded knee");
    let models = cutaway::assets::load_scene(knee).expect("knee loads");
    let mut scene = Scene::default();
    for m in models {
        let part = m.name.split(' ').next().unwrap_or("").to_string();
        if part == "skin" || part == "patella" || part == "femur" {
            let color = cutaway::assets::default_color(&part);
            scene
                .models
                .push(SceneModel::new(m.name, m.source, Arc::new(m.mesh), color));
        }
    }
    let planes = (0..7)
        .map(|i| {
            let x = -45.0 + 15.0 * i as f64;
            let z = 45.0 + 12.0 * (x / 25.0).sin();
            let slope = 12.0 / 25.0 * (x / 25.0).cos();
            let edge = DVec3::new(-slope, 0.0, 1.0).normalize() * 22.0;
            let front = DVec3::new(x, -75.0, z);
            cutter::BoundedPlane::from_front_edge(front + edge, front - edge, DVec3::Y, 45.0)
        })
        .collect();
    scene.cutters.push(SceneCutter {
        target: 0,
        cutter: cutter::Cutter {
            kind: CutKind::Curving,
            smooth: true,
            planes,
        },
        views: CutterViews::default(),
    });
    scene.camera = Camera {
        eye: DVec3::new(150.0, -300.0, 150.0),
        target: DVec3::new(0.0, -20.0, 40.0),
        up: DVec3::Z,
        fov_y_deg: 30.0,
    };
    scene
}

#[test]
fn golden_rounded_cut_on_the_knee_overlay_is_the_wall() {
    let scene = rounded_knee_scene();
    assert_eq!(scene.models.len(), 3, "skin, patella and femur");
    let preview = cutaway::cutting::cut_scene::preview_geometry(&scene);
    assert!(preview.notes.is_empty(), "{:?}", preview.notes);
    assert!(preview.reports[0].1.exact);
    // The walls lie on the overlay's surface (the one surface that cuts and is drawn), and that
    // surface is the rounded one, not the boxes.
    let surface = cutaway::cutting::cut_scene::cutter_mesh(&scene.cutters[0]);
    let boxes = scene.cutters[0].cutter.quad_mesh().triangulate();
    let on_surface = csg::SpatialIndex::build(&surface);
    let on_boxes = csg::SpatialIndex::build(&boxes);
    let mut off_boxes: f64 = 0.0;
    let mut wall_vertices = 0;
    for part in &preview.parts {
        if part.kind != cutaway::cutting::cut_scene::PartKind::Wall {
            continue;
        }
        for &p in &part.mesh.positions {
            let d = on_surface.closest_point(&surface, p).unwrap().distance;
            // New contour vertices are rounded once from the boolean's lattice (~3e-6 mm here).
            assert!(
                d < 1e-5,
                "wall vertex {p} is {d} mm off the overlay surface"
            );
            off_boxes = off_boxes.max(on_boxes.closest_point(&boxes, p).unwrap().distance);
            wall_vertices += 1;
        }
    }
    assert!(wall_vertices > 100, "{wall_vertices}");
    assert!(
        off_boxes > 1.0,
        "the walls follow the boxes ({off_boxes} mm)"
    );

    let Some(mut r) = renderer() else { return };
    let mut options = RenderPngOptions::new(2 * WIDTH, 2 * HEIGHT);
    options.deterministic = true;
    options.mode = Some(ViewMode::Edit);
    let image =
        cutaway::render::render_with_preview(&mut r, &scene, &options, Some(Arc::new(preview)))
            .unwrap();
    assert!(coverage(&image, [255, 255, 255]) > 0.2);
    compare_to_golden("rounded_knee_edit", &image, r.is_software());
}

#[test]
fn transparent_background_and_tiled_export() {
    let Some(mut r) = renderer() else { return };
    let scene = layered_scene();
    let mut options = RenderPngOptions::new(WIDTH, HEIGHT);
    options.deterministic = true;
    options.transparent_background = true;
    let image = render_with(&mut r, &scene, &options).unwrap();
    assert_eq!(pixel(&image, 0, 0)[3], 0, "corner should be transparent");
    assert_eq!(
        pixel(&image, WIDTH / 2, HEIGHT / 2)[3],
        255,
        "model should be opaque"
    );
    // A 2600×40 strip needs two tiles across; the seam must not show.
    let mut options = RenderPngOptions::new(2600, 40);
    options.deterministic = true;
    let wide = render_with(&mut r, &scene, &options).unwrap();
    assert_eq!(wide.dimensions(), (2600, 40));
    for y in 0..40 {
        let (a, b) = (pixel(&wide, 2047, y), pixel(&wide, 2048, y));
        let d = (0..3)
            .map(|k| (a[k] as i32 - b[k] as i32).abs())
            .max()
            .unwrap_or(0);
        assert!(d < 40, "seam at row {y}: {a:?} vs {b:?}");
    }
}

/// Not a check: writes larger supersampled pictures of every view for people to look at
/// (`cargo test --test render -- --ignored sample`; files in the target's tmp folder).
#[test]
#[ignore]
fn sample_renders_for_people() {
    let Some(mut r) = renderer() else { return };
    let sub = Some(SubCutterView {
        count: 4,
        width: 0.1,
        placement: cutter::subcutters::Placement::Even,
        relative: false,
    });
    let views = [
        ("sample_plain", None),
        ("sample_cut", Some(CutterViews::default())),
        (
            "sample_transparency_ribbons",
            Some(CutterViews {
                transparency: Some(0.3),
                ribbons: sub,
                ..CutterViews::default()
            }),
        ),
        (
            "sample_slices",
            Some(CutterViews {
                transparency: Some(0.25),
                slices: sub,
                ..CutterViews::default()
            }),
        ),
    ];
    for (name, v) in views {
        let scene = match v {
            Some(v) => with_cutter(layered_scene(), v),
            None => layered_scene(),
        };
        let image = render_with(&mut r, &scene, &RenderPngOptions::new(640, 480)).unwrap();
        let path = actual_dir().join(format!("{name}.png"));
        image.save(&path).unwrap();
        println!("wrote {}", path.display());
    }
}

mod sessions {
    use super::*;
    use cutaway::session;

    fn temp_dir(name: &str) -> PathBuf {
        let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
            .join(format!("session-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    /// Writes two disconnected spheres into one OBJ (two regions).
    fn write_two_region_obj(path: &Path) {
        let mut mesh = icosphere(DVec3::ZERO, 1.0, 1);
        mesh.append(&icosphere(DVec3::new(3.0, 0.0, 0.0), 0.5, 1));
        cutaway::io::write_mesh(path, &mesh).unwrap();
    }

    fn scene_for(dir: &Path) -> Scene {
        let path = dir.join("models").join("pair.obj");
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        write_two_region_obj(&path);
        let mut scene = Scene::default();
        for (region, m) in cutaway::io::load_models(&path)
            .unwrap()
            .into_iter()
            .enumerate()
        {
            let mut sm = SceneModel::new(
                m.name,
                m.source,
                Arc::new(m.mesh),
                [0.1 * region as f32, 0.5, 0.9],
            );
            sm.region = region;
            scene.models.push(sm);
        }
        scene.models[1].opacity = 0.5;
        scene.models[1].style = ModelStyle::Wireframe;
        scene.models[1].visible = false;
        scene.cutters.push(SceneCutter {
            target: 1,
            cutter: cutter::Cutter {
                kind: CutKind::Wedge,
                smooth: true,
                planes: corner_planes(),
            },
            views: CutterViews {
                cut: false,
                transparency: Some(0.25),
                ribbons: Some(SubCutterView {
                    count: 5,
                    width: 2.0,
                    placement: cutter::subcutters::Placement::Even,
                    relative: false,
                }),
                slices: None,
            },
        });
        scene.camera = camera();
        scene.render.background = [0.1, 0.2, 0.3, 1.0];
        scene.render.antialias = false;
        scene.render.stereo = Stereo::Anaglyph;
        scene
    }

    #[test]
    fn session_round_trip_is_exact_and_relative() {
        let dir = temp_dir("round-trip");
        let scene = scene_for(&dir);
        let file = dir.join("s.json");
        session::save(&file, &scene).unwrap();
        let text = std::fs::read_to_string(&file).unwrap();
        assert!(text.contains("\"cutaway-session/1\""));
        assert!(
            text.contains("models/pair.obj"),
            "paths must be relative: {text}"
        );
        let back = session::load(&file).unwrap();
        assert_eq!(back.models.len(), 2);
        for (a, b) in scene.models.iter().zip(&back.models) {
            assert_eq!(
                (a.color, a.opacity, a.style, a.visible, a.region),
                (b.color, b.opacity, b.style, b.visible, b.region)
            );
            assert_eq!(a.mesh.triangles, b.mesh.triangles);
        }
        assert_eq!(scene.cutters, back.cutters);
        assert_eq!(scene.camera, back.camera);
        assert_eq!(scene.render, back.render);
        // Saving again gives the same bytes, and leaves no temporary file behind.
        session::save(&file, &back).unwrap();
        assert_eq!(std::fs::read_to_string(&file).unwrap(), text);
        let names: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names.len(), 2, "{names:?}");
    }

    #[test]
    fn hand_written_session_expands_regions_and_ignores_unknown_fields() {
        let dir = temp_dir("hand-written");
        write_two_region_obj(&dir.join("pair.obj"));
        let file = dir.join("s.json");
        std::fs::write(
            &file,
            r#"{"format": "cutaway-session/1", "future": [1, 2],
                "models": [{"path": "pair.obj", "color": [0.9, 0.7, 0.6], "opacity": 1.0, "style": "solid", "visible": true, "note": "x"}],
                "cutters": [{"target": 1, "kind": "curving", "smooth": false, "planes": [[[0,0,0],[0,1,0],[0,1,-1],[0,0,-1]]],
                             "views": {"cut": true, "transparency": null, "ribbons": null, "slices": null}}],
                "camera": {"eye": [0, -300, 0], "target": [0, 0, 0], "up": [0, 0, 1], "fov_y_deg": 30},
                "render": {"background": [1, 1, 1, 1], "antialias": true, "stereo": "none"}}"#,
        )
        .unwrap();
        let scene = session::load(&file).unwrap();
        assert_eq!(scene.models.len(), 2, "both regions of pair.obj are models");
        assert_eq!(scene.models[1].region, 1);
        assert_eq!(scene.models[1].color, [0.9, 0.7, 0.6]);
        assert_eq!(scene.cutters[0].target, 1);
    }

    #[test]
    fn corrupt_session_is_a_one_line_error_naming_the_file_and_nothing_is_lost() {
        let dir = temp_dir("corrupt");
        let scene = scene_for(&dir);
        let good = dir.join("good.json");
        session::save(&good, &scene).unwrap();
        let before = std::fs::read(&good).unwrap();
        let bad = dir.join("bad.json");
        for (text, expect) in [
            (&before[..before.len() / 2], "line"),
            (&b"{\"format\": \"something-else/2\", \"models\": []}"[..], "something-else/2"),
            (&b"{\"format\": \"cutaway-session/1\", \"models\": [], \"cutters\": [{\"target\": 4, \"planes\": [[[0,0,0],[0,1,0],[0,1,1],[0,0,1]]]}]}"[..], "target 4"),
            (&b"{\"format\": \"cutaway-session/1\", \"models\": [{\"path\": \"missing.obj\"}]}"[..], "missing.obj"),
        ] {
            std::fs::write(&bad, text).unwrap();
            let err = session::load(&bad).unwrap_err();
            let line = cutaway::cli::error_line(&err);
            assert!(!line.contains('\n'));
            assert!(line.contains("bad.json") || expect == "missing.obj", "{line}");
            assert!(line.contains(expect), "{line}");
        }
        // A failed save (folder does not exist) leaves the old session untouched.
        assert!(session::save(&dir.join("no/such/dir/s.json"), &scene).is_err());
        assert_eq!(std::fs::read(&good).unwrap(), before);
    }

    #[test]
    fn cli_render_writes_the_png_headless() {
        let dir = temp_dir("cli");
        let mut scene = scene_for(&dir);
        scene.models[1].visible = true;
        scene.render.stereo = Stereo::None;
        let file = dir.join("s.json");
        session::save(&file, &scene).unwrap();
        let out = dir.join("out.png");
        let run = std::process::Command::new(env!("CARGO_BIN_EXE_cutaway"))
            .args(["render"])
            .arg(&file)
            .arg("--out")
            .arg(&out)
            .args(["--width", "96", "--height", "64"])
            .env(
                "WGPU_BACKEND",
                std::env::var("WGPU_BACKEND").unwrap_or_else(|_| "vulkan".into()),
            )
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&run.stderr);
        if !run.status.success() && stderr.contains("no GPU adapter") {
            println!("skipped: {stderr}");
            return;
        }
        assert!(run.status.success(), "{stderr}");
        let image = image::open(&out).unwrap().to_rgba8();
        assert_eq!(image.dimensions(), (96, 64));
        // Bad session: one line on stderr naming the file, non-zero exit.
        std::fs::write(&file, "{not json").unwrap();
        let run = std::process::Command::new(env!("CARGO_BIN_EXE_cutaway"))
            .args(["render"])
            .arg(&file)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert!(!run.status.success());
        assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
        assert!(
            stderr.starts_with("error: ") && stderr.contains("s.json"),
            "{stderr}"
        );
    }

    /// A model edited since it was loaded (here: its mesh replaced by a sphere elsewhere) is
    /// saved next to the session, so `cutaway render` shows the edited mesh even after the file
    /// it was loaded from is gone.
    #[test]
    fn cli_render_shows_an_edited_mesh_saved_with_the_session() {
        let dir = temp_dir("edited");
        let source = dir.join("small.ply");
        cutaway::io::write_mesh(&source, &icosphere(DVec3::new(0.0, 0.0, 3.0), 0.1, 1)).unwrap();
        let loaded = cutaway::io::load_models(&source).unwrap().remove(0);
        let mut model = SceneModel::new(
            loaded.name,
            loaded.source,
            Arc::new(loaded.mesh),
            [0.8, 0.2, 0.2],
        );
        model.replace_mesh(Arc::new(icosphere(DVec3::ZERO, 1.0, 2)));
        let mut scene = Scene::default();
        scene.models.push(model);
        scene.camera = camera();
        scene.render.antialias = false;
        let file = dir.join("edited.json");
        session::save(&file, &scene).unwrap();
        std::fs::remove_file(&source).unwrap();
        let out = dir.join("edited.png");
        let run = std::process::Command::new(env!("CARGO_BIN_EXE_cutaway"))
            .args(["render"])
            .arg(&file)
            .arg("--out")
            .arg(&out)
            .args(["--width", "64", "--height", "48"])
            .env(
                "WGPU_BACKEND",
                std::env::var("WGPU_BACKEND").unwrap_or_else(|_| "vulkan".into()),
            )
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&run.stderr);
        if !run.status.success() && stderr.contains("no GPU adapter") {
            println!("skipped: {stderr}");
            return;
        }
        assert!(run.status.success(), "{stderr}");
        let image = image::open(&out).unwrap().to_rgba8();
        // The unit sphere at the origin fills the middle of the view (the loaded sphere was
        // small and above it).
        assert!(coverage(&image, [255, 255, 255]) > 0.05);
        let [r, g, b, _] = pixel(&image, 32, 24);
        assert!(
            r > g && r > b,
            "centre pixel {r} {g} {b} is not the model's red"
        );
    }

    /// A successful render prints nothing, also without `XDG_RUNTIME_DIR` and without
    /// `WGPU_BACKEND` (then wgpu also probes OpenGL, whose window-system libraries complain
    /// about the missing runtime folder unless `cutaway` gives them one).
    #[test]
    fn cli_render_success_prints_nothing_without_a_runtime_dir() {
        let dir = temp_dir("quiet");
        let scene = scene_for(&dir);
        let file = dir.join("s.json");
        session::save(&file, &scene).unwrap();
        let out = dir.join("out.png");
        let run = std::process::Command::new(env!("CARGO_BIN_EXE_cutaway"))
            .args(["render"])
            .arg(&file)
            .arg("--out")
            .arg(&out)
            .args(["--width", "32", "--height", "32"])
            .env_remove("XDG_RUNTIME_DIR")
            .env_remove("WGPU_BACKEND")
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&run.stderr);
        if !run.status.success() && stderr.contains("no GPU adapter") {
            println!("skipped: {stderr}");
            return;
        }
        assert!(run.status.success(), "{stderr}");
        assert_eq!(
            stderr, "",
            "a successful render must print nothing on stderr"
        );
        assert!(out.is_file());
    }
}
