//! The wedge cut on the knee: dragged and swept on the front of the embedded knee phantom's skin the
//! way a user does in Edit mode (press, drag the first radius, sweep the rim), the pie rests on
//! the skin and reaches into it (thesis 3.3.2.3, figure 31), so the cut removes a sector of the
//! knee instead of a sliver sitting on the surface; the same on the real patella of
//! `CUTAWAY_ANATOMY/knee_vhf_left_denver` (skipped with the reason printed when that folder is
//! absent). A 1280×800 render of each cut goes to the
//! test's temporary folder (`CARGO_TARGET_TMPDIR`) for a person to look at; it is skipped with the
//! reason printed when no wgpu adapter exists (set `WGPU_BACKEND=vulkan` with lavapipe).

use csg::testkit::{Resource, skip};
use std::path::Path;
use std::sync::Arc;

use csg::Mesh;
use cutaway::cutting::cut_scene::{PartKind, preview_geometry};
use cutaway::render::ViewMode;
use cutaway::render::headless::HeadlessRenderer;
use cutaway::scene::{Scene, SceneCutter, SceneModel};
use cutaway::view::RenderPngOptions;
use cutaway::view::render_with_preview;
use cutter::CutKind;
use cutter::extrude::{RollSettings, extrude_move, initialize};
use cutter::surface::Surface;
use cutter::wedge::share_inside;
use cutter::{Camera, Cutter};
use glam::{DVec2, DVec3};

/// The embedded knee's skin, patella and femur (skin first: the target).
fn knee() -> Scene {
    let knee = cutaway::anatomy::assets::scene("knee").expect("embedded knee");
    let mut scene = Scene::default();
    let mut models = cutaway::anatomy::assets::load_scene(knee).expect("knee loads");
    models.sort_by_key(|m| !m.name.starts_with("skin"));
    for m in models {
        let part = m.name.split(' ').next().unwrap_or("").to_string();
        if part == "skin" || part == "patella" || part == "femur" {
            let color = cutaway::anatomy::colors::class_color(&part);
            scene
                .models
                .push(SceneModel::new(m.name, m.source, m.mesh, color));
        }
    }
    scene
}

/// Presses at `a` (pixels of a 1280×800 view), drags the pie's first radius `radius_px` up and
/// sweeps the rim 90° to the right on `mesh`, then checks that the wedge rests on the surface and
/// reaches into it: the apex outside, the front within a few δ of the surface, the shared axis's back inside, the
/// back of every plane deeper than the surface point seen under its rim, and more than half of
/// the wedge inside. Returns the wedge.
fn sweep_a_wedge(mesh: &Mesh, camera: &Camera, a: DVec2, radius_px: f64) -> Cutter {
    let index = csg::SpatialIndex::build(mesh);
    let surface = Surface::new(mesh, &index);
    let viewport = DVec2::new(1280.0, 800.0);
    let delta = (camera.eye - camera.target).length() / 2000.0;
    let mut wedge = initialize(
        &surface,
        camera,
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
        keep_direction: false,
        keep_depth: false,
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
    let tree = csg::winding::WindingTree::build(mesh);
    let inside = |p: DVec3| tree.winding_number(mesh, p) > 0.5;
    // It starts on the surface: the apex is outside, and the front rests on the surface (its
    // closest point, on the edges from the apex to the rim, is within a few δ of it).
    let apex = wedge.planes[0].front_top;
    assert!(!inside(apex), "the apex is under the surface");
    let rest = wedge
        .planes
        .iter()
        .flat_map(|p| (0..=8).map(move |k| apex.lerp(p.front_bottom, k as f64 / 8.0)))
        .map(|q| surface.distance(q))
        .fold(f64::INFINITY, f64::min)
        / delta;
    assert!(rest < 6.0, "the front floats {rest:.1}δ above the surface");
    // It reaches in: the back of the shared axis is inside, and the back of every plane lies
    // deeper than the surface point the view picks under its rim.
    assert!(
        inside(wedge.planes[0].back_top),
        "the axis stops short of the surface"
    );
    let depth_of = |q: DVec3| (q - camera.eye).dot(camera.forward());
    for (i, p) in wedge.planes.iter().enumerate() {
        let Some(px) = camera.project(viewport, p.front_bottom) else {
            continue;
        };
        let ray = camera.ray_through_pixel(viewport, px);
        let Some((_, picked)) = surface.ray_cast(ray.origin, ray.direction, f64::INFINITY) else {
            continue;
        };
        assert!(
            depth_of(p.back_bottom) > depth_of(picked) + 2.0 * delta,
            "plane {i}'s back is not below the surface point under its rim"
        );
    }
    // Most of the wedge cuts the target, not the air in front of it.
    let share = share_inside(&wedge, inside);
    println!(
        "wedge: {} planes, {:.0} % inside",
        wedge.planes.len(),
        share * 100.0
    );
    assert!(
        share > 0.5,
        "only {:.0} % of the wedge is inside",
        share * 100.0
    );
    wedge
}

/// Cuts `scene` (target 0) with `wedge`: the exact boolean makes walls of a sector, not a
/// sliver; renders it at 1280×800 from `camera` into the test's temporary folder as `name`.
fn cut_and_render(scene: &mut Scene, wedge: &Cutter, camera: Camera, name: &str) {
    assert_eq!(wedge.kind, CutKind::Wedge);
    scene.cutters.push(SceneCutter::new(
        0,
        Cutter {
            smooth: false,
            levels: cutter::subdivision::DEFAULT_LEVELS,
            ..wedge.clone()
        },
    ));
    scene.camera = camera;
    let preview = preview_geometry(scene);
    assert!(preview.notes.is_empty(), "{:?}", preview.notes);
    assert!(preview.reports[0].1.exact, "the boolean refused the wedge");
    let wall_area: f64 = preview
        .parts
        .iter()
        .filter(|p| p.kind == PartKind::Wall)
        .map(|p| p.mesh.area())
        .sum();
    let apex = wedge.planes[0].front_top;
    let radius = (wedge.planes[1].front_bottom - apex).length();
    assert!(
        wall_area > 0.5 * radius * radius,
        "walls of {wall_area:.0} mm² for a wedge of radius {radius:.0} mm: a sliver"
    );
    let backends = wgpu::Backends::from_env().unwrap_or(wgpu::Backends::VULKAN);
    let mut renderer = match HeadlessRenderer::with_backends(backends) {
        Ok(r) => r,
        Err(e) => return skip(Resource::Gpu, format!("the render: {e:#}")),
    };
    let mut options = RenderPngOptions::new(1280, 800);
    options.mode = Some(ViewMode::Preview);
    let image =
        render_with_preview(&mut renderer, scene, &options, Some(Arc::new(preview))).unwrap();
    let path = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    image.save(&path).unwrap();
    println!("screenshot: {}", path.display());
}

/// A camera turned from `camera` toward its right and up, looking at the same point.
fn oblique(camera: &Camera, right: f64, up: f64) -> Camera {
    let (r, u, _) = camera.basis();
    let d = camera.eye - camera.target;
    let l = d.length();
    Camera {
        eye: camera.target + (d + r * (right * l) + u * (up * l)).normalize() * l,
        ..*camera
    }
}

#[test]
fn a_wedge_on_the_knee_rests_on_the_skin_and_cuts_a_sector_out_of_it() {
    let mut scene = knee();
    assert_eq!(scene.models.len(), 3, "skin, patella and femur");
    assert!(scene.models[0].model.name.starts_with("skin"));
    let skin = scene.models[0].model.mesh.clone();
    let camera = Camera::framing(&skin.bbox(), DVec3::NEG_Y, DVec3::Z, 30.0);
    // On the front of the knee.
    let wedge = sweep_a_wedge(&skin, &camera, DVec2::new(630.0, 400.0), 90.0);
    cut_and_render(
        &mut scene,
        &wedge,
        oblique(&camera, 0.35, 0.45),
        "wedge-knee.png",
    );
}

#[test]
fn a_wedge_on_the_real_patella_cuts_a_sector_out_of_it() {
    let root = std::env::var_os("CUTAWAY_ANATOMY")
        .map(std::path::PathBuf::from)
        .unwrap_or_else(|| std::path::PathBuf::from("../shared/anatomy"));
    let folder = root.join("knee_vhf_left_denver");
    if !folder.is_dir() {
        return skip(
            Resource::Data,
            format!("{} not found (set CUTAWAY_ANATOMY)", folder.display()),
        );
    }
    // The patella (the target) with the bones and cartilage around it.
    let mut scene = Scene::default();
    let mut files: Vec<_> = std::fs::read_dir(&folder)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| {
            let name = p.file_name().unwrap().to_string_lossy().to_string();
            name.ends_with(".stl") && (name.contains("Bone") || name.contains("Cartilage"))
        })
        .collect();
    files.sort_by_key(|p| !p.to_string_lossy().contains("Bone_Patella"));
    for file in files {
        let mesh = cutaway::io::read_mesh(&file).expect("knee file loads");
        let name = file.file_stem().unwrap().to_string_lossy().to_string();
        let color = if name.contains("Bone") {
            [0.93, 0.87, 0.62]
        } else {
            [0.45, 0.7, 0.85]
        };
        scene.models.push(SceneModel::new(
            name,
            file.display().to_string(),
            Arc::new(mesh),
            color,
        ));
    }
    assert!(scene.models[0].model.name.contains("Patella"));
    let patella = scene.models[0].model.mesh.clone();
    // RAS: the front of the knee faces +Y.
    let camera = Camera::framing(&patella.bbox(), DVec3::Y, DVec3::Z, 30.0);
    let wedge = sweep_a_wedge(&patella, &camera, DVec2::new(640.0, 420.0), 140.0);
    let wide = Camera {
        eye: camera.target + (camera.eye - camera.target) * 2.5,
        ..oblique(&camera, 0.5, 0.4)
    };
    cut_and_render(&mut scene, &wedge, wide, "wedge-real-patella.png");
}
