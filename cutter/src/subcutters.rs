//! Ribbon and slice sub-cutters (thesis 3.4.2–3.4.3): thin boxes across the cutter's path.
//!
//! A sub-cutter is a two-plane [`Cutter`] of width `width` along the path, centred either on each
//! bounded cutting plane or at regular arc-length intervals along the path (its height and depth
//! interpolated from the planes on either side). The boolean of each sub-cutter with the target
//! gives a ribbon (no walls) or a slice (with walls); that choice is the renderer's.

use glam::DVec3;

use crate::cutter::{CutKind, Cutter};
use crate::plane::BoundedPlane;

/// One thin box centred on each plane of `cutter`, `width` wide along the path.
pub fn on_planes(cutter: &Cutter, width: f64) -> Vec<Cutter> {
    let path = cutter.path();
    (0..cutter.planes.len())
        .filter_map(|i| thin_box(&cutter.planes[i], tangent(&path, i), width))
        .collect()
}

/// `count` thin boxes at regular arc-length intervals along the path (the first and last centred
/// half an interval in from the ends), planes interpolated between their neighbours.
pub fn at_intervals(cutter: &Cutter, count: usize, width: f64) -> Vec<Cutter> {
    let path = cutter.path();
    if count == 0 || path.len() < 2 {
        return Vec::new();
    }
    let mut cumulative = vec![0.0];
    for w in path.windows(2) {
        let last = *cumulative.last().unwrap_or(&0.0);
        cumulative.push(last + (w[1] - w[0]).length());
    }
    let total = *cumulative.last().unwrap_or(&0.0);
    if total <= 0.0 {
        return Vec::new();
    }
    (0..count)
        .filter_map(|k| {
            let s = total * (k as f64 + 0.5) / count as f64;
            let i = cumulative
                .partition_point(|&c| c <= s)
                .clamp(1, path.len() - 1)
                - 1;
            let seg = cumulative[i + 1] - cumulative[i];
            let t = if seg > 0.0 {
                (s - cumulative[i]) / seg
            } else {
                0.0
            };
            let plane = cutter.planes[i].lerp(&cutter.planes[i + 1], t);
            let dir = (path[i + 1] - path[i]).normalize_or_zero();
            thin_box(&plane, dir, width)
        })
        .collect()
}

fn tangent(path: &[DVec3], i: usize) -> DVec3 {
    let lo = i.saturating_sub(1);
    let hi = (i + 1).min(path.len() - 1);
    (path[hi] - path[lo]).normalize_or_zero()
}

/// A box of `width` centred on `plane`, extending along the plane's normal (oriented along `dir`).
fn thin_box(plane: &BoundedPlane, dir: DVec3, width: f64) -> Option<Cutter> {
    let mut n = plane.normal();
    if n == DVec3::ZERO || width <= 0.0 {
        return None;
    }
    if n.dot(dir) < 0.0 {
        n = -n;
    }
    let half = n * (0.5 * width);
    let c = Cutter {
        kind: CutKind::Straight,
        smooth: false,
        planes: vec![plane.translated(-half), plane.translated(half)],
    };
    c.sanity_check().ok().map(|_| c)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cutter() -> Cutter {
        let planes = (0..5)
            .map(|i| {
                let x = i as f64 * 2.0;
                BoundedPlane::from_front_edge(
                    DVec3::new(x, 0.0, 1.0),
                    DVec3::new(x, 0.0, -1.0),
                    DVec3::Y,
                    1.0 + i as f64,
                )
            })
            .collect();
        Cutter {
            kind: CutKind::Curving,
            smooth: false,
            planes,
        }
    }

    #[test]
    fn ribbons_on_planes_are_thin_valid_boxes() {
        let r = on_planes(&cutter(), 0.2);
        assert_eq!(r.len(), 5);
        for (i, c) in r.iter().enumerate() {
            c.sanity_check().unwrap();
            assert!((c.quad_mesh().volume() - 0.2 * 2.0 * (1.0 + i as f64)).abs() < 1e-9);
        }
    }

    #[test]
    fn slices_at_intervals_interpolate_depth() {
        let r = at_intervals(&cutter(), 4, 0.1);
        assert_eq!(r.len(), 4);
        // Path length 8: centres at x = 1, 3, 5, 7; depth 1 + x/2.
        for (k, c) in r.iter().enumerate() {
            let x = 1.0 + 2.0 * k as f64;
            let mid = (c.planes[0].front_mid() + c.planes[1].front_mid()) * 0.5;
            assert!((mid.x - x).abs() < 1e-9);
            assert!((c.planes[0].depth() - (1.0 + x / 2.0)).abs() < 1e-9);
        }
    }
}
