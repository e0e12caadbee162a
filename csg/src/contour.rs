//! Stage 6b of the boolean: chain the contour segments into polylines.
//!
//! Segments share endpoint ids (one id per intersection point), so chaining is pure topology. For
//! a closed target every point has degree 2 and every polyline is a closed loop; open polylines
//! start and end at points of degree other than 2 (target boundary, non-manifold edges).

use glam::DVec3;

use crate::intersect::{FxMap, Segment};
use crate::output::Contour;

/// Chains `segments` into polylines; `sub_cutter(s)` names the sub-cutter of segment `s`.
pub(crate) fn chain(
    segments: &[Segment],
    positions: &[DVec3],
    sub_cutter: impl Fn(usize) -> u32,
) -> Vec<Contour> {
    let mut incident: FxMap<u32, Vec<u32>> = Default::default();
    for (s, seg) in segments.iter().enumerate() {
        incident.entry(seg.a).or_default().push(s as u32);
        incident.entry(seg.b).or_default().push(s as u32);
    }
    let mut used = vec![false; segments.len()];
    let mut out = Vec::new();
    let walk = |start_point: u32, first: u32, used: &mut Vec<bool>| -> (Vec<u32>, bool) {
        let mut pts = vec![start_point];
        let mut at = start_point;
        let mut seg = first;
        loop {
            used[seg as usize] = true;
            let s = &segments[seg as usize];
            let next = if s.a == at { s.b } else { s.a };
            if next == start_point {
                return (pts, true);
            }
            pts.push(next);
            at = next;
            let inc = &incident[&at];
            if inc.len() != 2 {
                return (pts, false);
            }
            let cand = if inc[0] == seg { inc[1] } else { inc[0] };
            if used[cand as usize] {
                return (pts, false);
            }
            seg = cand;
        }
    };
    // Open polylines first (from points of degree != 2), then loops.
    let mut starts: Vec<u32> = incident
        .iter()
        .filter(|(_, v)| v.len() != 2)
        .map(|(&p, _)| p)
        .collect();
    starts.sort_unstable();
    for p in starts {
        for &s in &incident[&p].clone() {
            if !used[s as usize] {
                let (pts, closed) = walk(p, s, &mut used);
                out.push(Contour {
                    points: pts.iter().map(|&i| positions[i as usize]).collect(),
                    closed,
                    sub_cutter: sub_cutter(s as usize),
                });
            }
        }
    }
    for s in 0..segments.len() {
        if !used[s] {
            let (pts, closed) = walk(segments[s].a, s as u32, &mut used);
            out.push(Contour {
                points: pts.iter().map(|&i| positions[i as usize]).collect(),
                closed,
                sub_cutter: sub_cutter(s),
            });
        }
    }
    out
}
