//! The [`Renderer`]: offscreen scene rendering ([`Renderer::prepare`]) and compositing into the
//! caller's pass ([`Renderer::paint`]).
//!
//! Passes per eye: (1) opaque meshes and lines with depth; (2) transparent meshes into the
//! weighted-blended accumulation targets, depth-tested against (1) without writing; (3) the
//! transparency composite over (1), then overlay lines (cutter outlines) on top. The blit in
//! `paint` downsamples the supersampled image, combines the anaglyph eyes and gamma-encodes.

use std::collections::HashMap;
use std::sync::{Arc, Weak};

use csg::Mesh;
use glam::{DMat4, DVec2, DVec3, DVec4};

use wgpu::util::DeviceExt as _;

use super::delta::MeshDelta;
use super::draw_data::{GpuMesh, GpuSegments, cutter_outline_segments, polyline_segments};
use super::gpu_data::{BlitUniform, DRAW_UNIFORM_STRIDE, DrawUniform, FrameUniform};
use super::pipelines::{
    ACCUM_FORMAT, COLOR_FORMAT, DEPTH_FORMAT, Pipelines, REVEALAGE_FORMAT, SCATTER_GROUP,
    SCATTER_ROW_GROUPS,
};
use super::{FrameInputs, OutputTarget, ViewMode, srgb_to_linear};
use crate::cutting::cut_scene::{PartKind, PreviewGeometry};
use crate::scene::{ModelStyle, Stereo};

/// Wall colour (sRGB) that the cut surfaces lean toward: a pale cream, distinct from anatomy
/// colours yet close enough to read as "inside of the same thing".
pub const WALL_TINT: [f32; 3] = [0.98, 0.93, 0.78];
/// How far a wall's colour goes from its model's colour toward [`WALL_TINT`].
pub const WALL_MIX: f32 = 0.6;
/// Contour line colour (sRGB) and width in pixels at 800 px image height.
pub const CONTOUR_COLOR: [f32; 3] = [0.08, 0.07, 0.1];
const CONTOUR_WIDTH_PX: f32 = 3.0;
const WIREFRAME_WIDTH_PX: f32 = 1.0;
/// Cutter overlay colours (sRGB) and opacities.
const CUTTER_FILL: [f32; 3] = [0.35, 0.6, 0.95];
const CUTTER_OUTLINE: [f32; 3] = [0.08, 0.28, 0.75];
const HIGHLIGHT: [f32; 3] = [1.0, 0.55, 0.1];
/// Brightness of back faces relative to front faces.
const BACK_FACE: f32 = 0.55;
/// Eye separation of the anaglyph as a fraction of the camera distance.
const EYE_SEPARATION: f64 = 0.035;
/// Cached uploads not used for this many frames are dropped.
const CACHE_FRAMES: u64 = 120;

struct CachedMesh {
    mesh: Weak<Mesh>,
    gpu: Option<GpuMesh>,
    last_used: u64,
    /// Faces currently hidden in `gpu`'s index buffer (ascending; see [`MeshDelta`]) and the
    /// delta they were hidden for.
    hidden: Vec<u32>,
    hidden_for: Option<Weak<MeshDelta>>,
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

/// Index words to overwrite in one model's index buffer: (word, value), ascending by word.
struct IndexPatch {
    key: usize,
    words: Vec<[u32; 2]>,
}

struct CachedPreview {
    preview: Weak<PreviewGeometry>,
    /// One per `PreviewGeometry::parts` entry.
    parts: Vec<Option<GpuMesh>>,
    /// Per model: its contour polylines.
    contours: HashMap<usize, GpuSegments>,
}

/// Offscreen images for one output size.
struct Targets {
    /// Size of the offscreen images (the output size times the supersampling factor).
    size: [u32; 2],
    /// One per eye.
    color_views: Vec<wgpu::TextureView>,
    depth_view: wgpu::TextureView,
    accum_view: wgpu::TextureView,
    revealage_view: wgpu::TextureView,
    composite_bind_group: wgpu::BindGroup,
    blit_bind_group: wgpu::BindGroup,
}

/// What one draw call draws.
#[derive(Clone, Copy)]
enum Source {
    /// A scene model's mesh, by cache key.
    Model(usize),
    /// `PreviewGeometry::parts[i]`.
    Part(usize),
    /// The patch of a [`MeshDelta`], by cache key.
    Delta(usize),
    /// A per-frame overlay mesh.
    Overlay(usize),
}

#[derive(Clone, Copy)]
enum Draw {
    Mesh(Source, u32),
    /// A mesh showing the intensity image ([`super::image_layer`]).
    ImageMesh(Source, u32),
    Edges(Source, u32),
    Contour(usize, u32),
    Lines(usize, u32),
}

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
    overlay_meshes: Vec<Option<GpuMesh>>,
    overlay_lines: Vec<Option<GpuSegments>>,
    /// Uploaded delta patches, by the delta's address.
    deltas: HashMap<usize, CachedDelta>,
    /// Index patches to apply before this frame's passes.
    patches: Vec<IndexPatch>,
    uploads: UploadStats,
    /// Bounding box of each model mesh seen (by address), so a frame does not scan the models.
    bboxes: HashMap<usize, (Weak<Mesh>, csg::Aabb)>,
    /// This frame's [`Scene::bbox`](crate::scene::Scene::bbox), the deltas' patches included.
    scene_bbox: csg::Aabb,
    frame_index: u64,
    image: super::image_layer::ImageRenderer,
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
            overlay_meshes: Vec::new(),
            overlay_lines: Vec::new(),
            deltas: HashMap::new(),
            patches: Vec::new(),
            uploads: UploadStats::default(),
            bboxes: HashMap::new(),
            scene_bbox: csg::Aabb::EMPTY,
            frame_index: 0,
            image: Default::default(),
        }
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

    /// Renders `frame` offscreen, recording into `encoder` (egui's encoder in a paint callback's
    /// `prepare`). Uploads new or changed meshes first. Call [`Renderer::paint`] afterwards.
    pub fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameInputs,
    ) {
        self.frame_index += 1;
        self.uploads = UploadStats::default();
        let supersample = if frame.scene.render.antialias && !frame.deterministic {
            2
        } else {
            1
        };
        let max_dim = device.limits().max_texture_dimension_2d;
        let size = [
            (frame.size[0].max(1) * supersample).min(max_dim),
            (frame.size[1].max(1) * supersample).min(max_dim),
        ];
        let eyes = if frame.scene.render.stereo == Stereo::Anaglyph {
            2
        } else {
            1
        };
        if self
            .targets
            .as_ref()
            .is_none_or(|t| t.size != size || t.color_views.len() != eyes)
        {
            self.targets = Some(self.create_targets(device, size, eyes));
        }

        self.scene_bbox = self.scene_bbox(frame);

        // Phase 1: uploads (mutable caches).
        let image = frame.scene.image.as_ref();
        let image_ready = self.image.prepare(device, queue, &self.pipelines, image);
        let on = |walls: bool| {
            image_ready && image.is_some_and(|l| if walls { l.on_walls } else { l.on_slices })
        };
        let draws = self.upload_and_list(device, frame, [on(true), on(false)]);
        let (draws, uniforms) = draws;
        self.apply_patches(device, encoder);

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
        let background = frame.scene.render.background;
        let alpha = background[3] as f64;
        let clear = wgpu::Color {
            r: srgb_to_linear(background[0]) as f64 * alpha,
            g: srgb_to_linear(background[1]) as f64 * alpha,
            b: srgb_to_linear(background[2]) as f64 * alpha,
            a: alpha,
        };
        for eye in 0..eyes {
            self.encode_eye(encoder, eye, clear, &draws);
        }
        self.evict();
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

    fn create_targets(&self, device: &wgpu::Device, size: [u32; 2], eyes: usize) -> Targets {
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

    /// Uploads what is missing and lists the draws of the frame with their uniforms.
    /// `image_on`: whether walls, and slices and ribbons, show the image.
    fn upload_and_list(
        &mut self,
        device: &wgpu::Device,
        frame: &FrameInputs,
        image_on: [bool; 2],
    ) -> (DrawList, Vec<DrawUniform>) {
        let [image_walls, image_slices] = image_on;
        let scene = &frame.scene;
        let mut list = DrawList::default();
        let mut uniforms: Vec<DrawUniform> = Vec::new();
        let mut push_uniform = |color: [f32; 3], opacity: f32, lit: bool, width: f32, bias: f32| {
            uniforms.push(DrawUniform {
                color: [
                    srgb_to_linear(color[0]),
                    srgb_to_linear(color[1]),
                    srgb_to_linear(color[2]),
                    opacity,
                ],
                params: [BACK_FACE, if lit { 1.0 } else { 0.0 }, width, bias],
            });
            (uniforms.len() - 1) as u32
        };
        let radius = 0.5 * self.scene_bbox.diagonal().max(1e-9);
        let contour_bias = (radius * 0.004) as f32;

        // Preview parts.
        // Edit mode shows the live cut under the cutters when the GUI provides one.
        let preview = if matches!(frame.mode, ViewMode::Preview | ViewMode::Edit) {
            frame.preview.clone()
        } else {
            None
        };
        if let Some(p) = &preview {
            let stale = self
                .preview
                .as_ref()
                .is_none_or(|c| !c.preview.upgrade().is_some_and(|q| Arc::ptr_eq(&q, p)));
            if stale {
                let cache = upload_preview(device, p);
                for part in &cache.parts {
                    self.uploads.mesh(part.as_ref());
                }
                for c in cache.contours.values() {
                    self.uploads.segments(Some(c));
                }
                self.preview = Some(cache);
            }
        } else {
            // Nothing to show: the last preview's buffers go now, not when the next one comes
            // (a model-sized kept part would otherwise stay on the GPU through Camera mode).
            self.preview = None;
        }
        let replaced = |m: usize| {
            preview
                .as_ref()
                .is_some_and(|p| p.replaced.get(m).copied().unwrap_or(false))
        };

        // Models (uncut, or the kept parts of cut ones).
        for (index, model) in scene.models.iter().enumerate() {
            let delta = frame
                .deltas
                .iter()
                .find(|d| Arc::ptr_eq(&d.base, &model.mesh));
            if !model.visible || model.opacity <= 0.0 || (replaced(index) && delta.is_none()) {
                continue;
            }
            let key = Arc::as_ptr(&model.mesh) as usize;
            let fresh = self.models.get(&key).is_some_and(|c| {
                c.mesh
                    .upgrade()
                    .is_some_and(|m| Arc::ptr_eq(&m, &model.mesh))
            });
            if !fresh {
                let gpu = GpuMesh::upload(device, &model.name, &model.mesh);
                self.uploads.mesh(gpu.as_ref());
                self.models.insert(
                    key,
                    CachedMesh {
                        mesh: Arc::downgrade(&model.mesh),
                        gpu,
                        last_used: 0,
                        hidden: Vec::new(),
                        hidden_for: None,
                    },
                );
            }
            let Some(cached) = self.models.get_mut(&key) else {
                continue;
            };
            cached.last_used = self.frame_index;
            if cached.gpu.is_none() {
                continue;
            }
            // Hide the faces the delta replaces (or show them again when it is gone).
            let same = match (&cached.hidden_for, delta) {
                (Some(w), Some(d)) => w.upgrade().is_some_and(|x| Arc::ptr_eq(&x, d)),
                (None, None) => true,
                _ => false,
            };
            if !same {
                let wanted: &[u32] = delta.map_or(&[], |d| &d.hidden);
                let words = hidden_patches(&model.mesh, &cached.hidden, wanted);
                self.uploads.bytes += (words.len() * size_of::<[u32; 2]>()) as u64;
                self.uploads.triangles += (words.len() / 3) as u64;
                if !words.is_empty() {
                    self.patches.push(IndexPatch { key, words });
                }
                cached.hidden = wanted.to_vec();
                cached.hidden_for = delta.map(Arc::downgrade);
            }
            let delta_key = delta.map(|d| {
                let dkey = Arc::as_ptr(d) as usize;
                let fresh = self
                    .deltas
                    .get(&dkey)
                    .is_some_and(|c| c.delta.upgrade().is_some_and(|x| Arc::ptr_eq(&x, d)));
                if !fresh {
                    let gpu = GpuMesh::upload_vertices(
                        device,
                        &format!("{} patch", model.name),
                        &d.vertices,
                        &d.patch.triangles,
                    );
                    self.uploads.mesh(gpu.as_ref());
                    self.deltas.insert(
                        dkey,
                        CachedDelta {
                            delta: Arc::downgrade(d),
                            gpu,
                            last_used: 0,
                        },
                    );
                }
                if let Some(c) = self.deltas.get_mut(&dkey) {
                    c.last_used = self.frame_index;
                }
                (dkey, d)
            });
            let mut sources = vec![Source::Model(key)];
            sources.extend(delta_key.map(|(k, _)| Source::Delta(k)));
            match model.style {
                ModelStyle::Solid => {
                    let u = push_uniform(model.color, model.opacity, true, 0.0, 0.0);
                    for source in sources {
                        if model.opacity < 1.0 {
                            list.transparent.push(Draw::Mesh(source, u));
                        } else {
                            list.opaque.push(Draw::Mesh(source, u));
                        }
                    }
                }
                ModelStyle::Wireframe => {
                    // The base's edges include those of hidden faces: a wireframe under a
                    // delta shows the old edges too until the change is committed.
                    if let Some(gpu) = self.models.get_mut(&key).and_then(|c| c.gpu.as_mut()) {
                        let had = gpu.edges.is_some();
                        gpu.ensure_edges(device, &model.name, &model.mesh);
                        if !had {
                            self.uploads.segments(gpu.edges.as_ref());
                        }
                    }
                    if let Some((k, d)) = delta_key
                        && let Some(gpu) = self.deltas.get_mut(&k).and_then(|c| c.gpu.as_mut())
                    {
                        let had = gpu.edges.is_some();
                        gpu.ensure_edges(device, &model.name, &d.patch);
                        if !had {
                            self.uploads.segments(gpu.edges.as_ref());
                        }
                    }
                    let u = push_uniform(model.color, 1.0, false, WIREFRAME_WIDTH_PX, 0.0);
                    for source in sources {
                        list.opaque.push(Draw::Edges(source, u));
                    }
                }
            }
        }

        if let (Some(p), Some(cache)) = (&preview, self.preview.as_mut()) {
            for (i, part) in p.parts.iter().enumerate() {
                let Some(model) = scene.models.get(part.model) else {
                    continue;
                };
                if !model.visible {
                    continue;
                }
                let Some(gpu) = cache.parts.get_mut(i).and_then(|g| g.as_mut()) else {
                    continue;
                };
                let wall = mix(model.color, WALL_TINT, WALL_MIX);
                match part.kind {
                    PartKind::Kept => match model.style {
                        ModelStyle::Solid if model.opacity <= 0.0 => {}
                        ModelStyle::Solid => {
                            let u = push_uniform(model.color, model.opacity, true, 0.0, 0.0);
                            if model.opacity < 1.0 {
                                list.transparent.push(Draw::Mesh(Source::Part(i), u));
                            } else {
                                list.opaque.push(Draw::Mesh(Source::Part(i), u));
                            }
                        }
                        ModelStyle::Wireframe => {
                            gpu.ensure_edges(device, &model.name, &part.mesh);
                            let u = push_uniform(model.color, 1.0, false, WIREFRAME_WIDTH_PX, 0.0);
                            list.opaque.push(Draw::Edges(Source::Part(i), u));
                        }
                    },
                    PartKind::Wall | PartKind::SliceWall => {
                        let u = push_uniform(wall, 1.0, true, 0.0, 0.0);
                        let image =
                            image_walls || (part.kind == PartKind::SliceWall && image_slices);
                        list.opaque.push(if image {
                            Draw::ImageMesh(Source::Part(i), u)
                        } else {
                            Draw::Mesh(Source::Part(i), u)
                        });
                    }
                    PartKind::Ribbon => {
                        let u = push_uniform(model.color, 1.0, true, 0.0, 0.0);
                        list.opaque.push(if image_slices {
                            Draw::ImageMesh(Source::Part(i), u)
                        } else {
                            Draw::Mesh(Source::Part(i), u)
                        });
                    }
                    PartKind::Removed => {
                        let u = push_uniform(model.color, part.opacity, true, 0.0, 0.0);
                        list.transparent.push(Draw::Mesh(Source::Part(i), u));
                    }
                }
            }
            let mut models: Vec<usize> = cache.contours.keys().copied().collect();
            models.sort_unstable();
            for m in models {
                if scene.models.get(m).is_some_and(|model| model.visible) {
                    let u = push_uniform(CONTOUR_COLOR, 1.0, false, CONTOUR_WIDTH_PX, contour_bias);
                    list.opaque.push(Draw::Contour(m, u));
                }
            }
        }

        // Cutter overlays (Edit mode), re-uploaded every frame: they change while dragging.
        self.overlay_meshes.clear();
        self.overlay_lines.clear();
        if frame.mode == ViewMode::Edit {
            for (k, overlay) in frame.overlays.iter().enumerate() {
                let surface = GpuMesh::upload(device, "cutter overlay surface", &overlay.surface);
                if surface.is_some() {
                    let opacity = if overlay.active { 0.35 } else { 0.22 };
                    // Pushed a little away from the eye: where the cutter coincides with the
                    // walls it cut, the walls win (no z-fighting, the live cut looks like the
                    // committed one); where it sticks out of the target it shows as a shell.
                    let u = push_uniform(CUTTER_FILL, opacity, true, 0.0, -contour_bias);
                    list.transparent
                        .push(Draw::Mesh(Source::Overlay(self.overlay_meshes.len()), u));
                    self.overlay_meshes.push(surface);
                }
                let outline = GpuSegments::upload(
                    device,
                    &format!("cutter {k} outline"),
                    &cutter_outline_segments(&overlay.planes),
                );
                if outline.is_some() {
                    let width = if overlay.active { 1.5 } else { 1.0 };
                    let u = push_uniform(CUTTER_OUTLINE, 0.85, false, width, 0.0);
                    list.overlay.push(Draw::Lines(self.overlay_lines.len(), u));
                    self.overlay_lines.push(outline);
                }
                if let Some(plane) = overlay
                    .highlighted_plane
                    .and_then(|i| overlay.planes.get(i))
                {
                    let quad = Mesh {
                        positions: plane.to_vec(),
                        triangles: vec![[0, 1, 2], [0, 2, 3]],
                    };
                    let u = push_uniform(HIGHLIGHT, 0.55, false, 0.0, 0.0);
                    list.transparent
                        .push(Draw::Mesh(Source::Overlay(self.overlay_meshes.len()), u));
                    self.overlay_meshes
                        .push(GpuMesh::upload(device, "highlighted plane", &quad));
                    let u = push_uniform(HIGHLIGHT, 1.0, false, 3.0, 0.0);
                    list.overlay.push(Draw::Lines(self.overlay_lines.len(), u));
                    self.overlay_lines.push(GpuSegments::upload(
                        device,
                        "highlighted plane outline",
                        &cutter_outline_segments(std::slice::from_ref(plane)),
                    ));
                }
            }
            for m in self.overlay_meshes.iter().flatten() {
                self.uploads.mesh(Some(m));
            }
            for l in self.overlay_lines.iter().flatten() {
                self.uploads.segments(Some(l));
            }
        }
        (list, uniforms)
    }

    fn mesh(&self, source: Source) -> Option<&GpuMesh> {
        match source {
            Source::Model(key) => self.models.get(&key)?.gpu.as_ref(),
            Source::Part(i) => self.preview.as_ref()?.parts.get(i)?.as_ref(),
            Source::Overlay(i) => self.overlay_meshes.get(i)?.as_ref(),
            Source::Delta(key) => self.deltas.get(&key)?.gpu.as_ref(),
        }
    }

    fn segments(&self, draw: Draw) -> Option<&GpuSegments> {
        match draw {
            Draw::Edges(source, _) => self.mesh(source)?.edges.as_ref(),
            Draw::Contour(model, _) => self.preview.as_ref()?.contours.get(&model),
            Draw::Lines(i, _) => self.overlay_lines.get(i)?.as_ref(),
            Draw::Mesh(..) | Draw::ImageMesh(..) => None,
        }
    }

    fn encode_eye(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        eye: usize,
        clear: wgpu::Color,
        draws: &DrawList,
    ) {
        let Some(targets) = &self.targets else { return };
        let frame_offset = (eye as u64 * DRAW_UNIFORM_STRIDE) as u32;
        let color_view = &targets.color_views[eye];
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("cutaway opaque pass"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: color_view,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(clear),
                        store: wgpu::StoreOp::Store,
                    },
                    depth_slice: None,
                })],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &targets.depth_view,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(1.0),
                        store: wgpu::StoreOp::Store,
                    }),
                    stencil_ops: None,
                }),
                occlusion_query_set: None,
                timestamp_writes: None,
                multiview_mask: None,
            });
            pass.set_bind_group(0, &self.frame_bind_group, &[frame_offset]);
            self.draw_all(&mut pass, &draws.opaque, false);
        }
        if !draws.transparent.is_empty() {
            {
                let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some("cutaway transparency pass"),
                    color_attachments: &[
                        Some(wgpu::RenderPassColorAttachment {
                            view: &targets.accum_view,
                            resolve_target: None,
                            ops: wgpu::Operations {
                                load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                                store: wgpu::StoreOp::Store,
                            },
                            depth_slice: None,
                        }),
                        Some(wgpu::RenderPassColorAttachment {
                            view: &targets.revealage_view,
                            resolve_target: None,
                            ops: wgpu::Operations {
                                load: wgpu::LoadOp::Clear(wgpu::Color::WHITE),
                                store: wgpu::StoreOp::Store,
                            },
                            depth_slice: None,
                        }),
                    ],
                    depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                        view: &targets.depth_view,
                        depth_ops: Some(wgpu::Operations {
                            load: wgpu::LoadOp::Load,
                            store: wgpu::StoreOp::Store,
                        }),
                        stencil_ops: None,
                    }),
                    occlusion_query_set: None,
                    timestamp_writes: None,
                    multiview_mask: None,
                });
                pass.set_bind_group(0, &self.frame_bind_group, &[frame_offset]);
                self.draw_all(&mut pass, &draws.transparent, true);
            }
        }
        if !draws.transparent.is_empty() || !draws.overlay.is_empty() {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("cutaway composite pass"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: color_view,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Load,
                        store: wgpu::StoreOp::Store,
                    },
                    depth_slice: None,
                })],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &targets.depth_view,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Load,
                        store: wgpu::StoreOp::Store,
                    }),
                    stencil_ops: None,
                }),
                occlusion_query_set: None,
                timestamp_writes: None,
                multiview_mask: None,
            });
            if !draws.transparent.is_empty() {
                pass.set_pipeline(&self.pipelines.composite);
                pass.set_bind_group(0, &targets.composite_bind_group, &[]);
                pass.draw(0..3, 0..1);
            }
            if !draws.overlay.is_empty() {
                pass.set_bind_group(0, &self.frame_bind_group, &[frame_offset]);
                self.draw_all(&mut pass, &draws.overlay, false);
            }
        }
    }

    fn draw_all(&self, pass: &mut wgpu::RenderPass<'_>, draws: &[Draw], transparent: bool) {
        for &draw in draws {
            match draw {
                Draw::Mesh(source, u) | Draw::ImageMesh(source, u) => {
                    let Some(mesh) = self.mesh(source) else {
                        continue;
                    };
                    let image = matches!(draw, Draw::ImageMesh(..)) && self.image.bind(pass);
                    if !image {
                        pass.set_pipeline(if transparent {
                            &self.pipelines.mesh_oit
                        } else {
                            &self.pipelines.mesh_opaque
                        });
                    }
                    pass.set_bind_group(
                        1,
                        &self.draw_bind_group,
                        &[u * DRAW_UNIFORM_STRIDE as u32],
                    );
                    pass.set_vertex_buffer(0, mesh.vertex_buffer.slice(..));
                    pass.set_index_buffer(mesh.index_buffer.slice(..), wgpu::IndexFormat::Uint32);
                    pass.draw_indexed(0..mesh.index_count, 0, 0..1);
                }
                Draw::Edges(_, u) | Draw::Contour(_, u) | Draw::Lines(_, u) => {
                    let Some(segments) = self.segments(draw) else {
                        continue;
                    };
                    pass.set_pipeline(if matches!(draw, Draw::Lines(..)) {
                        &self.pipelines.lines_overlay
                    } else {
                        &self.pipelines.lines_opaque
                    });
                    pass.set_bind_group(
                        1,
                        &self.draw_bind_group,
                        &[u * DRAW_UNIFORM_STRIDE as u32],
                    );
                    pass.set_vertex_buffer(0, segments.buffer.slice(..));
                    pass.draw(0..6, 0..segments.count);
                }
            }
        }
    }

    /// `Scene::bbox` of the frame's scene with each mesh's box computed once, and each model
    /// drawn with a delta grown by its patch (a scalpel step can open a cut a little past the
    /// mesh's old box; what a delta hides lies inside the base's box anyway).
    fn scene_bbox(&mut self, frame: &FrameInputs) -> csg::Aabb {
        self.bboxes.retain(|_, (w, _)| w.strong_count() > 0);
        let mut visible = csg::Aabb::EMPTY;
        let mut all = csg::Aabb::EMPTY;
        for model in &frame.scene.models {
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
    /// not draw them: each change makes a new one.
    fn evict(&mut self) {
        let now = self.frame_index;
        self.models.retain(|_, c| {
            c.mesh.strong_count() > 0 && now.saturating_sub(c.last_used) <= CACHE_FRAMES
        });
        self.deltas
            .retain(|_, c| c.delta.strong_count() > 0 && c.last_used == now);
    }

    /// Writes this frame's index patches (hidden faces) with the scatter compute shader, before
    /// the render passes that read the index buffers. Each patch list names every word once.
    fn apply_patches(&mut self, device: &wgpu::Device, encoder: &mut wgpu::CommandEncoder) {
        let patches = std::mem::take(&mut self.patches);
        if patches.is_empty() {
            return;
        }
        // A storage binding may be smaller than a big model's index buffer: bind it in windows
        // (a multiple of 256 bytes long, the offset alignment).
        let limit = device.limits().max_storage_buffer_binding_size;
        let window_words = ((limit / 4) & !63).max(64);
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("cutaway hide faces"),
            timestamp_writes: None,
        });
        pass.set_pipeline(&self.pipelines.scatter);
        for patch in &patches {
            let Some(gpu) = self.models.get(&patch.key).and_then(|c| c.gpu.as_ref()) else {
                continue;
            };
            let total_words = gpu.index_buffer.size() / 4;
            for run in patch
                .words
                .chunk_by(|a, b| u64::from(a[0]) / window_words == u64::from(b[0]) / window_words)
            {
                let window = u64::from(run[0][0]) / window_words;
                let first = window * window_words;
                let len = window_words.min(total_words - first);
                let relative: Vec<[u32; 2]> = run
                    .iter()
                    .map(|&[w, v]| [(u64::from(w) - first) as u32, v])
                    .collect();
                let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("cutaway index patches"),
                    contents: bytemuck::cast_slice(&relative),
                    usage: wgpu::BufferUsages::STORAGE,
                });
                let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("cutaway scatter bind group"),
                    layout: &self.pipelines.scatter_layout,
                    entries: &[
                        wgpu::BindGroupEntry {
                            binding: 0,
                            resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                                buffer: &gpu.index_buffer,
                                offset: first * 4,
                                size: wgpu::BufferSize::new(len * 4),
                            }),
                        },
                        wgpu::BindGroupEntry {
                            binding: 1,
                            resource: buffer.as_entire_binding(),
                        },
                    ],
                });
                pass.set_bind_group(0, &bind_group, &[]);
                let groups = (relative.len() as u32).div_ceil(SCATTER_GROUP);
                pass.dispatch_workgroups(
                    groups.min(SCATTER_ROW_GROUPS),
                    groups.div_ceil(SCATTER_ROW_GROUPS),
                    1,
                );
            }
        }
    }
}

#[derive(Default)]
struct DrawList {
    opaque: Vec<Draw>,
    transparent: Vec<Draw>,
    /// Drawn after the transparency composite, with no depth test.
    overlay: Vec<Draw>,
}

/// The index words that turn the hidden faces `old` into `new` (both ascending): a face no
/// longer hidden gets its three indices back from `mesh`, a newly hidden one becomes the
/// degenerate triangle at its first corner (no pixels). Proportional to the two lists.
fn hidden_patches(mesh: &Mesh, old: &[u32], new: &[u32]) -> Vec<[u32; 2]> {
    let mut out = Vec::new();
    let (mut i, mut j) = (0, 0);
    let emit = |f: u32, show: bool, out: &mut Vec<[u32; 2]>| {
        let Some(tri) = mesh.triangles.get(f as usize) else {
            return;
        };
        for k in 0..3 {
            let value = if show { tri[k] } else { tri[0] };
            out.push([3 * f + k as u32, value]);
        }
    };
    while i < old.len() || j < new.len() {
        match (old.get(i), new.get(j)) {
            (Some(&a), Some(&b)) if a == b => {
                i += 1;
                j += 1;
            }
            (Some(&a), Some(&b)) if a < b => {
                emit(a, true, &mut out);
                i += 1;
            }
            (Some(&a), None) => {
                emit(a, true, &mut out);
                i += 1;
            }
            (_, Some(&b)) => {
                emit(b, false, &mut out);
                j += 1;
            }
            (None, None) => break,
        }
    }
    out
}

fn upload_preview(device: &wgpu::Device, preview: &Arc<PreviewGeometry>) -> CachedPreview {
    let parts = preview
        .parts
        .iter()
        .map(|p| {
            GpuMesh::upload(
                device,
                &format!("preview part {:?} of model {}", p.kind, p.model),
                &p.mesh,
            )
        })
        .collect();
    let mut by_model: HashMap<usize, Vec<&[DVec3]>> = HashMap::new();
    for (model, line) in &preview.contours {
        by_model.entry(*model).or_default().push(line);
    }
    let contours = by_model
        .into_iter()
        .filter_map(|(model, lines)| {
            let segments = polyline_segments(lines);
            GpuSegments::upload(device, &format!("contour of model {model}"), &segments)
                .map(|s| (model, s))
        })
        .collect();
    CachedPreview {
        preview: Arc::downgrade(preview),
        parts,
        contours,
    }
}

fn uniform_bind_group(
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

fn draw_buffer(
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

fn mix(a: [f32; 3], b: [f32; 3], t: f32) -> [f32; 3] {
    [0, 1, 2].map(|k| a[k] + (b[k] - a[k]) * t)
}

/// The full image size (the tile's image, or the frame itself).
fn full_size(frame: &FrameInputs) -> [u32; 2] {
    frame.tile.map_or(frame.size, |t| t.full_size)
}

/// Near and far distances that enclose everything drawn, and the scene radius.
fn depth_range(frame: &FrameInputs, scene_bbox: csg::Aabb) -> (f64, f64, f64) {
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
    let radius = (0.5 * bbox.diagonal()).max(1e-6);
    // The anaglyph eyes sit a little off the camera.
    let distance =
        (bbox.center() - frame.camera.eye).length() + EYE_SEPARATION * frame.camera.distance();
    let far = distance + radius * 1.05;
    let near = (distance - radius * 1.05).max(far * 1e-4);
    (near, far, radius)
}

/// The camera of each eye: the scene camera, or two toed-in cameras for the anaglyph.
fn eye_cameras(frame: &FrameInputs) -> Vec<cutter::Camera> {
    let camera = frame.camera;
    if frame.scene.render.stereo != Stereo::Anaglyph {
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

fn frame_uniform(
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
