//! How clean an opened incision's lips are: the figures the tests hold the opening to.
//!
//! An opened cut should show two lips along the drawn path's offset curves,
//! `c(s) ± (w/2)·taper(s)·l(s)` (`c` the drawn path smoothed as the opening smooths it,
//! [`super::drawn::smooth`]; `l = n × t` its lateral direction on the surface; the taper as in
//! [`super::dffd`], from 0 at the path's ends to 1 `taper_len` away). [`Reference`] holds that
//! curve; [`Reference::measure`] takes the opened lip points (the display positions of the
//! coincident copies of each rest-pose lip point) and reports, per lip, the Hausdorff distance
//! to its offset curve, the sharpest turn between consecutive lip edges away from the tips (a
//! spike or a notch) and the smallest gap between the lips where the taper is 1.
//!
//! The measure knows nothing of the mesh, so the cutter's tests (which know the copies) and the
//! workspace's (which find them in a written mesh) measure alike.

use glam::DVec3;

use super::cut_point::segment_parameter;

/// The drawn path's offset curves (see the module doc).
#[derive(Clone, Debug)]
pub struct Reference {
    /// The smoothed path, densified.
    points: Vec<DVec3>,
    /// Unit lateral direction at each point.
    lateral: Vec<DVec3>,
    /// Unit surface normal at each point.
    normal: Vec<DVec3>,
    /// Taper at each point.
    taper: Vec<f64>,
    /// Arc length at each point.
    arc: Vec<f64>,
    width: f64,
}

/// The figures of one opened incision (see the module doc).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LipReport {
    /// Largest Hausdorff distance of a lip to its offset curve (over the stretch of curve the
    /// lip spans).
    pub hausdorff: f64,
    /// Largest distance of a lip point to its offset curve (the Hausdorff distance less the
    /// chords between lip points across a curving path).
    pub point_distance: f64,
    /// Largest angle (degrees) between consecutive lip edges where the taper is 1 (at their
    /// three points), edges shorter than [`MIN_EDGE`] widths joined with the next.
    pub worst_turn_deg: f64,
    /// Smallest distance from a lip point to the other lip where the taper is 1.
    pub min_gap: f64,
    /// Lip points measured on each side.
    pub points: [usize; 2],
    /// Pairs of copies that both lie on one side of the path where the taper is 1 (a lip
    /// crossing over).
    pub same_side: usize,
}

/// Lip edges shorter than this many widths are joined with the next for the turn (see
/// [`LipReport::worst_turn_deg`]).
pub const MIN_EDGE: f64 = 0.2;

/// Where a point projects onto a polyline: (distance, segment, parameter).
fn project(points: &[DVec3], p: DVec3) -> (f64, usize, f64) {
    let mut best = (f64::INFINITY, 0, 0.0);
    for k in 0..points.len().saturating_sub(1) {
        let (a, b) = (points[k], points[k + 1]);
        let u = segment_parameter(a, b, p);
        let d = a.lerp(b, u).distance(p);
        if d < best.0 {
            best = (d, k, u);
        }
    }
    if points.len() == 1 {
        best = (points[0].distance(p), 0, 0.0);
    }
    best
}

impl Reference {
    /// The offset curves of the path `path` (points on the surface with the surface's unit
    /// normal there, in drawing order) opened to `width`, tapering over `taper_len` from each
    /// end. The smoothed path is resampled every `width / 16`.
    pub fn new(path: &[(DVec3, DVec3)], width: f64, taper_len: f64) -> Reference {
        let raw: Vec<DVec3> = path.iter().map(|p| p.0).collect();
        let smooth = super::drawn::smooth(&raw, 0.5 * width);
        let normals: Vec<DVec3> = path.iter().map(|p| p.1).collect();
        let normals = super::drawn::smooth(&normals, 1.5);
        let step = width / 16.0;
        let mut points = Vec::new();
        let mut normal = Vec::new();
        for k in 0..smooth.len() {
            if k + 1 == smooth.len() {
                points.push(smooth[k]);
                normal.push(normals[k]);
                break;
            }
            let n = (smooth[k].distance(smooth[k + 1]) / step).ceil().max(1.0) as usize;
            for i in 0..n {
                let u = i as f64 / n as f64;
                points.push(smooth[k].lerp(smooth[k + 1], u));
                normal.push(normals[k].lerp(normals[k + 1], u));
            }
        }
        let m = points.len();
        let mut arc = vec![0.0; m];
        for k in 1..m {
            arc[k] = arc[k - 1] + points[k].distance(points[k - 1]);
        }
        let normal: Vec<DVec3> = normal.iter().map(|n| n.normalize_or_zero()).collect();
        let lateral = (0..m)
            .map(|k| {
                let t = points[(k + 1).min(m - 1)] - points[k.saturating_sub(1)];
                normal[k].cross(t).normalize_or_zero()
            })
            .collect();
        let (first, last) = (points[0], points[m - 1]);
        let taper = points
            .iter()
            .map(|p| {
                let x = (p.distance(first).min(p.distance(last)) / taper_len).min(1.0);
                x * x * (3.0 - 2.0 * x)
            })
            .collect();
        Reference {
            points,
            lateral,
            normal,
            taper,
            arc,
            width,
        }
    }

    /// The offset curve on side `sigma` (±1).
    fn offset(&self, sigma: f64) -> Vec<DVec3> {
        (0..self.points.len())
            .map(|k| self.points[k] + self.lateral[k] * (sigma * 0.5 * self.width * self.taper[k]))
            .collect()
    }

    /// Arc length, taper and signed lateral offset of `p` at its projection onto the path,
    /// and `p` with its offset along the surface normal there taken out (see
    /// [`Reference::measure`]).
    fn locate(&self, p: DVec3) -> (f64, f64, f64, DVec3) {
        let (_, k, u) = project(&self.points, p);
        let k1 = (k + 1).min(self.points.len() - 1);
        let c = self.points[k].lerp(self.points[k1], u);
        let s = self.arc[k] + u * (self.arc[k1] - self.arc[k]);
        let taper = self.taper[k] + u * (self.taper[k1] - self.taper[k]);
        let n = self.normal[k];
        (
            s,
            taper,
            (p - c).dot(self.lateral[k]),
            p - n * (p - c).dot(n),
        )
    }

    /// Measures the lips given as groups of display positions, one group per rest-pose lip
    /// point: its two copies (one per lip), or one point where the lips meet (a crack tip).
    /// Distances and turns are measured along the surface: each lip point's offset along the
    /// surface normal at the path (the surface's own relief under the lips, which the opening
    /// keeps) is left out.
    pub fn measure(&self, groups: &[Vec<DVec3>]) -> LipReport {
        let mut report = LipReport::default();
        // (arc length, taper, point) per side: 0 is +lateral, 1 is -lateral.
        let mut lips: [Vec<(f64, f64, DVec3)>; 2] = [Vec::new(), Vec::new()];
        let full = |t: f64| t >= 1.0 - 1e-9;
        for g in groups {
            match g.as_slice() {
                [p] => {
                    let (s, t, _, p) = self.locate(*p);
                    lips[0].push((s, t, p));
                    lips[1].push((s, t, p));
                }
                [p, q] => {
                    let (s, t, e, p) = self.locate(*p);
                    let (s2, t2, e2, q) = self.locate(*q);
                    if e * e2 > 0.0 && full(t) && full(t2) {
                        report.same_side += 1;
                    }
                    let (plus, minus) = if e >= e2 {
                        ((s, t, p), (s2, t2, q))
                    } else {
                        ((s2, t2, q), (s, t, p))
                    };
                    lips[0].push(plus);
                    lips[1].push(minus);
                }
                _ => {}
            }
        }
        for lip in lips.iter_mut() {
            lip.sort_by(|a, b| a.0.total_cmp(&b.0));
        }
        report.points = [lips[0].len(), lips[1].len()];
        let polyline = |lip: &[(f64, f64, DVec3)]| lip.iter().map(|x| x.2).collect::<Vec<_>>();
        for (side, sigma) in [(0, 1.0), (1, -1.0)] {
            let lip = &lips[side];
            if lip.is_empty() {
                continue;
            }
            let curve = self.offset(sigma);
            let line = polyline(lip);
            // Lip to curve.
            for p in &line {
                let d = project(&curve, *p).0;
                report.point_distance = report.point_distance.max(d);
                report.hausdorff = report.hausdorff.max(d);
            }
            // Curve to lip, over the stretch the lip spans.
            let (s0, s1) = (lip[0].0, lip[lip.len() - 1].0);
            for (k, c) in curve.iter().enumerate() {
                if self.arc[k] >= s0 && self.arc[k] <= s1 {
                    report.hausdorff = report.hausdorff.max(project(&line, *c).0);
                }
            }
            // Turning between consecutive lip edges where the taper is 1, the edges at least
            // `MIN_EDGE` widths long (a lip point closer than that to the one before or after is
            // passed over: its position, not the direction of a tiny edge, is what shows).
            let min_edge = MIN_EDGE * self.width;
            for k in 1..lip.len().saturating_sub(1) {
                let p = lip[k].2;
                let before = (0..k).rev().find(|&j| lip[j].2.distance(p) >= min_edge);
                let after = (k + 1..lip.len()).find(|&j| lip[j].2.distance(p) >= min_edge);
                let (Some(j), Some(m)) = (before, after) else {
                    continue;
                };
                if !(full(lip[j].1) && full(lip[k].1) && full(lip[m].1)) {
                    continue;
                }
                let turn = (p - lip[j].2).angle_between(lip[m].2 - p).to_degrees();
                report.worst_turn_deg = report.worst_turn_deg.max(turn);
            }
        }
        // The gap where the taper is 1.
        report.min_gap = f64::INFINITY;
        for side in 0..2 {
            let other = polyline(&lips[1 - side]);
            for x in lips[side].iter().filter(|x| full(x.1)) {
                report.min_gap = report.min_gap.min(project(&other, x.2).0);
            }
        }
        report
    }
}

/// The lip points of `scalpel`'s cuts as [`Reference::measure`] takes them: for each vertex a
/// cut segment ends at (groove floors aside), the positions in `shown` of it and its coincident
/// copies. Each point once.
pub fn lip_groups(scalpel: &super::Scalpel, shown: &[DVec3]) -> Vec<Vec<DVec3>> {
    let mesh = scalpel.dyn_mesh();
    let mut seen = std::collections::HashSet::new();
    let mut out = Vec::new();
    for s in scalpel.segments() {
        for v in [s.a, s.b] {
            if mesh.is_floor(v) || !seen.insert(v) {
                continue;
            }
            let copies = mesh.copies(v);
            seen.extend(copies.iter().copied());
            out.push(
                std::iter::once(v)
                    .chain(copies)
                    .filter(|&c| !mesh.is_floor(c))
                    .map(|c| shown[c as usize])
                    .collect(),
            );
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A straight path along x on z = 0 (normal +z): lateral is +y.
    fn straight() -> Reference {
        let path: Vec<(DVec3, DVec3)> = (0..=20)
            .map(|i| (DVec3::new(i as f64, 0.0, 0.0), DVec3::Z))
            .collect();
        Reference::new(&path, 1.0, 2.0)
    }

    fn lips(dy: impl Fn(f64) -> f64) -> Vec<Vec<DVec3>> {
        (0..=40)
            .map(|i| {
                let x = 0.5 * i as f64;
                let r = straight();
                let (_, t, _, _) = r.locate(DVec3::new(x, 0.0, 0.0));
                let y = 0.5 * t + dy(x);
                vec![DVec3::new(x, y, 0.0), DVec3::new(x, -y, 0.0)]
            })
            .collect()
    }

    #[test]
    fn lips_on_the_offset_curves_measure_clean_and_a_spike_does_not() {
        let r = straight();
        let clean = r.measure(&lips(|_| 0.0));
        // The lip's chords across the taper's curve near the ends.
        assert!(clean.hausdorff < 0.03, "{clean:?}");
        assert!(clean.worst_turn_deg < 1e-6, "{clean:?}");
        assert!((clean.min_gap - 1.0).abs() < 0.02, "{clean:?}");
        assert_eq!(clean.same_side, 0);
        let spiky = r.measure(&lips(|x| if x == 10.0 { 0.3 } else { 0.0 }));
        assert!((spiky.hausdorff - 0.3).abs() < 1e-6, "{spiky:?}");
        assert!(spiky.worst_turn_deg > 60.0, "{spiky:?}");
        let crossed = r.measure(&lips(|x| if x == 10.0 { -0.7 } else { 0.0 }));
        assert_eq!(crossed.same_side, 0, "copies swapped, still one each side");
        assert!(crossed.min_gap < 0.5, "{crossed:?}");
    }
}
