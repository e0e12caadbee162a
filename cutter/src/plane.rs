//! A bounded cutting plane (thesis 3.2): the quadrilateral that separates two boxes of a cutter.
//!
//! Naming follows the thesis's figures 23 and 27: a plane `ABCD` is `A` front-top, `B` back-top,
//! `C` back-bottom, `D` front-bottom. "Front" lies on the occluding surface, "back" deeper inside;
//! "top" and "bottom" are only the two ends of the front edge (the paint roller), with no relation
//! to the screen. The front edge `AD` is the roller; the back edges `AB` and `DC` point into the
//! object. Every operation here moves whole edges (front and back vertex together) or rotates
//! about the front edge, so the two back edges stay parallel and the plane stays planar.

use glam::{DQuat, DVec3};

/// One bounded cutting plane: front-top, back-top, back-bottom, front-bottom.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoundedPlane {
    /// `A`: the top end of the front edge, on (or just above) the surface.
    pub front_top: DVec3,
    /// `B`: `front_top` pushed into the object by the plane's depth.
    pub back_top: DVec3,
    /// `C`: `front_bottom` pushed into the object by the plane's depth.
    pub back_bottom: DVec3,
    /// `D`: the bottom end of the front edge.
    pub front_bottom: DVec3,
}

impl BoundedPlane {
    /// A plane from its front edge, a unit-or-not `back` direction and a depth.
    pub fn from_front_edge(front_top: DVec3, front_bottom: DVec3, back: DVec3, depth: f64) -> Self {
        let back = back.try_normalize().unwrap_or(DVec3::ZERO) * depth;
        BoundedPlane {
            front_top,
            back_top: front_top + back,
            back_bottom: front_bottom + back,
            front_bottom,
        }
    }

    /// The four corners in storage order (A, B, C, D).
    pub fn corners(&self) -> [DVec3; 4] {
        [
            self.front_top,
            self.back_top,
            self.back_bottom,
            self.front_bottom,
        ]
    }

    /// Builds a plane from corners in storage order.
    pub fn from_corners(c: [DVec3; 4]) -> Self {
        BoundedPlane {
            front_top: c[0],
            back_top: c[1],
            back_bottom: c[2],
            front_bottom: c[3],
        }
    }

    /// Midpoint of the front edge (`Q` in the thesis's figure 27).
    pub fn front_mid(&self) -> DVec3 {
        (self.front_top + self.front_bottom) * 0.5
    }

    /// Midpoint of the back edge.
    pub fn back_mid(&self) -> DVec3 {
        (self.back_top + self.back_bottom) * 0.5
    }

    /// Centre of the four corners.
    pub fn center(&self) -> DVec3 {
        (self.front_top + self.back_top + self.back_bottom + self.front_bottom) * 0.25
    }

    /// Length of the front edge `|AD|`.
    pub fn front_length(&self) -> f64 {
        (self.front_top - self.front_bottom).length()
    }

    /// Mean depth (length of the back edges `AB` and `DC`).
    pub fn depth(&self) -> f64 {
        0.5 * ((self.back_top - self.front_top).length()
            + (self.back_bottom - self.front_bottom).length())
    }

    /// Unit direction from front to back (mean of the two back edges), or zero when degenerate.
    pub fn back_direction(&self) -> DVec3 {
        ((self.back_top - self.front_top) + (self.back_bottom - self.front_bottom))
            .try_normalize()
            .unwrap_or(DVec3::ZERO)
    }

    /// Unit normal of the plane (`AD × AB` orientation), or zero when degenerate.
    pub fn normal(&self) -> DVec3 {
        let d = self.front_bottom - self.front_top;
        let b = self.back_direction();
        d.cross(b).try_normalize().unwrap_or(DVec3::ZERO)
    }

    /// Largest distance of a corner from the best plane through the corners, relative to the
    /// plane's size (0 for a perfectly planar quad).
    pub fn planarity_error(&self) -> f64 {
        let c = self.corners();
        let n = (c[2] - c[0]).cross(c[3] - c[1]);
        let Some(n) = n.try_normalize() else {
            return 0.0;
        };
        let centre = self.center();
        let size = (c[2] - c[0])
            .length()
            .max((c[3] - c[1]).length())
            .max(1e-300);
        c.iter()
            .map(|p| (p - centre).dot(n).abs())
            .fold(0.0, f64::max)
            / size
    }

    /// The same plane with both back vertices at `depth` from their front vertices along the
    /// current back direction (keeps the back edges parallel).
    pub fn with_depth(&self, depth: f64) -> Self {
        let dir = self.back_direction();
        BoundedPlane::from_front_edge(self.front_top, self.front_bottom, dir, depth)
    }

    /// The same plane with its back edge rotated by `angle` radians about the front edge (axis
    /// from front-bottom to front-top, right-hand rule).
    pub fn rotated_about_front_edge(&self, angle: f64) -> Self {
        let Some(axis) = (self.front_top - self.front_bottom).try_normalize() else {
            return *self;
        };
        let q = DQuat::from_axis_angle(axis, angle);
        BoundedPlane {
            front_top: self.front_top,
            back_top: self.front_top + q * (self.back_top - self.front_top),
            back_bottom: self.front_bottom + q * (self.back_bottom - self.front_bottom),
            front_bottom: self.front_bottom,
        }
    }

    /// The plane moved by `offset`.
    pub fn translated(&self, offset: DVec3) -> Self {
        BoundedPlane::from_corners(self.corners().map(|p| p + offset))
    }

    /// Linear interpolation of corresponding corners (`t = 0` gives `self`).
    pub fn lerp(&self, other: &BoundedPlane, t: f64) -> Self {
        let a = self.corners();
        let b = other.corners();
        BoundedPlane::from_corners([0, 1, 2, 3].map(|i| a[i].lerp(b[i], t)))
    }

    /// True when every corner is finite.
    pub fn is_finite(&self) -> bool {
        self.corners().iter().all(|p| p.is_finite())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plane() -> BoundedPlane {
        BoundedPlane::from_front_edge(DVec3::new(0.0, 0.0, 1.0), DVec3::ZERO, DVec3::Y, 2.0)
    }

    #[test]
    fn depth_and_rotation_keep_planarity() {
        let p = plane();
        assert!((p.depth() - 2.0).abs() < 1e-12);
        let deeper = p.with_depth(5.0);
        assert!((deeper.depth() - 5.0).abs() < 1e-12);
        let r = p.rotated_about_front_edge(0.3);
        assert!(r.planarity_error() < 1e-12);
        assert_eq!(r.front_top, p.front_top);
        assert!((r.depth() - 2.0).abs() < 1e-12);
        assert!((r.back_direction().dot(DVec3::Y) - 0.3f64.cos()).abs() < 1e-12);
    }

    #[test]
    fn twisted_quad_is_not_planar() {
        let mut p = plane();
        p.back_bottom.x += 0.5;
        assert!(p.planarity_error() > 0.05);
    }
}
