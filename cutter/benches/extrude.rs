//! One paint-roller extrusion step (a mouse move with the collision/rotation loop) on a
//! 1M-triangle target. DESIGN.md target: ≤ 1 ms. Run: `cargo bench -p cutter --bench extrude`.

use std::sync::Arc;

use criterion::{Criterion, criterion_group, criterion_main};
use glam::{DVec2, DVec3};

use csg::SpatialIndex;
use cutter::{Camera, Editor, EditorEvent, EditorSettings};

fn bench_extrude(c: &mut Criterion) {
    // 1,003,520 triangles, radius 50, seen from −Y.
    let mesh = Arc::new(csg::testkit::geodesic_sphere(224, 50.0));
    let started = std::time::Instant::now();
    let index = Arc::new(SpatialIndex::build(&mesh));
    eprintln!(
        "target: {} triangles, index built in {:?}",
        mesh.triangles.len(),
        started.elapsed()
    );
    let camera = Camera {
        eye: DVec3::new(0.0, -300.0, 0.0),
        target: DVec3::ZERO,
        up: DVec3::Z,
        fov_y_deg: 30.0,
    };
    let viewport = DVec2::new(1280.0, 800.0);
    let settings = EditorSettings::for_scene(&mesh.bbox(), camera.fov_y_deg);
    let mut group = c.benchmark_group("extrude_step_1M");
    for boxes in [1usize, 20] {
        let mut editor = Editor::new(mesh.clone(), index.clone(), camera, viewport, settings);
        for e in [
            EditorEvent::press(560.0, 430.0),
            EditorEvent::move_to(560.0, 400.0),
            EditorEvent::release(560.0, 370.0),
        ] {
            editor.handle(e);
        }
        let lead = editor.cutter().expect("cutter").leading().front_mid();
        let h = camera.project(viewport, lead).expect("visible");
        editor.handle(EditorEvent::press(h.x, h.y));
        // Grow `boxes` boxes (about 20 px each), then hold the drag open.
        let mut x = h.x;
        while editor.cutter().unwrap().box_count() < boxes {
            x += 2.0;
            editor.handle(EditorEvent::move_to(x, h.y + 0.2 * (x - h.x)));
        }
        let base = DVec2::new(x, h.y + 0.2 * (x - h.x));
        let mut k = 0u64;
        group.bench_function(format!("{boxes}_boxes"), |b| {
            b.iter(|| {
                // Alternate between two pointer positions 6 px apart: every step re-places the
                // leading plane with the full rotation search; no box is locked.
                k += 1;
                let dx = if k.is_multiple_of(2) { 3.0 } else { 9.0 };
                let r = editor.handle(EditorEvent::move_to(base.x + dx, base.y - dx * 0.5));
                std::hint::black_box(r)
            })
        });
        editor.clear_recording();
    }
    group.finish();
}

criterion_group!(benches, bench_extrude);
criterion_main!(benches);
