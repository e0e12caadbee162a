//! The long-lived GPU state: bind group layouts, pipelines and the sampler, created once per
//! [`super::Renderer`].

use super::OutputTarget;
use super::gpu_data::{DrawUniform, FrameUniform, Segment, Vertex};
use super::shaders;

/// Linear-light, premultiplied colour of the offscreen images.
pub const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
/// Weighted sums of the transparent layers.
pub const ACCUM_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
/// Product of (1 - opacity) of the transparent layers.
pub const REVEALAGE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R16Float;

pub struct Pipelines {
    pub frame_layout: wgpu::BindGroupLayout,
    pub draw_layout: wgpu::BindGroupLayout,
    pub composite_layout: wgpu::BindGroupLayout,
    pub blit_layout: wgpu::BindGroupLayout,
    pub mesh_opaque: wgpu::RenderPipeline,
    pub mesh_oit: wgpu::RenderPipeline,
    pub lines_opaque: wgpu::RenderPipeline,
    pub lines_overlay: wgpu::RenderPipeline,
    pub composite: wgpu::RenderPipeline,
    pub blit: wgpu::RenderPipeline,
    pub sampler: wgpu::Sampler,
    /// Scattered word writes into a storage buffer (`scatter.wgsl`): hides and shows faces of an
    /// uploaded index buffer.
    pub scatter_layout: wgpu::BindGroupLayout,
    pub scatter: wgpu::ComputePipeline,
}

/// Workgroup size of `scatter.wgsl` and the invocations per row of its dispatch grid.
pub const SCATTER_GROUP: u32 = 64;
pub const SCATTER_ROW_GROUPS: u32 = 65535;

const PREMULTIPLIED_OVER: wgpu::BlendState = wgpu::BlendState {
    color: wgpu::BlendComponent {
        src_factor: wgpu::BlendFactor::One,
        dst_factor: wgpu::BlendFactor::OneMinusSrcAlpha,
        operation: wgpu::BlendOperation::Add,
    },
    alpha: wgpu::BlendComponent {
        src_factor: wgpu::BlendFactor::One,
        dst_factor: wgpu::BlendFactor::OneMinusSrcAlpha,
        operation: wgpu::BlendOperation::Add,
    },
};

fn uniform_entry(binding: u32, size: u64, dynamic: bool) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: dynamic,
            min_binding_size: wgpu::BufferSize::new(size),
        },
        count: None,
    }
}

fn texture_entry(binding: u32, filterable: bool) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Float { filterable },
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        },
        count: None,
    }
}

/// What a layer's own pipeline draws with (the image layer, the risk map): its WGSL source, the
/// bind group layout after the frame's and the draw's (if any), the vertex stride (a position,
/// a normal and one scalar per vertex) and the entry points.
pub(super) struct LayerShader<'a> {
    pub label: &'a str,
    pub source: String,
    pub extra_layout: Option<&'a wgpu::BindGroupLayout>,
    pub vertex_stride: u64,
    pub vertex_entry: &'a str,
    pub fragment_entry: &'a str,
}

/// An opaque, depth-tested pipeline of two-sided triangles for a layer drawn over the scene's
/// meshes, as the mesh pipeline draws them but in the layer's own shader.
pub(super) fn layer_pipeline(
    device: &wgpu::Device,
    pipelines: &Pipelines,
    shader: LayerShader,
) -> wgpu::RenderPipeline {
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(shader.label),
        source: wgpu::ShaderSource::Wgsl(shader.source.into()),
    });
    let mut layouts = vec![Some(&pipelines.frame_layout), Some(&pipelines.draw_layout)];
    layouts.extend(shader.extra_layout.map(Some));
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(shader.label),
        bind_group_layouts: &layouts,
        immediate_size: 0,
    });
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(shader.label),
        layout: Some(&pipeline_layout),
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some(shader.vertex_entry),
            buffers: &[Some(wgpu::VertexBufferLayout {
                array_stride: shader.vertex_stride,
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
            entry_point: Some(shader.fragment_entry),
            targets: &[Some(COLOR_FORMAT.into())],
            compilation_options: Default::default(),
        }),
        multiview_mask: None,
        cache: None,
    })
}

pub(super) fn depth_state(
    write: bool,
    compare: wgpu::CompareFunction,
) -> Option<wgpu::DepthStencilState> {
    Some(wgpu::DepthStencilState {
        format: DEPTH_FORMAT,
        depth_write_enabled: Some(write),
        depth_compare: Some(compare),
        stencil: wgpu::StencilState::default(),
        bias: wgpu::DepthBiasState::default(),
    })
}

impl Pipelines {
    pub fn new(device: &wgpu::Device, output: OutputTarget) -> Pipelines {
        let frame_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("cutaway frame uniform layout"),
            entries: &[uniform_entry(0, size_of::<FrameUniform>() as u64, true)],
        });
        let draw_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("cutaway draw uniform layout"),
            entries: &[uniform_entry(0, size_of::<DrawUniform>() as u64, true)],
        });
        let composite_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("cutaway composite layout"),
            entries: &[texture_entry(0, false), texture_entry(1, false)],
        });
        let blit_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("cutaway blit layout"),
            entries: &[
                texture_entry(0, true),
                texture_entry(1, true),
                wgpu::BindGroupLayoutEntry {
                    binding: 2,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                    count: None,
                },
                uniform_entry(3, size_of::<super::gpu_data::BlitUniform>() as u64, false),
            ],
        });

        let scene_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("cutaway scene pipeline layout"),
            bind_group_layouts: &[Some(&frame_layout), Some(&draw_layout)],
            immediate_size: 0,
        });
        let composite_pipeline_layout =
            device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some("cutaway composite pipeline layout"),
                bind_group_layouts: &[Some(&composite_layout)],
                immediate_size: 0,
            });
        let blit_pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("cutaway blit pipeline layout"),
            bind_group_layouts: &[Some(&blit_layout)],
            immediate_size: 0,
        });

        let module = |label: &str, source: &str| {
            device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(label),
                source: wgpu::ShaderSource::Wgsl(source.into()),
            })
        };
        let mesh_module = module("cutaway mesh.wgsl", shaders::MESH);
        let lines_module = module("cutaway lines.wgsl", shaders::LINES);
        let composite_module = module("cutaway composite.wgsl", shaders::COMPOSITE);
        let blit_module = module("cutaway blit.wgsl", shaders::BLIT);

        let vertex_layout = wgpu::VertexBufferLayout {
            array_stride: size_of::<Vertex>() as u64,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: &wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32],
        };
        let segment_layout = wgpu::VertexBufferLayout {
            array_stride: size_of::<Segment>() as u64,
            step_mode: wgpu::VertexStepMode::Instance,
            attributes: &wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3],
        };
        let triangles = wgpu::PrimitiveState {
            topology: wgpu::PrimitiveTopology::TriangleList,
            cull_mode: None,
            ..Default::default()
        };

        let mesh_pipeline = |label: &str,
                             entry: &str,
                             targets: &[Option<wgpu::ColorTargetState>],
                             depth: Option<wgpu::DepthStencilState>| {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(label),
                layout: Some(&scene_layout),
                vertex: wgpu::VertexState {
                    module: &mesh_module,
                    entry_point: Some("vs_main"),
                    buffers: &[Some(vertex_layout.clone())],
                    compilation_options: Default::default(),
                },
                primitive: triangles,
                depth_stencil: depth,
                multisample: wgpu::MultisampleState::default(),
                fragment: Some(wgpu::FragmentState {
                    module: &mesh_module,
                    entry_point: Some(entry),
                    targets,
                    compilation_options: Default::default(),
                }),
                multiview_mask: None,
                cache: None,
            })
        };
        let mesh_opaque = mesh_pipeline(
            "cutaway mesh opaque",
            "fs_opaque",
            &[Some(COLOR_FORMAT.into())],
            depth_state(true, wgpu::CompareFunction::Less),
        );
        let additive = wgpu::BlendComponent {
            src_factor: wgpu::BlendFactor::One,
            dst_factor: wgpu::BlendFactor::One,
            operation: wgpu::BlendOperation::Add,
        };
        let multiply_by_one_minus_src = wgpu::BlendComponent {
            src_factor: wgpu::BlendFactor::Zero,
            dst_factor: wgpu::BlendFactor::OneMinusSrc,
            operation: wgpu::BlendOperation::Add,
        };
        let mesh_oit = mesh_pipeline(
            "cutaway mesh transparent (weighted blended)",
            "fs_oit",
            &[
                Some(wgpu::ColorTargetState {
                    format: ACCUM_FORMAT,
                    blend: Some(wgpu::BlendState {
                        color: additive,
                        alpha: additive,
                    }),
                    write_mask: wgpu::ColorWrites::ALL,
                }),
                Some(wgpu::ColorTargetState {
                    format: REVEALAGE_FORMAT,
                    blend: Some(wgpu::BlendState {
                        color: multiply_by_one_minus_src,
                        alpha: multiply_by_one_minus_src,
                    }),
                    write_mask: wgpu::ColorWrites::ALL,
                }),
            ],
            depth_state(false, wgpu::CompareFunction::Less),
        );

        let lines_pipeline = |label: &str,
                              blend: Option<wgpu::BlendState>,
                              depth: Option<wgpu::DepthStencilState>| {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(label),
                layout: Some(&scene_layout),
                vertex: wgpu::VertexState {
                    module: &lines_module,
                    entry_point: Some("vs_main"),
                    buffers: &[Some(segment_layout.clone())],
                    compilation_options: Default::default(),
                },
                primitive: triangles,
                depth_stencil: depth,
                multisample: wgpu::MultisampleState::default(),
                fragment: Some(wgpu::FragmentState {
                    module: &lines_module,
                    entry_point: Some("fs_main"),
                    targets: &[Some(wgpu::ColorTargetState {
                        format: COLOR_FORMAT,
                        blend,
                        write_mask: wgpu::ColorWrites::ALL,
                    })],
                    compilation_options: Default::default(),
                }),
                multiview_mask: None,
                cache: None,
            })
        };
        let lines_opaque = lines_pipeline(
            "cutaway lines opaque",
            None,
            depth_state(true, wgpu::CompareFunction::LessEqual),
        );
        let lines_overlay = lines_pipeline(
            "cutaway lines overlay",
            Some(PREMULTIPLIED_OVER),
            depth_state(false, wgpu::CompareFunction::Always),
        );

        let fullscreen = |label: &str,
                          layout: &wgpu::PipelineLayout,
                          module: &wgpu::ShaderModule,
                          target: wgpu::ColorTargetState,
                          depth: Option<wgpu::DepthStencilState>,
                          samples: u32| {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(label),
                layout: Some(layout),
                vertex: wgpu::VertexState {
                    module,
                    entry_point: Some("vs_main"),
                    buffers: &[],
                    compilation_options: Default::default(),
                },
                primitive: triangles,
                depth_stencil: depth,
                multisample: wgpu::MultisampleState {
                    count: samples,
                    ..Default::default()
                },
                fragment: Some(wgpu::FragmentState {
                    module,
                    entry_point: Some("fs_main"),
                    targets: &[Some(target)],
                    compilation_options: Default::default(),
                }),
                multiview_mask: None,
                cache: None,
            })
        };
        let composite = fullscreen(
            "cutaway transparency composite",
            &composite_pipeline_layout,
            &composite_module,
            wgpu::ColorTargetState {
                format: COLOR_FORMAT,
                blend: Some(PREMULTIPLIED_OVER),
                write_mask: wgpu::ColorWrites::ALL,
            },
            depth_state(false, wgpu::CompareFunction::Always),
            1,
        );
        let blit = fullscreen(
            "cutaway blit",
            &blit_pipeline_layout,
            &blit_module,
            wgpu::ColorTargetState {
                format: output.format,
                // Straight-alpha output replaces; premultiplied output composites over egui.
                blend: if output.straight_alpha {
                    None
                } else {
                    Some(PREMULTIPLIED_OVER)
                },
                write_mask: wgpu::ColorWrites::ALL,
            },
            output.depth_format.map(|format| wgpu::DepthStencilState {
                format,
                depth_write_enabled: Some(false),
                depth_compare: Some(wgpu::CompareFunction::Always),
                stencil: wgpu::StencilState::default(),
                bias: wgpu::DepthBiasState::default(),
            }),
            output.sample_count.max(1),
        );
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("cutaway blit sampler (bilinear: resolves 2x2 supersampling)"),
            address_mode_u: wgpu::AddressMode::ClampToEdge,
            address_mode_v: wgpu::AddressMode::ClampToEdge,
            address_mode_w: wgpu::AddressMode::ClampToEdge,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        let storage = |binding: u32, read_only: bool, min: u64| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only },
                has_dynamic_offset: false,
                min_binding_size: wgpu::BufferSize::new(min),
            },
            count: None,
        };
        let scatter_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("cutaway scatter layout"),
            // An index word; a (word, value) patch.
            entries: &[storage(0, false, 4), storage(1, true, 8)],
        });
        let scatter_pipeline_layout =
            device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some("cutaway scatter pipeline layout"),
                bind_group_layouts: &[Some(&scatter_layout)],
                immediate_size: 0,
            });
        let scatter_module = module("cutaway scatter.wgsl", shaders::SCATTER);
        let scatter = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("cutaway scatter"),
            layout: Some(&scatter_pipeline_layout),
            module: &scatter_module,
            entry_point: Some("main"),
            compilation_options: Default::default(),
            cache: None,
        });
        Pipelines {
            frame_layout,
            draw_layout,
            composite_layout,
            blit_layout,
            mesh_opaque,
            mesh_oit,
            lines_opaque,
            lines_overlay,
            composite,
            blit,
            sampler,
            scatter_layout,
            scatter,
        }
    }
}
