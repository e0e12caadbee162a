//! Interpolatory subdivision of a closed quad mesh (the rounded and freeform cuts, thesis 3.3.2.4).
//!
//! The thesis uses Kobbelt's interpolatory scheme for quadrilateral meshes. This is a variant of
//! it with the same structure and the two properties the editor relies on:
//!
//! - **interpolation**: every original vertex stays where it is, so dragging a plane's vertex
//!   still controls the smooth cutter;
//! - **closedness**: each level splits an `n`-gon into `n` quads around a face point, with one new
//!   point per edge shared by both faces of the edge, so a closed mesh stays closed and oriented.
//!
//! Edge points use the four-point rule `(−p₋₁ + 9p₀ + 9p₁ − p₂) / 16` along the edge. At a vertex
//! of valence 4 the outer neighbour `p₋₁` is the vertex opposite the edge (the neighbour sharing
//! no face with it), exactly as in Kobbelt's regular case. At a vertex of valence 3 (the corners
//! of a box chain's end planes and of a wedge's end planes) it is Kobbelt's virtual point, the
//! centroid of the three neighbours: it lies inside the corner, so the end cap is rounded the way
//! the sides are (its rim bulges out of the end plane's rectangle and the cap domes out past the
//! end plane, meeting the sides without a crease) instead of staying a flat end joined to the
//! rounded sides by a sharp, linear rim. At higher valences (a wedge's axis vertices, which stay
//! the sharp edge the wedge opens along) the outer neighbour is the reflection `2p₀ − p₁`, a
//! locally linear rule. Face points are the Boolean sum of the edge points,
//! `(2/n)·Σ edge points − (1/n)·Σ corners`, which reproduces the centre of any bilinear face.
//!
//! ## Never folding
//!
//! The four-point rule overshoots: on the inside of a tight turn the new points of neighbouring
//! boxes can cross, and a smooth cutter that intersects itself is refused by the exact boolean.
//! So [`smooth`] checks every level with `csg`'s exact self-intersection test
//! ([`csg::cutter_self_intersections`], the predicates the cut uses) and repairs it in place: each
//! new point is its linear position (edge midpoint, face centroid) plus a weight times its
//! smoothing displacement, and the weights of the new points around every intersecting pair are
//! halved, then zeroed, until the level is clean. A level whose linear refinement still
//! intersects itself is not applied. The result is therefore free of self-intersections whenever
//! the box mesh is, and [`Smoothing`] says how much smoothing had to be given up, so the editor
//! can tell the user.
//!
//! ## Adaptive along the path
//!
//! A uniform level count is too coarse in a tight turn and wasteful on a straight run. Before the
//! uniform levels, [`refine_path`] inserts planes between consecutive planes that turn by more
//! than [`ADAPTIVE_TURN_DEG`], by the same four-point rule applied to the corner curves (so the
//! result is what more levels would give there), up to [`ADAPTIVE_PASSES`] times: a sharp turn
//! gets up to four times the boxes, a straight run none.

use std::collections::HashMap;

use glam::DVec3;

use crate::quad_mesh::QuadMesh;

/// Subdivision levels of a smooth cutter unless told otherwise: each level splits every quad in
/// four, so two levels draw a box side as 16 quads.
pub const DEFAULT_LEVELS: u32 = 2;

/// The most levels [`smooth`] applies (each multiplies the face count by four).
pub const MAX_LEVELS: u32 = 4;

/// Consecutive planes whose normals differ by more than this get a plane inserted between them
/// by [`refine_path`].
pub const ADAPTIVE_TURN_DEG: f64 = 20.0;

/// Rounds of [`refine_path`] (each can halve a turn).
pub const ADAPTIVE_PASSES: u32 = 2;

/// Halvings of a damped weight before it is set to zero.
const HALVINGS: u32 = 3;

/// Intersecting pairs looked at per repair round.
const PAIRS_PER_ROUND: usize = 4096;

/// `levels` rounds of interpolatory subdivision of a closed, outward polygon mesh, unchecked (it
/// may fold; see [`smooth`]). Level 0 returns a copy. The output is all quads.
pub fn subdivide(mesh: &QuadMesh, levels: u32) -> QuadMesh {
    let mut m = mesh.clone();
    for _ in 0..levels {
        m = refine(&m).with_weights(&[]);
    }
    m
}

/// `levels` rounds of the same refinement with every new point at its linear position (edge
/// midpoints, face centroids): the same faces and vertex numbering as [`subdivide`], used to
/// carry a quantity (such as the path parameter of [`crate::adaptive`]) through the levels.
pub fn subdivide_linear(mesh: &QuadMesh, levels: u32) -> QuadMesh {
    let mut m = mesh.clone();
    for _ in 0..levels {
        let r = refine(&m);
        m = r.with_weights(&vec![0.0; r.linear.len()]);
    }
    m
}

/// A smooth cutter mesh and what its repair gave up (see the module doc).
#[derive(Clone, Debug, PartialEq)]
pub struct Smoothing {
    /// The subdivided mesh, all quads (the input itself when no level could be applied).
    pub mesh: QuadMesh,
    /// Levels asked for (at most [`MAX_LEVELS`]; 0 for a cutter that is not smooth).
    pub asked: u32,
    /// Levels applied (at most `asked`).
    pub levels: u32,
    /// Planes [`refine_path`] inserted before the levels (tight turns).
    pub inserted: usize,
    /// New points whose smoothing displacement was reduced to stay free of self-intersections.
    pub damped: usize,
    /// Faces the uniform subdivision had when [`crate::Cutter::smoothing`] made `mesh` adaptive
    /// (fewer faces where the path runs straight, [`crate::adaptive`]); 0 when it did not.
    pub uniform_faces: usize,
    /// The box chain that was subdivided (planes inserted in turns included), for the adaptive
    /// step; `None` for a wedge and when nothing was subdivided.
    pub chain: Option<QuadMesh>,
}

impl Smoothing {
    /// No smoothing: `mesh` as it is.
    pub fn none(mesh: QuadMesh) -> Smoothing {
        Smoothing {
            mesh,
            asked: 0,
            levels: 0,
            inserted: 0,
            damped: 0,
            uniform_faces: 0,
            chain: None,
        }
    }

    /// A one-line note for the status bar when smoothing was reduced, else `None`.
    pub fn note(&self) -> Option<String> {
        let asked = self.asked;
        if self.levels < asked {
            Some(format!(
                "smooth cutter: {} of {asked} subdivision levels kept (more would make it intersect itself)",
                self.levels
            ))
        } else if self.damped > 0 {
            Some(format!(
                "smooth cutter: rounding reduced at {} points where it would fold",
                self.damped
            ))
        } else {
            None
        }
    }
}

/// Up to `levels` (at most [`MAX_LEVELS`]) levels of interpolatory subdivision, each repaired so
/// that the mesh never intersects itself (see the module doc). `mesh` must be closed and outward.
pub fn smooth(mesh: &QuadMesh, levels: u32) -> Smoothing {
    smooth_with(mesh, levels, 1.0)
}

/// [`smooth`] with every new point's smoothing displacement scaled by `roundness` (0 to 1) before
/// any repair: the four-point rule with `roundness` times its tension (still C¹ for any
/// roundness in (0, 1]), the rounding of a cutter that must not bulge far past its boxes
/// ([`crate::cutter::VIEW_ROUNDNESS`]). `smooth` is `roundness` 1.
pub fn smooth_with(mesh: &QuadMesh, levels: u32, roundness: f64) -> Smoothing {
    let mut out = Smoothing {
        asked: levels.min(MAX_LEVELS),
        ..Smoothing::none(mesh.clone())
    };
    for _ in 0..levels.min(MAX_LEVELS) {
        let step = refine(&out.mesh);
        match step.repaired(roundness) {
            Some((mesh, damped)) => {
                out.mesh = mesh;
                out.levels += 1;
                out.damped += damped;
            }
            None => break,
        }
    }
    out
}

/// The corner quads of a box chain (front-top, back-top, back-bottom, front-bottom each) with
/// planes inserted where consecutive planes turn by more than [`ADAPTIVE_TURN_DEG`] (see the
/// module doc), `passes` times at most. Every input plane is kept, in order. The new quads are
/// not exactly planar; the caller checks the box mesh they make before using it.
pub fn refine_path(planes: &[[DVec3; 4]], passes: u32) -> Vec<[DVec3; 4]> {
    let mut planes = planes.to_vec();
    let threshold = ADAPTIVE_TURN_DEG.to_radians();
    for _ in 0..passes {
        let n = planes.len();
        if n < 2 {
            break;
        }
        // The cross product of the diagonals: the quad's normal, planar or not.
        let normal = |q: &[DVec3; 4]| (q[2] - q[0]).cross(q[3] - q[1]).normalize_or_zero();
        let at = |i: isize| -> [DVec3; 4] {
            if i < 0 {
                std::array::from_fn(|k| planes[0][k] * 2.0 - planes[1][k])
            } else if i as usize >= n {
                std::array::from_fn(|k| planes[n - 1][k] * 2.0 - planes[n - 2][k])
            } else {
                planes[i as usize]
            }
        };
        let mut out = Vec::with_capacity(2 * n);
        let mut inserted = false;
        for i in 0..n {
            out.push(planes[i]);
            if i + 1 == n {
                break;
            }
            if normal(&planes[i]).angle_between(normal(&planes[i + 1])) > threshold {
                let (a, b, c, d) = (
                    at(i as isize - 1),
                    at(i as isize),
                    at(i as isize + 1),
                    at(i as isize + 2),
                );
                out.push(std::array::from_fn(|k| {
                    (-a[k] + b[k] * 9.0 + c[k] * 9.0 - d[k]) / 16.0
                }));
                inserted = true;
            }
        }
        planes = out;
        if !inserted {
            break;
        }
    }
    planes
}

/// One level of subdivision before its new points are placed: the refined faces, every point's
/// linear position and the displacement the smoothing rule adds to it (zero for the old points).
struct Refinement {
    faces: Vec<Vec<u32>>,
    linear: Vec<DVec3>,
    displacement: Vec<DVec3>,
    /// Points `< first_new` are the coarse mesh's vertices (they never move).
    first_new: usize,
}

impl Refinement {
    /// The mesh with each new point at `linear + weight · displacement` (weight 1 where
    /// `weights` is shorter).
    fn with_weights(&self, weights: &[f64]) -> QuadMesh {
        let positions = self
            .linear
            .iter()
            .zip(&self.displacement)
            .enumerate()
            .map(|(i, (&l, &d))| l + d * weights.get(i).copied().unwrap_or(1.0))
            .collect();
        QuadMesh {
            positions,
            faces: self.faces.clone(),
        }
    }

    /// The refined mesh with as much smoothing (at most `roundness` of it) as keeps it free of
    /// self-intersections, and the number of new points damped; `None` when even the linear
    /// refinement intersects itself.
    fn repaired(&self, roundness: f64) -> Option<(QuadMesh, usize)> {
        let n = self.linear.len();
        let mut weights = vec![roundness; n];
        let mut halvings = vec![0u32; n];
        let mut vertex_faces: Vec<Vec<u32>> = vec![Vec::new(); n];
        for (fi, f) in self.faces.iter().enumerate() {
            for &v in f {
                vertex_faces[v as usize].push(fi as u32);
            }
        }
        // Triangle -> face of the fan triangulation (QuadMesh::triangulate).
        let tri_face: Vec<u32> = self
            .faces
            .iter()
            .enumerate()
            .flat_map(|(fi, f)| std::iter::repeat_n(fi as u32, f.len().saturating_sub(2)))
            .collect();
        for _ in 0..=HALVINGS + 1 {
            let mesh = self.with_weights(&weights);
            let pairs = match csg::cutter_self_intersections(&mesh.triangulate(), PAIRS_PER_ROUND) {
                Ok(pairs) => pairs,
                Err(_) => break,
            };
            if pairs.is_empty() {
                let damped = weights.iter().filter(|&&w| w < roundness).count();
                return Some((mesh, damped));
            }
            // Damp every new point of the faces around the offending triangles' corners.
            let mut marked = vec![false; n];
            for (a, b) in pairs {
                for t in [a, b] {
                    let face = &self.faces[tri_face[t] as usize];
                    for &v in face {
                        for &g in &vertex_faces[v as usize] {
                            for &u in &self.faces[g as usize] {
                                if u as usize >= self.first_new {
                                    marked[u as usize] = true;
                                }
                            }
                        }
                    }
                }
            }
            for (i, m) in marked.into_iter().enumerate() {
                if m {
                    halvings[i] += 1;
                    weights[i] = if halvings[i] > HALVINGS {
                        0.0
                    } else {
                        weights[i] * 0.5
                    };
                }
            }
        }
        // Last resort: the linear refinement of the whole level.
        let linear = self.with_weights(&vec![0.0; n]);
        match csg::cutter_self_intersections(&linear.triangulate(), 1) {
            Ok(pairs) if pairs.is_empty() => Some((linear, n - self.first_new)),
            _ => None,
        }
    }
}

fn refine(mesh: &QuadMesh) -> Refinement {
    let nv = mesh.positions.len();
    // Neighbours of each vertex, and the faces around each undirected edge.
    let mut neighbours: Vec<Vec<u32>> = vec![Vec::new(); nv];
    let mut edge_faces: HashMap<(u32, u32), Vec<usize>> = HashMap::new();
    for (fi, f) in mesh.faces.iter().enumerate() {
        for k in 0..f.len() {
            let a = f[k];
            let b = f[(k + 1) % f.len()];
            if !neighbours[a as usize].contains(&b) {
                neighbours[a as usize].push(b);
            }
            if !neighbours[b as usize].contains(&a) {
                neighbours[b as usize].push(a);
            }
            edge_faces.entry(key(a, b)).or_default().push(fi);
        }
    }
    let p = &mesh.positions;
    // The point across `v` from neighbour `w`: the opposite vertex (valence 4), Kobbelt's
    // virtual point (valence 3, the end-cap corners), else the reflection of `w` about `v`.
    let outer = |v: u32, w: u32| -> DVec3 {
        let ns = &neighbours[v as usize];
        if ns.len() == 3 {
            return virtual_point(ns.iter().map(|&q| p[q as usize]));
        }
        if ns.len() == 4 {
            let faces = edge_faces.get(&key(v, w)).map(Vec::as_slice).unwrap_or(&[]);
            let shares_face = |x: u32| faces.iter().any(|&fi| mesh.faces[fi].contains(&x));
            let opposite: Vec<u32> = ns
                .iter()
                .copied()
                .filter(|&x| x != w && !shares_face(x))
                .collect();
            if let [o] = opposite[..] {
                return p[o as usize];
            }
        }
        p[v as usize] * 2.0 - p[w as usize]
    };
    let mut linear = p.clone();
    let mut displacement = vec![DVec3::ZERO; nv];
    let mut edge_point: HashMap<(u32, u32), u32> = HashMap::new();
    let mut edges: Vec<(u32, u32)> = edge_faces.keys().copied().collect();
    edges.sort_unstable();
    for (a, b) in edges {
        let (pa, pb) = (p[a as usize], p[b as usize]);
        let mid = (pa + pb) * 0.5;
        let q = (-outer(a, b) + pa * 9.0 + pb * 9.0 - outer(b, a)) / 16.0;
        edge_point.insert((a, b), linear.len() as u32);
        linear.push(mid);
        displacement.push(q - mid);
    }
    let mut faces = Vec::with_capacity(mesh.faces.len() * 4);
    for f in &mesh.faces {
        let n = f.len();
        let e: Vec<u32> = (0..n)
            .map(|k| edge_point[&key(f[k], f[(k + 1) % n])])
            .collect();
        // Face point: the Boolean sum (2/n)·Σ edge points − (1/n)·Σ corners, whose linear part
        // is the centroid of the corners.
        let sum_v: DVec3 = f.iter().map(|&i| p[i as usize]).sum();
        let sum_d: DVec3 = e.iter().map(|&i| displacement[i as usize]).sum();
        let c = linear.len() as u32;
        linear.push(sum_v / n as f64);
        displacement.push(sum_d * (2.0 / n as f64));
        for k in 0..n {
            let prev = e[(k + n - 1) % n];
            faces.push(vec![f[k], e[k], c, prev]);
        }
    }
    Refinement {
        faces,
        linear,
        displacement,
        first_new: nv,
    }
}

/// Kobbelt's virtual point across a vertex of valence 3 from any of its neighbours
/// `q₀, q₁, q₂`: `(4/n)·Σ qⱼ − qᵢ₋₁ − qᵢ − qᵢ₊₁`, which for `n = 3` is the neighbours' centroid
/// (for `n = 4` the same formula gives the opposite vertex). It lies inside the corner, so the
/// four-point rule pushes the new points near the corner outward: the corner and the end cap
/// around it are rounded like the rest of the surface instead of staying a flat, sharp-edged end.
fn virtual_point(neighbours: impl Iterator<Item = DVec3>) -> DVec3 {
    let (sum, n) = neighbours.fold((DVec3::ZERO, 0.0), |(s, n), q| (s + q, n + 1.0));
    sum / n
}

fn key(a: u32, b: u32) -> (u32, u32) {
    if a < b { (a, b) } else { (b, a) }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cutter::{CutKind, Cutter};
    use crate::plane::BoundedPlane;

    #[test]
    fn subdivided_box_chain_interpolates_and_stays_closed() {
        let planes = (0..4)
            .map(|i| {
                let x = i as f64;
                BoundedPlane::from_front_edge(
                    DVec3::new(x, 0.1 * x * x, 1.0),
                    DVec3::new(x, 0.1 * x * x, -1.0),
                    DVec3::Y,
                    0.7,
                )
            })
            .collect();
        let c = Cutter {
            kind: CutKind::Curving,
            smooth: false,
            levels: crate::subdivision::DEFAULT_LEVELS,
            direction: crate::cutter::CutDirection::Normal,
            planes,
        };
        let q = c.quad_mesh();
        let s = subdivide(&q, 2);
        s.check_closed().unwrap();
        assert_eq!(s.faces.len(), q.faces.len() * 16);
        assert_eq!(&s.positions[..q.positions.len()], &q.positions[..]);
        assert!(s.volume() > 0.0);
        // Smoothing moves the faces: the volume changes but stays comparable.
        assert!((s.volume() / q.volume() - 1.0).abs() < 0.5);
    }

    /// Planes fanned half a turn around the z axis, their inner edges `inner` from it: the
    /// inside of the turn is tight, where the four-point rule overshoots.
    fn tight_turn(inner: f64, step_deg: f64, count: usize) -> Cutter {
        let planes = (0..count)
            .map(|i| {
                let a = (i as f64 * step_deg).to_radians();
                let radial = DVec3::new(a.cos(), a.sin(), 0.0);
                BoundedPlane::from_front_edge(
                    radial * inner,
                    radial * (inner + 2.0),
                    DVec3::NEG_Z,
                    1.0,
                )
            })
            .collect();
        Cutter {
            kind: CutKind::Curving,
            smooth: true,
            levels: crate::subdivision::DEFAULT_LEVELS,
            direction: crate::cutter::CutDirection::Normal,
            planes,
        }
    }

    #[test]
    fn smoothing_of_a_tight_turn_is_repaired_not_folded() {
        let c = tight_turn(0.05, 40.0, 6);
        c.sanity_check().unwrap();
        let boxes = c.quad_mesh();
        csg::check_cutter(&boxes.triangulate()).unwrap();
        let raw = subdivide(&boxes, 2).triangulate();
        assert!(
            csg::check_cutter(&raw).is_err(),
            "the fixture must fold when subdivided without repair"
        );
        let s = smooth(&boxes, 2);
        csg::check_cutter(&s.mesh.triangulate()).unwrap();
        s.mesh.check_closed().unwrap();
        assert_eq!(s.asked, 2);
        assert!(s.levels >= 1, "{s:?}");
        // Interpolating: the planes' corners are still there.
        assert_eq!(
            &s.mesh.positions[..boxes.positions.len()],
            &boxes.positions[..]
        );
        // The repair had to give something up, and says so.
        assert!(s.damped > 0 || s.levels < 2, "{s:?}");
        assert!(s.note().is_some());
        c.validate().unwrap();
    }

    #[test]
    fn repair_keeps_every_gentle_turn_fully_smooth() {
        for inner in [0.5, 1.0, 3.0] {
            let c = tight_turn(inner, 15.0, 6);
            let s = smooth(&c.quad_mesh(), 2);
            assert_eq!((s.levels, s.damped), (2, 0), "inner {inner}");
            assert_eq!(s.note(), None);
            assert_eq!(s.mesh, subdivide(&c.quad_mesh(), 2));
        }
    }

    #[test]
    fn path_refinement_only_where_it_turns() {
        let straight: Vec<[DVec3; 4]> = tight_turn(1.0, 0.0, 4)
            .planes
            .iter()
            .enumerate()
            .map(|(i, p)| p.corners().map(|c| c + DVec3::Y * i as f64))
            .collect();
        assert_eq!(refine_path(&straight, 2), straight);
        let turn: Vec<[DVec3; 4]> = tight_turn(1.0, 45.0, 4)
            .planes
            .iter()
            .map(|p| p.corners())
            .collect();
        let refined = refine_path(&turn, 2);
        // 45° turns: one pass about halves them (still above 20°), the second again.
        assert!(refined.len() >= 2 * 4 - 1 + 3, "{}", refined.len());
        assert!(refined.len() <= 3 * 4 + 1, "{}", refined.len());
        // Every input plane is kept, in order.
        let mut at = 0;
        for p in &turn {
            at += refined[at..]
                .iter()
                .position(|q| q == p)
                .expect("input plane kept");
        }
        assert_eq!(refine_path(&turn, 0), turn);
        // The inserted planes lie on the turn (the corners' distance from the axis is kept
        // within the four-point rule's overshoot).
        for q in &refined {
            let r = q[0].truncate().length();
            assert!((0.95..1.1).contains(&r), "{r}");
        }
    }

    /// The largest angle (degrees) between the normals of two faces sharing an edge.
    fn largest_crease(m: &QuadMesh) -> f64 {
        let normal = |f: &Vec<u32>| {
            let q = |k: usize| m.positions[f[k % f.len()] as usize];
            (q(2) - q(0)).cross(q(3) - q(1)).normalize()
        };
        let mut by_edge: HashMap<(u32, u32), Vec<DVec3>> = HashMap::new();
        for f in &m.faces {
            for k in 0..f.len() {
                by_edge
                    .entry(key(f[k], f[(k + 1) % f.len()]))
                    .or_default()
                    .push(normal(f));
            }
        }
        by_edge
            .values()
            .map(|n| n[0].angle_between(n[1]).to_degrees())
            .fold(0.0, f64::max)
    }

    /// A straight chain of `count` unit cubes along +x (front edge along z, depth along y).
    fn cube_chain(count: usize) -> Cutter {
        let planes = (0..=count)
            .map(|i| {
                let x = i as f64;
                BoundedPlane::from_front_edge(
                    DVec3::new(x, 0.0, 1.0),
                    DVec3::new(x, 0.0, 0.0),
                    DVec3::Y,
                    1.0,
                )
            })
            .collect();
        Cutter {
            kind: CutKind::Curving,
            smooth: true,
            levels: crate::subdivision::DEFAULT_LEVELS,
            direction: crate::cutter::CutDirection::Normal,
            planes,
        }
    }

    #[test]
    fn end_caps_are_rounded_like_the_sides() {
        let c = cube_chain(4);
        let boxes = c.quad_mesh();
        let s = smooth(&boxes, 3);
        assert_eq!((s.levels, s.damped), (3, 0), "{s:?}");
        s.mesh.check_closed().unwrap();
        csg::check_cutter(&s.mesh.triangulate()).unwrap();
        // Interpolating: the end planes' corners are still there.
        assert_eq!(
            &s.mesh.positions[..boxes.positions.len()],
            &boxes.positions[..]
        );
        // The end caps are domes beyond the end planes (x = 0 and x = 4), not flat squares:
        // their middle bulges out by a visible fraction of the cube, the rest of the cap too.
        let lo = s
            .mesh
            .positions
            .iter()
            .map(|p| p.x)
            .fold(f64::MAX, f64::min);
        let hi = s
            .mesh
            .positions
            .iter()
            .map(|p| p.x)
            .fold(f64::MIN, f64::max);
        assert!(lo < -0.05 && hi > 4.05, "ends at {lo} and {hi}");
        // Rounded all round: a flat cap meets the sides along a 90° crease; rounded, the
        // sharpest crease left is next to the interpolated corners (48° after three levels,
        // where the middle's sharpest is 27°).
        let crease = largest_crease(&s.mesh);
        assert!(crease < 55.0, "largest crease {crease:.1}°");
        // The end's outline is rounded like the middle's cross-section: the cap (everything at
        // or beyond the end plane) bulges out of the unit square the boxes have there, as the
        // middle plane's cross-section does.
        let bulge = |inside: &dyn Fn(f64) -> bool| {
            s.mesh
                .positions
                .iter()
                .filter(|p| inside(p.x))
                .map(|p| (p.y - 0.5).abs().max((p.z - 0.5).abs()))
                .fold(0.0, f64::max)
        };
        let end = bulge(&|x| x <= 1e-9);
        let middle = bulge(&|x| (x - 2.0).abs() < 1e-9);
        assert!(end > 0.52 && middle > 0.52, "{end} {middle}");
    }

    #[test]
    fn rounded_ends_of_thin_and_tight_cutters_stay_valid() {
        // Thin slabs, long boxes and a tight turn: the rounded ends never fold.
        for (front, depth, step) in [(0.05, 2.0, 1.0), (2.0, 0.05, 1.0), (1.0, 1.0, 8.0)] {
            let planes = (0..4)
                .map(|i| {
                    let x = i as f64 * step;
                    BoundedPlane::from_front_edge(
                        DVec3::new(x, 0.0, front),
                        DVec3::new(x, 0.0, 0.0),
                        DVec3::Y,
                        depth,
                    )
                })
                .collect();
            let c = Cutter {
                kind: CutKind::Curving,
                smooth: true,
                levels: crate::subdivision::DEFAULT_LEVELS,
                direction: crate::cutter::CutDirection::Normal,
                planes,
            };
            c.validate().unwrap();
            let s = smooth(&c.quad_mesh(), 3);
            csg::check_cutter(&s.mesh.triangulate()).unwrap();
        }
        let c = tight_turn(0.05, 40.0, 6);
        c.validate().unwrap();
    }

    #[test]
    fn flat_grid_stays_flat() {
        // A unit cube: every new point of a face stays on the cube's bounding box.
        let c = Cutter {
            kind: CutKind::Curving,
            smooth: false,
            levels: crate::subdivision::DEFAULT_LEVELS,
            direction: crate::cutter::CutDirection::Normal,
            planes: vec![
                BoundedPlane::from_front_edge(DVec3::new(0., 0., 1.), DVec3::ZERO, DVec3::Y, 1.0),
                BoundedPlane::from_front_edge(DVec3::new(1., 0., 1.), DVec3::X, DVec3::Y, 1.0),
            ],
        };
        let s = subdivide(&c.quad_mesh(), 1);
        s.check_closed().unwrap();
        for p in &s.positions {
            assert!(
                p.cmpge(DVec3::splat(-0.2)).all() && p.cmple(DVec3::splat(1.2)).all(),
                "{p}"
            );
        }
    }
}
