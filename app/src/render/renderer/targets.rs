//! The offscreen images one output size needs, made once per size (and eye count) and reused by
//! every frame and every view until the size changes: the colour image of each eye, one depth
//! buffer, and the two weighted-blended transparency targets, with the bind groups that read
//! them. Kept apart from the passes because their lifetime is the window's size, not a frame's.

use super::Renderer;
use crate::render::pipelines::{ACCUM_FORMAT, COLOR_FORMAT, DEPTH_FORMAT, REVEALAGE_FORMAT};

/// Offscreen images for one output size.
pub(super) struct Targets {
    /// Size of the offscreen images (the output size times the supersampling factor).
    pub(super) size: [u32; 2],
    /// One per eye.
    pub(super) color_views: Vec<wgpu::TextureView>,
    pub(super) depth_view: wgpu::TextureView,
    pub(super) accum_view: wgpu::TextureView,
    pub(super) revealage_view: wgpu::TextureView,
    pub(super) composite_bind_group: wgpu::BindGroup,
    pub(super) blit_bind_group: wgpu::BindGroup,
}

impl Renderer {
    pub(super) fn create_targets(
        &self,
        device: &wgpu::Device,
        size: [u32; 2],
        eyes: usize,
    ) -> Targets {
        let texture = |label: &str, format: wgpu::TextureFormat, sampled: bool| {
            let mut usage = wgpu::TextureUsages::RENDER_ATTACHMENT;
            if sampled {
                usage |= wgpu::TextureUsages::TEXTURE_BINDING;
            }
            device
                .create_texture(&wgpu::TextureDescriptor {
                    label: Some(label),
                    size: wgpu::Extent3d {
                        width: size[0],
                        height: size[1],
                        depth_or_array_layers: 1,
                    },
                    mip_level_count: 1,
                    sample_count: 1,
                    dimension: wgpu::TextureDimension::D2,
                    format,
                    usage,
                    view_formats: &[],
                })
                .create_view(&wgpu::TextureViewDescriptor::default())
        };
        let color_views: Vec<wgpu::TextureView> = (0..eyes)
            .map(|eye| texture(&format!("cutaway colour (eye {eye})"), COLOR_FORMAT, true))
            .collect();
        let depth_view = texture("cutaway depth", DEPTH_FORMAT, false);
        let accum_view = texture("cutaway transparency accumulation", ACCUM_FORMAT, true);
        let revealage_view = texture("cutaway transparency revealage", REVEALAGE_FORMAT, true);
        let composite_bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("cutaway composite bind group"),
            layout: &self.pipelines.composite_layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(&accum_view),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(&revealage_view),
                },
            ],
        });
        let right = color_views.last().unwrap_or(&color_views[0]);
        let blit_bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("cutaway blit bind group"),
            layout: &self.pipelines.blit_layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(&color_views[0]),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(right),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: wgpu::BindingResource::Sampler(&self.pipelines.sampler),
                },
                wgpu::BindGroupEntry {
                    binding: 3,
                    resource: self.blit_buffer.as_entire_binding(),
                },
            ],
        });
        Targets {
            size,
            color_views,
            depth_view,
            accum_view,
            revealage_view,
            composite_bind_group,
            blit_bind_group,
        }
    }
}
