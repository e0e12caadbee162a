//! What the shaders read besides vertices: the per-eye frame uniform (camera, depth range fitted
//! to the scene, light, viewport; a tile of a large image shifts and scales the projection) and
//! the buffer of per-draw uniforms. Pure functions of the frame, apart from the buffers.

use glam::{DMat4, DVec2, DVec4};

use crate::render::gpu_data::{DRAW_UNIFORM_STRIDE, DrawUniform, FrameUniform};
use crate::render::pipelines::Pipelines;
use crate::render::{FrameInputs, ViewMode};

/// Eye separation of the anaglyph as a fraction of the camera distance.
const EYE_SEPARATION: f64 = 0.035;

pub(super) fn uniform_bind_group(
    device: &wgpu::Device,
    label: &str,
    layout: &wgpu::BindGroupLayout,
    buffer: &wgpu::Buffer,
    size: u64,
) -> wgpu::BindGroup {
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(label),
        layout,
        entries: &[wgpu::BindGroupEntry {
            binding: 0,
            resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                buffer,
                offset: 0,
                size: wgpu::BufferSize::new(size),
            }),
        }],
    })
}

pub(super) fn draw_buffer(
    device: &wgpu::Device,
    pipelines: &Pipelines,
    capacity: u64,
) -> (wgpu::Buffer, wgpu::BindGroup) {
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("cutaway draw uniforms"),
        size: capacity * DRAW_UNIFORM_STRIDE,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let bind_group = uniform_bind_group(
        device,
        "cutaway draw bind group",
        &pipelines.draw_layout,
        &buffer,
        size_of::<DrawUniform>() as u64,
    );
    (buffer, bind_group)
}

/// The full image size (the tile's image, or the frame itself).
pub(super) fn full_size(frame: &FrameInputs) -> [u32; 2] {
    frame.tile.map_or(frame.size, |t| t.full_size)
}

/// Near and far distances that enclose everything drawn, and the scene radius. Inside the
/// scene the near plane is a ten-thousandth of the far one, but never more than a quarter of the
/// way to the point the camera orbits: zoomed onto a small structure of a large scene (the
/// closest zoom follows the selected model's size) the structure stays in front of the near
/// plane.
pub(super) fn depth_range(frame: &FrameInputs, scene_bbox: csg::Aabb) -> (f64, f64, f64) {
    let mut bbox = scene_bbox;
    if frame.mode == ViewMode::Edit {
        for o in &frame.overlays {
            for p in o.planes.iter().flatten() {
                bbox.grow(*p);
            }
        }
    }
    if bbox.is_empty() {
        return (0.1, 1000.0, 1.0);
    }
    near_far(&bbox, &frame.camera)
}

/// [`depth_range`] of a non-empty box seen by `camera`.
fn near_far(bbox: &csg::Aabb, camera: &cutter::Camera) -> (f64, f64, f64) {
    let radius = (0.5 * bbox.diagonal()).max(1e-6);
    // The anaglyph eyes sit a little off the camera.
    let distance = (bbox.center() - camera.eye).length() + EYE_SEPARATION * camera.distance();
    let far = distance + radius * 1.05;
    let closest = (far * 1e-4).min(0.25 * camera.distance()).max(far * 1e-7);
    let near = (distance - radius * 1.05).max(closest);
    (near, far, radius)
}

/// The camera of each eye: the scene camera, or two toed-in cameras for the anaglyph.
pub(super) fn eye_cameras(frame: &FrameInputs) -> Vec<cutter::Camera> {
    let camera = frame.camera;
    if !frame.look.anaglyph {
        return vec![camera];
    }
    let (right, _, _) = camera.basis();
    let half = right * (0.5 * EYE_SEPARATION * camera.distance());
    vec![
        cutter::Camera {
            eye: camera.eye - half,
            ..camera
        },
        cutter::Camera {
            eye: camera.eye + half,
            ..camera
        },
    ]
}

pub(super) fn frame_uniform(
    frame: &FrameInputs,
    camera: &cutter::Camera,
    size: [u32; 2],
    near: f64,
    far: f64,
) -> FrameUniform {
    let full = full_size(frame);
    let viewport = DVec2::new(full[0] as f64, full[1] as f64);
    let mut clip_from_world = camera.clip_from_world(viewport, near, far);
    if let Some(tile) = frame.tile {
        // Scale and shift NDC so the tile's rectangle fills the target.
        let (w, h) = (frame.size[0] as f64, frame.size[1] as f64);
        let sx = viewport.x / w;
        let sy = viewport.y / h;
        let cx = (tile.origin[0] as f64 + 0.5 * w) / viewport.x * 2.0 - 1.0;
        let cy = 1.0 - (tile.origin[1] as f64 + 0.5 * h) / viewport.y * 2.0;
        let tile_from_full = DMat4::from_cols(
            DVec4::new(sx, 0.0, 0.0, 0.0),
            DVec4::new(0.0, sy, 0.0, 0.0),
            DVec4::new(0.0, 0.0, 1.0, 0.0),
            DVec4::new(-cx * sx, -cy * sy, 0.0, 1.0),
        );
        clip_from_world = tile_from_full * clip_from_world;
    }
    let (right, up, forward) = camera.basis();
    let light = (-forward + up * 0.5 - right * 0.25).normalize();
    FrameUniform {
        clip_from_world: clip_from_world.as_mat4().to_cols_array_2d(),
        eye_in_world: camera.eye.as_vec3().extend(1.0).to_array(),
        light_in_world: light.as_vec3().extend(0.0).to_array(),
        viewport: [size[0] as f32, size[1] as f32, near as f32, far as f32],
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    /// A body 1.8 m tall in metres, the camera zoomed to 0.1 mm from a point inside it (a small
    /// structure's closest zoom): the near plane is in front of that point. Seen from outside,
    /// the range is the scene's as before.
    #[test]
    fn the_near_plane_stays_in_front_of_a_close_zoom() {
        let body = csg::Aabb {
            min: DVec3::new(-0.25, 0.0, -0.15),
            max: DVec3::new(0.25, 1.8, 0.15),
        };
        let target = DVec3::new(0.06, 1.01, 0.01);
        let close = cutter::Camera {
            eye: target - DVec3::Z * 1e-4,
            target,
            up: DVec3::Y,
            fov_y_deg: 30.0,
        };
        let (near, far, _) = near_far(&body, &close);
        assert!(near < 1e-4 && near > 0.0, "near {near}");
        assert!(far > 1.0);
        let whole = cutter::Camera::framing(&body, DVec3::Z, DVec3::Y, 30.0);
        let (near, far, radius) = near_far(&body, &whole);
        let distance = (body.center() - whole.eye).length() + EYE_SEPARATION * whole.distance();
        assert!((near - (distance - 1.05 * radius)).abs() < 1e-12);
        assert!((far - (distance + 1.05 * radius)).abs() < 1e-12);
    }
}
