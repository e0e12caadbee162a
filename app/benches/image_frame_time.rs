//! Frame time of the image on the walls: the chest segmentation with a box cut through the ribs
//! and lungs, rendered headless at 1280×800, N frames with the CT on the walls and N frames of
//! the same cut scene without the image (the peer: plain wall colour), each frame drawn and read
//! back. Prints ms/frame both ways and the ratio (the cost of trilinear sampling per wall
//! fragment), and one JSON line. The cut is computed once, outside the timing.
//!
//! Run: `WGPU_BACKEND=vulkan cargo bench -p cutaway --bench image_frame_time` (on a machine without a
//! GPU, Mesa's lavapipe draws: the software-rasterizer figure). Needs the chest CT in
//! `$CUTAWAY_ANATOMY/volumes/slicerio_chest` (default `../shared/anatomy`); without it, it says so
//! and exits.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

use cutaway::render::ViewMode;
use cutaway::render::headless::HeadlessRenderer;
use cutaway::view::RenderPngOptions;
use cutaway::view::render_with_preview;

const FRAMES: usize = 10;

fn chest_dir() -> Option<PathBuf> {
    let root = std::env::var_os("CUTAWAY_ANATOMY")
        .map(PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/anatomy"));
    let dir = root.join("volumes/slicerio_chest");
    dir.join("CTChest4.nrrd").is_file().then_some(dir)
}

fn main() {
    let Some(chest) = chest_dir() else {
        println!("image_frame_time: skipped: no chest CT (set CUTAWAY_ANATOMY)");
        return;
    };
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
    let session = serde_json::json!({
        "format": "cutaway-session/2",
        "models": [{"path": chest.join("Segmentation.seg.nrrd")}],
        "cutters": cutters,
        "camera": {"eye": [160, 720, -20], "target": [0, 0, -190], "up": [0, 0, 1], "fov_y_deg": 30},
        "image": {"path": chest.join("CTChest4.nrrd"), "window": [-600.0, 1500.0]}
    });
    let path =
        std::env::temp_dir().join(format!("cutaway-bench-image-{}.json", std::process::id()));
    std::fs::write(&path, session.to_string()).expect("write the session");
    let with_image = cutaway::session::load(&path).expect("load the chest session");
    let _ = std::fs::remove_file(&path);
    let mut without = with_image.clone();
    without.image = None;
    let preview = Arc::new(cutaway::cutting::cut_scene::preview_geometry(&with_image));
    assert!(preview.notes.is_empty(), "{:?}", preview.notes);

    let mut renderer = match HeadlessRenderer::new() {
        Ok(r) => r,
        Err(e) => {
            println!("image_frame_time: skipped: {e:#}");
            return;
        }
    };
    let mut options = RenderPngOptions::new(1280, 800);
    options.mode = Some(ViewMode::Preview);
    let mut ms_per_frame = |scene: &cutaway::scene::Scene| {
        // One frame first: uploads (meshes, the image texture) are not the per-frame cost.
        render_with_preview(&mut renderer, scene, &options, Some(preview.clone())).expect("render");
        let started = Instant::now();
        for _ in 0..FRAMES {
            render_with_preview(&mut renderer, scene, &options, Some(preview.clone()))
                .expect("render");
        }
        started.elapsed().as_secs_f64() * 1000.0 / FRAMES as f64
    };
    // Interleaved, best of three, so a busy neighbour on a shared machine affects both alike.
    let (mut plain, mut image) = (f64::INFINITY, f64::INFINITY);
    for _ in 0..3 {
        plain = plain.min(ms_per_frame(&without));
        image = image.min(ms_per_frame(&with_image));
    }
    let ratio = image / plain;
    println!(
        "image_frame_time on {}: 1280×800, {FRAMES} frames: {image:.1} ms/frame with the CT on the walls, {plain:.1} ms/frame without; ratio {ratio:.2}",
        renderer.adapter_name()
    );
    println!(
        "{}",
        serde_json::json!({
            "adapter": renderer.adapter_name(),
            "software": renderer.is_software(),
            "width": 1280,
            "height": 800,
            "frames": FRAMES,
            "image_ms_per_frame": image,
            "plain_ms_per_frame": plain,
            "ratio": ratio,
        })
    );
}
