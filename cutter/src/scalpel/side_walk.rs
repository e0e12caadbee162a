//! The opening's walk from the lips: the side of the cut every vertex within the support
//! opens to, with the rest of its field ([`FieldAt`]; see [`super::dffd`] for the field).
//!
//! Breadth-first over surface vertices from the lip copies (seeds with their side, from their
//! own surface triangles, [`lip_side`]); every other vertex takes the side of the vertex it is
//! first reached from. It never crosses the cut: the lips are split and groove walls are not
//! walked. The walk itself is bound by memory (the mesh around each vertex, the field kept for
//! it); the path corrections it asks for, by arithmetic: those are measured beside it
//! ([`super::blend::with_blends`]).

use std::collections::VecDeque;

use glam::DVec3;

use super::blend::{BlendInputs, Blends, with_blends};
use super::cut_grid::{Cell, CutGrid, InCells, Near, cell_of};
use super::dffd::{Frame, Inputs};
use super::dyn_mesh::{DynMesh, prev};
use super::field::{FieldAt, taper_at};
use super::field_cache::{Changes, FieldCache, Kept};
use super::nearest_cut::{self, Balls};
use super::sides::Sides;
use super::step::Scalpel;
use csg::fast_hash::FastSet;

/// Where a partial walk works: the cells it walks over (and seeds at the lips of), those whose
/// vertices' field it gives, and the field kept from before with what changed since (a
/// vertex's kept field is given when no change reaches it, [`FieldCache::kept`]).
pub(crate) struct WalkRegion<'a> {
    pub outer: &'a FastSet<Cell>,
    pub keep: &'a FastSet<Cell>,
    pub known: &'a FieldCache,
    pub changes: &'a Changes,
}

/// The field of every vertex the walk of the module doc reaches within the support, in the
/// order it reaches them, apart from the clock ([`FieldAt`]); fixed vertices are walked over,
/// not given. With a region, the walk stays in its outer cells and seeds only at lips there,
/// and gives the vertices of its kept cells only.
pub(crate) fn walk(
    scalpel: &Scalpel,
    inputs: &Inputs,
    grid: &CutGrid,
    region: Option<&WalkRegion>,
    side: &mut Sides,
) -> Vec<FieldAt> {
    let blend_inputs = BlendInputs {
        grid,
        segments: scalpel.segments(),
        corrections: &inputs.corrections,
        r: inputs.r,
    };
    let (mut field, blended) = with_blends(blend_inputs, |blends| {
        walk_asking(scalpel, inputs, grid, region, side, blends)
    });
    for (k, c) in blended {
        field[k as usize].correction = c;
    }
    field
}

/// [`walk`], asking `blends` for the path corrections of the field it gives (written there
/// after).
fn walk_asking(
    scalpel: &Scalpel,
    inputs: &Inputs,
    grid: &CutGrid,
    region: Option<&WalkRegion>,
    side: &mut Sides,
    blends: &mut Blends,
) -> Vec<FieldAt> {
    let outer = region.map(|g| g.outer);
    let mesh = scalpel.dyn_mesh();
    let segments = scalpel.segments();
    let mut field = Vec::new();
    let r = inputs.r;
    let nv = mesh.vertex_count() as u32;
    let (frames, tips) = (&inputs.frames, &inputs.tips);
    let onto_path = inputs.onto_path;
    let size = grid.size();
    let mut in_outer = InCells::new(outer, size);
    let mut in_keep = InCells::new(region.map(|g| g.keep), size);
    // Nearest point on the cut among the segments near `p`: (distance, point, segment index).
    // `last` is the previous answer's segment, measured first (see [`nearest_cut`]).
    let balls = Balls::new(segments);
    let mut last: Option<usize> = None;
    let mut near = Near::default();
    let mut nearest = |p: DVec3| -> Option<(f64, DVec3, usize)> {
        let lists = near.near_in_blocks(grid, p, &balls);
        let found = nearest_cut::nearest(segments, &balls, p, lists, last);
        last = found.map(|f| f.2).or(last);
        found
    };
    // The path correction of each vertex given (the corrections at the ends of the segments
    // near it within the support, weighted by inverse squared distance: exact at a lip vertex;
    // smooth around the zigzag's corners, where the nearest segment changes from one vertex to
    // the next and a correction taken from it alone would squash the small triangles there) is
    // asked of `blends` and written after the walk.
    //
    // Breadth-first over surface vertices from the lip copies (seeds with their side), within
    // the support; every other vertex takes the side of the vertex it was reached from. (So a
    // vertex takes the side of the first seed, in seed order, among those fewest surface edges
    // away: a region's vertices take the sides the whole walk gives them when its margin holds
    // those seeds and paths.)
    side.start(mesh.vertex_count());
    let mut queue: VecDeque<u32> = VecDeque::new();
    let mut fan = Vec::new();
    let seed_segments: Vec<usize> = match outer {
        None => (0..segments.len()).collect(),
        Some(o) => grid.segments_in(o),
    };
    for s in seed_segments.iter().map(|&i| &segments[i]) {
        for v in [s.a, s.b] {
            if v >= nv || !mesh.has_copies(v) || !in_outer.contains(mesh.pos(v)) {
                continue;
            }
            for c in std::iter::once(v).chain(mesh.copies(v)) {
                if side.contains(c) {
                    continue;
                }
                let p = mesh.pos(c);
                let Some((_, _, i)) = nearest(p) else {
                    continue;
                };
                let sigma = lip_side(mesh, c, &frames[i], &mut fan);
                if sigma != 0.0 {
                    side.insert(c, sigma);
                    queue.push_back(c);
                }
            }
        }
    }
    while let Some(v) = queue.pop_front() {
        let p = mesh.pos(v);
        let cell = cell_of(p, size);
        // Neighbours are queued without asking where they lie (several per vertex, most
        // already queued); one outside the region is dropped here, given nothing and walked
        // from nowhere, as if never queued.
        if !in_outer.contains_cell(cell) {
            continue;
        }
        let Some(sigma) = side.get(v) else {
            continue;
        };
        // A kept field says the vertex is within the support, as before. Outside the kept
        // cells (the margin) no change reaches (they would be kept cells otherwise), and only
        // that is asked of it: no vertex there was edited (the cells of those are walked), so
        // a field kept for one is its own and need not be fetched.
        let wanted = in_keep.contains_cell(cell);
        let kept = match region {
            Some(g) if wanted => g.known.kept(v, p, sigma, Some(g.changes)),
            _ => None,
        };
        let (dist, c, i) = match kept {
            Some(k) => (0.0, k.field_at.nearest, k.field_at.segment as usize),
            None if !wanted && region.is_some_and(|g| g.known.holds(v)) => {
                debug_assert!(region.is_some_and(|g| g.known.kept(v, p, sigma, None).is_some()));
                // Within the support; a margin vertex gives no field, so no nearest point.
                (0.0, p, 0)
            }
            None => {
                let Some(found) = nearest(p) else {
                    continue;
                };
                found
            }
        };
        if dist >= r {
            continue;
        }
        // The neighbours over the surface fan, each once, in the order the fan gives them: the
        // far corner of one triangle is the near corner of the next (`dest` of the next
        // half-edge), so only the last triangle's far corner is added.
        mesh.surface_fan_into(v, &mut fan);
        let far = fan.last().map(|&h| mesh.origin(prev(h)));
        for n in fan.iter().map(|&h| mesh.dest(h)).chain(far) {
            if !mesh.is_floor(n) && !side.contains(n) {
                side.insert(n, sigma);
                queue.push_back(n);
            }
        }
        if !wanted || (!inputs.fixed.is_empty() && inputs.fixed.contains(&v)) {
            continue;
        }
        if let Some(Kept {
            mut field_at,
            taper,
            correction,
        }) = kept
        {
            if taper {
                field_at.taper = taper_at(tips, field_at.nearest, inputs.taper_len);
            }
            if correction && onto_path {
                blends.ask(field.len() as u32, p);
            }
            field.push(field_at);
            continue;
        }
        let taper = taper_at(tips, c, inputs.taper_len);
        let falloff = {
            let s2 = (dist / r) * (dist / r);
            (1.0 - s2) * (1.0 - s2)
        };
        if onto_path {
            blends.ask(field.len() as u32, p);
        }
        field.push(FieldAt {
            vertex: v,
            segment: i as u32,
            rest: p,
            nearest: c,
            dist,
            sigma,
            taper,
            falloff,
            correction: DVec3::ZERO,
        });
    }
    field
}

/// The side (`±1` along the frame's lateral) lip copy `v` opens to, from its own surface
/// triangles: they lie left of the lip `y → v → x` (the first and last edges of its surface
/// fan), so the side is `+1` when that lip runs along the path. `0` when `v` is no lip (a
/// closed surface fan) or the lip runs across the path.
fn lip_side(mesh: &DynMesh, v: u32, frame: &Frame, fan: &mut Vec<u32>) -> f64 {
    let closed = mesh.fan_into(v, fan);
    if closed && !fan.iter().any(|&h| mesh.is_wall(h / 3)) {
        return 0.0;
    }
    if !mesh.surface_fan_into(v, fan) {
        return 0.0;
    }
    let (Some(&first), Some(&last)) = (fan.first(), fan.last()) else {
        return 0.0;
    };
    let along = mesh.pos(mesh.dest(first)) - mesh.pos(mesh.origin(prev(last)));
    let d = along.dot(frame.tangent);
    if d.abs() <= 1e-6 * along.length() {
        0.0
    } else {
        d.signum()
    }
}
