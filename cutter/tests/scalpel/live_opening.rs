//! The opening kept between steps (`scalpel::live_opening`) against the opening computed from
//! scratch (`dffd::open_displacements`): after every step of long strokes, the same vertices
//! move to the same positions, bit for bit; and a step recomputes a small part of them.

use std::collections::BTreeMap;

use super::*;
use cutter::scalpel::OpenOptions;
use cutter::scalpel::dffd::open_displacements;
use cutter::scalpel::live_opening::LiveOpening;

/// Both openings of `s` now; fails naming the first vertex that differs or is missing.
fn assert_same(s: &Scalpel, live: &LiveOpening, open: &OpenOptions, what: &str) {
    let scratch: BTreeMap<u32, [u64; 3]> = open_displacements(s, open, s.clock())
        .into_iter()
        .map(|(v, p)| (v, p.to_array().map(f64::to_bits)))
        .collect();
    let kept: BTreeMap<u32, [u64; 3]> = live
        .moved()
        .iter()
        .map(|(&v, p)| (v, p.to_array().map(f64::to_bits)))
        .collect();
    for (v, p) in &scratch {
        match kept.get(v) {
            None => panic!("{what}: vertex {v} moved from scratch, not by the live opening"),
            Some(q) => assert_eq!(q, p, "{what}: vertex {v} differs"),
        }
    }
    for v in kept.keys() {
        assert!(
            scratch.contains_key(v),
            "{what}: vertex {v} moved by the live opening only"
        );
    }
}

/// Strokes cut sample by sample with the live opening updated after each step (and each
/// stroke's end, and a clock advanced past the window), compared with the opening from scratch
/// every `every` steps. Returns the most vertices one incremental update recomputed and the
/// most the opening moved.
fn compare_along(
    mesh: &Mesh,
    depth: f64,
    strokes: &[Vec<DVec3>],
    open: OpenOptions,
    every: usize,
) -> (usize, usize) {
    let mut s = Scalpel::new(mesh, ScalpelOptions::default().with_depth(depth)).unwrap();
    let mut live = LiveOpening::new();
    let (mut most_recomputed, mut most_moved) = (0, 0);
    let mut step = 0;
    for (k, stroke) in strokes.iter().enumerate() {
        s.begin_stroke(stroke[0]).unwrap();
        live.update(&s, &open, s.clock());
        for &q in &stroke[1..] {
            s.step(q).unwrap();
            let u = live.update(&s, &open, s.clock());
            step += 1;
            if !u.full {
                most_recomputed = most_recomputed.max(u.vertices);
            }
            most_moved = most_moved.max(live.moved().len());
            if step % every == 0 {
                assert_same(&s, &live, &open, &format!("stroke {k} step {step}"));
            }
        }
        s.end_stroke().unwrap();
        live.update(&s, &open, s.clock());
        assert_same(&s, &live, &open, &format!("stroke {k} ended"));
        s.advance_clock(open.window);
        live.update(&s, &open, s.clock());
        assert_same(&s, &live, &open, &format!("stroke {k} opened"));
    }
    assert!(s.undo_stroke());
    live.update(&s, &open, s.clock());
    assert_same(&s, &live, &open, "last stroke undone");
    (most_recomputed, most_moved)
}

/// A groove crossing a long wavy groove, on a sphere the size of a patella, opened 2 wide:
/// equal after every step. Then, on a larger sphere, a long groove opened 1.5 wide: equal, and
/// no step recomputes half of what the opening moves.
#[test]
fn live_opening_equals_the_opening_from_scratch_on_crossing_grooves() {
    let r = 20.0;
    let sphere = csg::testkit::icosphere(6, r);
    let crossing = great_arc(
        DVec3::new(0.1, -1.0, 0.0),
        DVec3::new(0.3, 0.0, 1.0),
        r,
        -0.4,
        0.4,
        80,
    );
    let strokes = vec![wavy_arc(r, 160), crossing];
    let open = OpenOptions {
        width: 2.0,
        window: 0.5,
    };
    compare_along(&sphere, 3.0, &strokes, open, 1);
    let r = 40.0;
    let sphere = csg::testkit::icosphere(7, r);
    let open = OpenOptions {
        width: 1.5,
        window: 0.5,
    };
    let (recomputed, moved) = compare_along(&sphere, 1.0, &[wavy_arc(r, 200)], open, 1);
    assert!(
        recomputed * 2 < moved,
        "a step recomputed {recomputed} of the {moved} vertices the opening moves"
    );
}

/// Slits (no depth) opened 1 wide with no time window, and the same with a window: equal
/// after every step.
#[test]
fn live_opening_equals_the_opening_from_scratch_on_slits() {
    let r = 20.0;
    let sphere = csg::testkit::icosphere(6, r);
    let strokes = vec![
        wavy_arc(r, 160),
        great_arc(
            DVec3::new(0.1, -1.0, 0.0),
            DVec3::new(0.3, 0.0, 1.0),
            r,
            -0.4,
            0.4,
            80,
        ),
    ];
    for window in [0.0, 0.5] {
        let open = OpenOptions { width: 1.0, window };
        compare_along(&sphere, 0.0, &strokes, open, 1);
    }
}

/// The live opening keeps each vertex's field between steps and reuses it where no changed
/// segment or crack tip reaches the vertex. A stroke undone and another cut over the same
/// place puts different segments at the same indices, and a groove crossing an opened one
/// changes segments cut long before: after every step, and while the clock alone advances in
/// small steps (only ramps change), the kept opening equals the opening from scratch.
#[test]
fn live_opening_keeps_no_stale_field_after_undo_and_recut_or_a_crossing() {
    let r = 20.0;
    let sphere = csg::testkit::icosphere(6, r);
    let open = OpenOptions {
        width: 2.0,
        window: 0.5,
    };
    let mut s = Scalpel::new(&sphere, ScalpelOptions::default().with_depth(2.0)).unwrap();
    let mut live = LiveOpening::new();
    let first = wavy_arc(r, 120);
    // The same place cut again along a slightly different path.
    let again: Vec<DVec3> = first
        .iter()
        .map(|p| (*p + DVec3::new(0.0, 0.0, 0.15)).normalize() * r)
        .collect();
    let crossing = great_arc(
        DVec3::new(0.05, -1.0, 0.0),
        DVec3::new(0.2, 0.0, 1.0),
        r,
        -0.35,
        0.35,
        70,
    );
    let cut = |s: &mut Scalpel, live: &mut LiveOpening, stroke: &[DVec3], what: &str| {
        s.begin_stroke(stroke[0]).unwrap();
        live.update(s, &open, s.clock());
        for (k, &q) in stroke[1..].iter().enumerate() {
            s.step(q).unwrap();
            live.update(s, &open, s.clock());
            assert_same(s, live, &open, &format!("{what} step {k}"));
        }
        s.end_stroke().unwrap();
        live.update(s, &open, s.clock());
        assert_same(s, live, &open, &format!("{what} ended"));
        // The clock alone: only the ramps of the last segments change.
        for k in 0..6 {
            s.advance_clock(0.1 * open.window);
            live.update(s, &open, s.clock());
            assert_same(s, live, &open, &format!("{what} clock {k}"));
        }
    };
    cut(&mut s, &mut live, &first, "first");
    assert!(s.undo_stroke());
    live.update(&s, &open, s.clock());
    assert_same(&s, &live, &open, "first undone");
    cut(&mut s, &mut live, &again, "cut again");
    cut(&mut s, &mut live, &crossing, "crossing");
    assert!(s.undo_stroke());
    live.update(&s, &open, s.clock());
    assert_same(&s, &live, &open, "crossing undone");
    cut(&mut s, &mut live, &crossing, "crossing again");
}
