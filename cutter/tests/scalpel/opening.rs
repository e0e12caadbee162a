//! The opening of the incision (the discontinuous deformation of `scalpel::dffd`).

use super::*;

#[test]
fn s22_opening_reaches_its_width_and_leaves_the_rest_alone() {
    use cutter::scalpel::OpenOptions;
    use cutter::scalpel::dffd::open_positions;
    let (_, mut s) = sheet_delta(&[line(p(3.3, 10.5), p(16.7, 10.5), 0.5)]);
    s.advance_clock(1.0);
    let open = OpenOptions {
        width: 0.6,
        window: 0.5,
    };
    let shown = open_positions(&s, &open, s.clock());
    let m = s.dyn_mesh();
    // Lip copies at x = 10 (mid-slit) are 0.6 apart; far vertices did not move (bitwise).
    let mid: Vec<u32> = (0..m.vertex_count() as u32)
        .filter(|&v| (m.pos(v) - p(10.0, 10.5)).length() < 1e-9)
        .collect();
    assert_eq!(mid.len(), 2, "two lips at the middle");
    let gap = shown[mid[0] as usize].distance(shown[mid[1] as usize]);
    assert!((gap - 0.6).abs() <= 0.03, "gap {gap}");
    for v in 0..m.vertex_count() {
        let d = (m.pos(v as u32).y - 10.5).abs();
        if d > 3.0 * 0.6 + 1e-9 {
            assert_eq!(
                shown[v],
                m.pos(v as u32),
                "vertex {v} outside the support moved"
            );
        }
    }
    // Just after the cut the newest part is still closed (trailing window).
    let early = open_positions(&s, &open, s.clock() - 1.0);
    assert!(early[mid[0] as usize].distance(early[mid[1] as usize]) < gap);
}

/// A groove along a wavy path over a sphere (about the patella's size, as drawn on the knee)
/// opened to width `w`: the cut, the scalpel and the displayed positions.
fn opened_wavy_groove(w: f64) -> (Scalpel, Vec<DVec3>) {
    use cutter::scalpel::OpenOptions;
    use cutter::scalpel::dffd::open_positions;
    let r = 20.0;
    let sphere = csg::testkit::icosphere(5, r);
    let mut s = Scalpel::new(&sphere, ScalpelOptions::default().with_depth(3.0)).unwrap();
    let path = wavy_arc(r, 60);
    s.cut_stroke(&path).unwrap();
    s.advance_clock(1.0);
    let open = OpenOptions {
        width: w,
        window: 0.5,
    };
    let shown = open_positions(&s, &open, s.clock());
    (s, shown)
}

/// The torn opening: both lips of a groove used to take the side of the long wall triangles in
/// their fans (so parts of the path did not open) and each vertex moved across the mesh edge
/// nearest it rather than across the path (ragged lips, folded triangles). Along the whole
/// path, away from its tips, the two lips are now apart by most of the width, moving to opposite
/// sides, and no surface triangle folds over or is torn long.
#[test]
fn groove_opening_has_two_clean_lips_along_the_whole_path() {
    use cutter::scalpel::dffd::frames;
    let w = 2.0;
    let (s, shown) = opened_wavy_groove(w);
    let m = s.dyn_mesh();
    let t = topo(&s);
    assert!(t.closed && t.manifold, "{t:?}");
    let segments = s.segments();
    let frames = frames(segments, w);
    let (first, last) = (segments[0].pa, segments[segments.len() - 1].pb);
    let mut checked = 0;
    for (seg, frame) in segments.iter().zip(&frames) {
        let v = seg.b;
        let p = m.pos(v);
        if p.distance(first) < 2.0 * w || p.distance(last) < 2.0 * w {
            continue;
        }
        let lips: Vec<u32> = std::iter::once(v).chain(m.copies(v)).collect();
        assert_eq!(lips.len(), 2, "a groove lip vertex has two copies");
        let moved: Vec<f64> = lips
            .iter()
            .map(|&c| (shown[c as usize] - p).dot(frame.lateral))
            .collect();
        let gap = shown[lips[0] as usize].distance(shown[lips[1] as usize]);
        assert!(
            gap >= 0.7 * w && moved[0] * moved[1] < 0.0,
            "lips at {p:?} apart by {gap} (width {w}), moved {moved:?} across the path"
        );
        checked += 1;
    }
    assert!(checked >= 10, "only {checked} lip vertices checked");
    // No surface triangle folds over or is stretched across the gap.
    for tri in 0..m.triangle_count() as u32 {
        if m.is_wall(tri) {
            continue;
        }
        let [a, b, c] = m.triangles()[tri as usize];
        let rest = (m.pos(b) - m.pos(a)).cross(m.pos(c) - m.pos(a));
        let [a, b, c] = [a, b, c].map(|v| shown[v as usize]);
        let now = (b - a).cross(c - a);
        assert!(
            now.dot(rest) > 0.0 && now.length() <= 3.0 * rest.length(),
            "surface triangle {tri} folded or torn by the opening: area {} -> {}",
            rest.length() / 2.0,
            now.length() / 2.0
        );
    }
    // The groove walls face out of the sphere (the viewer above the cut sees them).
    let (mut up, mut all) = (0.0, 0.0);
    for tri in (0..m.triangle_count() as u32).filter(|&t| m.is_wall(t)) {
        let [a, b, c] = m.triangles()[tri as usize].map(|v| shown[v as usize]);
        let n = (b - a).cross(c - a);
        all += n.length();
        if n.dot((a + b + c).normalize()) > 0.0 {
            up += n.length();
        }
    }
    println!("wall area facing out: {:.3}", up / all);
    assert!(
        up >= 0.9 * all,
        "only {:.2} of the wall area faces out",
        up / all
    );
}
