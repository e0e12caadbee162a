//! `cutaway extrude TARGET --gesture G.json --out CUTTER.obj --json`: replays a recorded gesture
//! through the same [`cutter::Editor`] the GUI uses and writes the cutter as OBJ quads; with a
//! session as TARGET (`cutaway extrude SESSION.json --gesture G.json --out OUT.json`) the gesture
//! is replayed on the whole scene as the window replays it ([`super::extrude_session`]).
//!
//! The target file is the whole scene; the region painted on is the one under the first press
//! (else the first one seen through the initial drag, else the one nearest to the press ray), as
//! the thesis picks "the first region under the press" when no target was selected. δ comes from
//! that region's bounding box seen by the gesture's camera, the file's box when the region is
//! flat ([`cutter::EditorSettings::delta_for_target`], as the window sizes a new cutter from
//! the model it starts on). The gesture's version says which rules its events are read by
//! ([`Gesture::settings`]): a mesh has nothing behind the painted region, so a `/2` gesture's
//! cutter takes half the region's thickness under the stroke ([`cutter::reach`]).

use std::path::PathBuf;
use std::sync::Arc;

use anyhow::{Context, bail};
use glam::DVec2;

use csg::{EdgeAdjacency, Mesh, SpatialIndex};
use cutter::{Cutter, Editor, EditorEvent, EditorSettings};

use crate::io::gesture::{Gesture, MAX_REPLAY_BOXES, MAX_REPLAY_TIME, read_gesture};

#[derive(Debug, clap::Args)]
pub struct ExtrudeArgs {
    /// The anatomy the gesture paints on: a mesh, or a session (`.json`) whose structure under
    /// the first press is painted on.
    pub target: PathBuf,
    /// A `cutaway-gesture/1` or `/2` file.
    #[arg(long)]
    pub gesture: PathBuf,
    /// Where to write the cutter (OBJ quads), or for a session the session with the new cutter
    /// (`.json`).
    #[arg(long)]
    pub out: PathBuf,
    /// Subdivision levels of a smooth (rounded/freeform) cutter, 0 to 4 (default 2); each level
    /// splits every quad in four. Not used when the gesture's cutter is not smooth.
    #[arg(long)]
    pub levels: Option<u32>,
    /// Print one JSON object (see CONTRACT.md).
    #[arg(long)]
    pub json: bool,
}

/// The outcome of a replay.
#[derive(Clone, Debug)]
pub struct Replay {
    pub cutter: Cutter,
    /// Scene increment δ.
    pub delta: f64,
    /// Largest distance from a plane's front-edge midpoint to the painted region's surface.
    pub max_surface_gap: f64,
    /// Index of the painted region (connected component) of the target.
    pub region: usize,
}

/// Replays `gesture` on `target` (the whole file). Errors when the gesture makes no cutter.
pub fn replay(target: &Mesh, gesture: &Gesture) -> anyhow::Result<Replay> {
    if target.is_empty() {
        bail!("the target has no triangles");
    }
    let region = painted_region(target, gesture);
    let mut pieces = csg::regions::split_regions(target);
    if region >= pieces.len() {
        bail!("the target has no region {region}");
    }
    let mesh = Arc::new(pieces.swap_remove(region));
    let delta = EditorSettings::delta_for_target(&mesh.bbox(), &target.bbox(), &gesture.camera);
    let index = Arc::new(SpatialIndex::build(&mesh));
    let settings = gesture.settings(delta);
    let mut editor = Editor::new(mesh, index, gesture.camera, gesture.viewport, settings);
    let cutter = replay_events(&mut editor, gesture)?;
    let max_surface_gap = editor.max_surface_gap().unwrap_or(f64::INFINITY);
    Ok(Replay {
        cutter,
        delta,
        max_surface_gap,
        region,
    })
}

/// Feeds the gesture's events to `editor` within the replay's bounds (boxes and CPU time, see
/// [`crate::io::gesture`]) and returns the cutter they made.
pub fn replay_events(editor: &mut Editor, gesture: &Gesture) -> anyhow::Result<Cutter> {
    let started = crate::platform::thread_time::thread_cpu_time();
    for (i, &event) in gesture.events.iter().enumerate() {
        editor.handle(event);
        // One event adds a bounded number of boxes, so checking after each bounds the replay.
        let boxes = editor.cutter().map_or(0, |c| c.box_count());
        if boxes > MAX_REPLAY_BOXES {
            bail!(
                "event {i}: the cutter has {boxes} boxes, more than the limit of {MAX_REPLAY_BOXES}; replay stopped (a tiny viewport or spacing makes each pixel of a drag a whole box)"
            );
        }
        // One event costs at most a bounded re-fit, so checking after each bounds the time.
        if crate::platform::thread_time::thread_cpu_time() - started > MAX_REPLAY_TIME {
            bail!(
                "event {i} of {}: the replay used more than {:.1} s of CPU time and stopped (the cutter has {boxes} boxes; a tiny viewport makes every move re-fit many of them)",
                gesture.events.len(),
                MAX_REPLAY_TIME.as_secs_f64()
            );
        }
    }
    editor.cutter().cloned().ok_or_else(|| {
        anyhow::anyhow!(
            "the gesture made no cutter (the first press-drag-release must be at least 3 pixels long)"
        )
    })
}

/// The region under the first press: the region hit by the press ray, else by a ray through the
/// initial drag, else the region nearest to the press ray.
fn painted_region(target: &Mesh, gesture: &Gesture) -> usize {
    let adjacency = EdgeAdjacency::build(target);
    let regions = csg::regions::Regions::build(target, &adjacency);
    if regions.count <= 1 {
        return 0;
    }
    let index = SpatialIndex::build(target);
    let press = gesture.events.iter().find_map(|e| match *e {
        EditorEvent::Press { x, y, .. } => Some(DVec2::new(x, y)),
        _ => None,
    });
    let release = gesture.events.iter().find_map(|e| match *e {
        EditorEvent::Release { x, y, .. } => Some(DVec2::new(x, y)),
        _ => None,
    });
    let Some(a) = press else {
        return 0;
    };
    let b = release.unwrap_or(a);
    let region_of = |face: u32| regions.region_of_triangle[face as usize] as usize;
    for k in 0..=8 {
        let px = a.lerp(b, k as f64 / 8.0);
        let ray = gesture.camera.ray_through_pixel(gesture.viewport, px);
        if let Some(hit) = index.ray_cast(target, ray.origin, ray.direction, f64::INFINITY) {
            return region_of(hit.face);
        }
    }
    let ray = gesture.camera.ray_through_pixel(gesture.viewport, a);
    let depth = (target.bbox().center() - ray.origin)
        .dot(ray.direction)
        .max(0.0);
    index
        .closest_point(target, ray.at(depth))
        .map_or(0, |c| region_of(c.face))
}

pub fn run(args: &ExtrudeArgs) -> anyhow::Result<()> {
    let levels = args.levels.unwrap_or(cutter::subdivision::DEFAULT_LEVELS);
    if levels > cutter::subdivision::MAX_LEVELS {
        bail!(
            "--levels {levels}: at most {} subdivision levels",
            cutter::subdivision::MAX_LEVELS
        );
    }
    if super::extrude_session::is_session(&args.target) {
        return super::extrude_session::run(args, levels);
    }
    let target = crate::io::read_mesh(&args.target)?;
    let gesture = read_gesture(&args.gesture)?;
    let result = replay(&target, &gesture).with_context(|| args.gesture.display().to_string())?;
    let smoothing = result.cutter.smoothing(levels);
    let mesh = &smoothing.mesh;
    // The editor checked the cutter at the default levels; other levels are checked here.
    csg::check_cutter(&mesh.triangulate()).map_err(|e| {
        anyhow::anyhow!(
            "{}: the cutter with {levels} subdivision levels is not a valid cutter: {e}",
            args.gesture.display()
        )
    })?;
    crate::io::write_obj_polygons(&args.out, &mesh.positions, &mesh.faces)?;
    let closed = mesh.check_closed().is_ok() && mesh.volume() > 0.0;
    if args.json {
        let json = serde_json::json!({
            "planes": result.cutter.planes.len(),
            "boxes": result.cutter.box_count(),
            "kind": result.cutter.kind.name(),
            "closed": closed,
            "max_surface_gap": result.max_surface_gap,
            "delta": result.delta,
            "smooth": result.cutter.smooth,
            "region": result.region,
            "levels": smoothing.levels,
            "faces": mesh.faces.len(),
            "uniform_faces": if smoothing.uniform_faces > 0 { smoothing.uniform_faces } else { mesh.faces.len() },
        });
        println!("{json}");
    } else {
        println!(
            "{}: {} planes, {} boxes ({}), written to {}",
            args.target.display(),
            result.cutter.planes.len(),
            result.cutter.box_count(),
            result.cutter.kind.name(),
            args.out.display()
        );
    }
    Ok(())
}
