//! Stage 5 of the boolean: the untouched target faces inside the cutter, by a flood fill from
//! the split faces (output-sensitive: it walks inside the cutter only), plus one exact inside
//! test per untouched region whose box overlaps the cutter.

use super::faces::TargetFace;
use super::inputs::CutInputs;
use crate::classify;
use crate::intersect::FxMap;
use crate::split::{OUT, UNKNOWN};
use crate::target::{MANY_NEIGHBORS, NO_NEIGHBOR, Scratch};

/// What the flood fill finds.
pub(crate) struct Flood {
    /// Every removed face, ascending: the touched ones and the flooded (whole) ones.
    pub removed_faces: Vec<u32>,
    /// The flooded faces, ascending, and the sub-cutter of each.
    pub whole_faces: Vec<u32>,
    pub whole_sub_cutter: Vec<u32>,
    /// Exact inside tests made.
    pub inside_tests: usize,
}

/// Flood fill of the untouched faces from the split `faces` (see the module doc). The target's
/// scratch marks every face of `removed_faces` (touched by the contour, or flooded) in a bitmap,
/// which also gives them back in ascending order; a flooded face's status is recorded only when
/// there are several sub-cutters (with one it is always 1).
pub(crate) fn flood(cut: &CutInputs, faces: &[TargetFace]) -> Flood {
    let (target, cutter, isect) = (cut.target, cut.cutter, cut.isect);
    let mesh = &target.mesh;
    let mut inside_tests = 0;
    let many = cutter.components > 1;
    let mut local_scratch = None;
    let mut guard = target.scratch.0.try_lock();
    let scratch: &mut Scratch = match guard.as_deref_mut() {
        Ok(s) => s,
        Err(_) => local_scratch.insert(Scratch::for_faces(mesh.triangles.len())),
    };
    scratch.begin(mesh.triangles.len());
    for &t in &isect.target_order {
        scratch.mark_touched(t);
    }
    // Breadth-first: `queue` holds the flooded faces and their statuses in discovery order.
    // The faces of a large target are far apart in memory (on the peerbench sphere no
    // neighbour's index is within 4096), so each face's neighbour entry is a cache miss: the
    // loop below loads the entries of a batch of queued faces first (independent loads,
    // which the processor overlaps) and only then follows them.
    let mut queue: Vec<(u32, u32)> = Vec::new();
    let visit = |scratch: &mut Scratch, queue: &mut Vec<(u32, u32)>, t2, s| {
        if !scratch.is_marked(t2) {
            if many {
                scratch.mark_with(t2, s);
            } else {
                scratch.mark(t2);
            }
            queue.push((t2, s));
        }
    };
    // Seeds: across every side the contour does not cross, the status of its first corner
    // (its piece's status: a vertex has one status).
    for face in faces {
        let t = face.t;
        let neighbors = target.face_neighbors[t as usize];
        for k in 0..3 {
            let s = face.corner_status[k];
            if face.crossed & (1 << k) != 0 || s == OUT || s == UNKNOWN {
                continue;
            }
            match neighbors[k] {
                NO_NEIGHBOR => {}
                MANY_NEIGHBORS => {
                    let e = target.adjacency.triangle_edges[t as usize][k];
                    for &t2 in target.adjacency.faces_of_edge(e) {
                        visit(scratch, &mut queue, t2, s);
                    }
                }
                t2 => visit(scratch, &mut queue, t2, s),
            }
        }
    }
    // Untouched regions whose box overlaps the cutter: one inside test each.
    let mut touched_regions: FxMap<u32, ()> = Default::default();
    for &t in &isect.target_order {
        touched_regions.insert(target.components.region_of_triangle[t as usize], ());
    }
    for r in 0..target.components.count {
        if touched_regions.contains_key(&(r as u32))
            || !target.component_boxes[r].overlaps(&cutter.bounds)
        {
            continue;
        }
        let t0 = target.component_first_face[r];
        if t0 == u32::MAX || scratch.is_marked(t0) {
            continue;
        }
        inside_tests += 1;
        let v0 = mesh.triangles[t0 as usize][0];
        let s = classify::target_point_status(cutter, &target.lpoints[v0 as usize]);
        if s != OUT {
            visit(scratch, &mut queue, t0, s);
        }
    }
    const BATCH: usize = 32;
    let mut head = 0;
    while head < queue.len() {
        let end = queue.len().min(head + BATCH);
        let mut neighbors = [[0u32; 3]; BATCH];
        for (n, &(t, _)) in neighbors.iter_mut().zip(&queue[head..end]) {
            *n = target.face_neighbors[t as usize];
        }
        for i in 0..end - head {
            let (t, s) = queue[head + i];
            for (k, &t2) in neighbors[i].iter().enumerate() {
                if t2 < MANY_NEIGHBORS {
                    visit(scratch, &mut queue, t2, s);
                } else if t2 == MANY_NEIGHBORS {
                    let e = target.adjacency.triangle_edges[t as usize][k];
                    for &t2 in target.adjacency.faces_of_edge(e) {
                        visit(scratch, &mut queue, t2, s);
                    }
                }
            }
        }
        head = end;
    }
    // Every marked face, ascending: the touched ones and the flooded (whole) ones.
    let marked = scratch.marked_count();
    let mut removed_faces: Vec<u32> = Vec::with_capacity(marked);
    let mut whole_faces: Vec<u32> = Vec::with_capacity(marked);
    let mut whole_sub_cutter: Vec<u32> = Vec::with_capacity(marked);
    scratch.drain_marked(|t, touched, value| {
        removed_faces.push(t);
        if !touched {
            whole_faces.push(t);
            whole_sub_cutter.push(if many { value - 1 } else { 0 });
        }
    });
    scratch.clear_touched(&isect.target_order);
    drop(guard);
    Flood {
        removed_faces,
        whole_faces,
        whole_sub_cutter,
        inside_tests,
    }
}
