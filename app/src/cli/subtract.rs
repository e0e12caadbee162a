//! `cutaway subtract TARGET CUTTER --out DIR --json`.
//!
//! Reads both meshes and builds the target index (not timed), cuts with [`csg::subtract`]
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
use std::time::Instant;

use anyhow::Context;
use csg::Mesh;

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

/// One region's share of the cut (`regions` of the JSON).
#[derive(Debug, serde::Serialize)]
pub struct RegionReport {
    pub index: usize,
    pub kept_triangles: usize,
    pub walls_triangles: usize,
    pub removed_triangles: usize,
    /// Volume of the removed solid (removed + reversed walls).
    pub removed_volume: f64,
    /// kept + walls and removed + reversed walls are both closed (welded by exact position).
    pub closed: bool,
}

/// Everything `subtract` writes into DIR.
struct Outputs {
    kept: Mesh,
    walls: Mesh,
    removed: Mesh,
    contour: Vec<Vec<glam::DVec3>>,
    /// Per region: kept, walls, removed (empty for a target with one region).
    regions: Vec<csg::RegionParts>,
}

pub fn run(args: &SubtractArgs) -> anyhow::Result<()> {
    let target = crate::io::read_mesh(&args.target)?;
    let cutter = crate::io::read_mesh(&args.cutter)?;
    let target_triangles = target.triangles.len();
    let index =
        csg::TargetIndex::build(target).with_context(|| args.target.display().to_string())?;

    // Two clocks: the cut itself (kept and removed come back as deltas against the cached
    // target, as in the editor), then building the full meshes a file needs. It is one first
    // cut in a fresh process, slower than the warm figure of `cargo bench -p csg --bench boolean`.
    let clock = Instant::now();
    let result =
        csg::subtract(&index, &cutter).with_context(|| args.cutter.display().to_string())?;
    let cut_ms = clock.elapsed().as_secs_f64() * 1e3;
    let clock = Instant::now();
    let removed = result.removed.part().mesh.clone();
    let kept = result.kept_mesh(index.mesh());
    let materialize_ms = clock.elapsed().as_secs_f64() * 1e3;

    let regions = if index.regions.count > 1 {
        result.region_parts(&index)
    } else {
        Vec::new()
    };
    let region_reports: Vec<RegionReport> = regions
        .iter()
        .enumerate()
        .map(|(index, parts)| region_report(index, parts))
        .collect();
    let outputs = Outputs {
        kept,
        walls: result.walls.mesh.clone(),
        removed,
        contour: contour_polylines(&result.contours),
        regions,
    };
    write_outputs(&args.out, &outputs)?;

    let report = SubtractReport {
        target_triangles,
        cutter_triangles: cutter.triangles.len(),
        kept_triangles: outputs.kept.triangles.len(),
        walls_triangles: outputs.walls.triangles.len(),
        removed_triangles: outputs.removed.triangles.len(),
        contour_loops: result.contours.len(),
        boolean_ms: cut_ms + materialize_ms,
        cut_ms,
        materialize_ms,
        regions: region_reports,
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

/// The contours as polylines, a closed loop with its first point repeated at the end (written
/// as a closed `l` record).
fn contour_polylines(contours: &[csg::Contour]) -> Vec<Vec<glam::DVec3>> {
    contours
        .iter()
        .map(|c| {
            let mut p = c.points.clone();
            if c.closed
                && let Some(&first) = p.first()
            {
                p.push(first);
            }
            p
        })
        .collect()
}

/// The JSON entry of region `index`: its triangle counts, the volume of its removed solid and
/// whether both of its solids close up (measured on the welded meshes, not assumed).
fn region_report(index: usize, parts: &csg::RegionParts) -> RegionReport {
    let joined = |a: &Mesh, b: &Mesh| {
        let mut m = a.clone();
        m.append(b);
        csg::weld::weld_exact(&m)
    };
    let kept_walls = joined(&parts.kept, &parts.walls);
    let removed_walls = joined(&parts.removed, &parts.walls.reversed());
    let closed_manifold = |m: &Mesh| {
        let r = m.report();
        r.closed && r.misoriented_edges == 0
    };
    RegionReport {
        index,
        kept_triangles: parts.kept.triangles.len(),
        walls_triangles: parts.walls.triangles.len(),
        removed_triangles: parts.removed.triangles.len(),
        removed_volume: csg::cutcheck::volume(&removed_walls),
        closed: closed_manifold(&kept_walls) && closed_manifold(&removed_walls),
    }
}

/// Writes every output file into `dir` as one [`crate::io::OutputSet`]: the four union files,
/// then each region's three. The set replaces the previous run's outputs as a whole (a kill at
/// any moment leaves the old set or the new one once the next run, or
/// [`crate::io::recover_output_set`], has looked at `dir`), and `regions/` is replaced wholly so
/// no region folder of an earlier, larger target stays behind.
fn write_outputs(dir: &Path, outputs: &Outputs) -> anyhow::Result<()> {
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
