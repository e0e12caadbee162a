//! The render passes of one eye, replaying a frame's [`DrawList`]: (1) opaque meshes and lines
//! with depth; (2) transparent meshes into the weighted-blended accumulation targets, depth-tested
//! against (1) without writing; (3) the transparency composite over (1), then overlay lines
//! (cutter outlines) on top. Passes that would draw nothing are not begun.

use super::Renderer;
use super::draw_list::{Draw, DrawList};
use crate::render::gpu_data::DRAW_UNIFORM_STRIDE;

impl Renderer {
    pub(super) fn encode_eye(
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
        let transparency = targets
            .transparency
            .as_ref()
            .filter(|_| !draws.transparent.is_empty());
        if let Some(oit) = transparency {
            {
                let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some("cutaway transparency pass"),
                    color_attachments: &[
                        Some(wgpu::RenderPassColorAttachment {
                            view: &oit.accum_view,
                            resolve_target: None,
                            ops: wgpu::Operations {
                                load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                                store: wgpu::StoreOp::Store,
                            },
                            depth_slice: None,
                        }),
                        Some(wgpu::RenderPassColorAttachment {
                            view: &oit.revealage_view,
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
        if transparency.is_some() || !draws.overlay.is_empty() {
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
            if let Some(oit) = transparency {
                pass.set_pipeline(&self.pipelines.composite);
                pass.set_bind_group(0, &oit.composite_bind_group, &[]);
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
}
