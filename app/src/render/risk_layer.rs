//! The risk map on the GPU: the pipelines that draw walls coloured by their distance to the
//! critical structures (`shaders/risk.wgsl`, and `risk_image.wgsl` where the walls show the
//! intensity image), created the first time a map is drawn, so scenes without one pay nothing.
//! The refined walls themselves are uploaded with the frame's other geometry
//! (`renderer/draw_list.rs`); the distances come computed ([`crate::cutting::wall_risk`]).

use super::gpu_data::RiskVertex;
use super::pipelines::{COLOR_FORMAT, Pipelines, depth_state};

/// The risk pipelines of one renderer.
#[derive(Default)]
pub struct RiskRenderer {
    plain: Option<wgpu::RenderPipeline>,
    with_image: Option<wgpu::RenderPipeline>,
}

impl RiskRenderer {
    /// Creates the pipeline a frame needs: the plain one, and the one sampling the image when
    /// `image_layout` is given (the image's bind group layout, group 2).
    pub fn prepare(
        &mut self,
        device: &wgpu::Device,
        pipelines: &Pipelines,
        image_layout: Option<&wgpu::BindGroupLayout>,
    ) {
        if self.plain.is_none() {
            self.plain = Some(pipeline(device, pipelines, None));
        }
        if let Some(layout) = image_layout
            && self.with_image.is_none()
        {
            self.with_image = Some(pipeline(device, pipelines, Some(layout)));
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
) -> wgpu::RenderPipeline {
    let with_image = image_layout.is_some();
    let label = if with_image {
        "cutaway risk map over the image"
    } else {
        "cutaway risk map"
    };
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(label),
        source: wgpu::ShaderSource::Wgsl(super::shaders::risk(with_image).into()),
    });
    let mut layouts = vec![Some(&pipelines.frame_layout), Some(&pipelines.draw_layout)];
    layouts.extend(image_layout.map(Some));
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(label),
        bind_group_layouts: &layouts,
        immediate_size: 0,
    });
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(label),
        layout: Some(&pipeline_layout),
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("vs_risk"),
            buffers: &[Some(wgpu::VertexBufferLayout {
                array_stride: size_of::<RiskVertex>() as u64,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: &wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32],
            })],
            compilation_options: Default::default(),
        },
        primitive: wgpu::PrimitiveState {
            topology: wgpu::PrimitiveTopology::TriangleList,
            cull_mode: None,
            ..Default::default()
        },
        depth_stencil: depth_state(true, wgpu::CompareFunction::Less),
        multisample: wgpu::MultisampleState::default(),
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: Some(if with_image {
                "fs_risk_image"
            } else {
                "fs_risk"
            }),
            targets: &[Some(COLOR_FORMAT.into())],
            compilation_options: Default::default(),
        }),
        multiview_mask: None,
        cache: None,
    })
}
