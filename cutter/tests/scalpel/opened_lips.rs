//! The opened incision shows two clean lips along the drawn path (`scalpel::drawn`,
//! `scalpel::lip_measure`): each lip lies on the drawn path's offset curve, turns without
//! spikes away from the tips, stays apart from the other lip by most of the width, and no
//! surface triangle folds. Each case prints the figures of the opening along the rest-pose cut
//! (before: its zigzag along the mesh edges shifted sideways) and onto the drawn path (now).

use super::unfold::{bumpy_sphere, largest_turn};
use super::*;
use cutter::scalpel::OpenOptions;
use cutter::scalpel::dffd::{open_displacements, open_displacements_along_cut, taper_length};
use cutter::scalpel::lip_measure::{LipReport, Reference, lip_groups};
use cutter::scalpel::unfold::MAX_TURN_DEG;

/// Largest Hausdorff distance of a lip to its offset curve, in widths (the lip's chords between
/// its points across the curving path count: on the sheet they are 1.3 long on a path of radius
/// 2.7, 0.13 widths off the curve).
const HAUSDORFF_WIDTHS: f64 = 0.15;
/// Largest distance of a lip point to its offset curve, in widths.
const POINT_WIDTHS: f64 = 0.06;
/// Largest turn between consecutive lip edges away from the tips (degrees).
const LIP_TURN_DEG: f64 = 30.0;
/// Smallest gap between the lips where the taper is 1, in widths.
const GAP_WIDTHS: f64 = 0.8;

/// The display positions of `s` opened to `w` after the whole time window: onto the drawn path,
/// or (`along_cut`) as before, along the rest-pose cut.
fn shown(s: &Scalpel, w: f64, along_cut: bool) -> Vec<DVec3> {
    let open = OpenOptions {
        width: w,
        window: 0.5,
    };
    let mut out = s.dyn_mesh().positions().to_vec();
    let moved = if along_cut {
        open_displacements_along_cut(s, &open, s.clock())
    } else {
        open_displacements(s, &open, s.clock())
    };
    for (v, p) in moved {
        out[v as usize] = p;
    }
    out
}

/// Figures before and after for the cut `s` along `path` (surface points with their normals)
/// opened to `w`, printed under `name`; the figures after, and the largest surface turn.
fn measure(name: &str, s: &mut Scalpel, path: &[(DVec3, DVec3)], w: f64) -> (LipReport, f64) {
    s.advance_clock(1.0);
    let reference = Reference::new(path, w, taper_length(w, s.options().depth));
    let mut after = (LipReport::default(), 0.0);
    for along_cut in [true, false] {
        let shown = shown(s, w, along_cut);
        let r = reference.measure(&lip_groups(s, &shown));
        let turn = largest_turn(s, &shown);
        println!(
            "{name} {}: Hausdorff {:.3} w, points {:.3} w, lip turn {:.1}°, gap {:.2} w, same side {}, surface turn {turn:.1}°, lip points {:?}",
            if along_cut { "before" } else { "after " },
            r.hausdorff / w,
            r.point_distance / w,
            r.worst_turn_deg,
            r.min_gap / w,
            r.same_side,
            r.points
        );
        after = (r, turn);
    }
    after
}

fn assert_clean(name: &str, (r, turn): (LipReport, f64), w: f64) {
    assert!(r.points[0] >= 10 && r.points[1] >= 10, "{name}: {r:?}");
    assert_eq!(r.same_side, 0, "{name}: lips crossed: {r:?}");
    assert!(
        r.hausdorff <= HAUSDORFF_WIDTHS * w,
        "{name}: a lip is {:.3} widths from its offset curve",
        r.hausdorff / w
    );
    assert!(
        r.point_distance <= POINT_WIDTHS * w,
        "{name}: a lip point is {:.3} widths from its offset curve",
        r.point_distance / w
    );
    assert!(
        r.worst_turn_deg <= LIP_TURN_DEG,
        "{name}: a lip turns {:.1}° between two edges (a spike)",
        r.worst_turn_deg
    );
    assert!(
        r.min_gap >= GAP_WIDTHS * w,
        "{name}: the lips come within {:.2} widths",
        r.min_gap / w
    );
    assert!(
        turn <= MAX_TURN_DEG + 1e-6,
        "{name}: a surface triangle turned {turn:.1}°"
    );
}

/// On the sphere, the drawn samples with the sphere's normals.
fn on_sphere(samples: &[DVec3]) -> Vec<(DVec3, DVec3)> {
    samples.iter().map(|&p| (p, p.normalize())).collect()
}

#[test]
fn an_opened_groove_and_slit_on_a_sphere_have_lips_on_the_drawn_path() {
    let r = 20.0;
    let sphere = csg::testkit::icosphere(5, r);
    let samples = wavy_arc(r, 60);
    let w = 2.0;
    for (name, depth) in [("sphere groove", 3.0), ("sphere slit", 0.0)] {
        let mut s = Scalpel::new(&sphere, ScalpelOptions::default().with_depth(depth)).unwrap();
        s.cut_stroke(&samples).unwrap();
        let after = measure(name, &mut s, &on_sphere(&samples), w);
        assert_clean(name, after, w);
    }
}

#[test]
fn opened_grooves_on_a_bumpy_surface_have_lips_on_the_drawn_path() {
    use cutter::scalpel::cut_point::closest_face;
    let r = 60.0;
    let w = 3.0;
    let mut cases = 0;
    for seed in 1..=6u64 {
        let mesh = bumpy_sphere(r, 0.012, seed);
        let mut s = Scalpel::new(&mesh, ScalpelOptions::default().with_depth(4.0)).unwrap();
        // A wavy stroke over the front, every sample on the surface (with its face's normal).
        let path: Vec<(DVec3, DVec3)> = (0..=40)
            .map(|i| {
                let u = i as f64 / 40.0;
                let lon = -0.5 + 1.0 * u;
                let lat = 0.08 * (u * 3.1).sin();
                DVec3::new(lat.cos() * lon.sin(), -lat.cos() * lon.cos(), lat.sin()) * r
            })
            .filter_map(|q| {
                let (t, b, _) = closest_face(s.dyn_mesh(), q)?;
                let m = s.dyn_mesh();
                let [a, bb, c] = m.triangles()[t as usize].map(|v| m.pos(v));
                Some((
                    a * b.x + bb * b.y + c * b.z,
                    (bb - a).cross(c - a).normalize(),
                ))
            })
            .collect();
        let samples: Vec<DVec3> = path.iter().map(|p| p.0).collect();
        if let Err(e) = s.cut_stroke(&samples) {
            println!("seed {seed}: {e}");
            continue;
        }
        let name = format!("bumpy seed {seed}");
        let after = measure(&name, &mut s, &path, w);
        assert_clean(&name, after, w);
        cases += 1;
    }
    assert!(cases >= 4, "only {cases} strokes were cut");
}

#[test]
fn an_opened_wavy_slit_on_a_sheet_has_lips_on_the_drawn_path() {
    let mesh = sheet(20);
    let mut s = Scalpel::new(&mesh, ScalpelOptions::default()).unwrap();
    let path: Vec<(DVec3, DVec3)> = (0..=56)
        .map(|i| {
            let x = 3.0 + 0.25 * i as f64;
            (p(x, 10.0 + 1.5 * (0.5 * x).sin()), DVec3::Z)
        })
        .collect();
    let samples: Vec<DVec3> = path.iter().map(|p| p.0).collect();
    s.cut_stroke(&samples).unwrap();
    let w = 0.6;
    let after = measure("sheet slit", &mut s, &path, w);
    assert_clean("sheet slit", after, w);
}
