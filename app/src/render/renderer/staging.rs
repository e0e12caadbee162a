//! Uploads reach the GPU in batches of bounded size. wgpu stages every buffer made with its
//! contents in a host-side copy that lives until the queue submission carrying it has finished,
//! so a frame that uploads a whole scene (the first frame after a load, a new cut drawn in full,
//! every model turned to wireframe) held a second copy of all it uploaded until the frame was
//! submitted; on a software adapter (lavapipe) both copies are host memory, and that copy made
//! the peaks of the window and of `cutaway render`. After every [`BATCH`] bytes the uploads so far
//! are submitted and waited for, so their staged copies go before the next are made (as the image
//! layer's slabs are). A frame with small uploads (a live re-cut's patch) never waits.

/// Bytes uploaded between two flushes at most (plus one buffer).
pub(super) const BATCH: u64 = 8 << 20;

/// Bytes uploaded since the last flush.
#[derive(Debug, Default)]
pub(super) struct Staging {
    pending: u64,
}

impl Staging {
    /// Counts `bytes` uploaded; once [`BATCH`] is reached, submits the uploads and waits for them.
    pub(super) fn uploaded(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, bytes: u64) {
        self.pending += bytes;
        if self.pending >= BATCH {
            queue.submit(std::iter::empty());
            let _ = device.poll(wgpu::PollType::wait_indefinitely());
            self.pending = 0;
        }
    }
}
