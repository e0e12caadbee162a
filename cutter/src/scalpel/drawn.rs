//! The drawn path: where the tool went, as opposed to where the cut runs in the rest pose.
//!
//! The rest-pose cut runs along mesh edges: an edge crossing near a vertex goes through the
//! vertex, so the cut zigzags around the drawn path by up to a fraction of an edge
//! (`notes/scalpel.md` Q1, Q2). Opened as it is, the zigzag shifted sideways shows as lips with
//! spikes and notches. The opening ([`super::dffd`]) is a display deformation, so it can put the
//! lips where the user drew instead: each committed step records its tool sample ([`Sample`]),
//! each stroke's samples are smoothed over about one opening width ([`smooth`]: a box average
//! along the arc length that keeps the stroke's two ends), and [`corrections`] gives, for each
//! end of each cut segment, how far that smoothed path lies beside the cut, across the path (the
//! lateral correction that moves a lip onto it).
//!
//! A segment finds its stroke, and its place in it, by its time: the tool clock of the step that
//! cut it is the clock recorded with that step's sample. So a refused step (its segments rolled
//! back, its sample never recorded) needs no bookkeeping, and [`super::Scalpel::undo_stroke`]
//! only drops the undone stroke's samples. A segment with no sample of its own, or whose
//! smoothed path is far from it (the far side of a through-cut, under a sample on the near
//! side), gets no correction and opens as before.

use glam::DVec3;

use super::cut_point::segment_parameter;
use super::dyn_mesh::DynMesh;
use super::feet::foot;
use super::frames::Frame;
use super::kept_path::{KeptPath, Measured};
use super::step::CutSegment;

pub use super::sample::Sample;

/// A correction is used only when the smoothed path lies within this many (segment length plus
/// width) of the segment's end.
const REACH: f64 = 1.0;

/// The polyline `points` smoothed by a box average of half-length `half` along its arc length
/// (the curve, not its vertices, is averaged, so uneven sampling does not pull it); the window
/// shrinks toward the ends, so the first and last points stay where they are.
pub fn smooth(points: &[DVec3], half: f64) -> Vec<DVec3> {
    let n = points.len();
    if n < 3 || half.is_nan() || half <= 0.0 {
        return points.to_vec();
    }
    let mut arc = Vec::with_capacity(n);
    let mut s = 0.0;
    arc.push(0.0);
    for k in 1..n {
        s += points[k].distance(points[k - 1]);
        arc.push(s);
    }
    let total = s;
    // The point at arc length `x` on segment `k` (arc[k] <= x <= arc[k + 1]).
    let at = |k: usize, x: f64| {
        let len = arc[k + 1] - arc[k];
        if len > 0.0 {
            points[k].lerp(points[k + 1], (x - arc[k]) / len)
        } else {
            points[k]
        }
    };
    let mut out = Vec::with_capacity(n);
    let mut first = 0;
    for i in 0..n {
        let h = half.min(arc[i]).min(total - arc[i]);
        if h <= 0.0 {
            out.push(points[i]);
            continue;
        }
        let (a, b) = (arc[i] - h, arc[i] + h);
        while first + 1 < n && arc[first + 1] <= a {
            first += 1;
        }
        let mut sum = DVec3::ZERO;
        let mut k = first;
        while k + 1 < n && arc[k] < b {
            let (x0, x1) = (arc[k].max(a), arc[k + 1].min(b));
            if x1 > x0 {
                sum += at(k, 0.5 * (x0 + x1)) * (x1 - x0);
            }
            k += 1;
        }
        out.push(sum / (b - a));
    }
    out
}

/// The nearest point to `p` on the polyline `points[lo..=hi]`.
fn nearest_on(points: &[DVec3], lo: usize, hi: usize, p: DVec3) -> DVec3 {
    let mut best = points[lo];
    let mut best_d = best.distance_squared(p);
    for k in lo..hi {
        let (a, b) = (points[k], points[k + 1]);
        let c = a.lerp(b, segment_parameter(a, b, p));
        let d = c.distance_squared(p);
        if d < best_d {
            best = c;
            best_d = d;
        }
    }
    best
}

/// Per cut segment, the lateral corrections at its two ends (`pa`, `pb`): the offset along the
/// segment's frame lateral from the end to the nearest point of its stroke's drawn path,
/// smoothed over `width` (see the module doc). Zero where the segment has no sample or the path
/// is out of reach. Cost: the samples of the strokes the segments come from, plus a few samples
/// of path per segment; each sample's foot on the surface is searched for unless `kept` keeps
/// it ([`super::feet`]), and the strokes whose feet and the segments whose ends, frame and
/// stroke are what `kept` holds are not smoothed and measured again ([`KeptPath`]).
pub fn corrections(
    mesh: &DynMesh,
    samples: &[Sample],
    segments: &[CutSegment],
    frames: &[Frame],
    width: f64,
    mut kept: Option<&mut KeptPath>,
) -> Vec<[DVec3; 2]> {
    let mut out = vec![[DVec3::ZERO; 2]; segments.len()];
    if samples.is_empty() || width.is_nan() || width <= 0.0 {
        return out;
    }
    if let Some(k) = kept.as_deref_mut() {
        k.begin(segments.len(), width);
    }
    // Each segment's sample: the one its step recorded (the same clock), if any.
    let sample_of: Vec<Option<usize>> = segments
        .iter()
        .map(|s| {
            let j = samples.partition_point(|x| x.time < s.time);
            (j < samples.len() && samples[j].time == s.time).then_some(j)
        })
        .collect();
    // Each sample's stroke as the range of its samples (first, last), in one pass.
    let mut runs: Vec<(usize, usize)> = Vec::with_capacity(samples.len());
    let mut start = 0;
    for k in 0..samples.len() {
        if k + 1 == samples.len() || samples[k + 1].stroke != samples[k].stroke {
            runs.extend(std::iter::repeat_n((start, k), k + 1 - start));
            start = k + 1;
        }
    }
    // A cut vertex each sample's step reached (for putting the sample onto the surface): the
    // end nearest the sample among its segments' (a through-cut's step also cuts the far side),
    // else that of the sample before or after it in its stroke.
    let mut reached: Vec<Option<(u32, f64)>> = vec![None; samples.len()];
    for (s, j) in segments.iter().zip(&sample_of) {
        if let Some(j) = *j
            && (s.b as usize) < mesh.vertex_count()
        {
            let d = s.pb.distance(samples[j].point);
            if reached[j].is_none_or(|(_, e)| d < e) {
                reached[j] = Some((s.b, d));
            }
        }
    }
    // Smoothed strokes, made when a segment first needs them.
    let mut smoothed: Vec<DVec3> = samples.iter().map(|s| s.point).collect();
    let mut done: Vec<bool> = vec![false; samples.len()];
    for (i, s) in segments.iter().enumerate() {
        let Some(j) = sample_of[i] else {
            if let Some(k) = kept.as_deref_mut() {
                k.unmeasured(i);
            }
            continue;
        };
        let (lo, hi) = runs[j];
        if !done[j] {
            // The samples as the tool gave them may be off the surface (a path file's points):
            // their feet on the surface, as the cut went toward them.
            let mut last = None;
            let mut start: Vec<Option<u32>> = (lo..=hi)
                .map(|k| {
                    last = reached[k].map(|r| r.0).or(last);
                    last
                })
                .collect();
            let first = start.iter().flatten().next().copied();
            start.iter_mut().for_each(|v| *v = v.or(first));
            let points: Vec<DVec3> = (lo..=hi)
                .zip(start)
                .map(|(k, v)| {
                    let q = samples[k].point;
                    match (v, kept.as_deref_mut()) {
                        (None, _) => q,
                        (Some(v), Some(kept)) => kept.feet.foot(mesh, v, q),
                        (Some(v), None) => foot(mesh, v, q),
                    }
                })
                .collect();
            let smooth_stroke = |p: &[DVec3]| smooth(p, 0.5 * width);
            match kept.as_deref_mut() {
                Some(k) => smoothed[lo..=hi].copy_from_slice(k.smoothed(lo, points, smooth_stroke)),
                None => smoothed[lo..=hi].copy_from_slice(&smooth_stroke(&points)),
            }
            done[lo..=hi].iter_mut().for_each(|d| *d = true);
        }
        let lateral = frames[i].lateral;
        let measure = || measure(&smoothed, (lo, hi), j, s, lateral, width);
        out[i] = match kept.as_deref_mut() {
            Some(k) => {
                let inputs = Measured {
                    pa: s.pa,
                    pb: s.pb,
                    time: s.time,
                    lateral,
                    sample: j,
                    run: (lo, hi),
                    read: (j, j),
                    corrections: [DVec3::ZERO; 2],
                };
                k.corrections(i, inputs, measure)
            }
            None => measure().0,
        };
    }
    out
}

/// The lateral corrections at the ends of segment `s` (frame lateral `lateral`), cut at sample
/// `j` of the stroke whose samples are `lo..=hi`, against the smoothed path `smoothed`, and the
/// samples of it read (first, last).
fn measure(
    smoothed: &[DVec3],
    (lo, hi): (usize, usize),
    j: usize,
    s: &CutSegment,
    lateral: DVec3,
    width: f64,
) -> ([DVec3; 2], (usize, usize)) {
    let mut out = [DVec3::ZERO; 2];
    // The path the segment was cut along: behind its sample by the segment's length and a
    // width (the cut trails the tool), ahead by a width.
    let len = s.pa.distance(s.pb);
    let mut a = j;
    let mut back = 0.0;
    while a > lo && (back < len + width || j - a < 2) {
        back += smoothed[a].distance(smoothed[a - 1]);
        a -= 1;
    }
    let mut b = j;
    let mut ahead = 0.0;
    while b < hi && (ahead < width || b - j < 2) {
        ahead += smoothed[b].distance(smoothed[b + 1]);
        b += 1;
    }
    let reach = REACH * (len + width);
    for (k, p) in [s.pa, s.pb].into_iter().enumerate() {
        let q = nearest_on(smoothed, a, b, p);
        if q.distance(p) <= reach {
            out[k] = lateral * (q - p).dot(lateral);
        }
    }
    (out, (a, b))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn smoothing_keeps_a_line_and_the_ends_and_flattens_a_zigzag() {
        let line: Vec<DVec3> = (0..10).map(|i| DVec3::new(i as f64, 0.0, 0.0)).collect();
        for (a, b) in smooth(&line, 1.5).iter().zip(&line) {
            assert!(a.distance(*b) < 1e-12, "{a:?} moved off the line");
        }
        let zig: Vec<DVec3> = (0..21)
            .map(|i| DVec3::new(0.5 * i as f64, if i % 2 == 0 { 0.2 } else { -0.2 }, 0.0))
            .collect();
        let s = smooth(&zig, 1.0);
        assert_eq!(s[0], zig[0]);
        assert_eq!(s[20], zig[20]);
        for p in &s[3..18] {
            assert!(p.y.abs() < 0.05, "{p:?} not smoothed");
        }
    }
}
