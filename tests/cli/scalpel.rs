//! End-to-end tests of `cutaway scalpel` (CONTRACT.md: `cutaway-path/1` and its JSON).

use csg::testkit::{Resource, skip};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

mod walls;

fn cutaway() -> Command {
    Command::new(env!("CARGO_BIN_EXE_cutaway"))
}

fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("scalpel-{name}-{}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Writes an OBJ of an `n × n` unit grid on z = 0 (an open sheet).
fn write_sheet(path: &Path, n: u32) {
    let mut s = String::new();
    for j in 0..=n {
        for i in 0..=n {
            writeln!(s, "v {i} {j} 0").unwrap();
        }
    }
    let id = |i: u32, j: u32| j * (n + 1) + i + 1;
    for j in 0..n {
        for i in 0..n {
            writeln!(s, "f {} {} {}", id(i, j), id(i + 1, j), id(i + 1, j + 1)).unwrap();
            writeln!(s, "f {} {} {}", id(i, j), id(i + 1, j + 1), id(i, j + 1)).unwrap();
        }
    }
    std::fs::write(path, s).unwrap();
}

fn write_sphere(path: &Path) {
    let m = csg::testkit::icosphere(3, 10.0);
    let mut s = String::new();
    for p in &m.positions {
        writeln!(s, "v {} {} {}", p.x, p.y, p.z).unwrap();
    }
    for t in &m.triangles {
        writeln!(s, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1).unwrap();
    }
    std::fs::write(path, s).unwrap();
}

fn run_json(target: &Path, path: &Path, out: &Path) -> serde_json::Value {
    let o = cutaway()
        .arg("scalpel")
        .arg(target)
        .arg("--path")
        .arg(path)
        .arg("--out")
        .arg(out)
        .arg("--json")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{stderr}");
    let stdout = String::from_utf8(o.stdout).unwrap();
    assert_eq!(stdout.lines().count(), 1, "{stdout}");
    serde_json::from_str(&stdout).unwrap()
}

fn face_count(obj: &Path) -> usize {
    std::fs::read_to_string(obj)
        .unwrap()
        .lines()
        .filter(|l| l.starts_with("f "))
        .count()
}

fn assert_one_error_line(out: &Output, file: &Path, needle: &str) {
    assert!(!out.status.success());
    let stderr = String::from_utf8(out.stderr.clone()).unwrap();
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.starts_with(&format!("error: {}: ", file.display())),
        "{stderr}"
    );
    assert!(stderr.contains(needle), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
}

#[test]
fn slit_on_a_sheet_reports_the_contract_json() {
    let dir = scratch("slit");
    let (target, path, out) = (
        dir.join("sheet.obj"),
        dir.join("p.json"),
        dir.join("out.obj"),
    );
    write_sheet(&target, 20);
    let points: Vec<[f64; 3]> = (0..=30)
        .map(|i| [3.3 + 0.4 * i as f64, 5.4 + 0.1 * i as f64, 0.0])
        .collect();
    let json = serde_json::json!({"format": "cutaway-path/1", "depth": 0.0, "tool": "scalpel", "points": points});
    std::fs::write(&path, json.to_string()).unwrap();
    let v = run_json(&target, &path, &out);
    assert_eq!(v["steps"], 31);
    assert_eq!(v["closed"], false);
    assert_eq!(v["manifold"], true);
    let created = v["triangles_created"].as_u64().unwrap();
    let cut = v["triangles_cut"].as_u64().unwrap();
    assert!(cut > 10 && created > 10, "{v}");
    assert!(created <= 2 * cut + 4, "{v}");
    assert!(v["step_us_p50"].as_f64().unwrap() > 0.0);
    assert!(v["step_us_max"].as_f64().unwrap() >= v["step_us_p50"].as_f64().unwrap());
    let first = v["step_us_first"].as_f64().unwrap();
    assert!(
        first > 0.0 && first <= v["step_us_max"].as_f64().unwrap(),
        "{v}"
    );
    assert_eq!(face_count(&out), 800 + created as usize);
    for key in [
        "steps",
        "triangles_cut",
        "triangles_created",
        "step_us_p50",
        "step_us_max",
        "step_us_first",
        "open_us_p50",
        "open_us_max",
        "closed",
        "manifold",
    ] {
        assert!(v.get(key).is_some(), "missing {key}");
    }
    assert_eq!(v.as_object().unwrap().len(), 10);
}

/// The distances from the drawn line (each point moved onto `before`, the surface it was drawn
/// on) to the surface in `after`, leaving out points within `margin` of the path's ends: about
/// zero where the cut is shut, about half the opening where it opened.
fn gaps_along_path(
    before: &csg::Mesh,
    after: &csg::Mesh,
    points: &[[f64; 3]],
    margin: f64,
) -> Vec<f64> {
    let (on_before, on_after) = (
        csg::SpatialIndex::build(before),
        csg::SpatialIndex::build(after),
    );
    let on_surface: Vec<csg::DVec3> = points
        .iter()
        .map(|&p| on_before.closest_point(before, p.into()).unwrap().point)
        .collect();
    let (first, last) = (on_surface[0], on_surface[on_surface.len() - 1]);
    on_surface
        .iter()
        .filter(|p| p.distance(first) >= margin && p.distance(last) >= margin)
        .map(|&p| on_after.closest_point(after, p).unwrap().point.distance(p))
        .collect()
}

/// A groove drawn on a sphere and opened 1 mm wide: the output, read back, is closed and has
/// left the drawn line (the lips apart) along the path away from its ends, while the same groove
/// cut shut (`open` width 0) still passes through it: the measure tells the two apart.
#[test]
fn groove_on_a_sphere_stays_closed_and_opens() {
    let dir = scratch("groove");
    let target = dir.join("sphere.obj");
    write_sphere(&target);
    let sphere = cutaway::io::read_mesh(&target).unwrap();
    let points: Vec<[f64; 3]> = (0..=30)
        .map(|i| {
            let a = 0.2 + 1.0 * i as f64 / 30.0;
            [10.0 * a.cos(), 10.0 * a.sin(), 0.0]
        })
        .collect();
    let width = 1.0;
    let mut means = Vec::new();
    for open in [0.0, width] {
        let (path, out) = (
            dir.join(format!("p{open}.json")),
            dir.join(format!("out{open}.obj")),
        );
        let json = serde_json::json!({"format": "cutaway-path/1", "depth": 1.0, "tool": "scalpel",
            "points": points, "open": {"width": open, "window": 0.5}});
        std::fs::write(&path, json.to_string()).unwrap();
        let v = run_json(&target, &path, &out);
        assert_eq!(v["closed"], true, "{v}");
        assert_eq!(v["manifold"], true, "{v}");
        assert!(v["triangles_created"].as_u64().unwrap() > 0);
        // As written: a shut groove's two lips are coincident copies, which welding would join.
        let cut = cutaway::io::read_mesh_verbatim(&out).unwrap();
        let report = cut.report();
        assert!(
            report.closed,
            "open {open}: the output read back is not closed: {report:?}"
        );
        let gaps = gaps_along_path(&sphere, &cut, &points, 2.0 * width);
        assert!(gaps.len() >= 15, "{gaps:?}");
        let mean = gaps.iter().sum::<f64>() / gaps.len() as f64;
        println!(
            "open {open}: mean gap {mean:.3} mm over {} points",
            gaps.len()
        );
        if open > 0.0 {
            let close = gaps.iter().filter(|&&g| g < 0.15 * width).count();
            assert!(
                6 * close <= gaps.len(),
                "the opened surface passes within 0.15 widths of the cut at {close} of {} points: {gaps:?}",
                gaps.len()
            );
            assert!(mean >= 0.2 * width, "mean gap {mean} mm: {gaps:?}");
        }
        means.push(mean);
    }
    assert!(
        means[0] < 0.02 * width,
        "the shut groove is open: mean gap {}",
        means[0]
    );
}

/// The connected pieces of a mesh file as written (no welding: a cut loop leaves its two sides
/// on vertices of their own), with the area of each.
fn pieces(path: &Path) -> Vec<f64> {
    let mesh = cutaway::io::read_mesh_verbatim(path).unwrap();
    let regions = csg::regions::Regions::components(&mesh, &csg::EdgeAdjacency::build(&mesh));
    let mut areas = vec![0.0; regions.count];
    for (t, &r) in mesh.triangles.iter().zip(&regions.region_of_triangle) {
        let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
        areas[r as usize] += 0.5 * (b - a).cross(c - a).length();
    }
    areas
}

#[test]
fn strokes_cross_and_loop_detaches() {
    let dir = scratch("strokes");
    let (target, path, out) = (
        dir.join("sheet.obj"),
        dir.join("p.json"),
        dir.join("out.obj"),
    );
    write_sheet(&target, 20);
    let a: Vec<[f64; 3]> = (0..=20)
        .map(|i| [4.3 + 0.6 * i as f64, 10.5, 0.0])
        .collect();
    let b: Vec<[f64; 3]> = (0..=20)
        .map(|i| [10.1, 4.3 + 0.6 * i as f64, 0.0])
        .collect();
    let json = serde_json::json!({"format": "cutaway-path/1", "strokes": [a, b]});
    std::fs::write(&path, json.to_string()).unwrap();
    let v = run_json(&target, &path, &out);
    assert_eq!(v["steps"], 42);
    assert_eq!(v["manifold"], true);
    // Two crossing slits open the sheet but cut nothing off: one piece, all of its area.
    let areas = pieces(&out);
    assert_eq!(areas.len(), 1, "crossing slits: pieces of areas {areas:?}");
    assert!((areas[0] - 400.0).abs() < 1e-6, "{areas:?}");

    let circle: Vec<[f64; 3]> = (0..40)
        .map(|i| {
            let t = i as f64 / 40.0 * std::f64::consts::TAU;
            [10.2 + 4.0 * t.cos(), 9.7 + 4.0 * t.sin(), 0.0]
        })
        .collect();
    let json = serde_json::json!({"format": "cutaway-path/1", "tool": "loop", "points": circle});
    std::fs::write(&path, json.to_string()).unwrap();
    let v = run_json(&target, &path, &out);
    assert_eq!(v["steps"], 40);
    assert_eq!(v["manifold"], true);
    // The loop cuts out the disc it encloses: two pieces, the disc with about the area of the
    // drawn 40-gon (radius 4; measured 49.19 of its 50.06: the cut runs through the sheet's
    // triangles near, not exactly on, the drawn corners) and the sheet with the rest of the
    // 20 × 20.
    let mut areas = pieces(&out);
    areas.sort_by(f64::total_cmp);
    let disc = 0.5 * 40.0 * 16.0 * (std::f64::consts::TAU / 40.0).sin();
    assert_eq!(areas.len(), 2, "the loop: pieces of areas {areas:?}");
    assert!(
        (areas[0] - disc).abs() < 0.03 * disc,
        "disc {areas:?}, expected {disc}"
    );
    assert!(
        (areas[0] + areas[1] - 400.0).abs() < 1e-9 * 400.0,
        "{areas:?}"
    );
}

#[test]
fn bad_path_files_and_off_mesh_points_are_one_line_errors() {
    let dir = scratch("errors");
    let (target, path, out) = (
        dir.join("sheet.obj"),
        dir.join("p.json"),
        dir.join("out.obj"),
    );
    write_sheet(&target, 6);
    let run = || {
        cutaway()
            .arg("scalpel")
            .arg(&target)
            .arg("--path")
            .arg(&path)
            .arg("--out")
            .arg(&out)
            .arg("--json")
            .output()
            .unwrap()
    };
    std::fs::write(&path, r#"{"format":"cutaway-path/9","points":[[1,1,0]]}"#).unwrap();
    assert_one_error_line(&run(), &path, "cutaway-path/1");
    std::fs::write(&path, "not json").unwrap();
    assert_one_error_line(&run(), &path, "cutaway-path/1");
    std::fs::write(
        &path,
        r#"{"format":"cutaway-path/1","points":[[100,100,0],[1,1,0]]}"#,
    )
    .unwrap();
    assert_one_error_line(&run(), &path, "off the mesh");
    std::fs::write(
        &path,
        r#"{"format":"cutaway-path/1","points":[[1,1,0],[2,2,30]]}"#,
    )
    .unwrap();
    assert_one_error_line(&run(), &path, "off the mesh");
    assert!(!out.exists(), "nothing written on error");
}

/// A session camera looking at one mesh (up +Z, 30° vertical field of view) and the image size.
struct View {
    eye: [f64; 3],
    look_at: [f64; 3],
    size: (u32, u32),
}

impl View {
    /// `cutaway render` of `mesh` (loaded `exact` when given) from this view, written to
    /// `stem`.png (its session to `stem`.json); `None`, after saying so, when there is no GPU
    /// adapter.
    fn render(&self, mesh: &Path, exact: Option<bool>, stem: &Path) -> Option<image::RgbImage> {
        let mut model = serde_json::json!({"path": mesh, "color": [0.9, 0.75, 0.65]});
        if let Some(exact) = exact {
            model["exact"] = exact.into();
        }
        let s = serde_json::json!({"format": "cutaway-session/1", "models": [model],
            "camera": {"eye": self.eye, "target": self.look_at, "up": [0, 0, 1], "fov_y_deg": 30}});
        let (session, png) = (stem.with_extension("json"), stem.with_extension("png"));
        std::fs::write(&session, s.to_string()).unwrap();
        let (w, h) = self.size;
        let o = cutaway()
            .arg("render")
            .arg(&session)
            .arg("--out")
            .arg(&png)
            .args(["--width", &w.to_string(), "--height", &h.to_string()])
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        if !o.status.success() && err.contains("adapter") {
            skip(Resource::Gpu, format!("no GPU adapter ({err})"));
            return None;
        }
        assert!(o.status.success(), "render: {err}");
        Some(image::open(&png).unwrap().to_rgb8())
    }

    /// The pixel a point lands on (the session camera's perspective: right-handed look-at,
    /// vertical field of view).
    fn pixel(&self, p: [f64; 3]) -> (f64, f64) {
        let (e, t) = (csg::DVec3::from(self.eye), csg::DVec3::from(self.look_at));
        let f = (t - e).normalize();
        let r = f.cross(csg::DVec3::Z).normalize();
        let u = r.cross(f);
        let k = (15.0f64).to_radians().tan();
        let d = csg::DVec3::from(p) - e;
        let (x, y, z) = (d.dot(r), d.dot(u), d.dot(f));
        let (w, h) = (self.size.0 as f64, self.size.1 as f64);
        (
            (x / (z * k * w / h) + 1.0) / 2.0 * w,
            (1.0 - y / (z * k)) / 2.0 * h,
        )
    }
}

fn patella() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/knee/patella.ply")
}

/// Samples of a gentle arc on the patella's anterior face (-y), millimetres: the front-most
/// vertex near each (x, z).
fn patella_arc(mesh: &csg::Mesh) -> Vec<[f64; 3]> {
    (0..=40)
        .map(|i| {
            let u = i as f64 / 40.0;
            let (x, z) = (-12.0 + 24.0 * u, 33.0 + 4.0 * (3.1 * u).sin());
            let front = mesh
                .positions
                .iter()
                .filter(|p| (p.x - x).abs() < 1.5 && (p.z - z).abs() < 1.5)
                .min_by(|a, b| a.y.total_cmp(&b.y))
                .unwrap();
            [x, front.y, z]
        })
        .collect()
}

/// A groove drawn across the knee's patella (millimetres, the anterior face) and opened 2 mm
/// wide: along the whole path, away from its ends, the opened surface has left the line the
/// blade drew (the two lips moved apart, the groove between them), and the mesh is closed. The
/// opening used to move both lips of a groove one way along most of such a path (the surface
/// stayed shut there) and tear it elsewhere.
#[test]
fn groove_on_the_patella_opens_along_its_whole_path() {
    let dir = scratch("patella");
    let target = patella();
    let (path, out) = (dir.join("p.json"), dir.join("out.ply"));
    let mesh = cutaway::io::read_mesh(&target).unwrap();
    let points = patella_arc(&mesh);
    let width = 2.0;
    let json = serde_json::json!({"format": "cutaway-path/1", "depth": 3.0, "tool": "scalpel",
        "points": points, "open": {"width": width, "window": 0.5}});
    std::fs::write(&path, json.to_string()).unwrap();
    let v = run_json(&target, &path, &out);
    assert_eq!(v["closed"], true, "{v}");
    assert_eq!(v["manifold"], true, "{v}");
    let opened = cutaway::io::read_mesh(&out).unwrap();
    let (before, after) = (
        csg::SpatialIndex::build(&mesh),
        csg::SpatialIndex::build(&opened),
    );
    let on_surface: Vec<csg::DVec3> = points
        .iter()
        .map(|&p| before.closest_point(&mesh, p.into()).unwrap().point)
        .collect();
    let (first, last) = (on_surface[0], on_surface[on_surface.len() - 1]);
    // The lips follow mesh edges, which kink up to about half an edge (0.4 mm here) away from
    // the drawn line in places; there a lip passes closer to it. A shut groove passes at 0.
    let mut gaps = Vec::new();
    for &p in &on_surface {
        if p.distance(first) < 2.0 * width || p.distance(last) < 2.0 * width {
            continue;
        }
        gaps.push(after.closest_point(&opened, p).unwrap().point.distance(p));
    }
    assert!(gaps.len() >= 20, "{gaps:?}");
    let close = gaps.iter().filter(|&&g| g < 0.15 * width).count();
    assert!(
        6 * close <= gaps.len(),
        "the opened surface passes within 0.15 widths of the cut at {close} of {} points: {gaps:?}",
        gaps.len()
    );
    let mean = gaps.iter().sum::<f64>() / gaps.len() as f64;
    assert!(mean >= 0.2 * width, "mean gap {mean} mm: {gaps:?}");
}

/// The opened groove on the patella as the user sees it, at 1280×800 (`cutaway render`, lavapipe
/// when there is no GPU): the same groove cut shut (`open` width 0) and opened 2 mm wide, both
/// rendered from in front of the knee. Measured: around every drawn point away from the ends
/// (two widths), the opened image differs from the shut one (the lips apart, the walls and the
/// floor between them: mean difference over a 25×25 pixel window, about a millimetre, above 5 of
/// 255 at nine points in ten or more; measured 6 to 36, lowest where the walls face the light as
/// the surface does), and more than 200 pixels (about 9 mm, beyond the opening's 6 mm support)
/// from the drawn path the two images are the same pixel for pixel (the opening moves nothing
/// else). The images are left in the test's scratch folder to look at.
#[test]
fn opened_groove_on_the_patella_shows_along_its_whole_path_at_1280x800() {
    let dir = scratch("patella-image");
    let target = patella();
    let mesh = cutaway::io::read_mesh(&target).unwrap();
    let points = patella_arc(&mesh);
    let (w, h) = (1280u32, 800u32);
    let (eye, look_at) = ([0.0, -110.0, 36.0], [0.0, -44.0, 35.0]);
    let mut images = Vec::new();
    for width in [0.0, 2.0] {
        let path = dir.join(format!("p{width}.json"));
        let out = dir.join(format!("cut{width}.ply"));
        let json = serde_json::json!({"format": "cutaway-path/1", "depth": 3.0, "tool": "scalpel",
            "points": points, "open": {"width": width, "window": 0.5}});
        std::fs::write(&path, json.to_string()).unwrap();
        run_json(&target, &path, &out);
        let view = View {
            eye,
            look_at,
            size: (w, h),
        };
        let Some(image) = view.render(&out, None, &dir.join(format!("groove{width}"))) else {
            return;
        };
        images.push(image);
    }
    let (shut, open) = (&images[0], &images[1]);
    let view = View {
        eye,
        look_at,
        size: (w, h),
    };
    let pixel = |p: [f64; 3]| view.pixel(p);
    let drawn: Vec<(f64, f64)> = points.iter().map(|&p| pixel(p)).collect();
    let (first, last) = (points[0], points[points.len() - 1]);
    let dist = |a: [f64; 3], b: [f64; 3]| csg::DVec3::from(a).distance(csg::DVec3::from(b));
    let (mut shown, mut inner) = (0, 0);
    for (&p, &(px, py)) in points.iter().zip(&drawn) {
        if dist(p, first) < 4.0 || dist(p, last) < 4.0 {
            continue;
        }
        inner += 1;
        let (mut sum, mut n) = (0.0, 0.0);
        for y in (py as i64 - 12)..=(py as i64 + 12) {
            for x in (px as i64 - 12)..=(px as i64 + 12) {
                let (a, b) = (
                    shut.get_pixel(x as u32, y as u32),
                    open.get_pixel(x as u32, y as u32),
                );
                sum += (0..3)
                    .map(|c| (a[c] as f64 - b[c] as f64).abs())
                    .sum::<f64>()
                    / 3.0;
                n += 1.0;
            }
        }
        if sum / n > 5.0 {
            shown += 1;
        }
    }
    assert!(inner >= 20, "{inner} points");
    assert!(
        10 * shown >= 9 * inner,
        "the opening shows at {shown} of {inner} drawn points"
    );
    let mut far_differs = 0;
    for (x, y, a) in shut.enumerate_pixels() {
        let near = drawn
            .iter()
            .any(|&(px, py)| (px - x as f64).hypot(py - y as f64) <= 200.0);
        if !near && a != open.get_pixel(x, y) {
            far_differs += 1;
        }
    }
    assert_eq!(far_differs, 0, "pixels far from the cut changed");
}

/// The vertices and triangles of a binary PLY as `cutaway scalpel` writes it (double x, y, z;
/// triangles), read verbatim: no welding, so a shut groove's coincident lip copies stay apart
/// and the opened and shut outputs correspond vertex for vertex.
fn read_ply_verbatim(path: &Path) -> (Vec<csg::DVec3>, Vec<[usize; 3]>) {
    let bytes = std::fs::read(path).unwrap();
    let end = b"end_header\n";
    let at = bytes.windows(end.len()).position(|w| w == end).unwrap() + end.len();
    let header = std::str::from_utf8(&bytes[..at]).unwrap();
    assert!(header.contains("property double x"), "{header}");
    let count = |what: &str| -> usize {
        let line = header.lines().find(|l| l.starts_with(what)).unwrap();
        line.split_whitespace().last().unwrap().parse().unwrap()
    };
    let (nv, nf) = (count("element vertex"), count("element face"));
    let f64_at = |o: usize| f64::from_le_bytes(bytes[o..o + 8].try_into().unwrap());
    let positions = (0..nv)
        .map(|i| {
            csg::DVec3::new(
                f64_at(at + 24 * i),
                f64_at(at + 24 * i + 8),
                f64_at(at + 24 * i + 16),
            )
        })
        .collect();
    let mut o = at + 24 * nv;
    // A face is its three indices, and its wall mark when the file marks walls.
    let record = if header.contains("property uchar cutaway_wall") {
        14
    } else {
        13
    };
    let mut triangles = Vec::with_capacity(nf);
    for _ in 0..nf {
        assert_eq!(bytes[o], 3);
        let i = |k: usize| {
            u32::from_le_bytes(bytes[o + 1 + 4 * k..o + 5 + 4 * k].try_into().unwrap()) as usize
        };
        triangles.push([i(0), i(1), i(2)]);
        o += record;
    }
    (positions, triangles)
}

/// The groove on the patella with its samples on the surface (as the window's ray picks are),
/// cut shut and opened 2 mm wide: the two outputs are the same mesh vertex for vertex, and no
/// surface triangle (all its corners on the knee's surface: not a groove wall) turns more than
/// 60° from the shut one as the groove opens (a folded triangle showed as a shard or a crack).
#[test]
fn opened_groove_on_the_patella_folds_no_surface_triangle() {
    let dir = scratch("patella-fold");
    let target = patella();
    let mesh = cutaway::io::read_mesh(&target).unwrap();
    let index = csg::SpatialIndex::build(&mesh);
    let points: Vec<[f64; 3]> = patella_arc(&mesh)
        .iter()
        .map(|&p| {
            index
                .closest_point(&mesh, p.into())
                .unwrap()
                .point
                .to_array()
        })
        .collect();
    let mut outputs = Vec::new();
    for width in [0.0, 2.0] {
        let (path, out) = (
            dir.join(format!("p{width}.json")),
            dir.join(format!("o{width}.ply")),
        );
        let json = serde_json::json!({"format": "cutaway-path/1", "depth": 3.0, "tool": "scalpel",
            "points": points, "open": {"width": width, "window": 0.5}});
        std::fs::write(&path, json.to_string()).unwrap();
        let v = run_json(&target, &path, &out);
        assert_eq!(v["closed"], true, "{v}");
        outputs.push(read_ply_verbatim(&out));
    }
    let ((shut, tris), (opened, tris2)) = (&outputs[0], &outputs[1]);
    assert_eq!(tris, tris2, "the opening changes positions only");
    assert_eq!(shut.len(), opened.len());
    let moved = (0..shut.len()).filter(|&v| shut[v] != opened[v]).count();
    assert!(moved >= 50, "only {moved} vertices moved");
    let on_surface =
        |p: csg::DVec3| index.closest_point(&mesh, p).unwrap().point.distance(p) < 0.05;
    let (mut checked, mut worst) = (0, 0.0f64);
    for t in tris {
        if t.iter().all(|&v| shut[v] == opened[v]) || !t.iter().all(|&v| on_surface(shut[v])) {
            continue;
        }
        let normal = |p: &[csg::DVec3]| (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]);
        let (a, b) = (normal(shut), normal(opened));
        if a.length() == 0.0 {
            continue;
        }
        let turn = if b.length() == 0.0 {
            180.0
        } else {
            a.angle_between(b).to_degrees()
        };
        worst = worst.max(turn);
        checked += 1;
    }
    println!("{checked} opened surface triangles, largest turn {worst:.1}°");
    assert!(checked >= 100, "only {checked} surface triangles moved");
    assert!(
        worst <= 60.0,
        "a surface triangle turned {worst:.1}° as the groove opened"
    );
}

/// `--json` reports the opening's share of the steps: positive on a groove opened 2 mm wide
/// on the patella, each at most its step's time; 0 with the same strokes and no `"open"`.
#[test]
fn json_reports_the_openings_share_of_the_steps() {
    let dir = scratch("open-us");
    let target = patella();
    let mesh = cutaway::io::read_mesh(&target).unwrap();
    let points = patella_arc(&mesh);
    let out = dir.join("out.ply");
    let mut figures = Vec::new();
    for open in [true, false] {
        let mut json = serde_json::json!({"format": "cutaway-path/1", "depth": 3.0,
            "tool": "scalpel", "points": points});
        if open {
            json["open"] = serde_json::json!({"width": 2.0, "window": 0.5});
        }
        let path = dir.join(format!("p{open}.json"));
        std::fs::write(&path, json.to_string()).unwrap();
        let v = run_json(&target, &path, &out);
        let f = |k: &str| v[k].as_f64().unwrap_or_else(|| panic!("no {k} in {v}"));
        assert!(f("open_us_p50") <= f("open_us_max"), "{v}");
        assert!(f("open_us_max") <= f("step_us_max"), "{v}");
        figures.push((f("open_us_p50"), f("open_us_max")));
    }
    assert!(figures[0].0 > 0.0 && figures[0].1 > 0.0, "{figures:?}");
    assert_eq!(figures[1], (0.0, 0.0));
}
