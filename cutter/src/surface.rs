//! The target surface as the editor sees it: a mesh plus its spatial index, and the collision
//! queries of the extrusion (the thesis used `vtkCollisionDetectionFilter` over OBB trees).

use glam::DVec3;

use csg::{Aabb, Mesh, SpatialIndex};

use crate::geom;

/// A borrowed view of the target mesh and its index (built from that same mesh).
#[derive(Clone, Copy)]
pub struct Surface<'a> {
    pub mesh: &'a Mesh,
    /// Must have been built from `mesh`.
    pub index: &'a SpatialIndex,
}

impl<'a> Surface<'a> {
    /// Wraps a mesh and the index built from it.
    pub fn new(mesh: &'a Mesh, index: &'a SpatialIndex) -> Self {
        Surface { mesh, index }
    }

    /// True when the triangle `t` crosses the surface.
    pub fn triangle_intersects(&self, t: &[DVec3; 3], scratch: &mut Vec<u32>) -> bool {
        let b = Aabb::from_points(t.iter());
        scratch.clear();
        self.index.faces_in_box(&b, scratch);
        scratch
            .iter()
            .any(|&f| geom::tri_tri_intersect(t, &self.mesh.corners(f as usize)))
    }

    /// True when the quad `q` (split along its first diagonal) crosses the surface.
    ///
    /// Most candidate triangles from the box query lie entirely on one side of the quad's plane
    /// (the face rests above the surface); a sign test of their corners against each half of the
    /// quad rejects them before the full triangle/triangle test.
    pub fn quad_intersects(&self, q: &[DVec3; 4], scratch: &mut Vec<u32>) -> bool {
        let b = Aabb::from_points(q.iter());
        scratch.clear();
        self.index.faces_in_box(&b, scratch);
        let halves = geom::quad_triangles(q);
        let planes = halves.map(|t| {
            let n = (t[1] - t[0]).cross(t[2] - t[0]);
            (n, n.dot(t[0]))
        });
        scratch.iter().any(|&f| {
            let c = self.mesh.corners(f as usize);
            halves.iter().zip(&planes).any(|(t, &(n, d))| {
                let s = c.map(|p| n.dot(p) - d);
                let one_side = (s[0] > 0.0 && s[1] > 0.0 && s[2] > 0.0)
                    || (s[0] < 0.0 && s[1] < 0.0 && s[2] < 0.0);
                !one_side && geom::tri_tri_intersect(t, &c)
            })
        })
    }

    /// The triangles whose boxes overlap `region`, copied out for repeated local queries (the
    /// rotation search tests the same neighbourhood a dozen times per mouse move).
    pub fn local(&self, region: &Aabb) -> LocalSurface {
        let mut faces = Vec::new();
        self.index.faces_in_box(region, &mut faces);
        let tris = faces
            .iter()
            .map(|&f| self.mesh.corners(f as usize))
            .collect();
        LocalSurface { tris }
    }

    /// Distance from `p` to the surface (infinite for an empty mesh).
    pub fn distance(&self, p: DVec3) -> f64 {
        self.index
            .closest_point(self.mesh, p)
            .map_or(f64::INFINITY, |c| c.distance)
    }

    /// True when `p` lies behind the surface point closest to it (inside a closed, outward
    /// target), judged by that face's normal. Approximate where the closest point is on a sharp
    /// edge; used only to catch a face that slipped entirely under the surface, where no
    /// crossing is left to detect.
    pub fn is_inside(&self, p: DVec3) -> bool {
        self.index.closest_point(self.mesh, p).is_some_and(|c| {
            let n = self.mesh.face_normal_scaled(c.face as usize);
            (p - c.point).dot(n) < 0.0
        })
    }

    /// The surface point closest to `p`.
    pub fn closest_point(&self, p: DVec3) -> Option<DVec3> {
        self.index.closest_point(self.mesh, p).map(|c| c.point)
    }

    /// First hit of a ray (unit or not `direction`), as the hit point and its parameter.
    pub fn ray_cast(&self, origin: DVec3, direction: DVec3, t_max: f64) -> Option<(f64, DVec3)> {
        self.index
            .ray_cast(self.mesh, origin, direction, t_max)
            .map(|h| (h.t, h.point))
    }

    /// Bounding box of the target.
    pub fn bbox(&self) -> Aabb {
        self.mesh.bbox()
    }
}

/// A copy of the surface triangles in one neighbourhood (see [`Surface::local`]).
#[derive(Clone, Debug, Default)]
pub struct LocalSurface {
    pub tris: Vec<[DVec3; 3]>,
}

impl LocalSurface {
    /// True when the quad `q` crosses one of these triangles (same test as
    /// [`Surface::quad_intersects`], valid for quads inside the neighbourhood).
    pub fn quad_intersects(&self, q: &[DVec3; 4]) -> bool {
        let b = Aabb::from_points(q.iter());
        let halves = geom::quad_triangles(q);
        let planes = halves.map(|t| {
            let n = (t[1] - t[0]).cross(t[2] - t[0]);
            (n, n.dot(t[0]))
        });
        self.tris.iter().any(|c| {
            let lo = c[0].min(c[1]).min(c[2]);
            let hi = c[0].max(c[1]).max(c[2]);
            if lo.cmpgt(b.max).any() || hi.cmplt(b.min).any() {
                return false;
            }
            halves.iter().zip(&planes).any(|(t, &(n, d))| {
                let s = c.map(|p| n.dot(p) - d);
                let one_side = (s[0] > 0.0 && s[1] > 0.0 && s[2] > 0.0)
                    || (s[0] < 0.0 && s[1] < 0.0 && s[2] < 0.0);
                !one_side && geom::tri_tri_intersect(t, c)
            })
        })
    }
}
