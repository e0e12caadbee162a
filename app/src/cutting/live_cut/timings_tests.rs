//! Tests of [`super`] (`live_cut.rs`), kept in their own file.

use super::*;
use crate::render::ViewMode;
use crate::test_support::{
    box_cutter, deterministic_frame, median_and_max, plain_cutter, two_renderers_or_skip,
    with_sphere,
};

/// Per re-cut, the window's way (the live cut drawn from its delta) and the way before it
/// (the whole kept part cut, materialized and uploaded, as `preview_geometry_with` gives
/// it), each with a renderer of its own, in the same run.
#[test]
#[ignore = "a benchmark: prints figures and checks none; run it with `--ignored --nocapture`"]
fn live_recut_ui_thread_cost_on_two_million_triangles() {
    let Some((mut renderer, mut whole)) = two_renderers_or_skip() else {
        return;
    };
    let sphere = Arc::new(csg::testkit::geodesic_sphere(316, 100.0));
    let mut scene = with_sphere(Scene::default(), sphere.clone(), "sphere.ply");
    let frame = deterministic_frame(&scene, [640, 400], ViewMode::Camera);
    let first = renderer.time_prepare(&frame).expect("first frame");
    let base_bytes = renderer.last_frame_uploads().bytes;
    whole.time_prepare(&frame).expect("first frame");
    let mut live = LiveCut::default();
    let mut whole_cache = CutCache::default();
    let (mut cut_ms, mut ui_ms, mut bytes) = (Vec::new(), Vec::new(), Vec::new());
    let (mut whole_cut_ms, mut whole_ui_ms, mut whole_bytes) = (Vec::new(), Vec::new(), Vec::new());
    for k in 0..=10 {
        let x1 = -20.0 + 5.0 * k as f64;
        let planes = box_cutter(-60.0, x1, -120.0, -70.0, -8.0, 8.0);
        scene.cutters = vec![plain_cutter(0, cutter::CutKind::Curving, planes)];
        assert!(live.request(&scene, None));
        assert!(live.wait(Duration::from_secs(600)), "no live cut");
        let mut frame = deterministic_frame(&scene, [640, 400], ViewMode::Edit);
        frame.show_cut(live.geometry());
        frame.deltas = live.deltas();
        let ms = renderer.time_prepare(&frame).expect("frame");
        let uploaded = renderer.last_frame_uploads().bytes as f64 / 1e6;
        // The same re-cut the way before: whole kept part, uploaded whole.
        let started = Instant::now();
        let geometry = preview_geometry_with(&live_scene(&scene), &mut whole_cache);
        let whole_cut = started.elapsed().as_secs_f64() * 1000.0;
        frame.show_cut(Some(Arc::new(geometry)));
        frame.deltas.clear();
        let whole_frame = whole.time_prepare(&frame).expect("frame");
        if k > 0 {
            cut_ms.push(live.shown().unwrap().ms);
            ui_ms.push(ms);
            bytes.push(uploaded);
            whole_cut_ms.push(whole_cut);
            whole_ui_ms.push(whole_frame);
            whole_bytes.push(whole.last_frame_uploads().bytes as f64 / 1e6);
        }
    }
    let f = median_and_max;
    println!(
        "live re-cut on {} triangles ({}): first frame {first:.1} ms ({:.1} MB); {} re-cuts:\n  \
         delta: worker ms {}, UI thread ms {}, MB uploaded {}\n  \
         whole: worker ms {}, UI thread ms {}, MB uploaded {}",
        sphere.triangle_count(),
        renderer.adapter_name(),
        base_bytes as f64 / 1e6,
        ui_ms.len(),
        f(&cut_ms),
        f(&ui_ms),
        f(&bytes),
        f(&whole_cut_ms),
        f(&whole_ui_ms),
        f(&whole_bytes),
    );
}
