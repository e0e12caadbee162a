//! End-to-end tests of `cutaway subtract` (contract in `../shared/CONTRACT.md`), and cuts of the
//! real anatomy through the library (no panic, exact kept/removed area partition).

use csg::testkit::{Resource, skip};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::Command;

use csg::{DVec3, Mesh};

fn cutaway() -> Command {
    Command::new(env!("CARGO_BIN_EXE_cutaway"))
}

/// A fresh scratch folder for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("cutaway-subtract-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A box as an OBJ of quads (the form `cutaway extrude` writes), outward.
fn write_quad_box(path: &Path, min: DVec3, max: DVec3) {
    let mut s = String::new();
    for k in 0..8 {
        let x = if k & 1 != 0 { max.x } else { min.x };
        let y = if k & 2 != 0 { max.y } else { min.y };
        let z = if k & 4 != 0 { max.z } else { min.z };
        s += &format!("v {x:?} {y:?} {z:?}\n");
    }
    for q in [
        [0, 4, 6, 2],
        [1, 3, 7, 5],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 2, 3, 1],
        [4, 5, 7, 6],
    ] {
        s += &format!("f {} {} {} {}\n", q[0] + 1, q[1] + 1, q[2] + 1, q[3] + 1);
    }
    std::fs::write(path, s).unwrap();
}

fn weld(m: &Mesh) -> Mesh {
    let mut map: HashMap<[u64; 3], u32> = HashMap::new();
    let mut positions = Vec::new();
    let remap: Vec<u32> = m
        .positions
        .iter()
        .map(|p| {
            *map.entry(p.to_array().map(f64::to_bits))
                .or_insert_with(|| {
                    positions.push(*p);
                    (positions.len() - 1) as u32
                })
        })
        .collect();
    Mesh {
        positions,
        triangles: m
            .triangles
            .iter()
            .map(|t| t.map(|i| remap[i as usize]))
            .collect(),
    }
}

/// Every directed edge once, with its opposite once.
fn closed_oriented(m: &Mesh) -> bool {
    let m = weld(m);
    let mut directed: HashMap<(u32, u32), u32> = HashMap::new();
    for t in &m.triangles {
        for k in 0..3 {
            *directed.entry((t[k], t[(k + 1) % 3])).or_default() += 1;
        }
    }
    directed
        .iter()
        .all(|(&(a, b), &n)| n == 1 && directed.get(&(b, a)) == Some(&1))
}

#[test]
fn subtract_writes_the_four_files_and_the_json() {
    let dir = scratch("files");
    let target = dir.join("sphere.obj");
    cutaway::io::write_mesh(&target, &csg::testkit::icosphere(3, 10.0)).unwrap();
    let cutter = dir.join("box.obj");
    write_quad_box(
        &cutter,
        DVec3::new(-3.0, -3.0, 4.0),
        DVec3::new(3.0, 3.0, 20.0),
    );
    let out_dir = dir.join("out");
    let out = cutaway()
        .args(["subtract"])
        .arg(&target)
        .arg(&cutter)
        .arg("--out")
        .arg(&out_dir)
        .arg("--json")
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    for key in [
        "target_triangles",
        "cutter_triangles",
        "kept_triangles",
        "walls_triangles",
        "removed_triangles",
        "contour_loops",
    ] {
        assert!(json[key].is_u64(), "{key} missing in {json}");
    }
    assert!(json["boolean_ms"].is_f64());
    assert_eq!(json["target_triangles"], 1280);
    assert_eq!(json["cutter_triangles"], 12);
    assert_eq!(json["contour_loops"], 1);
    let kept = cutaway::io::read_mesh(&out_dir.join("kept.obj")).unwrap();
    let walls = cutaway::io::read_mesh(&out_dir.join("walls.obj")).unwrap();
    let removed = cutaway::io::read_mesh(&out_dir.join("removed.obj")).unwrap();
    assert_eq!(json["kept_triangles"], kept.triangles.len());
    assert_eq!(json["walls_triangles"], walls.triangles.len());
    assert_eq!(json["removed_triangles"], removed.triangles.len());
    // The files weld bit for bit along the contour: kept + walls and removed + reversed walls
    // are closed and consistently oriented.
    let mut kw = kept.clone();
    kw.append(&walls);
    assert!(closed_oriented(&kw));
    let mut rw = removed.clone();
    rw.append(&walls.reversed());
    assert!(closed_oriented(&rw));
    let (at, ak, ar) = (
        csg::testkit::icosphere(3, 10.0).area(),
        kept.area(),
        removed.area(),
    );
    assert!(((ak + ar) - at).abs() < 1e-9 * at);
    let contour = std::fs::read_to_string(out_dir.join("contour.obj")).unwrap();
    assert!(contour.lines().any(|l| l.starts_with("l ")));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn open_cutter_is_one_error_line_naming_the_file() {
    let dir = scratch("open");
    let target = dir.join("sphere.obj");
    cutaway::io::write_mesh(&target, &csg::testkit::icosphere(2, 1.0)).unwrap();
    let cutter = dir.join("open.obj");
    std::fs::write(
        &cutter,
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\n",
    )
    .unwrap();
    let out = cutaway()
        .args(["subtract"])
        .arg(&target)
        .arg(&cutter)
        .arg("--out")
        .arg(dir.join("out"))
        .arg("--json")
        .output()
        .unwrap();
    assert!(!out.status.success());
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.starts_with("error: "), "{stderr}");
    assert!(
        stderr.contains("open.obj") && stderr.contains("not closed"),
        "{stderr}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Runs `cutaway subtract TARGET CUTTER --out OUT` with extra environment variables.
fn run_subtract(
    target: &Path,
    cutter: &Path,
    out: &Path,
    env: &[(&str, &str)],
) -> std::process::Output {
    let mut command = cutaway();
    command
        .args(["subtract"])
        .arg(target)
        .arg(cutter)
        .arg("--out")
        .arg(out);
    for (k, v) in env {
        command.env(k, v);
    }
    command.output().unwrap()
}

/// Every entry under `dir` (relative paths, sorted) with its bytes; folders as `None`.
fn tree(dir: &Path) -> Vec<(String, Option<Vec<u8>>)> {
    fn walk(root: &Path, dir: &Path, out: &mut Vec<(String, Option<Vec<u8>>)>) {
        for entry in std::fs::read_dir(dir).unwrap().flatten() {
            let path = entry.path();
            let relative = path.strip_prefix(root).unwrap().display().to_string();
            if path.is_dir() {
                out.push((relative, None));
                walk(root, &path, out);
            } else {
                out.push((relative, Some(std::fs::read(&path).unwrap())));
            }
        }
    }
    let mut out = Vec::new();
    walk(dir, dir, &mut out);
    out.sort();
    out
}

/// `subtract`'s four outputs are one set: a run killed between the renames of the new set leaves
/// a commit that the next look at the folder finishes, so the folder then holds exactly the new
/// set and nothing else; without a kill the old set is replaced whole.
#[test]
fn outputs_are_replaced_as_a_set_even_when_killed_between_renames() {
    let dir = scratch("set");
    let target = dir.join("sphere.obj");
    cutaway::io::write_mesh(&target, &csg::testkit::icosphere(3, 10.0)).unwrap();
    let (small, large) = (dir.join("small.obj"), dir.join("large.obj"));
    write_quad_box(
        &small,
        DVec3::new(-3.0, -3.0, 4.0),
        DVec3::new(3.0, 3.0, 20.0),
    );
    write_quad_box(
        &large,
        DVec3::new(-6.0, -6.0, 2.0),
        DVec3::new(6.0, 6.0, 20.0),
    );
    // The two reference sets, each written by an undisturbed run.
    let (old_ref, new_ref) = (dir.join("old_ref"), dir.join("new_ref"));
    assert!(
        run_subtract(&target, &small, &old_ref, &[])
            .status
            .success()
    );
    assert!(
        run_subtract(&target, &large, &new_ref, &[])
            .status
            .success()
    );
    let (old_set, new_set) = (tree(&old_ref), tree(&new_ref));
    assert_eq!(old_set.len(), 4);
    assert_ne!(old_set, new_set);
    // Replaced whole.
    let out = dir.join("out");
    assert!(run_subtract(&target, &small, &out, &[]).status.success());
    assert!(run_subtract(&target, &large, &out, &[]).status.success());
    assert_eq!(tree(&out), new_set);
    // Killed after k of the 4 renames (0: right after the commit marker).
    for k in 0..4 {
        let out = dir.join(format!("killed-{k}"));
        assert!(run_subtract(&target, &small, &out, &[]).status.success());
        let killed = run_subtract(
            &target,
            &large,
            &out,
            &[("CUTAWAY_TEST_KILL_AFTER_RENAMES", &k.to_string())],
        );
        assert!(
            !killed.status.success(),
            "the test hook did not stop run {k}"
        );
        assert_ne!(tree(&out), new_set, "nothing to recover after {k} renames?");
        cutaway::io::recover_output_set(&out).unwrap();
        assert_eq!(tree(&out), new_set, "after a kill after {k} renames");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A cutter identical to the target: every face is coplanar with a cutter face, and the rule for
/// coplanar faces decides (the cutter is translated by δ = (ε, ε², ε³)). The target faces whose
/// normal's first non-zero component is negative lie outside the translated cutter and are kept,
/// the others are removed; the walls are the cutter's faces against the kept ones, so kept + walls
/// is a double layer of zero volume (the two sides may be triangulated differently) and removed +
/// reversed walls is the whole solid, closed.
#[test]
fn a_cutter_identical_to_the_target_leaves_a_zero_volume_double_layer() {
    let cube = csg::testkit::cube(DVec3::ZERO, DVec3::ONE);
    let index = csg::TargetIndex::build(cube.clone()).unwrap();
    let result = csg::subtract(&index, &cube).unwrap();
    let kept = result.kept_mesh(index.mesh());
    let walls = result.walls.mesh.clone();
    let removed = result.removed.part().mesh.clone();
    let first_nonzero_negative = |m: &Mesh, t: usize| {
        let n = m.face_normal_scaled(t);
        let c = [n.x, n.y, n.z].into_iter().find(|c| *c != 0.0).unwrap();
        c < 0.0
    };
    assert!(kept.triangle_count() > 0 && removed.triangle_count() > 0);
    assert!((0..kept.triangle_count()).all(|t| first_nonzero_negative(&kept, t)));
    assert!((0..removed.triangle_count()).all(|t| !first_nonzero_negative(&removed, t)));
    assert_eq!(kept.area() + removed.area(), cube.area());
    assert_eq!(kept.area(), 3.0);
    let mut layer = kept.clone();
    layer.append(&walls);
    let mut solid = removed.clone();
    solid.append(&walls.reversed());
    assert_eq!(walls.area(), kept.area());
    assert_eq!(layer.volume(), 0.0);
    assert!(closed_oriented(&solid));
    assert_eq!(solid.volume(), cube.volume());
}

/// The anatomy folder: `CUTAWAY_ANATOMY`, else `../shared/anatomy` next to the workspace.
fn anatomy_dir() -> Option<PathBuf> {
    if let Ok(p) = std::env::var("CUTAWAY_ANATOMY") {
        let p = PathBuf::from(p);
        let p = if p.is_relative() {
            Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join(p)
        } else {
            p
        };
        return p.is_dir().then_some(p);
    }
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/anatomy");
    p.is_dir().then_some(p)
}

fn mesh_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    let mut entries: Vec<PathBuf> = entries.filter_map(|e| e.ok().map(|e| e.path())).collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            mesh_files(&p, out);
        } else if matches!(
            p.extension()
                .and_then(|e| e.to_str())
                .map(str::to_ascii_lowercase)
                .as_deref(),
            Some("obj" | "stl" | "ply" | "vtk")
        ) {
            out.push(p);
        }
    }
}

/// Cuts every anatomy mesh with a box through the middle of its bounding box and with a thin
/// tilted slab: no panic, and kept + removed cover exactly the target surface.
#[test]
fn cuts_every_anatomy_mesh() {
    let Some(dir) = anatomy_dir() else {
        return skip(Resource::Data, "no anatomy folder (set CUTAWAY_ANATOMY)");
    };
    let mut files = Vec::new();
    mesh_files(&dir, &mut files);
    assert!(!files.is_empty());
    let mut cuts = 0;
    let (mut tri_fallbacks, mut status_fallbacks) = (0, 0);
    for file in &files {
        let Ok(mesh) = cutaway::io::read_mesh(file) else {
            continue; // unreadable files are the formats tests' business
        };
        if mesh.triangles.is_empty() {
            continue;
        }
        let bbox = mesh.bbox();
        let (c, s) = (bbox.center(), bbox.size());
        let index = csg::TargetIndex::build(mesh.clone()).unwrap();
        let area = mesh.area();
        // A box around the centre, a third of the size, and a slab through it.
        let boxes = [
            csg::testkit::cube(c - s / 6.0, c + s / 6.0),
            csg::testkit::cube(
                bbox.min - s * 0.1
                    + DVec3::new(0.0, s.y * 0.1 + c.y - bbox.min.y - s.y * 0.01, 0.0),
                bbox.max + s * 0.1
                    - DVec3::new(0.0, s.y * 0.1 + bbox.max.y - c.y - s.y * 0.013, 0.0),
            ),
        ];
        for cutter in &boxes {
            let r =
                csg::subtract(&index, cutter).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
            let kept = r.materialize(&mesh).area();
            let removed = r.removed.mesh.area();
            assert!(
                (kept + removed - area).abs() <= 1e-9 * area,
                "{}: area {kept} + {removed} != {area}",
                file.display()
            );
            tri_fallbacks += r.stats.triangulation_fallbacks;
            status_fallbacks += r.stats.status_fallbacks;
            cuts += 1;
        }
    }
    eprintln!(
        "{cuts} anatomy cuts; triangulation fallbacks {tri_fallbacks}, status fallbacks {status_fallbacks}"
    );
    assert!(cuts > 0);
}

/// Writes `parts` into one OBJ (one file, several shells).
fn write_joined(path: &Path, parts: &[Mesh]) {
    let mut m = Mesh::default();
    for p in parts {
        m.append(p);
    }
    cutaway::io::write_mesh(path, &m).unwrap();
}

/// Runs `cutaway subtract TARGET CUTTER --out OUT --json` and returns its JSON.
fn subtract_json(target: &Path, cutter: &Path, out_dir: &Path) -> serde_json::Value {
    let out = cutaway()
        .args(["subtract"])
        .arg(target)
        .arg(cutter)
        .arg("--out")
        .arg(out_dir)
        .arg("--json")
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

/// A cube of side 10 with a cube of side 4 inside, cut by a slab 3 thick crossing both. Both
/// outward: two solids, each cut closed, with its own files and JSON entry. The inner one
/// inward: one hollow solid, no per-region output.
#[test]
fn nested_cubes_are_cut_per_region() {
    let dir = scratch("nested");
    let outer = csg::testkit::cube(DVec3::ZERO, DVec3::splat(10.0));
    let inner = csg::testkit::cube(DVec3::splat(3.0), DVec3::splat(7.0));
    let cutter = dir.join("slab.obj");
    write_quad_box(
        &cutter,
        DVec3::new(3.5, -1.0, -1.0),
        DVec3::new(6.5, 11.0, 11.0),
    );

    let target = dir.join("nested.obj");
    write_joined(&target, &[outer.clone(), inner.clone()]);
    let out_dir = dir.join("out");
    let json = subtract_json(&target, &cutter, &out_dir);
    let (cut, materialize, total) = (
        json["cut_ms"].as_f64().unwrap(),
        json["materialize_ms"].as_f64().unwrap(),
        json["boolean_ms"].as_f64().unwrap(),
    );
    assert!(cut >= 0.0 && materialize >= 0.0);
    assert!((cut + materialize - total).abs() <= 1e-9 * total.max(1.0));
    let walls = cutaway::io::read_mesh(&out_dir.join("walls.obj")).unwrap();
    assert!((walls.area() - 232.0).abs() < 1e-9, "{}", walls.area());
    let regions = json["regions"].as_array().expect("regions in the JSON");
    assert_eq!(regions.len(), 2);
    for (i, (region, (walls_area, removed_volume))) in regions
        .iter()
        .zip([(200.0, 300.0), (32.0, 48.0)])
        .enumerate()
    {
        assert_eq!(region["index"], i);
        assert_eq!(region["closed"], true);
        let v = region["removed_volume"].as_f64().unwrap();
        assert!((v - removed_volume).abs() < 1e-9, "region {i}: {v}");
        let folder = out_dir.join("regions").join(i.to_string());
        let read = |name: &str| cutaway::io::read_mesh(&folder.join(name)).unwrap();
        let (kept, walls, removed) = (read("kept.obj"), read("walls.obj"), read("removed.obj"));
        assert_eq!(region["kept_triangles"], kept.triangles.len());
        assert_eq!(region["walls_triangles"], walls.triangles.len());
        assert_eq!(region["removed_triangles"], removed.triangles.len());
        assert!((walls.area() - walls_area).abs() < 1e-9, "region {i}");
        let mut kw = kept.clone();
        kw.append(&walls);
        assert!(closed_oriented(&kw), "region {i}: kept + walls");
        let mut rw = removed.clone();
        rw.append(&walls.reversed());
        assert!(closed_oriented(&rw), "region {i}: removed + reversed walls");
    }

    let hollow = dir.join("hollow.obj");
    write_joined(&hollow, &[outer, inner.reversed()]);
    let out_dir = dir.join("out-hollow");
    let json = subtract_json(&hollow, &cutter, &out_dir);
    assert!(json.get("regions").is_none(), "{json}");
    assert!(!out_dir.join("regions").exists());
    let kept = cutaway::io::read_mesh(&out_dir.join("kept.obj")).unwrap();
    let walls = cutaway::io::read_mesh(&out_dir.join("walls.obj")).unwrap();
    assert!((walls.area() - 168.0).abs() < 1e-9, "{}", walls.area());
    let mut kw = kept;
    kw.append(&walls);
    assert!(closed_oriented(&kw));
    let _ = std::fs::remove_dir_all(&dir);
}

/// The SPL brain atlas structures with the skin around them, as one target: nested closed
/// surfaces (brain structures inside the skin, ventricles inside the hemispheres' space). A box
/// through the middle of the head crosses several; every region is cut as its own solid, so
/// each one's kept + walls and removed + reversed walls close up and its volume identity holds
/// (`cutcheck::check_closed_cut` checks both per region).
#[test]
fn spl_atlas_with_skin_is_cut_closed_per_region() {
    let Some(dir) = anatomy_dir() else {
        return skip(Resource::Data, "no anatomy folder (set CUTAWAY_ANATOMY)");
    };
    let folder = dir.join("head_brain_spl_atlas");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&folder)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "vtk"))
        .collect();
    files.sort();
    assert!(files.len() >= 30, "{} files", files.len());
    // The closed structures (the contract's closed case; a few atlas surfaces are open).
    let mut target = Mesh::default();
    let mut used = Vec::new();
    for f in &files {
        let mesh = cutaway::io::read_mesh(f).unwrap();
        if mesh.report().closed {
            target.append(&mesh);
            used.push(f.file_name().unwrap().to_string_lossy().to_string());
        }
    }
    assert!(used.len() >= 20, "{used:?}");
    assert!(used.iter().any(|n| n.starts_with("skin")), "{used:?}");
    let index = csg::TargetIndex::build(target.clone()).unwrap();
    assert!(index.is_closed());
    let bbox = target.bbox();
    let (c, s) = (bbox.center(), bbox.size());
    // A box from the centre towards +x (the right side) and up: ventricles, nuclei, skin.
    let cutter = csg::testkit::cube(
        c - DVec3::new(0.05, 0.2, 0.05) * s,
        c + DVec3::new(0.6, 0.2, 0.6) * s,
    );
    let options = csg::CutOptions::default().with_merge_coincident(false);
    let result = csg::subtract_with(&index, &[&cutter], &options).unwrap();
    csg::cutcheck::check_closed_cut(&target, &result).unwrap();
    let parts = result.region_parts(&index);
    let cut_regions = parts
        .iter()
        .filter(|p| !p.walls.is_empty() && !p.kept.is_empty())
        .count();
    assert!(cut_regions >= 4, "only {cut_regions} regions crossed");
    // Nested solids: the skin's walls alone already cover the cut through the head, the
    // structures inside add their own.
    let skin_walls = parts.iter().map(|p| p.walls.area()).fold(0.0f64, f64::max);
    assert!(result.walls.mesh.area() > skin_walls);
    eprintln!(
        "{} regions, {cut_regions} crossed, walls {} triangles",
        index.regions.count,
        result.walls.mesh.triangles.len()
    );
}
