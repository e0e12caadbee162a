//! Groove walls are well shaped (`scalpel::groove`, "Wall shape"): no fan of long thin wall
//! triangles from a floor vertex shared far along the path.

use super::*;

/// Smallest angles (degrees) of the groove's wall triangles, sorted.
fn wall_angles(s: &Scalpel) -> Vec<f64> {
    let m = s.dyn_mesh();
    let mut angles: Vec<f64> = (0..m.triangle_count() as u32)
        .filter(|&t| m.is_wall(t))
        .map(|t| min_angle_deg(m, t))
        .collect();
    angles.sort_by(f64::total_cmp);
    angles
}

/// A wavy groove across a sphere of radius 20 (the patella's size, edges of about 0.75) at a
/// blade depth of one edge and of four edges (the window's default on the patella): the
/// smallest angle of every wall triangle is above a bound (9° and 4.5°: a strip of quads with a
/// floor vertex under every lip vertex would give about 45° and 14°, a fan reaching one blade
/// depth along the path half that), and nine in ten are above a higher one (14° and 6.5°).
/// Measured: 11.2° and 5.4° smallest, 17.4° and 7.7° at the tenth. A floor vertex shared over
/// six blade depths made fans whose farthest triangles had angles of 1.5° and 1.8° (2.1° and
/// 2.5° at the tenth).
#[test]
fn groove_walls_are_well_shaped() {
    let r = 20.0;
    let sphere = csg::testkit::icosphere(5, r);
    let path = wavy_arc(r, 60);
    for (depth, worst_bound, tenth_bound) in [(0.75, 9.0, 14.0), (3.0, 4.5, 6.5)] {
        let mut s = Scalpel::new(&sphere, ScalpelOptions::default().with_depth(depth)).unwrap();
        groove_strokes(&mut s, std::slice::from_ref(&path));
        let angles = wall_angles(&s);
        assert!(angles.len() >= 40, "{} wall triangles", angles.len());
        let tenth = angles[angles.len() / 10];
        println!(
            "depth {depth}: {} wall triangles, smallest angle {:.1}°, 10th percentile {tenth:.1}°, median {:.1}°",
            angles.len(),
            angles[0],
            angles[angles.len() / 2]
        );
        assert!(
            angles[0] >= worst_bound,
            "depth {depth}: a wall triangle has an angle of {:.2}°",
            angles[0]
        );
        assert!(
            tenth >= tenth_bound,
            "depth {depth}: one wall triangle in ten has an angle under {tenth:.2}°"
        );
    }
}
