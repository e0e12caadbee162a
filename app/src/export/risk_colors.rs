//! The risk map baked into a wall's vertex colours for glTF, as [`super::image_colors`] bakes
//! the image: every triangle of the refined wall ([`crate::cutting::wall_risk`]) gets vertices
//! of its own, each coloured as the renderer colours that point (the ramp within the far
//! distance; beyond it the wall colour, or the image where the walls show it, split to about a
//! voxel then).
//!
//! A viewer interpolates vertex colours, not distances, so the near and far lines are as sharp
//! as the refinement (a quarter millimetre where they run); the corner distances are lower
//! bounds, so a point within the near distance shows red or a red-orange mix, never a safer
//! colour.

use csg::Mesh;
use glam::DVec3;

use super::image_colors::{longest_edge, push_grid, target_edge};
use crate::cutting::wall_risk::RiskWall;
use crate::scene::ImageLayer;
use crate::scene::risk::RiskSettings;

/// A refined wall baked for glTF.
pub struct Baked {
    /// Vertices of its own per triangle (split further where the image shows).
    pub mesh: Mesh,
    /// sRGB (0..=1), one per vertex.
    pub colors: Vec<[f32; 3]>,
    /// The smooth normals of the wall it was refined from, interpolated (not unit length).
    pub normals: Vec<DVec3>,
}

/// Bakes `wall`, refined from `source`; `base` is the wall colour, `layer` the image the walls
/// show (if any).
pub fn bake(
    wall: &RiskWall,
    source: &Mesh,
    settings: &RiskSettings,
    layer: Option<&ImageLayer>,
    base: [f32; 3],
) -> Baked {
    let source_normals = super::gltf::vertex_normals(source);
    let normal_at: Vec<DVec3> = wall
        .origin
        .iter()
        .map(|o| {
            o.interpolate(source, |v| {
                source_normals[v as usize]
                    .try_normalize()
                    .unwrap_or(DVec3::ZERO)
            })
        })
        .collect();
    let target = layer.map(|l| target_edge(&wall.mesh, l));
    let mut out = Mesh::default();
    let mut distances = Vec::new();
    let mut normals = Vec::new();
    for (t, corner) in wall.corner_mm.iter().enumerate() {
        let d = corner.map(f64::from);
        let n = wall.mesh.triangles[t].map(|v| normal_at[v as usize]);
        // Only where the image shows (beyond the far distance) is a triangle split further.
        let beyond = d.iter().all(|&x| x >= settings.far_mm);
        let steps = match target {
            Some(edge) if beyond => {
                ((longest_edge(&wall.mesh, t) / edge).ceil() as u32).clamp(1, 256)
            }
            _ => 1,
        };
        push_grid(&mut out, wall.mesh.corners(t), steps, |u, v| {
            distances.push(d[0] + (d[1] - d[0]) * u + (d[2] - d[0]) * v);
            normals.push(n[0] + (n[1] - n[0]) * u + (n[2] - n[0]) * v);
        });
    }
    let colors = out
        .positions
        .iter()
        .zip(&distances)
        .map(|(&p, &d)| {
            settings.color_at(d).unwrap_or_else(|| match layer {
                Some(l) => l.color_at(p, base),
                None => base,
            })
        })
        .collect();
    Baked {
        mesh: out,
        colors,
        normals,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cutting::wall_risk::VertexOrigin;
    use crate::scene::risk::RISK_NEAR_COLOR;

    #[test]
    fn corners_take_the_ramp_colour_of_their_distance_and_the_wall_colour_beyond() {
        let wall = RiskWall {
            model: 0,
            cutter: 0,
            source: (1, 3),
            mesh: Mesh {
                positions: vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(1.0, 1.0, 0.0)],
                triangles: vec![[0, 1, 2], [1, 3, 2]],
            },
            corner_mm: vec![[1.0, 6.0, 30.0], [12.0, 14.0, 20.0]],
            origin: [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]]
                .into_iter()
                .map(|bary| VertexOrigin { triangle: 0, bary })
                .collect(),
        };
        let source = Mesh {
            positions: vec![DVec3::ZERO, DVec3::X, DVec3::Y],
            triangles: vec![[0, 1, 2]],
        };
        let settings = RiskSettings::default();
        let base = [0.9, 0.85, 0.7];
        let baked = bake(&wall, &source, &settings, None, base);
        let (mesh, colors) = (&baked.mesh, &baked.colors);
        assert!(
            baked
                .normals
                .iter()
                .all(|n| n.normalize().distance(DVec3::Z) < 1e-12)
        );
        assert_eq!(mesh.triangle_count(), 2);
        assert_eq!(
            mesh.positions.len(),
            6,
            "vertices of their own per triangle"
        );
        assert_eq!(colors[0], RISK_NEAR_COLOR);
        assert_eq!(Some(colors[1]), settings.color_at(6.0));
        assert_eq!(colors[2], base);
        assert!(colors[3..].iter().all(|&c| c == base));
    }
}
