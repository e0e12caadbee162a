//! Stage 6 of the boolean: everything that does not need the flood fill, assembled while it
//! runs: the new vertices placed, the kept pieces (welded by rounded position), the removed
//! pieces of split faces, the walls and the contours.

use glam::DVec3;
use rayon::prelude::*;

use super::error::CutError;
use super::faces::{CutterFaceWalls, TargetFace};
use super::inputs::{CutInputs, PARALLEL_MIN};
use crate::contour;
use crate::exact::{self, HPoint, LPoint};
use crate::intersect::{FxMap, PointKey};
use crate::output::{
    CutOptions, CutStats, PartBuilder, PositionBits, Provenance, Removed, position_bits,
};
use crate::phases::Phases;
use crate::split::{OUT, Vx};

/// What stage 6 gives back.
pub(crate) struct Output {
    pub new_positions: Vec<DVec3>,
    pub kept_new_faces: Vec<[u32; 3]>,
    pub kept_new_provenance: Vec<u32>,
    /// The removed pieces of split faces (the whole faces come from the flood fill).
    pub removed: Removed,
    pub walls: crate::output::Part,
    pub walls_solid: Vec<u32>,
    pub contours: Vec<crate::output::Contour>,
    /// The cutter-face counters.
    pub stats: CutStats,
    pub phases: Phases,
}

/// Assembles the output from the split `faces` and the cutter faces' walls; with
/// [`CutOptions::merge_coincident`], new vertices that round to the same position are welded.
pub(crate) fn assemble(
    cut: &CutInputs,
    faces: &[TargetFace],
    split_cutter: Vec<CutterFaceWalls>,
    options: &CutOptions,
) -> Result<Output, CutError> {
    let merge = options.merge_coincident;
    let (target, cutter, isect) = (cut.target, cut.cutter, cut.isect);
    let mesh = &target.mesh;
    let nt = mesh.positions.len() as u32;
    let mut sub = Phases::new(options.time_phases);
    let mut stats = CutStats::default();
    // A new vertex whose exact limit is the lattice point of one of its defining input
    // vertices (degenerate contact at a vertex) takes that vertex's exact input position, so
    // that it welds with it; otherwise it is its exact value rounded once.
    let place = |(h, key): (&HPoint, &PointKey)| -> DVec3 {
        if let Some(l) = may_be_lattice_point(h)
            .then(|| h.limit_lattice_point())
            .flatten()
        {
            let (tv, cv): (Vec<u32>, Vec<u32>) = match *key {
                PointKey::Ef { edge, face } => (
                    target.adjacency.edges[edge as usize].to_vec(),
                    cutter.triangles[face as usize].to_vec(),
                ),
                PointKey::Fe { edge, face } => (
                    mesh.triangles[face as usize].to_vec(),
                    cutter.edges[edge as usize].to_vec(),
                ),
            };
            if let Some(&v) = tv.iter().find(|&&v| target.lpoints[v as usize] == l) {
                return mesh.positions[v as usize];
            }
            if let Some(&v) = cv.iter().find(|&&v| cutter.lpoints[v as usize] == l) {
                return cutter.positions[v as usize];
            }
        }
        // Otherwise place it on the target's original geometry: on the original target edge
        // (EF) or inside the original target face (FE), with the parameters computed on the
        // lattice. Kept and removed then tile each target face up to f64 rounding.
        let l = h.limit();
        match *key {
            PointKey::Ef { edge, .. } => {
                let [p, q] = target.adjacency.edges[edge as usize];
                let (lp, lq) = (&target.lpoints[p as usize], &target.lpoints[q as usize]);
                let d: [f64; 3] = std::array::from_fn(|k| (lq[k] - lp[k]) as f64);
                let num: f64 = (0..3).map(|k| (l[k] - lp[k] as f64) * d[k]).sum();
                let den: f64 = (0..3).map(|k| d[k] * d[k]).sum();
                let t = if den > 0.0 {
                    (num / den).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                let (wp, wq) = (mesh.positions[p as usize], mesh.positions[q as usize]);
                wp + (wq - wp) * t
            }
            PointKey::Fe { face, .. } => {
                let tri = mesh.triangles[face as usize];
                let [u, v, w] = tri.map(|i| &target.lpoints[i as usize]);
                match exact::projection(&exact::normal(u, v, w)) {
                    Some((axis, _)) => {
                        let (i, j) = exact::plane_axes(axis);
                        let area = |a: [f64; 2], b: [f64; 2], c: [f64; 2]| {
                            (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
                        };
                        let pr = |p: &LPoint| [p[i] as f64, p[j] as f64];
                        let x = [l[i], l[j]];
                        let whole = area(pr(u), pr(v), pr(w));
                        let beta = area(pr(u), x, pr(w)) / whole;
                        let gamma = area(pr(u), pr(v), x) / whole;
                        let [wu, wv, ww] = tri.map(|i| mesh.positions[i as usize]);
                        wu + (wv - wu) * beta + (ww - wu) * gamma
                    }
                    None => target.lattice.to_world(l),
                }
            }
        }
    };
    let new_positions: Vec<DVec3> = if isect.points.len() >= PARALLEL_MIN {
        isect
            .points
            .par_iter()
            .zip(&isect.keys)
            .map(place)
            .collect()
    } else {
        isect.points.iter().zip(&isect.keys).map(place).collect()
    };
    sub.mark("place");
    let new_pos = &new_positions;
    let mut removed = Removed::new(target.mesh.clone(), new_pos.clone(), merge);
    // Kept ids: a new vertex whose rounded position equals (bit for bit) a corner of a touched
    // face or an earlier new vertex takes that id, and triangles that collapse are dropped
    // (they have no area; dropping them is an edge collapse, which keeps the surface closed).
    // The map holds the new vertices' positions only, each with the id it takes: the first
    // touched corner at that position (in the order of `faces`), else the first new vertex
    // there in the order of the loop below (`UNSET` until then).
    const UNSET: u32 = u32::MAX;
    let mut kept_new_faces = Vec::new();
    let mut kept_new_provenance = Vec::new();
    let mut kept_ids: FxMap<PositionBits, u32> = Default::default();
    let bits = position_bits;
    if merge {
        kept_ids.reserve(new_pos.len());
        for &p in new_pos.iter() {
            kept_ids.entry(bits(p)).or_insert(UNSET);
        }
        for face in faces {
            for v in mesh.triangles[face.t as usize] {
                if let Some(id) = kept_ids.get_mut(&bits(mesh.positions[v as usize]))
                    && *id == UNSET
                {
                    *id = v;
                }
            }
        }
    }
    sub.mark("kept ids");
    for TargetFace {
        t,
        pieces,
        statuses,
        ..
    } in faces
    {
        for (p, &s) in pieces.iter().zip(statuses) {
            for tri in &p.triangles {
                if s == OUT {
                    let ids = tri.map(|v| match v {
                        Vx::T(i) => i,
                        Vx::X(x) if merge => match kept_ids.get_mut(&bits(new_pos[x as usize])) {
                            Some(id) => {
                                if *id == UNSET {
                                    *id = nt + x;
                                }
                                *id
                            }
                            None => nt + x,
                        },
                        Vx::X(x) => nt + x,
                        Vx::C(_) => u32::MAX,
                    });
                    if ids[0] == ids[1] || ids[1] == ids[2] || ids[2] == ids[0] {
                        continue;
                    }
                    kept_new_faces.push(ids);
                    kept_new_provenance.push(*t);
                } else {
                    // Target pieces have target corners and contour points only.
                    let mut ids = [0u32; 3];
                    for (id, v) in ids.iter_mut().zip(tri) {
                        *id = match *v {
                            Vx::T(i) => i,
                            Vx::X(x) => nt + x,
                            Vx::C(c) => {
                                return Err(CutError::Internal(format!(
                                    "target face {t} has a piece with cutter vertex {c}"
                                )));
                            }
                        };
                    }
                    removed.piece_faces.push(ids);
                    removed.piece_provenance.push(*t);
                    removed.piece_sub_cutter.push(s - 1);
                }
            }
        }
    }
    sub.mark("kept+pieces");
    let mut wall_tris: Vec<([Vx; 3], u32, u32)> = Vec::new();
    for (tris, touched, fallbacks, status_fallbacks) in split_cutter {
        wall_tris.extend(tris);
        stats.touched_cutter_faces += usize::from(touched);
        stats.triangulation_fallbacks += fallbacks;
        stats.status_fallbacks += status_fallbacks;
    }
    let mut walls = PartBuilder::new(merge);
    let mut walls_solid = Vec::with_capacity(wall_tris.len());
    for (tri, f, solid) in &wall_tris {
        // Reversed: walls face out of kept (into the cutter).
        let ids = [tri[0], tri[2], tri[1]]
            .map(|v| walls.vertex(v, &mesh.positions, &cutter.positions, new_pos));
        if walls.push(
            ids,
            Provenance::Cutter(*f),
            cutter.face_component[*f as usize],
        ) {
            walls_solid.push(*solid);
        }
    }
    let contours = contour::chain(&isect.segments, new_pos, |s| {
        cutter.face_component[isect.segments[s].f as usize]
    });
    sub.mark("walls+contours");
    Ok(Output {
        new_positions,
        kept_new_faces,
        kept_new_provenance,
        removed,
        walls: walls.finish(),
        walls_solid,
        contours,
        stats,
        phases: sub,
    })
}

/// False when the unperturbed limit of `h` is certainly not a lattice point (then
/// [`HPoint::limit_lattice_point`] is `None`), decided in `f64`: with a non-zero constant
/// weight the limit is `x / w`; a quotient below 2³⁰ in magnitude (a point on a target face
/// is below 2²⁸) is computed with an absolute error below 2³⁰ · 3 · 2⁻⁵³ < 10⁻⁶, so one
/// farther than that from every integer is not one. Saves the exact 128-bit divisions for
/// almost every new vertex.
fn may_be_lattice_point(h: &HPoint) -> bool {
    if h.w[0] == 0 {
        return true;
    }
    let w = h.w[0] as f64;
    h.x.iter().all(|x| {
        let q = x[0] as f64 / w;
        q.abs() > (1u64 << 30) as f64 || (q - q.round()).abs() <= 1e-6
    })
}
