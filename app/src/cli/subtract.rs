//! `cutaway subtract TARGET CUTTER --out DIR --json`.
//!
//! Reads both meshes, then [`cut_mesh`] builds the target index (not timed), cuts with [`csg::subtract`]
//! (timed: `cut_ms`, what one drag frame of the editor pays against the cached index), builds the
//! full kept and removed meshes from the cut's deltas (timed: `materialize_ms`), then writes
//! `kept.obj`, `walls.obj`, `removed.obj` and `contour.obj` into DIR, and for a target with more
//! than one region each region's `regions/<index>/{kept,walls,removed}.obj` (see
//! `../shared/CONTRACT.md`). Every region is cut as its own solid (see [`csg::subtract`]), so
//! each closed region's kept + walls and removed + reversed walls are closed; the JSON reports
//! per region whether they are, measured on the meshes written.
//!
//! All files are written by [`write_outputs`] as one output set that replaces the previous run's
//! outputs as a whole.

use std::path::{Path, PathBuf};

use crate::cutting::mesh_cut::{MeshCut, MeshCutError, cut_mesh};

#[derive(Debug, clap::Args)]
pub struct SubtractArgs {
    /// The anatomy to cut (every region of it).
    pub target: PathBuf,
    /// The closed cutter (quads or triangles).
    pub cutter: PathBuf,
    /// Output folder for kept.obj, walls.obj, removed.obj, contour.obj (and regions/).
    #[arg(long)]
    pub out: PathBuf,
    /// Print one JSON object (see CONTRACT.md).
    #[arg(long)]
    pub json: bool,
}

/// The JSON printed by `--json` (field names fixed by the contract).
#[derive(Debug, serde::Serialize)]
pub struct SubtractReport {
    pub target_triangles: usize,
    pub cutter_triangles: usize,
    pub kept_triangles: usize,
    pub walls_triangles: usize,
    pub removed_triangles: usize,
    pub contour_loops: usize,
    /// `cut_ms` + `materialize_ms`.
    pub boolean_ms: f64,
    /// The local cut against the cached index.
    pub cut_ms: f64,
    /// Building the full kept and removed meshes from the cut.
    pub materialize_ms: f64,
    /// One entry per region, only when the target has more than one.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub regions: Vec<RegionReport>,
}

pub use crate::cutting::mesh_cut::RegionReport;

pub fn run(args: &SubtractArgs) -> anyhow::Result<()> {
    let target = crate::io::read_mesh(&args.target)?;
    let cutter = crate::io::read_mesh(&args.cutter)?;
    // It is one first cut in a fresh process, slower than the warm figure of
    // `cargo bench -p csg --bench boolean`.
    let cut = cut_mesh(target, &cutter).map_err(|e| match e {
        MeshCutError::Target(e) => e.context(args.target.display().to_string()),
        MeshCutError::Cutter(e) => e.context(args.cutter.display().to_string()),
    })?;
    write_outputs(&args.out, &cut)?;

    let report = SubtractReport {
        target_triangles: cut.target_triangles,
        cutter_triangles: cut.cutter_triangles,
        kept_triangles: cut.kept.triangles.len(),
        walls_triangles: cut.walls.triangles.len(),
        removed_triangles: cut.removed.triangles.len(),
        contour_loops: cut.contour.len(),
        boolean_ms: cut.cut_ms + cut.materialize_ms,
        cut_ms: cut.cut_ms,
        materialize_ms: cut.materialize_ms,
        regions: cut.region_reports.clone(),
    };
    if args.json {
        println!("{}", serde_json::to_string(&report)?);
    } else {
        println!(
            "kept {} triangles, walls {}, removed {}, {} contour loop(s), boolean {:.2} ms (cut {:.2} ms, materialize {:.2} ms)",
            report.kept_triangles,
            report.walls_triangles,
            report.removed_triangles,
            report.contour_loops,
            report.boolean_ms,
            report.cut_ms,
            report.materialize_ms
        );
        for r in &report.regions {
            println!(
                "  region {}: kept {}, walls {}, removed {}, removed volume {}, closed {}",
                r.index,
                r.kept_triangles,
                r.walls_triangles,
                r.removed_triangles,
                r.removed_volume,
                r.closed
            );
        }
    }
    Ok(())
}

/// Writes every output file into `dir` as one [`crate::io::OutputSet`]: the four union files,
/// then each region's three. The set replaces the previous run's outputs as a whole (a kill at
/// any moment leaves the old set or the new one once the next run, or
/// [`crate::io::recover_output_set`], has looked at `dir`), and `regions/` is replaced wholly so
/// no region folder of an earlier, larger target stays behind.
pub fn write_outputs(dir: &Path, outputs: &MeshCut) -> anyhow::Result<()> {
    let mut set = crate::io::OutputSet::begin(dir)?;
    set.write_mesh(Path::new("kept.obj"), &outputs.kept)?;
    set.write_mesh(Path::new("walls.obj"), &outputs.walls)?;
    set.write_mesh(Path::new("removed.obj"), &outputs.removed)?;
    set.write_obj_polylines(Path::new("contour.obj"), &outputs.contour)?;
    set.replace_folder(Path::new("regions"))?;
    for (i, parts) in outputs.regions.iter().enumerate() {
        let folder = Path::new("regions").join(i.to_string());
        set.write_mesh(&folder.join("kept.obj"), &parts.kept)?;
        set.write_mesh(&folder.join("walls.obj"), &parts.walls)?;
        set.write_mesh(&folder.join("removed.obj"), &parts.removed)?;
    }
    set.commit()
}
