//! The intensity image on the cut walls: rendered wall pixels follow a known function of world
//! position (ramp along x, checkerboard by z), for an image on an axis-aligned RAS grid, on a
//! permuted and flipped LPS grid read from a NRRD file, and on a grid coarser than the cut; and
//! the real chest CT beside its segmentation, rendered with a lung and a bone window.
//!
//! GPU tests run on `WGPU_BACKEND` (lavapipe with `vulkan`); without an adapter they print
//! "skipped: <why>" and pass. Renders are written to `target/test-output/image_walls/` to be
//! looked at.

use csg::testkit::{Resource, skip};
use std::path::{Path, PathBuf};
use std::sync::Arc;

use cutaway::io::intensity::{IntensityImage, Window};
use cutaway::render::ViewMode;
use cutaway::render::headless::HeadlessRenderer;
use cutaway::scene::{CutterViews, Scene, SceneCutter, SceneModel};
use cutaway::scene::{ImageLayer, WallDisplay};
use cutaway::view::RenderPngOptions;
use cutaway::view::render_with;
use cutter::Camera;
use cutter::{BoundedPlane, CutKind};
use glam::{DAffine3, DMat3, DVec2, DVec3};

const WIDTH: u32 = 320;
const HEIGHT: u32 = 240;

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

fn out_dir() -> PathBuf {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../target/test-output/image_walls");
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn box_planes(x0: f64, x1: f64, y0: f64, y1: f64, z0: f64, z1: f64) -> Vec<BoundedPlane> {
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

/// The 10 mm cube [0, 10]³ with a box cut x, z in 1..9 from the front to y = 5: the back wall
/// at y = 5 faces the camera, which looks along +y.
fn cube_scene(image: IntensityImage, window: Window) -> Scene {
    let mut scene = Scene::default();
    let cube = csg::testkit::cube(DVec3::ZERO, DVec3::splat(10.0));
    scene.models.push(SceneModel::new(
        "cube",
        "cube.obj",
        Arc::new(cube),
        [0.8, 0.3, 0.3],
    ));
    scene.cutters.push(SceneCutter {
        target: 0,
        cutter: cutter::Cutter {
            kind: CutKind::Straight,
            smooth: false,
            levels: cutter::subdivision::DEFAULT_LEVELS,
            direction: cutter::CutDirection::Normal,
            planes: box_planes(1.0, 9.0, -5.0, 5.0, 1.0, 9.0),
        },
        views: CutterViews::default(),
    });
    scene.camera = camera();
    scene.render.antialias = false;
    let mut layer = ImageLayer::new(Arc::new(image));
    layer.window = window;
    layer.display = WallDisplay::Image;
    scene.image = Some(layer);
    scene
}

fn camera() -> Camera {
    Camera {
        eye: DVec3::new(5.0, -40.0, 5.0),
        target: DVec3::new(5.0, 5.0, 5.0),
        up: DVec3::Z,
        fov_y_deg: 20.0,
    }
}

fn render(r: &mut HeadlessRenderer, scene: &Scene, name: &str) -> image::RgbaImage {
    let mut options = RenderPngOptions::new(WIDTH, HEIGHT);
    options.deterministic = true;
    options.mode = Some(ViewMode::Preview);
    let image = render_with(r, scene, &options).unwrap();
    image.save(out_dir().join(format!("{name}.png"))).unwrap();
    image
}

/// The grey of the pixel showing wall point (x, 5, z), and the expected grey.
fn wall_samples(
    image: &image::RgbaImage,
    f: &dyn Fn(DVec3) -> f64,
    window: Window,
) -> Vec<(f64, f64, DVec3)> {
    let viewport = DVec2::new(WIDTH as f64, HEIGHT as f64);
    let mut out = Vec::new();
    for xi in 0..=28 {
        for zi in 0..=28 {
            let p = DVec3::new(1.4 + xi as f64 * 0.25, 5.0, 1.4 + zi as f64 * 0.25);
            let px = camera().project(viewport, p).unwrap();
            let pixel = image.get_pixel(px.x as u32, px.y as u32).0;
            let grey = (pixel[0] as f64 + pixel[1] as f64 + pixel[2] as f64) / (3.0 * 255.0);
            out.push((grey, window.map(f(p)), p));
        }
    }
    out
}

fn correlation(pairs: &[(f64, f64, DVec3)]) -> f64 {
    let n = pairs.len() as f64;
    let (ma, mb) = pairs
        .iter()
        .fold((0.0, 0.0), |(a, b), p| (a + p.0 / n, b + p.1 / n));
    let (mut ab, mut aa, mut bb) = (0.0, 0.0, 0.0);
    for p in pairs {
        ab += (p.0 - ma) * (p.1 - mb);
        aa += (p.0 - ma).powi(2);
        bb += (p.1 - mb).powi(2);
    }
    ab / (aa * bb).sqrt().max(1e-12)
}

/// The function of world position an image holds.
type WallFunction = dyn Fn(DVec3) -> f64;

fn ramp(p: DVec3) -> f64 {
    100.0 * p.x
}

/// Bands 2 mm high along z, alternately 0 and 1000.
fn checker(p: DVec3) -> f64 {
    if (p.z / 2.0).floor() as i64 % 2 == 0 {
        0.0
    } else {
        1000.0
    }
}

const WINDOW: Window = Window {
    level: 500.0,
    width: 1000.0,
};

/// Checks that the wall follows `f`: correlation ≥ 0.95, and for the ramp, greys increase with x.
fn assert_follows(image: &image::RgbaImage, f: &dyn Fn(DVec3) -> f64, what: &str, ramp_in_x: bool) {
    let mut pairs = wall_samples(image, f, WINDOW);
    if !ramp_in_x {
        // Away from the band edges, where interpolation blends the bands.
        pairs.retain(|(_, _, p)| {
            let t = (p.z / 2.0).fract();
            (0.2..=0.8).contains(&t)
        });
    }
    let r = correlation(&pairs);
    println!(
        "{what}: correlation {r:.4} over {} wall pixels",
        pairs.len()
    );
    assert!(r >= 0.95, "{what}: correlation {r} < 0.95");
    if ramp_in_x {
        // Along each row of constant z, the grey rises with x (ties allowed between neighbours
        // closer than a grey level).
        let mut by_x: Vec<(f64, f64)> = pairs.iter().map(|(g, _, p)| (p.x, *g)).collect();
        by_x.sort_by(|a, b| a.0.total_cmp(&b.0));
        let first = by_x[..29].iter().map(|v| v.1).sum::<f64>() / 29.0;
        let last = by_x[by_x.len() - 29..].iter().map(|v| v.1).sum::<f64>() / 29.0;
        assert!(
            last > first + 0.4,
            "{what}: grey at high x {last} vs low x {first}"
        );
        for z in 0..=28 {
            let row: Vec<f64> = (0..=28).map(|x| pairs[x * 29 + z].0).collect();
            for w in row.windows(2) {
                assert!(
                    w[1] >= w[0] - 2.0 / 255.0,
                    "{what}: not monotonic along x: {row:?}"
                );
            }
        }
    }
}

fn ras_image(spacing: f64, f: impl Fn(DVec3) -> f32) -> IntensityImage {
    let n = (12.0 / spacing).round() as usize + 1;
    let m = DAffine3::from_mat3_translation(
        DMat3::from_diagonal(DVec3::splat(spacing)),
        DVec3::splat(-1.0),
    );
    IntensityImage::from_fn([n; 3], m, f)
}

/// The same function on a permuted, flipped grid in LPS space, written as an int16 NRRD and read
/// back through the reader: i runs along +z, j along RAS -x, k along RAS +y.
fn lps_nrrd_image(dir: &Path, name: &str, f: impl Fn(DVec3) -> f64) -> IntensityImage {
    let n = 25usize;
    let s = 0.5;
    // LPS origin (-11, 1, -1) is RAS (11, -1, -1).
    let origin_ras = DVec3::new(11.0, -1.0, -1.0);
    let ras = |i: usize, j: usize, k: usize| {
        origin_ras + DVec3::new(-s * j as f64, s * k as f64, s * i as f64)
    };
    let mut data = Vec::with_capacity(n * n * n * 2);
    for k in 0..n {
        for j in 0..n {
            for i in 0..n {
                data.extend_from_slice(&(f(ras(i, j, k)).round() as i16).to_le_bytes());
            }
        }
    }
    let header = format!(
        "NRRD0004\ntype: short\ndimension: 3\nspace: left-posterior-superior\nsizes: {n} {n} {n}\nspace directions: (0,0,{s}) ({s},0,0) (0,-{s},0)\nkinds: domain domain domain\nendian: little\nencoding: raw\nspace origin: (-11,1,-1)\n\n"
    );
    let path = dir.join(name);
    let mut bytes = header.into_bytes();
    bytes.extend(data);
    std::fs::write(&path, bytes).unwrap();
    let image = cutaway::io::volume::intensity::read_image(&path).unwrap();
    // The reader put voxel (i, j, k) where it was written.
    let p = image
        .world_from_voxel
        .transform_point3(DVec3::new(3.0, 4.0, 5.0));
    assert!(
        (p - ras(3, 4, 5)).length() < 1e-9,
        "{p} vs {}",
        ras(3, 4, 5)
    );
    image
}

#[test]
fn wall_pixels_follow_the_image_function() {
    let Some(mut r) = renderer() else { return };
    let dir = out_dir();
    let cases: Vec<(&str, IntensityImage, &WallFunction, bool)> = vec![
        ("ramp_ras", ras_image(0.5, |p| ramp(p) as f32), &ramp, true),
        (
            "checker_ras",
            ras_image(0.25, |p| checker(p) as f32),
            &checker,
            false,
        ),
        (
            "ramp_lps_permuted",
            lps_nrrd_image(&dir, "ramp_lps.nrrd", ramp),
            &ramp,
            true,
        ),
        (
            "checker_lps_permuted",
            lps_nrrd_image(&dir, "checker_lps.nrrd", checker),
            &checker,
            false,
        ),
        // A grid much coarser than the wall: the ramp is still exact under trilinear sampling.
        (
            "ramp_coarse",
            ras_image(3.0, |p| ramp(p) as f32),
            &ramp,
            true,
        ),
    ];
    for (name, image, f, in_x) in cases {
        let scene = cube_scene(image, WINDOW);
        let picture = render(&mut r, &scene, name);
        assert_follows(&picture, f, name, in_x);
    }
}

#[test]
fn a_wrong_image_is_caught_and_colour_mode_ignores_the_image() {
    let Some(mut r) = renderer() else { return };
    // The ramp along z instead of x does not pass as a ramp along x: the test can fail.
    let scene = cube_scene(ras_image(0.5, |p| 100.0 * p.z as f32), WINDOW);
    let picture = render(&mut r, &scene, "ramp_wrong_axis");
    let pairs = wall_samples(&picture, &ramp, WINDOW);
    let rho = correlation(&pairs);
    assert!(
        rho.abs() < 0.5,
        "a ramp along z correlates {rho} with one along x"
    );

    // Structure colour: the picture is the one without an image, pixel for pixel.
    let mut scene = cube_scene(ras_image(0.5, |p| ramp(p) as f32), WINDOW);
    scene.image.as_mut().unwrap().display = WallDisplay::Color;
    let color = render(&mut r, &scene, "ramp_color_display");
    scene.image = None;
    let plain = render(&mut r, &scene, "no_image");
    assert_eq!(
        color.as_raw(),
        plain.as_raw(),
        "colour display differs from no image"
    );
    // Blend: between the two.
    let mut scene = cube_scene(ras_image(0.5, |p| ramp(p) as f32), WINDOW);
    scene.image.as_mut().unwrap().display = WallDisplay::Blend;
    let blend = render(&mut r, &scene, "ramp_blend");
    let pairs = wall_samples(&blend, &ramp, WINDOW);
    assert!(correlation(&pairs) > 0.9, "blend still follows the ramp");
    assert_ne!(blend.as_raw(), plain.as_raw());
}

/// The chest CT folder of the real data (`$CUTAWAY_ANATOMY/volumes/slicerio_chest`, else
/// `../shared/anatomy` beside the workspace), or `None` with the reason printed.
fn chest_dir() -> Option<PathBuf> {
    let root = std::env::var_os("CUTAWAY_ANATOMY")
        .map(PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/anatomy"));
    let root = if root.is_relative() {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join(root)
    } else {
        root
    };
    let dir = root.join("volumes/slicerio_chest");
    if dir.join("CTChest4.nrrd").is_file() && dir.join("Segmentation.seg.nrrd").is_file() {
        Some(dir)
    } else {
        skip(Resource::Data, format!("no chest CT in {}", dir.display()));
        None
    }
}

/// The chest segmentation with a box cut from the front through the ribs and lungs to behind
/// the spine, the CT on the walls, at 1280×800 through `cutaway render`, with a lung window, a
/// bone window, and the structure colours (`--display color`) that say which structure each
/// wall pixel belongs to. With the lung window the lungs are darker than the soft tissue; with
/// the bone window the vertebrae and ribs are brighter than the soft tissue, the lungs black.
#[test]
fn chest_ct_on_the_walls_with_lung_and_bone_windows() {
    let Some(chest) = chest_dir() else { return };
    if renderer().is_none() {
        return;
    }
    let out = out_dir();
    let plane = |x: f64| {
        serde_json::json!([
            [x, 200, -90],
            [x, -100, -90],
            [x, -100, -290],
            [x, 200, -290]
        ])
    };
    let planes = serde_json::json!([plane(150.0), plane(0.0), plane(-150.0)]);
    let cutters: Vec<serde_json::Value> = [0, 2, 3, 4, 5, 6]
        .iter()
        .map(|t| serde_json::json!({"target": t, "kind": "straight", "planes": planes}))
        .collect();
    let mut pictures = Vec::new();
    for (name, window, display) in [
        ("lung", [-600.0, 1500.0], "image"),
        ("bone", [400.0, 1800.0], "image"),
        ("structures", [400.0, 1800.0], "color"),
    ] {
        let session = serde_json::json!({
            "format": "cutaway-session/2",
            "models": [{"path": chest.join("Segmentation.seg.nrrd")}],
            "cutters": cutters,
            "camera": {"eye": [160, 720, -20], "target": [0, 0, -190], "up": [0, 0, 1], "fov_y_deg": 30},
            "image": {"path": chest.join("CTChest4.nrrd"), "window": window}
        });
        let path = out.join(format!("chest_{name}.json"));
        std::fs::write(&path, serde_json::to_string_pretty(&session).unwrap()).unwrap();
        let png = out.join(format!("chest_{name}.png"));
        let status = std::process::Command::new(env!("CARGO_BIN_EXE_cutaway"))
            .args(["render"])
            .arg(&path)
            .arg("--out")
            .arg(&png)
            .args(["--display", display])
            .status()
            .unwrap();
        assert!(status.success(), "cutaway render {name}");
        let picture = image::open(&png).unwrap().to_rgba8();
        assert_eq!(picture.dimensions(), (1280, 800));
        pictures.push(picture);
    }
    // Which structure each wall pixel shows, from its structure colour: the lungs are green and
    // pink, bone tan (red over green over blue), soft tissue grey-green.
    let mut classes: [Vec<(u32, u32)>; 3] = Default::default();
    let (lung, bone, tissue) = (0, 1, 2);
    for y in 220..690 {
        for x in 340..940 {
            let [r, g, b, _] = pictures[2].get_pixel(x, y).0.map(i32::from);
            if r + g + b < 200 || r.min(g).min(b) > 245 {
                continue; // contour lines, background
            }
            let class = if g > r + 30 || (r > g + 40 && b >= g - 10) {
                lung
            } else if r > g + 5 && g > b + 25 {
                bone
            } else if g >= r {
                tissue
            } else {
                continue;
            };
            classes[class].push((x, y));
        }
    }
    let mean_grey = |picture: &image::RgbaImage, class: usize| {
        let greys: Vec<f64> = classes[class]
            .iter()
            .map(|&(x, y)| picture.get_pixel(x, y).0)
            .filter(|p| {
                (p[0] as i32 - p[1] as i32).abs() <= 2 && (p[1] as i32 - p[2] as i32).abs() <= 2
            })
            .map(|p| p[0] as f64 / 255.0)
            .collect();
        assert!(
            greys.len() * 4 > classes[class].len() * 3,
            "wall pixels without the image"
        );
        greys.iter().sum::<f64>() / greys.len() as f64
    };
    let counts = classes.each_ref().map(Vec::len);
    println!(
        "wall pixels: {} lung, {} bone, {} soft tissue",
        counts[0], counts[1], counts[2]
    );
    assert!(
        counts[lung] > 20_000 && counts[bone] > 5_000 && counts[tissue] > 50_000,
        "{counts:?}"
    );
    let [l, b] = [0, 1].map(|w| [lung, bone, tissue].map(|c| mean_grey(&pictures[w], c)));
    println!(
        "lung window grey: lung {:.3}, bone {:.3}, tissue {:.3}",
        l[0], l[1], l[2]
    );
    println!(
        "bone window grey: lung {:.3}, bone {:.3}, tissue {:.3}",
        b[0], b[1], b[2]
    );
    assert!(
        l[lung] < l[tissue] - 0.25,
        "lung window: lungs not dark: {l:?}"
    );
    assert!(
        b[bone] > b[tissue] + 0.08,
        "bone window: bone not bright: {b:?}"
    );
    assert!(
        b[lung] < 0.05 && b[bone] > b[lung] + 0.3,
        "bone window: {b:?}"
    );
}

/// The glTF export bakes the image into the walls' vertex colours: every coloured vertex on the
/// back wall has the grey of the ramp there (linear light, as glTF stores it).
#[test]
fn gltf_walls_carry_the_image_as_vertex_colours() {
    let scene = cube_scene(ras_image(0.5, |p| ramp(p) as f32), WINDOW);
    let (bytes, summary) = cutaway::export::glb_of_scene(&scene).unwrap();
    assert!(summary.exact, "{:?}", summary.notes);
    let gltf = gltf::Gltf::from_slice(&bytes).unwrap();
    let blob = gltf.blob.clone().expect("a BIN chunk");
    let mut checked = 0;
    for mesh in gltf.meshes() {
        for primitive in mesh.primitives() {
            let reader = primitive.reader(|_| Some(&blob));
            let Some(colors) = reader.read_colors(0) else {
                continue;
            };
            assert_eq!(primitive.material().name(), Some("image"));
            let positions: Vec<[f32; 3]> = reader.read_positions().unwrap().collect();
            let colors: Vec<[f32; 4]> = colors.into_rgba_f32().collect();
            assert_eq!(positions.len(), colors.len());
            for (p, c) in positions.iter().zip(&colors) {
                if (p[1] - 5.0).abs() > 1e-4 {
                    continue;
                }
                let grey = WINDOW.map(ramp(DVec3::new(p[0] as f64, 5.0, p[2] as f64)));
                let linear = if grey <= 0.04045 {
                    grey / 12.92
                } else {
                    ((grey + 0.055) / 1.055).powf(2.4)
                };
                assert!(
                    (c[0] as f64 - linear).abs() < 1e-3,
                    "{p:?}: {c:?} vs {linear}"
                );
                checked += 1;
            }
        }
    }
    assert!(checked >= 100, "{checked} baked vertices on the back wall");
}

/// A volume whose values are not labels is described by `info` as an intensity image (type,
/// value range, grid, the reason), for a synthetic CT and for the real chest CT.
#[test]
fn info_of_a_ct_says_it_is_an_intensity_image() {
    let dir = out_dir();
    let ct = dir.join("info_ct.nrrd");
    let mut bytes = b"NRRD0004\ntype: short\ndimension: 3\nspace: RAS\nsizes: 4 3 2\nspace directions: (2,0,0) (0,1,0) (0,0,1)\nendian: little\nencoding: raw\nspace origin: (0,0,0)\n\n".to_vec();
    for v in 0..24i16 {
        bytes.extend_from_slice(&(v * 100 - 1000).to_le_bytes());
    }
    std::fs::write(&ct, bytes).unwrap();
    let mut files = vec![ct];
    if let Some(chest) = chest_dir() {
        files.push(chest.join("CTChest4.nrrd"));
    }
    for file in &files {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_cutaway"))
            .arg("info")
            .arg(file)
            .arg("--json")
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        let intensity = &json["intensity"];
        println!("{}: {intensity}", file.display());
        assert!(
            intensity["reason"]
                .as_str()
                .unwrap()
                .starts_with("negative"),
            "{json}"
        );
        assert!(intensity["min"].as_f64().unwrap() <= -1000.0, "{json}");
        assert!(intensity["max"].as_f64().unwrap() > 0.0, "{json}");
        assert_eq!(json["triangles"], 0);
        assert!(json.get("labels").is_none());
        let text = std::process::Command::new(env!("CARGO_BIN_EXE_cutaway"))
            .arg("info")
            .arg(file)
            .output()
            .unwrap();
        let text = String::from_utf8_lossy(&text.stdout);
        assert!(text.contains("intensity image (negative"), "{text}");
    }
    let json: serde_json::Value = serde_json::from_slice(
        &std::process::Command::new(env!("CARGO_BIN_EXE_cutaway"))
            .arg("info")
            .arg(&files[0])
            .arg("--json")
            .output()
            .unwrap()
            .stdout,
    )
    .unwrap();
    assert_eq!(json["intensity"]["type"], "int16");
    assert_eq!(json["dims"], serde_json::json!([4, 3, 2]));
    assert_eq!(json["spacing"], serde_json::json!([2.0, 1.0, 1.0]));
    assert_eq!(json["bbox_min"], serde_json::json!([-1.0, -0.5, -0.5]));
}

/// An image wider than the device's 3-D texture limit is not dropped: it is drawn at reduced
/// resolution (the ramp along x still shows on the wall) and `render` has a message for it.
#[test]
fn an_image_over_the_texture_limit_is_shown_reduced() {
    let Some(mut r) = renderer() else { return };
    let limit = r.max_texture_dimension_3d() as usize;
    if limit > 16384 {
        return skip(
            Resource::Gpu,
            format!("the 3-D texture limit {limit} is too large for a small test image"),
        );
    }
    let n = limit + 1;
    let dx = 12.0 / (n - 1) as f64;
    let m = DAffine3::from_mat3_translation(
        DMat3::from_diagonal(DVec3::new(dx, 1.0, 1.0)),
        DVec3::splat(-1.0),
    );
    let image = IntensityImage::from_fn([n, 13, 13], m, |p| ramp(p) as f32);
    let notice = cutaway::io::intensity::fit::notice(&image, limit).expect("over the limit");
    println!("{notice}");
    assert!(notice.contains(&format!("exceeds the GPU's 3-D texture limit {limit}")));
    assert!(notice.contains("half resolution"), "{notice}");
    let scene = cube_scene(image, WINDOW);
    let picture = render(&mut r, &scene, "ramp_over_texture_limit");
    assert_follows(&picture, &ramp, "ramp over the texture limit", true);
}
