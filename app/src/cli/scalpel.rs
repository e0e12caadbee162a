//! `cutaway scalpel TARGET --path P.json --out OUT.obj --json`.
//!
//! Replays a `cutaway-path/1` file through the same [`cutter::scalpel::Scalpel`] the GUI's
//! Scalpel mode drives: one step per sample, strokes one after another; with a depth, each
//! stroke is then repeated on every stacked surface the blade reaches (multi-layer, see
//! `cutter::scalpel::layers`); then the opening (if the file asks for one) is evaluated after its
//! whole time window. `steps` and the step times count the path file's samples only. Any failed step is an error naming
//! the path file, the stroke and the point; nothing is written then.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::anyhow;
use cutter::scalpel::dffd::open_positions;
use cutter::scalpel::invariants::validate;
use cutter::scalpel::layers::{LayerStroke, layer_strokes};
use cutter::scalpel::{Scalpel, ScalpelOptions, Tool};

#[derive(Debug, clap::Args)]
pub struct ScalpelArgs {
    /// The surface to cut.
    pub target: PathBuf,
    /// A `cutaway-path/1` file.
    #[arg(long)]
    pub path: PathBuf,
    /// Where to write the cut mesh.
    #[arg(long)]
    pub out: PathBuf,
    /// Print one JSON object (see CONTRACT.md).
    #[arg(long)]
    pub json: bool,
}

pub fn run(args: &ScalpelArgs) -> anyhow::Result<()> {
    let path_file = crate::path_file::read_path_file(&args.path)?;
    let mesh = crate::io::read_mesh(&args.target)?;
    let target = args.target.display();
    let options = ScalpelOptions::default()
        .with_depth(path_file.depth)
        .with_tool(path_file.tool);
    let mut scalpel = Scalpel::new(&mesh, options).map_err(|e| anyhow!("{target}: {e}"))?;
    let triangles_before = scalpel.dyn_mesh().triangle_count();
    // Multi-layer: what the blade meets below each stroke, found on the uncut input.
    let layers: Vec<Vec<LayerStroke>> = if path_file.depth > 0.0 && path_file.tool == Tool::Scalpel
    {
        let index = csg::SpatialIndex::build(&mesh);
        let regions = csg::regions::Regions::build(&mesh, &csg::EdgeAdjacency::build(&mesh));
        path_file
            .strokes
            .iter()
            .map(|stroke| layer_strokes(&mesh, &index, &regions, stroke, path_file.depth))
            .collect()
    } else {
        vec![Vec::new(); path_file.strokes.len()]
    };
    let mut step_us: Vec<f64> = Vec::new();
    let mut triangles_cut = 0usize;
    let file = args.path.display();
    for (s, stroke) in path_file.strokes.iter().enumerate() {
        for (k, &q) in stroke.iter().enumerate() {
            let start = Instant::now();
            let r = if k == 0 {
                scalpel.begin_stroke(q)
            } else {
                scalpel.step(q)
            };
            step_us.push(start.elapsed().as_secs_f64() * 1e6);
            r.map_err(|e| anyhow!("{file}: stroke {s} point {k}: {e}"))?;
        }
        let report = scalpel
            .end_stroke()
            .map_err(|e| anyhow!("{file}: stroke {s}: {e}"))?;
        triangles_cut += report.triangles_cut;
        // The same stroke on every surface below, with the depth left there.
        for (l, layer) in layers[s].iter().enumerate() {
            scalpel.set_options(options.with_depth(layer.depth));
            let mut r = scalpel.begin_stroke(layer.samples[0]);
            for &q in &layer.samples[1..] {
                r = r.and_then(|_| scalpel.step(q));
            }
            let report = r
                .and_then(|_| scalpel.end_stroke())
                .map_err(|e| anyhow!("{file}: stroke {s}, layer {l} below it: {e}"))?;
            triangles_cut += report.triangles_cut;
            scalpel.set_options(options);
        }
    }
    let topology = validate(scalpel.dyn_mesh())
        .map_err(|e| anyhow!("{target}: internal error after cutting: {e}"))?;
    let mut out = scalpel.mesh();
    if let Some(open) = path_file.open {
        // Let the whole trailing window elapse: the written incision is fully open.
        scalpel.advance_clock(open.window);
        out.positions = open_positions(&scalpel, &open, scalpel.clock());
    }
    crate::io::write_mesh(&args.out, &out)?;
    if args.json {
        let mut sorted = step_us.clone();
        sorted.sort_by(f64::total_cmp);
        let p50 = if sorted.is_empty() {
            0.0
        } else {
            sorted[(sorted.len() - 1) / 2]
        };
        let max = sorted.last().copied().unwrap_or(0.0);
        let json = serde_json::json!({
            "steps": step_us.len(),
            "triangles_cut": triangles_cut,
            "triangles_created": scalpel.dyn_mesh().triangle_count().saturating_sub(triangles_before),
            "step_us_p50": p50,
            "step_us_max": max,
            "closed": topology.closed,
            "manifold": topology.manifold,
        });
        println!("{json}");
    }
    Ok(())
}
