//! The wedge cut on real anatomy: dragged and swept on the front of the embedded knee's skin the
//! way a user does in Edit mode (press, drag the first radius, sweep the rim), the pie rests on
//! the skin and reaches into it (thesis 3.3.2.3, figure 31), so the cut removes a sector of the
//! knee instead of a sliver sitting on the surface. A 1280×800 render of the cut goes to the
//! test's temporary folder (`CARGO_TARGET_TMPDIR`) for a person to look at; it is skipped with the
//! reason printed when no wgpu adapter exists (set `WGPU_BACKEND=vulkan` with lavapipe).

use std::path::Path;
use std::sync::Arc;

use cutaway::cutaway_geometry::{PartKind, preview_geometry};
use cutaway::render::headless::{HeadlessRenderer, render_with_preview};
use cutaway::render::{RenderPngOptions, ViewMode};
use cutaway::scene::{CutKind, CutterViews, Scene, SceneCutter, SceneModel};
use cutter::Camera;
use cutter::extrude::{RollSettings, extrude_move, initialize};
use cutter::surface::Surface;
use cutter::wedge::share_inside;
use glam::{DVec2, DVec3};

/// The embedded knee's skin, patella and femur (skin first: the target).
fn knee() -> Scene {
    let knee = cutaway::assets::scene("knee").expect("embedded knee");
    let mut scene = Scene::default();
    let mut models = cutaway::assets::load_scene(knee).expect("knee loads");
    models.sort_by_key(|m| !m.name.starts_with("skin"));
    for m in models {
        let part = m.name.split(' ').next().unwrap_or("").to_string();
        if part == "skin" || part == "patella" || part == "femur" {
            let color = cutaway::assets::default_color(&part);
            scene
                .models
                .push(SceneModel::new(m.name, m.source, Arc::new(m.mesh), color));
        }
    }
    scene
}

#[test]
fn a_wedge_on_the_knee_rests_on_the_skin_and_cuts_a_sector_out_of_it() {
    let mut scene = knee();
    assert_eq!(scene.models.len(), 3, "skin, patella and femur");
    assert!(scene.models[0].name.starts_with("skin"));
    let skin = scene.models[0].mesh.clone();
    let index = csg::SpatialIndex::build(&skin);
    let surface = Surface::new(&skin, &index);
    let camera = Camera::framing(&skin.bbox(), DVec3::NEG_Y, DVec3::Z, 30.0);
    let viewport = DVec2::new(1280.0, 800.0);
    let delta = (camera.eye - camera.target).length() / 2000.0;
    // Press on the front of the knee, drag the first radius up, sweep the rim 90° to the right.
    let a = DVec2::new(630.0, 400.0);
    let radius_px = 90.0;
    let mut wedge = initialize(
        &surface,
        &camera,
        viewport,
        a,
        a - DVec2::new(0.0, radius_px),
        delta,
        cutter::CutKind::Wedge,
        false,
    )
    .expect("the drag starts a wedge");
    let settings = RollSettings {
        delta,
        spacing: 20.0,
        straight: false,
    };
    for k in 1..=30 {
        let ang = (3.0 * k as f64).to_radians();
        let m = a + DVec2::new(ang.sin(), -ang.cos()) * radius_px;
        extrude_move(
            &mut wedge,
            &surface,
            &camera.ray_through_pixel(viewport, m),
            &settings,
        );
    }
    wedge.sanity_check().unwrap();
    assert!(
        wedge.planes.len() >= 4,
        "the rim swept: {} planes",
        wedge.planes.len()
    );

    let tree = csg::winding::WindingTree::build(&skin);
    let inside = |p: DVec3| tree.winding_number(&skin, p) > 0.5;
    // It starts on the skin: the apex is outside, a few δ from it, and so is every rim point
    // that has skin under it (the camera sees skin through it).
    let apex = wedge.planes[0].front_top;
    assert!(!inside(apex), "the apex is under the skin");
    let gap = surface.distance(apex) / delta;
    assert!(gap < 6.0, "the apex floats {gap:.1}δ above the skin");
    // It reaches in: the back of the shared axis and of every plane lies under the skin points
    // picked by the drag and the sweep.
    assert!(
        inside(wedge.planes[0].back_top),
        "the axis stops short of the skin"
    );
    for (i, p) in wedge.planes.iter().enumerate() {
        let ray =
            camera.ray_through_pixel(viewport, camera.project(viewport, p.front_bottom).unwrap());
        let picked = surface.ray_cast(ray.origin, ray.direction, f64::INFINITY);
        let Some((_, picked)) = picked else { continue };
        let depth_of = |q: DVec3| (q - camera.eye).dot(camera.forward());
        assert!(
            depth_of(p.back_bottom) > depth_of(picked) + 2.0 * delta,
            "plane {i}'s back is not below the skin point under its rim"
        );
    }
    // Most of the wedge cuts the knee, not the air in front of it.
    let share = share_inside(&wedge, inside);
    println!(
        "wedge: {} planes, {:.0} % inside the skin",
        wedge.planes.len(),
        share * 100.0
    );
    assert!(
        share > 0.5,
        "only {:.0} % of the wedge is in the skin",
        share * 100.0
    );

    // The exact cut makes walls; looked at in a 1280×800 render.
    scene.cutters.push(SceneCutter {
        target: 0,
        kind: CutKind::Wedge,
        smooth: false,
        planes: wedge.planes.iter().map(|p| p.corners()).collect(),
        views: CutterViews::default(),
    });
    let oblique = camera.eye - camera.target;
    scene.camera = Camera {
        eye: camera.target
            + DVec3::new(0.35 * oblique.length(), oblique.y, 0.45 * oblique.length()),
        ..camera
    };
    let preview = preview_geometry(&scene);
    assert!(preview.notes.is_empty(), "{:?}", preview.notes);
    assert!(preview.reports[0].1.exact, "the boolean refused the wedge");
    let wall_area: f64 = preview
        .parts
        .iter()
        .filter(|p| p.kind == PartKind::Wall)
        .map(|p| p.mesh.area())
        .sum();
    let radius = (wedge.planes[1].front_bottom - apex).length();
    assert!(
        wall_area > 0.5 * radius * radius,
        "walls of {wall_area:.0} mm² for a wedge of radius {radius:.0} mm: a sliver"
    );
    let backends = wgpu::Backends::from_env().unwrap_or(wgpu::Backends::VULKAN);
    let mut renderer = match HeadlessRenderer::with_backends(backends) {
        Ok(r) => r,
        Err(e) => {
            println!("skipped the render: {e:#}");
            return;
        }
    };
    let mut options = RenderPngOptions::new(1280, 800);
    options.mode = Some(ViewMode::Preview);
    let image =
        render_with_preview(&mut renderer, &scene, &options, Some(Arc::new(preview))).unwrap();
    let path = Path::new(env!("CARGO_TARGET_TMPDIR")).join("wedge-knee.png");
    image.save(&path).unwrap();
    println!("screenshot: {}", path.display());
}
