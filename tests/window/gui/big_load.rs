//! A two-million-triangle load and its index build run off the UI thread: the window keeps
//! drawing frames.

use super::*;

#[test]
fn a_two_million_triangle_load_and_index_never_block_the_window() {
    if let Some(reason) = no_adapter() {
        return skip(Resource::Gpu, reason);
    }
    let dir = temp_dir("big");
    // 1,997,120 triangles, written as binary PLY.
    let big = std::sync::Arc::new(csg::testkit::geodesic_sphere(316, 40.0));
    assert!(big.triangle_count() > 1_990_000);
    let file = dir.join("big_sphere.ply");
    cutaway::io::write_mesh(&file, &big).expect("write the big mesh");

    let small = dir.join("small.obj");
    cutaway::io::write_mesh(&small, &csg::testkit::icosphere(2, 10.0)).unwrap();
    let mut h = harness(&dir, vec![small], false);
    settle(&mut h);
    let ctx = h.ctx.clone();
    let models_before = h.state().scene.models.len();
    assert_eq!(models_before, 1);

    // The load: `apply` returns at once with the job pending, and frames keep coming; the
    // progress window (shown only to frames drawn while the job runs) offers Cancel.
    h.state_mut()
        .apply(&ctx, cutaway::gui::app::Action::Add(vec![file.clone()]));
    assert!(h.state().busy(), "the load did not start a background job");
    assert_eq!(h.state().scene.models.len(), models_before);
    let frames = step_until(&mut h, "progress window", |h| {
        h.query_by_label("Cancel").is_some()
    });
    assert!(
        h.state().busy(),
        "the job ended before Cancel could be pressed"
    );
    println!("{frames} frames drawn while the 2M-triangle load ran");
    h.get_by_label("Cancel").click();
    h.run_steps(3);
    assert!(!h.state().busy(), "Cancel left the job running");
    assert_eq!(
        h.state().scene.models.len(),
        models_before,
        "cancel changed the scene"
    );
    assert!(
        h.state().status.message.contains("cancelled"),
        "{}",
        h.state().status.message
    );

    // The index build of a 2M-triangle target: same story.
    let mut model = cutaway::scene::SceneModel::new("big", &file, big.clone(), [0.7, 0.7, 0.7]);
    model.visible = false;
    h.state_mut().scene.models.push(model);
    h.state_mut().start_index_job(&ctx, 1);
    assert!(
        h.state().busy(),
        "the index build did not start a background job"
    );
    let scene_before = h.state().scene.models.len();
    // The index build is fast (well under a second in release), so it may finish before its
    // progress window is drawn: then the window kept drawing frames while it ran and the index
    // is stored; otherwise Cancel is pressed and nothing is stored.
    let frames = step_until(&mut h, "progress window or the index", |h| {
        h.query_by_label("Cancel").is_some() || !h.state().busy()
    });
    if h.query_by_label("Cancel").is_some() && h.state().busy() {
        h.get_by_label("Cancel").click();
        h.run_steps(3);
        assert!(!h.state().busy());
        // The build may finish between the frame that showed Cancel and the click: then it
        // was not cancelled and its index is kept.
        let cancelled = h.state().status.message.contains("cancelled");
        assert_eq!(
            h.state().viewport.editor.index_for(&big).is_some(),
            !cancelled,
            "index stored: {}, status: {}",
            h.state().viewport.editor.index_for(&big).is_some(),
            h.state().status.message
        );
    } else {
        println!("the index build finished after {frames} frames, before Cancel showed");
        assert!(frames >= 1, "no frame was drawn while the index was built");
        assert!(
            h.state().viewport.editor.index_for(&big).is_some(),
            "the finished index was not stored"
        );
    }
    assert_eq!(h.state().scene.models.len(), scene_before);
    let _ = std::fs::remove_dir_all(&dir);
}
