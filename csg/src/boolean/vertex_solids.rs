//! Stage 3 of the boolean: each cutter vertex's status, the set of region solids it lies in
//! (see [`crate::solids`]). One inside test per cutter component seeds a walk along the cutter
//! edges; crossing a target face toggles that face's solid.

use super::error::CutError;
use super::inputs::CutInputs;
use crate::classify;
use crate::output::CutStats;
use crate::solids::SolidSets;

/// The solid set of every cutter vertex (ids into the returned [`SolidSets`]).
pub(crate) fn cutter_vertex_solids(
    cut: &CutInputs,
    stats: &mut CutStats,
) -> Result<(Vec<u32>, SolidSets), CutError> {
    let (target, cutter, isect) = (cut.target, cut.cutter, cut.isect);
    let nv = cutter.positions.len();
    let mut vertex_edges: Vec<Vec<u32>> = vec![Vec::new(); nv];
    for (g, e) in cutter.edges.iter().enumerate() {
        vertex_edges[e[0] as usize].push(g as u32);
        vertex_edges[e[1] as usize].push(g as u32);
    }
    let mut sets = SolidSets::new();
    let mut cutter_in: Vec<Option<u32>> = vec![None; nv];
    let closed = target.is_closed();
    for seed in 0..nv {
        if cutter_in[seed].is_some() {
            continue;
        }
        stats.inside_tests += 1;
        let s =
            classify::cutter_point_solids(target, &cutter.lpoints[seed], cutter.positions[seed]);
        cutter_in[seed] = Some(sets.intern(s));
        let mut stack = vec![seed];
        while let Some(v) = stack.pop() {
            let sv = cutter_in[v].unwrap_or(0);
            for &g in &vertex_edges[v] {
                let [a, b] = cutter.edges[g as usize];
                let other = if a as usize == v { b } else { a } as usize;
                let so = isect.cutter_edges[g as usize]
                    .iter()
                    .fold(sv, |set, x| sets.toggle(set, cut.solid_of_point(x.point)));
                match cutter_in[other] {
                    None => {
                        cutter_in[other] = Some(so);
                        stack.push(other);
                    }
                    Some(x) if x != so && closed => {
                        return Err(CutError::Internal(format!(
                            "crossing parity disagrees around cutter vertex {other}"
                        )));
                    }
                    _ => {}
                }
            }
        }
    }
    let cutter_in: Vec<u32> = cutter_in.into_iter().map(|s| s.unwrap_or(0)).collect();
    Ok((cutter_in, sets))
}
