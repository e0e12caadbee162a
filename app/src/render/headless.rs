//! Rendering with no window: a device of its own, the same [`Renderer`] as the window, tiles for
//! images larger than the device's maximum texture size, PNG pixels read back. A scene is made
//! into a frame by `crate::view` (`render_png`, `render_with`), which also computes its cut.
//!
//! On a machine with no GPU, Mesa's lavapipe (`WGPU_BACKEND=vulkan`) or llvmpipe over EGL
//! (`WGPU_BACKEND=gl`) serve; snapshot tests pin Vulkan because the two differ in a few pixels.

use std::sync::Arc;

use anyhow::Context as _;

use super::{FrameInputs, OutputTarget, Renderer, Tile};

/// Largest tile rendered at once (output pixels per side); bigger images are tiled.
const MAX_TILE: u32 = 2048;

/// A device, a queue and a renderer painting into `Rgba8Unorm` images.
pub struct HeadlessRenderer {
    device: wgpu::Device,
    queue: wgpu::Queue,
    renderer: Renderer,
    adapter: wgpu::AdapterInfo,
    /// The risk map of the last preview drawn (computed by the cutting layer, not here).
    risk: crate::cutting::wall_risk::RiskCache,
    /// The risk map the last `crate::view::render_with_preview` drew, if any.
    drawn: Option<Arc<crate::cutting::wall_risk::WallRisk>>,
}

impl HeadlessRenderer {
    /// Opens the first adapter `WGPU_BACKEND` (or the platform default) offers, software ones
    /// included. The error says why none could be opened.
    pub fn new() -> anyhow::Result<HeadlessRenderer> {
        let defaults = wgpu::InstanceDescriptor::new_without_display_handle().with_env();
        HeadlessRenderer::with_backends(defaults.backends)
    }

    /// [`HeadlessRenderer::new`] restricted to `backends` (tests pin Vulkan).
    pub fn with_backends(backends: wgpu::Backends) -> anyhow::Result<HeadlessRenderer> {
        let mut descriptor = wgpu::InstanceDescriptor::new_without_display_handle().with_env();
        descriptor.backends = backends;
        let instance = wgpu::Instance::new(descriptor);
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            force_fallback_adapter: false,
            compatible_surface: None,
            ..Default::default()
        }))
        .map_err(|e| {
            anyhow::anyhow!(
                "no GPU adapter (install mesa-vulkan-drivers and set WGPU_BACKEND=vulkan): {e}"
            )
        })?;
        let limits = adapter.limits();
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("cutaway headless device"),
            memory_hints: super::device_memory::MEMORY_HINTS,
            required_limits: wgpu::Limits {
                max_texture_dimension_2d: limits.max_texture_dimension_2d,
                // Intensity images are 3-D textures at their own grid size (up to 2048 a side).
                max_texture_dimension_3d: limits.max_texture_dimension_3d,
                ..wgpu::Limits::downlevel_defaults()
            },
            ..Default::default()
        }))
        .context("could not open the GPU device")?;
        let renderer = Renderer::new(&device, OutputTarget::png());
        Ok(HeadlessRenderer {
            device,
            queue,
            renderer,
            adapter: adapter.get_info(),
            risk: Default::default(),
            drawn: None,
        })
    }

    /// What the last frame uploaded (see [`Renderer::last_frame_uploads`]).
    pub fn last_frame_uploads(&self) -> super::UploadStats {
        self.renderer.last_frame_uploads()
    }

    /// Name and backend of the adapter, e.g. `llvmpipe (LLVM 15.0.6, 256 bits) (Vulkan)`.
    pub fn adapter_name(&self) -> String {
        format!("{} ({:?})", self.adapter.name, self.adapter.backend)
    }

    /// The device's largest 3-D texture side: an intensity image larger than this is shown at
    /// reduced resolution (`crate::io::intensity::fit`).
    pub fn max_texture_dimension_3d(&self) -> u32 {
        self.device.limits().max_texture_dimension_3d
    }

    /// The risk map the last `crate::view::render_with_preview` drew (for its legend), if any.
    pub fn drawn_risk(&self) -> Option<Arc<crate::cutting::wall_risk::WallRisk>> {
        self.drawn.clone()
    }

    /// The risk maps computed for this renderer's frames (the caller computes them; a map is
    /// kept while its preview is drawn again), and the one drawn last.
    pub fn risk_maps(
        &mut self,
    ) -> (
        &mut crate::cutting::wall_risk::RiskCache,
        &mut Option<Arc<crate::cutting::wall_risk::WallRisk>>,
    ) {
        (&mut self.risk, &mut self.drawn)
    }

    /// Sets how many triangles the GPU bins at a time (see [`Renderer::set_batch_triangles`]).
    pub fn set_batch_triangles(&mut self, triangles: Option<u32>) {
        self.renderer.set_batch_triangles(triangles);
    }

    /// True for software rasterizers (lavapipe, llvmpipe).
    pub fn is_software(&self) -> bool {
        self.adapter.device_type == wgpu::DeviceType::Cpu
    }

    /// Renders `frame` (whose `size` is the full image size) into an image, tile by tile when it is
    /// larger than [`MAX_TILE`]. Straight alpha, sRGB-encoded.
    pub fn render(&mut self, frame: &FrameInputs) -> anyhow::Result<image::RgbaImage> {
        let [width, height] = frame.size;
        if width == 0 || height == 0 || width > 16384 || height > 16384 {
            anyhow::bail!("image size {width}x{height} is outside 1..16384");
        }
        let supersample = frame.supersample();
        let max_tile =
            (self.device.limits().max_texture_dimension_2d / supersample).clamp(64, MAX_TILE);
        let mut image = image::RgbaImage::new(width, height);
        let mut y = 0;
        while y < height {
            let th = max_tile.min(height - y);
            let mut x = 0;
            while x < width {
                let tw = max_tile.min(width - x);
                let mut tile_frame = frame.clone();
                tile_frame.size = [tw, th];
                tile_frame.tile = (tw != width || th != height).then_some(Tile {
                    full_size: [width, height],
                    origin: [x, y],
                });
                let pixels = self.render_tile(&tile_frame)?;
                for row in 0..th {
                    for col in 0..tw {
                        let at = ((row * tw + col) * 4) as usize;
                        image.put_pixel(
                            x + col,
                            y + row,
                            image::Rgba([
                                pixels[at],
                                pixels[at + 1],
                                pixels[at + 2],
                                pixels[at + 3],
                            ]),
                        );
                    }
                }
                x += tw;
            }
            y += th;
        }
        Ok(image)
    }

    /// The UI thread's share of a frame, as in the window's paint callback: [`Renderer::prepare`]
    /// (uploads and command recording) and the queue submission, in milliseconds. Then waits for
    /// the GPU (not timed), so the next call starts idle. For the timing benchmarks (ignored
    /// tests run with `--ignored`); the image is not read back.
    pub fn time_prepare(&mut self, frame: &FrameInputs) -> anyhow::Result<f64> {
        let started = std::time::Instant::now();
        let mut encoder = self
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("cutaway timed frame"),
            });
        self.renderer
            .prepare(&self.device, &self.queue, &mut encoder, frame);
        self.queue.submit([encoder.finish()]);
        let ms = started.elapsed().as_secs_f64() * 1000.0;
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .context("GPU did not finish")?;
        Ok(ms)
    }

    /// One tile: prepare, blit into an `Rgba8Unorm` texture, copy out. Returns tightly packed
    /// RGBA rows.
    fn render_tile(&mut self, frame: &FrameInputs) -> anyhow::Result<Vec<u8>> {
        let [width, height] = frame.size;
        let texture = self.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("cutaway export tile"),
            size: wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: self.renderer.output().format,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
        let padded_row = (width * 4).div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT)
            * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
        let readback = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("cutaway export readback"),
            size: padded_row as u64 * height as u64,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        let mut encoder = self
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("cutaway export"),
            });
        self.renderer
            .prepare(&self.device, &self.queue, &mut encoder, frame);
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("cutaway export blit"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &view,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                        store: wgpu::StoreOp::Store,
                    },
                    depth_slice: None,
                })],
                depth_stencil_attachment: None,
                occlusion_query_set: None,
                timestamp_writes: None,
                multiview_mask: None,
            });
            self.renderer.paint(&mut pass);
        }
        encoder.copy_texture_to_buffer(
            wgpu::TexelCopyTextureInfo {
                texture: &texture,
                mip_level: 0,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            wgpu::TexelCopyBufferInfo {
                buffer: &readback,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(padded_row),
                    rows_per_image: Some(height),
                },
            },
            wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
        );
        self.queue.submit([encoder.finish()]);
        let slice = readback.slice(..);
        let (sender, receiver) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |result| {
            let _ = sender.send(result);
        });
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .context("GPU readback did not finish")?;
        receiver
            .recv()
            .context("GPU readback was dropped")?
            .context("GPU readback failed")?;
        let mapped = slice
            .get_mapped_range()
            .context("GPU readback could not be read")?;
        let mut pixels = Vec::with_capacity((width * height * 4) as usize);
        for row in 0..height as usize {
            let start = row * padded_row as usize;
            pixels.extend_from_slice(&mapped[start..start + width as usize * 4]);
        }
        drop(mapped);
        readback.unmap();
        Ok(pixels)
    }
}

/// The folder to use as `XDG_RUNTIME_DIR` when the process has none: `None` when the variable
/// already names an absolute path of an existing folder.
///
/// Why: at instance creation the window-system libraries that Mesa and wgpu load (Wayland's
/// client library among them) print `error: XDG_RUNTIME_DIR is invalid or not set in the
/// environment.` when the variable is unset or relative, although a headless render needs no
/// window system at all. `main` sets the variable to this private folder
/// (`<temp>/cutaway-runtime-<uid>`, mode 0700, created if needed) before any thread starts, so a
/// successful render prints nothing. Returns `None` too when the folder cannot be made safe (it
/// exists but belongs to another user or is not a folder): then nothing changes.
pub fn private_runtime_dir() -> Option<std::path::PathBuf> {
    use std::os::unix::fs::{DirBuilderExt as _, MetadataExt as _, PermissionsExt as _};
    let current = std::env::var_os("XDG_RUNTIME_DIR").map(std::path::PathBuf::from);
    if current.is_some_and(|d| d.is_absolute() && d.is_dir()) {
        return None;
    }
    // The owner of /proc/self is this process's effective user.
    let uid = std::fs::metadata("/proc/self").ok()?.uid();
    let dir = std::env::temp_dir().join(format!("cutaway-runtime-{uid}"));
    match std::fs::DirBuilder::new().mode(0o700).create(&dir) {
        Ok(()) => {}
        Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {}
        Err(_) => return None,
    }
    let metadata = std::fs::symlink_metadata(&dir).ok()?;
    let private = metadata.is_dir()
        && metadata.uid() == uid
        && metadata.permissions().mode() & 0o077 == 0
        && dir.is_absolute();
    private.then_some(dir)
}
