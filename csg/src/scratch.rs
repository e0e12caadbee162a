//! Per-cut scratch of a [`crate::TargetIndex`], allocated once with the index so that a warm
//! cut never allocates, clears or first-touches anything of the target's size.

/// Per-cut scratch indexed by face, allocated (and its pages written) when the index is built,
/// so that a cut never allocates, clears or first-touches anything of the target's size.
///
/// - `bits` (one bit per face) and `summary` (one bit per word of `bits`): the faces marked during
///   this cut (the faces the cut removes from kept), read back in ascending order by
///   [`Scratch::drain_marked`] in time proportional to their number (plus one word per 4096
///   faces), which clears them again. At 2M faces the bitmap is 250 KB, so the flood fill's
///   "seen" test stays in cache. `touched` (same layout as `bits`) marks the faces the contour
///   splits; the cut clears it through its list of those faces.
/// - `values`: per marked face its status, written only by cuts with several sub-cutters (a
///   single cutter's status is always 1), valid only for marked faces.
/// - `dirty`: a cut stopped before draining (an error); the next `begin` clears everything.
#[derive(Debug, Default)]
pub(crate) struct Scratch {
    pub(crate) bits: Vec<u64>,
    pub(crate) summary: Vec<u64>,
    pub(crate) touched: Vec<u64>,
    values: Vec<u32>,
    faces: usize,
    /// Number of marked faces.
    marked: usize,
    dirty: bool,
}

impl Scratch {
    /// Scratch for a target of `faces` faces, with every page written once.
    pub fn for_faces(faces: usize) -> Scratch {
        Scratch {
            // Non-zero fills, so that the pages are written now rather than at the first cut;
            // `begin` zeroes the bitmaps.
            bits: vec![u64::MAX; faces.div_ceil(64)],
            summary: vec![u64::MAX; faces.div_ceil(64 * 64)],
            touched: vec![u64::MAX; faces.div_ceil(64)],
            values: vec![u32::MAX; faces],
            faces,
            marked: 0,
            dirty: true,
        }
    }

    /// Starts a cut on a target of `faces` faces.
    pub fn begin(&mut self, faces: usize) {
        if self.faces != faces {
            *self = Scratch::for_faces(faces);
        }
        if self.dirty {
            self.bits.fill(0);
            self.summary.fill(0);
            self.touched.fill(0);
            self.dirty = false;
        }
        self.marked = 0;
    }

    /// Number of faces marked in this cut.
    pub fn marked_count(&self) -> usize {
        self.marked
    }

    /// Whether face `t` is marked.
    #[inline]
    pub fn is_marked(&self, t: u32) -> bool {
        self.bits[(t >> 6) as usize] & (1 << (t & 63)) != 0
    }

    /// Marks face `t` (see [`Scratch::drain_marked`]).
    #[inline]
    pub fn mark(&mut self, t: u32) {
        let w = (t >> 6) as usize;
        self.bits[w] |= 1 << (t & 63);
        self.summary[w >> 6] |= 1 << (w & 63);
        self.marked += 1;
        self.dirty = true;
    }

    /// Marks face `t` and records its value.
    #[inline]
    pub fn mark_with(&mut self, t: u32, value: u32) {
        self.mark(t);
        self.values[t as usize] = value;
    }

    /// Marks face `t` as touched by the contour (and as marked).
    #[inline]
    pub fn mark_touched(&mut self, t: u32) {
        self.mark(t);
        self.touched[(t >> 6) as usize] |= 1 << (t & 63);
    }

    /// Calls `visit(face, touched, value)` for every marked face in ascending order (`value`:
    /// what [`Scratch::mark_with`] stored, meaningless otherwise), and unmarks them all. The
    /// caller clears `touched` with [`Scratch::clear_touched`].
    pub fn drain_marked(&mut self, mut visit: impl FnMut(u32, bool, u32)) {
        for s in 0..self.summary.len() {
            let mut words = std::mem::take(&mut self.summary[s]);
            while words != 0 {
                let w = (s << 6) | words.trailing_zeros() as usize;
                words &= words - 1;
                let mut bits = std::mem::take(&mut self.bits[w]);
                let touched = self.touched[w];
                while bits != 0 {
                    let b = bits.trailing_zeros();
                    let t = (w << 6) | b as usize;
                    visit(t as u32, touched & (1 << b) != 0, self.values[t]);
                    bits &= bits - 1;
                }
            }
        }
    }

    /// Unmarks the touched faces `faces` (after [`Scratch::drain_marked`]); the scratch is then
    /// clean for the next cut.
    pub fn clear_touched(&mut self, faces: &[u32]) {
        for &t in faces {
            self.touched[(t >> 6) as usize] = 0;
        }
        self.dirty = false;
    }
}

/// The scratch of a [`TargetIndex`]: one per index, used by one cut at a time (a concurrent cut
/// on the same index uses its own). Cloning an index gives the clone a fresh scratch.
#[derive(Debug, Default)]
pub(crate) struct ScratchCell(pub std::sync::Mutex<Scratch>);

impl Clone for ScratchCell {
    fn clone(&self) -> Self {
        let faces = self.0.lock().map_or(0, |s| s.faces);
        ScratchCell(std::sync::Mutex::new(Scratch::for_faces(faces)))
    }
}
