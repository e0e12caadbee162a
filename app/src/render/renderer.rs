//! The [`Renderer`]: offscreen scene rendering ([`Renderer::prepare`]) and compositing into the
//! caller's pass ([`Renderer::paint`]).
//!
//! A frame uploads what is new and lists its draws ([`draw_list`]), hides the faces a delta
//! replaces in place ([`index_patches`]), writes the uniforms ([`uniforms`]) and records the
//! passes of each eye ([`passes`]) into the offscreen images of its size ([`targets`]). The blit
//! in `paint` downsamples the supersampled image, combines the anaglyph eyes and gamma-encodes.
//! This file holds what lives across frames: the caches of uploads, keyed by the meshes'
//! addresses and dropped with them, and the frame's order of work.

mod batches;
mod draw_list;
mod index_patches;
mod passes;
mod staging;
mod targets;
mod uniforms;

use std::collections::HashMap;
use std::sync::{Arc, Weak};

use csg::Mesh;

use super::draw_data::{GpuMesh, GpuSegments};
use super::gpu_data::{BlitUniform, DRAW_UNIFORM_STRIDE, DrawUniform, FrameUniform};
use super::pipelines::Pipelines;
use super::{FrameInputs, OutputTarget, srgb_to_linear};
use crate::cutting::delta::MeshDelta;
use draw_list::{CachedPreview, CachedRisk};
use index_patches::IndexPatch;
use targets::Targets;
use uniforms::{
    depth_range, draw_buffer, eye_cameras, frame_uniform, full_size, uniform_bind_group,
};

/// Wall colour (sRGB) that the cut surfaces lean toward: a pale cream, distinct from anatomy
/// colours yet close enough to read as "inside of the same thing".
pub const WALL_TINT: [f32; 3] = [0.98, 0.93, 0.78];
/// How far a wall's colour goes from its model's colour toward [`WALL_TINT`].
pub const WALL_MIX: f32 = 0.6;
/// Contour line colour (sRGB).
pub const CONTOUR_COLOR: [f32; 3] = [0.08, 0.07, 0.1];
/// Contour line width in pixels at 800 px image height.
pub const CONTOUR_WIDTH_PX: f32 = 3.0;
/// Brightness of back faces relative to front faces.
pub const BACK_FACE: f32 = 0.55;
/// How far contour lines are pulled toward the eye (so they win the depth test against the
/// surfaces they lie on), as a fraction of the scene's bounding radius.
pub const CONTOUR_OFFSET: f64 = 0.004;
/// Cached uploads not used for this many frames are dropped.
const CACHE_FRAMES: u64 = 120;

struct CachedMesh {
    mesh: Weak<Mesh>,
    gpu: Option<GpuMesh>,
    last_used: u64,
    /// The last frame that drew `gpu`'s wireframe edges (see [`Renderer::evict`]).
    edges_drawn: u64,
    /// Faces currently hidden in `gpu`'s index buffer (ascending; see [`MeshDelta`]) and the
    /// delta they were hidden for.
    hidden: Vec<u32>,
    hidden_for: Option<Weak<MeshDelta>>,
    /// The model's wall faces `gpu` was made with (address and length of the list): other
    /// marks on the same mesh upload it again.
    walls: (usize, usize),
}

/// The patch mesh of a [`MeshDelta`], uploaded.
struct CachedDelta {
    delta: Weak<MeshDelta>,
    gpu: Option<GpuMesh>,
    last_used: u64,
}

/// What went to the GPU: mesh, line and patch data (uniforms left out). See
/// [`Renderer::last_frame_uploads`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct UploadStats {
    /// Bytes of vertex, index, line-segment and index-patch data.
    pub bytes: u64,
    /// Triangles whose vertices or indices were uploaded (a hidden or shown face counts one).
    pub triangles: u64,
}

impl UploadStats {
    fn mesh(&mut self, mesh: Option<&GpuMesh>) {
        if let Some(m) = mesh {
            self.bytes += m.byte_size();
            self.triangles += u64::from(m.index_count / 3);
        }
    }

    fn segments(&mut self, segments: Option<&GpuSegments>) {
        if let Some(s) = segments {
            self.bytes += s.byte_size();
        }
    }
}

/// The uploads a [`Renderer`] keeps between frames (see [`Renderer::census`]).
pub use crate::platform::memory_census::GpuCensus;

/// See the module documentation of [`crate::render`].
pub struct Renderer {
    output: OutputTarget,
    pipelines: Pipelines,
    frame_buffer: wgpu::Buffer,
    frame_bind_group: wgpu::BindGroup,
    draw_buffer: wgpu::Buffer,
    /// Number of [`DrawUniform`] slots in `draw_buffer`.
    draw_capacity: u64,
    draw_bind_group: wgpu::BindGroup,
    blit_buffer: wgpu::Buffer,
    targets: Option<Targets>,
    models: HashMap<usize, CachedMesh>,
    preview: Option<CachedPreview>,
    /// The refined walls of the risk map being drawn.
    risk: Option<CachedRisk>,
    overlay_meshes: Vec<Option<GpuMesh>>,
    overlay_lines: Vec<Option<GpuSegments>>,
    /// Uploaded delta patches, by the delta's address.
    deltas: HashMap<usize, CachedDelta>,
    /// Index patches to apply before this frame's passes.
    patches: Vec<IndexPatch>,
    uploads: UploadStats,
    /// Bounding box of each model mesh seen (by address), so a frame does not scan the models.
    bboxes: HashMap<usize, (Weak<Mesh>, csg::Aabb)>,
    /// The box of this frame's models (see [`Renderer::scene_bbox`]), the deltas' patches
    /// included.
    scene_bbox: csg::Aabb,
    frame_index: u64,
    image: super::image_layer::ImageRenderer,
    risk_pipelines: super::risk_layer::RiskRenderer,
    /// Hands the allocator's free pages back after a preview or model uploads were dropped.
    free_pages: crate::platform::free_pages::FreePages,
    /// Bytes uploaded since the uploads were last submitted ([`staging`]).
    staging: staging::Staging,
    /// Triangles per submitted batch of a pass ([`batches`]): set on software adapters.
    batch_triangles: Option<u32>,
}

impl Renderer {
    /// Creates the pipelines for painting into `output` (see [`OutputTarget::egui`]).
    pub fn new(device: &wgpu::Device, output: OutputTarget) -> Renderer {
        let pipelines = Pipelines::new(device, output);
        let frame_buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("cutaway frame uniforms (one per eye)"),
            size: 2 * DRAW_UNIFORM_STRIDE,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let frame_bind_group = uniform_bind_group(
            device,
            "cutaway frame bind group",
            &pipelines.frame_layout,
            &frame_buffer,
            size_of::<FrameUniform>() as u64,
        );
        let draw_capacity = 64;
        let (draw_buffer, draw_bind_group) = draw_buffer(device, &pipelines, draw_capacity);
        let blit_buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("cutaway blit uniform"),
            size: size_of::<BlitUniform>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        Renderer {
            output,
            pipelines,
            frame_buffer,
            frame_bind_group,
            draw_buffer,
            draw_capacity,
            draw_bind_group,
            blit_buffer,
            targets: None,
            models: HashMap::new(),
            preview: None,
            risk: None,
            overlay_meshes: Vec::new(),
            overlay_lines: Vec::new(),
            deltas: HashMap::new(),
            patches: Vec::new(),
            uploads: UploadStats::default(),
            bboxes: HashMap::new(),
            scene_bbox: csg::Aabb::EMPTY,
            frame_index: 0,
            image: Default::default(),
            risk_pipelines: Default::default(),
            free_pages: Default::default(),
            staging: Default::default(),
            batch_triangles: (device.adapter_info().device_type == wgpu::DeviceType::Cpu)
                .then_some(batches::CPU_BATCH),
        }
    }

    /// Sets the triangles per submitted batch of a pass (`None`: a pass is one batch in the
    /// caller's encoder). [`Renderer::new`] batches on software adapters only.
    pub fn set_batch_triangles(&mut self, triangles: Option<u32>) {
        self.batch_triangles = triangles;
    }

    /// The target this renderer paints into.
    pub fn output(&self) -> OutputTarget {
        self.output
    }

    /// What the last [`Renderer::prepare`] uploaded (tests: a live re-cut or a scalpel step
    /// must not send a whole model).
    pub fn last_frame_uploads(&self) -> UploadStats {
        self.uploads
    }

    /// What the renderer keeps uploaded between frames (the memory test prints it per step).
    pub fn census(&self) -> GpuCensus {
        let mut c = GpuCensus::default();
        for gpu in self.models.values().filter_map(|m| m.gpu.as_ref()) {
            c.models += 1;
            c.model_bytes += gpu.byte_size();
            if let Some(e) = &gpu.edges {
                c.edge_sets += 1;
                c.edge_bytes += e.byte_size();
            }
        }
        for gpu in self.deltas.values().filter_map(|d| d.gpu.as_ref()) {
            c.deltas += 1;
            c.delta_bytes += gpu.byte_size();
        }
        if let Some(p) = &self.preview {
            for gpu in p.parts.iter().flatten() {
                c.preview_parts += 1;
                c.preview_bytes += gpu.byte_size();
                if let Some(e) = &gpu.edges {
                    c.edge_sets += 1;
                    c.edge_bytes += e.byte_size();
                }
            }
            c.preview_bytes += p.contours.values().map(|s| s.byte_size()).sum::<u64>();
        }
        for gpu in self.risk.iter().flat_map(|r| r.walls.iter().flatten()) {
            c.preview_parts += 1;
            c.preview_bytes += gpu.byte_size();
        }
        c
    }

    /// Renders `frame` offscreen, recording into `encoder` (egui's encoder in a paint callback's
    /// `prepare`), or on a software adapter submitting it batch by batch ([`batches`]). Uploads
    /// new or changed meshes first. Call [`Renderer::paint`] afterwards.
    pub fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameInputs,
    ) {
        self.frame_index += 1;
        self.uploads = UploadStats::default();
        let supersample = frame.supersample();
        let max_dim = device.limits().max_texture_dimension_2d;
        let size = [
            (frame.size[0].max(1) * supersample).min(max_dim),
            (frame.size[1].max(1) * supersample).min(max_dim),
        ];
        let eyes = if frame.look.anaglyph { 2 } else { 1 };
        if self
            .targets
            .as_ref()
            .is_none_or(|t| t.size != size || t.color_views.len() != eyes)
        {
            self.targets = Some(self.create_targets(device, size, eyes));
        }

        self.scene_bbox = self.scene_bbox(frame);

        // Phase 1: uploads (mutable caches).
        let image = frame.image.as_ref();
        let image_ready = self.image.prepare(device, queue, &self.pipelines, image);
        let on = |walls: bool| {
            image_ready && image.is_some_and(|l| if walls { l.on_walls } else { l.on_slices })
        };
        if let Some(risk) = &frame.risk {
            let image_layout = on(true).then(|| self.image.layout()).flatten();
            self.risk_pipelines
                .prepare(device, &self.pipelines, image_layout, &risk.ramp);
        }
        let draws = self.upload_and_list(device, queue, frame, [on(true), on(false)]);
        let (draws, uniforms) = draws;
        if let Some(mut targets) = self.targets.take() {
            self.keep_transparency_targets(device, &mut targets, !draws.transparent.is_empty());
            self.targets = Some(targets);
        }

        // Phase 2: uniforms.
        let line_scale = supersample as f32 * (full_size(frame)[1] as f32 / 800.0).max(1.0);
        let uniforms: Vec<DrawUniform> = uniforms
            .into_iter()
            .map(|mut u| {
                u.params[2] *= line_scale;
                u
            })
            .collect();
        if uniforms.len() as u64 > self.draw_capacity {
            self.draw_capacity = (uniforms.len() as u64).next_power_of_two();
            let (buffer, bind_group) = draw_buffer(device, &self.pipelines, self.draw_capacity);
            self.draw_buffer = buffer;
            self.draw_bind_group = bind_group;
        }
        let mut bytes = vec![0u8; uniforms.len() * DRAW_UNIFORM_STRIDE as usize];
        for (i, u) in uniforms.iter().enumerate() {
            let at = i * DRAW_UNIFORM_STRIDE as usize;
            bytes[at..at + size_of::<DrawUniform>()].copy_from_slice(bytemuck::bytes_of(u));
        }
        if !bytes.is_empty() {
            queue.write_buffer(&self.draw_buffer, 0, &bytes);
        }
        let (near, far, radius) = depth_range(frame, self.scene_bbox);
        let cameras = eye_cameras(frame);
        let mut frame_bytes = vec![0u8; 2 * DRAW_UNIFORM_STRIDE as usize];
        for (eye, camera) in cameras.iter().enumerate() {
            let u = frame_uniform(frame, camera, size, near, far);
            let at = eye * DRAW_UNIFORM_STRIDE as usize;
            frame_bytes[at..at + size_of::<FrameUniform>()].copy_from_slice(bytemuck::bytes_of(&u));
        }
        queue.write_buffer(&self.frame_buffer, 0, &frame_bytes);
        let _ = radius;
        let blit = BlitUniform {
            mode: u32::from(eyes == 2),
            encode_srgb: u32::from(!self.output.format.is_srgb()),
            straight_alpha: u32::from(self.output.straight_alpha),
            _pad: 0,
        };
        queue.write_buffer(&self.blit_buffer, 0, bytemuck::bytes_of(&blit));

        // Phase 3: passes.
        let background = frame.look.background;
        let alpha = background[3] as f64;
        let clear = wgpu::Color {
            r: srgb_to_linear(background[0]) as f64 * alpha,
            g: srgb_to_linear(background[1]) as f64 * alpha,
            b: srgb_to_linear(background[2]) as f64 * alpha,
            a: alpha,
        };
        let mut out =
            batches::Submissions::new(device, queue, encoder, self.batch_triangles.is_some());
        self.apply_patches(device, out.encoder());
        for eye in 0..eyes {
            self.encode_eye(&mut out, eye, clear, &draws);
        }
        out.finish();
        self.evict();
        self.free_pages.trim_if_due(std::time::Instant::now());
    }

    /// Composites the last prepared image into `pass` (a fullscreen triangle: the caller sets the
    /// viewport, as egui does for a paint callback's rect). Draws nothing before the first
    /// `prepare`.
    pub fn paint(&self, pass: &mut wgpu::RenderPass<'_>) {
        let Some(targets) = &self.targets else { return };
        pass.set_pipeline(&self.pipelines.blit);
        pass.set_bind_group(0, &targets.blit_bind_group, &[]);
        pass.draw(0..3, 0..1);
    }

    /// The box of the frame's visible models (of all when none is visible), as a scene's box is,
    /// with each mesh's box computed once, and each model
    /// drawn with a delta grown by its patch (a scalpel step can open a cut a little past the
    /// mesh's old box; what a delta hides lies inside the base's box anyway).
    fn scene_bbox(&mut self, frame: &FrameInputs) -> csg::Aabb {
        self.bboxes.retain(|_, (w, _)| w.strong_count() > 0);
        let mut visible = csg::Aabb::EMPTY;
        let mut all = csg::Aabb::EMPTY;
        for model in &frame.models {
            let key = Arc::as_ptr(&model.mesh) as usize;
            let cached = self
                .bboxes
                .get(&key)
                .filter(|(w, _)| w.upgrade().is_some_and(|m| Arc::ptr_eq(&m, &model.mesh)))
                .map(|(_, b)| *b);
            let mut b = match cached {
                Some(b) => b,
                None => {
                    let b = model.mesh.bbox();
                    self.bboxes.insert(key, (Arc::downgrade(&model.mesh), b));
                    b
                }
            };
            for d in frame
                .deltas
                .iter()
                .filter(|d| Arc::ptr_eq(&d.base, &model.mesh))
            {
                if !d.patch.triangles.is_empty() {
                    b = b.union(&d.patch.bbox());
                }
            }
            all = all.union(&b);
            if model.visible {
                visible = visible.union(&b);
            }
        }
        if visible.is_empty() { all } else { visible }
    }

    /// Drops uploads of meshes that no longer exist or were not drawn for a while (a model
    /// mesh dropped with faces hidden goes with them). Delta patches go as soon as a frame did
    /// not draw them: each change makes a new one. Wireframe edges (one and a half segments
    /// per triangle, bigger than the mesh's own buffers) are made on demand and go as soon as a
    /// frame did not draw them: the model is drawn solid again, or hidden, or replaced by its
    /// cut, and finding them again costs one pass over the mesh when they are next drawn.
    fn evict(&mut self) {
        let now = self.frame_index;
        let models = self.models.len();
        let mut edges_dropped = false;
        for c in self.models.values_mut() {
            if c.edges_drawn != now
                && let Some(gpu) = c.gpu.as_mut()
            {
                edges_dropped |= gpu.edges.take().is_some();
            }
        }
        if edges_dropped {
            self.free_pages.note_large_free();
        }
        self.models.retain(|_, c| {
            c.mesh.strong_count() > 0 && now.saturating_sub(c.last_used) <= CACHE_FRAMES
        });
        self.deltas
            .retain(|_, c| c.delta.strong_count() > 0 && c.last_used == now);
        if self.models.len() < models {
            self.free_pages.note_large_free();
        }
    }
}
