//! Expose on small scenes whose answer is known: the cutters are valid, aimed at the structures
//! that hide the focus, and after the exact cut every point of the focus the eye sees without
//! occluders is seen.

use super::*;
use csg::{SpatialIndex, TargetIndex, testkit};

const EYE: DVec3 = DVec3::new(0.0, -100.0, 0.0);

fn view() -> ExposeView {
    ExposeView {
        eye: EYE,
        forward: DVec3::Y,
        right: DVec3::X,
        up: DVec3::Z,
    }
}

fn translated(mut mesh: Mesh, by: DVec3) -> Mesh {
    for p in &mut mesh.positions {
        *p += by;
    }
    mesh
}

/// An elongated focus (a squashed sphere 16 × 6 × 6 at the origin) inside a closed head of
/// radius 30, behind a plate (y in −16..−13) that covers only its left half, and a ball beside
/// it that hides nothing.
fn scene() -> (Mesh, Vec<Mesh>) {
    let mut focus = testkit::geodesic_sphere(10, 3.0);
    for p in &mut focus.positions {
        p.x *= 8.0 / 3.0;
    }
    let head = testkit::geodesic_sphere(16, 30.0);
    let plate = testkit::cube(
        DVec3::new(-20.0, -16.0, -10.0),
        DVec3::new(-2.0, -13.0, 10.0),
    );
    let beside = translated(testkit::geodesic_sphere(6, 3.0), DVec3::new(18.0, 0.0, 0.0));
    (focus, vec![head, plate, beside])
}

/// What the eye sees of `focus` (its vertices, slightly pulled toward the eye) with `drawn` in
/// the way: the share of the vertices it sees with nothing in the way that it still sees.
fn seen_share(focus: &Mesh, drawn: &[Mesh]) -> f64 {
    let focus_index = SpatialIndex::build(focus);
    let mut scene = Mesh::default();
    for m in drawn {
        scene.append(m);
    }
    let scene_index = SpatialIndex::build(&scene);
    let (mut free, mut seen) = (0, 0);
    for &p in &focus.positions {
        let towards = p - EYE;
        // A vertex is seen when the focus's own first hit along its ray is (next to) it.
        let hit = focus_index.ray_cast(focus, EYE, towards, 1.0 + 1e-9);
        if hit.is_some_and(|h| h.t < 1.0 - 1e-6) {
            continue;
        }
        free += 1;
        if scene_index
            .ray_cast(&scene, EYE, towards, 1.0 - 1e-6)
            .is_none()
        {
            seen += 1;
        }
    }
    seen as f64 / free as f64
}

/// Each occluder as drawn after its cutters cut it (kept part and walls).
fn cut_occluders(occluders: &[Mesh], exposure: &Exposure) -> Vec<Mesh> {
    occluders
        .iter()
        .enumerate()
        .map(|(k, occluder)| {
            let mut mesh = occluder.clone();
            for c in exposure.cutters.iter().filter(|c| c.occluder == k) {
                let index = TargetIndex::build(mesh.clone()).unwrap();
                let cut = csg::subtract(&index, &c.cutter.surface()).unwrap();
                let mut drawn = cut.materialize(&mesh);
                drawn.append(&cut.walls.mesh);
                mesh = drawn;
            }
            mesh
        })
        .collect()
}

#[test]
fn the_cutters_open_the_head_and_the_plate_and_leave_the_rest() {
    let (focus, occluders) = scene();
    let refs: Vec<&Mesh> = occluders.iter().collect();
    let exposure = expose(&focus, &refs, &view(), &ExposeOptions::default(), &|| true).unwrap();
    // Nearest first: the head's skin in front, then the plate; nothing for the ball beside.
    let aimed: Vec<usize> = exposure.cutters.iter().map(|c| c.occluder).collect();
    assert_eq!(aimed, vec![0, 1], "{:?}", exposure.notes);
    assert!(exposure.notes.is_empty(), "{:?}", exposure.notes);
    assert!(
        (exposure.hidden - 1.0).abs() < 1e-12,
        "the head hides all of it"
    );
    assert!((exposure.cutters[0].opens - 1.0).abs() < 1e-12);
    assert!(
        (0.3..0.7).contains(&exposure.cutters[1].opens),
        "the plate hides about half: {}",
        exposure.cutters[1].opens
    );
    for c in &exposure.cutters {
        c.cutter.validate().unwrap();
        assert!(!c.simplified);
        assert!(c.cutter.box_count() >= 8, "{} boxes", c.cutter.box_count());
    }
    let before: Vec<Mesh> = occluders.clone();
    assert!(seen_share(&focus, &before) == 0.0, "hidden inside the head");
    let after = cut_occluders(&occluders, &exposure);
    let share = seen_share(&focus, &after);
    assert!(share >= 0.98, "seen after the cuts: {share}");
    // The ball beside is untouched and the focus is never cut.
    assert_eq!(after[2], occluders[2]);
}

#[test]
fn the_head_is_opened_no_wider_than_the_silhouette_and_margin_nor_deeper_than_needed() {
    let (focus, occluders) = scene();
    let refs: Vec<&Mesh> = occluders.iter().collect();
    let margin = 3.0;
    let options = ExposeOptions::default().with_margin(margin);
    let exposure = expose(&focus, &refs, &view(), &options, &|| true).unwrap();
    let head = &exposure.cutters[0].cutter;
    // Across the view (x, z scaled from the eye to the focus's depth, y = 0), the cutter stays
    // within the focus's half-widths (8, 3) plus the margin and a few cells.
    let slack = 1.5;
    for p in head.planes.iter().flat_map(|p| p.corners()) {
        let q = p - EYE;
        let (x, z) = (q.x * 100.0 / q.y, q.z * 100.0 / q.y);
        assert!(x.abs() <= 8.0 + margin + slack, "x {x}");
        assert!(z.abs() <= 3.0 + margin + slack, "z {z}");
    }
    // Front in front of the head's surface (y = −30), back behind the focus's near side
    // (y = −3) but not past its far side (y = 3) by more than the clearance and a few cells.
    let front = head
        .planes
        .iter()
        .flat_map(|p| [p.front_top, p.front_bottom]);
    assert!(front.clone().all(|p| p.y < -29.5), "front behind the skin");
    let back = head.planes.iter().flat_map(|p| [p.back_top, p.back_bottom]);
    assert!(
        back.clone().all(|p| p.y > -3.0 && p.y < 3.0),
        "{:?}",
        back.collect::<Vec<_>>()
    );
}

#[test]
fn a_focus_behind_the_eye_and_an_empty_focus_are_refused_and_cancel_stops() {
    let (focus, occluders) = scene();
    let refs: Vec<&Mesh> = occluders.iter().collect();
    let mut behind = view();
    behind.eye = DVec3::new(0.0, 2.0, 0.0);
    assert!(matches!(
        expose(&focus, &refs, &behind, &ExposeOptions::default(), &|| true),
        Err(ExposeError::BehindEye { .. })
    ));
    assert_eq!(
        expose(
            &Mesh::default(),
            &refs,
            &view(),
            &ExposeOptions::default(),
            &|| true
        )
        .unwrap_err(),
        ExposeError::EmptyFocus
    );
    assert_eq!(
        expose(&focus, &refs, &view(), &ExposeOptions::default(), &|| false).unwrap_err(),
        ExposeError::Cancelled
    );
}

#[test]
fn nothing_in_the_way_builds_nothing() {
    let (focus, occluders) = scene();
    let beside = [&occluders[2]];
    let exposure = expose(&focus, &beside, &view(), &ExposeOptions::default(), &|| {
        true
    })
    .unwrap();
    assert!(exposure.cutters.is_empty());
    assert_eq!(exposure.hidden, 0.0);
}

#[test]
fn occluders_hiding_little_are_left_within_the_share_allowed() {
    let (focus, occluders) = scene();
    let refs: Vec<&Mesh> = occluders.iter().collect();
    // The plate hides about half of the focus: left when 60 % may stay hidden, not by default.
    let generous = ExposeOptions {
        leave_share: 0.6,
        ..ExposeOptions::default()
    };
    let exposure = expose(&focus, &refs, &view(), &generous, &|| true).unwrap();
    assert_eq!(exposure.left, vec![1]);
    let aimed: Vec<usize> = exposure.cutters.iter().map(|c| c.occluder).collect();
    assert_eq!(aimed, vec![0]);
    let strict = expose(&focus, &refs, &view(), &ExposeOptions::default(), &|| true).unwrap();
    assert!(strict.left.is_empty());
}
