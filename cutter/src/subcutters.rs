//! Ribbon and slice sub-cutters (thesis 3.4.2–3.4.3, Fig. 44).
//!
//! Three placements ([`Placement`]): thin boxes across the path at regular arc-length intervals
//! (their height and depth interpolated from the planes on either side), thin boxes centred on
//! each bounded cutting plane, or horizontal layers parallel to the surface at depth steps (the
//! cutter's own planes cut down to a band of depths, so a layer follows a curving, wedge or
//! smooth cutter exactly as the cutter does; a smooth cutter's layers are smooth too). The
//! boolean of each sub-cutter with the target gives a ribbon (no walls) or a slice (with walls);
//! that choice is the renderer's.
//!
//! Sizes are given absolutely (model units) or relative to the cut ([`SubCutterSpec::relative`]),
//! so one default looks the same on a knee in millimetres and a body in metres: relative, the
//! width is the fraction of the spacing between neighbouring sub-cutters that each one fills
//! (between planes for [`Placement::Planes`], between depth steps for
//! [`Placement::Horizontal`]).

use glam::DVec3;

use crate::cutter::{CutKind, Cutter};
use crate::plane::BoundedPlane;

/// Largest relative width: neighbouring sub-cutters must stay apart (the boolean takes several
/// sub-cutters at once only when they are disjoint).
pub const MAX_RELATIVE: f64 = 0.95;

/// Where sub-cutters go (see the module doc).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Placement {
    /// `count` thin boxes at regular arc-length intervals along the path.
    #[default]
    Even,
    /// One thin box centred on each bounded cutting plane (`count` is not used).
    Planes,
    /// `count` layers parallel to the surface, centred at depth steps.
    Horizontal,
}

impl Placement {
    /// The name used by the session format.
    pub fn name(self) -> &'static str {
        match self {
            Placement::Even => "even",
            Placement::Planes => "planes",
            Placement::Horizontal => "horizontal",
        }
    }

    /// Parses a format name (`even`, `planes`, `horizontal`).
    pub fn from_name(name: &str) -> Option<Placement> {
        match name {
            "even" => Some(Placement::Even),
            "planes" => Some(Placement::Planes),
            "horizontal" => Some(Placement::Horizontal),
            _ => None,
        }
    }
}

/// Which sub-cutters to make: the ribbons or slices of a cutter (thesis 3.4.2), evenly spaced
/// along the path, centred on the cutting planes, or horizontal layers at depth steps. The app's
/// scene keeps a cutter's ribbon and slice views as this type.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SubCutterSpec {
    /// Number of sub-cutters, at least 1 (not used by [`Placement::Planes`]: one per plane).
    pub count: usize,
    /// Width of each sub-cutter (across the path, or the layer's thickness); positive. Model
    /// units, or with `relative` the fraction (0..1] of the spacing between sub-cutters each
    /// one fills.
    pub width: f64,
    pub placement: Placement,
    /// `width` is relative to the cut instead of absolute.
    pub relative: bool,
}

impl SubCutterSpec {
    /// What a new ribbon or slice view starts with: five evenly spaced sub-cutters, each filling
    /// a third of its interval (relative, so it looks the same in millimetres and metres).
    pub const NEW: SubCutterSpec = SubCutterSpec {
        count: 5,
        width: 0.35,
        placement: Placement::Even,
        relative: true,
    };
}

/// The sub-cutters of `cutter` for `spec`; each passes [`Cutter::sanity_check`] (candidates that
/// would not are left out).
pub fn sub_cutters(cutter: &Cutter, spec: &SubCutterSpec) -> Vec<Cutter> {
    if !(spec.width.is_finite() && spec.width > 0.0) {
        return Vec::new();
    }
    let path = cutter.path();
    let length: f64 = path.windows(2).map(|w| (w[1] - w[0]).length()).sum();
    match spec.placement {
        Placement::Even => {
            let width = if spec.relative {
                spec.width.min(MAX_RELATIVE) * length / spec.count.max(1) as f64
            } else {
                spec.width
            };
            at_intervals(cutter, spec.count, width)
        }
        Placement::Planes => {
            let width = if spec.relative {
                spec.width.min(MAX_RELATIVE) * length / cutter.box_count().max(1) as f64
            } else {
                spec.width
            };
            on_planes(cutter, width)
        }
        Placement::Horizontal => horizontal(cutter, spec.count, spec.width, spec.relative),
    }
}

/// The width in model units each sub-cutter of `spec` has on `cutter`: `spec.width` when it is
/// absolute, else the relative width times the spacing it fills (along the path, or the mean
/// depth step for horizontal layers). A width switched from relative to absolute starts here, so
/// it keeps its size in millimetres and metres alike.
pub fn absolute_width(cutter: &Cutter, spec: &SubCutterSpec) -> f64 {
    if !spec.relative {
        return spec.width;
    }
    let relative = spec.width.min(MAX_RELATIVE);
    let path = cutter.path();
    let length: f64 = path.windows(2).map(|w| (w[1] - w[0]).length()).sum();
    match spec.placement {
        Placement::Even => relative * length / spec.count.max(1) as f64,
        Placement::Planes => relative * length / cutter.box_count().max(1) as f64,
        Placement::Horizontal => {
            let planes = cutter.planes.len().max(1) as f64;
            let depth = cutter.planes.iter().map(|p| p.depth()).sum::<f64>() / planes;
            relative * depth / spec.count.max(1) as f64
        }
    }
}

/// `count` layers of `cutter` parallel to its front (the surface), centred at depth fractions
/// `(k + ½) / count`; each is the cutter's planes cut down to a band of depths, `width` thick
/// (model units), or with `relative` the fraction `width` of a depth step (per plane).
pub fn horizontal(cutter: &Cutter, count: usize, width: f64, relative: bool) -> Vec<Cutter> {
    if count == 0 || !(width.is_finite() && width > 0.0) {
        return Vec::new();
    }
    (0..count)
        .filter_map(|k| {
            let centre = (k as f64 + 0.5) / count as f64;
            let planes = cutter
                .planes
                .iter()
                .map(|p| {
                    let half = if relative {
                        0.5 * width.min(MAX_RELATIVE) / count as f64
                    } else {
                        0.5 * width / p.depth().max(f64::MIN_POSITIVE)
                    };
                    depth_band(p, (centre - half).max(0.0), (centre + half).min(1.0))
                })
                .collect();
            let c = Cutter {
                kind: cutter.kind,
                smooth: cutter.smooth,
                levels: cutter.levels,
                direction: cutter.direction,
                planes,
            };
            c.sanity_check().ok().map(|_| c)
        })
        .collect()
}

/// The part of `plane` between depth fractions `t0 < t1` (0 = front edge, 1 = back edge).
fn depth_band(plane: &BoundedPlane, t0: f64, t1: f64) -> BoundedPlane {
    let at = |front: DVec3, back: DVec3, t: f64| front.lerp(back, t);
    BoundedPlane {
        front_top: at(plane.front_top, plane.back_top, t0),
        back_top: at(plane.front_top, plane.back_top, t1),
        back_bottom: at(plane.front_bottom, plane.back_bottom, t1),
        front_bottom: at(plane.front_bottom, plane.back_bottom, t0),
    }
}

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
        levels: crate::subdivision::DEFAULT_LEVELS,
        direction: crate::cutter::CutDirection::Normal,
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
            levels: crate::subdivision::DEFAULT_LEVELS,
            direction: crate::cutter::CutDirection::Normal,
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
    fn relative_widths_scale_with_the_cut() {
        let spec = SubCutterSpec {
            count: 4,
            width: 0.5,
            placement: Placement::Even,
            relative: true,
        };
        let small = sub_cutters(&cutter(), &spec);
        let mut big = cutter();
        for p in &mut big.planes {
            *p = BoundedPlane::from_corners(p.corners().map(|c| c * 1000.0));
        }
        let big = sub_cutters(&big, &spec);
        assert_eq!((small.len(), big.len()), (4, 4));
        // Path length 8, 4 ribbons: spacing 2, half of it filled.
        let width = |c: &Cutter| (c.planes[1].front_mid() - c.planes[0].front_mid()).length();
        assert!((width(&small[0]) - 1.0).abs() < 1e-9);
        assert!((width(&big[0]) - 1000.0).abs() < 1e-6);
        let planes = SubCutterSpec {
            placement: Placement::Planes,
            ..spec
        };
        let on = sub_cutters(&cutter(), &planes);
        assert_eq!(on.len(), 5);
        assert!((width(&on[2]) - 1.0).abs() < 1e-9);
        // The same widths in model units, to start an absolute width from.
        assert!((absolute_width(&cutter(), &spec) - 1.0).abs() < 1e-9);
        assert!((absolute_width(&cutter(), &planes) - 1.0).abs() < 1e-9);
        let absolute = SubCutterSpec {
            relative: false,
            width: 3.0,
            ..spec
        };
        assert_eq!(absolute_width(&cutter(), &absolute), 3.0);
    }

    #[test]
    fn horizontal_layers_are_depth_bands_of_the_cutter() {
        let c = cutter();
        let layers = horizontal(&c, 3, 0.5, true);
        assert_eq!(layers.len(), 3);
        for (k, layer) in layers.iter().enumerate() {
            layer.sanity_check().unwrap();
            assert_eq!(layer.planes.len(), c.planes.len());
            for (p, q) in c.planes.iter().zip(&layer.planes) {
                // Centred at depth (k + 1/2)/3 of each plane, 1/6 of its depth thick.
                let centre = (q.front_mid() + q.back_mid()) * 0.5 - p.front_mid();
                let expect = p.depth() * (k as f64 + 0.5) / 3.0;
                assert!((centre.dot(p.back_direction()) - expect).abs() < 1e-9);
                assert!((q.depth() - p.depth() / 6.0).abs() < 1e-9);
            }
        }
        // Absolute: 0.25 units thick whatever the plane's depth.
        for layer in horizontal(&c, 2, 0.25, false) {
            for q in &layer.planes {
                assert!((q.depth() - 0.25).abs() < 1e-9);
            }
        }
        // A smooth cutter's layers are smooth.
        let smooth = Cutter {
            smooth: true,
            levels: crate::subdivision::DEFAULT_LEVELS,
            ..c.clone()
        };
        assert!(horizontal(&smooth, 2, 0.5, true).iter().all(|l| l.smooth));
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
