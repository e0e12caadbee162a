//! How deep a new cutter goes: it reaches the first structure behind its target.
//!
//! A cutter opens a window in its target (the skin) so that what lies behind shows through it.
//! The editor knows only its target; what lies behind is the [`Obstacles`] the app gives it (the
//! scene's other visible structures, each with a name), so this crate sees no scene.
//!
//! ## The default depth ([`default_depth`])
//! Rays start on the painted front edges (the first box's two planes, [`SAMPLES`] points across
//! each) and run along the cut direction. Each ray that enters the target gives:
//! - `entry`: where it enters the target's solid (the surface under the painted point);
//! - `far`: where it leaves the target for the last time, and `reentry`: where it enters it again
//!   after having left it (a cavity, the far wall of a shell), if it does;
//! - `hit`: the first other structure it meets past `entry`.
//!
//! Then, all distances measured from the front edge along the cut direction:
//! - the **limit** is the median over the rays of `min(reentry, far − FAR_SIDE_KEPT · (far −
//!   entry))`: the cut never reaches the far side of the target (the back of the head) nor the
//!   far wall of a shell, under the middle of the stroke at least (a ray grazing the target's rim
//!   is thin and would otherwise decide for the whole stroke);
//! - with a structure behind, the depth is the nearest `hit` plus a margin of
//!   [`REACH_MARGIN`] times that distance from the surface (`hit − entry`), so the structure's
//!   front shows in front of the cut's floor rather than touching it;
//! - with nothing behind, the depth is [`EMPTY_SHARE`] of the median `far` (half the target's
//!   thickness under the stroke);
//! - a stroke off the target (no ray enters it) gets [`EMPTY_SHARE`] of the target's smallest
//!   box side, the size of the target, not of the scene;
//! - the depth is at least the deepest `entry` plus [`MIN_DEPTH`]·δ: the depth is measured from
//!   the front edge, which rests just outside the surface, and where the surface curves away
//!   under a straight front edge (the sides of a forehead or of a knee) the box must still go
//!   past it there, so the opening is as wide as the stroke even when the structure behind is
//!   close (a fat layer 3 mm under the skin of a knee);
//! - the depth is then clamped to the limit, and is never less than [`MIN_DEPTH`]·δ.
//!
//! The default depth is decided once, from the first box (where the stroke was painted), and
//! rolling keeps it: a stroke across the forehead whose rays pass above the deep structures
//! gets half the head's thickness there, which reaches the ventricles below it too.
//!
//! ## What a cutter reaches ([`reached`])
//! Each plane's front edge is sampled the same way and cast along that plane's back direction,
//! as far as that plane's depth: the structures met are the cutter's reach, nearest first (the
//! status line's "42 mm: reaches left lateral ventricle", `cutaway extrude`'s `reaches`).

use std::sync::Arc;

use glam::DVec3;

use csg::{Mesh, PickIndex};

use crate::cutter::Cutter;
use crate::surface::Surface;

/// Points sampled across each front edge.
pub const SAMPLES: usize = 15;
/// Past the nearest structure behind the target, the depth goes on by this share of that
/// structure's distance from the surface.
pub const REACH_MARGIN: f64 = 0.5;
/// With nothing behind the target, the depth is this share of its thickness under the stroke.
pub const EMPTY_SHARE: f64 = 0.5;
/// The share of the target's thickness the cut always leaves on its far side.
pub const FAR_SIDE_KEPT: f64 = 0.1;
/// Smallest default depth, in multiples of δ (the thesis's initial 5δ).
pub const MIN_DEPTH: f64 = crate::roll::INITIAL_DEPTH;

/// One structure a ray meets: which, and at what distance along the ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ObstacleHit {
    /// The structure's index, as [`Obstacles::name`] knows it.
    pub structure: usize,
    /// Ray parameter of the first hit (the ray's direction is of unit length).
    pub t: f64,
}

/// What lies behind the target: the structures a cut through the target should reach.
pub trait Obstacles: Send + Sync {
    /// Every structure the ray `origin + t · direction` (`direction` of unit length) meets for
    /// `0 <= t <= t_max`, each once at its first hit, nearest first.
    fn hits(&self, origin: DVec3, direction: DVec3, t_max: f64) -> Vec<ObstacleHit>;

    /// The structure's name, for the status line and the CLI.
    fn name(&self, structure: usize) -> String;
}

/// One structure of [`MeshObstacles`].
#[derive(Clone)]
pub struct Obstacle {
    /// Index the caller knows the structure by (the scene's model index).
    pub structure: usize,
    pub name: String,
    pub mesh: Arc<Mesh>,
    /// Built from `mesh`.
    pub tree: Arc<PickIndex>,
}

/// [`Obstacles`] as a list of meshes with their ray-pick trees.
#[derive(Clone, Default)]
pub struct MeshObstacles {
    pub structures: Vec<Obstacle>,
}

impl Obstacles for MeshObstacles {
    fn hits(&self, origin: DVec3, direction: DVec3, t_max: f64) -> Vec<ObstacleHit> {
        let mut hits: Vec<ObstacleHit> = self
            .structures
            .iter()
            .filter_map(|s| {
                let hit = s.tree.ray_cast(&s.mesh, origin, direction, t_max)?;
                Some(ObstacleHit {
                    structure: s.structure,
                    t: hit.t,
                })
            })
            .collect();
        hits.sort_by(|a, b| a.t.total_cmp(&b.t));
        hits
    }

    fn name(&self, structure: usize) -> String {
        self.structures
            .iter()
            .find(|s| s.structure == structure)
            .map_or_else(|| format!("structure {structure}"), |s| s.name.clone())
    }
}

/// Why the default depth is what it is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ReachRule {
    /// It reaches the nearest structure behind the target, plus the margin.
    Structure(ObstacleHit),
    /// Nothing lies behind: a share of the target's thickness under the stroke.
    Thickness,
    /// The stroke does not cross the target: a share of the target's size.
    TargetSize,
}

/// The default depth of a new cutter and why.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reach {
    /// From the front edge along the cut direction.
    pub depth: f64,
    pub rule: ReachRule,
    /// True when the depth was cut back so the far side of the target stays.
    pub clamped: bool,
}

/// A point where a ray crosses the target's surface.
#[derive(Clone, Copy, Debug)]
struct Crossing {
    t: f64,
    entering: bool,
}

/// Where the ray `origin + t · direction` (`direction` unit) crosses the target, in order, each
/// judged entering or leaving by the face it crosses (the target is closed and outward).
fn crossings(surface: &Surface, origin: DVec3, direction: DVec3, t_max: f64) -> Vec<Crossing> {
    let scale = surface.bbox().diagonal().max(1e-300);
    let step = 1e-9 * scale;
    let mut out = Vec::new();
    let mut t0 = 0.0;
    // Each crossing moves the origin past the hit, so the loop ends; the bound guards against a
    // mesh so fine that the step does not leave a face.
    for _ in 0..256 {
        let start = origin + direction * t0;
        let Some(hit) = surface
            .index
            .ray_cast(surface.mesh, start, direction, t_max - t0)
        else {
            break;
        };
        let n = surface.mesh.face_normal_scaled(hit.face as usize);
        let t = t0 + hit.t;
        let facing = n.dot(direction);
        if facing != 0.0 {
            out.push(Crossing {
                t,
                entering: facing < 0.0,
            });
        }
        t0 = t + step;
        if t0 >= t_max {
            break;
        }
    }
    out
}

/// What one ray from the front edge finds.
#[derive(Clone, Copy, Debug)]
struct Probe {
    entry: f64,
    far: f64,
    /// Deepest the cut may go along this ray.
    limit: f64,
    hit: Option<ObstacleHit>,
}

/// Casts one ray from `origin` along `direction` through the target and what lies behind.
fn probe(
    surface: &Surface,
    obstacles: Option<&dyn Obstacles>,
    origin: DVec3,
    direction: DVec3,
    reach_max: f64,
) -> Option<Probe> {
    let cross = crossings(surface, origin, direction, reach_max);
    let first_in = cross.iter().position(|c| c.entering)?;
    let entry = cross[first_in].t;
    let far = cross
        .iter()
        .rev()
        .find(|c| !c.entering)
        .map_or(entry, |c| c.t);
    // Entering again after having left: a cavity's far wall, or the far wall of a shell.
    let reentry = cross[first_in..]
        .windows(2)
        .find(|w| !w[0].entering && w[1].entering)
        .map(|w| w[1].t);
    let mut limit = far - FAR_SIDE_KEPT * (far - entry);
    if let Some(r) = reentry {
        limit = limit.min(r);
    }
    let hit = obstacles.and_then(|o| {
        let start = origin + direction * entry;
        o.hits(start, direction, (far - entry).max(0.0))
            .first()
            .map(|h| ObstacleHit {
                structure: h.structure,
                t: h.t + entry,
            })
    });
    Some(Probe {
        entry,
        far,
        limit,
        hit,
    })
}

/// Points across the front edge `a`–`d`, ends included.
fn across(a: DVec3, d: DVec3) -> impl Iterator<Item = DVec3> {
    (0..SAMPLES).map(move |k| a.lerp(d, k as f64 / (SAMPLES - 1) as f64))
}

fn median(mut values: Vec<f64>) -> Option<f64> {
    if values.is_empty() {
        return None;
    }
    values.sort_by(f64::total_cmp);
    Some(values[values.len() / 2])
}

/// The default depth of a cutter whose first planes have the front edges `fronts` (front-top,
/// front-bottom) and cut along the unit `direction` into `surface` (the target), with
/// `obstacles` behind it (see the module docs). `delta` is the scene increment δ.
pub fn default_depth(
    surface: &Surface,
    obstacles: Option<&dyn Obstacles>,
    fronts: &[(DVec3, DVec3)],
    direction: DVec3,
    delta: f64,
) -> Reach {
    let bbox = surface.bbox();
    let reach_max = 4.0 * bbox.diagonal().max(1e-300)
        + fronts
            .iter()
            .map(|(a, _)| (*a - bbox.center()).length())
            .fold(0.0, f64::max);
    let probes: Vec<Probe> = fronts
        .iter()
        .flat_map(|&(a, d)| across(a, d))
        .filter_map(|p| probe(surface, obstacles, p, direction, reach_max))
        .collect();
    let floor = MIN_DEPTH * delta;
    let Some(limit) = median(probes.iter().map(|p| p.limit).collect()) else {
        let side = (bbox.max - bbox.min).min_element().max(0.0);
        return Reach {
            depth: (EMPTY_SHARE * side).max(floor),
            rule: ReachRule::TargetSize,
            clamped: false,
        };
    };
    let nearest = probes
        .iter()
        .filter_map(|p| p.hit.map(|h| (h, p.entry)))
        .min_by(|a, b| a.0.t.total_cmp(&b.0.t));
    let (wanted, rule) = match nearest {
        Some((hit, entry)) => (
            hit.t + REACH_MARGIN * (hit.t - entry).max(0.0),
            ReachRule::Structure(hit),
        ),
        None => {
            let far = median(probes.iter().map(|p| p.far).collect()).unwrap_or(limit);
            (EMPTY_SHARE * far, ReachRule::Thickness)
        }
    };
    // The window is the painted width: the box goes past the surface under every sample of the
    // front edge, its ends included, where a curved surface lies furthest behind a straight edge.
    let behind_edge = probes.iter().map(|p| p.entry).fold(0.0, f64::max);
    let wanted = wanted.max(behind_edge + floor);
    let clamped = wanted > limit;
    Reach {
        depth: wanted.min(limit).max(floor),
        rule,
        clamped,
    }
}

/// One structure a cutter reaches: which, and its distance from the nearest front edge.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reached {
    pub structure: usize,
    pub distance: f64,
}

/// The structures `cutter` reaches (see the module docs), nearest first.
pub fn reached(cutter: &Cutter, obstacles: &dyn Obstacles) -> Vec<Reached> {
    let mut out: Vec<Reached> = Vec::new();
    for plane in &cutter.planes {
        let direction = plane.back_direction();
        if direction == DVec3::ZERO {
            continue;
        }
        let depth = plane.depth();
        for p in across(plane.front_top, plane.front_bottom) {
            for h in obstacles.hits(p, direction, depth) {
                match out.iter_mut().find(|r| r.structure == h.structure) {
                    Some(r) => r.distance = r.distance.min(h.t),
                    None => out.push(Reached {
                        structure: h.structure,
                        distance: h.t,
                    }),
                }
            }
        }
    }
    out.sort_by(|a, b| a.distance.total_cmp(&b.distance));
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use csg::SpatialIndex;

    fn ball(radius: f64, centre: DVec3) -> Mesh {
        let mut m = csg::testkit::icosphere(3, radius);
        for p in &mut m.positions {
            *p += centre;
        }
        m
    }

    fn obstacle(structure: usize, name: &str, mesh: Mesh) -> Obstacle {
        let tree = Arc::new(PickIndex::build(&mesh));
        Obstacle {
            structure,
            name: name.to_string(),
            mesh: Arc::new(mesh),
            tree,
        }
    }

    /// A head of radius 50 with a ball of radius 5 whose front is 30 behind the head's front:
    /// a stroke over it reaches the ball plus half of the 30 from the surface; nothing behind
    /// gives half the thickness; the back of the head is never cut.
    #[test]
    fn the_depth_reaches_the_ball_behind_and_never_the_far_side() {
        let head = ball(50.0, DVec3::ZERO);
        let index = SpatialIndex::build(&head);
        let surface = Surface::new(&head, &index);
        let front = -50.5;
        let edge = (DVec3::new(-10.0, front, 5.0), DVec3::new(10.0, front, 5.0));
        let inner = MeshObstacles {
            structures: vec![obstacle(
                7,
                "ventricle",
                ball(5.0, DVec3::new(0.0, -15.0, 5.0)),
            )],
        };
        let r = default_depth(&surface, Some(&inner), &[edge], DVec3::Y, 0.1);
        let ReachRule::Structure(hit) = r.rule else {
            panic!("{r:?}");
        };
        assert_eq!(hit.structure, 7);
        // The ball's front is at y = -20, 30.5 from the front edge; the head's surface is
        // about 0.8 from the front edge at x = ±10 and 0.5 in the middle.
        assert!((hit.t - 30.5).abs() < 0.3, "{hit:?}");
        let expected = hit.t + REACH_MARGIN * (hit.t - 0.5);
        assert!((r.depth - expected).abs() < 0.5, "{r:?} vs {expected}");
        assert!(!r.clamped);

        let empty = default_depth(&surface, None, &[edge], DVec3::Y, 0.1);
        assert_eq!(empty.rule, ReachRule::Thickness);
        assert!((empty.depth - 0.5 * 100.5).abs() < 1.0, "{empty:?}");

        // A ball right at the back: the far tenth of the head stays.
        let back = MeshObstacles {
            structures: vec![obstacle(1, "back", ball(3.0, DVec3::new(0.0, 45.0, 5.0)))],
        };
        let r = default_depth(&surface, Some(&back), &[edge], DVec3::Y, 0.1);
        assert!(r.clamped, "{r:?}");
        assert!(r.depth < 0.92 * 100.5 && r.depth > 0.85 * 100.5, "{r:?}");

        // A wide stroke over a thin layer close behind: the box goes past the surface at the
        // stroke's ends (40 behind the edge there), not only to the layer (4 behind the middle).
        let wide = (DVec3::new(-30.0, front, 0.0), DVec3::new(30.0, front, 0.0));
        let layer = MeshObstacles {
            structures: vec![obstacle(2, "layer", ball(45.0, DVec3::ZERO))],
        };
        let r = default_depth(&surface, Some(&layer), &[wide], DVec3::Y, 0.1);
        assert!(matches!(r.rule, ReachRule::Structure(_)), "{r:?}");
        let edge_entry = 50.5 - (50.0f64 * 50.0 - 30.0 * 30.0).sqrt();
        assert!(
            r.depth > edge_entry && r.depth < edge_entry + 1.0,
            "{r:?} vs {edge_entry}"
        );

        // Off the head: half its smallest side.
        let off = (DVec3::new(80.0, front, 0.0), DVec3::new(90.0, front, 0.0));
        let r = default_depth(&surface, Some(&inner), &[off], DVec3::Y, 0.1);
        assert_eq!(r.rule, ReachRule::TargetSize);
        assert!((r.depth - 50.0).abs() < 1.0, "{r:?}");
    }
}
