//! Groove walls are well shaped (`scalpel::groove`, "Wall shape"): strips of quads, no fan of
//! long thin wall triangles from a floor vertex shared far along the path.

use super::lips::groove_cases;
use super::*;

/// For each wall triangle of the groove: its smallest angle (degrees) and that angle over what
/// a strip quad with a lip edge as long as the triangle's shortest edge has at the blade depth
/// (about `atan(shortest / depth)`; a lip edge much shorter than the blade is deep makes thin
/// wall triangles in any wall, a fan makes them thinner still). Sorted by the ratio.
fn wall_angles(s: &Scalpel, depth: f64) -> Vec<(f64, f64)> {
    let m = s.dyn_mesh();
    let mut out: Vec<(f64, f64)> = (0..m.triangle_count() as u32)
        .filter(|&t| m.is_wall(t))
        .map(|t| {
            let [a, b, c] = m.triangles()[t as usize].map(|v| m.pos(v));
            let shortest = a.distance(b).min(b.distance(c)).min(c.distance(a));
            let angle = min_angle_deg(m, t);
            let strip = (shortest / depth).atan().to_degrees().min(45.0);
            (angle, angle / strip)
        })
        .collect();
    out.sort_by(|x, y| x.1.total_cmp(&y.1));
    out
}

/// A wavy groove across a sphere of radius 20 (the patella's size, edges of about 0.75) at a
/// blade depth of one edge and of four edges (the window's default on the patella), and grooves
/// on the knee and the head: no wall triangle is thinner than 0.6 of what a strip quad with its
/// shortest edge gives (a fan reaching `s` along the path from its floor vertex gives
/// `d² / (s² + d²)` of it), and at depth one edge, where the strip's quads are nearly square, the
/// smallest wall angle is above 10°. Measured: the worst ratio 0.95 and 0.94 (sphere, depths
/// 0.75 and 3), 0.91 (patella), 0.95 (femur), 0.74 (skin); floor vertices shared over about a
/// blade depth of path (fans) gave 0.32, 0.55, 0.53, 0.41, 0.37. The smallest angles themselves
/// are set by the shortest lip edges (the cut splits some edges near a vertex): 11.3° and 3.0° on
/// the sphere, 0.3° on the patella, whose thin triangles leave lip edges of a hundredth of the
/// blade depth.
#[test]
fn groove_walls_are_well_shaped() {
    for (name, mesh, path, depth) in groove_cases(&[0.75, 3.0]) {
        let mut s = Scalpel::new(&mesh, ScalpelOptions::default().with_depth(depth)).unwrap();
        s.cut_stroke(&path).unwrap();
        let angles = wall_angles(&s, depth);
        assert!(
            angles.len() >= 40,
            "{name}: {} wall triangles",
            angles.len()
        );
        let smallest = angles.iter().map(|a| a.0).fold(180.0, f64::min);
        println!(
            "{name} depth {depth}: {} wall triangles, smallest angle {smallest:.1}°, worst ratio to a strip {:.2} (at {:.1}°), tenth {:.2}",
            angles.len(),
            angles[0].1,
            angles[0].0,
            angles[angles.len() / 10].1,
        );
        assert!(
            angles[0].1 >= 0.6,
            "{name} depth {depth}: a wall triangle of {:.2}° is {:.2} of a strip's",
            angles[0].0,
            angles[0].1
        );
        if depth < 1.0 {
            assert!(smallest >= 10.0, "{name}: a wall angle of {smallest}°");
        }
    }
}
