//! Checks of the boolean's robustness contract, and the body of its fuzz target.
//!
//! Public (not `cfg(test)`) for two callers that must agree on what "a correct cut" means: the
//! fuzz target in `csg/fuzz/` (built and run briefly by CI with `csg/fuzz/run-stable`) and the stable seeded runner
//! `csg/tests/fuzz_transforms.rs` (run by `cargo test`, so CI exercises the same body).
//!
//! [`check_closed_cut`] checks every promise the contract makes for a closed, edge-manifold
//! target on a result computed with `merge_coincident = false`; [`run_transform_case`] decodes
//! arbitrary bytes into a target shape and a randomly placed (rotated, scaled, translated,
//! optionally grid-snapped) cutter, cuts, and checks.

use std::collections::HashMap;

use glam::{DQuat, DVec3};

use crate::adjacency::EdgeAdjacency;
use crate::boolean::{CutError, subtract_with};
use crate::mesh::Mesh;
use crate::output::{CutOptions, CutResult, Part, Provenance, VertexSource};
use crate::regions::Regions;
use crate::target::TargetIndex;
use crate::testkit;

/// Relative tolerance of the measure identities: they are exact before the new vertices are
/// rounded to `f64`; afterwards only that rounding (about 1e-16 relative per vertex) remains.
pub const MEASURE_TOLERANCE: f64 = 1e-9;

/// The measure identities of a cut of a closed target: area(kept) + area(removed) = area(T),
/// vol(kept + walls) + vol(removed + reversed walls) = vol(T) (both to [`MEASURE_TOLERANCE`]),
/// and every target vertex keeps its exact coordinates in kept.
pub fn check_measures(target: &Mesh, result: &CutResult) -> Result<(), String> {
    measures(target, &result.materialize(target), result)
}

/// [`check_measures`] with kept already materialized.
fn measures(target: &Mesh, kept: &Mesh, result: &CutResult) -> Result<(), String> {
    let walls = &result.walls.mesh;
    let removed = &result.removed.part().mesh;
    let rel = |x: f64, y: f64| (x - y).abs() / y.abs().max(f64::MIN_POSITIVE);
    let (at, ak, ar) = (target.area(), kept.area(), removed.area());
    if rel(ak + ar, at) > MEASURE_TOLERANCE {
        return Err(format!("area: kept {ak} + removed {ar} != target {at}"));
    }
    let mut kw = kept.clone();
    kw.append(walls);
    let mut rw = removed.clone();
    rw.append(&walls.reversed());
    let (vt, vk, vr) = (volume(target), volume(&kw), volume(&rw));
    if rel(vk + vr, vt) > MEASURE_TOLERANCE {
        return Err(format!(
            "volume: kept+walls {vk} + removed+walls {vr} != target {vt}"
        ));
    }
    for (i, p) in target.positions.iter().enumerate() {
        if kept.positions[i].to_array().map(f64::to_bits) != p.to_array().map(f64::to_bits) {
            return Err(format!("target vertex {i} moved"));
        }
    }
    Ok(())
}

/// Signed volume about the origin (Σ a · (b × c) / 6): the same origin for every part, so the
/// parts' volumes add up with nothing but the rounding of the new vertices (unlike
/// [`Mesh::volume`], which measures each mesh about its own box centre).
pub fn volume(m: &Mesh) -> f64 {
    m.triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| m.positions[i as usize]);
            a.dot(b.cross(c))
        })
        .sum::<f64>()
        / 6.0
}

/// The faces of `p` as triples of symbolic vertex identities, reversed when `reverse`.
pub fn part_faces(p: &Part, reverse: bool) -> Vec<[VertexSource; 3]> {
    p.mesh
        .triangles
        .iter()
        .map(|t| {
            let f = t.map(|i| p.vertex_source[i as usize]);
            if reverse { [f[0], f[2], f[1]] } else { f }
        })
        .collect()
}

/// `Err` naming the first problem unless every directed edge is used once and its reverse once
/// (closed, edge-manifold, consistently oriented) and no triangle repeats a vertex.
pub fn closed_by_identity<K>(faces: &[[K; 3]]) -> Result<(), String>
where
    K: Copy + Eq + std::hash::Hash + std::fmt::Debug,
{
    let mut directed: HashMap<(K, K), u32> = HashMap::new();
    for (f, t) in faces.iter().enumerate() {
        if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
            return Err(format!("triangle {f} repeats a vertex: {t:?}"));
        }
        for k in 0..3 {
            *directed.entry((t[k], t[(k + 1) % 3])).or_default() += 1;
        }
    }
    for (&(a, b), &n) in &directed {
        if n != 1 {
            return Err(format!("directed edge ({a:?}, {b:?}) used {n} times"));
        }
        if directed.get(&(b, a)) != Some(&1) {
            return Err(format!("edge ({a:?}, {b:?}) has no opposite"));
        }
    }
    Ok(())
}

/// Checks a cut of a closed, edge-manifold `target` computed with `merge_coincident = false`:
/// area partition, volume identity, untouched vertices bit for bit, per region (see
/// [`crate::regions::Regions::build`]) kept + walls and removed + reversed walls closed and
/// oriented by vertex identity and the region's volume identity, closed contours, no fallback
/// used.
pub fn check_closed_cut(target: &Mesh, result: &CutResult) -> Result<(), String> {
    let (kept, kept_faces) = result.materialize_with_provenance(target);
    measures(target, &kept, result)?;
    regions_closed(target, &kept, &kept_faces, result)?;
    if let Some(c) = result.contours.iter().find(|c| !c.closed) {
        return Err(format!(
            "open contour of {} points on a closed target",
            c.points.len()
        ));
    }
    if result.stats.triangulation_fallbacks != 0 || result.stats.status_fallbacks != 0 {
        return Err(format!(
            "fallbacks used: {} triangulation, {} status",
            result.stats.triangulation_fallbacks, result.stats.status_fallbacks
        ));
    }
    Ok(())
}

/// Per region of `target`: its kept faces (`kept`, whose triangles come from target faces
/// `kept_faces`) and its walls close up by vertex identity, as do its removed faces and its
/// reversed walls, and vol(kept + walls) + vol(removed + reversed walls) = vol(region).
fn regions_closed(
    target: &Mesh,
    kept: &Mesh,
    kept_faces: &[u32],
    result: &CutResult,
) -> Result<(), String> {
    let regions = Regions::build(target, &EdgeAdjacency::build(target));
    let region = |t: u32| regions.region_of_triangle[t as usize];
    let n = target.positions.len() as u32;
    let src = |i: u32| {
        if i < n {
            VertexSource::Target(i)
        } else {
            VertexSource::New(i - n)
        }
    };
    let walls = &result.walls;
    if result.walls_solid.len() != walls.mesh.triangles.len() {
        return Err(format!(
            "{} wall solids for {} wall triangles",
            result.walls_solid.len(),
            walls.mesh.triangles.len()
        ));
    }
    let removed = result.removed.part();
    let wall_faces = part_faces(walls, false);
    let removed_faces = part_faces(removed, false);
    let position = |v: VertexSource| match v {
        VertexSource::Target(i) => target.positions[i as usize],
        VertexSource::New(k) => result.new_positions[k as usize],
        VertexSource::Cutter(_) => DVec3::NAN,
    };
    let wall_position =
        |t: usize, k: usize| walls.mesh.positions[walls.mesh.triangles[t][k] as usize];
    let signed = |p: [DVec3; 3]| p[0].dot(p[1].cross(p[2])) / 6.0;
    for r in 0..regions.count as u32 {
        let mut kw: Vec<[VertexSource; 3]> = Vec::new();
        let mut rw: Vec<[VertexSource; 3]> = Vec::new();
        let (mut vk, mut vr, mut vt) = (0.0, 0.0, 0.0);
        for (t, tri) in target.triangles.iter().enumerate() {
            if region(t as u32) == r {
                vt += signed(tri.map(|i| target.positions[i as usize]));
            }
        }
        for (tri, &t) in kept.triangles.iter().zip(kept_faces) {
            if region(t) == r {
                kw.push(tri.map(src));
                vk += signed(tri.map(|i| kept.positions[i as usize]));
            }
        }
        for (f, prov) in removed_faces.iter().zip(&removed.provenance) {
            if matches!(prov, Provenance::Target(t) if region(*t) == r) {
                rw.push(*f);
                vr += signed(f.map(position));
            }
        }
        for (t, f) in wall_faces.iter().enumerate() {
            if result.walls_solid[t] == r {
                kw.push(*f);
                rw.push([f[0], f[2], f[1]]);
                let w = signed(std::array::from_fn(|k| wall_position(t, k)));
                vk += w;
                vr -= w;
            }
        }
        closed_by_identity(&kw).map_err(|e| format!("region {r}: kept + walls: {e}"))?;
        closed_by_identity(&rw)
            .map_err(|e| format!("region {r}: removed + reversed walls: {e}"))?;
        let scale = vt.abs().max(target.area().powf(1.5)).max(f64::MIN_POSITIVE);
        if (vk + vr - vt).abs() / scale > MEASURE_TOLERANCE {
            return Err(format!(
                "region {r}: volume: kept+walls {vk} + removed+walls {vr} != region {vt}"
            ));
        }
    }
    Ok(())
}

/// Reads the fuzzer's bytes as numbers; missing bytes read as zero, so every input decodes.
struct Bytes<'a> {
    data: &'a [u8],
    at: usize,
}

impl Bytes<'_> {
    fn byte(&mut self) -> u8 {
        let b = self.data.get(self.at).copied().unwrap_or(0);
        self.at += 1;
        b
    }

    /// A number in `[lo, hi]` from two bytes.
    fn unit(&mut self, lo: f64, hi: f64) -> f64 {
        let v = u16::from_le_bytes([self.byte(), self.byte()]) as f64 / u16::MAX as f64;
        lo + (hi - lo) * v
    }
}

/// What [`run_transform_case`] did, for runners that count outcomes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CaseOutcome {
    /// The cut succeeded and every check passed; `contours` is the number of contour loops
    /// (0: the cutter missed the target or contains it, or lies inside it).
    Checked { contours: usize },
    /// The (snapped) cutter was refused with a typed error, as the contract allows.
    Refused,
}

/// The fuzz target's body: decodes `data` into a target (icosphere, torus, box, or a snapped
/// icosphere), a cutter (box, icosphere, torus) under a random rotation, non-uniform scale and
/// translation, optionally snapped to a coarse power-of-two grid (to force coincidences with the
/// target), cuts with `merge_coincident = false` and checks [`check_closed_cut`].
///
/// `Err` is a bug: a failed check, or [`CutError::Internal`], or any refusal of an unsnapped
/// cutter (rigid motions and scaling keep a valid cutter valid). A snapped cutter may become
/// flat or self-intersecting; those typed refusals are [`CaseOutcome::Refused`]. Panics are
/// bugs too (the fuzzer reports them).
pub fn run_transform_case(data: &[u8]) -> Result<CaseOutcome, String> {
    let mut b = Bytes { data, at: 0 };
    let target_kind = b.byte() % 4;
    let cutter_kind = b.byte() % 3;
    let target = match target_kind {
        0 => testkit::icosphere(2, 10.0),
        1 => testkit::torus(7.0, 3.0, 16, 8),
        2 => testkit::cube(DVec3::splat(-8.0), DVec3::splat(8.0)),
        _ => snap(&testkit::icosphere(2, 10.0), 0.25),
    };
    let mut cutter = match cutter_kind {
        0 => testkit::cube(DVec3::splat(-1.0), DVec3::splat(1.0)),
        1 => testkit::icosphere(1, 1.0),
        _ => testkit::torus(1.0, 0.4, 8, 6),
    };
    let axis = DVec3::new(b.unit(-1.0, 1.0), b.unit(-1.0, 1.0), b.unit(-1.0, 1.0));
    let rotation = DQuat::from_axis_angle(
        axis.try_normalize().unwrap_or(DVec3::Z),
        b.unit(0.0, std::f64::consts::TAU),
    );
    let scale = DVec3::new(b.unit(0.3, 9.0), b.unit(0.3, 9.0), b.unit(0.3, 9.0));
    let shift = DVec3::new(
        b.unit(-12.0, 12.0),
        b.unit(-12.0, 12.0),
        b.unit(-12.0, 12.0),
    );
    let snap_code = b.byte();
    for p in &mut cutter.positions {
        *p = rotation * (*p * scale) + shift;
    }
    let snapped = snap_code & 1 == 1;
    if snapped {
        // Grid steps 2, 1, 1/2, …, 1/64: many cutter vertices land on target planes and vertices.
        let step = 2f64.powi(1 - i32::from((snap_code >> 1) % 8));
        cutter = snap(&cutter, step);
    }
    let index = TargetIndex::build(target.clone()).map_err(|e| format!("target index: {e}"))?;
    let options = CutOptions::default().with_merge_coincident(false);
    match subtract_with(&index, &[&cutter], &options) {
        Ok(r) => {
            check_closed_cut(&target, &r)?;
            // The default (merged) output must keep the measure identities too.
            let merged = subtract_with(&index, &[&cutter], &CutOptions::default())
                .map_err(|e| format!("merged cut failed after the symbolic one passed: {e}"))?;
            check_measures_only(&target, &merged)?;
            Ok(CaseOutcome::Checked {
                contours: r.contours.len(),
            })
        }
        Err(e @ CutError::Internal(_)) => Err(format!("{e}")),
        Err(
            CutError::SelfIntersecting { .. }
            | CutError::NotPositive { .. }
            | CutError::NotOriented { .. }
            | CutError::NotClosed { .. }
            | CutError::DegenerateTriangle { .. },
        ) if snapped => Ok(CaseOutcome::Refused),
        Err(e) => Err(format!("valid cutter refused: {e}")),
    }
}

/// Area partition and volume identity only (for merged outputs, which are closed by position
/// only on generic cuts).
pub fn check_measures_only(target: &Mesh, result: &CutResult) -> Result<(), String> {
    let kept = result.materialize(target);
    let removed = &result.removed.part().mesh;
    let rel = |x: f64, y: f64| (x - y).abs() / y.abs().max(f64::MIN_POSITIVE);
    let (at, ak, ar) = (target.area(), kept.area(), removed.area());
    if rel(ak + ar, at) > MEASURE_TOLERANCE {
        return Err(format!(
            "merged area: kept {ak} + removed {ar} != target {at}"
        ));
    }
    let mut kw = kept;
    kw.append(&result.walls.mesh);
    let mut rw = removed.clone();
    rw.append(&result.walls.mesh.reversed());
    let (vt, vk, vr) = (volume(target), volume(&kw), volume(&rw));
    if rel(vk + vr, vt) > MEASURE_TOLERANCE {
        return Err(format!(
            "merged volume: kept+walls {vk} + removed+walls {vr} != target {vt}"
        ));
    }
    Ok(())
}

fn snap(m: &Mesh, step: f64) -> Mesh {
    Mesh {
        positions: m
            .positions
            .iter()
            .map(|p| (*p / step).round() * step)
            .collect(),
        triangles: m.triangles.clone(),
    }
}

/// Diagnostic of self-intersecting targets: the cutter faces in which contour segments of two
/// different target faces cross each other, with the number of crossing pairs (exact, under the
/// tie-break rule), ascending by face. Empty for every target that does not intersect itself
/// (the segments of one closed, non-self-intersecting surface never cross on a cutter face).
///
/// The boolean does not construct these crossing points (see the robustness contract: such
/// faces' walls come from the topology-only fallback, usually but not always counted in
/// [`crate::output::CutStats`]); this names them. O(s²) per cutter face with `s` segments, for
/// tests and diagnostics only.
pub fn crossing_cutter_faces(
    target: &TargetIndex,
    cutters: &[&Mesh],
) -> Result<Vec<(u32, usize)>, CutError> {
    use crate::exact;
    let cutter = crate::boolean::prepare_cutter(target, cutters)?;
    if !cutter.bounds.overlaps(&target.bounds) {
        return Ok(Vec::new());
    }
    let isect = crate::intersect::intersect(target, &cutter).map_err(CutError::Internal)?;
    let mut out = Vec::new();
    for (f, seg_ids) in isect.cutter_faces.iter().enumerate() {
        if seg_ids.len() < 2 {
            continue;
        }
        let [a, b, c] = cutter.face_points(f as u32);
        let Some((axis, _)) = exact::projection(&exact::normal(a, b, c)) else {
            continue;
        };
        let (i, j) = exact::plane_axes(axis);
        let segs: Vec<(u32, u32)> = seg_ids
            .iter()
            .map(|&s| {
                let s = &isect.segments[s as usize];
                (s.a, s.b)
            })
            .collect();
        // Boxes of the limit points (rounded, so widened by a relative margin) prune the pairs.
        let boxes: Vec<[f64; 4]> = segs
            .iter()
            .map(|&(p, q)| {
                let (lp, lq) = (
                    isect.points[p as usize].limit(),
                    isect.points[q as usize].limit(),
                );
                let pad = 1e-6 * (lp[i].abs() + lp[j].abs() + lq[i].abs() + lq[j].abs() + 1.0);
                [
                    lp[i].min(lq[i]) - pad,
                    lp[i].max(lq[i]) + pad,
                    lp[j].min(lq[j]) - pad,
                    lp[j].max(lq[j]) + pad,
                ]
            })
            .collect();
        let pt = |p: u32| &isect.points[p as usize];
        let mut crossings = 0;
        for (k1, &(p1, q1)) in segs.iter().enumerate() {
            for (k2, &(p2, q2)) in segs.iter().enumerate().skip(k1 + 1) {
                let (b1, b2) = (&boxes[k1], &boxes[k2]);
                if b1[1] < b2[0] || b2[1] < b1[0] || b1[3] < b2[2] || b2[3] < b1[2] {
                    continue;
                }
                if p1 == p2 || p1 == q2 || q1 == p2 || q1 == q2 {
                    continue;
                }
                let o1 = exact::orient2d(pt(p1), pt(q1), pt(p2), axis);
                let o2 = exact::orient2d(pt(p1), pt(q1), pt(q2), axis);
                if o1 * o2 >= 0 {
                    continue;
                }
                let o3 = exact::orient2d(pt(p2), pt(q2), pt(p1), axis);
                let o4 = exact::orient2d(pt(p2), pt(q2), pt(q1), axis);
                if o3 * o4 < 0 {
                    crossings += 1;
                }
            }
        }
        if crossings > 0 {
            out.push((f as u32, crossings));
        }
    }
    Ok(out)
}
