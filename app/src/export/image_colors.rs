//! The intensity image baked into a wall's vertex colours for glTF: the wall is subdivided until
//! its triangles are about a voxel across (bounded by [`MAX_TRIANGLES`] per part), and every
//! vertex gets the colour the renderer shows there ([`ImageLayer::color_at`]).
//!
//! Each triangle is split on its own into an n × n grid of smaller ones (n from its longest
//! edge), so neighbours split differently meet with T-junctions: the vertices lie exactly on the
//! shared edge, so the surface has no gap, only the colours are interpolated a little
//! differently on either side.

use csg::Mesh;
use glam::DVec3;

use crate::scene::ImageLayer;

/// Most triangles one baked part may have; a larger wall gets coarser colours.
pub const MAX_TRIANGLES: usize = 400_000;

/// The subdivided mesh and one sRGB colour (0..=1) per vertex.
pub fn bake(mesh: &Mesh, layer: &ImageLayer, base: [f32; 3]) -> (Mesh, Vec<[f32; 3]>) {
    let target = target_edge(mesh, layer);
    let mut out = Mesh::default();
    for t in 0..mesh.triangles.len() {
        let n = ((longest_edge(mesh, t) / target).ceil() as u32).clamp(1, 256);
        push_grid(&mut out, mesh.corners(t), n, |_, _| {});
    }
    let colors = out
        .positions
        .iter()
        .map(|&p| layer.color_at(p, base))
        .collect();
    (out, colors)
}

/// Appends triangle `corners` split into an n × n grid of smaller ones to `out` (vertices of its
/// own), calling `at(u, v)` for each new vertex in order: the point `a + (b − a) u + (c − a) v`.
pub fn push_grid(out: &mut Mesh, corners: [DVec3; 3], n: u32, mut at: impl FnMut(f64, f64)) {
    let [a, b, c] = corners;
    // Row i has n - i + 1 points: a + (b - a) j / n + (c - a) i / n.
    let mut row_start = Vec::with_capacity(n as usize + 1);
    for i in 0..=n {
        row_start.push(out.positions.len() as u32);
        for j in 0..=(n - i) {
            let (u, v) = (j as f64 / n as f64, i as f64 / n as f64);
            out.positions.push(a + (b - a) * u + (c - a) * v);
            at(u, v);
        }
    }
    for i in 0..n {
        for j in 0..(n - i) {
            let v0 = row_start[i as usize] + j;
            let v1 = v0 + 1;
            let v2 = row_start[i as usize + 1] + j;
            out.triangles.push([v0, v1, v2]);
            if j + 1 < n - i {
                let v3 = v2 + 1;
                out.triangles.push([v1, v3, v2]);
            }
        }
    }
}

/// The edge length a bake aims at for `mesh` under `layer`: about a voxel, longer where that
/// would pass [`MAX_TRIANGLES`].
pub fn target_edge(mesh: &Mesh, layer: &ImageLayer) -> f64 {
    let spacing = layer.image.world_from_voxel.matrix3;
    let voxel = [spacing.x_axis, spacing.y_axis, spacing.z_axis]
        .iter()
        .map(|c| c.length())
        .fold(f64::INFINITY, f64::min)
        .max(1e-6);
    let area_in_voxels: f64 = (0..mesh.triangles.len())
        .map(|t| (longest_edge(mesh, t) / voxel).powi(2))
        .sum();
    voxel * (area_in_voxels / MAX_TRIANGLES as f64).sqrt().max(1.0)
}

/// The longest edge of triangle `t` of `mesh`.
pub fn longest_edge(mesh: &Mesh, t: usize) -> f64 {
    let p = mesh.corners(t);
    (0..3)
        .map(|k| (p[k] - p[(k + 1) % 3]).length())
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::intensity::{IntensityImage, Window};
    use glam::DAffine3;
    use std::sync::Arc;

    #[test]
    fn a_wall_is_split_to_about_a_voxel_and_coloured_by_the_image() {
        let image =
            IntensityImage::from_fn([11, 11, 11], DAffine3::IDENTITY, |p| 100.0 * p.x as f32);
        let mut layer = ImageLayer::new(Arc::new(image));
        layer.window = Window {
            level: 500.0,
            width: 1000.0,
        };
        // One triangle 8 voxels across on the plane y = 5.
        let wall = Mesh {
            positions: vec![
                DVec3::new(1.0, 5.0, 1.0),
                DVec3::new(9.0, 5.0, 1.0),
                DVec3::new(1.0, 5.0, 9.0),
            ],
            triangles: vec![[0, 1, 2]],
        };
        let (mesh, colors) = bake(&wall, &layer, [1.0, 0.0, 0.0]);
        assert_eq!(colors.len(), mesh.positions.len());
        assert!(
            mesh.triangles.len() >= 64,
            "{} triangles",
            mesh.triangles.len()
        );
        let area: f64 = (0..mesh.triangles.len())
            .map(|t| mesh.face_normal_scaled(t).length() / 2.0)
            .sum();
        assert!((area - 32.0).abs() < 1e-9, "area {area}");
        for (p, c) in mesh.positions.iter().zip(&colors) {
            let expected = (p.x / 10.0) as f32;
            assert!(
                (c[0] - expected).abs() < 1e-4 && (c[1] - expected).abs() < 1e-4,
                "{p}: {c:?}"
            );
        }
    }
}
