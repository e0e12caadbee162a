//! `cutaway scalpel TARGET --path P.json --out OUT.obj --json`.
//!
//! Replays a `cutaway-path/1` file through the window's own scalpel session
//! ([`crate::scalpel_session::replay`]): each connected region of the target is a surface of
//! its own (a model, as in a scene), each stroke is cut on the region nearest its first point
//! and, with a depth, on every region the blade reaches below it (multi-layer); the opening (if
//! the file asks for one) is shown after its whole time window, as the window shows a released
//! stroke. So the written mesh is what Scalpel mode shows after the same strokes, bit for bit.
//! A `.ply` output marks the incision walls (groove and through-cut walls) with the
//! `cutaway_wall` face property, so `cutaway render` of a session naming it `"exact"` draws
//! them as the window does; other formats carry the mesh alone.
//! `steps` and the step times count the path file's samples; the first step of each stroke
//! includes its press. Any refusal is an error naming the path file, the stroke and the point;
//! nothing is written then.

use std::path::PathBuf;
use std::sync::Arc;

use anyhow::anyhow;
use cutter::scalpel::DynMesh;
use cutter::scalpel::invariants::validate;

use crate::scalpel_session::{ScalpelSession, ScalpelSettings, replay::replay};
use crate::scene::{Scene, SceneModel};

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

/// The scene `cutaway scalpel` cuts: one model per connected region of `mesh`, in region order.
pub fn region_scene(mesh: &csg::Mesh, source: &std::path::Path) -> Scene {
    let mut scene = Scene::default();
    for (k, region) in csg::regions::split_regions(mesh).into_iter().enumerate() {
        let mut model = SceneModel::new(
            format!("region {}", k + 1),
            source,
            Arc::new(region),
            [0.8, 0.8, 0.8],
        );
        model.model.index = k;
        scene.models.push(model);
    }
    scene
}

/// The settings the window would cut a path file's strokes with.
pub fn path_settings(path_file: &crate::io::path_file::PathFile) -> ScalpelSettings {
    ScalpelSettings {
        tool: path_file.tool,
        depth: path_file.depth,
        opening: path_file.open.map_or(0.0, |o| o.width),
        window: path_file.open.map_or(0.0, |o| o.window),
        layers: true,
    }
}

pub fn run(args: &ScalpelArgs) -> anyhow::Result<()> {
    let path_file = crate::io::path_file::read_path_file(&args.path)?;
    let mesh = crate::io::read_mesh(&args.target)?;
    let target = args.target.display();
    if mesh.triangles.is_empty() {
        return Err(anyhow!("{target}: the mesh has no triangles"));
    }
    let mut scene = region_scene(&mesh, &args.target);
    let mut session = ScalpelSession::headless(path_settings(&path_file));
    let file = args.path.display();
    let done =
        replay(&mut session, &mut scene, &path_file.strokes).map_err(|e| anyhow!("{file}: {e}"))?;
    let mut out = csg::Mesh::default();
    // The incision walls of every model, in the written mesh's face ids.
    let mut walls: Vec<u32> = Vec::new();
    let (mut closed, mut manifold) = (true, true);
    for m in &scene.models {
        let topology = validate(&DynMesh::from_mesh(&m.model.mesh))
            .map_err(|e| anyhow!("{target}: internal error after cutting: {e}"))?;
        closed &= topology.closed;
        manifold &= topology.manifold;
        let first = out.triangles.len() as u32;
        walls.extend(m.wall_faces().iter().map(|&f| first + f));
        out.append(&m.model.mesh);
    }
    crate::io::write_mesh_walls(&args.out, &out, &walls)?;
    if args.json {
        let mut sorted = done.step_us.clone();
        sorted.sort_by(f64::total_cmp);
        let p50 = if sorted.is_empty() {
            0.0
        } else {
            sorted[(sorted.len() - 1) / 2]
        };
        let max = sorted.last().copied().unwrap_or(0.0);
        let json = serde_json::json!({
            "steps": done.step_us.len(),
            "triangles_cut": done.triangles_cut,
            "triangles_created": out.triangles.len().saturating_sub(mesh.triangles.len()),
            "step_us_p50": p50,
            "step_us_max": max,
            "step_us_first": done.step_us.first().copied().unwrap_or(0.0),
            "closed": closed,
            "manifold": manifold,
        });
        println!("{json}");
    }
    Ok(())
}
