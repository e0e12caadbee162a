//! Adaptive subdivision of a smooth box-chain cutter: every level where the path curves, fewer
//! where it runs straight, without cracks.
//!
//! A box chain (a curving or straight cutter) subdivided uniformly is a grid on its sides: rings
//! of points around the cross-section, one ring per path parameter `t` (plane `i` is ring
//! `t = i`, each level adds rings halfway between), with the domed end caps closing the first
//! and last ring. The four-point rule reproduces straight lines, so where the path runs straight
//! the rings between two planes lie on the segments joining them and carry no shape, while where
//! the path turns they bend the surface. Across the path every ring needs all its points (that
//! is the rounding of the cross-section, the same in a straight run as in a turn), so the level
//! that can differ from place to place is the one along the path: [`drop_flat_rings`] removes the
//! rings whose every point lies within a tolerance of the segment joining its neighbours on the
//! kept rings either side, and joins the side quads across them.
//!
//! Whole rings go or stay, so neighbouring quads always share their edges and the surface stays
//! closed and oriented with no T-junctions (no transition faces needed). Every kept point is a
//! point of the uniformly subdivided surface, every plane's ring (integer `t`) is kept so the
//! cutter still interpolates its planes, and every removed point lies within the tolerance of the
//! result (it is on a kept edge's segment up to the tolerance). The caller checks the result with
//! the exact self-intersection test and keeps the uniform surface when it fails.

use std::collections::HashMap;

use glam::DVec3;

use crate::quad_mesh::QuadMesh;

/// A removed ring point may lie this far from the kept surface, as a fraction of the cutter's
/// cross-section (the median diagonal of its planes): well under a pixel when the cross-section
/// fills a quarter of a 1280×800 view.
pub const ADAPTIVE_TOLERANCE: f64 = 0.002;

/// At most this many ring intervals of the uniform grid are joined into one quad, so no side
/// quad becomes a long sliver.
const MAX_JOIN: usize = 16;

/// The uniformly subdivided box chain `fine` with the rings that carry no shape removed (see the
/// module doc). `t` is each vertex's path parameter (see [`path_parameters`]); `tolerance` in
/// model units. Returns `None` when the mesh is not a box chain's grid (then nothing is removed).
/// The kept vertices keep their order, so the planes' corners stay a prefix.
pub fn drop_flat_rings(fine: &QuadMesh, t: &[f64], tolerance: f64) -> Option<QuadMesh> {
    if t.len() != fine.positions.len() || fine.positions.is_empty() {
        return None;
    }
    // Rings by parameter, and the along-path neighbour of each vertex (towards larger t).
    let mut ring_ts: Vec<f64> = t.to_vec();
    ring_ts.sort_by(f64::total_cmp);
    ring_ts.dedup();
    let ring_of: HashMap<u64, usize> = ring_ts
        .iter()
        .enumerate()
        .map(|(i, v)| (v.to_bits(), i))
        .collect();
    let ring = |v: u32| ring_of[&t[v as usize].to_bits()];
    let mut next: Vec<Option<u32>> = vec![None; t.len()];
    for f in &fine.faces {
        for k in 0..f.len() {
            let (a, b) = (f[k], f[(k + 1) % f.len()]);
            let (lo, hi) = match ring(a).cmp(&ring(b)) {
                std::cmp::Ordering::Less => (a, b),
                std::cmp::Ordering::Greater => (b, a),
                std::cmp::Ordering::Equal => continue,
            };
            if ring(hi) != ring(lo) + 1 {
                return None;
            }
            match next[lo as usize] {
                None => next[lo as usize] = Some(hi),
                Some(h) if h == hi => {}
                Some(_) => return None,
            }
        }
    }
    let last = ring_ts.len() - 1;
    let mut members: Vec<Vec<u32>> = vec![Vec::new(); ring_ts.len()];
    for v in 0..t.len() as u32 {
        members[ring(v)].push(v);
    }
    // Every vertex strictly between the end rings is a side vertex with an along neighbour.
    for r in 1..last {
        if members[r].iter().any(|&v| next[v as usize].is_none()) {
            return None;
        }
    }
    let p = &fine.positions;
    // Can rings a+1..b-1 go, joining ring a to ring b directly?
    let joinable = |a: usize, b: usize| -> bool {
        members[a].iter().all(|&start| {
            let Some(mut v) = next[start as usize] else {
                return true; // an end cap's inner point: no side edge leaves it
            };
            let mut inner = Vec::with_capacity(b - a - 1);
            for _ in a + 1..b {
                inner.push(v);
                v = next[v as usize].expect("checked above");
            }
            let (s, e) = (p[start as usize], p[v as usize]);
            inner
                .iter()
                .all(|&i| distance_to_segment(p[i as usize], s, e) <= tolerance)
        })
    };
    let is_plane = |r: usize| ring_ts[r].fract() == 0.0;
    let mut kept = vec![false; ring_ts.len()];
    kept[0] = true;
    let mut a = 0;
    while a < last {
        let mut b = a + 1;
        while b < last && !is_plane(b) && b - a < MAX_JOIN && joinable(a, b + 1) {
            b += 1;
        }
        kept[b] = true;
        a = b;
    }
    if kept.iter().all(|&k| k) {
        return Some(fine.clone());
    }
    // Follow the along neighbours to the next kept ring.
    let to_kept = |mut v: u32| -> u32 {
        while !kept[ring(v)] {
            v = next[v as usize].expect("inner rings have along neighbours");
        }
        v
    };
    let mut faces = Vec::with_capacity(fine.faces.len());
    for f in &fine.faces {
        let low = f
            .iter()
            .map(|&v| ring(v))
            .min()
            .expect("faces have corners");
        if !kept[low] {
            continue;
        }
        faces.push(
            f.iter()
                .map(|&v| if ring(v) == low { v } else { to_kept(v) })
                .collect::<Vec<u32>>(),
        );
    }
    // Keep the used vertices, in order.
    let mut new_index = vec![u32::MAX; p.len()];
    let mut positions = Vec::new();
    for v in 0..p.len() {
        if kept[ring(v as u32)] {
            new_index[v] = positions.len() as u32;
            positions.push(p[v]);
        }
    }
    for f in &mut faces {
        for v in f.iter_mut() {
            *v = new_index[*v as usize];
        }
    }
    Some(QuadMesh { positions, faces })
}

/// Each vertex's path parameter after `levels` levels of [`crate::subdivision::subdivide`] of a
/// box chain whose vertex `4i + k` is corner `k` of plane `i` (the layout of
/// [`crate::Cutter::quad_mesh`] for curving and straight cutters): the linear subdivision of the
/// plane index, so a ring of the grid shares one exactly representable value.
pub fn path_parameters(chain: &QuadMesh, levels: u32) -> Vec<f64> {
    let param = QuadMesh {
        positions: (0..chain.positions.len())
            .map(|v| DVec3::new((v / 4) as f64, 0.0, 0.0))
            .collect(),
        faces: chain.faces.clone(),
    };
    crate::subdivision::subdivide_linear(&param, levels)
        .positions
        .iter()
        .map(|q| q.x)
        .collect()
}

/// The cross-section scale [`ADAPTIVE_TOLERANCE`] is a fraction of: the median diagonal of the
/// planes' corner quads.
pub fn cross_section(planes: &[[DVec3; 4]]) -> f64 {
    let mut d: Vec<f64> = planes
        .iter()
        .map(|q| (q[2] - q[0]).length().max((q[3] - q[1]).length()))
        .collect();
    if d.is_empty() {
        return 0.0;
    }
    d.sort_by(f64::total_cmp);
    d[d.len() / 2]
}

fn distance_to_segment(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    let ab = b - a;
    let len2 = ab.length_squared();
    let s = if len2 > 0.0 {
        ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.distance(a + ab * s)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cutter::{CutKind, Cutter};
    use crate::plane::BoundedPlane;
    use crate::subdivision::subdivide;

    /// Unit-square planes through `points` (front edge along z), each reaching back along its
    /// direction, as a smooth curving cutter.
    fn chain(points: &[(DVec3, DVec3)]) -> Cutter {
        Cutter {
            kind: CutKind::Curving,
            smooth: true,
            levels: 2,
            direction: crate::cutter::CutDirection::Normal,
            planes: points
                .iter()
                .map(|&(c, back)| BoundedPlane::from_front_edge(c + DVec3::Z, c, back, 1.0))
                .collect(),
        }
    }

    fn straight(count: usize) -> Cutter {
        chain(
            &(0..count)
                .map(|i| (DVec3::X * i as f64, DVec3::Y))
                .collect::<Vec<_>>(),
        )
    }

    #[test]
    fn straight_run_keeps_only_plane_rings_and_stays_closed() {
        let c = straight(11);
        let q = c.quad_mesh();
        let fine = subdivide(&q, 2);
        let t = path_parameters(&q, 2);
        let adaptive = drop_flat_rings(&fine, &t, 1e-9).expect("a box chain");
        adaptive.check_closed().unwrap();
        csg::check_cutter(&adaptive.triangulate()).unwrap();
        assert!(adaptive.faces.len() < fine.faces.len());
        // The rounded ends curve the first and last two boxes; between them the run is straight
        // and only the planes' rings are left.
        let off_plane = |m: &QuadMesh, lo: f64, hi: f64| {
            m.positions
                .iter()
                .filter(|p| p.x > lo && p.x < hi && (p.x - p.x.round()).abs() > 1e-9)
                .count()
        };
        assert!(off_plane(&fine, 2.0, 8.0) > 0);
        assert_eq!(off_plane(&adaptive, 2.0, 8.0), 0);
        // Near the ends the rings bend the surface: they stay.
        assert_eq!(off_plane(&adaptive, -1.0, 1.0), off_plane(&fine, -1.0, 1.0));
        // Same solid: a straight run's inner rings are on the segments joining the planes.
        assert!((adaptive.volume() / fine.volume() - 1.0).abs() < 1e-12);
        // The planes' corners are a prefix, untouched.
        assert_eq!(&adaptive.positions[..q.positions.len()], &q.positions[..]);
    }

    #[test]
    fn a_turn_keeps_its_rings_and_removed_points_stay_within_tolerance() {
        // Straight for five boxes, then a quarter turn of radius 4 (planes across the path).
        let mut points: Vec<(DVec3, DVec3)> =
            (0..6).map(|i| (DVec3::X * i as f64, DVec3::Y)).collect();
        for k in 1..=4 {
            let a = (k as f64 * 22.5).to_radians();
            points.push((
                DVec3::new(5.0 + 4.0 * a.sin(), 4.0 - 4.0 * a.cos(), 0.0),
                DVec3::new(-a.sin(), a.cos(), 0.0),
            ));
        }
        let c = chain(&points);
        let q = c.quad_mesh();
        let fine = subdivide(&q, 2);
        let t = path_parameters(&q, 2);
        let corners: Vec<[DVec3; 4]> = c.planes.iter().map(|p| p.corners()).collect();
        let tol = ADAPTIVE_TOLERANCE * cross_section(&corners);
        let adaptive = drop_flat_rings(&fine, &t, tol).unwrap();
        adaptive.check_closed().unwrap();
        csg::check_cutter(&adaptive.triangulate()).unwrap();
        assert!(adaptive.faces.len() < fine.faces.len());
        // The rings inside the turn bend the surface: they stay.
        let in_turn = |m: &QuadMesh| m.positions.iter().filter(|p| p.x > 5.2).count();
        assert_eq!(in_turn(&adaptive), in_turn(&fine));
        // Every removed point is within the tolerance of the kept surface.
        let kept = adaptive.triangulate();
        let index = csg::SpatialIndex::build(&kept);
        for p in &fine.positions {
            let d = index.closest_point(&kept, *p).unwrap().distance;
            assert!(d <= tol * 1.0001, "{d} > {tol}");
        }
    }

    #[test]
    fn not_a_grid_is_left_alone() {
        let c = straight(3);
        let q = c.quad_mesh();
        let fine = subdivide(&q, 1);
        // Parameters that do not follow the grid: refused.
        let t: Vec<f64> = (0..fine.positions.len()).map(|v| (v % 3) as f64).collect();
        assert!(drop_flat_rings(&fine, &t, 1.0).is_none());
        assert!(drop_flat_rings(&fine, &[], 1.0).is_none());
    }
}
