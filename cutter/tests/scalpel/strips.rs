//! Strip walls (`scalpel::groove`, "Wall shape"): a floor vertex under every lip vertex, so each
//! segment's wall on each lip is a quad of two triangles that does not fold, and the floor is a
//! smooth polyline under the path (its direction averaged along the path, not each vertex's
//! own normal on a noisy surface).

use super::lips::{groove_cases, projected_path};
use super::*;
use cutter::scalpel::DynMesh;
use cutter::scalpel::dyn_mesh::is_real;

/// Unit normal of triangle `t`.
fn normal(m: &DynMesh, t: u32) -> DVec3 {
    let [a, b, c] = m.triangles()[t as usize].map(|v| m.pos(v));
    (b - a).cross(c - a).normalize_or_zero()
}

/// The largest angle (degrees) between the normals of two wall triangles sharing an edge that
/// runs from a lip down to the floor (a quad's diagonal or the edge between two quads; the
/// floor edges and the edge under a crack tip, where the two lips' walls meet in a V, are left
/// out: there the triangles on either side are mirror images, their third corners copies of one
/// lip point).
fn worst_wall_fold(m: &DynMesh) -> f64 {
    let mut worst = 0.0f64;
    for t in (0..m.triangle_count() as u32).filter(|&t| m.is_wall(t)) {
        let tri = m.triangles()[t as usize];
        for k in 0..3 {
            let g = m.twin(3 * t + k);
            let (a, b) = (tri[k as usize], tri[(k as usize + 1) % 3]);
            if !is_real(g) || !m.is_wall(g / 3) || (m.is_floor(a) && m.is_floor(b)) {
                continue;
            }
            let third = |t: u32| {
                let x = m.triangles()[t as usize];
                x.into_iter().find(|&v| v != a && v != b).unwrap()
            };
            if m.same_point(third(t), third(g / 3)) {
                continue;
            }
            let c = normal(m, t).dot(normal(m, g / 3)).clamp(-1.0, 1.0);
            worst = worst.max(c.acos().to_degrees());
        }
    }
    worst
}

/// The floor polylines of the mesh's grooves (chains of edges between floor vertices), each as
/// its vertices in order.
fn floor_polylines(m: &DynMesh) -> Vec<Vec<u32>> {
    let mut next: std::collections::BTreeMap<u32, Vec<u32>> = Default::default();
    for t in (0..m.triangle_count() as u32).filter(|&t| m.is_wall(t)) {
        let tri = m.triangles()[t as usize];
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            if m.is_floor(a) && m.is_floor(b) {
                for (x, y) in [(a, b), (b, a)] {
                    let e = next.entry(x).or_default();
                    if !e.contains(&y) {
                        e.push(y);
                    }
                }
            }
        }
    }
    let mut seen = std::collections::BTreeSet::new();
    let mut out = Vec::new();
    for (&start, n) in &next {
        if n.len() != 1 || seen.contains(&start) {
            continue;
        }
        let mut line = vec![start];
        seen.insert(start);
        while let Some(&y) = next[line.last().unwrap()]
            .iter()
            .find(|y| !seen.contains(*y))
        {
            seen.insert(y);
            line.push(y);
        }
        out.push(line);
    }
    out
}

/// The largest turning angle (degrees) of the polyline `p` at the scale of the walls: at each
/// vertex, between the chords to the vertices at least `span` before and after it (the cut
/// splits some edges close to a vertex: lip edges, and floor edges under them, much shorter
/// than the blade is deep, where a wobble of a few hundredths of an edge turns a polyline by
/// tens of degrees over one short edge). Vertices within `ends` (along the polyline) of either
/// end are left out: there the floor rises to the crack tips by design
/// ([`cutter::scalpel::taper`]).
fn worst_turn(p: &[DVec3], span: f64, ends: f64) -> f64 {
    let mut arc = vec![0.0];
    for w in p.windows(2) {
        arc.push(arc.last().unwrap() + w[0].distance(w[1]));
    }
    let total = *arc.last().unwrap();
    let mut worst = 0.0f64;
    for i in 1..p.len().saturating_sub(1) {
        if arc[i] < ends || total - arc[i] < ends {
            continue;
        }
        let back = (0..i).rev().find(|&j| p[j].distance(p[i]) >= span);
        let ahead = (i + 1..p.len()).find(|&j| p[j].distance(p[i]) >= span);
        if let (Some(j), Some(k)) = (back, ahead) {
            worst = worst.max((p[i] - p[j]).angle_between(p[k] - p[i]).to_degrees());
        }
    }
    worst
}

/// The two lips of the one groove in the mesh, each as its points from one tip to the other:
/// the lip edges (surface half-edges with a wall across) chain into one loop through both tips
/// (a crack tip is not duplicated), split at the loop's points nearest the drawn path's ends.
fn lip_polylines(m: &DynMesh, from: DVec3, to: DVec3) -> Vec<Vec<DVec3>> {
    let mut next = std::collections::BTreeMap::new();
    for t in (0..m.triangle_count() as u32).filter(|&t| !m.is_wall(t)) {
        let tri = m.triangles()[t as usize];
        for k in 0..3 {
            let g = m.twin(3 * t + k as u32);
            if is_real(g) && m.is_wall(g / 3) {
                next.insert(tri[k], tri[(k + 1) % 3]);
            }
        }
    }
    let Some(&start) = next.keys().next() else {
        return Vec::new();
    };
    let mut lap = vec![start];
    while let Some(&w) = next.get(lap.last().unwrap()) {
        if w == start || lap.len() > next.len() {
            break;
        }
        lap.push(w);
    }
    let pts: Vec<DVec3> = lap.iter().map(|&v| m.pos(v)).collect();
    let nearest = |x: DVec3| {
        (0..pts.len())
            .min_by(|&i, &j| pts[i].distance(x).total_cmp(&pts[j].distance(x)))
            .unwrap()
    };
    let (a, b) = (nearest(from), nearest(to));
    let (a, b) = (a.min(b), a.max(b));
    let mut other: Vec<DVec3> = pts[b..].to_vec();
    other.extend_from_slice(&pts[..=a]);
    vec![pts[a..=b].to_vec(), other]
}

/// Floor vertices per surface vertex on the lips (one per lip vertex for strip walls, less one
/// at each crack tip).
fn floor_vertices(m: &DynMesh) -> usize {
    (0..m.vertex_count() as u32)
        .filter(|&v| m.is_floor(v))
        .count()
}

/// The walls of one groove, measured on the sphere and on the real meshes: at most 4 wall
/// triangles per segment and 8 around a floor vertex (T4, no fan), a floor vertex under every
/// interior path vertex on one floor polyline, no two neighbouring wall triangles folded over
/// (normals more than 90° apart), and a floor that turns no more than the lips above it.
/// Measured (sphere depth 3, patella, femur, skin): at most 6, 8, 6, 8 wall triangles around a
/// floor vertex (16, 20, 14, 12 with floor vertices shared along the path); folds 40°, 54°, 18°,
/// 55° (12°, 123°, 180°, 134°); floor turns 12°, 20°, 7°, 48° under lips turning 14°, 22°, 6°,
/// 58° (18°, 16°, 24°, 115° under 13°, 34°, 45°, 139°).
#[test]
fn groove_walls_are_strips_under_a_smooth_floor() {
    for (name, mesh, path, depth) in groove_cases(&[3.0]) {
        let mut s = Scalpel::new(&mesh, ScalpelOptions::default().with_depth(depth)).unwrap();
        s.cut_stroke(&path).unwrap();
        let m = s.dyn_mesh();
        let b = survey::element_budget(&mesh, m);
        let floors = floor_vertices(m);
        let lines = floor_polylines(m);
        let fold = worst_wall_fold(m);
        // Away from the tapers at the tips (two blade depths, and one more: a floor vertex there
        // sits under the path up to a depth across).
        let taper = (cutter::scalpel::taper::TAPER_DEPTHS + 1.0) * depth;
        let turn = floor_polylines(m)
            .iter()
            .map(|l| {
                let p: Vec<DVec3> = l.iter().map(|&v| m.pos(v)).collect();
                worst_turn(&p, 0.5 * depth, taper)
            })
            .fold(0.0, f64::max);
        // The floor runs under the lips: it may turn as much as they do (on the noisy head skin
        // the cut wobbles around the drawn path by up to a quarter of an edge), at the same
        // scale, no more.
        let drawn: Vec<DVec3> = projected_path(&mesh, &path).iter().map(|d| d.0).collect();
        let path_turn = worst_turn(&drawn, 0.5 * depth, taper);
        let lip_turn = lip_polylines(m, drawn[0], drawn[drawn.len() - 1])
            .iter()
            .map(|l| worst_turn(l, 0.5 * depth, taper))
            .fold(0.0, f64::max);
        println!(
            "{name}: {} wall triangles on {} lip edges ({:.2} per segment, at most {} around a floor vertex), {floors} floor vertices in {} polyline(s), worst fold {fold:.1}°, worst floor turn {turn:.1}° (lips {lip_turn:.1}°, drawn path {path_turn:.1}°)",
            b.wall_triangles,
            b.lip_edges,
            b.walls_per_segment_mean,
            b.walls_per_floor_vertex_max,
            lines.len()
        );
        assert!(b.walls_per_segment_mean <= 4.0, "{name}: T4 {b:?}");
        assert!(b.walls_per_floor_vertex_max <= 8, "{name}: T4 {b:?}");
        // One floor vertex per interior path vertex: a segment per lip edge pair, one path
        // vertex fewer than segments inside.
        assert_eq!(floors + 1, b.lip_edges / 2, "{name}: floor vertices");
        assert_eq!(lines.len(), 1, "{name}: the floor is one polyline");
        assert_eq!(lines[0].len(), floors, "{name}: every floor vertex on it");
        assert!(fold < 90.0, "{name}: wall triangles folded over by {fold}°");
        assert!(
            turn <= lip_turn.max(15.0) + 5.0,
            "{name}: the floor turns by {turn}°, the lips by {lip_turn}°"
        );
    }
}
