//! `cutaway info MESH --json`: facts about one mesh file (see `../shared/CONTRACT.md`).
//!
//! The file is read as one mesh ([`crate::io::read_mesh`]: every part welded on its own, then
//! concatenated) and described by [`csg::Mesh::report`]. `volume` is the signed enclosed volume;
//! it is meaningful only when `closed` is true.
//!
//! A label volume (file or mask directory) is described by the same mesh fields, computed on all
//! its label surfaces together, plus its grid (`dims`, `spacing`) and its labels (value, name,
//! colour, voxel count).

use std::io::Write as _;
use std::path::{Path, PathBuf};

use anyhow::Context as _;
use serde::Serialize;

#[derive(Debug, clap::Args)]
pub struct InfoArgs {
    /// The mesh file (.obj, .stl, .ply, .vtk), or a label volume (.nrrd, .seg.nrrd, .nhdr,
    /// .nii, .nii.gz, a folder of masks).
    pub mesh: PathBuf,
    /// Colour table naming the labels of a volume (Slicer .ctbl/.txt, FreeSurfer LUT, ITK-SNAP).
    #[arg(long)]
    pub labels: Option<PathBuf>,
    /// Print one JSON object (see CONTRACT.md).
    #[arg(long)]
    pub json: bool,
}

/// The `info --json` object. Field order is the contract's order.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Info {
    pub vertices: usize,
    pub triangles: usize,
    pub regions: usize,
    pub closed: bool,
    pub manifold: bool,
    pub bbox_min: [f64; 3],
    pub bbox_max: [f64; 3],
    pub volume: f64,
    /// Label volumes only: voxels along i, j, k.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dims: Option<[usize; 3]>,
    /// Label volumes only: voxel size along i, j, k in millimetres.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spacing: Option<[f64; 3]>,
    /// Label volumes only: the labels present, ascending.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub labels: Option<Vec<LabelInfo>>,
    /// Intensity images only (a volume whose values are not labels).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub intensity: Option<IntensityInfo>,
}

/// What an intensity image holds, in `info --json`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct IntensityInfo {
    /// The stored sample type (`int16`, `float32`, …).
    #[serde(rename = "type")]
    pub sample: &'static str,
    pub min: f64,
    pub max: f64,
    /// Why it is not a label map.
    pub reason: String,
}

/// One label of a volume in `info --json`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LabelInfo {
    pub value: u32,
    pub name: String,
    /// sRGB, 0..=255.
    pub color: [u8; 3],
    pub voxels: u64,
}

/// Reads `path` and computes its [`Info`] (all the work of `cutaway info` except printing).
pub fn info(path: &Path) -> anyhow::Result<Info> {
    info_with_labels(path, None)
}

/// [`info`] with a colour table for a volume's labels.
pub fn info_with_labels(path: &Path, labels: Option<&Path>) -> anyhow::Result<Info> {
    if crate::io::volume::is_volume(path) {
        return volume_info(path, labels);
    }
    let mesh = crate::io::read_mesh(path)?;
    Ok(mesh_info(&mesh))
}

fn volume_info(path: &Path, labels: Option<&Path>) -> anyhow::Result<Info> {
    use crate::io::volume::content::{VolumeContent, read_content};
    if path.is_dir() {
        return mask_folder_info(path, labels);
    }
    let volume = match read_content(path, labels)? {
        VolumeContent::Labels(volume) => volume,
        VolumeContent::Image { image, reason } => return Ok(image_info(&image, reason)),
    };
    let mut info = surfaces_info(&|each| {
        crate::io::volume::surfaces_each(
            &volume,
            csg::labels::SurfaceOptions::default(),
            &|_| true,
            each,
        )
    })
    .with_context(|| path.display().to_string())?;
    info.dims = Some(volume.dims);
    info.spacing = Some(volume.spacing());
    info.labels = Some(label_infos(&volume.structures));
    Ok(info)
}

/// A folder of masks, surfaced mask by mask as its files are read (never packed into a
/// full-size label map).
fn mask_folder_info(dir: &Path, labels: Option<&Path>) -> anyhow::Result<Info> {
    use crate::io::volume::{color_table, mask_surfaces};
    let table = match labels {
        Some(table) => color_table::read(table)?,
        None => Vec::new(),
    };
    let folder = std::sync::Mutex::new(None);
    let mut info = surfaces_info(&|each| {
        let options = csg::labels::SurfaceOptions::default();
        let found = mask_surfaces::surfaces_each(dir, &table, &options, &|_| true, &|_, s| {
            s.is_none_or(each)
        })?;
        *folder.lock().unwrap_or_else(|e| e.into_inner()) = Some(found);
        Ok(())
    })?;
    // The folder's errors name the folder or the mask file already.
    let folder = folder.into_inner().unwrap_or_else(|e| e.into_inner());
    let folder = folder.expect("set when the surfaces were made");
    let m = folder.world_from_voxel.matrix3;
    info.dims = Some(folder.dims);
    info.spacing = Some([m.x_axis.length(), m.y_axis.length(), m.z_axis.length()]);
    info.labels = Some(label_infos(&folder.structures));
    Ok(info)
}

fn label_infos(structures: &[crate::io::volume::Structure]) -> Vec<LabelInfo> {
    structures
        .iter()
        .map(|s| LabelInfo {
            value: s.value,
            name: s.name.clone(),
            color: s.color,
            voxels: s.voxels,
        })
        .collect()
}

/// What takes each structure's surface as it is made; false stops.
type SurfaceSink<'a> = dyn Fn(crate::io::volume::StructureSurface) -> bool + Sync + 'a;

/// The mesh fields of a volume's label surfaces together (`make` hands each to the sink), each surface measured by the worker
/// that made it and dropped: no surface is kept and none is copied into one large mesh. The
/// surfaces are separate meshes, so vertices, triangles, volume and the box add up, and
/// `closed`/`manifold` hold for all when they hold for each; a label's cavities are its own,
/// so `regions` is the sum of each label's regions.
fn surfaces_info(make: &dyn Fn(&SurfaceSink) -> anyhow::Result<()>) -> anyhow::Result<Info> {
    let total = std::sync::Mutex::new((Info::default(), csg::Aabb::EMPTY, 0usize));
    make(&|surface: crate::io::volume::StructureSurface| {
        let one = label_surface_info(&surface.mesh);
        let bbox = surface.mesh.bbox();
        let mut total = total.lock().unwrap_or_else(|e| e.into_inner());
        let (info, total_box, count) = &mut *total;
        info.vertices += one.vertices;
        info.triangles += one.triangles;
        info.regions += one.regions;
        info.closed = (*count == 0 || info.closed) && one.closed;
        info.manifold = (*count == 0 || info.manifold) && one.manifold;
        info.volume += one.volume;
        *total_box = total_box.union(&bbox);
        *count += 1;
        true
    })?;
    let (mut info, bbox, _) = total.into_inner().unwrap_or_else(|e| e.into_inner());
    info.bbox_min = bbox.min.to_array();
    info.bbox_max = bbox.max.to_array();
    Ok(info)
}

/// An intensity image: no surfaces (the mesh fields are zero, the box is the grid's world box),
/// its grid, and what it holds.
fn image_info(image: &crate::io::intensity::IntensityImage, reason: String) -> Info {
    let bbox = image.world_bbox();
    let m = image.world_from_voxel.matrix3;
    let (min, max) = image.range();
    Info {
        vertices: 0,
        triangles: 0,
        regions: 0,
        closed: false,
        manifold: false,
        bbox_min: bbox.min.to_array(),
        bbox_max: bbox.max.to_array(),
        volume: 0.0,
        dims: Some(image.dims),
        spacing: Some([m.x_axis.length(), m.y_axis.length(), m.z_axis.length()]),
        labels: None,
        intensity: Some(IntensityInfo {
            sample: image.kind().name(),
            min,
            max,
            reason,
        }),
    }
}

/// [`mesh_info`] of a label surface, from its guarantee ([`csg::labels::LabelSurface`]: closed,
/// oriented, manifold and free of self-intersection by construction, proved by the exact test
/// `volume_surfaces_exact` on every shared volume) instead of the full report: the regions are
/// counted without edge adjacency or rays ([`csg::regions::Regions::count_of_valid_closed`]).
fn label_surface_info(mesh: &csg::Mesh) -> Info {
    let made = !mesh.triangles.is_empty();
    let regions = csg::regions::Regions::count_of_valid_closed(mesh);
    info_of(mesh, regions, made, made)
}

fn mesh_info(mesh: &csg::Mesh) -> Info {
    let report = mesh.report();
    info_of(mesh, report.regions, report.closed, report.manifold)
}

/// The mesh fields of `mesh` with its region count and closed/manifold facts.
fn info_of(mesh: &csg::Mesh, regions: usize, closed: bool, manifold: bool) -> Info {
    let bbox = mesh.bbox();
    Info {
        vertices: mesh.positions.len(),
        triangles: mesh.triangles.len(),
        regions,
        closed,
        manifold,
        bbox_min: bbox.min.to_array(),
        bbox_max: bbox.max.to_array(),
        volume: mesh.volume(),
        dims: None,
        spacing: None,
        labels: None,
        intensity: None,
    }
}

pub fn run(args: &InfoArgs) -> anyhow::Result<()> {
    let info = info_with_labels(&args.mesh, args.labels.as_deref())?;
    let text = if args.json {
        format!("{}\n", serde_json::to_string(&info)?)
    } else {
        table(&args.mesh, &info)
    };
    // `print!` would panic on a closed pipe (`cutaway info … | head -0`); report it instead.
    let mut stdout = std::io::stdout().lock();
    stdout
        .write_all(text.as_bytes())
        .and_then(|()| stdout.flush())?;
    Ok(())
}

/// The human-readable form: one fact per line, names aligned.
fn table(path: &Path, info: &Info) -> String {
    let yes_no = |b: bool| if b { "yes" } else { "no" };
    let xyz = |v: [f64; 3]| format!("{} {} {}", v[0], v[1], v[2]);
    let size = [0, 1, 2].map(|k| info.bbox_max[k] - info.bbox_min[k]);
    let volume = if info.closed {
        info.volume.to_string()
    } else {
        format!("{} (not meaningful: the mesh is open)", info.volume)
    };
    if let Some(image) = &info.intensity {
        let mut text = format!("{:<10} {}\n", "file", path.display());
        text += &format!(
            "{:<10} intensity image ({}), not labels: open it with --image or on its own\n",
            "content", image.reason
        );
        text += &format!(
            "{:<10} {}, {} to {}\n",
            "values", image.sample, image.min, image.max
        );
        if let (Some(dims), Some(spacing)) = (info.dims, info.spacing) {
            text += &format!("{:<10} {} {} {}\n", "dims", dims[0], dims[1], dims[2]);
            text += &format!("{:<10} {}\n", "spacing", xyz(spacing));
        }
        text += &format!("{:<10} {}\n", "bbox min", xyz(info.bbox_min));
        text += &format!("{:<10} {}\n", "bbox max", xyz(info.bbox_max));
        return text;
    }
    let rows = [
        ("file", path.display().to_string()),
        ("vertices", info.vertices.to_string()),
        ("triangles", info.triangles.to_string()),
        ("regions", info.regions.to_string()),
        ("closed", yes_no(info.closed).to_owned()),
        ("manifold", yes_no(info.manifold).to_owned()),
        ("bbox min", xyz(info.bbox_min)),
        ("bbox max", xyz(info.bbox_max)),
        ("bbox size", xyz(size)),
        ("volume", volume),
    ];
    let mut text: String = rows
        .iter()
        .map(|(name, value)| format!("{name:<10} {value}\n"))
        .collect();
    if let (Some(dims), Some(spacing)) = (info.dims, info.spacing) {
        text += &format!("{:<10} {} {} {}\n", "dims", dims[0], dims[1], dims[2]);
        text += &format!("{:<10} {}\n", "spacing", xyz(spacing));
    }
    for label in info.labels.iter().flatten() {
        let [r, g, b] = label.color;
        text += &format!(
            "label {:<4} {} ({} voxels, colour {r} {g} {b})\n",
            label.value, label.name, label.voxels
        );
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn json_fields_are_in_contract_order() {
        let info = Info {
            vertices: 8,
            triangles: 12,
            regions: 1,
            closed: true,
            manifold: true,
            bbox_min: [0.0, 0.0, 0.0],
            bbox_max: [1.0, 2.0, 3.5],
            volume: 7.0,
            dims: None,
            spacing: None,
            labels: None,
            intensity: None,
        };
        assert_eq!(
            serde_json::to_string(&info).unwrap(),
            r#"{"vertices":8,"triangles":12,"regions":1,"closed":true,"manifold":true,"bbox_min":[0.0,0.0,0.0],"bbox_max":[1.0,2.0,3.5],"volume":7.0}"#
        );
        let text = table(Path::new("cube.obj"), &info);
        assert!(text.contains("triangles  12\n"), "{text}");
        assert!(text.contains("bbox size  1 2 3.5\n"), "{text}");
    }

    #[test]
    fn volume_fields_follow_the_mesh_fields() {
        let info = Info {
            vertices: 8,
            triangles: 12,
            regions: 1,
            closed: true,
            manifold: true,
            bbox_min: [0.0; 3],
            bbox_max: [1.0; 3],
            volume: 1.0,
            dims: Some([4, 5, 6]),
            spacing: Some([1.0, 0.5, 2.0]),
            labels: Some(vec![LabelInfo {
                value: 3,
                name: "skin".into(),
                color: [225, 190, 150],
                voxels: 42,
            }]),
            intensity: None,
        };
        let json = serde_json::to_string(&info).unwrap();
        assert!(
            json.ends_with(r#""volume":1.0,"dims":[4,5,6],"spacing":[1.0,0.5,2.0],"labels":[{"value":3,"name":"skin","color":[225,190,150],"voxels":42}]}"#),
            "{json}"
        );
        let text = table(Path::new("a.nrrd"), &info);
        assert!(
            text.contains("label 3    skin (42 voxels, colour 225 190 150)"),
            "{text}"
        );
    }
}
