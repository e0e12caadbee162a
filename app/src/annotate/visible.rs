//! Which structure the camera sees at each point of an image, by ray casting (an ID render on
//! the CPU): one ray from the eye through the centre of every `step`-th pixel against the
//! surfaces as drawn (kept parts, walls, ribbons and slices of cut models; the whole mesh of the
//! others). Only opaque, solid, visible models hide and are seen: a translucent skin lets the
//! labelled structures behind it show, as on screen. Used to put a label's leader on a pixel
//! where its structure really is visible.

use csg::{Mesh, SpatialIndex};
use glam::DVec2;
use rayon::prelude::*;

use crate::cutaway_geometry::{PartKind, PreviewGeometry};
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
    let mut owner: Vec<u32> = Vec::new();
    let mut add = |mesh: &Mesh, m: usize| {
        all.append(mesh);
        owner.resize(all.triangle_count(), m as u32);
    };
    for m in 0..scene.models.len() {
        if !is_opaque(scene, m) {
            continue;
        }
        match preview {
            Some(p) if p.replaced.get(m).copied().unwrap_or(false) => {
                for part in p.parts.iter().filter(|p| p.model == m) {
                    if part.kind != PartKind::Removed {
                        add(&part.mesh, m);
                    }
                }
            }
            _ => add(&scene.models[m].mesh, m),
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
        };
    }
    let index = SpatialIndex::build(&all);
    let viewport = DVec2::new(size[0] as f64, size[1] as f64);
    let far = scene.camera.distance() * 1e3 + scene.bbox().diagonal().max(1.0) * 10.0;
    let cells = (0..columns * rows)
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
        cells,
    }
}

/// The point where model `m` is most surely visible: among the cells that see it, the one with
/// the most cells of `m` around it (within two cells), ties broken by nearness to the centroid
/// of its cells; `None` when no cell sees it.
pub fn anchor(grid: &VisibleGrid, m: u32) -> Option<[f32; 2]> {
    let cells: Vec<(u32, u32)> = (0..grid.rows)
        .flat_map(|r| (0..grid.columns).map(move |c| (c, r)))
        .filter(|&(c, r)| grid.at(c, r) == Some(m))
        .collect();
    if cells.is_empty() {
        return None;
    }
    let n = cells.len() as f64;
    let cx = cells.iter().map(|&(c, _)| c as f64).sum::<f64>() / n;
    let cy = cells.iter().map(|&(_, r)| r as f64).sum::<f64>() / n;
    let interior = |c: u32, r: u32| {
        let mut count = 0;
        for dr in -2i64..=2 {
            for dc in -2i64..=2 {
                let (cc, rr) = (c as i64 + dc, r as i64 + dr);
                if cc >= 0
                    && rr >= 0
                    && cc < grid.columns as i64
                    && rr < grid.rows as i64
                    && grid.at(cc as u32, rr as u32) == Some(m)
                {
                    count += 1;
                }
            }
        }
        count
    };
    let best = cells.iter().copied().max_by(|&(a, b), &(c, d)| {
        let far = |x: u32, y: u32| -((x as f64 - cx).powi(2) + (y as f64 - cy).powi(2));
        interior(a, b)
            .cmp(&interior(c, d))
            .then(far(a, b).total_cmp(&far(c, d)))
    })?;
    Some(grid.pixel(best.0, best.1))
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
        };
        for m in [0, 1] {
            let [x, y] = anchor(&grid, m).unwrap();
            let (c, r) = ((x / 4.0) as u32, (y / 4.0) as u32);
            assert_eq!(grid.at(c, r), Some(m));
        }
        assert_eq!(anchor(&grid, 2), None);
    }
}
