//! The drawn path as the last step's path corrections saw it, kept between steps by the live
//! opening.
//!
//! Every step the path corrections ([`super::drawn::corrections`]) smooth each stroke's samples
//! (their feet on the surface) and measure each cut segment's ends against the smoothed path.
//! A step only adds to the stroke being drawn and edits the mesh around its own cut: the other
//! strokes, and their segments' corrections, are what they were, yet were made again every step
//! (work that grew with the incision's length). [`KeptPath`] keeps them:
//! - the samples' feet ([`Feet`], dropped where the mesh changed under them);
//! - per stroke, the feet it was smoothed from and the smoothed points: the smoothing is a
//!   function of those points and the width alone, so feet equal bit for bit give the kept
//!   smoothed stroke;
//! - per segment, what its corrections were measured from (its ends, its clock, its frame's
//!   lateral, its sample, its stroke's range and the smoothed points it read) and the
//!   corrections: with those equal bit for bit, the measurement gives the kept corrections.
//!   The stroke being drawn is smoothed again every step, but only its last points change (a
//!   point's smoothing reads the points within half a width of it), so its segments behind the
//!   tool keep their corrections too.
//!
//! So the corrections made with a [`KeptPath`] equal those made from scratch, bit for bit.

use glam::DVec3;

use super::feet::Feet;
use csg::fast_hash::FastMap;

/// What the path corrections kept from the last step (see the module doc).
#[derive(Default)]
pub struct KeptPath {
    /// The samples' feet on the surface.
    pub feet: Feet,
    /// The width the strokes were smoothed and the corrections measured for (its bits).
    width: u64,
    /// Per stroke, by its first sample's index.
    strokes: FastMap<usize, Stroke>,
    /// Per segment, what its corrections were measured from and the corrections.
    segments: Vec<Option<Measured>>,
}

/// A stroke as it was smoothed.
struct Stroke {
    /// The feet it was smoothed from and the smoothed points.
    feet: Vec<DVec3>,
    smoothed: Vec<DVec3>,
    /// The smoothed points of the step before, when this step smoothed it again.
    before: Option<Vec<DVec3>>,
}

/// A segment's path corrections and what they were measured from.
#[derive(Clone, Copy)]
pub(crate) struct Measured {
    pub pa: DVec3,
    pub pb: DVec3,
    pub time: f64,
    pub lateral: DVec3,
    /// The sample of the step that cut it and its stroke's samples (first, last).
    pub sample: usize,
    pub run: (usize, usize),
    /// The samples of the smoothed stroke the measure read (first, last).
    pub read: (usize, usize),
    pub corrections: [DVec3; 2],
}

impl Measured {
    /// Whether `self` was measured for the same segment, frame and sample as `other`, bit for
    /// bit, in a stroke starting at the same sample.
    fn same_segment(&self, other: &Measured) -> bool {
        same_bits(self.pa, other.pa)
            && same_bits(self.pb, other.pb)
            && self.time.to_bits() == other.time.to_bits()
            && same_bits(self.lateral, other.lateral)
            && self.sample == other.sample
            && self.run.0 == other.run.0
    }
}

impl KeptPath {
    /// Drops everything kept, the feet too.
    pub fn clear(&mut self) {
        self.feet.clear();
        self.forget_measures();
    }

    /// Drops the smoothed strokes and the corrections (the feet stay).
    fn forget_measures(&mut self) {
        self.strokes.clear();
        self.segments.clear();
    }

    /// Starts a pass over `segments` segments measured for `width`: what was kept for another
    /// width is dropped.
    pub(crate) fn begin(&mut self, segments: usize, width: f64) {
        if self.width != width.to_bits() {
            self.forget_measures();
            self.width = width.to_bits();
        }
        self.segments.resize(segments, None);
        for stroke in self.strokes.values_mut() {
            stroke.before = None;
        }
    }

    /// The stroke starting at sample `lo` smoothed from `feet`: the kept one when it was
    /// smoothed from the same feet, else `smooth(feet)`, kept.
    pub(crate) fn smoothed(
        &mut self,
        lo: usize,
        feet: Vec<DVec3>,
        smooth: impl FnOnce(&[DVec3]) -> Vec<DVec3>,
    ) -> &[DVec3] {
        let same = self.strokes.get(&lo).is_some_and(|k| {
            k.feet.len() == feet.len() && k.feet.iter().zip(&feet).all(|(a, b)| same_bits(*a, *b))
        });
        if !same {
            let smoothed = smooth(&feet);
            let before = self.strokes.remove(&lo).map(|k| k.smoothed);
            self.strokes.insert(
                lo,
                Stroke {
                    feet,
                    smoothed,
                    before,
                },
            );
        }
        &self.strokes[&lo].smoothed
    }

    /// The corrections of segment `i` (its stroke smoothed by [`KeptPath::smoothed`] in this
    /// pass) when they were measured from the same values as `measure` would read now, else
    /// those `measure` gives (with the samples it read), kept.
    ///
    /// Every segment is measured or kept in every pass, so a segment's kept measure read its
    /// stroke as the pass before smoothed it: the stroke's kept points if it was not smoothed
    /// again, else its points `before`. The measure walks the smoothed stroke from the
    /// segment's sample out to the samples it read (or the stroke's ends) and reads nothing
    /// else: those points equal bit for bit, and no end of the stroke cut the walk short where
    /// it moved, give the same corrections.
    pub(crate) fn corrections(
        &mut self,
        i: usize,
        inputs: Measured,
        measure: impl FnOnce() -> ([DVec3; 2], (usize, usize)),
    ) -> [DVec3; 2] {
        if let Some(kept) = self.segments[i]
            && kept.same_segment(&inputs)
            && let Some(stroke) = self.strokes.get(&inputs.run.0)
        {
            let (lo, (a, b)) = (inputs.run.0, kept.read);
            let (hi_then, hi_now) = (kept.run.1, inputs.run.1);
            let same = match &stroke.before {
                None => hi_then == hi_now,
                Some(before) => {
                    (hi_then == hi_now || (b < hi_then && b < hi_now))
                        && before[a - lo..=b - lo]
                            .iter()
                            .zip(&stroke.smoothed[a - lo..=b - lo])
                            .all(|(x, y)| same_bits(*x, *y))
                }
            };
            if same {
                return kept.corrections;
            }
        }
        let (corrections, read) = measure();
        self.segments[i] = Some(Measured {
            corrections,
            read,
            ..inputs
        });
        corrections
    }

    /// Segment `i` has no corrections measured (no sample of its own).
    pub(crate) fn unmeasured(&mut self, i: usize) {
        self.segments[i] = None;
    }
}

/// Whether `a` and `b` are the same bit for bit (`0.0` and `-0.0` differ).
fn same_bits(a: DVec3, b: DVec3) -> bool {
    a.to_array().map(f64::to_bits) == b.to_array().map(f64::to_bits)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalpel::drawn::{Sample, corrections};
    use crate::scalpel::dyn_mesh::DynMesh;
    use crate::scalpel::frames::{Frame, frames};
    use crate::scalpel::step::CutSegment;

    /// The vertices of `mesh` within 0.3 of the plane through the centre with normal `n`, on
    /// the side of `side`, in order around `n`.
    fn ring(mesh: &DynMesh, n: DVec3, side: DVec3) -> Vec<u32> {
        let mut ring: Vec<u32> = (0..mesh.vertex_count() as u32)
            .filter(|&v| mesh.pos(v).dot(n).abs() < 0.3 && mesh.pos(v).dot(side) > 0.0)
            .collect();
        let angle = |v: u32| {
            let p = mesh.pos(v);
            p.dot(side).atan2(p.dot(n.cross(side)))
        };
        ring.sort_by(|&a, &b| angle(a).total_cmp(&angle(b)));
        ring
    }

    /// A stroke along `vertices`, samples a little beside them: its samples and segments from
    /// clock `t0` on.
    fn stroke(
        mesh: &DynMesh,
        number: usize,
        vertices: &[u32],
        t0: f64,
    ) -> (Vec<Sample>, Vec<CutSegment>) {
        let mut samples = Vec::new();
        let mut segments = Vec::new();
        for (k, w) in vertices.windows(2).enumerate() {
            let time = t0 + k as f64;
            let (pa, pb) = (mesh.pos(w[0]), mesh.pos(w[1]));
            let beside = pb.normalize().cross(pb - pa).normalize() * 0.05 * (k % 3) as f64;
            samples.push(Sample::new(number, time, pb + beside));
            segments.push(CutSegment {
                a: w[0],
                b: w[1],
                pa,
                pb,
                normal: pb.normalize(),
                time,
            });
        }
        (samples, segments)
    }

    fn bits(c: &[[DVec3; 2]]) -> Vec<[u64; 6]> {
        c.iter()
            .map(|[a, b]| {
                let [x, y, z] = a.to_array().map(f64::to_bits);
                let [u, v, w] = b.to_array().map(f64::to_bits);
                [x, y, z, u, v, w]
            })
            .collect()
    }

    /// The corrections made with `kept` after the calls before, and from scratch, bit for bit.
    fn check(
        mesh: &DynMesh,
        samples: &[Sample],
        segments: &[CutSegment],
        frames: &[Frame],
        width: f64,
        kept: &mut KeptPath,
        what: &str,
    ) {
        let with = corrections(mesh, samples, segments, frames, width, Some(kept));
        let fresh = corrections(mesh, samples, segments, frames, width, None);
        assert_eq!(bits(&with), bits(&fresh), "{what}");
    }

    #[test]
    fn kept_corrections_are_those_made_from_scratch_as_strokes_grow_move_and_turn() {
        let mesh = DynMesh::from_mesh(&csg::testkit::icosphere(4, 10.0));
        let first = ring(&mesh, DVec3::Z, DVec3::Y);
        let second = ring(&mesh, DVec3::X, DVec3::NEG_Z);
        let (mut samples, mut segments) = stroke(&mesh, 0, &first[..14], 1.0);
        let (s2, g2) = stroke(&mesh, 1, &second[..10], 100.0);
        let width = 1.0;
        let mut kept = KeptPath::default();
        let go = |samples: &[Sample], segments: &[CutSegment], kept: &mut KeptPath, what| {
            let frames = frames(segments, width);
            check(&mesh, samples, segments, &frames, width, kept, what);
        };
        go(&samples, &segments, &mut kept, "the first stroke");
        let some = corrections(
            &mesh,
            &samples,
            &segments,
            &frames(&segments, width),
            width,
            None,
        );
        assert!(some.iter().flatten().any(|c| *c != DVec3::ZERO));
        // The second stroke, sample by sample (the first stays: its corrections are kept).
        for k in 0..s2.len() {
            samples.push(s2[k]);
            segments.push(g2[k]);
            go(&samples, &segments, &mut kept, "the second stroke growing");
        }
        // A sample of the first stroke moves (its foot, its smoothed stroke, its corrections).
        samples[5].point += DVec3::new(0.0, 0.0, 0.2);
        go(&samples, &segments, &mut kept, "a sample moved");
        // A segment's frame turns: only its lateral changes.
        let mut turned = frames(&segments, width);
        turned[3].lateral = (turned[3].lateral + 0.3 * turned[3].tangent).normalize();
        check(
            &mesh,
            &samples,
            &segments,
            &turned,
            width,
            &mut kept,
            "a frame turned",
        );
        go(&samples, &segments, &mut kept, "the frame back");
        // Another width; the second stroke undone.
        let frames2 = frames(&segments, 1.5);
        check(
            &mesh,
            &samples,
            &segments,
            &frames2,
            1.5,
            &mut kept,
            "another width",
        );
        samples.truncate(13);
        segments.truncate(13);
        go(&samples, &segments, &mut kept, "the second stroke undone");
    }
}
