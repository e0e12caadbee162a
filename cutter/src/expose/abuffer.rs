//! Every surface crossing of every sampled ray: the meshes rasterized into the view grid, each
//! cell keeping all the depths its centre ray crosses a mesh at (an "A-buffer"), nearest first.
//!
//! A ray through a cell centre crosses a triangle when the centre lies inside the triangle's
//! image in `(u, v)` (see `frame.rs`). The test is watertight: the edge function of an edge is
//! evaluated from its lower-numbered vertex, so the two triangles sharing the edge get exactly
//! opposite values, and a centre exactly on an edge belongs to one side by a top-left rule. A
//! ray therefore crosses a closed surface an even number of times, and the parity of the
//! crossings before a depth says whether that point is inside. The depth at the centre is
//! interpolated as `1/z`, which is exact on a flat triangle.
//!
//! Triangles with a corner at or behind `near` (the eye's plane, pushed forward) are left out:
//! no ray of the grid can reach them from the front.

use csg::Mesh;
use rayon::prelude::*;

use crate::expose::frame::ViewFrame;

/// One crossing of a cell's ray with a mesh.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Crossing {
    /// View depth of the crossing.
    pub z: f64,
    /// Index of the mesh crossed, in the order the meshes were given.
    pub mesh: u32,
}

/// The crossings of every cell's ray, nearest first.
#[derive(Clone, Debug, Default)]
pub struct ABuffer {
    /// Cell `c`'s crossings are `crossings[starts[c]..starts[c + 1]]`; `cells + 1` entries.
    starts: Vec<usize>,
    /// Sorted by cell, then by depth.
    crossings: Vec<Crossing>,
}

impl ABuffer {
    /// Rasterizes `meshes` into `frame`'s grid. Triangles with a corner at a depth `<= near`
    /// are skipped.
    pub fn build(frame: &ViewFrame, meshes: &[&Mesh], near: f64) -> ABuffer {
        let mut found: Vec<(u32, Crossing)> = meshes
            .par_iter()
            .enumerate()
            .flat_map_iter(|(m, mesh)| {
                let mut found = Vec::new();
                rasterize(frame, mesh, m as u32, near, &mut found);
                found
            })
            .collect();
        // By cell, then depth; ties (a ray through an edge two meshes share) by mesh, so the
        // order never depends on the threads.
        found.par_sort_unstable_by(|a, b| {
            (a.0.cmp(&b.0))
                .then(a.1.z.total_cmp(&b.1.z))
                .then(a.1.mesh.cmp(&b.1.mesh))
        });
        let mut starts = vec![0; frame.cells() + 1];
        for (cell, _) in &found {
            starts[*cell as usize + 1] += 1;
        }
        for c in 0..frame.cells() {
            starts[c + 1] += starts[c];
        }
        ABuffer {
            starts,
            crossings: found.into_iter().map(|(_, x)| x).collect(),
        }
    }

    /// The crossings of cell `cell`'s ray, nearest first.
    pub fn at(&self, cell: usize) -> &[Crossing] {
        &self.crossings[self.starts[cell]..self.starts[cell + 1]]
    }

    /// Number of crossings in all.
    pub fn len(&self) -> usize {
        self.crossings.len()
    }

    /// True when no ray crosses anything.
    pub fn is_empty(&self) -> bool {
        self.crossings.is_empty()
    }
}

/// Adds the crossings of `mesh`'s triangles (tagged `tag`) with the grid's rays to `out`.
fn rasterize(frame: &ViewFrame, mesh: &Mesh, tag: u32, near: f64, out: &mut Vec<(u32, Crossing)>) {
    let projected: Vec<[f64; 3]> = mesh.positions.iter().map(|&p| frame.project(p)).collect();
    let u_end = frame.column_edge(frame.columns);
    let v_end = frame.row_edge(frame.rows);
    for tri in &mesh.triangles {
        let [a, b, c] = tri.map(|i| projected[i as usize]);
        if a[2] <= near || b[2] <= near || c[2] <= near {
            continue;
        }
        let (u_min, u_max) = (a[0].min(b[0]).min(c[0]), a[0].max(b[0]).max(c[0]));
        let (v_min, v_max) = (a[1].min(b[1]).min(c[1]), a[1].max(b[1]).max(c[1]));
        if u_max < frame.origin[0] || u_min > u_end || v_max < frame.origin[1] || v_min > v_end {
            continue;
        }
        // Signed area (twice) of the image; edge-on triangles are crossed by no ray.
        let area = edge(tri[0], a, tri[1], b, [c[0], c[1]]);
        if area == 0.0 || !area.is_finite() {
            continue;
        }
        let sign = area.signum();
        let Some((i0, i1)) = cell_range(u_min, u_max, frame.origin[0], frame.cell, frame.columns)
        else {
            continue;
        };
        let Some((j0, j1)) = cell_range(v_min, v_max, frame.origin[1], frame.cell, frame.rows)
        else {
            continue;
        };
        // The edges opposite each corner, counter-clockwise in the image.
        let edges = [(1, 2), (2, 0), (0, 1)];
        let corners = [a, b, c];
        let include_on_edge = edges.map(|(p, q)| {
            let d = [
                (corners[q][0] - corners[p][0]) * sign,
                (corners[q][1] - corners[p][1]) * sign,
            ];
            top_left(d)
        });
        for i in i0..=i1 {
            for j in j0..=j1 {
                let centre = frame.centre(i, j);
                let mut w = [0.0; 3];
                let mut inside = true;
                for (k, &(p, q)) in edges.iter().enumerate() {
                    let e = edge(tri[p], corners[p], tri[q], corners[q], centre) * sign;
                    if e < 0.0 || (e == 0.0 && !include_on_edge[k]) {
                        inside = false;
                        break;
                    }
                    w[k] = e;
                }
                if !inside {
                    continue;
                }
                let total = w[0] + w[1] + w[2];
                if total <= 0.0 {
                    continue;
                }
                let inverse_z = (w[0] / a[2] + w[1] / b[2] + w[2] / c[2]) / total;
                out.push((
                    frame.index(i, j) as u32,
                    Crossing {
                        z: 1.0 / inverse_z,
                        mesh: tag,
                    },
                ));
            }
        }
    }
}

/// Columns (or rows) whose centres lie in `[low, high]`, clamped to the grid; `None` when none.
fn cell_range(low: f64, high: f64, origin: f64, cell: f64, count: usize) -> Option<(usize, usize)> {
    let first = ((low - origin) / cell - 0.5).ceil().max(0.0);
    let last = ((high - origin) / cell - 0.5)
        .floor()
        .min(count as f64 - 1.0);
    (first <= last).then_some((first as usize, last as usize))
}

/// Twice the signed area of (`p`, `q`, `x`) in the image: positive when `x` lies left of the
/// edge `p → q`. Evaluated from the lower-numbered vertex, so the edge `q → p` gives exactly the
/// negated value.
fn edge(p_id: u32, p: [f64; 3], q_id: u32, q: [f64; 3], x: [f64; 2]) -> f64 {
    let raw =
        |p: [f64; 3], q: [f64; 3]| (q[0] - p[0]) * (x[1] - p[1]) - (q[1] - p[1]) * (x[0] - p[0]);
    if p_id <= q_id { raw(p, q) } else { -raw(q, p) }
}

/// The top-left rule for an edge of direction `d` of a counter-clockwise image: a point exactly
/// on it belongs to the triangle for one of the two directions an edge can have.
fn top_left(d: [f64; 2]) -> bool {
    d[1] > 0.0 || (d[1] == 0.0 && d[0] < 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    fn frame(resolution: usize) -> ViewFrame {
        ViewFrame::oriented(
            DVec3::new(0.0, -100.0, 0.0),
            DVec3::Y,
            DVec3::X,
            DVec3::Z,
            &[],
        )
        .with_grid([-0.2, 0.2], [-0.2, 0.2], resolution)
    }

    #[test]
    fn every_ray_through_a_closed_surface_crosses_it_an_even_number_of_times() {
        let sphere = csg::testkit::geodesic_sphere(12, 10.0);
        let frame = frame(97);
        let buffer = ABuffer::build(&frame, &[&sphere], 1e-6);
        let mut through = 0;
        for c in 0..frame.cells() {
            let n = buffer.at(c).len();
            assert!(n.is_multiple_of(2), "cell {c} crosses {n} times");
            through += usize::from(n > 0);
        }
        // The sphere of radius 10 seen from 100 covers a disc of radius tan(asin 0.1) in the
        // 0.4-wide grid (a little less: the geodesic sphere's vertices lie on the sphere).
        let share = through as f64 / frame.cells() as f64;
        let radius = 10.0 / 9900f64.sqrt();
        let expected = std::f64::consts::PI * radius * radius / 0.16;
        assert!((share - expected).abs() < 0.03, "{share} vs {expected}");
    }

    #[test]
    fn depths_are_those_of_the_surface() {
        // A square facing the eye at depth 50 (y = -50) and a sphere behind it.
        let square = csg::testkit::cube(DVec3::new(-5.0, -51.0, -5.0), DVec3::new(5.0, -49.0, 5.0));
        let frame = frame(31);
        let buffer = ABuffer::build(&frame, &[&square], 1e-6);
        let centre = frame.index(15, 15);
        let hits = buffer.at(centre);
        assert_eq!(hits.len(), 2);
        assert!(
            (hits[0].z - 49.0).abs() < 1e-9 && (hits[1].z - 51.0).abs() < 1e-9,
            "{hits:?}"
        );
    }
}
