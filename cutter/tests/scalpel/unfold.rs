//! The opening must not fold the surface over: on a bumpy surface (like the head skin) a
//! groove's cut runs along mesh edges that detour around the drawn path, and vertices of one
//! surface triangle framed by different cut segments can move so that it turns over (a bright
//! shard or a dark crack on the opened lip). `scalpel::unfold` bounds the turn; its own tests
//! build folds directly, this one checks whole opened grooves.

use super::*;

/// A coarse sphere of radius `r` with every vertex pushed in or out by up to `bump` (fixed
/// seeds), so cuts along its edges zigzag like on a scanned skin surface.
pub(super) fn bumpy_sphere(r: f64, bump: f64, seed: u64) -> Mesh {
    let sphere = csg::testkit::icosphere(5, r);
    let mut rng = csg::testkit::SplitMix(seed);
    let positions = sphere
        .positions
        .iter()
        .map(|p| *p * (1.0 + bump * (2.0 * rng.next_f64() - 1.0)))
        .collect();
    Mesh::new(positions, sphere.triangles.clone()).unwrap()
}

/// The largest angle (degrees) by which a surface triangle's normal turns when `shown` replaces
/// the rest positions.
pub(super) fn largest_turn(s: &Scalpel, shown: &[DVec3]) -> f64 {
    let m = s.dyn_mesh();
    let mut worst = 0.0f64;
    for tri in 0..m.triangle_count() as u32 {
        if m.is_wall(tri) {
            continue;
        }
        let [a, b, c] = m.triangles()[tri as usize];
        let rest = (m.pos(b) - m.pos(a)).cross(m.pos(c) - m.pos(a));
        let [a, b, c] = [a, b, c].map(|v| shown[v as usize]);
        let now = (b - a).cross(c - a);
        if rest.length() == 0.0 {
            continue;
        }
        let turn = if now.length() == 0.0 {
            180.0
        } else {
            rest.angle_between(now).to_degrees()
        };
        worst = worst.max(turn);
    }
    worst
}

#[test]
fn opened_grooves_on_a_bumpy_surface_do_not_fold() {
    use cutter::scalpel::OpenOptions;
    use cutter::scalpel::cut_point::closest_face;
    use cutter::scalpel::dffd::open_positions;
    use cutter::scalpel::unfold::MAX_TURN_DEG;
    let r = 60.0;
    let mut steep = 0;
    let mut cases = 0;
    for seed in 1..=6u64 {
        let mesh = bumpy_sphere(r, 0.012, seed);
        let mut s = Scalpel::new(&mesh, ScalpelOptions::default().with_depth(4.0)).unwrap();
        // A wavy stroke over the front, drawn as a user would (every sample on the surface).
        let path: Vec<DVec3> = (0..=40)
            .map(|i| {
                let u = i as f64 / 40.0;
                let lon = -0.5 + 1.0 * u;
                let lat = 0.08 * (u * 3.1).sin();
                DVec3::new(lat.cos() * lon.sin(), -lat.cos() * lon.cos(), lat.sin()) * r
            })
            .filter_map(|q| {
                let (t, w, _) = closest_face(s.dyn_mesh(), q)?;
                let m = s.dyn_mesh();
                let [a, b, c] = m.triangles()[t as usize].map(|v| m.pos(v));
                Some(a * w.x + b * w.y + c * w.z)
            })
            .collect();
        if let Err(e) = s.cut_stroke(&path) {
            println!("seed {seed}: {e}");
            continue;
        }
        s.advance_clock(1.0);
        let open = OpenOptions {
            width: 3.0,
            window: 0.5,
        };
        let shown = open_positions(&s, &open, s.clock());
        let turn = largest_turn(&s, &shown);
        println!("seed {seed}: largest surface turn {turn:.1}°");
        assert!(
            turn <= MAX_TURN_DEG + 1e-6,
            "seed {seed}: a surface triangle turned {turn:.1}° when the groove opened"
        );
        cases += 1;
        steep += usize::from(turn > 30.0);
    }
    assert!(cases >= 4, "only {cases} strokes were cut");
    println!("{steep} of {cases} strokes turn a triangle by more than 30°");
}
