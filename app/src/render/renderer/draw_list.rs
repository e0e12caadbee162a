//! What a frame draws: uploads what is new (model meshes, a preview's parts and contours, delta
//! patches, the cutter overlays of Edit mode) into the renderer's caches and lists each draw with
//! its uniform (colour, opacity, line width), sorted into the opaque, transparent and overlay
//! passes. The one place that decides how each kind of geometry looks; the passes only replay
//! the list.

use std::collections::HashMap;
use std::sync::{Arc, Weak};

use csg::Mesh;
use glam::DVec3;

use super::index_patches::{IndexPatch, hidden_patches};
use super::staging::Staging;
use super::{
    BACK_FACE, CONTOUR_COLOR, CONTOUR_OFFSET, CONTOUR_WIDTH_PX, CachedDelta, CachedMesh, Renderer,
    WALL_MIX, WALL_TINT,
};
use crate::cutting::wall_risk::WallRisk;
use crate::cutting::wall_split;
use crate::render::draw_data::{
    GpuMesh, GpuSegments, cutter_outline_segments, polyline_segments, risk_vertices,
};
use crate::render::gpu_data::DrawUniform;
use crate::render::{CutDrawing, DrawStyle, FrameInputs, PartLook, ViewMode, srgb_to_linear};

const WIREFRAME_WIDTH_PX: f32 = 1.0;
/// Cutter overlay colours (sRGB) and opacities.
const CUTTER_FILL: [f32; 3] = [0.35, 0.6, 0.95];
const CUTTER_OUTLINE: [f32; 3] = [0.08, 0.28, 0.75];
const HIGHLIGHT: [f32; 3] = [1.0, 0.55, 0.1];

pub(super) struct CachedPreview {
    pub(super) preview: Weak<dyn CutDrawing>,
    /// One per part of the cut.
    pub(super) parts: Vec<Option<GpuMesh>>,
    /// Per model: its contour polylines.
    pub(super) contours: HashMap<usize, GpuSegments>,
}

/// The refined walls of a risk map, uploaded.
pub(super) struct CachedRisk {
    pub(super) risk: Weak<WallRisk>,
    /// One per `WallRisk::walls` entry.
    pub(super) walls: Vec<Option<GpuMesh>>,
}

/// What one draw call draws.
#[derive(Clone, Copy)]
pub(super) enum Source {
    /// A scene model's mesh, by cache key.
    Model(usize),
    /// Part `i` of the cut.
    Part(usize),
    /// The patch of a [`MeshDelta`](crate::cutting::delta::MeshDelta), by cache key.
    Delta(usize),
    /// A per-frame overlay mesh.
    Overlay(usize),
    /// `WallRisk::walls[i]` of the frame's risk map.
    Risk(usize),
}

#[derive(Clone, Copy)]
pub(super) enum Draw {
    Mesh(Source, u32),
    /// A mesh showing the intensity image ([`crate::render::image_layer`]).
    ImageMesh(Source, u32),
    /// A wall coloured by the risk map ([`crate::render::risk_layer`]); true: beyond the far
    /// distance it shows the image.
    RiskMesh(Source, u32, bool),
    Edges(Source, u32),
    Contour(usize, u32),
    Lines(usize, u32),
}

#[derive(Default)]
pub(super) struct DrawList {
    pub(super) opaque: Vec<Draw>,
    pub(super) transparent: Vec<Draw>,
    /// Drawn after the transparency composite, with no depth test.
    pub(super) overlay: Vec<Draw>,
}

impl Renderer {
    /// Uploads what is missing and lists the draws of the frame with their uniforms.
    /// `image_on`: whether walls, and slices and ribbons, show the image.
    pub(super) fn upload_and_list(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        frame: &FrameInputs,
        image_on: [bool; 2],
    ) -> (DrawList, Vec<DrawUniform>) {
        let [image_walls, image_slices] = image_on;
        let models = &frame.models;
        let mut list = DrawList::default();
        let mut uniforms: Vec<DrawUniform> = Vec::new();
        let mut push_uniform = |color: [f32; 3], opacity: f32, lit: bool, width: f32, bias: f32| {
            // Incision walls of a mesh (scalpel grooves) in the colour the cut's walls have.
            let wall = mix(color, WALL_TINT, WALL_MIX);
            uniforms.push(DrawUniform {
                color: [
                    srgb_to_linear(color[0]),
                    srgb_to_linear(color[1]),
                    srgb_to_linear(color[2]),
                    opacity,
                ],
                params: [BACK_FACE, if lit { 1.0 } else { 0.0 }, width, bias],
                wall_color: [
                    srgb_to_linear(wall[0]),
                    srgb_to_linear(wall[1]),
                    srgb_to_linear(wall[2]),
                    1.0,
                ],
            });
            (uniforms.len() - 1) as u32
        };
        let radius = 0.5 * self.scene_bbox.diagonal().max(1e-9);
        let contour_bias = (radius * CONTOUR_OFFSET) as f32;

        // Preview parts.
        // Edit mode shows the live cut under the cutters when the GUI provides one.
        let preview = if matches!(frame.mode, ViewMode::Preview | ViewMode::Edit) {
            frame.cut.clone()
        } else {
            None
        };
        if let Some(p) = &preview {
            let stale = self
                .preview
                .as_ref()
                .is_none_or(|c| !c.preview.upgrade().is_some_and(|q| same_cut(&q, p)));
            if stale {
                let cache = upload_preview(device, queue, &mut self.staging, p);
                for part in &cache.parts {
                    self.uploads.mesh(part.as_ref());
                }
                for c in cache.contours.values() {
                    self.uploads.segments(Some(c));
                }
                if self.preview.is_some() {
                    // The app dropped the old preview's meshes when it made this one.
                    self.free_pages.note_large_free();
                }
                self.preview = Some(cache);
            }
        } else {
            // Nothing to show: the last preview's buffers go now, not when the next one comes
            // (a model-sized kept part would otherwise stay on the GPU through Camera mode).
            if self.preview.take().is_some() {
                self.free_pages.note_large_free();
            }
        }
        // The risk map's walls, drawn in place of the preview's walls they were refined from.
        let risk = frame.risk.clone().filter(|_| preview.is_some());
        match &risk {
            Some(r) => {
                let stale = self
                    .risk
                    .as_ref()
                    .is_none_or(|c| !c.risk.upgrade().is_some_and(|q| Arc::ptr_eq(&q, r)));
                if stale {
                    let walls: Vec<Option<GpuMesh>> = (0..r.walls.len())
                        .map(|j| {
                            let cut = preview.as_ref()?;
                            let source =
                                (0..cut.part_count()).find(|&i| cut.risk_wall(r, i) == Some(j))?;
                            let (vertices, triangles) =
                                risk_vertices(&r.walls[j], r, cut.part(source).mesh);
                            let gpu = GpuMesh::upload_vertices(
                                device,
                                "risk map wall",
                                &vertices,
                                &triangles,
                            );
                            let bytes = gpu.as_ref().map_or(0, GpuMesh::byte_size);
                            self.staging.uploaded(device, queue, bytes);
                            gpu
                        })
                        .collect();
                    for w in &walls {
                        self.uploads.mesh(w.as_ref());
                    }
                    self.risk = Some(CachedRisk {
                        risk: Arc::downgrade(r),
                        walls,
                    });
                }
            }
            None => self.risk = None,
        }
        let replaced = |m: usize| preview.as_ref().is_some_and(|p| p.replaced(m));

        // Models (uncut, or the kept parts of cut ones).
        for (index, model) in models.iter().enumerate() {
            let delta = frame
                .deltas
                .iter()
                .find(|d| Arc::ptr_eq(&d.base, &model.mesh));
            if !model.visible || model.opacity <= 0.0 || (replaced(index) && delta.is_none()) {
                continue;
            }
            let key = Arc::as_ptr(&model.mesh) as usize;
            let walls = model.wall_faces();
            let walls_id = (walls.as_ptr() as usize, walls.len());
            let fresh = self.models.get(&key).is_some_and(|c| {
                c.walls == walls_id
                    && c.mesh
                        .upgrade()
                        .is_some_and(|m| Arc::ptr_eq(&m, &model.mesh))
            });
            if !fresh {
                let gpu = if walls.is_empty() {
                    GpuMesh::upload(device, &model.name, &model.mesh)
                } else {
                    // Incision walls on vertices of their own: a hard edge at the lips.
                    let drawn = wall_split::drawn(&model.mesh, walls);
                    GpuMesh::upload_vertices(device, &model.name, &drawn.vertices, &drawn.triangles)
                };
                self.uploads.mesh(gpu.as_ref());
                let bytes = gpu.as_ref().map_or(0, GpuMesh::byte_size);
                self.staging.uploaded(device, queue, bytes);
                self.models.insert(
                    key,
                    CachedMesh {
                        mesh: Arc::downgrade(&model.mesh),
                        gpu,
                        last_used: 0,
                        edges_drawn: 0,
                        hidden: Vec::new(),
                        hidden_for: None,
                        walls: walls_id,
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
                let triangle = |f: u32| wall_split::drawn_triangle(&model.mesh, walls, f);
                let words = hidden_patches(&triangle, &cached.hidden, wanted);
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
                        &d.triangles,
                    );
                    self.uploads.mesh(gpu.as_ref());
                    let bytes = gpu.as_ref().map_or(0, GpuMesh::byte_size);
                    self.staging.uploaded(device, queue, bytes);
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
                DrawStyle::Solid => {
                    let u = push_uniform(model.color, model.opacity, true, 0.0, 0.0);
                    for source in sources {
                        if model.opacity < 1.0 {
                            list.transparent.push(Draw::Mesh(source, u));
                        } else {
                            list.opaque.push(Draw::Mesh(source, u));
                        }
                    }
                }
                DrawStyle::Wireframe => {
                    // The base's edges include those of hidden faces: a wireframe under a
                    // delta shows the old edges too until the change is committed.
                    let frame_index = self.frame_index;
                    if let Some(cached) = self.models.get_mut(&key)
                        && let Some(gpu) = cached.gpu.as_mut()
                    {
                        cached.edges_drawn = frame_index;
                        let had = gpu.edges.is_some();
                        gpu.ensure_edges(device, &model.name, &model.mesh);
                        if !had {
                            self.uploads.segments(gpu.edges.as_ref());
                            let bytes = gpu.edges.as_ref().map_or(0, GpuSegments::byte_size);
                            self.staging.uploaded(device, queue, bytes);
                            // Finding the edges went through a model-sized hash set.
                            self.free_pages.note_large_free();
                        }
                    }
                    if let Some((k, d)) = delta_key
                        && let Some(gpu) = self.deltas.get_mut(&k).and_then(|c| c.gpu.as_mut())
                    {
                        let had = gpu.edges.is_some();
                        gpu.ensure_edges(device, &model.name, &d.patch);
                        if !had {
                            self.uploads.segments(gpu.edges.as_ref());
                            let bytes = gpu.edges.as_ref().map_or(0, GpuSegments::byte_size);
                            self.staging.uploaded(device, queue, bytes);
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
            for i in 0..p.part_count() {
                let part = p.part(i);
                let Some(model) = models.get(part.model) else {
                    continue;
                };
                if !model.visible {
                    continue;
                }
                let Some(gpu) = cache.parts.get_mut(i).and_then(|g| g.as_mut()) else {
                    continue;
                };
                let wall = mix(model.color, WALL_TINT, WALL_MIX);
                match part.look {
                    PartLook::Kept => match model.style {
                        DrawStyle::Solid if model.opacity <= 0.0 => {}
                        DrawStyle::Solid => {
                            let u = push_uniform(model.color, model.opacity, true, 0.0, 0.0);
                            if model.opacity < 1.0 {
                                list.transparent.push(Draw::Mesh(Source::Part(i), u));
                            } else {
                                list.opaque.push(Draw::Mesh(Source::Part(i), u));
                            }
                        }
                        DrawStyle::Wireframe => {
                            if gpu.edges.is_none() {
                                gpu.ensure_edges(device, &model.name, part.mesh);
                                let bytes = gpu.edges.as_ref().map_or(0, GpuSegments::byte_size);
                                self.staging.uploaded(device, queue, bytes);
                                self.free_pages.note_large_free();
                            }
                            let u = push_uniform(model.color, 1.0, false, WIREFRAME_WIDTH_PX, 0.0);
                            list.opaque.push(Draw::Edges(Source::Part(i), u));
                        }
                    },
                    PartLook::Wall | PartLook::SliceWall | PartLook::Incisions => {
                        // What a cut left of the model's scalpel incisions is uploaded as
                        // incision walls (see `upload_preview`): the model's colour, shaded as
                        // the uncut model's incisions are.
                        let colour = if part.look == PartLook::Incisions {
                            model.color
                        } else {
                            wall
                        };
                        let u = push_uniform(colour, 1.0, true, 0.0, 0.0);
                        let warned = risk.as_ref().and_then(|r| p.risk_wall(r, i));
                        if let Some(j) = warned {
                            list.opaque
                                .push(Draw::RiskMesh(Source::Risk(j), u, image_walls));
                            continue;
                        }
                        let image =
                            image_walls || (part.look == PartLook::SliceWall && image_slices);
                        list.opaque.push(if image {
                            Draw::ImageMesh(Source::Part(i), u)
                        } else {
                            Draw::Mesh(Source::Part(i), u)
                        });
                    }
                    PartLook::Ribbon => {
                        let u = push_uniform(model.color, 1.0, true, 0.0, 0.0);
                        list.opaque.push(if image_slices {
                            Draw::ImageMesh(Source::Part(i), u)
                        } else {
                            Draw::Mesh(Source::Part(i), u)
                        });
                    }
                    PartLook::Removed => {
                        let u = push_uniform(model.color, part.opacity, true, 0.0, 0.0);
                        list.transparent.push(Draw::Mesh(Source::Part(i), u));
                    }
                }
            }
            let mut models: Vec<usize> = cache.contours.keys().copied().collect();
            models.sort_unstable();
            for m in models {
                if frame.models.get(m).is_some_and(|model| model.visible) {
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

    pub(super) fn mesh(&self, source: Source) -> Option<&GpuMesh> {
        match source {
            Source::Model(key) => self.models.get(&key)?.gpu.as_ref(),
            Source::Part(i) => self.preview.as_ref()?.parts.get(i)?.as_ref(),
            Source::Overlay(i) => self.overlay_meshes.get(i)?.as_ref(),
            Source::Delta(key) => self.deltas.get(&key)?.gpu.as_ref(),
            Source::Risk(i) => self.risk.as_ref()?.walls.get(i)?.as_ref(),
        }
    }

    pub(super) fn segments(&self, draw: Draw) -> Option<&GpuSegments> {
        match draw {
            Draw::Edges(source, _) => self.mesh(source)?.edges.as_ref(),
            Draw::Contour(model, _) => self.preview.as_ref()?.contours.get(&model),
            Draw::Lines(i, _) => self.overlay_lines.get(i)?.as_ref(),
            Draw::Mesh(..) | Draw::ImageMesh(..) | Draw::RiskMesh(..) => None,
        }
    }
}

fn upload_preview(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    staging: &mut Staging,
    preview: &Arc<dyn CutDrawing>,
) -> CachedPreview {
    let parts = (0..preview.part_count())
        .map(|i| {
            let p = preview.part(i);
            let label = format!("preview part {:?} of model {}", p.look, p.model);
            let gpu = if p.look == PartLook::Incisions {
                // Every face an incision wall: drawn as on the uncut model (the wall flag, the
                // walls' own normals with the crease at the groove's floor).
                let all: Vec<u32> = (0..p.mesh.triangles.len() as u32).collect();
                let drawn = wall_split::drawn(p.mesh, &all);
                GpuMesh::upload_vertices(device, &label, &drawn.vertices, &drawn.triangles)
            } else {
                GpuMesh::upload(device, &label, p.mesh)
            };
            staging.uploaded(device, queue, gpu.as_ref().map_or(0, GpuMesh::byte_size));
            gpu
        })
        .collect();
    let mut by_model: HashMap<usize, Vec<&[DVec3]>> = HashMap::new();
    for (model, line) in preview.contours() {
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

/// Whether two handles hold the same cut (the same allocation; vtables are not compared).
fn same_cut(a: &Arc<dyn CutDrawing>, b: &Arc<dyn CutDrawing>) -> bool {
    std::ptr::addr_eq(Arc::as_ptr(a), Arc::as_ptr(b))
}

fn mix(a: [f32; 3], b: [f32; 3], t: f32) -> [f32; 3] {
    [0, 1, 2].map(|k| a[k] + (b[k] - a[k]) * t)
}
