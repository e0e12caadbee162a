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
    let linked = |j: usize| segments[j].pb == segments[j + 1].pa;
    (0..segments.len())
        .map(|i| {
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
        })
        .collect()
}
