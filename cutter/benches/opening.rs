//! The opening's cost per frame (notes/scalpel.md §4 P4: ≤ 1 ms for ≤ 10k affected vertices).
//!
//! A wavy groove across a sphere of ~330k triangles (radius 20, about a patella's size), opened
//! 2 wide (support 3 widths on either side, about 10k vertices). Prints the median time of
//! `open_displacements` (lips onto the drawn path) and of `open_displacements_along_cut` (the
//! rest-pose cut shifted sideways, the opening before it followed the path) over 30 runs, the
//! vertices each moves and the ratio of the two times; target ≤ 1 ms at ≤ 10k vertices.
//! Run: `cargo bench -p cutter --bench opening`.

use std::time::Instant;

use glam::DVec3;

use cutter::scalpel::dffd::{open_displacements, open_displacements_along_cut};
use cutter::scalpel::{OpenOptions, Scalpel, ScalpelOptions};

const RUNS: usize = 30;

fn median_ms(mut f: impl FnMut() -> usize) -> (f64, usize) {
    let mut times = Vec::with_capacity(RUNS);
    let mut moved = 0;
    for _ in 0..RUNS {
        let t = Instant::now();
        moved = std::hint::black_box(f());
        times.push(t.elapsed().as_secs_f64() * 1e3);
    }
    times.sort_by(f64::total_cmp);
    (times[RUNS / 2], moved)
}

fn main() {
    let r = 20.0;
    let sphere = csg::testkit::icosphere(7, r);
    let samples: Vec<DVec3> = (0..=120)
        .map(|i| {
            let u = i as f64 / 120.0;
            let lon = -0.6 + 1.2 * u;
            let lat = 0.12 * (u * std::f64::consts::TAU).sin();
            DVec3::new(lat.cos() * lon.sin(), -lat.cos() * lon.cos(), lat.sin()) * r
        })
        .collect();
    let mut s = Scalpel::new(&sphere, ScalpelOptions::default().with_depth(3.0)).unwrap();
    s.cut_stroke(&samples).unwrap();
    s.advance_clock(1.0);
    let open = OpenOptions {
        width: 2.0,
        window: 0.5,
    };
    let (path_ms, path_moved) = median_ms(|| open_displacements(&s, &open, s.clock()).len());
    let (cut_ms, cut_moved) =
        median_ms(|| open_displacements_along_cut(&s, &open, s.clock()).len());
    println!(
        "opening ({} triangles, {} segments): onto the path {path_ms:.3} ms ({path_moved} vertices), \
         along the cut {cut_ms:.3} ms ({cut_moved} vertices), ratio {:.2}; target <= 1 ms at <= 10k vertices",
        sphere.triangles.len(),
        s.segments().len(),
        path_ms / cut_ms
    );
}
