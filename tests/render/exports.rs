//! A transparent background and a tiled export, and the sample pictures for people to look at.

use super::*;

#[test]
fn transparent_background_and_tiled_export() {
    let Some(mut r) = renderer() else { return };
    let scene = layered_scene();
    let mut options = RenderPngOptions::new(WIDTH, HEIGHT);
    options.deterministic = true;
    options.transparent_background = true;
    let image = render_with(&mut r, &scene, &options).unwrap();
    assert_eq!(pixel(&image, 0, 0)[3], 0, "corner should be transparent");
    assert_eq!(
        pixel(&image, WIDTH / 2, HEIGHT / 2)[3],
        255,
        "model should be opaque"
    );
    // A 2600×40 strip needs two tiles across; the seam must not show.
    let mut options = RenderPngOptions::new(2600, 40);
    options.deterministic = true;
    let wide = render_with(&mut r, &scene, &options).unwrap();
    assert_eq!(wide.dimensions(), (2600, 40));
    for y in 0..40 {
        let (a, b) = (pixel(&wide, 2047, y), pixel(&wide, 2048, y));
        let d = (0..3)
            .map(|k| (a[k] as i32 - b[k] as i32).abs())
            .max()
            .unwrap_or(0);
        assert!(d < 40, "seam at row {y}: {a:?} vs {b:?}");
    }
}

/// Not a check: writes larger supersampled pictures of every view for people to look at
/// (`cargo test --test render -- --ignored sample`; files in the target's tmp folder).
#[test]
#[ignore]
fn sample_renders_for_people() {
    let Some(mut r) = renderer() else { return };
    let sub = Some(even_sub_cutters(4, 0.1));
    let views = [
        ("sample_plain", None),
        ("sample_cut", Some(CutterViews::default())),
        (
            "sample_transparency_ribbons",
            Some(CutterViews {
                transparency: Some(0.3),
                ribbons: sub,
                ..CutterViews::default()
            }),
        ),
        (
            "sample_slices",
            Some(CutterViews {
                transparency: Some(0.25),
                slices: sub,
                ..CutterViews::default()
            }),
        ),
    ];
    for (name, v) in views {
        let scene = match v {
            Some(v) => with_cutter(layered_scene(), v),
            None => layered_scene(),
        };
        let image = render_with(&mut r, &scene, &RenderPngOptions::new(640, 480)).unwrap();
        let path = actual_dir().join(format!("{name}.png"));
        image.save(&path).unwrap();
        println!("wrote {}", path.display());
    }
}
