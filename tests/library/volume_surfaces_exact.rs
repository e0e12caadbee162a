//! The guarantee the label surfaces' users rely on without checking at run time: every label of
//! every real volume of the anatomy folder becomes a surface that is closed, consistently
//! oriented, manifold, free of degenerate triangles and free of self-intersection, each checked
//! exactly (the boolean's cutter check: no two triangles touching or crossing), and whose
//! regions counted from that guarantee ([`csg::regions::Regions::count_of_valid_closed`], what
//! `info` reports) are those of the full rule. `cutaway surfaces`, `info` and the window
//! therefore run none of those checks per label (a debug build asserts
//! [`csg::Mesh::is_closed_oriented`] on every label surface it makes); decimation, which has no
//! such guarantee, keeps its exact check in `csg::labels`.
//!
//! Labels of the atlas of at least [`LARGE`] voxels also keep their voxel volume within
//! [`VOLUME_TOLERANCE`], the tolerance stated for it; the chest volumes are coarse (their ribs
//! are one or two voxels thick and lose about a quarter of their voxel volume), so their volume
//! errors are printed, not bounded.

use std::path::Path;

use cutaway::io::volume::{read_volume, surfaces};
use rayon::prelude::*;

/// Labels with at least this many voxels are held to [`VOLUME_TOLERANCE`].
const LARGE: u64 = 1000;
/// Relative volume error of a large label against its voxels (the atlas's thin labels measure
/// up to 7.5 %, see `csg/tests/label_atlas.rs`).
const VOLUME_TOLERANCE: f64 = 0.08;

/// Every volume file and mask folder of the anatomy folder's `volumes/`.
const VOLUMES: [&str; 5] = [
    "spl_head_atlas/hncma-atlas.nrrd",
    "nifti_chest/chest_labels.nii.gz",
    "nifti_chest/per_structure",
    "slicerio_chest/Segmentation.seg.nrrd",
    "slicerio_chest/SegmentationOverlapping.seg.nrrd",
];

#[test]
fn every_label_of_every_shared_volume_is_closed_and_free_of_self_intersection() {
    let Some(dir) = super::volumes::volumes() else {
        return;
    };
    // Every entry of the folder is listed above, so a new volume is not silently left out.
    let mut listed = Vec::new();
    for entry in std::fs::read_dir(&dir).unwrap() {
        let sub = entry.unwrap().path();
        for file in std::fs::read_dir(&sub).unwrap() {
            let file = file.unwrap().path();
            let name = file.file_name().unwrap().to_string_lossy().into_owned();
            if name.ends_with(".nrrd") && name != "CTChest4.nrrd"
                || name.ends_with(".nii.gz")
                || file.is_dir()
            {
                listed.push(file.strip_prefix(&dir).unwrap().to_path_buf());
            }
        }
    }
    listed.sort();
    let mut expected: Vec<_> = VOLUMES.iter().map(|v| Path::new(v).to_path_buf()).collect();
    expected.sort();
    assert_eq!(listed, expected, "the volumes of {}", dir.display());

    let mut checked = 0;
    for name in VOLUMES {
        let path = dir.join(name);
        let volume = read_volume(&path, None).unwrap();
        let voxel_volume = volume.world_from_voxel.matrix3.determinant().abs();
        let made = surfaces(&volume, None, &|_| true).unwrap();
        assert_eq!(made.len(), volume.structures.len(), "{name}");
        let failures: Vec<String> = made
            .par_iter()
            .filter_map(|s| {
                let label = format!("{name} label {} ({})", s.structure.value, s.structure.name);
                let mesh = &s.mesh;
                if !mesh.is_closed_oriented() {
                    return Some(format!("{label}: not closed and oriented"));
                }
                let report = mesh.report();
                if !(report.closed && report.manifold && report.degenerate_triangles == 0) {
                    return Some(format!("{label}: {report:?}"));
                }
                if let Err(e) = csg::check_cutter(mesh) {
                    return Some(format!("{label}: {e}"));
                }
                let regions = csg::regions::Regions::count_of_valid_closed(mesh);
                if regions != report.regions {
                    return Some(format!(
                        "{label}: {regions} regions counted from the guarantee, {} by the rule",
                        report.regions
                    ));
                }
                let expected = s.structure.voxels as f64 * voxel_volume;
                let error = (mesh.volume() - expected).abs() / expected;
                let bounded = name.starts_with("spl_head_atlas");
                if bounded && s.structure.voxels >= LARGE && error > VOLUME_TOLERANCE {
                    return Some(format!("{label}: volume off by {:.1} %", 100.0 * error));
                }
                None
            })
            .collect();
        assert!(failures.is_empty(), "{}", failures.join("\n"));
        let worst = made
            .iter()
            .filter(|s| s.structure.voxels >= LARGE)
            .map(|s| {
                let expected = s.structure.voxels as f64 * voxel_volume;
                (s.mesh.volume() - expected).abs() / expected
            })
            .fold(0.0, f64::max);
        eprintln!(
            "{name}: {} labels exact; largest volume error of labels >= {LARGE} voxels {:.1} %",
            made.len(),
            100.0 * worst
        );
        checked += made.len();
    }
    // The atlas alone has 312 labels.
    assert!(checked > 312, "{checked} labels checked");
}
