//! `cutaway subtract TARGET CUTTER --out DIR --json`. OWNER: boolean helper.
//!
//! Reads both meshes, builds the target index (not timed), cuts with [`csg::subtract`] and builds
//! the removed piece (timed: `boolean_ms`), then writes `kept.obj`, `walls.obj`, `removed.obj`
//! and `contour.obj` into DIR (see `../shared/CONTRACT.md`).
//!
//! The outputs are one [`crate::io::OutputSet`]: they replace the previous run's outputs as a
//! whole, and a kill at any moment leaves the old set or the new one once the next run (or
//! [`crate::io::recover_output_set`]) has looked at DIR. More outputs join the set by one more
//! `set.write_…` call before the commit.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::Context;

#[derive(Debug, clap::Args)]
pub struct SubtractArgs {
    /// The anatomy to cut (every region of it).
    pub target: PathBuf,
    /// The closed cutter (quads or triangles).
    pub cutter: PathBuf,
    /// Output folder for kept.obj, walls.obj, removed.obj, contour.obj.
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
    pub boolean_ms: f64,
}

pub fn run(args: &SubtractArgs) -> anyhow::Result<()> {
    let target = crate::io::read_mesh(&args.target)?;
    let cutter = crate::io::read_mesh(&args.cutter)?;
    let target_triangles = target.triangles.len();
    let index =
        csg::TargetIndex::build(target).with_context(|| args.target.display().to_string())?;

    // The clock covers the cut and building the removed piece's mesh (the boolean returns it as
    // a delta and builds it on first read), so `boolean_ms` is the whole boolean; it excludes
    // copying the kept part out of the target for writing. It is one first cut in a fresh
    // process, slower than the warm figure of `cargo bench -p csg --bench boolean`.
    let clock = Instant::now();
    let result =
        csg::subtract(&index, &cutter).with_context(|| args.cutter.display().to_string())?;
    let removed = result.removed.part();
    let boolean_ms = clock.elapsed().as_secs_f64() * 1e3;

    let mut set = crate::io::OutputSet::begin(&args.out)?;
    let kept = result.kept_mesh(index.mesh());
    set.write_mesh(Path::new("kept.obj"), &kept)?;
    set.write_mesh(Path::new("walls.obj"), &result.walls.mesh)?;
    set.write_mesh(Path::new("removed.obj"), &removed.mesh)?;
    let polylines: Vec<Vec<glam::DVec3>> = result
        .contours
        .iter()
        .map(|c| {
            let mut p = c.points.clone();
            if c.closed
                && let Some(&first) = p.first()
            {
                p.push(first); // written as a closed `l` record
            }
            p
        })
        .collect();
    set.write_obj_polylines(Path::new("contour.obj"), &polylines)?;
    set.commit()?;

    let report = SubtractReport {
        target_triangles,
        cutter_triangles: cutter.triangles.len(),
        kept_triangles: kept.triangles.len(),
        walls_triangles: result.walls.mesh.triangles.len(),
        removed_triangles: removed.mesh.triangles.len(),
        contour_loops: result.contours.len(),
        boolean_ms,
    };
    if args.json {
        println!("{}", serde_json::to_string(&report)?);
    } else {
        println!(
            "kept {} triangles, walls {}, removed {}, {} contour loop(s), boolean {:.2} ms",
            report.kept_triangles,
            report.walls_triangles,
            report.removed_triangles,
            report.contour_loops,
            report.boolean_ms
        );
    }
    Ok(())
}
