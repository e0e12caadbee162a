//! The path's direction at each cut segment, smoothed over the zigzag of the mesh edges the cut
//! runs along: the opening ([`super::dffd`]) moves lip copies across it and the drawn path
//! ([`super::drawn`]) measures each segment's sideways offset along it.

use glam::DVec3;

use super::step::CutSegment;

/// The path's direction at a cut segment, smoothed over the zigzag of the mesh edges it runs
/// along (see the module doc).
#[derive(Clone, Copy, Debug)]
pub struct Frame {
    /// Unit tangent of the path (the direction it was cut in).
    pub tangent: DVec3,
    /// Unit `normal × tangent`: the side a lip copy with `σ = +1` moves to.
    pub lateral: DVec3,
}

/// Segments on either side of a segment averaged into its [`Frame`], at most.
const SMOOTH_SEGMENTS: usize = 24;

/// One [`Frame`] per segment: the sum of the segment vectors and of the normals of the connected
/// segments (each one's end is the next one's start) within `width` (and at least two segments)
/// of it on either side, normalised.
pub fn frames(segments: &[CutSegment], width: f64) -> Vec<Frame> {
    (0..segments.len())
        .map(|i| frame_at(segments, width, i))
        .collect()
}

/// [`frames`], taking the frame of `before` (segments and their frames for the same `width`)
/// wherever the segments a frame reads (at most [`SMOOTH_SEGMENTS`] on either side) are the
/// same, bit for bit: a step changes only the segments near the tool, and making every frame
/// of a long incision again was a sixth of what the opening's inputs cost.
pub fn frames_reusing(
    segments: &[CutSegment],
    width: f64,
    before: (&[CutSegment], &[Frame]),
) -> Vec<Frame> {
    let (old, old_frames) = before;
    // Changed segments before each index (an index one list lacks counts as changed: a frame
    // near the end reads how far the list goes).
    let n = segments.len().max(old.len());
    let mut changed = Vec::with_capacity(n + 1);
    changed.push(0u32);
    for i in 0..n {
        let same = matches!((segments.get(i), old.get(i)), (Some(a), Some(b)) if same_bits(a, b));
        changed.push(changed[i] + u32::from(!same));
    }
    (0..segments.len())
        .map(|i| {
            let (lo, hi) = (
                i.saturating_sub(SMOOTH_SEGMENTS),
                (i + SMOOTH_SEGMENTS + 1).min(n),
            );
            if changed[hi] == changed[lo] {
                old_frames[i]
            } else {
                frame_at(segments, width, i)
            }
        })
        .collect()
}

/// Whether two segments are the same, bit for bit.
fn same_bits(a: &CutSegment, b: &CutSegment) -> bool {
    let bits = |s: &CutSegment| [s.pa, s.pb, s.normal].map(|p| p.to_array().map(f64::to_bits));
    a.a == b.a && a.b == b.b && a.time.to_bits() == b.time.to_bits() && bits(a) == bits(b)
}

/// The frame of segment `i` (see [`frames`]).
fn frame_at(segments: &[CutSegment], width: f64, i: usize) -> Frame {
    let linked = |j: usize| segments[j].pb == segments[j + 1].pa;
    let s = &segments[i];
    let mut tangent = s.pb - s.pa;
    let mut normal = s.normal;
    let reach = width.max(2.0 * tangent.length());
    let (mut back, mut len) = (i, 0.0);
    while back > 0 && i - back < SMOOTH_SEGMENTS && linked(back - 1) {
        back -= 1;
        let t = segments[back].pb - segments[back].pa;
        len += t.length();
        tangent += t;
        normal += segments[back].normal;
        if len >= reach && i - back >= 2 {
            break;
        }
    }
    let (mut ahead, mut len) = (i, 0.0);
    while ahead + 1 < segments.len() && ahead - i < SMOOTH_SEGMENTS && linked(ahead) {
        ahead += 1;
        let t = segments[ahead].pb - segments[ahead].pa;
        len += t.length();
        tangent += t;
        normal += segments[ahead].normal;
        if len >= reach && ahead - i >= 2 {
            break;
        }
    }
    let tangent = tangent.normalize_or_zero();
    let normal = normal.normalize_or_zero();
    let lateral = normal.cross(tangent).normalize_or_zero();
    Frame { tangent, lateral }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_taken_from_before_are_those_made_again_bit_for_bit() {
        let mut rng = csg::testkit::SplitMix(5);
        let mut random = || rng.next_f64();
        // Two strokes of short zigzagging segments (linked within each).
        let mut segments = Vec::new();
        for stroke in 0..2 {
            let mut p = DVec3::new(0.0, 10.0 * stroke as f64, 0.0);
            for _ in 0..80 {
                let q = p + DVec3::new(0.4, random() - 0.5, 0.1 * (random() - 0.5));
                let mut s = CutSegment::between(p, q);
                s.normal = DVec3::new(0.1 * random(), 0.1 * random(), 1.0);
                segments.push(s);
                p = q;
            }
        }
        let bits = |f: &[Frame]| -> Vec<[u64; 6]> {
            f.iter()
                .map(|f| {
                    let [a, b, c] = f.tangent.to_array().map(f64::to_bits);
                    let [d, e, g] = f.lateral.to_array().map(f64::to_bits);
                    [a, b, c, d, e, g]
                })
                .collect()
        };
        let width = 2.0;
        let old = frames(&segments, width);
        // Segments changed in place, added at the end, removed from the end.
        let mut changed = segments.clone();
        changed[30].pb.y += 0.2;
        changed[31].pa = changed[30].pb;
        changed[100].normal = DVec3::X;
        let mut longer = segments.clone();
        longer.push(CutSegment::between(
            segments[159].pb,
            segments[159].pb + DVec3::X,
        ));
        let shorter = &segments[..150];
        for now in [&changed[..], &longer[..], shorter, &segments[..]] {
            let kept = frames_reusing(now, width, (&segments, &old));
            assert_eq!(bits(&kept), bits(&frames(now, width)));
        }
        // A changed segment changes the frames around it: some are made again, not all kept.
        let kept = frames_reusing(&changed, width, (&segments, &old));
        assert_ne!(bits(&kept[25..35]), bits(&old[25..35]));
    }
}
