//! Which structure the camera sees at each point of an image, by ray casting (an ID render on
//! the CPU): one ray from the eye through the centre of every `step`-th pixel against the
//! surfaces as drawn (kept parts, walls, ribbons and slices of cut models; the whole mesh of the
//! others). Only opaque, solid, visible models hide and are seen: a translucent skin lets the
//! labelled structures behind it show, as on screen. Used to put a label's leader on a pixel
//! where its structure really is visible.

use csg::{Mesh, SpatialIndex};
use glam::DVec2;
use rayon::prelude::*;

use crate::cutting::cut_scene::{PartKind, PreviewGeometry};
use crate::scene::{ModelStyle, Scene};

/// The model seen through each cell of a grid laid over the image.
#[derive(Clone, Debug, PartialEq)]
pub struct VisibleGrid {
    /// Cell size in pixels; cell (c, r) is sampled at pixel ((c + ½)·step, (r + ½)·step).
    pub step: u32,
    pub columns: u32,
    pub rows: u32,
    /// Row-major; the index into `Scene::models` of the model hit first, or `None`.
    pub cells: Vec<Option<u32>>,
    /// Row-major; whether the hit is on a cut face (a wall or slice wall) rather than on the
    /// structure's own surface. The contour line is drawn where the two meet, so an anchor keeps
    /// away from that border too.
    pub cut_face: Vec<bool>,
}

impl VisibleGrid {
    /// The model seen in cell (c, r).
    pub fn at(&self, c: u32, r: u32) -> Option<u32> {
        self.cells[(r * self.columns + c) as usize]
    }

    /// Pixel at the centre of cell (c, r).
    pub fn pixel(&self, c: u32, r: u32) -> [f32; 2] {
        [
            (c as f32 + 0.5) * self.step as f32,
            (r as f32 + 0.5) * self.step as f32,
        ]
    }
}

/// Whether model `m` hides what is behind it (and so can be labelled where it is seen).
pub fn is_opaque(scene: &Scene, m: usize) -> bool {
    let model = &scene.models[m];
    model.visible && model.style == ModelStyle::Solid && model.opacity >= 0.99
}

/// Casts the rays of a `size`-pixel image, one per `step`×`step` cell, through `scene` as
/// drawn with `preview` (the cut parts; `None`: every model whole).
pub fn visible_grid(
    scene: &Scene,
    preview: Option<&PreviewGeometry>,
    size: [u32; 2],
    step: u32,
) -> VisibleGrid {
    let step = step.max(1);
    let mut all = Mesh::default();
    // Per triangle of `all`: the model it belongs to.
    let mut owner: Vec<(u32, bool)> = Vec::new();
    let mut add = |mesh: &Mesh, m: usize, cut: bool| {
        all.append(mesh);
        owner.resize(all.triangle_count(), (m as u32, cut));
    };
    for m in 0..scene.models.len() {
        if !is_opaque(scene, m) {
            continue;
        }
        match preview {
            Some(p) if p.replaced.get(m).copied().unwrap_or(false) => {
                for part in p.parts.iter().filter(|p| p.model == m) {
                    if part.kind != PartKind::Removed {
                        let cut = matches!(part.kind, PartKind::Wall | PartKind::SliceWall);
                        add(&part.mesh, m, cut);
                    }
                }
            }
            _ => add(&scene.models[m].model.mesh, m, false),
        }
    }
    let columns = size[0].div_ceil(step);
    let rows = size[1].div_ceil(step);
    if all.triangle_count() == 0 {
        return VisibleGrid {
            step,
            columns,
            rows,
            cells: vec![None; (columns * rows) as usize],
            cut_face: vec![false; (columns * rows) as usize],
        };
    }
    let index = SpatialIndex::build(&all);
    let viewport = DVec2::new(size[0] as f64, size[1] as f64);
    let far = scene.camera.distance() * 1e3 + scene.bbox().diagonal().max(1.0) * 10.0;
    let hits: Vec<Option<(u32, bool)>> = (0..columns * rows)
        .into_par_iter()
        .map(|i| {
            let (c, r) = (i % columns, i / columns);
            let pixel = DVec2::new(
                (c as f64 + 0.5) * step as f64,
                (r as f64 + 0.5) * step as f64,
            );
            let ray = scene.camera.ray_through_pixel(viewport, pixel);
            index
                .ray_cast(&all, ray.origin, ray.direction, far)
                .map(|hit| owner[hit.face as usize])
        })
        .collect();
    VisibleGrid {
        step,
        columns,
        rows,
        cells: hits.iter().map(|h| h.map(|(m, _)| m)).collect(),
        cut_face: hits.iter().map(|h| h.is_some_and(|(_, cut)| cut)).collect(),
    }
}

/// The point where model `m` is most surely visible: the cell of `m` farthest from any cell
/// that does not see the same part of `m` (its own surface, or its cut faces, between which the
/// contour line is drawn) or lies outside the image, ties broken by nearness to the centroid of
/// its cells; `None` when no cell sees it.
pub fn anchor(grid: &VisibleGrid, m: u32) -> Option<[f32; 2]> {
    let (columns, rows) = (grid.columns as usize, grid.rows as usize);
    let class = |i: usize| (grid.cells[i] == Some(m)).then_some(grid.cut_face[i]);
    if !(0..columns * rows).any(|i| class(i).is_some()) {
        return None;
    }
    // Chamfer distance (3-4 weights) to the nearest cell of another class or the image's edge.
    let mut distance = vec![u32::MAX / 2; columns * rows];
    for i in 0..columns * rows {
        if class(i).is_none() {
            distance[i] = 0;
        }
    }
    let neighbours_before = [(-1i64, 0i64, 3u32), (-1, -1, 4), (0, -1, 3), (1, -1, 4)];
    let pass = |distance: &mut Vec<u32>, order: &mut dyn Iterator<Item = usize>, sign: i64| {
        for i in order {
            if distance[i] == 0 {
                continue;
            }
            let (c, r) = ((i % columns) as i64, (i / columns) as i64);
            let mut best = distance[i];
            for &(dc, dr, w) in &neighbours_before {
                let (cc, rr) = (c + sign * dc, r + sign * dr);
                let d = if cc < 0 || rr < 0 || cc >= columns as i64 || rr >= rows as i64 {
                    0
                } else {
                    let j = rr as usize * columns + cc as usize;
                    if class(j) != class(i) { 0 } else { distance[j] }
                };
                best = best.min(d + w);
            }
            distance[i] = best;
        }
    };
    pass(&mut distance, &mut (0..columns * rows), 1);
    pass(&mut distance, &mut (0..columns * rows).rev(), -1);
    let cells: Vec<usize> = (0..columns * rows)
        .filter(|&i| class(i).is_some())
        .collect();
    let n = cells.len() as f64;
    let cx = cells.iter().map(|&i| (i % columns) as f64).sum::<f64>() / n;
    let cy = cells.iter().map(|&i| (i / columns) as f64).sum::<f64>() / n;
    let near =
        |i: usize| -(((i % columns) as f64 - cx).powi(2) + ((i / columns) as f64 - cy).powi(2));
    let best = cells.iter().copied().max_by(|&a, &b| {
        distance[a]
            .cmp(&distance[b])
            .then(near(a).total_cmp(&near(b)))
    })?;
    Some(grid.pixel((best % columns) as u32, (best / columns) as u32))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_anchor_is_inside_the_structure_s_cells_even_for_a_ring() {
        // A ring of model 1 around a hole of model 0: the centroid is in the hole, the anchor
        // must not be.
        let (columns, rows) = (21, 21);
        let cells = (0..columns * rows)
            .map(|i| {
                let (c, r) = ((i % columns) as i32 - 10, (i / columns) as i32 - 10);
                let d2 = c * c + r * r;
                if d2 <= 16 {
                    Some(0)
                } else if d2 <= 81 {
                    Some(1)
                } else {
                    None
                }
            })
            .collect();
        let grid = VisibleGrid {
            step: 4,
            columns,
            rows,
            cells,
            cut_face: vec![false; (columns * rows) as usize],
        };
        for m in [0, 1] {
            let [x, y] = anchor(&grid, m).unwrap();
            let (c, r) = ((x / 4.0) as u32, (y / 4.0) as u32);
            assert_eq!(grid.at(c, r), Some(m));
        }
        assert_eq!(anchor(&grid, 2), None);
    }
}
