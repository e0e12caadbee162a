//! The nearest cut point to a vertex, and the cut segments within reach of it, for the opening
//! ([`super::dffd`]).
//!
//! The opening asks, for every vertex within its support, which of the cut segments the cut
//! grid lists around it ([`super::cut_grid::Near::near`], some seventy on a groove opened
//! two wide) is nearest, and blends the path corrections of the segment ends within the
//! support. Measuring each of those segments exactly was most of the opening's time. So each
//! segment is bounded by a ball (its middle, half its length, [`Balls`]): a segment whose ball
//! lies farther than the best distance so far, or than the reach, cannot change the answer and
//! is skipped after one distance to its middle. The segment nearest the vertex before (the walk
//! goes from a vertex to its neighbours) is measured first, so most others are skipped.
//! A vertex near a crossing of two grooves has some ninety segments around it, and one distance
//! each was still most of a question: the list is cut into runs of [`BLOCK`] (in index order, so
//! mostly stretches of one path) and each run bounded by a ball of its balls
//! ([`Balls::blocks`]), a run whose ball is out of reach skipped whole.
//!
//! The answers are those of the plain scan in index order, bit for bit: the same segment (the
//! lowest index among equally near ones), its point computed the same way; a skip needs the
//! ball to be farther by a slack far above rounding (relative to the coordinates).

use glam::DVec3;

use super::step::CutSegment;

/// Relative slack of a skip (times the largest coordinate and the distance).
const SLACK: f64 = 1e-9;

/// Segments per run of a list bounded by one ball ([`Balls::blocks`]).
pub(crate) const BLOCK: usize = 8;

/// A ball: its middle and radius.
pub(crate) type Ball = (DVec3, f64);

/// Per cut segment, a ball holding it: its middle and half its length (see the module doc).
pub(crate) struct Balls {
    balls: Vec<Ball>,
}

impl Balls {
    pub fn new(segments: &[CutSegment]) -> Balls {
        Balls {
            balls: segments
                .iter()
                .map(|s| (s.pa.midpoint(s.pb), 0.5 * s.pa.distance(s.pb)))
                .collect(),
        }
    }

    /// Whether segment `i` may come within `reach` of `p` (false only when it cannot).
    #[inline]
    pub fn may_reach(&self, i: usize, p: DVec3, reach: f64) -> bool {
        let (m, h) = self.balls[i];
        ball_may_reach((m, h), p, reach)
    }

    /// Per run of [`BLOCK`] segments of `list` (indices), a ball holding their balls: its
    /// middle is that of their middles' bounding box, its radius the farthest reach of theirs
    /// from it, widened far past rounding (so a run skipped holds no segment
    /// [`Balls::may_reach`] would keep).
    pub fn blocks(&self, list: &[usize]) -> Vec<Ball> {
        list.chunks(BLOCK)
            .map(|run| {
                let (lo, hi) = run.iter().fold(
                    (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
                    |(lo, hi), &i| (lo.min(self.balls[i].0), hi.max(self.balls[i].0)),
                );
                let m = lo.midpoint(hi);
                let h = run
                    .iter()
                    .map(|&i| m.distance(self.balls[i].0) + self.balls[i].1)
                    .fold(0.0, f64::max);
                (m, h * (1.0 + 1e-12))
            })
            .collect()
    }
}

/// Whether a ball `(middle, radius)` may come within `reach` of `p`.
#[inline]
fn ball_may_reach((m, h): Ball, p: DVec3, reach: f64) -> bool {
    let lim = reach + h + slack(p, reach);
    m.distance_squared(p) <= lim * lim
}

/// The absolute slack of a skip at `p` for distance `d` (see [`SLACK`]).
#[inline]
fn slack(p: DVec3, d: f64) -> f64 {
    SLACK * (1.0 + p.abs().max_element() + d)
}

/// The point of segment `s` nearest `p`, and its squared distance (the one formula every
/// caller uses, so that equal inputs give equal bits).
#[inline]
pub(crate) fn point_on(s: &CutSegment, p: DVec3) -> (f64, DVec3) {
    let ab = s.pb - s.pa;
    let l2 = ab.length_squared();
    let u = if l2 > 0.0 {
        ((p - s.pa).dot(ab) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let c = s.pa + ab * u;
    (c.distance_squared(p), c)
}

/// The nearest point to `p` on the segments `near` (indices into `segments`, ascending):
/// (distance, point, segment index), the lowest index among equally near ones. `blocks`: the
/// balls of `near`'s runs ([`Balls::blocks`]). `first`, when it is one of `near`, is measured
/// first (see the module doc); the answer does not depend on it.
pub(crate) fn nearest(
    segments: &[CutSegment],
    balls: &Balls,
    p: DVec3,
    (near, blocks): (&[usize], &[Ball]),
    first: Option<usize>,
) -> Option<(f64, DVec3, usize)> {
    let mut best: Option<(f64, DVec3, usize)> = None;
    let mut reach = f64::INFINITY;
    let mut consider = |i: usize, reach: &mut f64| {
        if !balls.may_reach(i, p, *reach) {
            return;
        }
        let (d2, c) = point_on(&segments[i], p);
        if best.is_none_or(|b| d2 < b.0 || (d2 == b.0 && i < b.2)) {
            best = Some((d2, c, i));
            *reach = d2.sqrt();
        }
    };
    debug_assert_eq!(blocks.len(), near.len().div_ceil(BLOCK), "a ball per run");
    let first = first.filter(|f| near.binary_search(f).is_ok());
    if let Some(f) = first {
        consider(f, &mut reach);
    }
    for (run, &block) in near.chunks(BLOCK).zip(blocks) {
        if !ball_may_reach(block, p, reach) {
            continue;
        }
        for &i in run {
            if Some(i) != first {
                consider(i, &mut reach);
            }
        }
    }
    best.map(|(d2, c, i)| (d2.sqrt(), c, i))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plain(segments: &[CutSegment], p: DVec3, near: &[usize]) -> Option<(f64, DVec3, usize)> {
        let mut best: Option<(f64, DVec3, usize)> = None;
        for &i in near {
            let (d2, c) = point_on(&segments[i], p);
            if best.is_none_or(|b| d2 < b.0) {
                best = Some((d2, c, i));
            }
        }
        best.map(|(d2, c, i)| (d2.sqrt(), c, i))
    }

    #[test]
    fn nearest_is_the_plain_scan_bit_for_bit_whatever_is_measured_first() {
        let mut rng = csg::testkit::SplitMix(7);
        let mut random = || rng.next_f64();
        // A zigzag polyline far from the origin (large coordinates, short segments), with a
        // repeated segment (an exact tie) and a degenerate one.
        let mut points = vec![DVec3::new(100.0, -40.0, 7.0)];
        for _ in 0..80 {
            let last = *points.last().unwrap();
            points.push(last + DVec3::new(0.4, random() - 0.5, 0.2 * (random() - 0.5)));
        }
        let mut segments: Vec<CutSegment> = points
            .windows(2)
            .map(|w| CutSegment::between(w[0], w[1]))
            .collect();
        segments.push(segments[10]);
        segments.push(CutSegment::between(points[20], points[20]));
        let balls = Balls::new(&segments);
        let all: Vec<usize> = (0..segments.len()).collect();
        let blocks = balls.blocks(&all);
        let mut queries: Vec<DVec3> = points.clone();
        for _ in 0..400 {
            let k = (random() * 80.0) as usize;
            let d = DVec3::new(random(), random(), random()) - 0.5;
            queries.push(points[k].lerp(points[k + 1], random()) + d * 3.0);
        }
        for (n, &p) in queries.iter().enumerate() {
            let want = plain(&segments, p, &all);
            for first in [None, Some(0), Some(n % segments.len()), Some(10), Some(999)] {
                let got = nearest(&segments, &balls, p, (&all, &blocks), first);
                let bits = |x: Option<(f64, DVec3, usize)>| {
                    x.map(|(d, c, i)| (d.to_bits(), c.to_array().map(f64::to_bits), i))
                };
                assert_eq!(bits(got), bits(want), "{p:?} first {first:?}");
            }
        }
        // The repeated segment ties with the original: the lower index wins.
        let on = points[10].lerp(points[11], 0.5);
        assert_eq!(
            nearest(&segments, &balls, on, (&all, &blocks), Some(80))
                .unwrap()
                .2,
            10
        );
    }

    #[test]
    fn a_ball_out_of_reach_holds_no_point_within_reach() {
        let s = CutSegment::between(DVec3::new(50.0, 0.0, 0.0), DVec3::new(51.0, 0.0, 0.0));
        let balls = Balls::new(std::slice::from_ref(&s));
        let p = DVec3::new(50.5, 2.0, 0.0);
        assert!(balls.may_reach(0, p, 2.0));
        assert!(!balls.may_reach(0, p, 1.0));
        assert!(balls.may_reach(0, DVec3::new(53.0, 0.0, 0.0), 2.0));
    }
}
