//! Tests of [`super`] (`wall_risk.rs`): distances against brute force, the lower bound at every
//! point of a refined triangle, the inside of a closed structure at distance 0.

use super::*;
use crate::cutting::cut_results::PreviewPart;
use crate::scene::SceneModel;

/// A scene with a critical sphere (radius 5 about the origin, mm) named `vessel`.
fn scene_with_vessel() -> Scene {
    let mut scene = Scene::default();
    scene.models.push(SceneModel::new(
        "vessel",
        "vessel.obj",
        Arc::new(csg::testkit::icosphere(2, 5.0)),
        [0.8, 0.1, 0.1],
    ));
    scene.models.push(SceneModel::new(
        "skin",
        "skin.obj",
        Arc::new(csg::testkit::icosphere(1, 50.0)),
        [0.9, 0.7, 0.6],
    ));
    scene.risk = RiskSettings {
        critical: vec!["vessel".into()],
        ..RiskSettings::default()
    };
    scene
}

/// A preview whose only part is `wall`, a wall of cutter 0 on model 1.
fn preview_with_wall(wall: Mesh) -> PreviewGeometry {
    PreviewGeometry {
        replaced: vec![false, true],
        parts: vec![PreviewPart {
            model: 1,
            cutter: 0,
            kind: PartKind::Wall,
            opacity: 1.0,
            mesh: wall,
        }],
        ..PreviewGeometry::default()
    }
}

/// A square wall in the plane x = `x`, `half` across from the x axis, as two triangles.
fn square_wall(x: f64, half: f64) -> Mesh {
    Mesh {
        positions: vec![
            DVec3::new(x, -half, -half),
            DVec3::new(x, half, -half),
            DVec3::new(x, half, half),
            DVec3::new(x, -half, half),
        ],
        triangles: vec![[0, 1, 2], [0, 2, 3]],
    }
}

/// The distance from `p` to the solid `mesh` (closed, outward, convex) by brute force: every
/// triangle's closest point, and 0 inside (behind every face's plane).
fn brute(mesh: &Mesh, p: DVec3) -> f64 {
    let mut inside = true;
    let mut best = f64::INFINITY;
    for t in 0..mesh.triangle_count() {
        let [a, b, c] = mesh.corners(t);
        inside &= (b - a).cross(c - a).dot(p - a) < 0.0;
        let (q, _) = csg::spatial::closest_on_triangle(p, a, b, c);
        best = best.min(p.distance(q));
    }
    if inside { 0.0 } else { best }
}

/// Points spread over triangle `t` of `mesh`, with the interpolated corner value there.
fn samples(wall: &RiskWall, t: usize) -> Vec<(DVec3, f64)> {
    let [a, b, c] = wall.mesh.corners(t);
    let v = wall.corner_mm[t].map(f64::from);
    let n = 4;
    let mut out = Vec::new();
    for i in 0..=n {
        for j in 0..=n - i {
            let (u, w) = (i as f64 / n as f64, j as f64 / n as f64);
            let p = a + (b - a) * u + (c - a) * w;
            out.push((p, v[0] + (v[1] - v[0]) * u + (v[2] - v[0]) * w));
        }
    }
    out
}

fn longest_edge(mesh: &Mesh, t: usize) -> f64 {
    let p = mesh.corners(t);
    (0..3)
        .map(|k| (p[k] - p[(k + 1) % 3]).length())
        .fold(0.0, f64::max)
}

#[test]
fn corner_distances_match_brute_force_and_bound_every_point_from_below() {
    let scene = scene_with_vessel();
    let vessel = scene.models[0].model.mesh.clone();
    // 1.5 mm from the vessel at its closest, reaching 20 mm away: red, band and beyond.
    let preview = preview_with_wall(square_wall(6.5, 20.0));
    let risk = wall_risk(&scene, &preview, &mut CriticalIndexes::default()).expect("a map");
    assert_eq!(risk.walls.len(), 1);
    let wall = &risk.walls[0];
    assert!(wall.matches(&preview.parts[0]));
    assert_eq!(wall.corner_mm.len(), wall.mesh.triangle_count());
    assert!(
        wall.mesh.triangle_count() > 100,
        "{} triangles: the wall was not refined",
        wall.mesh.triangle_count()
    );
    let nearest = risk.nearest.as_ref().expect("nearest");
    assert_eq!(nearest.structure, "vessel");
    let truth = brute(&vessel, DVec3::new(6.5, 0.0, 0.0));
    assert!(
        nearest.distance_mm >= truth - 1e-9 && nearest.distance_mm < truth + 0.05,
        "{} vs {truth}",
        nearest.distance_mm
    );
    let mut red_points = 0;
    for t in 0..wall.mesh.triangle_count() {
        let l = longest_edge(&wall.mesh, t);
        // Each corner: the exact distance, or that less the triangle's longest edge.
        for (k, &v) in wall.mesh.triangles[t].iter().enumerate() {
            let exact = brute(&vessel, wall.mesh.positions[v as usize]);
            let shown = f64::from(wall.corner_mm[t][k]);
            let is_exact = (shown - exact).abs() < 1e-4;
            let is_lowered = (shown - (exact - l)).abs() < 1e-4;
            assert!(
                is_exact || is_lowered,
                "triangle {t} corner {k}: {shown} for {exact} (edge {l})"
            );
        }
        for (p, shown) in samples(wall, t) {
            let exact = brute(&vessel, p);
            // Never safer than it is: as dangerous a side of each line, and inside the band
            // (where the shade is read) at most the true distance.
            let side = |d: f64| usize::from(d > 2.0) + usize::from(d >= 10.0);
            assert!(
                side(shown) <= side(exact),
                "{p}: shown {shown} is safer than exact {exact}"
            );
            if side(shown) == 1 {
                assert!(shown <= exact + 1e-4, "{p}: shown {shown} > exact {exact}");
            }
            // Never more than two band edges more dangerous.
            assert!(
                shown >= exact - 2.0 * BAND_EDGE_MM - 1e-4 || side(shown) == side(exact),
                "{p}: shown {shown} << exact {exact}"
            );
            if exact <= 2.0 {
                red_points += 1;
            }
            // The lines are where they are, up to two finest edges toward danger.
            let slack = 2.0 * risk.margin_mm + 1e-4;
            if exact > 2.0 + slack {
                assert!(shown > 2.0, "{p}: {exact} mm away, shown red ({shown})");
            }
            if exact >= 10.0 + slack {
                assert!(shown >= 10.0, "{p}: {exact} mm away, shown {shown}");
            }
        }
    }
    assert!(red_points > 0, "no sample within 2 mm");
    assert_eq!(risk.margin_mm, FINEST_EDGE_MM);
}

/// One large wall triangle whose corners are all over 10 mm from a small structure that passes
/// 1 mm from its middle: interpolating the corners would call it safe; the map shows red there.
#[test]
fn a_structure_near_the_middle_of_a_large_triangle_shows_red() {
    let mut scene = scene_with_vessel();
    let ball = {
        let mut m = csg::testkit::icosphere(2, 1.0);
        for p in &mut m.positions {
            p.x += 2.0;
        }
        m
    };
    scene.models[0].model.mesh = Arc::new(ball);
    // The triangle lies in x = 0; the ball's surface is 1 mm from it at the origin.
    let wall = Mesh {
        positions: vec![
            DVec3::new(0.0, -30.0, -20.0),
            DVec3::new(0.0, 30.0, -20.0),
            DVec3::new(0.0, 0.0, 35.0),
        ],
        triangles: vec![[0, 1, 2]],
    };
    for &p in &wall.positions {
        assert!(brute(&scene.models[0].model.mesh, p) > 10.0);
    }
    let preview = preview_with_wall(wall);
    let risk = wall_risk(&scene, &preview, &mut CriticalIndexes::default()).expect("a map");
    let wall = &risk.walls[0];
    let at_origin = (0..wall.mesh.triangle_count())
        .flat_map(|t| samples(wall, t))
        .filter(|(p, _)| p.length() < 0.3)
        .map(|(_, shown)| shown)
        .fold(f64::NEG_INFINITY, f64::max);
    assert!(
        at_origin.is_finite() && at_origin <= 2.0,
        "shown {at_origin} mm at the point 1 mm from the structure"
    );
}

#[test]
fn a_wall_through_a_closed_structure_is_at_distance_zero_inside_it() {
    let scene = scene_with_vessel();
    // Through the vessel's middle: the part inside is 0, not the distance to its surface.
    let preview = preview_with_wall(square_wall(0.0, 12.0));
    let risk = wall_risk(&scene, &preview, &mut CriticalIndexes::default()).expect("a map");
    let wall = &risk.walls[0];
    assert_eq!(risk.nearest.as_ref().unwrap().distance_mm, 0.0);
    let mut inside = 0;
    for (t, tri) in wall.mesh.triangles.iter().enumerate() {
        for (k, &v) in tri.iter().enumerate() {
            let p = wall.mesh.positions[v as usize];
            if p.length() < 4.0 {
                inside += 1;
                assert!(wall.corner_mm[t][k] <= 0.0, "{p}: {}", wall.corner_mm[t][k]);
            }
        }
    }
    assert!(inside > 0);
}

#[test]
fn no_map_when_off_or_when_no_critical_name_is_a_structure() {
    let mut scene = scene_with_vessel();
    let preview = preview_with_wall(square_wall(6.5, 20.0));
    let mut indexes = CriticalIndexes::default();
    scene.risk.shown = false;
    assert!(wall_risk(&scene, &preview, &mut indexes).is_none());
    scene.risk.shown = true;
    scene.risk.critical = vec!["liver".into()];
    assert!(wall_risk(&scene, &preview, &mut indexes).is_none());
    scene.risk.critical = vec!["liver".into(), "vessel".into()];
    let risk = wall_risk(&scene, &preview, &mut indexes).expect("a map");
    assert_eq!(risk.missing, vec!["liver".to_string()]);
    // A scalpel incision (no cutter) and a kept part get no map.
    let mut other = preview.clone();
    other.parts[0].cutter = usize::MAX;
    assert!(
        wall_risk(&scene, &other, &mut indexes)
            .unwrap()
            .walls
            .is_empty()
    );
}

#[test]
fn a_wall_in_metres_is_measured_in_millimetres() {
    let mut scene = scene_with_vessel();
    let scale = |m: &Mesh| {
        let mut m = m.clone();
        for p in &mut m.positions {
            *p *= 0.001;
        }
        m
    };
    for model in &mut scene.models {
        model.model.mesh = Arc::new(scale(&model.model.mesh));
    }
    scene.unit = crate::scene::LengthUnit::Metre;
    let preview = preview_with_wall(scale(&square_wall(6.5, 20.0)));
    let risk = wall_risk(&scene, &preview, &mut CriticalIndexes::default()).expect("a map");
    let d = risk.nearest.unwrap().distance_mm;
    assert!((1.4..1.6).contains(&d), "{d} mm");
}
