//! Teaching exports end to end. Labelled images: the leader of each label ends on a pixel where
//! the picture shows that structure, labels do not overlap, and `cutaway render --labels` draws
//! them (and refuses an unknown name with one line). Turntables: `cutaway turntable` and
//! `cutaway render --turntable N` write one frame per step of the orbit (each a different view)
//! and a GIF holding them all, with no progress noise when stderr is not a terminal.
//!
//! Rendering needs a GPU adapter (lavapipe with `WGPU_BACKEND=vulkan`); without one the tests
//! print "skipped: …" and pass.

use csg::testkit::{Resource, skip};
use std::path::Path;
use std::process::Command;

use crate::scene_files::{box_obj, box_planes, cut_view, cutter, model, scratch, write_session};
use cutaway::annotate::labelled::{annotate, chosen, pixel};
use cutaway::render::HeadlessRenderer;
use cutaway::view::{RenderPngOptions, render_with};

/// A red 10 mm cube (a corner cut away) and a blue box beside it, seen from the front.
fn two_boxes(dir: &Path) -> std::path::PathBuf {
    write_session(
        dir,
        &[
            ("cube.obj", box_obj([0.0; 3], [10.0; 3])),
            ("side.obj", box_obj([14.0, 0.0, 0.0], [20.0, 6.0, 6.0])),
        ],
        vec![
            model("cube.obj", [0.9, 0.15, 0.15]),
            model("side.obj", [0.15, 0.25, 0.9]),
        ],
        vec![cutter(
            0,
            box_planes(5.0, 15.0, -5.0, 5.0, 5.0, 15.0),
            cut_view(),
        )],
        [10.0, -60.0, 25.0],
    )
}

fn renderer() -> Option<HeadlessRenderer> {
    match HeadlessRenderer::new() {
        Ok(r) => Some(r),
        Err(e) => {
            skip(Resource::Gpu, format!("no GPU adapter ({e})"));
            None
        }
    }
}

#[test]
fn leaders_end_on_their_structure_s_visible_pixels() {
    let dir = scratch("annotate-leaders");
    let session = two_boxes(&dir);
    let mut scene = cutaway::session::load(&session).unwrap();
    // Look at the middle of the pair.
    scene.camera.target = glam::DVec3::new(10.0, 3.0, 5.0);
    let Some(mut renderer) = renderer() else {
        return;
    };
    let options = RenderPngOptions::new(480, 320);
    let picture = render_with(&mut renderer, &scene, &options).unwrap();
    let preview = cutaway::cutting::cut_scene::preview_geometry(&scene);
    let models = chosen(&scene, &[]).unwrap();
    assert_eq!(models, [0, 1]);
    let mut labelled = picture.clone();
    let drawn = annotate(&mut labelled, &scene, Some(&preview), &models);
    labelled.save(dir.join("labelled.png")).unwrap();
    picture.save(dir.join("picture.png")).unwrap();
    assert_eq!(drawn.labels.len(), 2, "unlabelled: {:?}", drawn.unlabelled);
    for (m, label) in &drawn.labels {
        let end = label.leader[1];
        let under = pixel(&picture, end).unwrap();
        let (r, b) = (under[0] as i32, under[2] as i32);
        match m {
            0 => assert!(r > b + 40, "cube's leader ends on {under:?} at {end:?}"),
            _ => assert!(b > r + 40, "side's leader ends on {under:?} at {end:?}"),
        }
    }
    assert!(!drawn.labels[0].1.rect.overlaps(&drawn.labels[1].1.rect));
    // The labels are drawn: their boxes changed the picture.
    for (_, label) in &drawn.labels {
        let r = label.rect;
        let changed = (r.y as u32..(r.y + r.h) as u32)
            .flat_map(|y| (r.x as u32..(r.x + r.w) as u32).map(move |x| (x, y)))
            .filter(|&(x, y)| picture.get_pixel(x, y) != labelled.get_pixel(x, y))
            .count();
        assert!(changed > 20, "{changed} pixels changed in {r:?}");
    }
    let bar = drawn.scale_bar.unwrap();
    assert!(bar.pixels > 10.0 && bar.pixels <= 480.0 * 0.25);
}

#[test]
fn render_labels_on_the_command_line() {
    let dir = scratch("annotate-cli");
    let session = two_boxes(&dir);
    let run = |extra: &[&str], out: &str| {
        Command::new(env!("CARGO_BIN_EXE_cutaway"))
            .arg("render")
            .arg(&session)
            .args(["--out", dir.join(out).to_str().unwrap()])
            .args(["--width", "320", "--height", "240"])
            .args(extra)
            .env(
                "WGPU_BACKEND",
                std::env::var("WGPU_BACKEND").unwrap_or_else(|_| "vulkan".into()),
            )
            .output()
            .unwrap()
    };
    let plain = run(&[], "plain.png");
    let stderr = String::from_utf8_lossy(&plain.stderr);
    if !plain.status.success() && stderr.contains("no GPU adapter") {
        return skip(Resource::Gpu, stderr);
    }
    assert!(plain.status.success(), "{stderr}");
    let one = run(&["--labels", "cube"], "one.png");
    assert!(
        one.status.success(),
        "{}",
        String::from_utf8_lossy(&one.stderr)
    );
    let all = run(&["--labels"], "all.png");
    assert!(
        all.status.success(),
        "{}",
        String::from_utf8_lossy(&all.stderr)
    );
    let a = image::open(dir.join("plain.png")).unwrap().to_rgba8();
    let b = image::open(dir.join("all.png")).unwrap().to_rgba8();
    assert_eq!(a.dimensions(), b.dimensions());
    assert_ne!(a, b, "--labels drew nothing");
    let c = image::open(dir.join("one.png")).unwrap().to_rgba8();
    assert_ne!(b, c, "one label drew as much as all");
    let bad = run(&["--labels", "liver"], "bad.png");
    let stderr = String::from_utf8_lossy(&bad.stderr);
    assert!(!bad.status.success());
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.contains("no structure named 'liver'"), "{stderr}");
    assert!(!dir.join("bad.png").exists());
}

#[test]
fn turntable_writes_every_frame_and_a_gif_of_them() {
    let dir = scratch("annotate-turntable");
    let session = two_boxes(&dir);
    let out = dir.join("turn");
    let run = Command::new(env!("CARGO_BIN_EXE_cutaway"))
        .arg("turntable")
        .arg(&session)
        .args(["--out", out.to_str().unwrap()])
        .args(["--frames", "4", "--width", "64", "--height", "48", "--gif"])
        .env(
            "WGPU_BACKEND",
            std::env::var("WGPU_BACKEND").unwrap_or_else(|_| "vulkan".into()),
        )
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    if !run.status.success() && stderr.contains("no GPU adapter") {
        return skip(Resource::Gpu, stderr);
    }
    assert!(run.status.success(), "{stderr}");
    let frames: Vec<image::RgbaImage> = (1..=4)
        .map(|k| {
            image::open(out.join(format!("frames/frame-{k:04}.png")))
                .unwrap()
                .to_rgba8()
        })
        .collect();
    assert!(!out.join("frames/frame-0005.png").exists());
    // The view turns: a quarter turn shows another picture than the start.
    assert_ne!(frames[0], frames[1]);
    use image::AnimationDecoder as _;
    let gif = std::fs::File::open(out.join("turntable.gif")).unwrap();
    let decoded = image::codecs::gif::GifDecoder::new(std::io::BufReader::new(gif))
        .unwrap()
        .into_frames()
        .collect_frames()
        .unwrap();
    assert_eq!(decoded.len(), 4);
    assert_eq!(decoded[0].buffer().dimensions(), (64, 48));
    let bad = Command::new(env!("CARGO_BIN_EXE_cutaway"))
        .arg("turntable")
        .arg(&session)
        .args(["--out", out.to_str().unwrap(), "--frames", "0"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&bad.stderr);
    assert!(!bad.status.success());
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.contains("--frames 0"), "{stderr}");
}

#[test]
fn render_turntable_writes_n_different_frames_a_gif_and_clean_json() {
    let dir = scratch("annotate-render-turntable");
    let session = two_boxes(&dir);
    let out = dir.join("orbit");
    let run = Command::new(env!("CARGO_BIN_EXE_cutaway"))
        .arg("render")
        .arg(&session)
        .args(["--out", out.to_str().unwrap()])
        .args(["--turntable", "5", "--width", "64", "--height", "48"])
        .args(["--gif", "--delay-ms", "120", "--json", "--labels"])
        .env(
            "WGPU_BACKEND",
            std::env::var("WGPU_BACKEND").unwrap_or_else(|_| "vulkan".into()),
        )
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    if !run.status.success() && stderr.contains("no GPU adapter") {
        return skip(Resource::Gpu, stderr);
    }
    assert!(run.status.success(), "{stderr}");
    assert!(
        !stderr.contains("frame 1/5"),
        "progress printed to a stderr that is not a terminal: {stderr}"
    );
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert_eq!(stdout.lines().count(), 1, "{stdout}");
    let report: serde_json::Value = serde_json::from_str(stdout.trim()).unwrap();
    assert_eq!(report["frames"], 5);
    assert_eq!(report["gif"], true);
    assert!(report["render_ms"].as_f64().unwrap() > 0.0);
    let frames: Vec<image::RgbaImage> = (1..=5)
        .map(|k| {
            image::open(out.join(format!("frames/frame-{k:04}.png")))
                .unwrap()
                .to_rgba8()
        })
        .collect();
    assert!(!out.join("frames/frame-0006.png").exists());
    for a in 0..5 {
        for b in a + 1..5 {
            assert_ne!(
                frames[a],
                frames[b],
                "frames {} and {} are equal",
                a + 1,
                b + 1
            );
        }
    }
    use image::AnimationDecoder as _;
    let gif = std::fs::File::open(out.join("turntable.gif")).unwrap();
    let decoded = image::codecs::gif::GifDecoder::new(std::io::BufReader::new(gif))
        .unwrap()
        .into_frames()
        .collect_frames()
        .unwrap();
    assert_eq!(decoded.len(), 5);
    assert_eq!(decoded[4].delay().numer_denom_ms(), (120, 1));
    // Only the set's files are left (no staging folder).
    let mut top: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    top.sort();
    assert_eq!(top, ["frames", "turntable.gif"]);
    let bad = Command::new(env!("CARGO_BIN_EXE_cutaway"))
        .arg("render")
        .arg(&session)
        .args(["--out", dir.join("none").to_str().unwrap()])
        .args(["--turntable", "0"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&bad.stderr);
    assert!(!bad.status.success());
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.contains("--turntable 0"), "{stderr}");
    assert!(!dir.join("none").exists());
}
