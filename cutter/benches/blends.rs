//! The path corrections a walk of the opening asks for, blended beside it: our two-thread
//! pipeline (`scalpel::blend::with_blends`) against rayon doing the same, from the same run.
//!
//! The workload is a step of the live opening at a crossing of two grooves, in miniature: a
//! walk over 6,000 points that waits on memory at each (a dependent read in a 64 MB table, as
//! the walk waits on the mesh and the kept field) and asks for the blend at a third of them,
//! each over the 250 segment ends a crossing lists around a point. Three ways:
//! - one thread: every blend measured where it is asked;
//! - ours: batches of blends handed to one helper thread started for the walk (it sleeps
//!   between batches after a short spin, woken by the next); the rest measured by the walk's
//!   thread at the end;
//! - rayon: the walk in `rayon::scope`, every batch spawned as a task (each pool thread keeps
//!   its own blend cache), as a pool would be used for it.
//!
//! Between two walks the bench works 3 ms on one thread, as a step does. Prints the median
//! time of each over 200 walks, and ours against each. The live opening
//! needs ours faster than both (rayon's workers, woken per batch, joined too late on the
//! machines measured). Run: `cargo bench -p cutter --bench blends`.

use std::cell::RefCell;
use std::sync::Mutex;
use std::time::Instant;

use glam::DVec3;

use cutter::scalpel::blend::{Blend, BlendInputs, with_blends};
use cutter::scalpel::cut_grid::CutGrid;
use cutter::scalpel::step::CutSegment;

const WALKS: usize = 200;
const POINTS: usize = 6_000;
const BATCH: usize = 32;

/// A dependent read in `table` (the walk's wait on memory); returns the next index.
fn wait_on_memory(table: &[u64], i: usize) -> usize {
    (table[i] as usize) % table.len()
}

/// Between two walks a step does its other work on one thread (about 3 ms: the changes, the
/// unfolding), and any thread that waited for work has gone to sleep.
fn between_walks() {
    let t = Instant::now();
    let mut x = 1u64;
    while t.elapsed().as_secs_f64() < 3e-3 {
        x = std::hint::black_box(x.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1));
    }
}

fn median_ms(mut f: impl FnMut() -> f64) -> f64 {
    let mut times: Vec<f64> = (0..WALKS)
        .map(|_| {
            between_walks();
            let t = Instant::now();
            std::hint::black_box(f());
            t.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[WALKS / 2]
}

thread_local! {
    static BLEND: RefCell<(usize, Blend)> = RefCell::new((usize::MAX, Blend::default()));
}

fn main() {
    // Two grooves crossing: 0.4-long segments along x and along y through the origin.
    let mut segments = Vec::new();
    for k in -60..60 {
        let (a, b) = (k as f64 * 0.4, (k + 1) as f64 * 0.4);
        segments.push(CutSegment {
            a: 0,
            b: 1,
            pa: DVec3::new(a, 0.0, 0.0),
            pb: DVec3::new(b, 0.0, 0.0),
            normal: DVec3::Z,
            time: 0.0,
        });
        segments.push(CutSegment {
            a: 0,
            b: 1,
            pa: DVec3::new(0.0, a, 0.0),
            pb: DVec3::new(0.0, b, 0.0),
            normal: DVec3::Z,
            time: 0.0,
        });
    }
    let corrections: Vec<[DVec3; 2]> = (0..segments.len())
        .map(|i| [DVec3::new(0.01 * i as f64, 0.02, 0.0), DVec3::splat(0.003)])
        .collect();
    let r = 6.0;
    let grid = CutGrid::new(&segments, 2, r);
    let inputs = BlendInputs {
        grid: &grid,
        segments: &segments,
        corrections: &corrections,
        r,
    };
    // Points within the support of the crossing, in rows as a walk reaches them.
    let points: Vec<DVec3> = (0..POINTS)
        .map(|k| {
            let (u, v) = ((k % 80) as f64 * 0.15 - 6.0, (k / 80) as f64 * 0.16 - 6.0);
            DVec3::new(u, v, 0.01 * ((k * 7) % 13) as f64)
        })
        .collect();
    let table: Vec<u64> = (0..1u64 << 23)
        .map(|i| i.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 17)
        .collect();
    let walk_one = || {
        let mut blend = Blend::default();
        let mut i = 1;
        let mut sum = 0.0;
        for (k, &p) in points.iter().enumerate() {
            i = wait_on_memory(&table, i);
            if k % 3 == 0 {
                sum += blend.correction_at(&inputs, p).x;
            }
        }
        sum + i as f64
    };
    let walk_ours = || {
        let mut i = 1;
        let (walked, blended) = with_blends(inputs, |blends| {
            for (k, &p) in points.iter().enumerate() {
                i = wait_on_memory(&table, i);
                if k % 3 == 0 {
                    blends.ask(k as u32, p);
                }
            }
            i
        });
        blended.iter().map(|b| b.1.x).sum::<f64>() + walked as f64
    };
    let mut generation = 0usize;
    let mut walk_rayon = || {
        generation += 1;
        let walk = generation;
        let out = Mutex::new(Vec::new());
        let walked = rayon::scope(|scope| {
            let mut i = 1;
            let mut pending = Vec::with_capacity(BATCH);
            for (k, &p) in points.iter().enumerate() {
                i = wait_on_memory(&table, i);
                if k % 3 == 0 {
                    pending.push(p);
                    if pending.len() == BATCH {
                        let batch = std::mem::replace(&mut pending, Vec::with_capacity(BATCH));
                        let out = &out;
                        scope.spawn(move |_| {
                            let done: Vec<f64> = BLEND.with(|b| {
                                let mut b = b.borrow_mut();
                                if b.0 != walk {
                                    *b = (walk, Blend::default());
                                }
                                batch
                                    .iter()
                                    .map(|&p| b.1.correction_at(&inputs, p).x)
                                    .collect()
                            });
                            out.lock().expect("results").extend(done);
                        });
                    }
                }
            }
            let mut blend = Blend::default();
            let rest: Vec<f64> = pending
                .iter()
                .map(|&p| blend.correction_at(&inputs, p).x)
                .collect();
            out.lock().expect("results").extend(rest);
            i
        });
        out.into_inner().expect("results").iter().sum::<f64>() + walked as f64
    };
    assert_eq!(
        walk_one().to_bits(),
        walk_one().to_bits(),
        "the workload is deterministic"
    );
    let one = median_ms(walk_one);
    let ours = median_ms(walk_ours);
    let rayon = median_ms(&mut walk_rayon);
    println!(
        "a walk of {POINTS} points asking {} blends: one thread {one:.3} ms, ours (helper thread) \
         {ours:.3} ms, rayon {rayon:.3} ms; ours / one thread {:.2}, ours / rayon {:.2}",
        POINTS / 3,
        ours / one,
        ours / rayon
    );
}
