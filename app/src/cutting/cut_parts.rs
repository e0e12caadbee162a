//! One cutter against one indexed target: the cutter's closed surface, its exact cut, the contour
//! as polylines, and the ribbons and slices of its sub-cutters. [`super::cut_scene`] strings these
//! together over the cutters of a scene; kept apart so that file reads as the sequence and the
//! cache, and this one as what a single cut produces. The types both speak are in
//! [`super::cut_results`]; imports go cut_scene → cut_parts → cut_results.

use std::collections::HashMap;

use csg::{Mesh, TargetIndex};
use glam::DVec3;

use super::cut_results::{CutParts, PartKind, PreviewGeometry, PreviewPart, SURFACE, Step};
use crate::scene::SceneCutter;

/// The closed triangulated cutter: the surface the boolean cuts with and the Edit overlay draws
/// ([`cutter::Cutter::surface`]: subdivided when the cutter is smooth). Empty for fewer than two
/// planes. Every cut and every overlay of the application takes its cutter surface from here.
pub fn cutter_surface(cutter: &cutter::Cutter) -> Mesh {
    if cutter.planes.len() < 2 {
        return Mesh::default();
    }
    cutter.surface()
}

/// [`cutter_surface`] of a scene cutter.
pub fn cutter_mesh(cutter: &SceneCutter) -> Mesh {
    cutter_surface(&cutter.cutter)
}

/// The exact cut of `cutter` out of the indexed target.
pub fn cut_exact(target: &TargetIndex, cutter: &SceneCutter) -> Result<CutParts, csg::CutError> {
    let mesh = cutter_mesh(cutter);
    if mesh.is_empty() {
        return Ok(CutParts {
            kept: target.mesh().clone(),
            ..CutParts::default()
        });
    }
    let result = csg::subtract(target, &mesh)?;
    Ok(CutParts {
        kept: result.materialize(target.mesh()),
        walls: result.walls.mesh,
        removed: result.removed.into_part().mesh,
        contour: contour_polylines(result.contours),
    })
}

/// The contour loops as polylines to draw: a closed loop repeats its first point at the end.
pub fn contour_polylines(contours: Vec<csg::Contour>) -> Vec<Vec<DVec3>> {
    contours
        .into_iter()
        .map(|c| {
            let mut points = c.points;
            if c.closed
                && let Some(&first) = points.first()
            {
                points.push(first);
            }
            points
        })
        .collect()
}

/// Ribbons (the removed surface inside the sub-cutters of `view`) and the walls of those
/// sub-cutters inside the target (facing out of the kept part) for one step of [`cut_in_turn`](super::cut_scene::cut_in_turn),
/// by the exact boolean. Ribbons keep only the model's own surface, not the walls of earlier
/// cutters.
///
/// Horizontal layers are the cutter's own planes cut down to a depth band (smooth when the
/// cutter is), so they follow its shape. A smooth cutter's rounded sides are not its planes: thin
/// boxes across it are made larger than its cross-section, and all its sub-cutters are clipped to
/// the smooth surface, so ribbons and slices follow it exactly (the ribbons are the removed piece
/// inside the sub-cutters, the slice walls are the sub-cutters' walls inside the smooth cutter).
pub fn sub_cuts(
    step: &Step,
    cutter: &SceneCutter,
    view: &crate::scene::SubCutterSpec,
    with_walls: bool,
) -> Result<(Mesh, Mesh), csg::CutError> {
    use cutter::subcutters::Placement;
    let whole = &cutter.cutter;
    if whole.planes.len() < 2 {
        return Ok((Mesh::default(), Mesh::default()));
    }
    let clip = whole.smooth;
    let mut subs = cutter::subcutters::sub_cutters(whole, view);
    if clip && view.placement != Placement::Horizontal {
        for sub in &mut subs {
            for p in &mut sub.planes {
                *p = grown(p, 1.5);
            }
        }
    }
    let meshes: Vec<Mesh> = subs.iter().map(|c| c.surface()).collect();
    if meshes.is_empty() {
        return Ok((Mesh::default(), Mesh::default()));
    }
    let refs: Vec<&Mesh> = meshes.iter().collect();
    if !clip {
        let surface_only = |f: u32| step.before_tags.get(f as usize) == Some(&SURFACE);
        return cut_each(step.before, &refs, surface_only);
    }
    let ribbons = inside(step.removed, &refs)?;
    let walls = if with_walls {
        let (_, walls) = cut_each(step.before, &refs, |_| true)?;
        inside(&walls, &[&whole.surface()])?
    } else {
        Mesh::default()
    };
    Ok((ribbons, walls))
}

/// The removed surface (the target faces `keep` accepts) and the walls of several sub-cutters:
/// in one boolean when they are disjoint, else (sub-cutters that overlap in a tight turn) one
/// boolean each, the pieces put together.
fn cut_each(
    target: &TargetIndex,
    subs: &[&Mesh],
    keep: impl Fn(u32) -> bool,
) -> Result<(Mesh, Mesh), csg::CutError> {
    let pieces = |result: csg::CutResult| {
        let removed = select(
            &result.removed.mesh,
            |t| matches!(result.removed.provenance[t], csg::Provenance::Target(f) if keep(f)),
        );
        (removed, result.walls.mesh)
    };
    match csg::subtract_many(target, subs) {
        Ok(result) => Ok(pieces(result)),
        Err(csg::CutError::SelfIntersecting {
            first_sub,
            second_sub,
            ..
        }) if first_sub != second_sub => {
            let (mut removed, mut walls) = (Mesh::default(), Mesh::default());
            for sub in subs {
                let (r, w) = pieces(csg::subtract(target, sub)?);
                removed.append(&r);
                walls.append(&w);
            }
            Ok((removed, walls))
        }
        Err(e) => Err(e),
    }
}

/// The part of `mesh` (open or closed) inside the cutters, by the exact boolean.
fn inside(mesh: &Mesh, cutters: &[&Mesh]) -> Result<Mesh, csg::CutError> {
    if mesh.is_empty() {
        return Ok(Mesh::default());
    }
    let index = TargetIndex::build(mesh.clone())
        .map_err(|e| csg::CutError::Internal(format!("the piece to clip: {e}")))?;
    Ok(cut_each(&index, cutters, |_| true)?.0)
}

/// `plane` scaled by `factor` about its centre (a thin box that spans a smooth cutter's
/// overshoot).
fn grown(plane: &cutter::BoundedPlane, factor: f64) -> cutter::BoundedPlane {
    let c = plane.center();
    cutter::BoundedPlane::from_corners(plane.corners().map(|p| c + (p - c) * factor))
}

pub(super) fn push_part(
    out: &mut PreviewGeometry,
    model: usize,
    cutter: usize,
    kind: PartKind,
    opacity: f32,
    mesh: Mesh,
) {
    if mesh.is_empty() {
        return;
    }
    out.parts.push(PreviewPart {
        model,
        cutter,
        kind,
        opacity,
        mesh,
    });
}

/// Undirected edges (vertex pairs, smaller first) of `mesh` chained into polylines; closed loops
/// repeat their first point at the end.
pub(super) fn chain_edges(mesh: &Mesh, mut edges: Vec<(u32, u32)>) -> Vec<Vec<DVec3>> {
    let mut next: HashMap<u32, Vec<u32>> = HashMap::new();
    edges.sort_unstable();
    for &(a, b) in &edges {
        next.entry(a).or_default().push(b);
        next.entry(b).or_default().push(a);
    }
    let mut used: HashMap<(u32, u32), bool> = edges.iter().map(|&e| (e, false)).collect();
    let mut lines = Vec::new();
    for &(a0, b0) in &edges {
        if used[&(a0, b0)] {
            continue;
        }
        used.insert((a0, b0), true);
        let mut line = vec![a0, b0];
        let mut cur = b0;
        loop {
            let step = next[&cur]
                .iter()
                .copied()
                .find(|&n| !used[&(cur.min(n), cur.max(n))]);
            let Some(n) = step else { break };
            used.insert((cur.min(n), cur.max(n)), true);
            line.push(n);
            cur = n;
            if n == a0 {
                break;
            }
        }
        lines.push(
            line.into_iter()
                .map(|i| mesh.positions[i as usize])
                .collect(),
        );
    }
    lines
}

/// The triangles `keep(t)` accepts, compacted.
pub fn select(mesh: &Mesh, keep: impl Fn(usize) -> bool) -> Mesh {
    Mesh {
        positions: mesh.positions.clone(),
        triangles: (0..mesh.triangle_count())
            .filter(|&t| keep(t))
            .map(|t| mesh.triangles[t])
            .collect(),
    }
    .compacted()
}
