//! What the pointer is over: the leading plane's handle, a plane's front vertex, a plane, or
//! nothing. Picking works on the planes as drawn (projected with the editor's camera), apart
//! from the event handling that acts on the result.

use glam::{DVec2, DVec3};

use super::{CursorHint, Editor, HANDLE_PX, VERTEX_PX};
use crate::cutter::CutKind;
use crate::geom;

/// What a pixel is over.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Pick {
    Nothing,
    Handle,
    Vertex { plane: usize, top: bool },
    Plane(usize),
}

impl Editor {
    pub(super) fn hint(&self, pick: Pick) -> CursorHint {
        if self.cutter.is_none() {
            return CursorHint::Crosshair;
        }
        match pick {
            Pick::Nothing => CursorHint::Default,
            Pick::Handle => CursorHint::Grab,
            Pick::Vertex { .. } => CursorHint::Move,
            Pick::Plane(_) => CursorHint::PointingHand,
        }
    }

    pub(super) fn project(&self, p: DVec3) -> Option<DVec2> {
        self.camera.project(self.viewport, p)
    }

    /// What the pixel `px` is over: the handle first, then a front vertex, then a plane.
    pub(super) fn pick(&self, px: DVec2) -> Pick {
        let Some(cutter) = &self.cutter else {
            return Pick::Nothing;
        };
        let lead = cutter.leading();
        if let (Some(a), Some(d)) = (
            self.project(lead.front_top),
            self.project(lead.front_bottom),
        ) {
            let s0 = a + (d - a) / 3.0;
            let s1 = a + (d - a) * (2.0 / 3.0);
            if segment_distance(px, s0, s1) <= HANDLE_PX {
                return Pick::Handle;
            }
        }
        let mut best: Option<(f64, Pick)> = None;
        for (i, p) in cutter.planes.iter().enumerate() {
            for (top, v) in [(true, p.front_top), (false, p.front_bottom)] {
                if cutter.kind == CutKind::Wedge && top {
                    continue;
                }
                if let Some(q) = self.project(v) {
                    let dist = (q - px).length();
                    if dist <= VERTEX_PX && best.is_none_or(|(b, _)| dist < b) {
                        best = Some((dist, Pick::Vertex { plane: i, top }));
                    }
                }
            }
        }
        if let Some((_, pick)) = best {
            return pick;
        }
        self.plane_under(px).map_or(Pick::Nothing, Pick::Plane)
    }

    /// The plane whose quad the pointer's ray hits first, else the plane whose projected front
    /// edge is nearest within [`HANDLE_PX`].
    pub(super) fn plane_under(&self, px: DVec2) -> Option<usize> {
        let cutter = self.cutter.as_ref()?;
        let ray = self.ray(px);
        let mut best: Option<(f64, usize)> = None;
        for (i, p) in cutter.planes.iter().enumerate() {
            for t in geom::quad_triangles(&p.corners()) {
                if let Some(s) = geom::ray_triangle(ray.origin, ray.direction, &t)
                    && best.is_none_or(|(b, _)| s < b)
                {
                    best = Some((s, i));
                }
            }
        }
        if let Some((_, i)) = best {
            return Some(i);
        }
        let mut near: Option<(f64, usize)> = None;
        for (i, p) in cutter.planes.iter().enumerate() {
            if let (Some(a), Some(d)) = (self.project(p.front_top), self.project(p.front_bottom)) {
                let dist = segment_distance(px, a, d);
                if dist <= HANDLE_PX && near.is_none_or(|(b, _)| dist < b) {
                    near = Some((dist, i));
                }
            }
        }
        near.map(|(_, i)| i)
    }

    /// The plane under the pointer ([`Editor::plane_under`]), else the plane whose projected
    /// front edge is nearest to it, at any distance (planes seen edge-on, as a cutter cut along
    /// the view is from there, show only their front edges).
    pub(super) fn nearest_plane(&self, px: DVec2) -> Option<usize> {
        if let Some(i) = self.plane_under(px) {
            return Some(i);
        }
        let cutter = self.cutter.as_ref()?;
        cutter
            .planes
            .iter()
            .enumerate()
            .filter_map(|(i, p)| {
                let a = self.project(p.front_top)?;
                let d = self.project(p.front_bottom)?;
                Some((segment_distance(px, a, d), i))
            })
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .map(|(_, i)| i)
    }

    /// True when the pointer is over any part of the cutter (its mesh, or near a front edge).
    pub(super) fn over_cutter(&self, px: DVec2) -> bool {
        let Some(cutter) = &self.cutter else {
            return false;
        };
        if self.pick(px) != Pick::Nothing {
            return true;
        }
        let ray = self.ray(px);
        let mesh = cutter.quad_mesh().triangulate();
        (0..mesh.triangles.len())
            .any(|t| geom::ray_triangle(ray.origin, ray.direction, &mesh.corners(t)).is_some())
    }
}

/// Distance from `p` to the segment `a`–`b`.
fn segment_distance(p: DVec2, a: DVec2, b: DVec2) -> f64 {
    let ab = b - a;
    let t = if ab.length_squared() > 0.0 {
        ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a + ab * t - p).length()
}
