//! The risk map: a cut wall 1 mm in front of a critical sphere is red where it passes the sphere
//! and keeps its wall colour far from it; the legend is drawn under the picture; the map can be
//! switched off; `cutaway render --critical` refuses a name that is no structure.

use super::*;
use cutaway::scene::risk::RiskSettings;

/// A 80 mm block of tissue with its front half cut away by a 40 × 40 mm box (the back wall at
/// y = 0 faces the camera), and a critical vessel of radius 5 mm behind that wall, 1 mm from it.
fn vessel_behind_a_wall() -> Scene {
    let mut scene = Scene::default();
    scene.models.push(model(
        "tissue",
        csg::testkit::cube(DVec3::splat(-40.0), DVec3::splat(40.0)),
        [0.93, 0.76, 0.62],
    ));
    scene.models.push(model(
        "vessel",
        icosphere(DVec3::new(0.0, 6.0, 0.0), 5.0, 3),
        [0.75, 0.1, 0.15],
    ));
    let plane = |x: f64| {
        cutter::BoundedPlane::from_corners([
            DVec3::new(x, -60.0, 20.0),
            DVec3::new(x, 0.0, 20.0),
            DVec3::new(x, 0.0, -20.0),
            DVec3::new(x, -60.0, -20.0),
        ])
    };
    scene.cutters.push(SceneCutter {
        target: 0,
        cutter: cutter::Cutter {
            kind: CutKind::Straight,
            smooth: false,
            levels: cutter::subdivision::DEFAULT_LEVELS,
            planes: vec![plane(-20.0), plane(20.0)],
            direction: cutter::CutDirection::Normal,
        },
        views: CutterViews::default(),
    });
    scene.camera = Camera {
        eye: DVec3::new(0.0, -150.0, 0.0),
        target: DVec3::ZERO,
        up: DVec3::Z,
        fov_y_deg: 30.0,
    };
    scene.risk = RiskSettings {
        critical: vec!["vessel".into()],
        ..RiskSettings::default()
    };
    scene
}

/// The pixel where world point `p` is seen in a `size` image of `scene`.
fn pixel_of(scene: &Scene, size: [u32; 2], p: DVec3) -> [u32; 2] {
    let at = scene
        .camera
        .project(glam::DVec2::new(size[0] as f64, size[1] as f64), p)
        .expect("in front of the camera");
    [at.x as u32, at.y as u32]
}

fn is_red(p: [u8; 4]) -> bool {
    p[0] > 150 && (p[1] as i32) < 70 && (p[2] as i32) < 70
}

fn close(a: [u8; 4], b: [u8; 4], tolerance: i32) -> bool {
    (0..3).all(|k| (a[k] as i32 - b[k] as i32).abs() <= tolerance)
}

#[test]
fn a_wall_near_a_critical_vessel_is_red_and_far_from_it_keeps_its_colour() {
    let Some(mut r) = renderer() else { return };
    let size = [320, 240];
    let scene = vessel_behind_a_wall();
    let mut options = RenderPngOptions::new(size[0], size[1]);
    options.deterministic = true;
    let mapped = render_with(&mut r, &scene, &options).unwrap();
    let mut plain_scene = scene.clone();
    plain_scene.risk.shown = false;
    let plain = render_with(&mut r, &plain_scene, &options).unwrap();
    mapped.save(actual_dir().join("risk_map.png")).unwrap();
    plain.save(actual_dir().join("risk_map_off.png")).unwrap();

    // 1 mm from the vessel: red (the plain wall is cream there).
    let [x, y] = pixel_of(&scene, size, DVec3::ZERO);
    let at_vessel = pixel(&mapped, x, y);
    assert!(
        is_red(at_vessel),
        "{at_vessel:?} at the wall point 1 mm from the vessel"
    );
    assert!(!is_red(pixel(&plain, x, y)));
    // 1.5 mm (within 2 mm) off the closest point, still red.
    let [x, y] = pixel_of(&scene, size, DVec3::new(2.0, 0.0, 0.5));
    assert!(is_red(pixel(&mapped, x, y)), "{:?}", pixel(&mapped, x, y));
    // About 6 mm away: the graded band (orange to yellow: red high, green between).
    let [x, y] = pixel_of(&scene, size, DVec3::new(8.0, 0.0, 0.0));
    let band = pixel(&mapped, x, y);
    assert!(
        band[0] > 180 && band[1] > 70 && band[1] < 235 && (band[2] as i32) < 90,
        "{band:?} about 5 mm from the vessel"
    );
    // 17 mm away: the wall's own colour, as drawn without the map.
    let [x, y] = pixel_of(&scene, size, DVec3::new(15.0, 0.0, 15.0));
    let (far, far_plain) = (pixel(&mapped, x, y), pixel(&plain, x, y));
    assert!(
        close(far, far_plain, 3),
        "{far:?} vs {far_plain:?} far from the vessel"
    );
    // The kept tissue around the cut is untouched by the map.
    let [x, y] = pixel_of(&scene, size, DVec3::new(30.0, -40.0, 30.0));
    assert!(close(pixel(&mapped, x, y), pixel(&plain, x, y), 3));
    // Counting: red only near the vessel (a disc of about 3.6 mm radius on the wall, plus the
    // error toward danger), nowhere else.
    let per_mm = 240.0 / (2.0 * 150.0 * (15f64).to_radians().tan());
    let red: Vec<(u32, u32)> = mapped
        .enumerate_pixels()
        .filter(|(_, _, p)| is_red(p.0))
        .map(|(x, y, _)| (x, y))
        .collect();
    let [cx, cy] = pixel_of(&scene, size, DVec3::ZERO);
    let farthest = red
        .iter()
        .map(|&(x, y)| ((x as f64 - cx as f64).powi(2) + (y as f64 - cy as f64).powi(2)).sqrt())
        .fold(0.0, f64::max);
    assert!(
        farthest <= (3.61 + 0.6) * per_mm + 2.0,
        "red {:.1} mm from the closest point",
        farthest / per_mm
    );
    assert!(red.len() as f64 > 0.8 * std::f64::consts::PI * (3.6 * per_mm).powi(2));
}

#[test]
fn the_cli_draws_the_legend_and_refuses_an_unknown_critical_name() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("risk-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let mut scene = vessel_behind_a_wall();
    for (m, name) in scene.models.iter_mut().zip(["tissue", "vessel"]) {
        let path = dir.join(format!("{name}.obj"));
        cutaway::io::write_mesh(&path, &m.model.mesh).unwrap();
        m.model.source = path;
        // A structure keeps its name in the session (a region would be `vessel 1`).
        m.unit = cutaway::scene::ModelUnit::Structure;
    }
    scene.risk = RiskSettings::default();
    let session = dir.join("s.json");
    cutaway::session::save(&session, &scene).unwrap();
    let text = std::fs::read_to_string(&session).unwrap();
    assert!(!text.contains("\"risk\""), "no map, no risk object: {text}");

    let cli = |extra: &[&str], out: &Path| {
        let mut command = std::process::Command::new(env!("CARGO_BIN_EXE_cutaway"));
        command
            .arg("render")
            .arg(&session)
            .arg("--out")
            .arg(out)
            .args(["--width", "480", "--height", "360"])
            .args(extra)
            .env(
                "WGPU_BACKEND",
                std::env::var("WGPU_BACKEND").unwrap_or_else(|_| "vulkan".into()),
            );
        command.output().unwrap()
    };
    let refused = dir.join("refused.png");
    let run = cli(&["--critical", "liver"], &refused);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(!run.status.success());
    assert!(
        stderr.starts_with("error: ")
            && stderr.contains("s.json")
            && stderr.contains("no structure named 'liver' (structures: tissue, vessel)")
            && stderr.lines().count() == 1,
        "{stderr}"
    );
    assert!(!refused.exists());

    let (with, without) = (dir.join("with.png"), dir.join("without.png"));
    let run = cli(&["--critical", "vessel"], &with);
    let stderr = String::from_utf8_lossy(&run.stderr);
    if !run.status.success() && stderr.contains("no GPU adapter") {
        println!("skipped: {stderr}");
        return;
    }
    assert!(run.status.success(), "{stderr}");
    let run = cli(&[], &without);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let with = image::open(&with).unwrap().to_rgba8();
    let without = image::open(&without).unwrap().to_rgba8();
    // The legend: a bar whose left part is the ramp's red, in the bottom band, which the picture
    // without the map does not have.
    let bottom = |img: &image::RgbaImage| {
        img.enumerate_pixels()
            .filter(|(_, y, p)| *y > 300 && is_red(p.0))
            .count()
    };
    assert!(bottom(&with) > 30, "no red legend swatch");
    assert_eq!(bottom(&without), 0);
    // `--no-risk` on a session that has a map draws none.
    scene.risk.critical = vec!["vessel".into()];
    cutaway::session::save(&session, &scene).unwrap();
    assert!(
        std::fs::read_to_string(&session)
            .unwrap()
            .contains("\"risk\"")
    );
    let off = dir.join("off.png");
    let run = cli(&["--no-risk"], &off);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let off = image::open(&off).unwrap().to_rgba8();
    assert_eq!(bottom(&off), 0);
    let mut red = 0;
    for p in off.pixels() {
        red += usize::from(is_red(p.0));
    }
    assert_eq!(red, 0, "--no-risk drew red");
}
