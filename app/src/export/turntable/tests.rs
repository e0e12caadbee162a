//! Tests of the turntable export: the orbit, the GIF, and progress and cancel of the shared
//! function (the window's job and both CLI forms call it).

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU32, Ordering};

use super::*;
use crate::scene::SceneModel;

#[test]
fn the_orbit_turns_about_the_up_axis_keeping_distance_and_height() {
    let camera = cutter::Camera {
        eye: DVec3::new(0.0, -100.0, 30.0),
        target: DVec3::new(0.0, 0.0, 10.0),
        up: DVec3::Z,
        fov_y_deg: 30.0,
    };
    assert!((orbit(&camera, 0, 8).eye - camera.eye).length() < 1e-12);
    let quarter = orbit(&camera, 2, 8);
    assert!(
        (quarter.eye - DVec3::new(100.0, 0.0, 30.0)).length() < 1e-9,
        "{:?}",
        quarter.eye
    );
    for k in 0..8 {
        let c = orbit(&camera, k, 8);
        assert!((c.distance() - camera.distance()).abs() < 1e-9);
        assert!((c.eye.z - 30.0).abs() < 1e-9);
        assert_eq!(c.target, camera.target);
    }
}

#[test]
fn the_gif_holds_every_frame_and_loops() {
    let frames: Vec<RgbaImage> = (0..3u8)
        .map(|k| RgbaImage::from_pixel(8, 6, image::Rgba([k * 100, 0, 0, 255])))
        .collect();
    let bytes = encode_gif(frames, 50).unwrap();
    assert_eq!(&bytes[..6], b"GIF89a");
    use image::AnimationDecoder as _;
    let decoded = image::codecs::gif::GifDecoder::new(std::io::Cursor::new(&bytes))
        .unwrap()
        .into_frames()
        .collect_frames()
        .unwrap();
    assert_eq!(decoded.len(), 3);
    assert_eq!(decoded[2].buffer().get_pixel(3, 3)[0], 200);
    assert_eq!(decoded[1].delay().numer_denom_ms(), (50, 1));
    // NETSCAPE2.0 application extension: the animation loops.
    assert!(bytes.windows(11).any(|w| w == b"NETSCAPE2.0"));
}

#[test]
fn bad_options_are_refused_in_one_line_naming_the_folder() {
    let out = Path::new("/nonexistent/turn");
    for options in [
        TurntableOptions {
            frames: 0,
            ..Default::default()
        },
        TurntableOptions {
            frames: MAX_FRAMES + 1,
            ..Default::default()
        },
        TurntableOptions {
            delay_ms: 5,
            ..Default::default()
        },
    ] {
        let e = format!("{:#}", options.validate(out).unwrap_err());
        assert!(e.starts_with("/nonexistent/turn: "), "{e}");
        assert_eq!(e.lines().count(), 1);
    }
    assert!(TurntableOptions::default().validate(out).is_ok());
}

/// Records progress and cancels once `cancel_after` frames are done.
struct Recorder {
    done: AtomicU32,
    calls: AtomicU32,
    cancel_after: u32,
    cancel: AtomicBool,
}

impl Recorder {
    fn new(cancel_after: u32) -> Recorder {
        Recorder {
            done: AtomicU32::new(0),
            calls: AtomicU32::new(0),
            cancel_after,
            cancel: AtomicBool::new(false),
        }
    }
}

impl TurntableProgress for Recorder {
    fn frame_done(&self, done: u32, total: u32) {
        assert!(done <= total);
        assert_eq!(
            done,
            self.done.load(Ordering::SeqCst) + 1,
            "frames in order"
        );
        self.done.store(done, Ordering::SeqCst);
        self.calls.fetch_add(1, Ordering::SeqCst);
        if done >= self.cancel_after {
            self.cancel.store(true, Ordering::SeqCst);
        }
    }
    fn cancelled(&self) -> bool {
        self.cancel.load(Ordering::SeqCst)
    }
}

/// A box off the turning axis, so every frame of a turn looks different.
fn off_centre_box() -> Scene {
    let mut scene = Scene::default();
    let mesh = csg::testkit::cube(DVec3::new(5.0, -4.0, -3.0), DVec3::new(25.0, 4.0, 9.0));
    scene.models.push(SceneModel::new(
        "box",
        "box.obj",
        Arc::new(mesh),
        [0.9, 0.6, 0.5],
    ));
    scene.camera = cutter::Camera {
        eye: DVec3::new(0.0, -120.0, 40.0),
        target: DVec3::ZERO,
        up: DVec3::Z,
        fov_y_deg: 35.0,
    };
    scene
}

fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("cutaway-{name}-{}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    dir
}

fn gpu_available() -> bool {
    match crate::render::HeadlessRenderer::new() {
        Ok(_) => true,
        Err(e) => {
            csg::testkit::skip(csg::testkit::Resource::Gpu, format!("{e:#}"));
            false
        }
    }
}

#[test]
fn every_frame_is_reported_and_the_frames_differ() {
    if !gpu_available() {
        return;
    }
    let out = scratch("turntable-frames");
    let recorder = Recorder::new(u32::MAX);
    let options = TurntableOptions {
        frames: 4,
        gif: true,
        delay_ms: 100,
    };
    let summary = export_turntable(
        &off_centre_box(),
        &RenderPngOptions::new(64, 48),
        &options,
        &out,
        &recorder,
        None,
    )
    .unwrap();
    assert_eq!(summary.frames, 4);
    assert_eq!(recorder.calls.load(Ordering::SeqCst), 4);
    let frames: Vec<RgbaImage> = (0..4)
        .map(|k| image::open(out.join(frame_name(k))).unwrap().to_rgba8())
        .collect();
    for k in 1..4 {
        assert_ne!(frames[0], frames[k], "frame {} looks as frame 1", k + 1);
    }
    assert!(out.join(GIF_NAME).is_file());
    // A second export without the GIF and with fewer frames replaces the whole set.
    let options = TurntableOptions {
        frames: 2,
        gif: false,
        delay_ms: 100,
    };
    let small = RenderPngOptions::new(64, 48);
    export_turntable(&off_centre_box(), &small, &options, &out, &Quiet, None).unwrap();
    assert!(out.join(frame_name(1)).is_file());
    assert!(!out.join(frame_name(2)).exists(), "a stale frame was left");
    assert!(!out.join(GIF_NAME).exists(), "a stale GIF was left");
    std::fs::remove_dir_all(&out).ok();
}

#[test]
fn a_cancel_stops_between_frames_and_writes_nothing() {
    if !gpu_available() {
        return;
    }
    let out = scratch("turntable-cancel");
    let recorder = Recorder::new(2);
    let options = TurntableOptions {
        frames: 6,
        gif: true,
        delay_ms: 100,
    };
    let err = export_turntable(
        &off_centre_box(),
        &RenderPngOptions::new(48, 32),
        &options,
        &out,
        &recorder,
        None,
    )
    .unwrap_err();
    assert!(
        err.downcast_ref::<TurntableCancelled>().is_some(),
        "{err:#}"
    );
    assert_eq!(
        recorder.calls.load(Ordering::SeqCst),
        2,
        "frames drawn after the cancel"
    );
    assert!(!out.exists(), "a cancelled export left {}", out.display());

    // Into a folder holding an earlier turntable: the earlier set stays as it was.
    let first = TurntableOptions {
        frames: 3,
        gif: false,
        delay_ms: 100,
    };
    let picture = RenderPngOptions::new(48, 32);
    export_turntable(&off_centre_box(), &picture, &first, &out, &Quiet, None).unwrap();
    let before = std::fs::read(out.join(frame_name(0))).unwrap();
    let mut turned = off_centre_box();
    turned.camera = orbit(&turned.camera, 1, 4);
    let recorder = Recorder::new(1);
    assert!(export_turntable(&turned, &picture, &options, &out, &recorder, None).is_err());
    let mut left: Vec<String> = std::fs::read_dir(out.join("frames"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    left.sort();
    assert_eq!(left, ["frame-0001.png", "frame-0002.png", "frame-0003.png"]);
    assert_eq!(std::fs::read(out.join(frame_name(0))).unwrap(), before);
    assert!(!out.join(GIF_NAME).exists());
    let top: Vec<_> = std::fs::read_dir(&out).unwrap().collect();
    assert_eq!(top.len(), 1, "only frames/ is left (no staging folder)");
    std::fs::remove_dir_all(&out).ok();
}

#[test]
fn a_cancel_before_the_first_frame_writes_nothing() {
    let out = scratch("turntable-cancel-early");
    let recorder = Recorder::new(0);
    recorder.cancel.store(true, Ordering::SeqCst);
    let err = export_turntable(
        &off_centre_box(),
        &RenderPngOptions::new(48, 32),
        &TurntableOptions::default(),
        &out,
        &recorder,
        None,
    )
    .unwrap_err();
    assert!(
        err.downcast_ref::<TurntableCancelled>().is_some(),
        "{err:#}"
    );
    assert_eq!(recorder.calls.load(Ordering::SeqCst), 0);
    assert!(!out.exists());
}
