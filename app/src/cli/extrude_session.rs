//! `cutaway extrude SESSION.json --gesture G.json --out OUT.json --json`: a gesture replayed on
//! a whole scene as the window replays it, for scripts and tests.
//!
//! The target is the visible structure under the first press (else the first one seen through
//! the initial drag), picked as a press in the window picks it. The editor is the window's
//! ([`crate::cutting::editing::new_editor`]: δ from the target, what lies behind it from the
//! scene's other visible structures), so a `/2` gesture's new cutter reaches the first structure
//! behind the target. The session is written with the new cutter added (its smoothness
//! `--levels`) and the gesture's camera, the view it was painted from; the JSON adds what the
//! mesh form prints: the target's name, the cutter's depth in mm, the structures it reaches and
//! how much of the painted region it opens ([`cutter::opening`]).

use std::path::Path;
use std::sync::Arc;

use anyhow::{Context, bail};
use glam::DVec2;

use csg::{SpatialIndex, TargetIndex};
use cutter::reach::{Reach, ReachRule, Reached};
use cutter::{Cutter, EditorEvent};

use super::extrude::{ExtrudeArgs, replay_events};
use crate::cutting::pick::ScenePicks;
use crate::io::gesture::{Gesture, read_gesture};
use crate::scene::{Scene, SceneCutter};

/// True when TARGET names a session (a `.json` file) rather than a mesh.
pub fn is_session(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("json"))
}

/// A gesture replayed on a scene.
#[derive(Clone)]
pub struct SceneReplay {
    /// The scene with the new cutter last and the gesture's camera.
    pub scene: Scene,
    /// The model painted on.
    pub target: usize,
    pub cutter: Cutter,
    /// Scene increment δ.
    pub delta: f64,
    /// Largest distance from a plane's front-edge midpoint to the target's surface.
    pub max_surface_gap: f64,
    /// Why the cutter started as deep as it did (`/2` gestures).
    pub reach: Option<Reach>,
    /// What the cutter reaches, nearest first (model indexes).
    pub reached: Vec<Reached>,
    /// How much of the painted region the cut opens, seen from the gesture's camera (None when
    /// the cut is refused or nothing painted is in view).
    pub opening: Option<cutter::opening::Opening>,
}

/// Replays `gesture` on `scene` (see the module docs).
pub fn replay_on_scene(scene: &Scene, gesture: &Gesture) -> anyhow::Result<SceneReplay> {
    let mut picks = ScenePicks::default();
    let target = target_under_press(scene, gesture, &mut picks)?;
    let mesh = scene.models[target].model.mesh.clone();
    let index = Arc::new(SpatialIndex::build(&mesh));
    let mut editor = crate::cutting::editing::new_editor(
        scene,
        target,
        index,
        gesture.camera,
        gesture.viewport,
        gesture.settings(1.0),
        &mut picks,
    )
    .context("the target is not in the scene")?;
    let delta = editor.delta();
    let cutter = replay_events(&mut editor, gesture)?;
    let max_surface_gap = editor.max_surface_gap().unwrap_or(f64::INFINITY);
    let reached = editor.reached();
    let reach = editor.reach().copied();
    let mut out = scene.clone();
    out.cutters.push(SceneCutter::new(target, cutter.clone()));
    out.camera = gesture.camera;
    let opening = opening(&out, target, gesture);
    Ok(SceneReplay {
        scene: out,
        target,
        cutter,
        delta,
        max_surface_gap,
        reach,
        reached,
        opening,
    })
}

/// How much of the painted region the scene's last cutter opens in `target`.
fn opening(scene: &Scene, target: usize, gesture: &Gesture) -> Option<cutter::opening::Opening> {
    let cutter = scene.cutters.last()?;
    let index = TargetIndex::build(scene.models[target].model.mesh.clone()).ok()?;
    let parts = crate::cutting::cut_parts::cut_exact(&index, cutter).ok()?;
    cutter::opening::measure(
        &gesture.camera,
        gesture.viewport,
        &cutter.cutter,
        &parts.contour,
    )
}

/// The visible structure under the first press, else the first one seen through the initial
/// drag.
fn target_under_press(
    scene: &Scene,
    gesture: &Gesture,
    picks: &mut ScenePicks,
) -> anyhow::Result<usize> {
    let first = |pick: fn(&EditorEvent) -> Option<DVec2>| gesture.events.iter().find_map(pick);
    let Some(a) = first(|e| match *e {
        EditorEvent::Press { x, y, .. } => Some(DVec2::new(x, y)),
        _ => None,
    }) else {
        bail!("the gesture has no press");
    };
    let b = first(|e| match *e {
        EditorEvent::Release { x, y, .. } => Some(DVec2::new(x, y)),
        _ => None,
    })
    .unwrap_or(a);
    for k in 0..=8 {
        let px = a.lerp(b, k as f64 / 8.0);
        let ray = gesture.camera.ray_through_pixel(gesture.viewport, px);
        if let Some((model, _)) = picks.pick(scene, &ray) {
            return Ok(model);
        }
    }
    bail!(
        "the first press at ({}, {}) and the drag after it meet no visible structure",
        a.x,
        a.y
    )
}

/// The contract's name of the rule that set the first depth.
fn rule_name(reach: &Option<Reach>) -> Option<&'static str> {
    reach.map(|r| match r.rule {
        ReachRule::Structure(_) => "structure",
        ReachRule::Thickness => "thickness",
        ReachRule::TargetSize => "target_size",
    })
}

/// Runs the session form of `cutaway extrude`.
pub fn run(args: &ExtrudeArgs, levels: u32) -> anyhow::Result<()> {
    if !is_session(&args.out) {
        bail!(
            "{}: a session is written as a .json file",
            args.out.display()
        );
    }
    let scene = crate::session::load(&args.target)?;
    let gesture = read_gesture(&args.gesture)?;
    let mut result = replay_on_scene(&scene, &gesture)
        .with_context(|| format!("{} on {}", args.gesture.display(), args.target.display()))?;
    if let Some(c) = result.scene.cutters.last_mut() {
        c.cutter.levels = levels;
    }
    let written = &result.scene.cutters.last().expect("the new cutter").cutter;
    let smoothing = written.smoothing(levels);
    csg::check_cutter(&smoothing.mesh.triangulate()).map_err(|e| {
        anyhow::anyhow!(
            "{}: the cutter with {levels} subdivision levels is not a valid cutter: {e}",
            args.gesture.display()
        )
    })?;
    crate::session::save(&args.out, &result.scene)?;
    let unit = result.scene.unit;
    let depth_mm = unit.to_mm(result.cutter.depth());
    let name = |m: usize| result.scene.models[m].model.name.clone();
    let reaches: Vec<String> = result.reached.iter().map(|r| name(r.structure)).collect();
    if args.json {
        let mesh = &smoothing.mesh;
        let closed = mesh.check_closed().is_ok() && mesh.volume() > 0.0;
        let opening = result.opening.map(|o| {
            serde_json::json!({
                "painted_px2": o.painted,
                "opened_px2": o.opened,
                "ratio": o.ratio(),
                "covered": o.covered(),
                "outside": o.outside(),
            })
        });
        let json = serde_json::json!({
            "target": name(result.target),
            "cutters": result.scene.cutters.len(),
            "planes": result.cutter.planes.len(),
            "boxes": result.cutter.box_count(),
            "kind": result.cutter.kind.name(),
            "direction": result.cutter.direction.name(),
            "closed": closed,
            "max_surface_gap": result.max_surface_gap,
            "delta": result.delta,
            "smooth": result.cutter.smooth,
            "levels": smoothing.levels,
            "faces": mesh.faces.len(),
            "uniform_faces": if smoothing.uniform_faces > 0 { smoothing.uniform_faces } else { mesh.faces.len() },
            "depth_mm": depth_mm,
            "depth_rule": rule_name(&result.reach),
            "reaches": reaches,
            "opening": opening,
        });
        println!("{json}");
    } else {
        println!(
            "{}: cutter {} on {}, {}, written to {}",
            args.target.display(),
            result.scene.cutters.len(),
            name(result.target),
            crate::cutting::obstacles::depth_line(depth_mm, &reaches),
            args.out.display()
        );
    }
    Ok(())
}
