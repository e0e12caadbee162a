//! The risk map's distances: every cut wall's distance to the critical structures
//! ([`crate::scene::risk`]), per vertex, on a wall refined where the colour changes, so that what
//! the view, `cutaway render` and the glTF export show never makes a wall look safer than it is.
//!
//! ## The distance
//! `d(p)` is the distance from wall point `p` to the nearest critical *solid*: 0 inside a closed
//! structure (a wall through a vessel is at distance 0, not at the distance to the vessel's
//! surface), else the distance to its surface. The surface distance is the exact closest point
//! through the structure's [`SpatialIndex`] (the query `crate::metrics::distance` makes for
//! `metrics --critical`, vertex by vertex); inside is the structure's generalized winding number
//! above ½ ([`WindingTree`]; it errs only within rounding of the surface, where `d` is about 0
//! anyway). `d` is 1-Lipschitz: it changes no faster than the point moves.
//!
//! ## Refinement, and why the picture cannot lie
//! The renderer interpolates a value linearly across each triangle and maps it to the ramp per
//! fragment (so the 2 mm and 10 mm lines stay sharp). Linear interpolation of exact vertex
//! distances is not a bound: a structure close to the middle of a large wall triangle whose
//! corners are all 10 mm away would be shown as 10 mm. Since `d` is 1-Lipschitz, on a triangle
//! `T` with corner distances `dᵢ` and longest edge `ℓ`, every point has
//! `max dᵢ − ℓ ≤ d(p) ≤ min dᵢ + ℓ`, and `d(p) ≥ Σ λᵢ (dᵢ − ℓ)` (λ its barycentric
//! coordinates). So each wall triangle is split at its edge midpoints, level by level, until:
//! - the bounds put all of `T` beyond `far_mm` or within `near_mm`: its corners carry their
//!   exact distances and the whole triangle shows one side of the line, correctly;
//! - otherwise its corners carry `dᵢ − ℓ`, a lower bound at every point of `T`, once `T` is at
//!   most [`FINEST_EDGE_MM`] across, or [`BAND_EDGE_MM`] where those lowered corners stay inside
//!   the graded band (the shade there is at most that much too dangerous, never red). A wall
//!   point within `near_mm` is then always red, and no point shows safer than it is; a point at
//!   most about twice [`WallRisk::margin_mm`] beyond a line may be coloured as inside it (the
//!   error is toward danger, and bounded).
//!
//! Each triangle is split on its own (as the image baking does), so differently split
//! neighbours meet with T-junctions: the new vertices lie on the shared edge, the surface has no
//! gap. A wall refined past [`MAX_TRIANGLES`] is refined again with coarser steps (the bounds
//! hold at any step; only the margin grows, and [`WallRisk::margin_mm`] says how much).
//!
//! The work runs where the cuts run: a worker in the window (cached per cut), the headless
//! render before it draws. The renderer only draws the result.

use std::collections::HashMap;
use std::sync::{Arc, Weak};

use csg::winding::WindingTree;
use csg::{Mesh, SpatialIndex};
use glam::{DVec2, DVec3};
use rayon::prelude::*;

use super::cut_results::{PartKind, PreviewGeometry, PreviewPart};
use crate::scene::Scene;
use crate::scene::risk::{RISK_BAND_END, RISK_BAND_START, RISK_NEAR_COLOR, RiskSettings};

/// The colours (sRGB) a map is drawn with: red within the near distance, a ramp from orange to
/// yellow across the graded band. A map carries them, so the renderer draws the map it is given
/// with the colours the scene's legend and the glTF export use, without reading the scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RiskRamp {
    pub near: [f32; 3],
    pub band_start: [f32; 3],
    pub band_end: [f32; 3],
}

impl RiskRamp {
    /// The scene's ramp ([`crate::scene::risk`]).
    pub const SCENE: RiskRamp = RiskRamp {
        near: RISK_NEAR_COLOR,
        band_start: RISK_BAND_START,
        band_end: RISK_BAND_END,
    };
}

/// Longest edge (mm) of a wall triangle that may straddle the near or far line: the most the
/// map errs toward danger.
pub const FINEST_EDGE_MM: f64 = 0.25;
/// Longest edge (mm) of a wall triangle inside the graded band.
pub const BAND_EDGE_MM: f64 = 1.0;
/// Most triangles one refined wall may have.
pub const MAX_TRIANGLES: usize = 400_000;

/// One cutter's walls on one structure, refined, with a distance at every triangle corner.
#[derive(Clone, Debug)]
pub struct RiskWall {
    /// The preview part it colours: its model and cutter (a [`PartKind::Wall`] part).
    pub model: usize,
    pub cutter: usize,
    /// Triangle and vertex counts of that part's mesh, so a drawer can tell a part of another
    /// cut from the one this was computed for.
    pub source: (usize, usize),
    /// The wall, refined (shared vertices; see the module doc).
    pub mesh: Mesh,
    /// Where each vertex of `mesh` lies on the part's own wall: a triangle of it and the
    /// barycentric coordinates there, so a drawer interpolates what it computes per vertex of the
    /// wall (its normals) and the refined wall looks exactly as the wall does.
    pub origin: Vec<VertexOrigin>,
    /// Per triangle of `mesh`, per corner: the distance in mm whose linear interpolation over
    /// the triangle is at most the true distance at every point of it (or, where the whole
    /// triangle lies on one side of a line, the exact corner distances).
    pub corner_mm: Vec<[f32; 3]>,
}

impl RiskWall {
    /// Whether `part` is the wall this was computed for.
    pub fn matches(&self, part: &PreviewPart) -> bool {
        part.kind == PartKind::Wall
            && part.model == self.model
            && part.cutter == self.cutter
            && self.source == (part.mesh.triangle_count(), part.mesh.positions.len())
    }
}

/// Where a refined vertex lies on the wall it was refined from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VertexOrigin {
    /// The wall's triangle.
    pub triangle: u32,
    /// `[u, v]`: the point is `a + (b − a) u + (c − a) v` of that triangle's corners.
    pub bary: [f64; 2],
}

impl VertexOrigin {
    /// The value at this point of what `per_vertex` gives at the wall triangle's corners,
    /// interpolated linearly.
    pub fn interpolate(&self, wall: &Mesh, per_vertex: impl Fn(u32) -> DVec3) -> DVec3 {
        let [a, b, c] = wall.triangles[self.triangle as usize].map(per_vertex);
        let [u, v] = self.bary;
        a + (b - a) * u + (c - a) * v
    }
}

/// The wall point nearest a critical structure.
#[derive(Clone, Debug, PartialEq)]
pub struct Nearest {
    /// mm (0 when a wall touches or enters it), exact at a wall vertex.
    pub distance_mm: f64,
    /// The critical structure's name.
    pub structure: String,
}

/// The distances of every cutter wall of a preview to the critical structures.
#[derive(Clone, Debug)]
pub struct WallRisk {
    /// What the map was computed for (the ramp's distances).
    pub settings: RiskSettings,
    /// The colours it is drawn with.
    pub ramp: RiskRamp,
    pub walls: Vec<RiskWall>,
    /// The wall vertex nearest a critical structure (`None` without walls).
    pub nearest: Option<Nearest>,
    /// How far beyond the near or far line (mm) a wall point may still be coloured as inside it
    /// (the finest edge used; never the other way).
    pub margin_mm: f64,
    /// Critical names no structure of the scene has (they are left out).
    pub missing: Vec<String>,
}

impl WallRisk {
    /// The legend's title: which structures, and the closest wall
    /// (`Distance to optic chiasm, closest wall 3.4 mm`).
    pub fn caption(&self) -> String {
        let names: Vec<&str> = self
            .settings
            .critical
            .iter()
            .filter(|n| !self.missing.contains(n))
            .map(String::as_str)
            .collect();
        let joined = names.join(", ");
        let what = if names.len() == 1 || joined.chars().count() <= 40 {
            joined
        } else {
            format!("{} critical structures", names.len())
        };
        match &self.nearest {
            Some(n) => format!("Distance to {what}, closest wall {:.1} mm", n.distance_mm),
            None => format!("Distance to {what}, no cut walls"),
        }
    }

    /// The refined wall for preview part `part`, if this map has it.
    pub fn wall_for(&self, part: &PreviewPart) -> Option<&RiskWall> {
        self.walls.iter().find(|w| w.matches(part))
    }
}

/// What a risk map depends on besides the cut: the settings, the critical structures' meshes
/// and the length unit. A map computed for a preview stays right while this and the preview
/// stay the same.
#[derive(Clone, Debug)]
pub struct RiskKey {
    settings: RiskSettings,
    critical: Vec<Weak<Mesh>>,
    mm_per_unit: f64,
}

impl RiskKey {
    pub fn of(scene: &Scene) -> RiskKey {
        RiskKey {
            settings: scene.risk.clone(),
            critical: scene
                .models
                .iter()
                .filter(|m| scene.risk.critical.contains(&m.model.name))
                .map(|m| Arc::downgrade(&m.model.mesh))
                .collect(),
            mm_per_unit: scene.unit.mm_per_unit(),
        }
    }
}

impl PartialEq for RiskKey {
    fn eq(&self, other: &RiskKey) -> bool {
        self.settings == other.settings
            && self.mm_per_unit == other.mm_per_unit
            && self.critical.len() == other.critical.len()
            && self
                .critical
                .iter()
                .zip(&other.critical)
                .all(|(a, b)| a.strong_count() > 0 && Weak::ptr_eq(a, b))
    }
}

/// The last map computed, and what for: a turntable or a repeated render of one cut computes
/// it once.
#[derive(Default)]
pub struct RiskCache {
    last: Option<(Weak<PreviewGeometry>, RiskKey, Option<Arc<WallRisk>>)>,
    indexes: CriticalIndexes,
}

impl RiskCache {
    /// The risk map of `preview` in `scene` (see [`wall_risk`]), computed unless the last one
    /// was for the same preview and key.
    pub fn map(&mut self, scene: &Scene, preview: &Arc<PreviewGeometry>) -> Option<Arc<WallRisk>> {
        if !scene.risk.is_on() {
            return None;
        }
        let key = RiskKey::of(scene);
        if let Some((p, k, risk)) = &self.last
            && p.upgrade().is_some_and(|p| Arc::ptr_eq(&p, preview))
            && *k == key
        {
            return risk.clone();
        }
        let risk = wall_risk(scene, preview, &mut self.indexes).map(Arc::new);
        self.last = Some((Arc::downgrade(preview), key, risk.clone()));
        risk
    }
}

/// A critical structure's indexes: closest points and (closed ones) inside.
struct CriticalSolid {
    name: String,
    mesh: Arc<Mesh>,
    index: SpatialIndex,
    winding: Option<WindingTree>,
}

/// The indexes of critical structures, built once per mesh and kept while it lives (the
/// window's risk worker keeps one across cuts).
#[derive(Default)]
pub struct CriticalIndexes {
    solids: Vec<(Weak<Mesh>, Arc<CriticalSolid>)>,
}

impl CriticalIndexes {
    fn solid(&mut self, name: &str, mesh: &Arc<Mesh>) -> Arc<CriticalSolid> {
        self.solids.retain(|(w, _)| w.strong_count() > 0);
        if let Some((_, s)) = self
            .solids
            .iter()
            .find(|(w, s)| w.upgrade().is_some_and(|m| Arc::ptr_eq(&m, mesh)) && s.name == name)
        {
            return s.clone();
        }
        let closed = mesh.report().closed;
        let solid = Arc::new(CriticalSolid {
            name: name.to_string(),
            mesh: mesh.clone(),
            index: SpatialIndex::build(mesh),
            winding: closed.then(|| WindingTree::build(mesh)),
        });
        self.solids.push((Arc::downgrade(mesh), solid.clone()));
        solid
    }

    /// Drops the indexes of meshes other than `keep`'s.
    fn keep_only(&mut self, keep: &[Arc<CriticalSolid>]) {
        self.solids
            .retain(|(_, s)| keep.iter().any(|k| Arc::ptr_eq(k, s)));
    }
}

/// The risk map of `preview`'s cutter walls in `scene` (`None` when the map is off, or no
/// critical name is a structure of the scene). `indexes` keeps the critical structures' indexes
/// between calls.
pub fn wall_risk(
    scene: &Scene,
    preview: &PreviewGeometry,
    indexes: &mut CriticalIndexes,
) -> Option<WallRisk> {
    let settings = &scene.risk;
    if !settings.is_on() || settings.check().is_err() {
        return None;
    }
    let mut solids = Vec::new();
    let mut missing = Vec::new();
    for name in &settings.critical {
        let models: Vec<_> = scene
            .models
            .iter()
            .filter(|m| &m.model.name == name)
            .collect();
        if models.is_empty() {
            missing.push(name.clone());
        }
        for model in models {
            if !model.model.mesh.triangles.is_empty() {
                solids.push(indexes.solid(name, &model.model.mesh));
            }
        }
    }
    indexes.keep_only(&solids);
    if solids.is_empty() {
        return None;
    }
    let field = Field {
        solids: &solids,
        mm_per_unit: scene.unit.mm_per_unit(),
    };
    let mut walls = Vec::new();
    let mut nearest: Option<(f64, usize)> = None;
    let mut margin_mm: f64 = 0.0;
    for part in &preview.parts {
        if part.kind != PartKind::Wall || part.cutter == usize::MAX || part.mesh.is_empty() {
            continue;
        }
        let mut finest = FINEST_EDGE_MM;
        let refined = loop {
            if let Some(r) = refine(&part.mesh, &field, settings, finest) {
                break r;
            }
            finest *= 2.0;
        };
        margin_mm = margin_mm.max(finest);
        if let Some((d, k)) = refined.nearest
            && nearest.is_none_or(|(best, _)| d < best)
        {
            nearest = Some((d, k));
        }
        walls.push(RiskWall {
            model: part.model,
            cutter: part.cutter,
            source: (part.mesh.triangle_count(), part.mesh.positions.len()),
            mesh: refined.mesh,
            corner_mm: refined.corner_mm,
            origin: refined.origin,
        });
    }
    Some(WallRisk {
        settings: settings.clone(),
        ramp: RiskRamp::SCENE,
        walls,
        nearest: nearest.map(|(d, k)| Nearest {
            distance_mm: d,
            structure: solids[k].name.clone(),
        }),
        margin_mm: if margin_mm > 0.0 {
            margin_mm
        } else {
            FINEST_EDGE_MM
        },
        missing,
    })
}

/// The distance field of the critical solids.
struct Field<'a> {
    solids: &'a [Arc<CriticalSolid>],
    mm_per_unit: f64,
}

impl Field<'_> {
    /// The distance (mm) from `p` to the nearest critical solid, and which solid.
    fn at(&self, p: DVec3) -> (f64, usize) {
        let mut best = f64::INFINITY;
        let mut which = 0;
        for (k, s) in self.solids.iter().enumerate() {
            if let Some(c) = s.index.closest_point_within(&s.mesh, p, best)
                && c.distance < best
            {
                best = c.distance;
                which = k;
            }
        }
        if best > 0.0 {
            for (k, s) in self.solids.iter().enumerate() {
                if let Some(tree) = &s.winding
                    && tree.winding_number(&s.mesh, p).abs() > 0.5
                {
                    return (0.0, k);
                }
            }
        }
        (best * self.mm_per_unit, which)
    }
}

/// A refined wall.
struct Refined {
    mesh: Mesh,
    corner_mm: Vec<[f32; 3]>,
    origin: Vec<VertexOrigin>,
    /// The smallest vertex distance (mm) and its solid.
    nearest: Option<(f64, usize)>,
}

/// A triangle being refined: its vertices, the wall triangle it lies in, and its corners'
/// barycentric coordinates there.
struct Piece {
    vertices: [u32; 3],
    source: u32,
    bary: [DVec2; 3],
}

/// Refines `wall` as the module doc says, straddling triangles down to `finest` mm; `None` when
/// that would pass [`MAX_TRIANGLES`].
fn refine(wall: &Mesh, field: &Field, settings: &RiskSettings, finest: f64) -> Option<Refined> {
    let (near, far) = (settings.near_mm, settings.far_mm);
    let band_edge = BAND_EDGE_MM.max(finest);
    let mut positions: Vec<DVec3> = Vec::new();
    let mut origin: Vec<VertexOrigin> = Vec::new();
    let mut ids: HashMap<[u64; 3], u32> = HashMap::new();
    // The vertex at `p` (made on first use; a point on an edge two wall triangles share gets the
    // same interpolated values from either, so the first one's origin serves both).
    let mut vertex = |p: DVec3,
                      at: VertexOrigin,
                      positions: &mut Vec<DVec3>,
                      origin: &mut Vec<VertexOrigin>|
     -> u32 {
        *ids.entry(p.to_array().map(f64::to_bits))
            .or_insert_with(|| {
                positions.push(p);
                origin.push(at);
                (positions.len() - 1) as u32
            })
    };
    let corners = [DVec2::ZERO, DVec2::X, DVec2::Y];
    let mut active: Vec<Piece> = Vec::with_capacity(wall.triangles.len());
    for (t, tri) in wall.triangles.iter().enumerate() {
        let mut vertices = [0; 3];
        for k in 0..3 {
            let at = VertexOrigin {
                triangle: t as u32,
                bary: corners[k].to_array(),
            };
            vertices[k] = vertex(
                wall.positions[tri[k] as usize],
                at,
                &mut positions,
                &mut origin,
            );
        }
        active.push(Piece {
            vertices,
            source: t as u32,
            bary: corners,
        });
    }
    let mut distances: Vec<(f64, usize)> = Vec::new();
    let mut out = Mesh::default();
    let mut corner_mm = Vec::new();
    while !active.is_empty() {
        // The distances of the vertices made since the last level, in parallel.
        let fresh: Vec<(f64, usize)> = positions[distances.len()..]
            .par_iter()
            .map(|&p| field.at(p))
            .collect();
        distances.extend(fresh);
        let mut next = Vec::new();
        for piece in active {
            let t = piece.vertices;
            let p = t.map(|v| positions[v as usize]);
            let d = t.map(|v| distances[v as usize].0);
            let longest = (0..3)
                .map(|k| (p[k] - p[(k + 1) % 3]).length())
                .fold(0.0, f64::max)
                * field.mm_per_unit;
            let lower = d.iter().copied().fold(f64::NEG_INFINITY, f64::max) - longest;
            let upper = d.iter().copied().fold(f64::INFINITY, f64::min) + longest;
            let one_side = lower >= far || upper <= near || !longest.is_finite();
            // Lowered by the longest edge, the corners bound every point from below; inside
            // the band they may stay coarser as long as they stay out of the red.
            let lowered = d.map(|x| x - longest);
            let in_band = lowered.iter().all(|&x| x > near) && upper < far;
            let shown = if one_side {
                Some(d)
            } else if longest <= finest || (in_band && longest <= band_edge) {
                Some(lowered)
            } else {
                None
            };
            if let Some(c) = shown {
                out.triangles.push(t);
                corner_mm.push(c.map(at_most));
                continue;
            }
            let [a, b, c] = t;
            let [ba, bb, bc] = piece.bary;
            let mut mid = |i: usize, j: usize, bi: DVec2, bj: DVec2| {
                let at = VertexOrigin {
                    triangle: piece.source,
                    bary: ((bi + bj) * 0.5).to_array(),
                };
                vertex((p[i] + p[j]) * 0.5, at, &mut positions, &mut origin)
            };
            let (ab, bc_, ca) = (mid(0, 1, ba, bb), mid(1, 2, bb, bc), mid(2, 0, bc, ba));
            let (mab, mbc, mca) = ((ba + bb) * 0.5, (bb + bc) * 0.5, (bc + ba) * 0.5);
            let child = |vertices: [u32; 3], bary: [DVec2; 3]| Piece {
                vertices,
                source: piece.source,
                bary,
            };
            next.extend([
                child([a, ab, ca], [ba, mab, mca]),
                child([ab, b, bc_], [mab, bb, mbc]),
                child([ca, bc_, c], [mca, mbc, bc]),
                child([ab, bc_, ca], [mab, mbc, mca]),
            ]);
        }
        if out.triangles.len() + next.len() > MAX_TRIANGLES {
            return None;
        }
        active = next;
    }
    let nearest = distances.iter().copied().min_by(|a, b| a.0.total_cmp(&b.0));
    out.positions = positions;
    Some(Refined {
        mesh: out,
        corner_mm,
        origin,
        nearest,
    })
}

/// `x` as the largest `f32` not above it, so storing a bound never makes it safer.
fn at_most(x: f64) -> f32 {
    let y = x as f32;
    if f64::from(y) > x { y.next_down() } else { y }
}

#[cfg(test)]
#[path = "wall_risk_tests.rs"]
mod tests;
