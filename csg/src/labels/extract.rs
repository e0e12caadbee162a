//! Raw surface of one label: marching cubes over the label's padded bounding box.
//!
//! Notation: local voxel `(u, v, w)` is global voxel `(u, v, w) + origin`, where `origin` is the
//! label's box minimum minus one, so the local grid is the box padded by one voxel of outside on
//! every side (voxels outside the grid are outside too): the surface is always closed. Cube
//! `(u, v, w)` has local corners `(u..=u+1, v..=v+1, w..=w+1)`.
//!
//! Stages per layer of cubes `w`: read slice `w + 1` into a mask, then for each cube look up its
//! polygons ([`super::cases`]), create the edge vertices it is the first to meet (and a centre
//! vertex per fanned polygon), and emit the polygon's triangles (its direct fill, or one fan
//! triangle per segment). Edge vertex ids live in rolling buffers of
//! two slices, so memory is O(box slice), never O(grid).

use glam::DVec3;

use super::cases;
use super::scan::LabelStats;
use super::{Constraint, LabelGrid, LabelValue, VoxelSurface};

/// No vertex yet on this edge.
const NONE: u32 = u32::MAX;

/// How far an edge vertex stays from the voxel centres at the ends of its edge (in voxels), so
/// that smoothing cannot collapse a triangle onto a voxel centre.
pub const EDGE_MARGIN: f64 = 0.05;

/// Midpoint of each cube edge in the unit cube (as [`cases::edge_midpoint`]).
const EDGE_MIDPOINTS: [DVec3; 12] = {
    let mut mids = [DVec3::ZERO; 12];
    let mut e = 0;
    while e < 12 {
        let [a, b] = cases::EDGE_CORNERS[e];
        mids[e] = DVec3::new(
            half(a, 0) + half(b, 0),
            half(a, 1) + half(b, 1),
            half(a, 2) + half(b, 2),
        );
        e += 1;
    }
    mids
};

/// Half the `bit`-th coordinate of corner `c`.
const fn half(c: usize, bit: usize) -> f64 {
    ((c >> bit) & 1) as f64 * 0.5
}

/// Edge vertex ids of the current layer of cubes: x- and y-edges of its low and high slices (the
/// x-edge of local voxel `(u, v)` at `2 * (u + width * v)`, its y-edge at the next index), and the
/// z-edges between them at `u + width * v`.
struct LayerEdges {
    width: usize,
    xy_lo: Vec<u32>,
    xy_hi: Vec<u32>,
    z_mid: Vec<u32>,
}

impl LayerEdges {
    /// The id slot of edge `e` of cube `(u, v)` in this layer.
    fn slot(&mut self, u: usize, v: usize, e: u8) -> &mut u32 {
        let width = self.width;
        match e {
            0..4 => {
                let (dv, dz) = ((e & 1) as usize, (e >> 1) as usize);
                let ids = if dz == 0 {
                    &mut self.xy_lo
                } else {
                    &mut self.xy_hi
                };
                &mut ids[2 * (u + width * (v + dv))]
            }
            4..8 => {
                let f = e - 4;
                let (du, dz) = ((f & 1) as usize, (f >> 1) as usize);
                let ids = if dz == 0 {
                    &mut self.xy_lo
                } else {
                    &mut self.xy_hi
                };
                &mut ids[2 * (u + du + width * v) + 1]
            }
            _ => {
                let f = e - 8;
                let (du, dv) = ((f & 1) as usize, (f >> 1) as usize);
                &mut self.z_mid[u + du + width * (v + dv)]
            }
        }
    }

    /// Moves on to the next layer: the high slice becomes the low one.
    fn advance(&mut self) {
        std::mem::swap(&mut self.xy_lo, &mut self.xy_hi);
        self.xy_hi.fill(NONE);
        self.z_mid.fill(NONE);
    }
}

/// The raw surface of label `stats.value` in box coordinates, with constraint boxes. `None`
/// when it would need more than `u32::MAX` vertices.
pub fn extract_label<T: LabelValue>(
    grid: &LabelGrid<T>,
    stats: &LabelStats,
) -> Option<VoxelSurface> {
    let value = stats.value;
    let origin = stats.min.map(|m| m as i64 - 1);
    let size = [0, 1, 2].map(|a| stats.max[a] - stats.min[a] + 3);
    let [width, height, depth] = size;
    let plane = width * height;
    let table = cases::table();

    let mut mask_lo = vec![0u8; plane];
    let mut mask_hi = vec![0u8; plane];
    let mut rows_lo = vec![EMPTY_ROW; height];
    let mut rows_hi = vec![EMPTY_ROW; height];
    read_slice(grid, value, origin, size, 0, &mut mask_lo, &mut rows_lo);
    let mut edges = LayerEdges {
        width,
        xy_lo: vec![NONE; 2 * plane],
        xy_hi: vec![NONE; 2 * plane],
        z_mid: vec![NONE; plane],
    };
    let mut out = VoxelSurface {
        origin: DVec3::new(origin[0] as f64, origin[1] as f64, origin[2] as f64),
        ..VoxelSurface::default()
    };
    let mut overflow = false;

    for w in 0..depth - 1 {
        read_slice(grid, value, origin, size, w + 1, &mut mask_hi, &mut rows_hi);
        for v in 0..height - 1 {
            // Cubes with an inside corner: from one left of the first inside voxel of the four
            // rows they touch to the last one (the box's padding keeps both in range).
            let rows = [rows_lo[v], rows_lo[v + 1], rows_hi[v], rows_hi[v + 1]];
            let first = rows.iter().map(|r| r.0).min().unwrap_or(usize::MAX);
            let last = rows.iter().map(|r| r.1).max().unwrap_or(0);
            if first > last {
                continue;
            }
            let (row0, row1) = (width * v..width * (v + 1), width * (v + 1)..width * (v + 2));
            let (lo0, lo1) = (&mask_lo[row0.clone()], &mask_lo[row1.clone()]);
            let (hi0, hi1) = (&mask_hi[row0], &mask_hi[row1]);
            // The four corners of column u of the cube row, in the config bits of its low
            // corners (dx = 0); the next column's shifted by one are the high corners.
            let column = |u: usize| lo0[u] | lo1[u] << 2 | hi0[u] << 4 | hi1[u] << 6;
            let mut left = column(first - 1);
            for u in first - 1..last + 1 {
                let right = column(u + 1);
                let config = left | right << 1;
                left = right;
                if config == 0 || config == 255 {
                    continue;
                }
                let cube = DVec3::new(u as f64, v as f64, w as f64);
                let mut vertex = |out: &mut VoxelSurface, e: u8| {
                    let slot = edges.slot(u, v, e);
                    if *slot == NONE {
                        *slot = out.positions.len() as u32;
                        push_edge_vertex(out, cube, e as usize);
                    }
                    *slot
                };
                for polygon in &table[config as usize] {
                    match polygon.direct[..] {
                        [a, b, c] => {
                            let t = [a, b, c].map(|e| vertex(&mut out, e));
                            out.triangles.push(t);
                            continue;
                        }
                        [a, b, c, d] => {
                            let q = [a, b, c, d].map(|e| vertex(&mut out, e));
                            out.quads.push(q);
                            continue;
                        }
                        _ => {}
                    }
                    let centre = out.positions.len() as u32;
                    out.positions.push(cube + polygon.centre);
                    out.constraint
                        .push(Constraint::centre(out.centre_boxes.len()));
                    out.centre_boxes
                        .push([cube + polygon.lo, cube + polygon.hi]);
                    for &[from, to] in &polygon.segments {
                        let (a, b) = (vertex(&mut out, from), vertex(&mut out, to));
                        out.triangles.push([centre, a, b]);
                    }
                }
                if out.positions.len() >= NONE as usize - 64 {
                    overflow = true;
                }
            }
            if overflow {
                return None;
            }
        }
        std::mem::swap(&mut mask_lo, &mut mask_hi);
        std::mem::swap(&mut rows_lo, &mut rows_hi);
        edges.advance();
    }
    Some(out)
}

/// Appends the vertex of cube edge `e` at its midpoint; smoothing keeps it on the edge less
/// [`EDGE_MARGIN`] at each end.
fn push_edge_vertex(out: &mut VoxelSurface, cube: DVec3, e: usize) {
    out.positions.push(cube + EDGE_MIDPOINTS[e]);
    out.constraint.push(Constraint::edge(e / 4));
}

/// `(first, last)` local u of the inside voxels of a mask row; `first > last` when there are none.
type RowSpan = (usize, usize);

/// The span of a row with no inside voxel.
const EMPTY_ROW: RowSpan = (usize::MAX, 0);

/// Fills `mask` with 1 where local slice `w` holds `value`, 0 elsewhere (outside the grid too),
/// and `rows` with each row's span of inside voxels.
fn read_slice<T: LabelValue>(
    grid: &LabelGrid<T>,
    value: u32,
    origin: [i64; 3],
    size: [usize; 3],
    w: usize,
    mask: &mut [u8],
    rows: &mut [RowSpan],
) {
    mask.fill(0);
    rows.fill(EMPTY_ROW);
    let [nx, ny, nz] = grid.dims.map(|d| d as i64);
    let z = w as i64 + origin[2];
    if z < 0 || z >= nz {
        return;
    }
    let [width, height, _] = size;
    // Local u range that lies inside the grid.
    let u0 = (-origin[0]).max(0) as usize;
    let u1 = ((nx - origin[0]) as usize).min(width);
    for v in 0..height {
        let y = v as i64 + origin[1];
        if y < 0 || y >= ny {
            continue;
        }
        let row_start = (nx * (y + ny * z)) as usize;
        let row = &grid.data[row_start..row_start + nx as usize];
        let out = &mut mask[width * v..width * (v + 1)];
        let (mut first, mut last) = EMPTY_ROW;
        for u in u0..u1 {
            let x = (u as i64 + origin[0]) as usize;
            let inside = row[x].to_u32() == value;
            out[u] = inside as u8;
            if inside {
                first = first.min(u);
                last = u;
            }
        }
        rows[v] = (first, last);
    }
}
