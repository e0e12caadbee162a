//! End-to-end tests of the `cutaway` command line (the contract in `../shared/CONTRACT.md`).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn cutaway() -> Command {
    Command::new(env!("CARGO_BIN_EXE_cutaway"))
}

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../tests/data")
        .join(name)
}

fn scratch(name: &str) -> PathBuf {
    let dir =
        Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("cli-{name}-{}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn info_json(path: &Path) -> serde_json::Value {
    let out = cutaway()
        .arg("info")
        .arg(path)
        .arg("--json")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{}: {stderr}", path.display());
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert_eq!(
        stdout.lines().count(),
        1,
        "one JSON object on one line: {stdout}"
    );
    serde_json::from_str(&stdout).unwrap()
}

/// Checks the contract's failure shape: exit code not 0, exactly one stderr line
/// `error: <file>: …`, no panic, nothing on stdout.
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

#[test]
fn missing_file_is_one_error_line() {
    // With or without an extension, a path that is not there is said to be missing (not of an
    // unknown format).
    for missing in [
        "/nonexistent/knee.stl",
        "/nonexistent/knee",
        "/nonexistent/masks/",
    ] {
        let out = cutaway()
            .args(["info", missing, "--json"])
            .output()
            .unwrap();
        let line = assert_one_error_line(&out, Path::new(missing));
        assert!(line.contains("No such file or directory"), "{line}");
    }
}

#[test]
fn info_json_has_exactly_the_contract_fields() {
    let value = info_json(&data("cube_ascii.ply"));
    let keys: Vec<&str> = value
        .as_object()
        .unwrap()
        .keys()
        .map(|k| k.as_str())
        .collect();
    let mut expected = [
        "vertices",
        "triangles",
        "regions",
        "closed",
        "manifold",
        "bbox_min",
        "bbox_max",
        "volume",
    ];
    let mut sorted_keys = keys.clone();
    sorted_keys.sort_unstable();
    expected.sort_unstable();
    assert_eq!(sorted_keys, expected);
    assert_eq!(value["vertices"], 8);
    assert_eq!(value["triangles"], 12);
    assert_eq!(value["regions"], 1);
    assert_eq!(value["closed"], true);
    assert_eq!(value["manifold"], true);
    assert_eq!(value["bbox_min"], serde_json::json!([10.0, 20.0, 30.0]));
    assert_eq!(value["bbox_max"], serde_json::json!([11.0, 21.0, 31.0]));
    assert_eq!(value["volume"], 1.0);
}

#[test]
fn info_counts_regions_of_every_part_and_every_format() {
    let obj = info_json(&data("two_cubes.obj"));
    assert_eq!(
        (obj["vertices"].as_u64(), obj["triangles"].as_u64()),
        (Some(16), Some(24))
    );
    assert_eq!(obj["regions"], 2);
    assert_eq!(obj["volume"], 2.0);
    let stl = info_json(&data("tetra_ascii.stl"));
    assert_eq!(
        (stl["vertices"].as_u64(), stl["triangles"].as_u64()),
        (Some(4), Some(4))
    );
    assert!((stl["volume"].as_f64().unwrap() - 1.0 / 6.0).abs() < 1e-15);
    let vtk = info_json(&data("cube_strips.vtk"));
    assert_eq!(vtk["closed"], true);
    assert_eq!(vtk["manifold"], true);
    assert_eq!(vtk["volume"], 1.0);

    // An open mesh: one triangle removed from the cube.
    let dir = scratch("open");
    let text = std::fs::read_to_string(data("cube_ascii.ply")).unwrap();
    let open = text.replace("4 3 0 4 7\n", "3 3 0 4\n");
    std::fs::write(dir.join("open.ply"), open).unwrap();
    let value = info_json(&dir.join("open.ply"));
    assert_eq!(value["triangles"], 11);
    assert_eq!(value["closed"], false);
}

#[test]
fn info_without_json_prints_a_readable_table() {
    let out = cutaway()
        .arg("info")
        .arg(data("two_cubes.obj"))
        .output()
        .unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    for expected in [
        "triangles  24",
        "regions    2",
        "closed     yes",
        "volume     2",
    ] {
        assert!(
            text.lines().any(|l| l.starts_with(expected)),
            "{expected:?} in\n{text}"
        );
    }
}

#[test]
fn bad_inputs_fail_with_one_line_naming_the_file() {
    let dir = scratch("bad");
    let mut absurd_stl = vec![0u8; 84 + 50];
    absurd_stl[80..84].copy_from_slice(&4_000_000_000u32.to_le_bytes());
    let garbage: Vec<u8> = (0..5000u32)
        .map(|i| (i.wrapping_mul(2654435761) >> 11) as u8)
        .collect();
    let ply = std::fs::read(data("cube_ascii.ply")).unwrap();
    let cases: Vec<(&str, Vec<u8>, &str)> = vec![
        ("empty.stl", Vec::new(), "empty"),
        ("garbage.obj", garbage.clone(), "OBJ"),
        ("garbage.ply", garbage.clone(), "PLY"),
        ("garbage.vtk", garbage.clone(), "VTK"),
        ("garbage.stl", garbage, "STL"),
        ("truncated.ply", ply[..ply.len() - 20].to_vec(), "PLY"),
        ("absurd.stl", absurd_stl, "4000000000"),
        (
            "absurd.ply",
            b"ply\nformat ascii 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\nproperty float z\nend_header\n1 2 3\n".to_vec(),
            "PLY",
        ),
        (
            "absurd.vtk",
            b"# vtk DataFile Version 3.0\nx\nBINARY\nDATASET POLYDATA\nPOINTS 4000000000 float\n\0\0\0\0".to_vec(),
            "VTK",
        ),
        ("wrong.stl", ply, "looks like PLY"),
        ("notes.txt", b"hello".to_vec(), "unknown mesh format"),
    ];
    for (name, bytes, needle) in cases {
        let path = dir.join(name);
        std::fs::write(&path, bytes).unwrap();
        let out = cutaway()
            .arg("info")
            .arg(&path)
            .arg("--json")
            .output()
            .unwrap();
        let line = assert_one_error_line(&out, &path);
        assert!(line.contains(needle), "{name}: {line}");
    }
    let missing = dir.join("missing.obj");
    let out = cutaway().arg("info").arg(&missing).output().unwrap();
    assert_one_error_line(&out, &missing);
    let out = cutaway().arg("info").arg(&dir).output().unwrap();
    assert_one_error_line(&out, &dir);
}

/// Inputs that once ran away (a session asking for 10⁹ ribbons, a gesture with a 1×2 viewport, a
/// link to /dev/zero) stop at once with one line naming the file and the field.
#[test]
fn runaway_inputs_are_refused_up_front_naming_the_file_and_field() {
    let dir = scratch("runaway");
    std::fs::copy(data("two_cubes.obj"), dir.join("m.obj")).unwrap();
    let session = dir.join("s.json");
    std::fs::write(
        &session,
        r#"{"format": "cutaway-session/1", "models": [{"path": "m.obj"}],
            "cutters": [{"target": 0, "planes": [[[0,0,0],[0,1,0],[0,1,-1],[0,0,-1]]],
                         "views": {"ribbons": {"count": 1000000000, "width": 2}}}]}"#,
    )
    .unwrap();
    let out = cutaway()
        .arg("render")
        .arg(&session)
        .args(["--out"])
        .arg(dir.join("x.png"))
        .output()
        .unwrap();
    let line = assert_one_error_line(&out, &session);
    assert!(line.contains("views.ribbons.count 1000000000"), "{line}");

    let gesture = dir.join("g.json");
    std::fs::write(
        &gesture,
        r#"{"format": "cutaway-gesture/1", "viewport": [1, 2],
            "camera": {"eye": [0, -300, 0], "target": [0, 0, 0], "up": [0, 0, 1], "fov_y_deg": 30},
            "events": [{"type": "press", "x": 0, "y": 0}]}"#,
    )
    .unwrap();
    let out = cutaway()
        .arg("extrude")
        .arg(dir.join("m.obj"))
        .arg("--gesture")
        .arg(&gesture)
        .arg("--out")
        .arg(dir.join("c.obj"))
        .output()
        .unwrap();
    let line = assert_one_error_line(&out, &gesture);
    assert!(line.contains("viewport [1, 2]"), "{line}");

    let zero = dir.join("zero.obj");
    std::os::unix::fs::symlink("/dev/zero", &zero).unwrap();
    let out = cutaway().arg("info").arg(&zero).output().unwrap();
    let line = assert_one_error_line(&out, &zero);
    assert!(line.contains("character device"), "{line}");
}
