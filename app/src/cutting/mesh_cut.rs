//! One closed cutter cut out of every region of a target mesh, with the meshes a caller writes or
//! hands on: what `cutaway subtract` and the Python `cutaway.subtract` both do. Two clocks: the
//! cut itself against the built index (`cut_ms`, what one drag frame of the editor pays), then
//! building the full kept and removed meshes from the cut's deltas (`materialize_ms`).

use std::time::Instant;

use csg::Mesh;
use glam::DVec3;

/// The outcome of [`cut_mesh`].
#[derive(Debug)]
pub struct MeshCut {
    pub target_triangles: usize,
    pub cutter_triangles: usize,
    pub kept: Mesh,
    pub walls: Mesh,
    pub removed: Mesh,
    /// The contours as polylines, a closed loop with its first point repeated at the end.
    pub contour: Vec<Vec<DVec3>>,
    /// Per region: kept, walls, removed (empty for a target with one region).
    pub regions: Vec<csg::RegionParts>,
    /// One per entry of `regions`.
    pub region_reports: Vec<RegionReport>,
    pub cut_ms: f64,
    pub materialize_ms: f64,
}

/// One region's share of the cut (`regions` of `cutaway subtract --json`).
#[derive(Clone, Debug, serde::Serialize)]
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

/// Which input a [`cut_mesh`] error is about, so the caller names the right file.
#[derive(Debug)]
pub enum MeshCutError {
    /// The target could not be indexed (not a valid solid).
    Target(anyhow::Error),
    /// The cutter was refused by the boolean.
    Cutter(anyhow::Error),
}

/// Cuts `cutter` out of every region of `target` (each region as its own solid, see
/// [`csg::subtract`]).
pub fn cut_mesh(target: Mesh, cutter: &Mesh) -> Result<MeshCut, MeshCutError> {
    let target_triangles = target.triangles.len();
    let index = csg::TargetIndex::build(target).map_err(|e| MeshCutError::Target(e.into()))?;
    let clock = Instant::now();
    let result = csg::subtract(&index, cutter).map_err(|e| MeshCutError::Cutter(e.into()))?;
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
    let region_reports = regions
        .iter()
        .enumerate()
        .map(|(index, parts)| region_report(index, parts))
        .collect();
    Ok(MeshCut {
        target_triangles,
        cutter_triangles: cutter.triangles.len(),
        kept,
        walls: result.walls.mesh.clone(),
        removed,
        contour: contour_polylines(&result.contours),
        regions,
        region_reports,
        cut_ms,
        materialize_ms,
    })
}

/// The contours as polylines, a closed loop with its first point repeated at the end (written
/// as a closed `l` record).
fn contour_polylines(contours: &[csg::Contour]) -> Vec<Vec<DVec3>> {
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

/// The report of region `index`: its triangle counts, the volume of its removed solid and
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
