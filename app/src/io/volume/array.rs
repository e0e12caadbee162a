//! Label volumes that come from memory instead of a file (a numpy array handed over by the Python
//! package), and the surface options `cutaway surfaces` checks: both front ends build the same
//! [`LabelVolume`] with the same names and colours and surface it through
//! [`super::surfaces_with`].

use std::path::Path;

use glam::DAffine3;

use super::{LabelData, LabelInfo, LabelVolume, RawVolume};

/// The surface options of `cutaway surfaces --smoothing S --decimate F`, checked with its
/// messages (`None`: the default of `csg::labels`, no decimation).
pub fn surface_options(
    smoothing: Option<f64>,
    decimate: Option<f64>,
) -> anyhow::Result<csg::labels::SurfaceOptions> {
    if let Some(s) = smoothing
        && !(0.0..=1.0).contains(&s)
    {
        anyhow::bail!("--smoothing {s} is outside 0..=1");
    }
    if let Some(f) = decimate
        && !(f > 0.0 && f <= 1.0)
    {
        anyhow::bail!("--decimate {f} is outside 0 < F <= 1");
    }
    let mut options = csg::labels::SurfaceOptions::default();
    if let Some(smoothing) = smoothing {
        options.smoothing = smoothing;
    }
    options.decimate = decimate;
    Ok(options)
}

/// A one-layer label volume from a label map in memory (`data` x fastest, `dims` long), placed
/// in world space by `world_from_voxel` (RAS mm), named by `names` (else `label N` and its
/// default colour). `source` is what errors and the models' source name. Checked as a file's
/// volume is: sizes, a finite and non-singular matrix, at least one labelled voxel.
pub fn volume_from_labels(
    source: &Path,
    dims: [usize; 3],
    world_from_voxel: DAffine3,
    data: LabelData,
    names: &[LabelInfo],
) -> anyhow::Result<LabelVolume> {
    use anyhow::Context as _;
    let with_source = || source.display().to_string();
    let voxels = super::check_dims(dims.map(|d| d as u64), 1).with_context(with_source)?;
    if data.len() != voxels {
        anyhow::bail!(
            "{}: {} labels for a {} × {} × {} grid",
            source.display(),
            data.len(),
            dims[0],
            dims[1],
            dims[2]
        );
    }
    let m = world_from_voxel.matrix3;
    let world_from_voxel =
        super::affine([m.x_axis, m.y_axis, m.z_axis], world_from_voxel.translation)
            .with_context(with_source)?;
    let raw = RawVolume {
        dims,
        world_from_voxel,
        layers: vec![data],
        names: Vec::new(),
    };
    super::finish(source, raw, names).with_context(with_source)
}
