//! Label surfaces: the classic non-manifold configurations of a binary mask by name, random masks,
//! orientation under mirroring transforms, and volume/centroid fidelity.
//!
//! Every surface is checked with the structural validator, the exact topological report
//! (closed, manifold, no degenerate triangle) and the boolean's own exact cutter checks (closed,
//! oriented, positive volume, no self-intersection, touching included), and a few are cut.

use glam::{DAffine3, DMat3, DVec3};
use proptest::prelude::*;

use super::*;
use crate::mesh::Mesh;
use crate::target::TargetIndex;

/// A grid of `dims` with `value_at(i, j, k)` and the given transform.
fn grid_data(dims: [usize; 3], mut value_at: impl FnMut(usize, usize, usize) -> u16) -> Vec<u16> {
    let mut data = Vec::with_capacity(dims.iter().product());
    for k in 0..dims[2] {
        for j in 0..dims[1] {
            for i in 0..dims[0] {
                data.push(value_at(i, j, k));
            }
        }
    }
    data
}

fn surfaces_of(
    dims: [usize; 3],
    data: &[u16],
    world_from_voxel: DAffine3,
    smoothing: f64,
) -> Vec<LabelSurface> {
    let grid = LabelGrid::new(dims, data, world_from_voxel).unwrap();
    let options = SurfaceOptions::default().with_smoothing(smoothing);
    label_surfaces(&grid, &options, &|_| true).unwrap()
}

/// Asserts everything the API promises of one surface; returns its region count.
/// Checks a label surface the way the boolean needs it and returns its connected sheets
/// (components; a cavity's sheet counts on its own here, though it joins its solid's region).
fn assert_valid(surface: &LabelSurface) -> usize {
    let mesh = &surface.mesh;
    mesh.sanity_check().unwrap();
    let report = mesh.report();
    assert!(
        report.closed && report.manifold,
        "label {}: {report:?}",
        surface.value
    );
    assert_eq!(report.degenerate_triangles, 0, "label {}", surface.value);
    assert!(mesh.is_closed_oriented(), "label {}", surface.value);
    assert!(mesh.volume() > 0.0, "label {} not outward", surface.value);
    let target = TargetIndex::build(mesh.clone()).unwrap();
    if let Err(e) = crate::boolean::prepare_cutter(&target, &[mesh]) {
        panic!(
            "label {}: the boolean refuses it as a cutter: {e}",
            surface.value
        );
    }
    report.components
}

/// Both smoothing extremes and the default.
const LEVELS: [f64; 3] = [0.0, 0.5, 1.0];

#[test]
fn one_voxel() {
    let data = grid_data([3, 3, 3], |i, j, k| (i == 1 && j == 1 && k == 1) as u16);
    for s in LEVELS {
        let out = surfaces_of([3, 3, 3], &data, DAffine3::IDENTITY, s);
        assert_eq!(out.len(), 1);
        assert_eq!((out[0].value, out[0].voxels), (1, 1));
        assert_eq!(assert_valid(&out[0]), 1);
        // The raw surface is the octahedron-like cut through the edge midpoints around the
        // voxel centre: inside the voxel, containing its centre.
        let bbox = out[0].mesh.bbox();
        assert!(bbox.min.cmpge(DVec3::splat(0.5)).all() && bbox.max.cmple(DVec3::splat(1.5)).all());
    }
}

#[test]
fn edge_touching_voxels() {
    // Two voxels sharing only the edge x = y = 1.5 (z-aligned): two separate sheets.
    let data = grid_data([4, 4, 3], |i, j, k| {
        (k == 1 && ((i == 1 && j == 1) || (i == 2 && j == 2))) as u16
    });
    for s in LEVELS {
        let out = surfaces_of([4, 4, 3], &data, DAffine3::IDENTITY, s);
        assert_eq!(assert_valid(&out[0]), 2);
    }
}

#[test]
fn corner_touching_voxels() {
    let data = grid_data([4, 4, 4], |i, j, k| {
        ((i, j, k) == (1, 1, 1) || (i, j, k) == (2, 2, 2)) as u16
    });
    for s in LEVELS {
        let out = surfaces_of([4, 4, 4], &data, DAffine3::IDENTITY, s);
        assert_eq!(assert_valid(&out[0]), 2);
    }
}

#[test]
fn checkerboard() {
    // Two labels in a 3-D checkerboard: every voxel touches same-label voxels only along edges
    // and corners, so each label is many one-voxel sheets.
    let dims = [6, 5, 4];
    let data = grid_data(dims, |i, j, k| 1 + ((i + j + k) % 2) as u16);
    for s in LEVELS {
        let out = surfaces_of(dims, &data, DAffine3::IDENTITY, s);
        assert_eq!(out.len(), 2);
        for surface in &out {
            assert_eq!(assert_valid(surface) as u64, surface.voxels);
        }
    }
}

#[test]
fn label_on_border() {
    // A label filling the whole grid, and one filling a face slab: closed at the grid border.
    let dims = [5, 4, 3];
    let data = grid_data(dims, |i, _, _| 1 + (i == 0) as u16);
    for s in LEVELS {
        let out = surfaces_of(dims, &data, DAffine3::IDENTITY, s);
        assert_eq!(out.len(), 2);
        for surface in &out {
            assert_eq!(assert_valid(surface), 1);
        }
    }
}

#[test]
fn hollow_shell() {
    // A 5³ cube of label 1 with a 3³ hole holding label 2: label 1 is a shell whose inner
    // surface faces inward (two sheets, one region with a cavity, total volume positive),
    // label 2 one solid.
    let dims = [7, 7, 7];
    let inside = |c: usize, lo: usize, hi: usize| (lo..=hi).contains(&c);
    let data = grid_data(dims, |i, j, k| {
        let shell = [i, j, k].iter().all(|&c| inside(c, 1, 5));
        let core = [i, j, k].iter().all(|&c| inside(c, 2, 4));
        if core { 2 } else { shell as u16 }
    });
    for s in LEVELS {
        let out = surfaces_of(dims, &data, DAffine3::IDENTITY, s);
        assert_eq!(out.len(), 2);
        assert_eq!(assert_valid(&out[0]), 2);
        assert_eq!(assert_valid(&out[1]), 1);
        // Its inner sheet faces inward and lies inside the outer one: a cavity, one region.
        assert_eq!(out[0].mesh.report().regions, 1);
        // The shell's inner surface faces inward: its volume is the shell's 98 voxels.
        let shell = out[0].mesh.volume();
        assert!((shell - 98.0).abs() < 98.0 * 0.25, "shell volume {shell}");
    }
}

#[test]
fn mirrored_transform_keeps_surfaces_outward() {
    // A negative determinant (LPS-style axis flip with anisotropic spacing) mirrors the voxels;
    // the surfaces must still be outward in world space.
    let dims = [6, 6, 6];
    let data = grid_data(dims, |i, j, k| {
        ((1..5).contains(&i) && (2..4).contains(&j) && k > 0) as u16
    });
    let world_from_voxel = DAffine3::from_mat3_translation(
        DMat3::from_diagonal(DVec3::new(-0.7, 0.5, 1.2)),
        DVec3::new(10.0, -3.0, 2.0),
    );
    for s in LEVELS {
        let out = surfaces_of(dims, &data, world_from_voxel, s);
        assert_valid(&out[0]);
    }
}

#[test]
fn surface_is_accepted_as_a_boolean_target() {
    let dims = [12, 12, 12];
    let data = grid_data(dims, |i, j, k| {
        let d = DVec3::new(i as f64, j as f64, k as f64) - DVec3::splat(5.5);
        (d.length() < 4.5) as u16
    });
    let out = surfaces_of(dims, &data, DAffine3::IDENTITY, 0.5);
    let target = TargetIndex::build(out[0].mesh.clone()).unwrap();
    let cutter = crate::testkit::cube(DVec3::splat(5.3), DVec3::splat(12.0));
    let options = crate::CutOptions::default().with_merge_coincident(false);
    let result = crate::subtract_with(&target, &[&cutter], &options).unwrap();
    crate::cutcheck::check_closed_cut(&out[0].mesh, &result).unwrap();
}

/// Volume and centroid of a ball against its voxels, at the default smoothing: a label of at
/// least 1000 voxels keeps its voxel volume within 5 % and its centroid within 0.1 voxel.
#[test]
fn volume_and_centroid_follow_the_voxels() {
    let dims = [24, 22, 20];
    let centre = DVec3::new(11.3, 10.6, 9.8);
    let data = grid_data(dims, |i, j, k| {
        let d = (DVec3::new(i as f64, j as f64, k as f64) - centre) / DVec3::new(8.0, 7.0, 6.0);
        (d.length() < 1.0) as u16
    });
    let world_from_voxel = DAffine3::from_mat3_translation(
        DMat3::from_diagonal(DVec3::new(0.8, 0.8, 1.5)),
        DVec3::ONE,
    );
    let out = surfaces_of(dims, &data, world_from_voxel, 0.5);
    let surface = &out[0];
    assert!(surface.voxels >= 1000);
    assert_valid(surface);
    let voxel_volume = 0.8 * 0.8 * 1.5;
    let expected = surface.voxels as f64 * voxel_volume;
    let error = (surface.mesh.volume() - expected).abs() / expected;
    assert!(error < 0.05, "volume error {error}");
    let mut sum = DVec3::ZERO;
    for k in 0..dims[2] {
        for j in 0..dims[1] {
            for i in 0..dims[0] {
                if data[i + dims[0] * (j + dims[1] * k)] == 1 {
                    sum += DVec3::new(i as f64, j as f64, k as f64);
                }
            }
        }
    }
    let voxel_centroid = world_from_voxel.transform_point3(sum / surface.voxels as f64);
    let offset = (mesh_centroid(&surface.mesh) - voxel_centroid).abs() / DVec3::new(0.8, 0.8, 1.5);
    assert!(
        offset.max_element() < 0.1,
        "centroid off by {offset} voxels"
    );
}

/// Centroid of the solid a closed, outward mesh bounds.
pub(crate) fn mesh_centroid(mesh: &Mesh) -> DVec3 {
    let origin = mesh.bbox().center();
    let mut moment = DVec3::ZERO;
    let mut volume = 0.0;
    for t in 0..mesh.triangles.len() {
        let [a, b, c] = mesh.corners(t).map(|p| p - origin);
        let v = a.dot(b.cross(c)) / 6.0;
        volume += v;
        moment += (a + b + c) * (v / 4.0);
    }
    origin + moment / volume
}

#[test]
fn smoothing_removes_the_staircase() {
    // A slanted slab: raw, the surface has visible steps; smoothed, its normals vary less. The
    // deviation is weighted by area, so it measures the surface, not how its polygons are split
    // into triangles.
    let dims = [16, 16, 8];
    let data = grid_data(dims, |i, j, k| (i + j / 2 < 12 && k > 0 && k < 7) as u16);
    let spread = |s: f64| {
        let out = surfaces_of(dims, &data, DAffine3::IDENTITY, s);
        let mesh = &out[0].mesh;
        let mut deviation = 0.0;
        let mut total_area = 0.0;
        let slant = DVec3::new(1.0, 0.5, 0.0).normalize();
        for t in 0..mesh.triangles.len() {
            let scaled = mesh.face_normal_scaled(t);
            let n = scaled.normalize();
            if n.dot(slant) > 0.7 {
                let area = scaled.length();
                deviation += (1.0 - n.dot(slant)) * area;
                total_area += area;
            }
        }
        deviation / total_area
    };
    let (raw, default, strongest) = (spread(0.0), spread(0.5), spread(1.0));
    assert!(
        default < raw * 0.6 && strongest < raw * 0.6,
        "raw {raw}, default {default}, strongest {strongest}"
    );
}

#[test]
fn only_and_counts() {
    let dims = [5, 5, 5];
    let data = grid_data(dims, |i, _, _| [0, 3, 3, 7, 9][i]);
    let grid = LabelGrid::new(dims, &data, DAffine3::IDENTITY).unwrap();
    assert_eq!(label_counts(&grid), vec![(3, 50), (7, 25), (9, 25)]);
    let options = SurfaceOptions::default().with_only(vec![9, 3, 4]);
    let out = label_surfaces(&grid, &options, &|_| true).unwrap();
    assert_eq!(out.iter().map(|s| s.value).collect::<Vec<_>>(), vec![3, 9]);
}

#[test]
fn wide_values_and_types() {
    let dims = [3, 2, 2];
    let data: Vec<u32> = vec![0, 70000, 70000, 5, 0, 0, 0, 0, 70000, 0, 0, 0];
    let grid = LabelGrid::new(dims, &data, DAffine3::IDENTITY).unwrap();
    assert_eq!(label_counts(&grid), vec![(5, 1), (70000, 3)]);
    let bytes: Vec<u8> = vec![2; 8];
    let grid = LabelGrid::new([2, 2, 2], &bytes, DAffine3::IDENTITY).unwrap();
    let out = label_surfaces(&grid, &SurfaceOptions::default(), &|_| true).unwrap();
    assert_eq!((out.len(), out[0].value, out[0].voxels), (1, 2, 8));
}

#[test]
fn bad_input_is_an_error() {
    let data = vec![1u16; 7];
    assert!(matches!(
        LabelGrid::new([2, 2, 2], &data, DAffine3::IDENTITY),
        Err(LabelSurfaceError::DataLength {
            expected: 8,
            actual: 7,
            ..
        })
    ));
    assert!(matches!(
        LabelGrid::new([usize::MAX, 2, 2], &data, DAffine3::IDENTITY),
        Err(LabelSurfaceError::DimsOverflow { .. })
    ));
    let flat = DAffine3::from_mat3(DMat3::from_diagonal(DVec3::new(1.0, 0.0, 1.0)));
    assert!(matches!(
        LabelGrid::new([7, 1, 1], &data, flat),
        Err(LabelSurfaceError::BadTransform { .. })
    ));
    let grid = LabelGrid::new([7, 1, 1], &data, DAffine3::IDENTITY).unwrap();
    let bad = SurfaceOptions::default().with_smoothing(1.5);
    assert!(matches!(
        label_surfaces(&grid, &bad, &|_| true),
        Err(LabelSurfaceError::BadSmoothing { .. })
    ));
    for fraction in [0.0, -0.5, 1.5, f64::NAN] {
        let decimate = SurfaceOptions {
            decimate: Some(fraction),
            ..SurfaceOptions::default()
        };
        assert!(matches!(
            label_surfaces(&grid, &decimate, &|_| true),
            Err(LabelSurfaceError::BadDecimate { .. })
        ));
    }
}

#[test]
fn decimation_keeps_surfaces_closed_and_close() {
    // A ball split into two labels, and a thin slanted plate one voxel thick: decimated, each
    // surface stays valid for the boolean and moves less than a tenth of a voxel on average (the
    // volume change over the area; a quarter at 10 %, where the small ball becomes coarse); the ball's halves keep about
    // the asked fraction of their triangles. The plate's two sheets lie under a voxel apart, so
    // the exact check refuses the deep decimations and fewer triangles are removed there.
    let dims = [24, 24, 24];
    let data = grid_data(dims, |i, j, k| {
        let d = DVec3::new(i as f64, j as f64, k as f64) - DVec3::splat(11.5);
        if d.length() < 8.0 {
            1 + (i > 12 && j > 10) as u16
        } else if (i + j / 2 + k / 3) % 17 == 0 {
            3
        } else {
            0
        }
    });
    let grid = LabelGrid::new(dims, &data, DAffine3::IDENTITY).unwrap();
    let full = label_surfaces(&grid, &SurfaceOptions::default(), &|_| true).unwrap();
    for fraction in [0.5, 0.25, 0.1] {
        let options = SurfaceOptions {
            decimate: Some(fraction),
            ..SurfaceOptions::default()
        };
        let out = label_surfaces(&grid, &options, &|_| true).unwrap();
        assert_eq!(out.len(), full.len());
        for (d, f) in out.iter().zip(&full) {
            assert_valid(d);
            let (kept, all) = (d.mesh.triangle_count(), f.mesh.triangle_count());
            let most = if d.value == 3 {
                all as f64 * 0.99
            } else {
                all as f64 * fraction * 1.2 + 8.0
            };
            assert!(
                kept as f64 <= most,
                "label {} at {fraction}: {kept} of {all} triangles",
                d.value
            );
            // The volume change over the area is the mean distance the surface moved (voxels).
            let moved = (d.mesh.volume() - f.mesh.volume()).abs() / f.mesh.area();
            assert!(
                moved < if fraction < 0.25 { 0.25 } else { 0.1 },
                "label {} at {fraction}: the surface moved {moved} voxels on average",
                d.value
            );
        }
    }
}

#[test]
fn progress_runs_to_one_and_cancels() {
    let dims = [6, 6, 6];
    let data = grid_data(dims, |i, j, k| ((i + 2 * j + 3 * k) % 5) as u16);
    let grid = LabelGrid::new(dims, &data, DAffine3::IDENTITY).unwrap();
    let last = std::sync::Mutex::new(0.0f32);
    label_surfaces(&grid, &SurfaceOptions::default(), &|p| {
        *last.lock().unwrap() = p;
        true
    })
    .unwrap();
    assert_eq!(*last.lock().unwrap(), 1.0);
    assert_eq!(
        label_surfaces(&grid, &SurfaceOptions::default(), &|p| p < 0.3),
        Err(LabelSurfaceError::Cancelled)
    );
}

#[test]
fn each_surface_is_handed_over_once_and_a_refusal_stops() {
    let dims = [9, 8, 7];
    let data = grid_data(dims, |i, j, k| {
        ((i / 2 + 2 * (j / 3) + 3 * (k / 2)) % 6) as u16
    });
    let grid = LabelGrid::new(dims, &data, DAffine3::IDENTITY).unwrap();
    let options = SurfaceOptions::default();
    let collected = label_surfaces(&grid, &options, &|_| true).unwrap();
    assert!(collected.len() >= 5, "{} labels", collected.len());
    let handed = std::sync::Mutex::new(Vec::new());
    label_surfaces_each(&grid, &options, &|_| true, &|s| {
        handed.lock().unwrap().push(s);
        true
    })
    .unwrap();
    let mut handed = handed.into_inner().unwrap();
    handed.sort_by_key(|s| s.value);
    assert_eq!(handed, collected);
    for s in &handed {
        assert!(s.mesh.is_closed_oriented(), "label {}", s.value);
    }
    let calls = std::sync::atomic::AtomicUsize::new(0);
    let stopped = label_surfaces_each(&grid, &options, &|_| true, &|_| {
        calls.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        false
    });
    assert_eq!(stopped, Err(LabelSurfaceError::Cancelled));
    assert!(calls.into_inner() < collected.len());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Random multi-label masks of random density: every label's surface is valid at every
    /// smoothing level, and its raw volume is positive.
    #[test]
    fn random_masks(
        dims in (1usize..7, 1usize..7, 1usize..6),
        seed in any::<u64>(),
        labels in 1u16..4,
        smoothing in prop_oneof![Just(0.0), Just(0.5), Just(1.0), 0.0..=1.0f64],
    ) {
        let dims = [dims.0, dims.1, dims.2];
        let mut state = seed | 1;
        let data = grid_data(dims, |_, _, _| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state % (labels as u64 + 1)) as u16
        });
        let out = surfaces_of(dims, &data, DAffine3::IDENTITY, smoothing);
        for surface in &out {
            assert_valid(surface);
        }
    }
}
