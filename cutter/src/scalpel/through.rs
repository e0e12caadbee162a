//! Cutting through: a blade deeper than the structure is thick.
//!
//! When a groove starts on a closed surface and the blade's depth reaches the opposite side of
//! the structure (a ray from the start point along the inward normal meets a surface facing away
//! before `depth`), the stroke cuts a slit on the near side and, in step, a slit on the far side
//! under it (the far cut follows, for each sample, where the ray from it along the inward normal
//! leaves the structure: [`ray_hit_near`], searched near the far cut; where that is not found,
//! the sample moved by the last thickness), and joins their lips with two walls. The result is
//! a slot through the structure: a closed surface stays closed and its genus grows by one (χ
//! drops by 2). A slot cannot open into another cut or a boundary (its end there would not
//! close): where it reaches one, it ends at its last tip and the stroke starts a new slot past
//! it (`Scalpel::step`, `start_cut`; the new far side found by [`ray_hit_near`]). Both tips
//! landing on another slot's two end vertices is such a meeting too (`Scalpel::far_tip`: that
//! slot's end edge joins them already, and walls here would use it a second time).
//!
//! Walls: the near slit's left lip `t0 … tK` and the far slit's left lip `f0 … fM` (both in
//! stroke order; the far surface faces the other way, so its lip on the same side is the one
//! running backwards) are joined by a strip of `K + M` triangles, merged by normalized arc length;
//! the right lips likewise. Both strips share the end edges `t0 f0` and `tK fM` (the crack tips
//! are single vertices), so the slot closes at its ends. The walls are rebuilt for the whole
//! stroke in each step's temporary part (cost proportional to the stroke, not the mesh).

use std::collections::HashMap;

use glam::DVec3;

use super::cut_point::closest_on_triangle;
use super::dyn_mesh::DynMesh;
use super::groove::find_lips;

/// The first surface (non-wall) triangle hit by the ray `origin + s · dir` (`s > 0`), ignoring
/// triangles around vertex `skip` and its copies: `(triangle, barycentric weights, s)`. A linear
/// scan, used only where a stroke starts (`begin_stroke`).
pub fn ray_first_hit(
    mesh: &DynMesh,
    origin: DVec3,
    dir: DVec3,
    skip: u32,
) -> Option<(u32, DVec3, f64)> {
    let mut best: Option<(u32, DVec3, f64)> = None;
    for (t, tri) in mesh.triangles().iter().enumerate() {
        if mesh.is_wall(t as u32) || tri.iter().any(|&v| mesh.same_point(v, skip)) {
            continue;
        }
        let [a, b, c] = tri.map(|v| mesh.pos(v));
        if let Some(s) = ray_triangle(origin, dir, a, b, c)
            && best.is_none_or(|(_, _, bs)| s < bs)
        {
            let hit = origin + dir * s;
            best = Some((t as u32, closest_on_triangle(hit, a, b, c), s));
        }
    }
    best
}

/// The surface triangle facing away from `dir` (a far side) hit by the ray `origin + s · dir`
/// (`s > 0`) nearest `expected` along the ray, searched best-first outward from vertex `v`'s
/// triangles (by the distance of each triangle's bounding box from `origin + expected · dir`,
/// over twins, walls included as passages), at most `limit` triangles: `(triangle,
/// barycentric weights, s)`. Cost independent of the mesh size: where a through-cut follows
/// its far side step by step, and where it restarts inside a stroke.
pub fn ray_hit_near(
    mesh: &DynMesh,
    v: u32,
    origin: DVec3,
    dir: DVec3,
    expected: f64,
    limit: usize,
) -> Option<(u32, DVec3, f64)> {
    // (triangle, weights, s, |s - expected|)
    let mut best: Option<(u32, DVec3, f64, f64)> = None;
    super::cut_point::visit_near(
        mesh,
        v,
        origin + dir * expected,
        limit,
        |t, box_distance| {
            if best.is_some_and(|b| box_distance >= b.3) {
                return false;
            }
            if !mesh.is_wall(t) && mesh.face_normal_scaled(t).dot(dir) > 0.0 {
                let [a, b, c] = mesh.triangles()[t as usize].map(|x| mesh.pos(x));
                if let Some(s) = ray_triangle(origin, dir, a, b, c)
                    && best.is_none_or(|b| (s - expected).abs() < b.3)
                {
                    let w = closest_on_triangle(origin + dir * s, a, b, c);
                    best = Some((t, w, s, (s - expected).abs()));
                }
            }
            true
        },
    );
    best.map(|(t, w, s, _)| (t, w, s))
}

/// Parameter `s > 0` where the ray `origin + s · dir` meets triangle `(a, b, c)`
/// (Möller–Trumbore), if it does.
fn ray_triangle(origin: DVec3, dir: DVec3, a: DVec3, b: DVec3, c: DVec3) -> Option<f64> {
    let (e1, e2) = (b - a, c - a);
    let p = dir.cross(e2);
    let det = e1.dot(p);
    if det.abs() <= f64::MIN_POSITIVE {
        return None;
    }
    let inv = 1.0 / det;
    let s0 = origin - a;
    let u = s0.dot(p) * inv;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let qv = s0.cross(e1);
    let v = dir.dot(qv) * inv;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let s = e2.dot(qv) * inv;
    (s > 0.0).then_some(s)
}

/// The lip half-edges of each segment of `path`: `(a → b side, b → a side)`.
fn lips(mesh: &DynMesh, path: &[u32]) -> Option<Vec<(u32, u32)>> {
    path.windows(2)
        .map(|w| find_lips(mesh, w[0], w[1]))
        .collect()
}

/// Normalized arc-length parameter of each vertex of `path`.
fn params(mesh: &DynMesh, path: &[u32]) -> Vec<f64> {
    let mut out = vec![0.0];
    let mut total = 0.0;
    for w in path.windows(2) {
        total += mesh.pos(w[0]).distance(mesh.pos(w[1]));
        out.push(total);
    }
    if total > 0.0 {
        out.iter_mut().for_each(|x| *x /= total);
    }
    out
}

/// One side's wall: a strip between the near lip `near` (half-edges, one per near segment) and
/// the far lip `far`; `near_forward` / `far_forward` tell whether each lip's half-edges run in
/// stroke order. Wall half-edges not on a lip wait in `frontier` for their twin. Ties in arc
/// length go to the near lip on one side and to the far lip on the other, so that the two
/// strips never both use an edge between two crack tips (which are shared by both sides).
#[allow(clippy::too_many_arguments)]
fn strip(
    mesh: &mut DynMesh,
    near: &[u32],
    near_forward: bool,
    near_params: &[f64],
    far: &[u32],
    far_forward: bool,
    far_params: &[f64],
    ends: (u32, u32, u32, u32),
    near_on_tie: bool,
    frontier: &mut HashMap<(u32, u32), u32>,
) {
    // Vertex `i` of a lip (in stroke order) from its half-edges.
    let vertex = |mesh: &DynMesh, lip: &[u32], forward: bool, i: usize, first: u32, last: u32| {
        if lip.is_empty() {
            return first;
        }
        if i == 0 {
            first
        } else if i == lip.len() {
            last
        } else if forward {
            mesh.origin(lip[i])
        } else {
            mesh.dest(lip[i])
        }
    };
    let (k, m) = (near.len(), far.len());
    let (mut i, mut j) = (0usize, 0usize);
    while i < k || j < m {
        let (a, b) = (near_params.get(i + 1), far_params.get(j + 1));
        let take_near = j == m || (i < k && (a < b || (near_on_tie && a == b)));
        let (lip, apex) = if take_near {
            let apex = vertex(mesh, far, far_forward, j, ends.2, ends.3);
            i += 1;
            (near[i - 1], apex)
        } else {
            let apex = vertex(mesh, near, near_forward, i, ends.0, ends.1);
            j += 1;
            (far[j - 1], apex)
        };
        let (u, w) = (mesh.origin(lip), mesh.dest(lip));
        let tri = [w, u, apex];
        let t = mesh.push_wall_tri(tri);
        mesh.link(3 * t, lip);
        for e in 1..3u32 {
            let h = 3 * t + e;
            let (a, b) = (tri[e as usize], tri[((e + 1) % 3) as usize]);
            if let Some(g) = frontier.remove(&(b, a)) {
                mesh.link(h, g);
            } else {
                frontier.insert((a, b), h);
            }
        }
        mesh.refresh_vert_he(t);
    }
}

/// Joins the lips of the near slit `near` and the far slit `far` (paths in stroke order, from
/// crack tip to crack tip) with walls. Returns false (the caller rolls back) when a lip is
/// missing or the walls do not close.
pub fn build_walls(mesh: &mut DynMesh, near: &[u32], far: &[u32]) -> bool {
    if near.len() < 2 && far.len() < 2 {
        return true;
    }
    let (Some(nl), Some(fl)) = (lips(mesh, near), lips(mesh, far)) else {
        return false;
    };
    let (np, fp) = (params(mesh, near), params(mesh, far));
    let near_ab: Vec<u32> = nl.iter().map(|l| l.0).collect();
    let near_ba: Vec<u32> = nl.iter().map(|l| l.1).collect();
    let far_ab: Vec<u32> = fl.iter().map(|l| l.0).collect();
    let far_ba: Vec<u32> = fl.iter().map(|l| l.1).collect();
    let (n0, n1) = (near[0], near[near.len() - 1]);
    let (f0, f1) = (far[0], far[far.len() - 1]);
    // The far surface faces the other way: its lip on the near lip `a → b`'s side runs `b → a`.
    // Try that pairing, then the other one (a fold can flip it).
    for swap in [false, true] {
        let mark = mesh.mark();
        let mut frontier = HashMap::new();
        let (far_left, far_left_fwd, far_right, far_right_fwd) = if swap {
            (&far_ab, true, &far_ba, false)
        } else {
            (&far_ba, false, &far_ab, true)
        };
        let ends = (n0, n1, f0, f1);
        strip(
            mesh,
            &near_ab,
            true,
            &np,
            far_left,
            far_left_fwd,
            &fp,
            ends,
            true,
            &mut frontier,
        );
        strip(
            mesh,
            &near_ba,
            false,
            &np,
            far_right,
            far_right_fwd,
            &fp,
            ends,
            false,
            &mut frontier,
        );
        if frontier.is_empty() {
            return true;
        }
        mesh.rollback(mark);
    }
    false
}
