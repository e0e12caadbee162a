//! Export Image writes the viewport's picture at any size.

use super::*;

#[test]
fn export_image_writes_the_viewport_picture_at_any_size() {
    if let Some(reason) = no_adapter() {
        return skip(Resource::Gpu, reason);
    }
    let dir = temp_dir("export");
    let mut h = harness(&dir, Vec::new(), false);
    settle(&mut h);
    h.state_mut().viewport.show_marker = false; // a window overlay, not part of the picture
    let ctx = h.ctx.clone();
    let size = h.state().viewport.size_px;
    let (w, h1) = (size.x as u32, size.y as u32);

    // 1× the viewport: the same pixels as the 3D view of the window.
    let one = dir.join("one.png");
    h.state_mut().export_image.width = w;
    h.state_mut().export_image.height = h1;
    h.state_mut().export_image.transparent = false;
    h.state_mut()
        .apply(&ctx, cutaway::gui::app::Action::ExportImageTo(one.clone()));
    settle(&mut h);
    assert!(!h.state().status.is_error, "{}", h.state().status.message);
    let exported = image::open(&one).expect("exported PNG").to_rgba8();
    assert_eq!(exported.dimensions(), (w, h1));
    let window = h.render().expect("render the window");
    let rect = h.state().viewport.rect;
    let ppp = h.ctx.pixels_per_point();
    let view = image::imageops::crop_imm(
        &window,
        (rect.min.x * ppp).round() as u32,
        (rect.min.y * ppp).round() as u32,
        w,
        h1,
    )
    .to_image();
    view.save(dir.join("view.png")).unwrap();
    // The first-use hint is a window overlay at the top of the view, not part of the picture:
    // compared below it.
    let below_hint = |img: &image::RgbaImage| {
        let top = (60.0 * ppp).round() as u32;
        image::imageops::crop_imm(img, 0, top, w, h1 - top).to_image()
    };
    assert!(
        cutaway::gui::viewport::first_use_hint(h.state()).is_some(),
        "the hint this comparison leaves out is no longer shown"
    );
    let d = image_compare::difference(
        &below_hint(&exported),
        &below_hint(&view),
        &image_compare::SAME_PICTURE,
    );
    println!("export vs viewport: {d}");
    assert!(
        d.within(&image_compare::SAME_PICTURE),
        "export differs from the viewport: {d} ({})",
        dir.display()
    );

    // 2× the viewport, transparent background: the picture `cutaway render` makes of the saved
    // session, with the background cleared.
    let session = dir.join("session.json");
    h.state_mut().apply(
        &ctx,
        cutaway::gui::app::Action::SaveSessionTo(session.clone()),
    );
    let two = dir.join("two.png");
    h.state_mut().export_image.width = 2 * w;
    h.state_mut().export_image.height = 2 * h1;
    h.state_mut().export_image.transparent = true;
    h.state_mut()
        .apply(&ctx, cutaway::gui::app::Action::ExportImageTo(two.clone()));
    settle(&mut h);
    let exported = image::open(&two).expect("exported PNG").to_rgba8();
    assert_eq!(exported.dimensions(), (2 * w, 2 * h1));
    assert_eq!(
        exported.get_pixel(2, 2)[3],
        0,
        "background is not transparent"
    );
    let reference = dir.join("cli.png");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_cutaway"))
        .arg("render")
        .arg(&session)
        .arg("--out")
        .arg(&reference)
        .args(["--width", &(2 * w).to_string()])
        .args(["--height", &(2 * h1).to_string()])
        .output()
        .expect("run cutaway render");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let mut reference = image::open(&reference).unwrap().to_rgba8();
    // The CLI draws the scene background; composite the export over it to compare.
    let bg = h.state().scene.render.background;
    let bg = [bg[0], bg[1], bg[2]].map(|c| (c * 255.0).round());
    let mut composited = exported.clone();
    for p in composited.pixels_mut() {
        let a = p[3] as f32 / 255.0;
        for k in 0..3 {
            p[k] = (p[k] as f32 * a + bg[k] * (1.0 - a)).round() as u8;
        }
        p[3] = 255;
    }
    for p in reference.pixels_mut() {
        p[3] = 255;
    }
    let d = image_compare::difference(&composited, &reference, &image_compare::SAME_PICTURE);
    println!("2x transparent export vs cutaway render: {d}");
    assert!(
        d.within(&image_compare::SAME_PICTURE),
        "export differs from `cutaway render`: {d} ({})",
        dir.display()
    );
    let _ = std::fs::remove_dir_all(&dir);
}
