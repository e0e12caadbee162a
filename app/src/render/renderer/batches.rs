//! How much of a frame the GPU works on at a time. On a software adapter (lavapipe, llvmpipe)
//! the GPU is the host: its rasterizer first bins every triangle of a submission, with its edge
//! equations and interpolants (about 300 bytes each with the mesh shader's varyings), and its
//! binning runs ahead of its rasterizing threads by as many 36 MB scenes as it likes. A frame
//! of the SPL brain atlas (600k triangles) held 185 MB of binned triangles at its peak, more
//! than the models and their uploads together.
//!
//! So on such an adapter a pass's draws are cut into batches of at most [`CPU_BATCH`]
//! triangles (a big mesh into index ranges), each recorded in its own render pass and submitted
//! on its own; before a batch is submitted, the one before it has finished. At most two
//! batches are binned at a time, and the order of the draws, hence the picture, is unchanged.
//! On other adapters a pass is one batch in the caller's encoder, as one submission.

use std::ops::Range;

use super::draw_list::Draw;

/// Triangles per batch on a software adapter (a line segment counts two): about 10 MB binned.
pub(super) const CPU_BATCH: u32 = 1 << 15;

/// A draw, or the part of it one batch takes: `range` counts triangles for meshes and segments
/// for lines.
#[derive(Clone)]
pub(super) struct BatchDraw {
    pub(super) draw: Draw,
    pub(super) range: Range<u32>,
}

/// Cuts `draws` into batches of at most `budget` triangles each, in order; `size` gives a
/// draw's count of triangles or segments and whether it is lines (a segment is two triangles).
/// `None`: one batch of everything; a budget under 2 counts as 2. There is always at least one batch, empty when `draws` is.
pub(super) fn split(
    draws: &[Draw],
    budget: Option<u32>,
    size: impl Fn(Draw) -> (u32, bool),
) -> Vec<Vec<BatchDraw>> {
    let budget = budget.map_or(u32::MAX, |b| b.max(2));
    let mut batches = vec![Vec::new()];
    let mut room = budget;
    for &draw in draws {
        let (count, lines) = size(draw);
        let cost = if lines { 2 } else { 1 };
        let mut start = 0;
        while start < count {
            if room < cost {
                batches.push(Vec::new());
                room = budget;
            }
            let take = (count - start).min(room / cost);
            batches
                .last_mut()
                .expect("at least one batch")
                .push(BatchDraw {
                    draw,
                    range: start..start + take,
                });
            start += take;
            room -= take * cost;
        }
    }
    batches
}

/// Where the passes are recorded: the caller's encoder, or on a software adapter one encoder
/// per batch, made when the batch records its first command and submitted at
/// [`Submissions::end_batch`] (so no empty batch is submitted).
pub(super) struct Submissions<'a> {
    device: &'a wgpu::Device,
    queue: &'a wgpu::Queue,
    caller: &'a mut wgpu::CommandEncoder,
    /// Whether batches are submitted on their own.
    separate: bool,
    /// The batch being recorded, when batches are submitted on their own.
    own: Option<wgpu::CommandEncoder>,
    /// The last batch submitted, not yet waited for.
    in_flight: Option<wgpu::SubmissionIndex>,
}

impl<'a> Submissions<'a> {
    /// Records into `caller`, or with `separate` into encoders of its own.
    pub(super) fn new(
        device: &'a wgpu::Device,
        queue: &'a wgpu::Queue,
        caller: &'a mut wgpu::CommandEncoder,
        separate: bool,
    ) -> Self {
        Submissions {
            device,
            queue,
            caller,
            separate,
            own: None,
            in_flight: None,
        }
    }

    pub(super) fn encoder(&mut self) -> &mut wgpu::CommandEncoder {
        if !self.separate {
            return self.caller;
        }
        let device = self.device;
        self.own.get_or_insert_with(|| {
            device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("cutaway batch"),
            })
        })
    }

    /// Ends the batch recorded so far: submits it, then waits for the batch before it.
    pub(super) fn end_batch(&mut self) {
        let Some(own) = self.own.take() else { return };
        let submitted = self.queue.submit([own.finish()]);
        if let Some(previous) = self.in_flight.replace(submitted) {
            let _ = self.device.poll(wgpu::PollType::Wait {
                submission_index: Some(previous),
                timeout: None,
            });
        }
    }

    /// Submits what was recorded after the last batch (the composite), without waiting.
    pub(super) fn finish(mut self) {
        if let Some(own) = self.own.take() {
            self.queue.submit([own.finish()]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::draw_list::Source;
    use super::*;

    fn sizes(draws: &[(u32, bool)]) -> Vec<Draw> {
        (0..draws.len())
            .map(|i| Draw::Mesh(Source::Model(i), 0))
            .collect()
    }

    fn key(d: Draw) -> usize {
        match d {
            Draw::Mesh(Source::Model(i), _) => i,
            _ => unreachable!(),
        }
    }

    #[test]
    fn batches_cover_every_draw_in_order_within_the_budget() {
        let spec = [(10, false), (0, false), (25, false), (3, true), (7, false)];
        let draws = sizes(&spec);
        let size = |d: Draw| spec[key(d)];
        let batches = split(&draws, Some(8), size);
        let mut seen: Vec<(usize, u32)> = Vec::new();
        for batch in &batches {
            let cost: u32 = batch
                .iter()
                .map(|b| (b.range.end - b.range.start) * if spec[key(b.draw)].1 { 2 } else { 1 })
                .sum();
            assert!(cost <= 8, "a batch of {cost} triangles");
            assert!(!batch.is_empty());
            for b in batch {
                assert!(b.range.start < b.range.end, "an empty piece");
                seen.extend(b.range.clone().map(|u| (key(b.draw), u)));
            }
        }
        let expected: Vec<(usize, u32)> = spec
            .iter()
            .enumerate()
            .flat_map(|(i, &(n, _))| (0..n).map(move |u| (i, u)))
            .collect();
        assert_eq!(seen, expected);
        // 10 + 25 + 7 triangles and 3 segments: a segment never straddles two batches, so the
        // fifth batch ends one short.
        assert_eq!(batches.len(), 7);
    }

    #[test]
    fn without_a_budget_a_pass_is_one_batch_of_whole_draws() {
        let spec = [(100_000, false), (5, true)];
        let draws = sizes(&spec);
        let batches = split(&draws, None, |d| spec[key(d)]);
        assert_eq!(batches.len(), 1);
        let ranges: Vec<Range<u32>> = batches[0].iter().map(|b| b.range.clone()).collect();
        assert_eq!(ranges, vec![0..100_000, 0..5]);
        assert_eq!(split(&[], Some(4), |_| (0, false)).len(), 1);
    }
}
