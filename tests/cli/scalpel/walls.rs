//! The opened incision reads as a cut: `cutaway scalpel` marks the groove's walls in its PLY
//! output and `cutaway render` of a session naming that file `"exact"` draws them in the wall
//! colour (the model's colour leaning toward the cut walls' cream), with a hard edge at the lips.

use super::*;

/// Linear light of an sRGB byte.
fn linear(c: u8) -> f64 {
    let c = c as f64 / 255.0;
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// Whether pixel (x, y) has the wall colour's hue. The model is drawn in [0.9, 0.75, 0.65]
/// (sRGB), linear green/red 0.66 and blue/red 0.48 whatever the light (diffuse light scales the
/// three alike; the white highlight lifts green/red to 0.73 at most); its walls in the mix
/// toward `WALL_TINT`, [0.95, 0.86, 0.73]: green/red 0.80, blue/red 0.55. Pixels within two of
/// the background (white) are left out: the silhouette's edge blends the model with white.
fn wall_coloured(image: &image::RgbImage, x: u32, y: u32) -> bool {
    let white = image::Rgb([255u8, 255, 255]);
    let (w, h) = image.dimensions();
    for v in y.saturating_sub(2)..(y + 3).min(h) {
        for u in x.saturating_sub(2)..(x + 3).min(w) {
            if *image.get_pixel(u, v) == white {
                return false;
            }
        }
    }
    let [r, g, b] = image.get_pixel(x, y).0.map(linear);
    r > 0.02 && (0.76..0.9).contains(&(g / r)) && (0.45..0.7).contains(&(b / r))
}

/// The groove of `opened_groove_on_the_patella_shows_along_its_whole_path_at_1280x800`, opened
/// 2 mm, rendered at 1280×800 from its marked PLY (`"exact": true`, walls drawn) and from the
/// same file read as an ordinary mesh (welded: no marks). With the marks, wall-coloured pixels
/// lie along the whole incision (at nine in ten drawn points or more, at least 20 in a 25×25
/// window around the point) and none farther than 100 pixels (about 4.5 mm) from the drawn
/// path; without them there is no wall-coloured pixel at all (the colour comes from the marks,
/// not from the light). The images are left in the test's scratch folder to look at.
#[test]
fn opened_groove_on_the_patella_draws_its_walls_in_the_wall_colour_at_1280x800() {
    let dir = scratch("patella-walls");
    let target = patella();
    let mesh = cutaway::io::read_mesh(&target).unwrap();
    let points = patella_arc(&mesh);
    let (w, h) = (1280u32, 800u32);
    let (eye, look_at) = ([0.0, -110.0, 36.0], [0.0, -44.0, 35.0]);
    let (path, out) = (dir.join("p.json"), dir.join("cut.ply"));
    let json = serde_json::json!({"format": "cutaway-path/1", "depth": 3.0, "tool": "scalpel",
        "points": points, "open": {"width": 2.0, "window": 0.5}});
    std::fs::write(&path, json.to_string()).unwrap();
    run_json(&target, &path, &out);
    let header = std::fs::read(&out).unwrap();
    let header = String::from_utf8_lossy(&header[..400]);
    assert!(header.contains("property uchar cutaway_wall"), "{header}");
    let mut images = Vec::new();
    let view = View {
        eye,
        look_at,
        size: (w, h),
    };
    for exact in [true, false] {
        let Some(image) = view.render(&out, Some(exact), &dir.join(format!("walls-{exact}")))
        else {
            return;
        };
        images.push(image);
    }
    let (walls, plain) = (&images[0], &images[1]);
    let pixel = |p: [f64; 3]| view.pixel(p);
    let drawn: Vec<(f64, f64)> = points.iter().map(|&p| pixel(p)).collect();
    let (first, last) = (points[0], points[points.len() - 1]);
    let dist = |a: [f64; 3], b: [f64; 3]| csg::DVec3::from(a).distance(csg::DVec3::from(b));
    let (mut shown, mut inner) = (0, 0);
    let mut counts = Vec::new();
    for (&p, &(px, py)) in points.iter().zip(&drawn) {
        if dist(p, first) < 4.0 || dist(p, last) < 4.0 {
            continue;
        }
        inner += 1;
        let mut n = 0;
        for y in (py as i64 - 12)..=(py as i64 + 12) {
            for x in (px as i64 - 12)..=(px as i64 + 12) {
                if x >= 0 && y >= 0 && wall_coloured(walls, x as u32, y as u32) {
                    n += 1;
                }
            }
        }
        counts.push(n);
        if n >= 20 {
            shown += 1;
        }
    }
    assert!(inner >= 20, "{inner} points");
    assert!(
        10 * shown >= 9 * inner,
        "wall-coloured pixels at {shown} of {inner} drawn points: {counts:?}"
    );
    let (mut far, mut total) = (0, 0);
    for (x, y, _) in walls.enumerate_pixels() {
        if !wall_coloured(walls, x, y) {
            continue;
        }
        total += 1;
        let near = drawn
            .iter()
            .any(|&(px, py)| (px - x as f64).hypot(py - y as f64) <= 100.0);
        if !near {
            far += 1;
        }
    }
    assert!(total > 2000, "{total} wall-coloured pixels");
    assert_eq!(far, 0, "wall-coloured pixels far from the incision");
    let unmarked = plain
        .enumerate_pixels()
        .filter(|&(x, y, _)| wall_coloured(plain, x, y))
        .count();
    assert_eq!(unmarked, 0, "wall-coloured pixels without the marks");
}
