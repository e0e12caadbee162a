//! Stage 1 of the boolean: the cutter validated (closed, oriented, positive volume, free of
//! self-intersections, within range) and quantized to the target's lattice, with the same exact
//! predicates the cut uses. The cutter editor calls [`check_cutter`] on every edit.

use super::error::CutError;
use crate::exact::{self, LPoint};
use crate::intersect::{self, FxMap, PreparedCutter};
use crate::lattice::Lattice;
use crate::mesh::Mesh;
use crate::target::{IBox, TargetIndex};

/// Stage 1: validation and quantization of the cutter(s).
pub(crate) fn prepare_cutter(
    target: &TargetIndex,
    cutters: &[&Mesh],
) -> Result<PreparedCutter, CutError> {
    let cutter = prepare_unchecked(&target.lattice, cutters)?;
    check_self_intersections(&cutter)?;
    Ok(cutter)
}

/// Checks a cutter on its own, before any target exists (the cutter editor validates every edit
/// with it): closed, consistently oriented, positive volume and free of self-intersections, with
/// the same exact predicates as [`subtract`](crate::subtract), on the lattice of the cutter's own bounding box.
/// A target much larger than the cutter has a coarser lattice, so a cutter whose faces come within
/// a few of its lattice steps of each other can still be refused by the cut itself.
pub fn check_cutter(cutter: &Mesh) -> Result<(), CutError> {
    let prepared = prepare_unchecked(&Lattice::for_box(&cutter.bbox()), &[cutter])?;
    check_self_intersections(&prepared)
}

/// Every pair of intersecting triangles of `cutter` (at most `limit`; exact, touching counts, as
/// in [`check_cutter`]), or the first other defect [`check_cutter`] finds. Lets a caller repair
/// every offending place of a cutter at once instead of one pair per check.
pub fn cutter_self_intersections(
    cutter: &Mesh,
    limit: usize,
) -> Result<Vec<(usize, usize)>, CutError> {
    let prepared = prepare_unchecked(&Lattice::for_box(&cutter.bbox()), &[cutter])?;
    Ok(self_intersections(&prepared, limit))
}

/// Validation and quantization without the self-intersection check.
fn prepare_unchecked(lattice: &Lattice, cutters: &[&Mesh]) -> Result<PreparedCutter, CutError> {
    let mut positions = Vec::new();
    let mut lpoints = Vec::new();
    let mut triangles = Vec::new();
    let mut face_component = Vec::new();
    let mut sub_of_vertex = Vec::new();
    for (k, m) in cutters.iter().enumerate() {
        m.sanity_check().map_err(|source| CutError::InvalidMesh {
            sub_cutter: k,
            source,
        })?;
        if m.triangles.is_empty() {
            return Err(CutError::EmptyCutter { sub_cutter: k });
        }
        let base = positions.len() as u32;
        for (i, &p) in m.positions.iter().enumerate() {
            let q = lattice.quantize(p).ok_or(CutError::OutOfRange {
                sub_cutter: k,
                vertex: i,
                position: p.to_array(),
            })?;
            positions.push(p);
            lpoints.push(q);
            sub_of_vertex.push(k as u32);
        }
        for (i, t) in m.triangles.iter().enumerate() {
            if t[0] == t[1] || t[1] == t[2] || t[2] == t[0] {
                return Err(CutError::DegenerateTriangle {
                    sub_cutter: k,
                    triangle: i,
                });
            }
            triangles.push(t.map(|v| v + base));
            face_component.push(k as u32);
        }
    }
    // Edges: every undirected edge in exactly two faces, traversed in opposite directions.
    let mut edge_map: FxMap<(u32, u32), u32> = Default::default();
    let mut edges: Vec<[u32; 2]> = Vec::new();
    let mut edge_dirs: Vec<[bool; 2]> = Vec::new();
    let mut edge_count: Vec<usize> = Vec::new();
    let mut tri_edges = Vec::with_capacity(triangles.len());
    for t in triangles.iter() {
        let mut te = [0u32; 3];
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let key = (a.min(b), a.max(b));
            let id = *edge_map.entry(key).or_insert_with(|| {
                edges.push([key.0, key.1]);
                edge_dirs.push([false; 2]);
                edge_count.push(0);
                (edges.len() - 1) as u32
            });
            let c = edge_count[id as usize];
            if c < 2 {
                edge_dirs[id as usize][c] = a < b;
            }
            edge_count[id as usize] += 1;
            te[k] = id;
        }
        tri_edges.push(te);
    }
    for (e, &c) in edge_count.iter().enumerate() {
        let [a, b] = edges[e];
        let sub_cutter = sub_of_vertex[a as usize] as usize;
        let local = |v: u32| v - first_vertex(cutters, sub_cutter);
        if c != 2 {
            return Err(CutError::NotClosed {
                sub_cutter,
                a: local(a),
                b: local(b),
                faces: c,
            });
        }
        if edge_dirs[e][0] == edge_dirs[e][1] {
            return Err(CutError::NotOriented {
                sub_cutter,
                a: local(a),
                b: local(b),
            });
        }
    }
    let mut face_boxes = Vec::with_capacity(triangles.len());
    let mut bounds = IBox::EMPTY;
    for t in &triangles {
        let b = IBox::of_triangle(t.map(|v| &lpoints[v as usize]));
        bounds = bounds.union(&b);
        face_boxes.push(b);
    }
    let cutter = PreparedCutter {
        positions,
        lpoints,
        triangles,
        edges,
        tri_edges,
        face_component,
        components: cutters.len() as u32,
        face_boxes,
        bounds,
    };
    // Orientation: positive exact volume per sub-cutter.
    let mut vol = vec![0i128; cutters.len()];
    let o = [0i64; 3];
    for (f, t) in cutter.triangles.iter().enumerate() {
        let [a, b, c] = t.map(|v| &cutter.lpoints[v as usize]);
        let k = cutter.face_component[f] as usize;
        vol[k] = vol[k].saturating_add(exact::orient3d(&o, a, b, c));
    }
    if let Some(k) = vol.iter().position(|&v| v <= 0) {
        return Err(CutError::NotPositive { sub_cutter: k });
    }
    Ok(cutter)
}

fn first_vertex(cutters: &[&Mesh], k: usize) -> u32 {
    cutters[..k].iter().map(|m| m.positions.len() as u32).sum()
}

/// Exact self-intersection check of the cutter (touching counts). Triangles sharing an edge are
/// not compared; triangles sharing one vertex are compared through their opposite edges.
fn check_self_intersections(cutter: &PreparedCutter) -> Result<(), CutError> {
    match self_intersections(cutter, 1).first() {
        Some(&(a, b)) => Err(CutError::SelfIntersecting {
            first: a,
            second: b,
            first_sub: cutter.face_component[a] as usize,
            second_sub: cutter.face_component[b] as usize,
        }),
        None => Ok(()),
    }
}

/// Up to `limit` intersecting triangle pairs `(a, b)`, `a < b`, in the order of `a` (see
/// [`check_self_intersections`]).
fn self_intersections(cutter: &PreparedCutter, limit: usize) -> Vec<(usize, usize)> {
    let bvh = intersect::cutter_bvh(cutter);
    let mut found: Vec<(usize, usize)> = Vec::new();
    for f1 in 0..cutter.triangles.len() {
        if found.len() >= limit {
            break;
        }
        let t1 = cutter.triangles[f1];
        let mut hits = Vec::new();
        bvh.query(&cutter.face_boxes[f1], &cutter.face_boxes, |f2| {
            let f2 = f2 as usize;
            if f2 <= f1 {
                return;
            }
            let t2 = cutter.triangles[f2];
            let shared: Vec<u32> = t1.iter().copied().filter(|v| t2.contains(v)).collect();
            if shared.len() >= 2 {
                return;
            }
            let p1 = t1.map(|v| &cutter.lpoints[v as usize]);
            let p2 = t2.map(|v| &cutter.lpoints[v as usize]);
            let hit = |ta: &[u32; 3], pa: &[&LPoint; 3], pb: &[&LPoint; 3]| {
                (0..3).any(|k| {
                    let (i, j) = (k, (k + 1) % 3);
                    if shared.len() == 1 && (ta[i] == shared[0] || ta[j] == shared[0]) {
                        return false;
                    }
                    exact::segment_meets_triangle(pa[i], pa[j], pb[0], pb[1], pb[2])
                })
            };
            if hit(&t1, &p1, &p2) || hit(&t2, &p2, &p1) {
                hits.push(f2);
            }
        });
        hits.sort_unstable();
        found.extend(hits.into_iter().map(|f2| (f1, f2)));
    }
    found.truncate(limit);
    found
}
