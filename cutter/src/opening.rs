//! How much of the painted region a cut opens, seen from the view it was painted in.
//!
//! The painted region is the roller's footprint: the front faces of the cutter's boxes (the
//! quads between consecutive planes' front edges), projected to the image. The opening is what
//! the cut's contour (where the cutter meets the target's surface, the rim of the hole) encloses,
//! projected the same way. Both are measured in square pixels by scanlines: every row of a grid
//! over their joint bounds crosses each polygon's edges, each contour loop and each face fills
//! between alternate crossings (even-odd), and the loops' and faces' spans are joined per row.
//!
//! [`Opening::ratio`] (opened / painted) says whether the window is as large as what was
//! painted; [`Opening::outside`] (opened outside the painted region / painted) whether it spills
//! beyond it (a rounded cutter's bulge); [`Opening::covered`] how much of the painted region is
//! open. Tests and `cutaway extrude` on a session report them.

use glam::{DVec2, DVec3};

use crate::camera::Camera;
use crate::cutter::Cutter;

/// Rows of the scanline grid over the measured region.
pub const ROWS: usize = 800;

/// The painted and opened areas of a cut, in square pixels.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Opening {
    /// The projected front faces of the boxes.
    pub painted: f64,
    /// What the projected contour encloses.
    pub opened: f64,
    /// The part of `opened` inside `painted`.
    pub inside: f64,
}

impl Opening {
    /// Opened / painted: 1 when the window is exactly as large as what was painted.
    pub fn ratio(&self) -> f64 {
        self.opened / self.painted
    }

    /// The share of the painted region that is open.
    pub fn covered(&self) -> f64 {
        self.inside / self.painted
    }

    /// What opens outside the painted region, as a share of the painted region.
    pub fn outside(&self) -> f64 {
        (self.opened - self.inside).max(0.0) / self.painted
    }
}

/// Measures the opening of `cutter` whose cut left the contour loops `contour` (closed
/// polylines, the last point repeating the first or not), seen by `camera` in a `viewport`-pixel
/// image. None when nothing painted projects to the image (a plane behind the eye, a wedge seen
/// edge-on).
pub fn measure(
    camera: &Camera,
    viewport: DVec2,
    cutter: &Cutter,
    contour: &[Vec<DVec3>],
) -> Option<Opening> {
    let project = |p: DVec3| camera.project(viewport, p);
    let mut faces: Vec<Vec<DVec2>> = Vec::new();
    for pair in cutter.planes.windows(2) {
        let quad = [
            pair[0].front_top,
            pair[0].front_bottom,
            pair[1].front_bottom,
            pair[1].front_top,
        ];
        faces.push(quad.iter().map(|&p| project(p)).collect::<Option<_>>()?);
    }
    let loops: Vec<Vec<DVec2>> = contour
        .iter()
        .filter_map(|l| l.iter().map(|&p| project(p)).collect::<Option<Vec<_>>>())
        .filter(|l| l.len() >= 3)
        .collect();
    let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
    for p in faces.iter().chain(&loops).flatten() {
        lo = lo.min(*p);
        hi = hi.max(*p);
    }
    if !(lo.is_finite() && hi.is_finite()) || hi.y <= lo.y {
        return None;
    }
    let row = (hi.y - lo.y) / ROWS as f64;
    let mut out = Opening::default();
    for k in 0..ROWS {
        let y = lo.y + (k as f64 + 0.5) * row;
        let painted = union(faces.iter().flat_map(|f| spans(f, y)).collect());
        let opened = union(loops.iter().flat_map(|l| spans(l, y)).collect());
        out.painted += length(&painted) * row;
        out.opened += length(&opened) * row;
        out.inside += length(&intersection(&painted, &opened)) * row;
    }
    (out.painted > 0.0).then_some(out)
}

/// The spans of row `y` inside the closed polygon `poly` (even-odd).
fn spans(poly: &[DVec2], y: f64) -> Vec<(f64, f64)> {
    let mut xs = Vec::new();
    for (i, &a) in poly.iter().enumerate() {
        let b = poly[(i + 1) % poly.len()];
        if (a.y <= y) != (b.y <= y) {
            xs.push(a.x + (y - a.y) / (b.y - a.y) * (b.x - a.x));
        }
    }
    xs.sort_by(f64::total_cmp);
    xs.chunks_exact(2).map(|c| (c[0], c[1])).collect()
}

/// The spans joined into disjoint, ordered spans.
fn union(mut spans: Vec<(f64, f64)>) -> Vec<(f64, f64)> {
    spans.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut out: Vec<(f64, f64)> = Vec::with_capacity(spans.len());
    for (a, b) in spans {
        match out.last_mut() {
            Some(last) if a <= last.1 => last.1 = last.1.max(b),
            _ => out.push((a, b)),
        }
    }
    out
}

/// The overlap of two lists of disjoint, ordered spans.
fn intersection(a: &[(f64, f64)], b: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let (mut i, mut j) = (0, 0);
    let mut out = Vec::new();
    while i < a.len() && j < b.len() {
        let (lo, hi) = (a[i].0.max(b[j].0), a[i].1.min(b[j].1));
        if lo < hi {
            out.push((lo, hi));
        }
        if a[i].1 < b[j].1 {
            i += 1;
        } else {
            j += 1;
        }
    }
    out
}

fn length(spans: &[(f64, f64)]) -> f64 {
    spans.iter().map(|(a, b)| b - a).sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cutter::CutKind;
    use crate::plane::BoundedPlane;

    fn camera() -> Camera {
        Camera {
            eye: DVec3::new(0.0, -300.0, 0.0),
            target: DVec3::ZERO,
            up: DVec3::Z,
            fov_y_deg: 30.0,
        }
    }

    /// A 40 × 20 strip in the plane y = 0 facing the camera: a contour of the same square opens
    /// all of it; a contour half as wide opens half; one shifted sideways by a quarter opens
    /// three quarters of it and a quarter outside.
    #[test]
    fn the_opening_is_measured_against_the_painted_strip() {
        let plane = |x: f64| {
            BoundedPlane::from_front_edge(
                DVec3::new(x, 0.0, 10.0),
                DVec3::new(x, 0.0, -10.0),
                DVec3::Y,
                5.0,
            )
        };
        let cutter = Cutter {
            kind: CutKind::Curving,
            smooth: false,
            levels: 0,
            direction: crate::cutter::CutDirection::Normal,
            planes: vec![plane(-20.0), plane(0.0), plane(20.0)],
        };
        let viewport = DVec2::new(800.0, 600.0);
        let rect = |x0: f64, x1: f64| {
            vec![
                DVec3::new(x0, 0.0, -10.0),
                DVec3::new(x1, 0.0, -10.0),
                DVec3::new(x1, 0.0, 10.0),
                DVec3::new(x0, 0.0, 10.0),
                DVec3::new(x0, 0.0, -10.0),
            ]
        };
        let full = measure(&camera(), viewport, &cutter, &[rect(-20.0, 20.0)]).unwrap();
        assert!((full.ratio() - 1.0).abs() < 0.01, "{full:?}");
        assert!(full.outside() < 0.01 && full.covered() > 0.99);
        let half = measure(&camera(), viewport, &cutter, &[rect(-10.0, 10.0)]).unwrap();
        assert!((half.ratio() - 0.5).abs() < 0.01, "{half:?}");
        let shifted = measure(&camera(), viewport, &cutter, &[rect(-10.0, 30.0)]).unwrap();
        assert!((shifted.covered() - 0.75).abs() < 0.01, "{shifted:?}");
        assert!((shifted.outside() - 0.25).abs() < 0.01, "{shifted:?}");
        assert!(measure(&camera(), viewport, &cutter, &[]).unwrap().opened == 0.0);
    }
}
