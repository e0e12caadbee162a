//! Groove ends (`scalpel::taper`): the groove's depth goes to zero over a short distance toward
//! both tips instead of dropping to the full depth over one path segment.

use super::*;
use cutter::scalpel::taper::{MIN_DEPTH, TAPER_DEPTHS};

/// Grooves of `depth` along wavy paths of several lengths over a sphere of radius 20 (the
/// patella's size): every floor vertex near either tip is at most as deep as the taper allows
/// at its distance from that tip (the last floor vertex used to sit at the full depth wherever
/// the path ended, down to one segment from the tip, and the first one at the full depth one
/// segment from the start), the ones far from both ends are at the full depth, and the sphere
/// stays closed and manifold after every step.
#[test]
fn groove_ends_taper_to_the_tips() {
    let r = 20.0;
    let depth = 3.0;
    let reach = TAPER_DEPTHS * depth;
    let sphere = csg::testkit::icosphere(5, r);
    let path = wavy_arc(r, 60);
    // Paths of several lengths, so that the end falls at different distances after the last
    // floor change (the last floor vertex is then raised toward the tip).
    let (mut near, mut near_start, mut far) = (0, 0, 0);
    for samples in [40, 46, 52, 60] {
        let path = &path[..=samples];
        let mut s = Scalpel::new(&sphere, ScalpelOptions::default().with_depth(depth)).unwrap();
        groove_strokes(&mut s, &[path.to_vec()]);
        let segments = s.segments();
        let tip = segments[segments.len() - 1].pb;
        let start = segments[0].pa;
        let m = s.dyn_mesh();
        let floors: Vec<u32> = (0..m.vertex_count() as u32)
            .filter(|&v| m.is_floor(v))
            .collect();
        assert!(floors.len() >= 2, "{} floor vertices", floors.len());
        for &f in &floors {
            let p = m.pos(f);
            let below = r - p.length();
            let above = p.normalize() * r;
            let to_tip = tip.distance(above);
            let to_start = start.distance(above);
            let allowed = depth * (to_tip.min(to_start) / reach).clamp(MIN_DEPTH, 1.0);
            let across = path
                .iter()
                .map(|q| q.distance(above))
                .fold(f64::INFINITY, f64::min);
            println!(
                "floor at {to_tip:.2} from the end tip, {to_start:.2} from the start ({across:.2} from the nearest sample): {below:.3} deep (allowed {allowed:.3})"
            );
            assert!(
                below <= allowed * 1.05 + 1e-9,
                "floor vertex {to_tip} from the end tip, {to_start} from the start is {below} deep (taper allows {allowed})"
            );
            if to_start < reach {
                near_start += 1;
            } else if to_tip >= reach {
                far += 1;
                assert!(
                    below >= 0.9 * depth,
                    "floor vertex {to_tip} from the end tip is only {below} deep"
                );
            } else {
                near += 1;
            }
        }
    }
    assert!(
        near >= 1 && near_start >= 1 && far >= 1,
        "{near} floor vertices near the end tip, {near_start} near the start, {far} far"
    );
}
