//! The risk map on the GPU: the pipelines that draw walls coloured by their distance to the
//! critical structures (`shaders/risk.wgsl`, and `risk_image.wgsl` where the walls show the
//! intensity image), created the first time a map is drawn, so scenes without one pay nothing.
//! The refined walls themselves are uploaded with the frame's other geometry
//! (`renderer/draw_list.rs`); the distances and the ramp's colours come with the map
//! ([`crate::cutting::wall_risk`]).

use super::gpu_data::RiskVertex;
use super::pipelines::{LayerShader, Pipelines, layer_pipeline};
use crate::cutting::wall_risk::RiskRamp;

/// The risk pipelines of one renderer.
#[derive(Default)]
pub struct RiskRenderer {
    /// The colours the pipelines were made with.
    ramp: Option<RiskRamp>,
    plain: Option<wgpu::RenderPipeline>,
    with_image: Option<wgpu::RenderPipeline>,
}

impl RiskRenderer {
    /// Creates the pipeline a frame needs, drawing with `ramp`'s colours: the plain one, and the
    /// one sampling the image when `image_layout` is given (the image's bind group layout,
    /// group 2). Pipelines made with other colours are made again.
    pub fn prepare(
        &mut self,
        device: &wgpu::Device,
        pipelines: &Pipelines,
        image_layout: Option<&wgpu::BindGroupLayout>,
        ramp: &RiskRamp,
    ) {
        if self.ramp.as_ref() != Some(ramp) {
            *self = RiskRenderer {
                ramp: Some(*ramp),
                ..Default::default()
            };
        }
        if self.plain.is_none() {
            self.plain = Some(pipeline(device, pipelines, None, ramp));
        }
        if let Some(layout) = image_layout
            && self.with_image.is_none()
        {
            self.with_image = Some(pipeline(device, pipelines, Some(layout), ramp));
        }
    }

    /// Sets the risk pipeline on `pass`: with the image when `image` (its bind group) is given
    /// and that pipeline exists, else the plain one. False before [`RiskRenderer::prepare`].
    pub fn bind(&self, pass: &mut wgpu::RenderPass<'_>, image: Option<&wgpu::BindGroup>) -> bool {
        if let (Some(group), Some(pipeline)) = (image, &self.with_image) {
            pass.set_pipeline(pipeline);
            pass.set_bind_group(2, group, &[]);
            return true;
        }
        match &self.plain {
            Some(pipeline) => {
                pass.set_pipeline(pipeline);
                true
            }
            None => false,
        }
    }
}

fn pipeline(
    device: &wgpu::Device,
    pipelines: &Pipelines,
    image_layout: Option<&wgpu::BindGroupLayout>,
    ramp: &RiskRamp,
) -> wgpu::RenderPipeline {
    let with_image = image_layout.is_some();
    let label = if with_image {
        "cutaway risk map over the image"
    } else {
        "cutaway risk map"
    };
    layer_pipeline(
        device,
        pipelines,
        LayerShader {
            label,
            source: super::shaders::risk(with_image, ramp),
            extra_layout: image_layout,
            vertex_stride: size_of::<RiskVertex>() as u64,
            vertex_entry: "vs_risk",
            fragment_entry: if with_image {
                "fs_risk_image"
            } else {
                "fs_risk"
            },
        },
    )
}
