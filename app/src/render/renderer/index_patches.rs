//! Hiding faces in place: a [`MeshDelta`](crate::cutting::delta::MeshDelta) replaces some faces
//! of a model, and instead of uploading the model again the renderer overwrites those faces'
//! index words in the model's index buffer (a degenerate triangle hides a face, its indices show
//! it again) with the scatter compute shader. The words a change needs are proportional to the
//! faces hidden or shown, not to the model.

use wgpu::util::DeviceExt as _;

use super::Renderer;
use crate::render::pipelines::{SCATTER_GROUP, SCATTER_ROW_GROUPS};

/// Index words to overwrite in one model's index buffer: (word, value), ascending by word.
pub(super) struct IndexPatch {
    pub(super) key: usize,
    pub(super) words: Vec<[u32; 2]>,
}

impl Renderer {
    /// Writes this frame's index patches (hidden faces) with the scatter compute shader, before
    /// the render passes that read the index buffers. Each patch list names every word once.
    pub(super) fn apply_patches(
        &mut self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
    ) {
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

/// The index words that turn the hidden faces `old` into `new` (both ascending): a face no
/// longer hidden gets its three drawn indices back from `triangle` (what the model's index
/// buffer holds for it, `None` for no such face), a newly hidden one becomes the degenerate
/// triangle at its first corner (no pixels). Proportional to the two lists.
pub(super) fn hidden_patches(
    triangle: &dyn Fn(u32) -> Option<[u32; 3]>,
    old: &[u32],
    new: &[u32],
) -> Vec<[u32; 2]> {
    let mut out = Vec::new();
    let (mut i, mut j) = (0, 0);
    let emit = |f: u32, show: bool, out: &mut Vec<[u32; 2]>| {
        let Some(tri) = triangle(f) else {
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
