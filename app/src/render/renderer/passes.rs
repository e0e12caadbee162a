//! The render passes of one eye, replaying a frame's [`DrawList`]: (1) opaque meshes and lines
//! with depth; (2) transparent meshes into the weighted-blended accumulation targets, depth-tested
//! against (1) without writing; (3) the transparency composite over (1), then overlay lines
//! (cutter outlines) on top. Passes that would draw nothing are not begun. On a software adapter
//! (1) and (2) are each cut into batches, one render pass and submission each ([`batches`]): the
//! first clears, the others load what it drew.

use super::Renderer;
use super::batches::{self, BatchDraw, Submissions};
use super::draw_list::{Draw, DrawList};
use crate::render::gpu_data::DRAW_UNIFORM_STRIDE;

impl Renderer {
    pub(super) fn encode_eye(
        &self,
        out: &mut Submissions<'_>,
        eye: usize,
        clear: wgpu::Color,
        draws: &DrawList,
    ) {
        let Some(targets) = &self.targets else { return };
        let frame_offset = (eye as u64 * DRAW_UNIFORM_STRIDE) as u32;
        let color_view = &targets.color_views[eye];
        let load = |first: bool, value: wgpu::Color| {
            if first {
                wgpu::LoadOp::Clear(value)
            } else {
                wgpu::LoadOp::Load
            }
        };
        let depth = &targets.depth_view;
        for (i, batch) in self.batches(&draws.opaque).iter().enumerate() {
            {
                let colors = [attachment(color_view, load(i == 0, clear))];
                let depth_load = if i == 0 {
                    wgpu::LoadOp::Clear(1.0)
                } else {
                    wgpu::LoadOp::Load
                };
                let mut pass = begin(
                    out.encoder(),
                    "cutaway opaque pass",
                    &colors,
                    depth,
                    depth_load,
                );
                pass.set_bind_group(0, &self.frame_bind_group, &[frame_offset]);
                self.draw_all(&mut pass, batch, false);
            }
            out.end_batch();
        }
        let transparency = targets
            .transparency
            .as_ref()
            .filter(|_| !draws.transparent.is_empty());
        if let Some(oit) = transparency {
            for (i, batch) in self.batches(&draws.transparent).iter().enumerate() {
                {
                    let colors = [
                        attachment(&oit.accum_view, load(i == 0, wgpu::Color::TRANSPARENT)),
                        attachment(&oit.revealage_view, load(i == 0, wgpu::Color::WHITE)),
                    ];
                    let label = "cutaway transparency pass";
                    let mut pass = begin(out.encoder(), label, &colors, depth, wgpu::LoadOp::Load);
                    pass.set_bind_group(0, &self.frame_bind_group, &[frame_offset]);
                    self.draw_all(&mut pass, batch, true);
                }
                out.end_batch();
            }
        }
        if transparency.is_some() || !draws.overlay.is_empty() {
            let colors = [attachment(color_view, wgpu::LoadOp::Load)];
            let label = "cutaway composite pass";
            let mut pass = begin(out.encoder(), label, &colors, depth, wgpu::LoadOp::Load);
            if let Some(oit) = transparency {
                pass.set_pipeline(&self.pipelines.composite);
                pass.set_bind_group(0, &oit.composite_bind_group, &[]);
                pass.draw(0..3, 0..1);
            }
            if !draws.overlay.is_empty() {
                pass.set_bind_group(0, &self.frame_bind_group, &[frame_offset]);
                let whole = self.batches_of(&draws.overlay, None);
                self.draw_all(&mut pass, &whole[0], false);
            }
        }
    }

    /// `draws` cut into this renderer's batches.
    fn batches(&self, draws: &[Draw]) -> Vec<Vec<BatchDraw>> {
        self.batches_of(draws, self.batch_triangles)
    }

    fn batches_of(&self, draws: &[Draw], budget: Option<u32>) -> Vec<Vec<BatchDraw>> {
        batches::split(draws, budget, |draw| match draw {
            Draw::Mesh(source, _) | Draw::ImageMesh(source, _) | Draw::RiskMesh(source, ..) => {
                (self.mesh(source).map_or(0, |m| m.index_count / 3), false)
            }
            Draw::Edges(..) | Draw::Contour(..) | Draw::Lines(..) => {
                (self.segments(draw).map_or(0, |s| s.count), true)
            }
        })
    }

    fn draw_all(&self, pass: &mut wgpu::RenderPass<'_>, draws: &[BatchDraw], transparent: bool) {
        for BatchDraw { draw, range } in draws {
            let (draw, range) = (*draw, range.clone());
            let indices = 3 * range.start..3 * range.end;
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
                    pass.draw_indexed(indices.clone(), 0, 0..1);
                }
                Draw::RiskMesh(source, u, over_image) => {
                    let Some(mesh) = self.mesh(source) else {
                        continue;
                    };
                    let image = over_image.then(|| self.image.bind_group()).flatten();
                    if !self.risk_pipelines.bind(pass, image) {
                        continue;
                    }
                    pass.set_bind_group(
                        1,
                        &self.draw_bind_group,
                        &[u * DRAW_UNIFORM_STRIDE as u32],
                    );
                    pass.set_vertex_buffer(0, mesh.vertex_buffer.slice(..));
                    pass.set_index_buffer(mesh.index_buffer.slice(..), wgpu::IndexFormat::Uint32);
                    pass.draw_indexed(indices.clone(), 0, 0..1);
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
                    pass.draw(0..6, range);
                }
            }
        }
    }
}

/// A colour target of a pass, stored at its end.
fn attachment(
    view: &wgpu::TextureView,
    load: wgpu::LoadOp<wgpu::Color>,
) -> Option<wgpu::RenderPassColorAttachment<'_>> {
    Some(wgpu::RenderPassColorAttachment {
        view,
        resolve_target: None,
        ops: wgpu::Operations {
            load,
            store: wgpu::StoreOp::Store,
        },
        depth_slice: None,
    })
}

/// Begins a pass drawing into `colors` with the depth target `depth`, both stored at its end.
fn begin<'e>(
    encoder: &'e mut wgpu::CommandEncoder,
    label: &str,
    colors: &[Option<wgpu::RenderPassColorAttachment<'_>>],
    depth: &wgpu::TextureView,
    depth_load: wgpu::LoadOp<f32>,
) -> wgpu::RenderPass<'e> {
    encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some(label),
        color_attachments: colors,
        depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
            view: depth,
            depth_ops: Some(wgpu::Operations {
                load: depth_load,
                store: wgpu::StoreOp::Store,
            }),
            stencil_ops: None,
        }),
        occlusion_query_set: None,
        timestamp_writes: None,
        multiview_mask: None,
    })
}
