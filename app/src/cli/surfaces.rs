//! `cutaway surfaces VOLUME --out DIR [--labels TABLE] [--smoothing F] [--decimate F]
//! [--format ply|obj|stl] --json`: one closed surface per label of a segmentation volume, written as
//! `DIR/<value>_<name>.<ext>` (see `../shared/CONTRACT.md`).
//!
//! The files are written as one output set (`io::atomic`): an error (a full disk, a bad label)
//! leaves none of the new files behind, and a kill leaves the old set or the new one. The set
//! replaces the surfaces of an earlier run in DIR: files named like ours (`<digits>_<name>.` and a
//! mesh extension we write) that the new run does not write are removed at commit; other files in
//! DIR stay.
//! `surfaces_ms` is the wall time from opening the volume to the last file renamed.

use std::collections::HashSet;
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::Context as _;
use serde::Serialize;

use crate::io::volume::{self, StructureSurface};

#[derive(Debug, clap::Args)]
pub struct SurfacesArgs {
    /// The label volume (.nrrd, .seg.nrrd, .nhdr, .nii, .nii.gz, or a folder of masks).
    pub volume: PathBuf,
    /// Output folder (created if missing).
    #[arg(long)]
    pub out: PathBuf,
    /// Colour table naming the labels (Slicer .ctbl/.txt, FreeSurfer LUT, ITK-SNAP).
    #[arg(long)]
    pub labels: Option<PathBuf>,
    /// Smoothing, 0 (voxel surface) to 1 (strongest); default that of `csg::labels`.
    #[arg(long)]
    pub smoothing: Option<f64>,
    /// Keep this fraction of each surface's triangles (0 < F <= 1) by quadric edge collapse;
    /// each decimated surface is checked to stay closed and free of self-intersection.
    #[arg(long)]
    pub decimate: Option<f64>,
    /// Mesh file format.
    #[arg(long, value_enum, default_value_t = MeshFormat::Ply)]
    pub format: MeshFormat,
    /// Print one JSON object (see CONTRACT.md).
    #[arg(long)]
    pub json: bool,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum MeshFormat {
    Ply,
    Obj,
    Stl,
}

impl MeshFormat {
    fn extension(self) -> &'static str {
        match self {
            MeshFormat::Ply => "ply",
            MeshFormat::Obj => "obj",
            MeshFormat::Stl => "stl",
        }
    }
}

/// The `surfaces --json` object (field order is the contract's).
#[derive(Debug, Serialize)]
pub struct SurfacesReport {
    pub labels: usize,
    pub surfaces_ms: f64,
    pub surfaces: Vec<SurfaceEntry>,
}

#[derive(Debug, Serialize)]
pub struct SurfaceEntry {
    pub value: u32,
    pub name: String,
    /// sRGB, 0..=255.
    pub color: [u8; 3],
    pub voxels: u64,
    pub triangles: usize,
    pub closed: bool,
    pub volume: f64,
    /// The file written (DIR joined with `<value>_<name>.<ext>`).
    pub file: String,
}

pub fn run(args: &SurfacesArgs) -> anyhow::Result<()> {
    let report = surfaces(args)?;
    let text = if args.json {
        format!("{}\n", serde_json::to_string(&report)?)
    } else {
        let mut text = String::new();
        for s in &report.surfaces {
            text += &format!(
                "{:>5} {:<40} {:>9} voxels {:>9} triangles  {}\n",
                s.value, s.name, s.voxels, s.triangles, s.file
            );
        }
        text + &format!(
            "{} surfaces in {:.0} ms\n",
            report.labels, report.surfaces_ms
        )
    };
    let mut stdout = std::io::stdout().lock();
    stdout
        .write_all(text.as_bytes())
        .and_then(|()| stdout.flush())?;
    Ok(())
}

/// All the work of `cutaway surfaces` except printing.
pub fn surfaces(args: &SurfacesArgs) -> anyhow::Result<SurfacesReport> {
    let clock = Instant::now();
    let options = volume::array::surface_options(args.smoothing, args.decimate)?;
    let volume = volume::read_volume(&args.volume, args.labels.as_deref())?;
    let surfaces = volume::surfaces_with(&volume, options, &|_| true)
        .with_context(|| args.volume.display().to_string())?;
    let names = file_names(&surfaces, args.format.extension());
    let files: Vec<PathBuf> = names.iter().map(|n| args.out.join(n)).collect();
    write_set(&args.out, &names, &surfaces)?;
    let surfaces_ms = clock.elapsed().as_secs_f64() * 1e3;
    let entries = surfaces
        .iter()
        .zip(&files)
        .map(|(s, file)| {
            let report = s.mesh.report();
            SurfaceEntry {
                value: s.structure.value,
                name: s.structure.name.clone(),
                color: s.structure.color,
                voxels: s.structure.voxels,
                triangles: s.mesh.triangles.len(),
                closed: report.closed,
                volume: s.mesh.volume(),
                file: file.display().to_string(),
            }
        })
        .collect();
    Ok(SurfacesReport {
        labels: surfaces.len(),
        surfaces_ms,
        surfaces: entries,
    })
}

/// `<value>_<name>.<ext>` per surface, the name made safe for every file system (letters,
/// digits, `-`, `_` and `.` kept, anything else `_`; at most 80 characters); a name that would
/// repeat (two layers with the same value and name) gets `_layer<n>`.
pub fn file_names(surfaces: &[StructureSurface], ext: &str) -> Vec<String> {
    let mut used = HashSet::new();
    surfaces
        .iter()
        .map(|s| {
            let base = format!("{}_{}", s.structure.value, sanitize(&s.structure.name));
            let mut name = format!("{base}.{ext}");
            if !used.insert(name.to_ascii_lowercase()) {
                name = format!("{base}_layer{}.{ext}", s.structure.layer);
                used.insert(name.to_ascii_lowercase());
            }
            name
        })
        .collect()
}

fn sanitize(name: &str) -> String {
    let cleaned: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' || c == '.' {
                c
            } else {
                '_'
            }
        })
        .take(80)
        .collect();
    let cleaned = cleaned.trim_matches('.');
    if cleaned.is_empty() {
        "label".to_owned()
    } else {
        cleaned.to_owned()
    }
}

/// Writes every surface into `dir` as one [`crate::io::OutputSet`]: on any error none of the new
/// files is in place, and a kill leaves the old set or the new one (see `io::atomic`).
fn write_set(dir: &Path, names: &[String], surfaces: &[StructureSurface]) -> anyhow::Result<()> {
    let mut set = crate::io::OutputSet::begin(dir)?;
    for (name, s) in names.iter().zip(surfaces) {
        set.write_mesh(Path::new(name), &s.mesh)?;
    }
    for earlier in earlier_surface_files(dir)? {
        set.replace_file(&earlier)?;
    }
    set.commit()
}

/// The regular files directly in `dir` named like a surface of an earlier run: `<digits>_`, then
/// anything, then `.ply`, `.obj` or `.stl`.
fn earlier_surface_files(dir: &Path) -> anyhow::Result<Vec<PathBuf>> {
    let entries =
        std::fs::read_dir(dir).with_context(|| format!("{}: cannot list", dir.display()))?;
    let mut out = Vec::new();
    for entry in entries.flatten() {
        let name = entry.file_name();
        let Some(name) = name.to_str() else { continue };
        if entry.file_type().is_ok_and(|t| t.is_file()) && is_surface_file_name(name) {
            out.push(PathBuf::from(name));
        }
    }
    Ok(out)
}

/// True for names [`file_names`] makes: `<digits>_<name>.<ply|obj|stl>`, not hidden.
fn is_surface_file_name(name: &str) -> bool {
    let Some((stem, ext)) = name.rsplit_once('.') else {
        return false;
    };
    let Some((value, rest)) = stem.split_once('_') else {
        return false;
    };
    let known_ext = [MeshFormat::Ply, MeshFormat::Obj, MeshFormat::Stl]
        .iter()
        .any(|f| f.extension() == ext);
    known_ext && !value.is_empty() && value.bytes().all(|b| b.is_ascii_digit()) && !rest.is_empty()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::volume::Structure;

    fn surface(value: u32, layer: usize, name: &str) -> StructureSurface {
        StructureSurface {
            structure: Structure {
                layer,
                value,
                name: name.into(),
                color: [0, 0, 0],
                voxels: 1,
            },
            mesh: csg::Mesh::default(),
        }
    }

    #[test]
    fn surface_file_names_are_recognised() {
        for name in [
            "1_right_lung.ply",
            "4_Left-Hippocampus_layer1.obj",
            "17_label.stl",
        ] {
            assert!(is_surface_file_name(name), "{name}");
        }
        for name in [
            "notes.txt",
            "1_a.vtk",
            "a_1.ply",
            "_x.ply",
            "12_.ply",
            "12.ply",
            "x1_a.ply",
        ] {
            assert!(!is_surface_file_name(name), "{name}");
        }
    }

    #[test]
    fn file_names_are_safe_and_distinct() {
        let s = [
            surface(1, 0, "right lung"),
            surface(2, 0, "a/b\\c:d*"),
            surface(3, 0, "..."),
            surface(4, 0, "Left-Hippocampus"),
            surface(4, 1, "Left-Hippocampus"),
        ];
        assert_eq!(
            file_names(&s, "ply"),
            [
                "1_right_lung.ply",
                "2_a_b_c_d_.ply",
                "3_label.ply",
                "4_Left-Hippocampus.ply",
                "4_Left-Hippocampus_layer1.ply"
            ]
        );
    }
}
