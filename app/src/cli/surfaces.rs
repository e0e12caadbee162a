//! `cutaway surfaces VOLUME --out DIR [--labels TABLE] [--smoothing F] [--decimate F]
//! [--format ply|obj|stl] --json`: one closed surface per label of a segmentation volume, written as
//! `DIR/<value>_<name>.<ext>` (see `../shared/CONTRACT.md`).
//!
//! The files are written as one output set (`io::atomic`): an error (a full disk, a bad label)
//! leaves none of the new files behind, and a kill leaves the old set or the new one. The set
//! replaces the surfaces of an earlier run in DIR: files named like ours (`<digits>_<name>.` and a
//! mesh extension we write) that the new run does not write are removed at commit; other files in
//! DIR stay.
//! `surfaces_ms` is the wall time from opening the volume to the last file renamed, the report
//! included.

use std::collections::HashSet;
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

use anyhow::Context as _;
use serde::Serialize;

use crate::io::volume::{self, Structure};

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
///
/// Each surface is handed over as soon as a worker has made it: the worker measures what the
/// report needs (triangles, `closed`, volume) and a writer thread stages the file while the
/// other surfaces are still being made, so no mesh is kept after its file is written and
/// nothing is computed after the clock stops. A folder of masks is surfaced mask by mask as its
/// files are read ([`volume::mask_surfaces`]).
pub fn surfaces(args: &SurfacesArgs) -> anyhow::Result<SurfacesReport> {
    let clock = Instant::now();
    let options = volume::array::surface_options(args.smoothing, args.decimate)?;
    let ext = args.format.extension();
    // A volume's structures are known before any surface (their names made distinct up front);
    // a mask folder's as each mask is read and surfaced (its values are distinct).
    let folder = args.volume.is_dir();
    let volume = if folder {
        None
    } else {
        Some(volume::read_volume(&args.volume, args.labels.as_deref())?)
    };
    let table = match (&args.labels, folder) {
        (Some(table), true) => volume::color_table::read(table)?,
        _ => Vec::new(),
    };
    let known: Vec<(Structure, String)> = match &volume {
        Some(v) => v
            .structures
            .iter()
            .cloned()
            .zip(file_names(&v.structures, ext))
            .collect(),
        None => Vec::new(),
    };
    let name_of = |s: &Structure| match known
        .binary_search_by_key(&(s.value, s.layer), |(k, _)| (k.value, k.layer))
    {
        Ok(i) => known[i].1.clone(),
        Err(_) => file_names(std::slice::from_ref(s), ext).remove(0),
    };
    let mut set = crate::io::OutputSet::begin(&args.out)?;
    let arrived: Mutex<Vec<(Structure, String, MeshFacts)>> = Mutex::new(Vec::new());
    let write_error: Mutex<Option<anyhow::Error>> = Mutex::new(None);
    let stop = AtomicBool::new(false);
    let made = std::thread::scope(|scope| {
        let (to_writer, from_workers) = std::sync::mpsc::channel::<(String, csg::Mesh)>();
        let writer = scope.spawn(|| {
            for (name, mesh) in from_workers {
                if stop.load(Ordering::Relaxed) {
                    continue;
                }
                if let Err(e) = set.write_mesh(Path::new(&name), &mesh) {
                    *write_error.lock().unwrap_or_else(|e| e.into_inner()) = Some(e);
                    stop.store(true, Ordering::Relaxed);
                }
            }
        });
        let to_writer = Mutex::new(to_writer);
        let each = |surface: volume::StructureSurface| {
            let name = name_of(&surface.structure);
            let measured = MeshFacts::of(&surface.mesh);
            lock(&arrived).push((surface.structure, name.clone(), measured));
            let sent = lock(&to_writer).send((name, surface.mesh)).is_ok();
            sent && !stop.load(Ordering::Relaxed)
        };
        let made = match &volume {
            Some(v) => volume::surfaces_each(v, options.clone(), &|_| true, &each)
                .with_context(|| args.volume.display().to_string()),
            // Its errors name the folder or the mask file.
            None => volume::mask_surfaces::surfaces_each(
                &args.volume,
                &table,
                &options,
                &|_| true,
                &|_, surface| surface.is_none_or(&each),
            )
            .map(|_| ()),
        };
        drop(to_writer);
        writer.join().expect("the surface writer thread panicked");
        made
    });
    if let Some(e) = write_error.into_inner().unwrap_or_else(|e| e.into_inner()) {
        return Err(e);
    }
    made?;
    for earlier in earlier_surface_files(&args.out)? {
        set.replace_file(&earlier)?;
    }
    set.commit()?;
    let mut arrived = arrived.into_inner().unwrap_or_else(|e| e.into_inner());
    arrived.sort_by_key(|(s, _, _)| (s.value, s.layer));
    let entries = arrived
        .into_iter()
        .map(|(s, name, facts)| SurfaceEntry {
            value: s.value,
            name: s.name,
            color: s.color,
            voxels: s.voxels,
            triangles: facts.triangles,
            closed: facts.closed,
            volume: facts.volume,
            file: args.out.join(name).display().to_string(),
        })
        .collect::<Vec<_>>();
    let surfaces_ms = clock.elapsed().as_secs_f64() * 1e3;
    Ok(SurfacesReport {
        labels: entries.len(),
        surfaces_ms,
        surfaces: entries,
    })
}

fn lock<T>(m: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|e| e.into_inner())
}

/// What the report says of one surface, measured by the worker that made it.
#[derive(Clone, Copy, Debug)]
struct MeshFacts {
    triangles: usize,
    closed: bool,
    volume: f64,
}

impl MeshFacts {
    /// `closed` is the guarantee of [`csg::labels::LabelSurface`]: closed and oriented by
    /// construction (decimated ones by the exact check that decimation runs), proved on every
    /// label of every shared volume by the exact test `volume_surfaces_exact`, on random grids
    /// by the labels' property tests, and asserted on every surface a debug build makes. No
    /// check runs here: the linear one was a sixth of the command's time.
    fn of(mesh: &csg::Mesh) -> MeshFacts {
        MeshFacts {
            triangles: mesh.triangles.len(),
            closed: !mesh.triangles.is_empty(),
            volume: mesh.volume(),
        }
    }
}

/// `<value>_<name>.<ext>` per structure, the name made safe for every file system (letters,
/// digits, `-`, `_` and `.` kept, anything else `_`; at most 80 characters); a name that would
/// repeat (two layers with the same value and name) gets `_layer<n>`.
pub fn file_names(structures: &[Structure], ext: &str) -> Vec<String> {
    let mut used = HashSet::new();
    structures
        .iter()
        .map(|s| {
            let base = format!("{}_{}", s.value, sanitize(&s.name));
            let mut name = format!("{base}.{ext}");
            if !used.insert(name.to_ascii_lowercase()) {
                name = format!("{base}_layer{}.{ext}", s.layer);
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

    fn surface(value: u32, layer: usize, name: &str) -> Structure {
        Structure {
            layer,
            value,
            name: name.into(),
            color: [0, 0, 0],
            voxels: 1,
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

    /// A folder with no volume file is one error that names it once.
    #[test]
    fn a_folder_without_volumes_is_named_once() {
        let dir =
            std::env::temp_dir().join(format!("cutaway-surfaces-no-masks-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("notes.txt"), "not a mask").unwrap();
        let args = SurfacesArgs {
            volume: dir.clone(),
            out: dir.join("out"),
            labels: None,
            smoothing: None,
            decimate: None,
            format: MeshFormat::Ply,
            json: true,
        };
        let err = format!("{:#}", surfaces(&args).unwrap_err());
        let named = dir.display().to_string();
        assert_eq!(err.matches(&named).count(), 1, "{err}");
        assert!(err.contains("no volume files"), "{err}");
        std::fs::remove_dir_all(&dir).ok();
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
