//! The cutter (thesis 3.2): an ordered list of bounded cutting planes and the closed quad mesh of
//! the "boxes" between consecutive planes.
//!
//! Box `i` joins plane `i` (its left face) to plane `i + 1` (its right face) with a front, back,
//! top and bottom quad; planes `0` and `n - 1` close the ends. A wedge cutter's planes all share
//! their top edge (front-top and back-top are the same two points for every plane), so its boxes
//! are prisms fanned around that axis: front and back faces become triangles and the top faces
//! vanish. The mesh is oriented outward by construction (the face order is fixed and flipped as a
//! whole when the planes run the other way round), so callers never fix orientation themselves.

use glam::DVec3;

use crate::geom;
use crate::plane::BoundedPlane;
pub use crate::quad_mesh::QuadMesh;

/// The three cut types of the thesis (3.3.2.1–3.3.2.3). Rounded/freeform is `smooth` on top.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum CutKind {
    /// Paint-roller curving path (the default).
    #[default]
    Curving,
    /// Straight path (the Shift constraint always on).
    Straight,
    /// Wedge ("Circle" button): prisms sharing one top axis.
    Wedge,
}

impl CutKind {
    /// The name used by the gesture and session formats.
    pub fn name(self) -> &'static str {
        match self {
            CutKind::Curving => "curving",
            CutKind::Straight => "straight",
            CutKind::Wedge => "wedge",
        }
    }

    /// Parses a format name (`curving`, `straight`, `wedge`).
    pub fn from_name(name: &str) -> Option<CutKind> {
        match name {
            "curving" => Some(CutKind::Curving),
            "straight" => Some(CutKind::Straight),
            "wedge" => Some(CutKind::Wedge),
            _ => None,
        }
    }
}

/// Which way a cutter's boxes go into the target: the first box goes along the view either way
/// (the strip is painted in the view plane).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum CutDirection {
    /// Every plane keeps the direction of the plane before it, so the whole cutter goes along
    /// the view it was painted in: the way you look at the surface is the way you look into it,
    /// and the opening is what was painted as seen from there.
    #[default]
    View,
    /// Each rolled plane goes along the inward normal of its box's front face (thesis 3.3.2):
    /// the cut follows the surface, a trench of even depth under it.
    Normal,
}

impl CutDirection {
    /// The name used by the gesture and session formats (`view`, `normal`).
    pub fn name(self) -> &'static str {
        match self {
            CutDirection::View => "view",
            CutDirection::Normal => "normal",
        }
    }

    /// Parses a format name (`view`, `normal`).
    pub fn from_name(name: &str) -> Option<CutDirection> {
        match name {
            "view" => Some(CutDirection::View),
            "normal" => Some(CutDirection::Normal),
            _ => None,
        }
    }
}

/// Why a list of planes is not a valid cutter. Each variant names the offending plane or box.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum CutterError {
    /// A cutter needs at least one box. Extrude or keep the initial box.
    #[error("a cutter needs at least 2 planes, this one has {count}")]
    TooFewPlanes { count: usize },
    /// NaN or infinite coordinate.
    #[error("plane {plane} has a non-finite corner")]
    NonFinite { plane: usize },
    /// Zero-length front edge or zero depth.
    #[error("plane {plane} is degenerate (front edge {front_length}, depth {depth})")]
    Degenerate {
        plane: usize,
        front_length: f64,
        depth: f64,
    },
    /// The four corners are not in one plane (relative error given).
    #[error("plane {plane} is not planar (relative error {error:e})")]
    NotPlanar { plane: usize, error: f64 },
    /// Wedge planes must share front-top and back-top with plane 0.
    #[error("wedge plane {plane} does not share the top axis of plane 0")]
    WedgeAxisNotShared { plane: usize },
    /// Planes `plane` and `plane + 1` intersect.
    #[error("planes {plane} and {} cross", plane + 1)]
    ConsecutivePlanesCross { plane: usize },
    /// Box `index` is turned inside out (non-positive volume relative to the whole cutter).
    #[error("box {index} is inverted or flat (volume {volume:e})")]
    InvertedBox { index: usize, volume: f64 },
    /// Two faces of the mesh that share no vertex intersect.
    #[error("the cutter mesh intersects itself (faces {face_a} and {face_b})")]
    SelfIntersecting { face_a: usize, face_b: usize },
    /// An edge is not used exactly twice in opposite directions.
    #[error("the cutter mesh is not closed and oriented at edge {a}-{b}")]
    NotClosed { a: u32, b: u32 },
    /// The exact check of the cutting surface refused it.
    #[error("the cutter surface is not a valid cutter: {reason}")]
    Refused { reason: String },
    /// The wedge sweeps a full turn or more.
    #[error("the wedge sweeps {degrees:.0} degrees, which overlaps itself")]
    WedgeOverlaps { degrees: f64 },
}

/// A cutter: the planes and the kind they were made with.
#[derive(Clone, Debug, PartialEq)]
pub struct Cutter {
    /// How the cutter was made; a `Wedge` cutter's planes share the top axis.
    pub kind: CutKind,
    /// Render and cut the subdivided (rounded/freeform) mesh instead of the boxes.
    pub smooth: bool,
    /// Subdivision levels of the smooth surface, the user's "Smoothness" (0 to
    /// [`crate::subdivision::MAX_LEVELS`], more is clamped; default
    /// [`crate::subdivision::DEFAULT_LEVELS`]). Ignored when not `smooth`.
    pub levels: u32,
    /// Which way its planes go: rolled planes keep the back direction of the plane before them
    /// ([`CutDirection::View`], a window cut straight in from where it was painted) or go along
    /// the normal of their front face ([`CutDirection::Normal`], the thesis's roller, and every
    /// cutter made before the direction was a choice). A smooth cutter along the view is rounded
    /// more gently ([`VIEW_ROUNDNESS`]), so its window stays the size that was painted.
    pub direction: CutDirection,
    /// The bounded cutting planes in extrusion order. At least 2; each planar; consecutive planes
    /// never cross; for `Wedge`, every plane's `front_top`/`back_top` equal plane 0's. The last
    /// plane is the leading plane (the paint roller's handle). Checked by [`Cutter::sanity_check`].
    pub planes: Vec<BoundedPlane>,
}

/// The share of the interpolating subdivision's rounding a smooth cutter along the view gets
/// (1 along the normal). Its boxes go deep, straight in: the full rounding bulges a box's sides
/// out by an eighth of its width at mid-depth, where a deep box meets a curved surface, so the
/// window would spill past what was painted (15 % on a sphere); half of it keeps the surface
/// smooth (the four-point rule with half the tension is still C¹) and the window within 5 %.
pub const VIEW_ROUNDNESS: f64 = 0.5;

/// Relative planarity tolerance of [`Cutter::sanity_check`].
const PLANARITY_TOL: f64 = 1e-6;

impl Cutter {
    /// Number of boxes (planes − 1).
    pub fn box_count(&self) -> usize {
        self.planes.len().saturating_sub(1)
    }

    /// The depth of the cutter: its leading plane's, which the planes it rolls out take.
    pub fn depth(&self) -> f64 {
        self.leading().depth()
    }

    /// The leading plane (the last one).
    pub fn leading(&self) -> &BoundedPlane {
        self.planes.last().expect("a cutter has planes")
    }

    /// The closed outward quad mesh of the boxes (before any smoothing).
    pub fn quad_mesh(&self) -> QuadMesh {
        let mut mesh = if self.kind == CutKind::Wedge {
            self.wedge_faces()
        } else {
            self.box_faces()
        };
        if mesh.volume() < 0.0 {
            for f in &mut mesh.faces {
                f.reverse();
            }
        }
        mesh
    }

    /// The closed polygon mesh the cutter is: the boxes, or when `smooth` their interpolating
    /// subdivision with [`Cutter::levels`] levels ([`Cutter::smoothing`]: repaired so that it
    /// never folds, adaptive along the path).
    pub fn display_mesh(&self) -> QuadMesh {
        self.smoothing(self.levels).mesh
    }

    /// The closed, outward, triangulated cutter surface: what the boolean cuts with and what the
    /// Edit overlay draws (one function for both, so what the user edits is what cuts).
    pub fn surface(&self) -> csg::Mesh {
        self.display_mesh().triangulate()
    }

    /// [`Cutter::surface`] with `levels` subdivision levels instead of [`Cutter::levels`] when
    /// smooth (ignored when not).
    pub fn surface_with_levels(&self, levels: u32) -> csg::Mesh {
        self.smoothing(levels).mesh.triangulate()
    }

    /// The smoothing of the box mesh with `levels` levels (none when the cutter is not smooth),
    /// with what its repair gave up: [`Cutter::uniform_smoothing`] made adaptive along the path
    /// for curving and straight cutters ([`crate::adaptive`]: the rings of straight runs that
    /// carry no shape removed), kept only when it passes the exact check.
    pub fn smoothing(&self, levels: u32) -> crate::subdivision::Smoothing {
        let mut s = self.uniform_smoothing(levels);
        if s.levels == 0 || self.kind == CutKind::Wedge {
            return s;
        }
        let Some(chain) = s.chain.take() else {
            return s;
        };
        let t = crate::adaptive::path_parameters(&chain, s.levels);
        let tolerance = crate::adaptive::ADAPTIVE_TOLERANCE
            * crate::adaptive::cross_section(
                &self.planes.iter().map(|p| p.corners()).collect::<Vec<_>>(),
            );
        if let Some(adaptive) = crate::adaptive::drop_flat_rings(&s.mesh, &t, tolerance)
            && adaptive.faces.len() < s.mesh.faces.len()
            && csg::check_cutter(&adaptive.triangulate()).is_ok()
        {
            s.uniform_faces = s.mesh.faces.len();
            s.mesh = adaptive;
        }
        s
    }

    /// [`Cutter::smoothing`] without the adaptive step: every level everywhere. A curving or
    /// straight cutter's tight turns get planes inserted first
    /// ([`crate::subdivision::refine_path`]) when the box mesh they make passes the exact check.
    pub fn uniform_smoothing(&self, levels: u32) -> crate::subdivision::Smoothing {
        let q = self.quad_mesh();
        if self.smooth {
            let mut base = q;
            let mut inserted = 0;
            if self.kind != CutKind::Wedge {
                let corners: Vec<[DVec3; 4]> = self.planes.iter().map(|p| p.corners()).collect();
                let refined =
                    crate::subdivision::refine_path(&corners, crate::subdivision::ADAPTIVE_PASSES);
                if refined.len() > corners.len() {
                    let chain = Cutter {
                        kind: self.kind,
                        smooth: false,
                        levels: 0,
                        direction: self.direction,
                        planes: refined
                            .iter()
                            .map(|c| BoundedPlane::from_corners(*c))
                            .collect(),
                    }
                    .quad_mesh();
                    if csg::check_cutter(&chain.triangulate()).is_ok() {
                        inserted = refined.len() - corners.len();
                        base = chain;
                    }
                }
            }
            let roundness = match self.direction {
                CutDirection::View => VIEW_ROUNDNESS,
                CutDirection::Normal => 1.0,
            };
            let mut s = crate::subdivision::smooth_with(&base, levels, roundness);
            s.inserted = inserted;
            if self.kind != CutKind::Wedge {
                s.chain = Some(base);
            }
            s
        } else {
            crate::subdivision::Smoothing::none(q)
        }
    }

    /// Same as [`Cutter::surface`] (kept for callers that think of it as the triangle mesh).
    pub fn triangle_mesh(&self) -> csg::Mesh {
        self.surface()
    }

    /// [`Cutter::sanity_check`] plus the exact check the boolean makes of the surface it will
    /// cut with ([`csg::check_cutter`]: closed, oriented, positive, free of self-intersections
    /// with touching counted). The editor runs it on every edit it accepts, so a cutter the
    /// editor holds is always one the exact boolean takes.
    pub fn validate(&self) -> Result<(), CutterError> {
        self.validated_smoothing().map(|_| ())
    }

    /// [`Cutter::sanity_check`] plus the exact check of [`Cutter::validate`] on the box mesh
    /// alone (for a smooth cutter, before subdivision). Cheap enough for every pointer move of a
    /// drag. A smooth cutter that passes it passes [`Cutter::validate`] too: the smoothing keeps
    /// a level only once it is free of self-intersections, inserts planes in turns only when the
    /// box mesh they make passes the exact check, keeps the adaptive surface only when it passes
    /// it too, and otherwise keeps the boxes.
    pub fn validate_boxes(&self) -> Result<(), CutterError> {
        self.sanity_check()?;
        csg::check_cutter(&self.quad_mesh().triangulate()).map_err(|e| CutterError::Refused {
            reason: e.to_string(),
        })
    }

    /// [`Cutter::validate`], returning the smoothing it checked (what the repair gave up is in
    /// it, see [`crate::subdivision::Smoothing::note`]).
    pub fn validated_smoothing(&self) -> Result<crate::subdivision::Smoothing, CutterError> {
        self.sanity_check()?;
        let smoothing = self.smoothing(self.levels);
        // A level is kept only once `csg::cutter_self_intersections` (the same preparation and
        // predicate as `csg::check_cutter`) found nothing in it, so a subdivided mesh has passed
        // the exact check already; the boxes (no level kept) are checked here.
        if smoothing.levels == 0 {
            csg::check_cutter(&smoothing.mesh.triangulate()).map_err(|e| CutterError::Refused {
                reason: e.to_string(),
            })?;
        }
        Ok(smoothing)
    }

    fn box_faces(&self) -> QuadMesh {
        let n = self.planes.len() as u32;
        let positions = self.planes.iter().flat_map(|p| p.corners()).collect();
        // Vertex 4i + k: k = 0 front-top, 1 back-top, 2 back-bottom, 3 front-bottom of plane i.
        let v = |i: u32, k: u32| 4 * i + k;
        let mut faces = Vec::with_capacity(4 * n as usize + 2);
        faces.push(vec![v(0, 0), v(0, 1), v(0, 2), v(0, 3)]);
        for i in 0..n.saturating_sub(1) {
            let q = i + 1;
            faces.push(vec![v(i, 0), v(i, 3), v(q, 3), v(q, 0)]); // front
            faces.push(vec![v(i, 1), v(q, 1), v(q, 2), v(i, 2)]); // back
            faces.push(vec![v(i, 0), v(q, 0), v(q, 1), v(i, 1)]); // top
            faces.push(vec![v(i, 3), v(i, 2), v(q, 2), v(q, 3)]); // bottom
        }
        let l = n - 1;
        faces.push(vec![v(l, 0), v(l, 3), v(l, 2), v(l, 1)]);
        QuadMesh { positions, faces }
    }

    fn wedge_faces(&self) -> QuadMesh {
        let n = self.planes.len() as u32;
        let mut positions = vec![self.planes[0].front_top, self.planes[0].back_top];
        for p in &self.planes {
            positions.push(p.back_bottom);
            positions.push(p.front_bottom);
        }
        // 0 = shared front-top (axis front), 1 = shared back-top; plane i: 2 + 2i back-bottom,
        // 3 + 2i front-bottom.
        let bb = |i: u32| 2 + 2 * i;
        let fb = |i: u32| 3 + 2 * i;
        let mut faces = Vec::with_capacity(3 * n as usize + 2);
        faces.push(vec![0, 1, bb(0), fb(0)]);
        for i in 0..n.saturating_sub(1) {
            let q = i + 1;
            faces.push(vec![0, fb(i), fb(q)]); // front
            faces.push(vec![1, bb(q), bb(i)]); // back
            faces.push(vec![fb(i), bb(i), bb(q), fb(q)]); // bottom (outer rim)
        }
        let l = n - 1;
        faces.push(vec![0, fb(l), bb(l), 1]);
        QuadMesh { positions, faces }
    }

    /// The closed mesh of box `index` alone, oriented like the whole cutter's quad mesh.
    fn box_volume(&self, index: usize, orientation: f64) -> f64 {
        let c = Cutter {
            kind: self.kind,
            smooth: false,
            levels: 0,
            direction: self.direction,
            planes: self.planes[index..index + 2].to_vec(),
        };
        let m = if c.kind == CutKind::Wedge {
            c.wedge_faces()
        } else {
            c.box_faces()
        };
        m.volume() * orientation
    }

    /// Checks every invariant written on [`Cutter::planes`] plus the mesh: closed, outward, every
    /// box positively oriented, no self-intersection. Called after every edit in tests and by the
    /// editor before it accepts an edit.
    pub fn sanity_check(&self) -> Result<(), CutterError> {
        let Cutter {
            kind,
            smooth: _,
            levels: _,
            direction: _,
            planes,
        } = self;
        if planes.len() < 2 {
            return Err(CutterError::TooFewPlanes {
                count: planes.len(),
            });
        }
        for (i, p) in planes.iter().enumerate() {
            if !p.is_finite() {
                return Err(CutterError::NonFinite { plane: i });
            }
            let (front_length, depth) = (p.front_length(), p.depth());
            if front_length <= 0.0 || depth <= 0.0 {
                return Err(CutterError::Degenerate {
                    plane: i,
                    front_length,
                    depth,
                });
            }
            let error = p.planarity_error();
            if error > PLANARITY_TOL {
                return Err(CutterError::NotPlanar { plane: i, error });
            }
            if *kind == CutKind::Wedge
                && (p.front_top != planes[0].front_top || p.back_top != planes[0].back_top)
            {
                return Err(CutterError::WedgeAxisNotShared { plane: i });
            }
        }
        let mesh = self.quad_mesh();
        mesh.check_closed()
            .map_err(|(a, b)| CutterError::NotClosed { a, b })?;
        let orientation = if self.box_faces_orientation_flipped(&mesh) {
            -1.0
        } else {
            1.0
        };
        for i in 0..planes.len() - 1 {
            let volume = self.box_volume(i, orientation);
            if volume <= 0.0 {
                return Err(CutterError::InvertedBox { index: i, volume });
            }
        }
        if *kind == CutKind::Wedge {
            let degrees = self.wedge_sweep().to_degrees();
            if degrees >= 359.0 {
                return Err(CutterError::WedgeOverlaps { degrees });
            }
        } else {
            for i in 0..planes.len() - 1 {
                if geom::quad_quad_intersect(&planes[i].corners(), &planes[i + 1].corners()) {
                    return Err(CutterError::ConsecutivePlanesCross { plane: i });
                }
            }
        }
        if let Some((face_a, face_b)) = self_intersection(&mesh) {
            return Err(CutterError::SelfIntersecting { face_a, face_b });
        }
        Ok(())
    }

    /// True when [`Cutter::quad_mesh`] had to reverse the construction order of the faces.
    fn box_faces_orientation_flipped(&self, oriented: &QuadMesh) -> bool {
        // The first face is always plane 0's end cap; compare its first two vertices' order.
        let raw = if self.kind == CutKind::Wedge {
            self.wedge_faces()
        } else {
            self.box_faces()
        };
        raw.faces[0] != oriented.faces[0]
    }

    /// Total angle swept by a wedge's front edges around the shared axis (radians).
    pub fn wedge_sweep(&self) -> f64 {
        let a = self.planes[0].front_top;
        let mut total = 0.0;
        for w in self.planes.windows(2) {
            let u = w[0].front_bottom - a;
            let v = w[1].front_bottom - a;
            total += u.angle_between(v);
        }
        total
    }

    /// Front-edge midpoints of all planes (the extrusion path on the surface).
    pub fn path(&self) -> Vec<DVec3> {
        self.planes.iter().map(|p| p.front_mid()).collect()
    }
}

/// First pair of faces that share no vertex and intersect (faces fan-triangulated), if any.
fn self_intersection(mesh: &QuadMesh) -> Option<(usize, usize)> {
    struct Tri {
        face: usize,
        v: [u32; 3],
        p: [DVec3; 3],
        lo: DVec3,
        hi: DVec3,
    }
    let mut tris = Vec::new();
    for (fi, f) in mesh.faces.iter().enumerate() {
        for k in 1..f.len() - 1 {
            let v = [f[0], f[k], f[k + 1]];
            let p = v.map(|i| mesh.positions[i as usize]);
            tris.push(Tri {
                face: fi,
                v,
                p,
                lo: p[0].min(p[1]).min(p[2]),
                hi: p[0].max(p[1]).max(p[2]),
            });
        }
    }
    tris.sort_by(|a, b| a.lo.x.total_cmp(&b.lo.x));
    for i in 0..tris.len() {
        let a = &tris[i];
        for b in &tris[i + 1..] {
            if b.lo.x > a.hi.x {
                break;
            }
            if b.lo.y > a.hi.y || a.lo.y > b.hi.y || b.lo.z > a.hi.z || a.lo.z > b.hi.z {
                continue;
            }
            if a.face == b.face || a.v.iter().any(|x| b.v.contains(x)) {
                continue;
            }
            if geom::tri_tri_intersect(&a.p, &b.p) {
                return Some((a.face.min(b.face), a.face.max(b.face)));
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A straight cutter along +X: front edge along Z at y = 0, back toward +Y.
    pub(crate) fn straight(n: usize) -> Cutter {
        let planes = (0..n)
            .map(|i| {
                let x = i as f64;
                BoundedPlane::from_front_edge(
                    DVec3::new(x, 0.0, 1.0),
                    DVec3::new(x, 0.0, -1.0),
                    DVec3::Y,
                    0.5,
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
    fn straight_cutter_is_valid_box() {
        let c = straight(4);
        c.sanity_check().unwrap();
        let m = c.quad_mesh();
        assert_eq!(m.faces.len(), 4 * 3 + 2);
        assert!((m.volume() - 3.0 * 2.0 * 0.5).abs() < 1e-12);
        assert!(m.faces.iter().all(|f| f.len() == 4));
    }

    #[test]
    fn reversed_planes_still_outward() {
        let mut c = straight(3);
        c.planes.reverse();
        c.sanity_check().unwrap();
        assert!(c.quad_mesh().volume() > 0.0);
    }

    #[test]
    fn crossing_planes_are_rejected() {
        let mut c = straight(3);
        // Tilt plane 1's back edge far beyond plane 2.
        c.planes[1] = c.planes[1].rotated_about_front_edge(-1.4).with_depth(5.0);
        assert!(c.sanity_check().is_err());
    }

    #[test]
    fn one_plane_is_too_few() {
        let mut c = straight(2);
        c.planes.pop();
        assert_eq!(
            c.sanity_check(),
            Err(CutterError::TooFewPlanes { count: 1 })
        );
    }

    #[test]
    fn wedge_is_closed_prism_fan() {
        let a = DVec3::new(0.0, 0.0, 0.0);
        let planes = (0..4)
            .map(|i| {
                let ang = i as f64 * 0.3;
                let fb = DVec3::new(ang.cos(), 0.0, ang.sin()) * 3.0;
                BoundedPlane::from_front_edge(a, fb, DVec3::Y, 1.0)
            })
            .collect();
        let c = Cutter {
            kind: CutKind::Wedge,
            smooth: false,
            levels: crate::subdivision::DEFAULT_LEVELS,
            direction: crate::cutter::CutDirection::Normal,
            planes,
        };
        c.sanity_check().unwrap();
        let m = c.quad_mesh();
        assert!(m.volume() > 0.0);
        assert!(m.faces.iter().any(|f| f.len() == 3));
    }
}
