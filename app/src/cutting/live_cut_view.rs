//! Tests of [`super`] (`live_cut.rs`), kept in their own file.

use super::*;
use crate::cutting::cut_scene::tests::box_cutter;
use crate::render::{FrameInputs, HeadlessRenderer, ViewMode};
use crate::scene::{SceneCutter, SceneModel};

/// Pixels that differ between two images of the same size.
pub(crate) fn differing_pixels(a: &image::RgbaImage, b: &image::RgbaImage) -> usize {
    assert_eq!(a.dimensions(), b.dimensions());
    a.pixels().zip(b.pixels()).filter(|(p, q)| p != q).count()
}

#[test]
fn the_live_cut_from_its_delta_looks_as_the_whole_kept_part_and_uploads_little() {
    let mut renderer = match HeadlessRenderer::new() {
        Ok(r) => r,
        Err(e) => {
            println!("skipped: {e}");
            return;
        }
    };
    let sphere = Arc::new(csg::testkit::icosphere(6, 10.0));
    let mut scene = crate::scene::Scene::default();
    scene.models.push(SceneModel::new(
        "sphere",
        "sphere.obj",
        sphere.clone(),
        [0.9, 0.7, 0.6],
    ));
    scene.camera = scene.framing_camera();
    let frame = |scene: &Scene| {
        let mut f = FrameInputs::new(scene.clone(), [320, 240], ViewMode::Edit);
        f.deterministic = true;
        f
    };
    let uncut = renderer.render(&frame(&scene)).expect("render");
    let model_bytes = renderer.last_frame_uploads().bytes;
    let mut live = LiveCut::default();
    for (k, x1) in [1.0, 4.0, 2.5].into_iter().enumerate() {
        scene.cutters = vec![SceneCutter {
            target: 0,
            cutter: cutter::Cutter {
                kind: cutter::CutKind::Curving,
                smooth: false,
                planes: box_cutter(-4.0, x1, -12.0, -8.0, -2.0, 3.0),
            },
            views: CutterViews::default(),
        }];
        assert!(live.request(&scene, None));
        assert!(live.wait(Duration::from_secs(120)), "no live cut");
        assert_eq!(
            live.deltas().len(),
            1,
            "{:?}",
            live.shown().unwrap().geometry.notes
        );
        // The way before: the whole kept part as a preview part.
        let mut whole = frame(&scene);
        whole.preview = Some(Arc::new(crate::cutting::cut_scene::preview_geometry(
            &live_scene(&scene),
        )));
        let expected = renderer.render(&whole).expect("render");
        let mut delta = frame(&scene);
        delta.preview = live.geometry();
        delta.deltas = live.deltas();
        let got = renderer.render(&delta).expect("render");
        let uploads = renderer.last_frame_uploads();
        if k == 0 {
            let _ = got.save(std::env::temp_dir().join("live-cut-from-delta.png"));
        }
        assert_ne!(differing_pixels(&got, &uncut), 0, "re-cut {k}: nothing cut");
        assert_eq!(
            differing_pixels(&got, &expected),
            0,
            "re-cut {k}: the view differs"
        );
        // Neither the model nor anything its size went up: the patch, walls, contour and
        // index patches only.
        assert!(
            uploads.bytes * 10 < model_bytes,
            "re-cut {k}: {} bytes uploaded, the model is {model_bytes}",
            uploads.bytes
        );
        assert!(uploads.triangles * 10 < sphere.triangle_count() as u64);
    }
    // Without the live cut the model is whole again (its hidden faces are shown).
    let again = renderer.render(&frame(&scene)).expect("render");
    assert_eq!(differing_pixels(&again, &uncut), 0);
}
