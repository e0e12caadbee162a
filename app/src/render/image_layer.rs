//! The intensity image on the GPU: one integer 3-D texture per image, uploaded once, and the
//! pipeline that draws walls, slices and ribbons with it (`shaders/image.wgsl`).
//!
//! # Memory
//! The texture holds the file's samples bit for bit at their own size (`uint8` → `R8Uint`,
//! `int16`/`uint16` → `R16Uint`, `int32`/`float32` → `R32Uint`); the shader decodes the kind
//! and interpolates by hand. No float copy is ever made, so on a software rasterizer, where
//! the texture lives in system memory, the image costs its own size once more, not twice. The
//! upload goes slab by slab (at most [`UPLOAD_SLAB_BYTES`] staged at a time), so the staging
//! memory stays small however large the scan.
//!
//! The pipeline is created the first time an image is drawn, so scenes without one pay nothing.

use std::sync::{Arc, Weak};

use bytemuck::{Pod, Zeroable};
use wgpu::util::DeviceExt as _;

use super::frame::ImageDraw;
use super::gpu_data::Vertex;
use super::pipelines::{LayerShader, Pipelines, layer_pipeline};
use crate::io::intensity::{IntensityImage, SampleKind};

/// Largest piece of the image staged for upload at once.
pub const UPLOAD_SLAB_BYTES: usize = 32 << 20;

/// Keep in sync with `ImageParams` in `image.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct ImageUniform {
    pub voxel_from_world: [[f32; 4]; 4],
    /// xyz: grid size; w: sample kind (0 uint8, 1 int16, 2 uint16, 3 int32, 4 float32).
    pub dims: [f32; 4],
    /// x: slope, y: intercept; z: window low; w: 1 / window width.
    pub values: [f32; 4],
    /// x: image weight against the structure colour.
    pub mix: [f32; 4],
}

impl ImageUniform {
    pub fn new(layer: &ImageDraw) -> ImageUniform {
        let image = &layer.image;
        let kind = match image.kind() {
            SampleKind::U8 => 0.0,
            SampleKind::I16 => 1.0,
            SampleKind::U16 => 2.0,
            SampleKind::I32 => 3.0,
            SampleKind::F32 => 4.0,
        };
        let (slope, intercept) = image.scale();
        let m = glam::DMat4::from(image.voxel_from_world()).as_mat4();
        ImageUniform {
            voxel_from_world: m.to_cols_array_2d(),
            dims: [
                image.dims[0] as f32,
                image.dims[1] as f32,
                image.dims[2] as f32,
                kind,
            ],
            values: [
                slope as f32,
                intercept as f32,
                layer.window.low() as f32,
                (1.0 / layer
                    .window
                    .width
                    .max(crate::io::intensity::Window::MIN_WIDTH)) as f32,
            ],
            mix: [layer.image_weight, 0.0, 0.0, 0.0],
        }
    }
}

struct Uploaded {
    image: Weak<IntensityImage>,
    /// The reduced grid on the GPU when the image is over the texture limit: its size and
    /// world → voxel matrix (the reduced values live only in the texture).
    grid: Option<([usize; 3], glam::DAffine3)>,
    bind_group: wgpu::BindGroup,
    uniform: wgpu::Buffer,
    /// Kept alive for the bind group.
    _texture: wgpu::Texture,
}

/// The image state of one renderer: the uploaded texture, its uniform and the pipeline.
#[derive(Default)]
pub struct ImageRenderer {
    layout: Option<wgpu::BindGroupLayout>,
    pipeline: Option<wgpu::RenderPipeline>,
    uploaded: Option<Uploaded>,
    /// Bytes of image data sent this frame (0 when the texture was already there).
    pub uploaded_bytes: u64,
    /// Set while the image on the GPU is a reduced copy because the scan is larger than the
    /// device's 3-D texture limit (`crate::io::intensity::fit::notice`).
    pub notice: Option<String>,
}

impl ImageRenderer {
    /// Uploads `layer`'s image when it is not the one on the GPU, writes the window and display
    /// uniform, and drops the texture when the scene has no image. Returns whether image draws
    /// can be made this frame.
    pub fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        pipelines: &Pipelines,
        layer: Option<&ImageDraw>,
    ) -> bool {
        self.uploaded_bytes = 0;
        let Some(layer) = layer else {
            self.uploaded = None;
            self.notice = None;
            return false;
        };
        let limit = device.limits().max_texture_dimension_3d as usize;
        let layout = self
            .layout
            .get_or_insert_with(|| bind_group_layout(device))
            .clone();
        if self.pipeline.is_none() {
            self.pipeline = Some(pipeline(device, pipelines, &layout));
        }
        let fresh = self.uploaded.as_ref().is_some_and(|u| {
            u.image
                .upgrade()
                .is_some_and(|i| Arc::ptr_eq(&i, &layer.image))
        });
        if !fresh {
            // The old texture goes first, so two scans are never on the GPU together.
            self.uploaded = None;
            // Larger than the texture limit: a block-averaged copy, only while it is uploaded.
            let fitted = crate::io::intensity::fit::fit_to_limit(&layer.image, limit);
            self.notice = crate::io::intensity::fit::notice(&layer.image, limit);
            self.uploaded = Some(upload(device, queue, &layout, &layer.image, &fitted));
            self.uploaded_bytes = fitted.bytes().len() as u64;
        }
        if let Some(u) = &self.uploaded {
            let mut uniform = ImageUniform::new(layer);
            if let Some((dims, voxel_from_world)) = u.grid {
                // The shader samples the reduced grid: its size and world → voxel matrix.
                let m = glam::DMat4::from(voxel_from_world).as_mat4();
                uniform.voxel_from_world = m.to_cols_array_2d();
                uniform.dims[..3].copy_from_slice(&dims.map(|d| d as f32));
            }
            queue.write_buffer(&u.uniform, 0, bytemuck::bytes_of(&uniform));
        }
        true
    }

    /// The layout of the image's bind group, once an image was prepared (the risk map's
    /// pipeline over the image is made with it).
    pub fn layout(&self) -> Option<&wgpu::BindGroupLayout> {
        self.layout.as_ref()
    }

    /// The uploaded image's bind group (group 2), when there is one this frame.
    pub fn bind_group(&self) -> Option<&wgpu::BindGroup> {
        self.uploaded.as_ref().map(|u| &u.bind_group)
    }

    /// Sets the image pipeline and its bind group (group 2) on `pass`; false when there is no
    /// image this frame.
    pub fn bind(&self, pass: &mut wgpu::RenderPass<'_>) -> bool {
        match (&self.pipeline, &self.uploaded) {
            (Some(pipeline), Some(u)) => {
                pass.set_pipeline(pipeline);
                pass.set_bind_group(2, &u.bind_group, &[]);
                true
            }
            _ => false,
        }
    }
}

fn bind_group_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("cutaway image layout"),
        entries: &[
            wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: wgpu::BufferSize::new(size_of::<ImageUniform>() as u64),
                },
                count: None,
            },
            wgpu::BindGroupLayoutEntry {
                binding: 1,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Uint,
                    view_dimension: wgpu::TextureViewDimension::D3,
                    multisampled: false,
                },
                count: None,
            },
        ],
    })
}

fn pipeline(
    device: &wgpu::Device,
    pipelines: &Pipelines,
    layout: &wgpu::BindGroupLayout,
) -> wgpu::RenderPipeline {
    layer_pipeline(
        device,
        pipelines,
        LayerShader {
            label: "cutaway mesh with image",
            source: super::shaders::MESH_IMAGE.to_string(),
            extra_layout: Some(layout),
            vertex_stride: size_of::<Vertex>() as u64,
            vertex_entry: "vs_main",
            fragment_entry: "fs_image",
        },
    )
}

fn upload(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    layout: &wgpu::BindGroupLayout,
    source: &Arc<IntensityImage>,
    image: &Arc<IntensityImage>,
) -> Uploaded {
    let format = match image.kind().size() {
        1 => wgpu::TextureFormat::R8Uint,
        2 => wgpu::TextureFormat::R16Uint,
        _ => wgpu::TextureFormat::R32Uint,
    };
    let [nx, ny, nz] = image.dims.map(|d| d as u32);
    let texture = device.create_texture(&wgpu::TextureDescriptor {
        label: Some("cutaway intensity image"),
        size: wgpu::Extent3d {
            width: nx,
            height: ny,
            depth_or_array_layers: nz,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D3,
        format,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    let row = image.dims[0] * image.kind().size();
    let slice = row * image.dims[1];
    let slab = (UPLOAD_SLAB_BYTES / slice).max(1);
    let bytes = image.bytes();
    let mut z = 0;
    while z < image.dims[2] {
        let count = slab.min(image.dims[2] - z);
        queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture: &texture,
                mip_level: 0,
                origin: wgpu::Origin3d {
                    x: 0,
                    y: 0,
                    z: z as u32,
                },
                aspect: wgpu::TextureAspect::All,
            },
            &bytes[z * slice..(z + count) * slice],
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(row as u32),
                rows_per_image: Some(ny),
            },
            wgpu::Extent3d {
                width: nx,
                height: ny,
                depth_or_array_layers: count as u32,
            },
        );
        // Each slab goes to the GPU before the next is staged.
        queue.submit(std::iter::empty());
        let _ = device.poll(wgpu::PollType::wait_indefinitely());
        z += count;
    }
    let uniform = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("cutaway image uniform"),
        contents: bytemuck::bytes_of(&ImageUniform::default()),
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
    });
    let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
    let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("cutaway image bind group"),
        layout,
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: uniform.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: wgpu::BindingResource::TextureView(&view),
            },
        ],
    });
    Uploaded {
        image: Arc::downgrade(source),
        grid: (!Arc::ptr_eq(source, image)).then(|| (image.dims, image.voxel_from_world())),
        bind_group,
        uniform,
        _texture: texture,
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn uniform_size_matches_the_wgsl_layout() {
        // mat4x4<f32> 64 + 3 × vec4<f32> 48.
        assert_eq!(size_of::<super::ImageUniform>(), 112);
    }
}
