//! The view frame of an exposure and its grid of rays.
//!
//! Notation: `E` the eye, `F` the unit view direction, `U` and `V` two unit directions across
//! the view (`U`, `V`, `F` orthonormal). A point `P` has view depth `z = (P − E)·F` and view
//! coordinates `u = (P − E)·U / z`, `v = (P − E)·V / z`: the tangents of its angles off the view
//! axis, so every ray from the eye is one `(u, v)` and `P = E + z (F + u U + v V)`.
//!
//! Two facts make the cutters simple in these coordinates. A plane through the eye is a straight
//! line in `(u, v)`, so a bounded plane whose corners lie on two rays is planar whatever depths
//! they sit at, and the faces joining two such planes run along rays: seen from the eye they are
//! edge-on and hide nothing. And on a flat triangle `1/z` is affine in `(u, v)`, so depths
//! interpolate exactly across a triangle's image.
//!
//! `U` is the long axis of the focus's image (the cutter's planes are stacked along it), `V` runs
//! along each plane's front edge. The grid covers the focus's image plus the margin with square
//! cells of side `cell` (in `(u, v)`); cell `(i, j)` (column `i` along `U`, row `j` along `V`)
//! is sampled by the ray through its centre.

use glam::DVec3;

/// The eye, the view axes and the grid of sampled rays.
#[derive(Clone, Debug)]
pub struct ViewFrame {
    pub eye: DVec3,
    /// Unit view direction `F`.
    pub forward: DVec3,
    /// Unit `U`: the long axis of the focus's image; the planes are stacked along it.
    pub along: DVec3,
    /// Unit `V`: across the image; each plane's front edge runs along it.
    pub across: DVec3,
    /// `(u, v)` of the corner of cell `(0, 0)` with the smallest coordinates.
    pub origin: [f64; 2],
    /// Side of a cell in `(u, v)`; positive.
    pub cell: f64,
    /// Columns (along `U`) and rows (along `V`); each at least 1.
    pub columns: usize,
    pub rows: usize,
}

impl ViewFrame {
    /// Number of cells.
    pub fn cells(&self) -> usize {
        self.columns * self.rows
    }

    /// Index of cell `(column, row)`: cells of one column are consecutive.
    pub fn index(&self, column: usize, row: usize) -> usize {
        column * self.rows + row
    }

    /// `(u, v)` of the centre of cell `(column, row)`.
    pub fn centre(&self, column: usize, row: usize) -> [f64; 2] {
        [
            self.origin[0] + (column as f64 + 0.5) * self.cell,
            self.origin[1] + (row as f64 + 0.5) * self.cell,
        ]
    }

    /// `u` of the boundary before column `column` (`columns` gives the far boundary).
    pub fn column_edge(&self, column: usize) -> f64 {
        self.origin[0] + column as f64 * self.cell
    }

    /// `v` of the boundary below row `row`.
    pub fn row_edge(&self, row: usize) -> f64 {
        self.origin[1] + row as f64 * self.cell
    }

    /// `(u, v, z)` of a world point (`z` may be zero or negative behind the eye; `u`, `v` are
    /// then meaningless).
    pub fn project(&self, p: DVec3) -> [f64; 3] {
        let q = p - self.eye;
        let z = q.dot(self.forward);
        [q.dot(self.along) / z, q.dot(self.across) / z, z]
    }

    /// The world point at view coordinates `(u, v)` and depth `z`.
    pub fn point(&self, u: f64, v: f64, z: f64) -> DVec3 {
        self.eye + (self.forward + self.along * u + self.across * v) * z
    }

    /// The axes for an eye looking along `forward` with `right` and `up` across the view, turned
    /// about the view axis so that `along` follows the long axis of `image` (view coordinates
    /// `(s, t)` of points, in the `right`, `up` frame). The grid is not set (see
    /// [`ViewFrame::with_grid`]).
    pub fn oriented(
        eye: DVec3,
        forward: DVec3,
        right: DVec3,
        up: DVec3,
        image: &[[f64; 2]],
    ) -> ViewFrame {
        let angle = principal_angle(image);
        let (sin, cos) = angle.sin_cos();
        ViewFrame {
            eye,
            forward,
            along: right * cos + up * sin,
            across: up * cos - right * sin,
            origin: [0.0, 0.0],
            cell: 1.0,
            columns: 1,
            rows: 1,
        }
    }

    /// This frame with a grid covering `[u0, u1] × [v0, v1]` by square cells, `resolution` of
    /// them along the longer side.
    pub fn with_grid(mut self, u: [f64; 2], v: [f64; 2], resolution: usize) -> ViewFrame {
        let resolution = resolution.max(1);
        let longer = (u[1] - u[0]).max(v[1] - v[0]).max(f64::MIN_POSITIVE);
        self.cell = longer / resolution as f64;
        self.columns = (((u[1] - u[0]) / self.cell).ceil() as usize).clamp(1, resolution);
        self.rows = (((v[1] - v[0]) / self.cell).ceil() as usize).clamp(1, resolution);
        // Centred on the box, so the extra part of the last cell is shared by both sides.
        let centre = [(u[0] + u[1]) * 0.5, (v[0] + v[1]) * 0.5];
        self.origin = [
            centre[0] - self.columns as f64 * self.cell * 0.5,
            centre[1] - self.rows as f64 * self.cell * 0.5,
        ];
        self
    }
}

/// Angle (radians, from the first axis) of the long axis of a point set: the principal axis of
/// its covariance; 0 for fewer than two points or a round set.
fn principal_angle(points: &[[f64; 2]]) -> f64 {
    if points.len() < 2 {
        return 0.0;
    }
    let n = points.len() as f64;
    let mean = points
        .iter()
        .fold([0.0, 0.0], |m, p| [m[0] + p[0] / n, m[1] + p[1] / n]);
    let (mut xx, mut yy, mut xy) = (0.0, 0.0, 0.0);
    for p in points {
        let (dx, dy) = (p[0] - mean[0], p[1] - mean[1]);
        xx += dx * dx;
        yy += dy * dy;
        xy += dx * dy;
    }
    if xx + yy <= 0.0 {
        return 0.0;
    }
    0.5 * (2.0 * xy).atan2(xx - yy)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn project_and_point_are_inverse() {
        let frame = ViewFrame::oriented(
            DVec3::new(0.0, -100.0, 0.0),
            DVec3::Y,
            DVec3::X,
            DVec3::Z,
            &[[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]],
        );
        let p = DVec3::new(3.0, 20.0, -7.0);
        let [u, v, z] = frame.project(p);
        assert!((frame.point(u, v, z) - p).length() < 1e-12);
        // The long axis of points on the diagonal is the diagonal.
        assert!((frame.along - (DVec3::X + DVec3::Z).normalize()).length() < 1e-12);
        assert!(frame.along.dot(frame.across).abs() < 1e-15);
    }

    #[test]
    fn the_grid_covers_the_box_with_square_cells() {
        let frame = ViewFrame::oriented(DVec3::ZERO, DVec3::Y, DVec3::X, DVec3::Z, &[]).with_grid(
            [-2.0, 2.0],
            [-0.5, 0.5],
            100,
        );
        assert_eq!((frame.columns, frame.rows), (100, 25));
        assert!((frame.cell - 0.04).abs() < 1e-15);
        assert!(frame.column_edge(0) <= -2.0 && frame.column_edge(100) >= 2.0);
        assert!(frame.row_edge(0) <= -0.5 && frame.row_edge(25) >= 0.5);
    }
}
