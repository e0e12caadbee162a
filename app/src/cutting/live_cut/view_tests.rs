//! Tests of [`super`] (`live_cut.rs`), kept in their own file.

use super::*;
use crate::render::ViewMode;
use crate::test_support::{
    box_cutter, deterministic_frame, differing_pixels, plain_cutter, renderer_or_skip, with_sphere,
};

#[test]
fn the_live_cut_from_its_delta_looks_as_the_whole_kept_part_and_uploads_little() {
    let Some(mut renderer) = renderer_or_skip() else {
        return;
    };
    let sphere = Arc::new(csg::testkit::icosphere(6, 10.0));
    let mut scene = with_sphere(Scene::default(), sphere.clone(), "sphere.obj");
    let frame = |scene: &Scene| deterministic_frame(scene, [320, 240], ViewMode::Edit);
    let uncut = renderer.render(&frame(&scene)).expect("render");
    let model_bytes = renderer.last_frame_uploads().bytes;
    let mut live = LiveCut::default();
    for (k, x1) in [1.0, 4.0, 2.5].into_iter().enumerate() {
        scene.cutters = vec![plain_cutter(
            0,
            cutter::CutKind::Curving,
            box_cutter(-4.0, x1, -12.0, -8.0, -2.0, 3.0),
        )];
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
        whole.show_cut(Some(Arc::new(crate::cutting::cut_scene::preview_geometry(
            &live_scene(&scene),
        ))));
        let expected = renderer.render(&whole).expect("render");
        let mut delta = frame(&scene);
        delta.show_cut(live.geometry());
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
