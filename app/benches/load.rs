//! Loading benchmarks: a 1M-triangle binary STL and OBJ, and `cutaway info` on a 2M-triangle
//! OBJ (read, weld, validate, regions, measures). The inputs are geodesic spheres generated here
//! into a scratch folder, never committed.
//!
//! Run: `cargo bench -p cutaway --bench load`.
//! Targets (DESIGN.md's performance table): each 1M load at most 1 s, `info` on 2M at most 2 s.

use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use csg::testkit;

/// Writes the inputs once per run: (1M STL, 1M OBJ, 2M OBJ).
fn inputs() -> (PathBuf, PathBuf, PathBuf) {
    let dir = std::env::temp_dir().join(format!("cutaway-bench-load-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scratch folder");
    let one_million = testkit::geodesic_sphere(224, 100.0); // 1,003,520 triangles
    let two_million = testkit::geodesic_sphere(316, 100.0); // 1,997,120 triangles
    let stl = dir.join("sphere_1m.stl");
    let obj = dir.join("sphere_1m.obj");
    let obj2 = dir.join("sphere_2m.obj");
    cutaway::io::write_mesh(&stl, &one_million).expect("write STL");
    cutaway::io::write_mesh(&obj, &one_million).expect("write OBJ");
    cutaway::io::write_mesh(&obj2, &two_million).expect("write OBJ");
    for path in [&stl, &obj, &obj2] {
        let bytes = std::fs::metadata(path).map(|m| m.len()).unwrap_or(0);
        eprintln!("input {}: {:.1} MB", path.display(), bytes as f64 / 1e6);
    }
    (stl, obj, obj2)
}

fn load(path: &Path) -> usize {
    let parts = cutaway::io::read_parts(path).expect("load");
    parts.iter().map(|p| p.mesh.triangle_count()).sum()
}

fn load_benches(c: &mut Criterion) {
    let (stl, obj, obj2) = inputs();
    assert_eq!(load(&stl), 1_003_520);
    assert_eq!(load(&obj), 1_003_520);

    let mut group = c.benchmark_group("load");
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(10));
    group.bench_function("binary STL 1M triangles", |b| {
        b.iter(|| black_box(load(&stl)))
    });
    group.bench_function("OBJ 1M triangles", |b| b.iter(|| black_box(load(&obj))));
    group.bench_function("info OBJ 2M triangles", |b| {
        b.iter(|| black_box(cutaway::cli::info::info(&obj2).expect("info")))
    });
    group.finish();

    if let Some(dir) = stl.parent() {
        std::fs::remove_dir_all(dir).ok();
    }
}

criterion_group!(benches, load_benches);
criterion_main!(benches);
