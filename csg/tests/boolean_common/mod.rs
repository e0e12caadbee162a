//! Shared helpers of the boolean tests: cutter generators and the invariant checks.
#![allow(dead_code)]

use std::collections::HashMap;

use csg::{CutOptions, CutResult, DVec3, Mesh, TargetIndex, VertexSource};

pub use csg::cutcheck::volume;

pub fn area(m: &Mesh) -> f64 {
    m.area()
}

/// Welds bit-identical positions (so parts from different meshes share contour vertices).
pub fn weld(m: &Mesh) -> Mesh {
    let mut map: HashMap<[u64; 3], u32> = HashMap::new();
    let mut positions = Vec::new();
    let mut remap = Vec::with_capacity(m.positions.len());
    for p in &m.positions {
        let key = [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()];
        let id = *map.entry(key).or_insert_with(|| {
            positions.push(*p);
            (positions.len() - 1) as u32
        });
        remap.push(id);
    }
    Mesh {
        positions,
        triangles: m
            .triangles
            .iter()
            .map(|t| t.map(|i| remap[i as usize]))
            .collect(),
    }
}

/// `Err` naming the first problem unless every edge has exactly two faces traversing it in
/// opposite directions and no triangle repeats an index (after welding by position).
pub fn check_closed_oriented(m: &Mesh) -> Result<(), String> {
    check_closed_by_source(&weld(m).triangles)
}

pub fn concat(a: &Mesh, b: &Mesh) -> Mesh {
    let mut m = a.clone();
    m.append(b);
    m
}

// The measure identities (area partition, volume identity, exact vertices) are the fuzz body's.
pub use csg::cutcheck::check_measures;

// The closedness-by-identity check and the face lists are the fuzz body's (one definition).
pub use csg::cutcheck::{closed_by_identity as check_closed_by_source, part_faces};

/// Checks every invariant of the robustness contract for a closed target on a result computed
/// with `merge_coincident = false` (closedness by symbolic identity) and the measures.
pub fn check_cut(target: &Mesh, result: &CutResult) -> Result<(), String> {
    check_measures(target, result)?;
    let n = target.positions.len() as u32;
    let (kept, _) = result.materialize_with_provenance(target);
    let src = |i: u32| {
        if i < n {
            VertexSource::Target(i)
        } else {
            VertexSource::New(i - n)
        }
    };
    let kept_faces: Vec<[VertexSource; 3]> = kept.triangles.iter().map(|t| t.map(src)).collect();
    let mut kw = kept_faces.clone();
    kw.extend(part_faces(&result.walls, false));
    check_closed_by_source(&kw).map_err(|e| format!("kept + walls: {e}"))?;
    let mut rw = part_faces(&result.removed, false);
    rw.extend(part_faces(&result.walls, true));
    check_closed_by_source(&rw).map_err(|e| format!("removed + reversed walls: {e}"))?;
    if result.walls.provenance.len() != result.walls.mesh.triangles.len()
        || result.removed.provenance.len() != result.removed.mesh.triangles.len()
        || result.kept_new_provenance.len() != result.kept_new_faces.len()
    {
        return Err("provenance length mismatch".into());
    }
    for c in &result.contours {
        if !c.closed {
            return Err("open contour on a closed target".into());
        }
    }
    if result.stats.status_fallbacks != 0 {
        return Err(format!(
            "{} status fallbacks",
            result.stats.status_fallbacks
        ));
    }
    if result.stats.triangulation_fallbacks != 0 {
        return Err(format!(
            "{} triangulation fallbacks",
            result.stats.triangulation_fallbacks
        ));
    }
    Ok(())
}

/// Checks the merged output (the default) by position: closed and oriented after welding.
pub fn check_cut_welded(target: &Mesh, result: &CutResult) -> Result<(), String> {
    check_measures(target, result)?;
    let kept = result.materialize(target);
    let kw = concat(&kept, &result.walls.mesh);
    check_closed_oriented(&kw).map_err(|e| format!("kept + walls: {e}"))?;
    let rw = concat(&result.removed.mesh, &result.walls.mesh.reversed());
    check_closed_oriented(&rw).map_err(|e| format!("removed + reversed walls: {e}"))?;
    Ok(())
}

/// Cuts without merging coincident vertices and checks the contract; then cuts with the
/// default options and checks the measures. Returns the default result.
pub fn cut_checked(index: &TargetIndex, target: &Mesh, cutter: &Mesh) -> Result<CutResult, String> {
    let symbolic = csg::subtract_with(
        index,
        &[cutter],
        &CutOptions::default().with_merge_coincident(false),
    )
    .map_err(|e| format!("cut failed: {e}"))?;
    check_cut(target, &symbolic)?;
    let merged = csg::subtract(index, cutter).map_err(|e| format!("cut failed: {e}"))?;
    check_measures(target, &merged)?;
    Ok(merged)
}

/// A closed strip: a rectangle (`width` along `side`, `height` along `up`) swept along `path`,
/// as triangles; ends capped. Outward oriented when the path turns gently.
pub fn strip(path: &[DVec3], up: DVec3, width: f64, height: f64) -> Mesh {
    let n = path.len();
    let mut positions = Vec::new();
    for i in 0..n {
        let tangent = if i + 1 < n {
            path[i + 1] - path[i]
        } else {
            path[i] - path[i - 1]
        };
        let side = tangent.cross(up).normalize() * (width * 0.5);
        let u = up.normalize() * (height * 0.5);
        let c = path[i];
        // 0: -side -up, 1: +side -up, 2: +side +up, 3: -side +up
        positions.extend([c - side - u, c + side - u, c + side + u, c - side + u]);
    }
    let mut quads: Vec<[u32; 4]> = Vec::new();
    for i in 0..n as u32 - 1 {
        let (a, b) = (4 * i, 4 * (i + 1));
        for k in 0..4u32 {
            let k1 = (k + 1) % 4;
            quads.push([a + k, a + k1, b + k1, b + k]);
        }
    }
    let last = 4 * (n as u32 - 1);
    quads.push([0, 3, 2, 1]);
    quads.push([last, last + 1, last + 2, last + 3]);
    let mut triangles = Vec::new();
    for [a, b, c, d] in quads {
        triangles.push([a, b, c]);
        triangles.push([a, c, d]);
    }
    let mut m = Mesh {
        positions,
        triangles,
    };
    if volume(&m) < 0.0 {
        m = m.reversed();
    }
    m
}

/// Snaps every coordinate to a multiple of `step`.
pub fn snapped(m: &Mesh, step: f64) -> Mesh {
    Mesh {
        positions: m
            .positions
            .iter()
            .map(|p| (*p / step).round() * step)
            .collect(),
        triangles: m.triangles.clone(),
    }
}

/// Cuts and checks (see [`cut_checked`]); panics with the problem.
pub fn cut_and_check(target: &Mesh, cutter: &Mesh) -> CutResult {
    let index = TargetIndex::build(target.clone()).expect("target index");
    cut_checked(&index, target, cutter).unwrap_or_else(|e| panic!("{e}"))
}
