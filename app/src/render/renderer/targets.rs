//! The offscreen images one output size needs, made once per size (and eye count) and reused by
//! every frame and every view until the size changes: the colour image of each eye and one depth
//! buffer, with the bind group that reads them. Kept apart from the passes because their
//! lifetime is the window's size, not a frame's.
//!
//! The two weighted-blended transparency targets are made only while frames draw something
//! transparent ([`Targets::transparency`]): at the supersampled size they hold as much as the
//! colour image and half again (on a software adapter, host memory), and most frames (Edit mode,
//! a cut without a transparent removed piece, every image of `cutaway render` without one) draw
//! nothing transparent.

use super::Renderer;
use crate::render::pipelines::{ACCUM_FORMAT, COLOR_FORMAT, DEPTH_FORMAT, REVEALAGE_FORMAT};

/// Offscreen images for one output size.
pub(super) struct Targets {
    /// Size of the offscreen images (the output size times the supersampling factor).
    pub(super) size: [u32; 2],
    /// One per eye.
    pub(super) color_views: Vec<wgpu::TextureView>,
    pub(super) depth_view: wgpu::TextureView,
    /// Present while frames draw transparent meshes (see the module documentation).
    pub(super) transparency: Option<TransparencyTargets>,
    pub(super) blit_bind_group: wgpu::BindGroup,
}

/// The weighted-blended transparency targets of one output size, and the bind group with which
/// the composite reads them.
pub(super) struct TransparencyTargets {
    pub(super) accum_view: wgpu::TextureView,
    pub(super) revealage_view: wgpu::TextureView,
    pub(super) composite_bind_group: wgpu::BindGroup,
}

/// An image of `size` that passes render into (and, `sampled`, later passes read).
fn target(
    device: &wgpu::Device,
    size: [u32; 2],
    label: &str,
    format: wgpu::TextureFormat,
    sampled: bool,
) -> wgpu::TextureView {
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
}

impl Renderer {
    pub(super) fn create_targets(
        &self,
        device: &wgpu::Device,
        size: [u32; 2],
        eyes: usize,
    ) -> Targets {
        let texture =
            |label: &str, format, sampled: bool| target(device, size, label, format, sampled);
        let color_views: Vec<wgpu::TextureView> = (0..eyes)
            .map(|eye| texture(&format!("cutaway colour (eye {eye})"), COLOR_FORMAT, true))
            .collect();
        let depth_view = texture("cutaway depth", DEPTH_FORMAT, false);
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
            transparency: None,
            blit_bind_group,
        }
    }

    /// Makes the transparency targets of `targets` when `wanted` and missing, drops them when not
    /// `wanted` (see the module documentation).
    pub(super) fn keep_transparency_targets(
        &self,
        device: &wgpu::Device,
        targets: &mut Targets,
        wanted: bool,
    ) {
        if !wanted {
            targets.transparency = None;
            return;
        }
        if targets.transparency.is_some() {
            return;
        }
        let size = targets.size;
        let accum_view = target(
            device,
            size,
            "cutaway transparency accumulation",
            ACCUM_FORMAT,
            true,
        );
        let revealage_view = target(
            device,
            size,
            "cutaway transparency revealage",
            REVEALAGE_FORMAT,
            true,
        );
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
        targets.transparency = Some(TransparencyTargets {
            accum_view,
            revealage_view,
            composite_bind_group,
        });
    }
}
