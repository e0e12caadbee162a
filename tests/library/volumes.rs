//! Segmentation label volumes end to end: the real volumes of the anatomy folder open with the
//! labels, names and colours their files hold; `info`, `surfaces` and `subtract` accept them; bad
//! volume files are one-line errors.
//!
//! The real volumes are under `$CUTAWAY_ANATOMY/volumes` (else `../shared/anatomy` beside the
//! workspace); tests that need them print why and skip when the folder is absent.

use csg::testkit::{Resource, skip};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use cutaway::io::volume::{LabelVolume, read_volume};

fn cutaway() -> Command {
    Command::new(env!("CARGO_BIN_EXE_cutaway"))
}

fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("volumes-{name}-{}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The `volumes` folder of the anatomy data, or why it is missing.
pub(crate) fn volumes() -> Option<PathBuf> {
    let root = std::env::var_os("CUTAWAY_ANATOMY")
        .map(PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/anatomy"));
    let root = if root.is_relative() {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join(root)
    } else {
        root
    };
    let dir = root.join("volumes");
    if dir.is_dir() {
        Some(dir)
    } else {
        skip(
            Resource::Data,
            format!(
                "no anatomy volumes at {} (set CUTAWAY_ANATOMY)",
                dir.display()
            ),
        );
        None
    }
}

/// `value name r g b a` lines of a colour table, as plain text parsing (independent of the
/// reader under test).
fn table(path: &Path) -> BTreeMap<u32, (String, [u8; 3])> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .filter(|l| !l.trim().is_empty() && !l.starts_with('#'))
        .map(|l| {
            let w: Vec<&str> = l.split_whitespace().collect();
            let c = |i: usize| w[i].parse::<u8>().unwrap();
            (w[0].parse().unwrap(), (w[1].to_owned(), [c(2), c(3), c(4)]))
        })
        .collect()
}

fn structures(volume: &LabelVolume) -> Vec<(u32, String, [u8; 3])> {
    volume
        .structures
        .iter()
        .map(|s| (s.value, s.name.clone(), s.color))
        .collect()
}

#[test]
fn spl_atlas_has_its_312_labels_named_by_its_colour_table() {
    let Some(dir) = volumes() else { return };
    let volume = read_volume(&dir.join("spl_head_atlas/hncma-atlas.nrrd"), None).unwrap();
    assert_eq!(volume.dims, [256, 256, 256]);
    assert_eq!(volume.spacing(), [1.0, 1.0, 1.0]);
    assert_eq!(volume.structures.len(), 312);
    let lut = table(&dir.join("spl_head_atlas/hncma-atlas-lut.ctbl"));
    for s in &volume.structures {
        match lut.get(&s.value) {
            Some((name, color)) => assert_eq!((&s.name, s.color), (name, *color)),
            None => assert_eq!(s.name, format!("label {}", s.value)),
        }
    }
    // Label 1 is a single voxel the table does not name; skin (3) is listed but absent.
    assert_eq!(
        (volume.structures[0].value, volume.structures[0].voxels),
        (1, 1)
    );
    assert_eq!(volume.structures[0].name, "label 1");
    assert!(volume.structures.iter().all(|s| s.value != 3));
    // LPS with permuted axes: voxel (0,0,0) sits at LPS (-128,-128,128), RAS (128,128,128).
    let corner = volume.world_from_voxel.transform_point3(glam::DVec3::ZERO);
    assert_eq!(corner.to_array(), [128.0, 128.0, 128.0]);
}

#[test]
fn slicer_segmentations_hold_names_colours_and_layers() {
    let Some(dir) = volumes() else { return };
    let chest = dir.join("slicerio_chest");
    let expected = table(&dir.join("nifti_chest/chest_labels.txt"));
    let plain = read_volume(&chest.join("Segmentation.seg.nrrd"), None).unwrap();
    assert_eq!(plain.dims, [128, 128, 34]);
    let got = structures(&plain);
    assert_eq!(got.len(), 7);
    for (value, name, color) in &got {
        let (table_name, table_color) = &expected[value];
        assert_eq!(name.replace(' ', "_"), *table_name);
        assert_eq!(color, table_color);
    }
    assert_eq!(got[0].1, "ribs");

    let layered = read_volume(&chest.join("SegmentationOverlapping.seg.nrrd"), None).unwrap();
    assert_eq!(layered.layers.len(), 2);
    let names: Vec<(u32, usize, &str)> = layered
        .structures
        .iter()
        .map(|s| (s.value, s.layer, s.name.as_str()))
        .collect();
    assert_eq!(names.len(), 8, "{names:?}");
    assert!(names.contains(&(1, 0, "ribs")), "{names:?}");
    assert!(names.contains(&(1, 1, "overlapping sphere")), "{names:?}");
    let sphere = layered.structures.iter().find(|s| s.layer == 1).unwrap();
    assert_eq!(sphere.color, [220, 245, 20]);
    // The sphere overlaps other segments: its voxels are counted on its own layer.
    assert!(sphere.voxels > 1000, "{}", sphere.voxels);
}

#[test]
fn nifti_and_mask_folder_match_the_segmentation_they_were_made_from() {
    let Some(dir) = volumes() else { return };
    let seg = read_volume(&dir.join("slicerio_chest/Segmentation.seg.nrrd"), None).unwrap();
    let nifti = read_volume(&dir.join("nifti_chest/chest_labels.nii.gz"), None).unwrap();
    let masks = read_volume(&dir.join("nifti_chest/per_structure"), None).unwrap();
    let lut = table(&dir.join("nifti_chest/chest_labels.txt"));
    assert_eq!(nifti.dims, seg.dims);
    assert_eq!(masks.dims, seg.dims);
    for (a, b) in seg.structures.iter().zip(&nifti.structures) {
        assert_eq!((a.value, a.voxels), (b.value, b.voxels));
        assert_eq!((&b.name, b.color), (&lut[&b.value].0, lut[&b.value].1));
    }
    // LPS in the NRRD, RAS in the NIfTI: the same world matrix once both are RAS (the NIfTI
    // stores f32).
    let (a, b) = (
        seg.world_from_voxel.to_cols_array(),
        nifti.world_from_voxel.to_cols_array(),
    );
    for (x, y) in a.iter().zip(&b) {
        assert!((x - y).abs() < 1e-4, "{a:?} vs {b:?}");
    }
    // One mask per structure, named after its file, with the voxels of that label.
    assert_eq!(masks.structures.len(), 7);
    assert_eq!(masks.layers.len(), 1, "the chest masks do not overlap");
    for mask in &masks.structures {
        let label = nifti
            .structures
            .iter()
            .find(|s| s.name == mask.name)
            .unwrap();
        assert_eq!(mask.voxels, label.voxels, "{}", mask.name);
    }
}

#[test]
fn seg_nrrd_and_nifti_give_the_same_surfaces() {
    let Some(dir) = volumes() else { return };
    let seg = read_volume(&dir.join("slicerio_chest/Segmentation.seg.nrrd"), None).unwrap();
    let nifti = read_volume(&dir.join("nifti_chest/chest_labels.nii.gz"), None).unwrap();
    let a = cutaway::io::volume::surfaces(&seg, None, &|_| true).unwrap();
    let b = cutaway::io::volume::surfaces(&nifti, None, &|_| true).unwrap();
    assert_eq!(a.len(), 7);
    for (x, y) in a.iter().zip(&b) {
        let (rx, ry) = (x.mesh.report(), y.mesh.report());
        assert!(rx.closed && rx.manifold && ry.closed && ry.manifold);
        assert_eq!(x.mesh.triangles.len(), y.mesh.triangles.len());
        let (vx, vy) = (x.mesh.volume(), y.mesh.volume());
        assert!(vx > 0.0 && (vx - vy).abs() < 1e-4 * vx, "{vx} vs {vy}");
        let (bx, by) = (x.mesh.bbox(), y.mesh.bbox());
        assert!(bx.min.distance(by.min) < 1e-3 && bx.max.distance(by.max) < 1e-3);
    }
}

fn run_json(args: &[&std::ffi::OsStr]) -> serde_json::Value {
    let out = cutaway().args(args).output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{args:?}: {stderr}");
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert_eq!(stdout.lines().count(), 1, "{stdout}");
    serde_json::from_str(&stdout).unwrap()
}

/// The object's keys, sorted (serde_json's map does not keep the order; the order printed is
/// checked by the unit tests of the report structs).
fn keys(value: &serde_json::Value) -> Vec<&str> {
    value
        .as_object()
        .unwrap()
        .keys()
        .map(String::as_str)
        .collect()
}

fn sorted<const N: usize>(mut names: [&str; N]) -> [&str; N] {
    names.sort();
    names
}

#[test]
fn surfaces_writes_one_closed_named_mesh_per_label() {
    let Some(dir) = volumes() else { return };
    let out = scratch("surfaces");
    // An earlier, larger run (another format too) and a file of the user's in the folder: the
    // earlier surfaces are replaced as a whole, the user's file stays.
    std::fs::create_dir_all(&out).unwrap();
    for stale in ["99_old_structure.obj", "3_thoracic_vertebral_column.ply"] {
        std::fs::write(out.join(stale), "stale").unwrap();
    }
    std::fs::write(out.join("notes.txt"), "mine").unwrap();
    let volume = dir.join("slicerio_chest/Segmentation.seg.nrrd");
    let json = run_json(&[
        "surfaces".as_ref(),
        volume.as_os_str(),
        "--out".as_ref(),
        out.as_os_str(),
        "--format".as_ref(),
        "obj".as_ref(),
        "--json".as_ref(),
    ]);
    assert_eq!(keys(&json), sorted(["labels", "surfaces_ms", "surfaces"]));
    assert_eq!(json["labels"], 7);
    assert!(json["surfaces_ms"].as_f64().unwrap() > 0.0);
    let entries = json["surfaces"].as_array().unwrap();
    assert_eq!(
        keys(&entries[0]),
        sorted([
            "value",
            "name",
            "color",
            "voxels",
            "triangles",
            "closed",
            "volume",
            "file"
        ])
    );
    let mut names: Vec<String> = Vec::new();
    for entry in entries {
        let file = PathBuf::from(entry["file"].as_str().unwrap());
        assert_eq!(file.parent().unwrap(), out);
        names.push(file.file_name().unwrap().to_string_lossy().into_owned());
        let mesh = cutaway::io::read_mesh(&file).unwrap();
        let report = mesh.report();
        assert!(report.closed && report.manifold, "{}", file.display());
        assert_eq!(entry["closed"], true);
        assert_eq!(
            entry["triangles"].as_u64().unwrap() as usize,
            mesh.triangles.len()
        );
        let volume = entry["volume"].as_f64().unwrap();
        assert!(volume > 0.0 && (mesh.volume() - volume).abs() < 1e-9 * volume);
    }
    assert_eq!(
        names,
        [
            "1_ribs.obj",
            "2_cervical_vertebral_column.obj",
            "3_thoracic_vertebral_column.obj",
            "4_lumbar_vertebral_column.obj",
            "5_right_lung.obj",
            "6_left_lung.obj",
            "7_tissue.obj"
        ]
    );
    assert_eq!(entries[4]["color"], serde_json::json!([22, 197, 71]));
    // Nothing but the named files and the user's is left in the folder (no temporary files,
    // nothing of the earlier run).
    let mut left: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    left.sort();
    names.push("notes.txt".into());
    assert_eq!(left, names);
    std::fs::remove_dir_all(&out).ok();
}

#[test]
fn surfaces_decimate_keeps_a_fraction_of_closed_triangles() {
    let Some(dir) = volumes() else { return };
    let volume = dir.join("slicerio_chest/Segmentation.seg.nrrd");
    let run = |name: &str, extra: &[&str]| {
        let out = scratch(name);
        let mut args: Vec<&std::ffi::OsStr> = vec![
            "surfaces".as_ref(),
            volume.as_os_str(),
            "--out".as_ref(),
            out.as_os_str(),
            "--json".as_ref(),
        ];
        args.extend(extra.iter().map(std::ffi::OsStr::new));
        let json = run_json(&args);
        std::fs::remove_dir_all(&out).ok();
        json
    };
    let full = run("decimate_full", &[]);
    let quarter = run("decimate_quarter", &["--decimate", "0.25"]);
    let (full, quarter) = (
        full["surfaces"].as_array().unwrap(),
        quarter["surfaces"].as_array().unwrap(),
    );
    assert_eq!(full.len(), quarter.len());
    for (f, q) in full.iter().zip(quarter) {
        let (nf, nq) = (
            f["triangles"].as_u64().unwrap(),
            q["triangles"].as_u64().unwrap(),
        );
        assert!(nq * 10 <= nf * 3, "{}: {nq} of {nf} triangles", q["name"]);
        assert_eq!(q["closed"], true);
        // Quadric placement does not preserve volume: thin tubes (the ribs, a few voxels
        // across) lose about a quarter of theirs at a quarter of the triangles (measured 27 %).
        let (vf, vq) = (f["volume"].as_f64().unwrap(), q["volume"].as_f64().unwrap());
        assert!(
            (vq - vf).abs() < 0.35 * vf,
            "{}: volume {vq} vs {vf}",
            q["name"]
        );
    }
    // A fraction outside 0 < F <= 1 is one error line.
    for bad in ["0", "1.5", "nan"] {
        let out = cutaway()
            .args(["surfaces".as_ref(), volume.as_os_str(), "--out".as_ref()])
            .arg(scratch("decimate_bad"))
            .args(["--decimate", bad])
            .output()
            .unwrap();
        assert!(!out.status.success(), "--decimate {bad}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(err.trim().lines().count(), 1, "{err}");
        assert!(err.contains("--decimate"), "{err}");
    }
}

#[test]
fn info_on_a_volume_adds_grid_and_labels_to_the_mesh_fields() {
    let Some(dir) = volumes() else { return };
    let volume = dir.join("nifti_chest/chest_labels.nii.gz");
    let json = run_json(&["info".as_ref(), volume.as_os_str(), "--json".as_ref()]);
    assert_eq!(
        keys(&json),
        sorted([
            "vertices",
            "triangles",
            "regions",
            "closed",
            "manifold",
            "bbox_min",
            "bbox_max",
            "volume",
            "dims",
            "spacing",
            "labels"
        ])
    );
    assert_eq!(json["dims"], serde_json::json!([128, 128, 34]));
    assert_eq!(json["closed"], true);
    let spacing: Vec<f64> = serde_json::from_value(json["spacing"].clone()).unwrap();
    assert!(
        (spacing[0] - 3.046_875_9).abs() < 1e-6 && spacing[2] == 10.0,
        "{spacing:?}"
    );
    let labels = json["labels"].as_array().unwrap();
    assert_eq!(labels.len(), 7);
    assert_eq!(
        labels[0],
        serde_json::json!({"value": 1, "name": "ribs", "color": [253, 232, 158], "voxels": labels[0]["voxels"]})
    );
    assert!(labels[0]["voxels"].as_u64().unwrap() > 0);
    // The same structures as a folder of masks, surfaced mask by mask: the same grid, every
    // label's voxels (named after its file), the same surfaces in all.
    let folder = dir.join("nifti_chest/per_structure");
    let masks = run_json(&["info".as_ref(), folder.as_os_str(), "--json".as_ref()]);
    assert_eq!(masks["dims"], json["dims"]);
    assert_eq!(masks["spacing"], json["spacing"]);
    for key in ["triangles", "vertices", "regions", "closed", "manifold"] {
        assert_eq!(masks[key], json[key], "{key}");
    }
    let mut voxels: Vec<(String, u64)> = labels
        .iter()
        .map(|l| {
            (
                l["name"].as_str().unwrap().to_owned(),
                l["voxels"].as_u64().unwrap(),
            )
        })
        .collect();
    let mut mask_voxels: Vec<(String, u64)> = masks["labels"]
        .as_array()
        .unwrap()
        .iter()
        .map(|l| {
            (
                l["name"].as_str().unwrap().to_owned(),
                l["voxels"].as_u64().unwrap(),
            )
        })
        .collect();
    voxels.sort();
    mask_voxels.sort();
    assert_eq!(mask_voxels, voxels);
}

/// A closed cube OBJ (outward).
fn cube_obj(path: &Path, min: [f64; 3], max: [f64; 3]) {
    let mut text = String::new();
    for k in 0..8 {
        let p = [0, 1, 2].map(|a| if k >> a & 1 == 1 { max[a] } else { min[a] });
        text += &format!("v {} {} {}\n", p[0], p[1], p[2]);
    }
    for f in [
        [1, 3, 4, 2],
        [5, 6, 8, 7],
        [1, 2, 6, 5],
        [3, 7, 8, 4],
        [1, 5, 7, 3],
        [2, 4, 8, 6],
    ] {
        text += &format!("f {} {} {} {}\n", f[0], f[1], f[2], f[3]);
    }
    std::fs::write(path, text).unwrap();
}

/// `kept` + `walls` of a cut, welded: closed when the cut is exact on a closed target.
fn assert_kept_and_walls_closed(kept: &csg::Mesh, walls: &csg::Mesh, what: &str) {
    let mut closed = kept.clone();
    closed.append(walls);
    let closed = csg::weld::weld_exact(&closed);
    let report = closed.report();
    assert!(
        report.closed && report.manifold,
        "{what}: kept + walls not closed: {report:?}"
    );
    assert!(closed.volume() > 0.0, "{what}");
}

#[test]
fn subtract_cuts_a_volume_target_exactly() {
    let out = scratch("subtract");
    // Two labels apart from each other (so welding kept + walls cannot join them): a 6³ box
    // (value 3) and a 4×6×4 bar (value 7) in a 16³ LPS volume with 0.75 mm voxels.
    let mut samples = vec![0u8; 16 * 16 * 16];
    for k in 0..16 {
        for j in 0..16 {
            for i in 0..16 {
                let v = if (2..8).contains(&i) && (2..8).contains(&j) && (2..8).contains(&k) {
                    3
                } else if (10..14).contains(&i) && (5..11).contains(&j) && (6..10).contains(&k) {
                    7
                } else {
                    0
                };
                samples[i + 16 * (j + 16 * k)] = v;
            }
        }
    }
    let header = HEADER.replace(
        "(1,0,0) (0,1,0) (0,0,1)",
        "(0.75,0,0) (0,0.75,0) (0,0,0.75)",
    );
    let target = out.join("two.nrrd");
    std::fs::write(&target, [header.as_bytes(), &gzip(&samples)].concat()).unwrap();
    let cutter = out.join("cutter.obj");
    // RAS: voxel (i,j,k) is at (-0.75 i, -0.75 j, 0.75 k); cut through the middle of both labels.
    cube_obj(&cutter, [-20.0, -5.6, 3.1], [1.0, 1.0, 20.0]);
    let json = run_json(&[
        "subtract".as_ref(),
        target.as_os_str(),
        cutter.as_os_str(),
        "--out".as_ref(),
        out.as_os_str(),
        "--json".as_ref(),
    ]);
    assert!(json["walls_triangles"].as_u64().unwrap() > 0, "{json}");
    assert!(json["removed_triangles"].as_u64().unwrap() > 0, "{json}");
    let kept = cutaway::io::read_mesh_verbatim(&out.join("kept.obj")).unwrap();
    let walls = cutaway::io::read_mesh_verbatim(&out.join("walls.obj")).unwrap();
    assert_kept_and_walls_closed(&kept, &walls, "two-label volume");
    std::fs::remove_dir_all(&out).ok();
}

#[test]
fn every_chest_label_cuts_exactly() {
    let Some(dir) = volumes() else { return };
    let parts = cutaway::io::read_parts(&dir.join("nifti_chest/chest_labels.nii.gz")).unwrap();
    assert_eq!(parts.len(), 7);
    assert_eq!(parts[0].name, "ribs");
    assert_eq!(
        parts[0].color,
        Some([253.0 / 255.0, 232.0 / 255.0, 158.0 / 255.0])
    );
    let mut all = csg::Mesh::default();
    for part in &parts {
        all.append(&part.mesh);
    }
    let bbox = all.bbox();
    let mid = (bbox.min + bbox.max) * 0.5;
    let cutter = {
        let out = scratch("cutter");
        let path = out.join("cutter.obj");
        cube_obj(
            &path,
            [bbox.min.x - 1.0, mid.y + 0.123, mid.z - 40.3],
            [mid.x + 0.377, bbox.max.y + 1.0, mid.z + 41.1],
        );
        let mesh = cutaway::io::read_mesh(&path).unwrap();
        std::fs::remove_dir_all(&out).ok();
        mesh
    };
    for part in &parts {
        let index = csg::TargetIndex::build(part.mesh.clone()).unwrap();
        let result = csg::subtract(&index, &cutter).unwrap();
        let kept = result.kept_mesh(index.mesh());
        assert_kept_and_walls_closed(&kept, &result.walls.mesh, &part.name);
    }
}

// ---------------------------------------------------------------------------------------------
// Malformed volumes: each is one error line naming the file, exit code not 0, no panic.

fn assert_one_error_line(out: &Output, file: &Path) -> String {
    assert!(!out.status.success());
    let stderr = String::from_utf8(out.stderr.clone()).unwrap();
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.starts_with(&format!("error: {}: ", file.display())),
        "{stderr}"
    );
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(out.stdout.is_empty());
    stderr
}

fn gzip(bytes: &[u8]) -> Vec<u8> {
    use std::io::Write as _;
    let mut e = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
    e.write_all(bytes).unwrap();
    e.finish().unwrap()
}

/// A 16×16×16 NRRD header (`sizes`, `type`, `encoding`, geometry replaceable by the caller).
const HEADER: &str = "NRRD0004\ntype: unsigned char\ndimension: 3\nspace: left-posterior-superior\nsizes: 16 16 16\nspace directions: (1,0,0) (0,1,0) (0,0,1)\nendian: little\nencoding: gzip\nspace origin: (0,0,0)\n\n";

fn labels() -> Vec<u8> {
    (0..4096u32)
        .map(|i| (i.wrapping_mul(2654435761) >> 29) as u8)
        .collect()
}

fn info_error(file: &Path, extra: &[&str]) -> String {
    let out = cutaway()
        .arg("info")
        .arg(file)
        .args(extra)
        .arg("--json")
        .output()
        .unwrap();
    assert_one_error_line(&out, file)
}

#[test]
fn malformed_volumes_are_one_line_errors() {
    let dir = scratch("malformed");
    let packed = gzip(&labels());
    let nrrd = |header: &str, data: &[u8]| [header.as_bytes(), data].concat();
    let float_data: Vec<u8> = (0..4096)
        .flat_map(|i| (i as f32 * 0.25).to_le_bytes())
        .collect();
    let cases: Vec<(&str, Vec<u8>, &[&str])> = vec![
        (
            "truncated.nrrd",
            nrrd(HEADER, &packed[..packed.len() / 2]),
            &["gzip"],
        ),
        (
            "corrupt.nrrd",
            nrrd(
                HEADER,
                &[&packed[..10], &[0xff; 64][..], &packed[74..]].concat(),
            ),
            &["gzip", "bytes"],
        ),
        (
            "short.nrrd",
            nrrd(&HEADER.replace("gzip", "raw"), &labels()[..4000]),
            &["voxel data is 4000 bytes", "need 4096"],
        ),
        (
            "long.nrrd",
            nrrd(HEADER, &gzip(&[labels(), labels()].concat())),
            &["more than the 4096 bytes"],
        ),
        (
            "zero.nrrd",
            nrrd(&HEADER.replace("16 16 16", "16 0 16"), &packed),
            &["size 0 of axis 1"],
        ),
        (
            "wide.nrrd",
            nrrd(&HEADER.replace("16 16 16", "16 4096 16"), &packed),
            &["size 4096 of axis 1 is outside 1..=2048"],
        ),
        (
            "huge.nrrd",
            nrrd(&HEADER.replace("16 16 16", "2048 2048 1000"), &packed),
            &["more than the limit of 4000000000"],
        ),
        (
            "singular.nrrd",
            nrrd(
                &HEADER.replace("(0,1,0) (0,0,1)", "(0,1,0) (1,1,0)"),
                &packed,
            ),
            &["singular direction matrix"],
        ),
        (
            "nan.nrrd",
            nrrd(&HEADER.replace("(0,1,0)", "(0,nan,0)"), &packed),
            &["not finite"],
        ),
        (
            "nan-spacing.nrrd",
            nrrd(
                &HEADER
                    .replace("space: left-posterior-superior\n", "")
                    .replace(
                        "space directions: (1,0,0) (0,1,0) (0,0,1)",
                        "spacings: 1 NaN 1",
                    )
                    .replace("space origin: (0,0,0)\n", ""),
                &packed,
            ),
            &["spacing NaN on spatial axis 1"],
        ),
        (
            "empty.nrrd",
            nrrd(HEADER, &gzip(&[0; 4096])),
            &["empty label map"],
        ),
        (
            "encoding.nrrd",
            nrrd(&HEADER.replace("gzip", "bzip2"), &packed),
            &["unsupported encoding 'bzip2'"],
        ),
        (
            "4d.nrrd",
            nrrd(
                &HEADER
                    .replace("dimension: 3", "dimension: 4")
                    .replace("16 16 16", "16 16 16 2")
                    .replace("(0,0,1)", "(0,0,1) none"),
                &packed,
            ),
            &["layer) axis first"],
        ),
        (
            "text.nrrd",
            b"NRRD0004\ntype: uchar\nthis line is junk\n\n".to_vec(),
            &["line 3", "expected 'field: value'"],
        ),
        ("not-nifti.nii", vec![0u8; 400], &["not a NIfTI-1/2 file"]),
    ];
    // Values that are not labels (fractions, negatives) make an intensity image, which `info`
    // describes and `surfaces` refuses with the reason.
    let not_labels = [
        (
            "float.nrrd",
            nrrd(
                &HEADER.replace("unsigned char", "float"),
                &gzip(&float_data),
            ),
            "float32 values with fractions, such as 0.25",
        ),
        (
            "negative.nrrd",
            nrrd(
                &HEADER.replace("unsigned char", "signed char"),
                &gzip(&[0xffu8; 4096]),
            ),
            "negative int8 values, such as -1",
        ),
    ];
    for (name, bytes, reason) in &not_labels {
        let path = dir.join(name);
        std::fs::write(&path, bytes).unwrap();
        let out = cutaway()
            .arg("info")
            .arg(&path)
            .arg("--json")
            .output()
            .unwrap();
        let json = String::from_utf8_lossy(&out.stdout);
        assert!(out.status.success(), "{name}: {json}");
        assert!(json.contains(reason), "{name}: {json}");
        let out = cutaway()
            .arg("surfaces")
            .arg(&path)
            .arg("--out")
            .arg(dir.join("out"))
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{name}");
        assert!(
            err.contains("an intensity image") && err.contains(reason),
            "{name}: {err}"
        );
    }
    for (name, bytes, needles) in &cases {
        let path = dir.join(name);
        std::fs::write(&path, bytes).unwrap();
        let err = info_error(&path, &[]);
        assert!(needles.iter().any(|n| err.contains(n)), "{name}: {err}");
    }

    // NIfTI: a valid 2×2×2 file, then broken copies.
    let mut nii = vec![0u8; 352];
    nii[0..4].copy_from_slice(&348i32.to_le_bytes());
    for (i, d) in [3i16, 2, 2, 2, 1, 1, 1, 1].iter().enumerate() {
        nii[40 + 2 * i..42 + 2 * i].copy_from_slice(&d.to_le_bytes());
    }
    nii[70..72].copy_from_slice(&2i16.to_le_bytes());
    for i in 0..8 {
        nii[76 + 4 * i..80 + 4 * i].copy_from_slice(&1f32.to_le_bytes());
    }
    nii[108..112].copy_from_slice(&352f32.to_le_bytes());
    nii[344..348].copy_from_slice(b"n+1\0");
    nii.extend_from_slice(&[0, 1, 0, 1, 2, 2, 0, 0]);
    let good = dir.join("good.nii.gz");
    std::fs::write(&good, gzip(&nii)).unwrap();
    assert!(
        cutaway()
            .arg("info")
            .arg(&good)
            .arg("--json")
            .output()
            .unwrap()
            .status
            .success()
    );
    let mut time_series = nii.clone();
    time_series[40..42].copy_from_slice(&4i16.to_le_bytes());
    time_series[48..50].copy_from_slice(&3i16.to_le_bytes());
    let mut float = nii.clone();
    float[70..72].copy_from_slice(&16i16.to_le_bytes());
    float.extend_from_slice(&[0; 24]);
    float[352..356].copy_from_slice(&0.5f32.to_le_bytes());
    let float_nii = dir.join("float.nii");
    std::fs::write(&float_nii, &float).unwrap();
    let out = cutaway()
        .arg("info")
        .arg(&float_nii)
        .arg("--json")
        .output()
        .unwrap();
    let json = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success() && json.contains("float32 values with fractions, such as 0.5"),
        "{json}"
    );
    let mut complex = nii.clone();
    complex[70..72].copy_from_slice(&32i16.to_le_bytes());
    let gz = gzip(&nii);
    let nifti_cases: Vec<(&str, Vec<u8>, &str)> = vec![
        ("cut.nii", nii[..356].to_vec(), "voxel data is 4 bytes"),
        ("cut.nii.gz", gz[..gz.len() - 12].to_vec(), "gzip"),
        ("time.nii", time_series, "dim[4] = 3"),
        ("complex.nii", complex, "datatype 32 is not a label type"),
    ];
    for (name, bytes, needle) in &nifti_cases {
        let path = dir.join(name);
        std::fs::write(&path, bytes).unwrap();
        let err = info_error(&path, &[]);
        assert!(err.contains(needle), "{name}: {err}");
    }

    // A colour table with a junk line is an error naming the table and the line.
    let table = dir.join("table.txt");
    std::fs::write(&table, "1 one 1 2 3 255\nnot a colour\n").unwrap();
    let out = cutaway()
        .arg("surfaces")
        .arg(&good)
        .arg("--out")
        .arg(dir.join("out"))
        .arg("--labels")
        .arg(&table)
        .output()
        .unwrap();
    let err = assert_one_error_line(&out, &table);
    assert!(err.contains("line 2: 'not a colour'"), "{err}");
    assert!(!dir.join("out").exists(), "nothing is written on error");
    std::fs::remove_dir_all(&dir).ok();
}
