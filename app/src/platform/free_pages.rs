//! Pages the allocator keeps after large frees go back to the system.
//!
//! Blocks of [`LARGE_BLOCK`](crate::platform::large_blocks::LARGE_BLOCK) or more are mapped on their own and
//! returned when freed, but everything smaller comes from glibc's arenas, one per thread that
//! allocates (the UI thread, the live-cut worker, the parallel cut's workers, and on a software
//! adapter the driver's threads). A freed chunk inside an arena stays resident until the same
//! arena reuses it; glibc gives back only the free top of an arena. Each re-cut, Preview and view
//! toggle frees thousands of small pieces (wall and ribbon meshes of small models, contour
//! polylines, per-part hash maps, the driver's small buffers) on whichever thread made them, so the
//! first showing of ribbons, slices and transparent views left tens of megabytes free but resident
//! in arenas that other threads never reuse: the memory test saw the allocator's free space grow
//! from 47 MB to 72 MB (and the resident size by a fifth) with the memory in use flat.
//!
//! The renderer calls [`FreePages::note_large_free`] when it drops a preview or model uploads (the
//! old preview's CPU meshes were dropped with it), and [`FreePages::trim_if_due`] once per frame:
//! at most every [`MIN_INTERVAL`] it asks glibc (`malloc_trim`) to return every whole free page of
//! every arena. That costs about a millisecond per call and one page fault per page touched again; done only
//! after large frees, not per frame, it never shows in a frame's time. Other C libraries: nothing.

use std::time::{Duration, Instant};

/// The shortest time between two trims (a drag re-cuts every frame; one trim per burst is enough).
pub const MIN_INTERVAL: Duration = Duration::from_millis(250);

/// When to trim: after a large free, not more often than [`MIN_INTERVAL`].
#[derive(Debug, Default)]
pub struct FreePages {
    /// A large free happened since the last trim.
    pending: bool,
    last_trim: Option<Instant>,
}

impl FreePages {
    /// Records that model-sized data was freed: the next [`FreePages::trim_if_due`] at least
    /// [`MIN_INTERVAL`] after the last trim hands the free pages back.
    pub fn note_large_free(&mut self) {
        self.pending = true;
    }

    /// Hands free arena pages back to the system ([`trim_now`]) when a large free happened since
    /// the last trim and that trim is at least [`MIN_INTERVAL`] before `now`. Returns whether it
    /// trimmed.
    pub fn trim_if_due(&mut self, now: Instant) -> bool {
        let due = self.pending
            && self
                .last_trim
                .is_none_or(|t| now.saturating_duration_since(t) >= MIN_INTERVAL);
        if due {
            trim_now();
            self.pending = false;
            self.last_trim = Some(now);
        }
        due
    }
}

/// Returns every whole free page of the C allocator's arenas to the system.
#[allow(unsafe_code)] // glibc's allocator releases its free pages through `malloc_trim` only
pub fn trim_now() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    {
        unsafe extern "C" {
            fn malloc_trim(pad: usize) -> i32;
        }
        // SAFETY: malloc_trim only releases free memory of glibc's arenas (advising the kernel
        // that whole free pages are unneeded); it takes no pointer and touches no live block.
        unsafe {
            malloc_trim(0);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn trims_only_after_a_large_free_and_not_more_often_than_the_interval() {
        let start = Instant::now();
        let mut pages = FreePages::default();
        assert!(!pages.trim_if_due(start), "nothing was freed");
        pages.note_large_free();
        assert!(pages.trim_if_due(start), "a large free was noted");
        assert!(
            !pages.trim_if_due(start),
            "the free was handed back already"
        );
        pages.note_large_free();
        let soon = start + MIN_INTERVAL / 2;
        assert!(
            !pages.trim_if_due(soon),
            "the last trim is less than the interval ago"
        );
        assert!(
            pages.trim_if_due(start + MIN_INTERVAL),
            "the interval passed with a free pending"
        );
    }

    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    #[test]
    fn trimming_returns_freed_small_blocks_to_the_system() {
        // Many small blocks (under the mmap threshold, so from an arena), then all freed but the
        // last: the arena's top stays in use, so only a trim can give the freed pages back.
        let rss = || -> u64 {
            let status = std::fs::read_to_string("/proc/self/status").unwrap();
            let kb = status
                .lines()
                .find_map(|l| l.strip_prefix("VmRSS:"))
                .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<u64>().ok())
                .unwrap();
            kb << 10
        };
        let handle = std::thread::spawn(move || {
            let mut blocks: Vec<Vec<u8>> = (0..4096).map(|i| vec![i as u8; 16 << 10]).collect();
            let keep = blocks.pop();
            drop(blocks);
            let before = rss();
            trim_now();
            let after = rss();
            drop(keep);
            (before, after)
        });
        let (before, after) = handle.join().unwrap();
        assert!(
            before >= after + (32 << 20),
            "64 MB of freed small blocks: resident {before} bytes before the trim, {after} after"
        );
    }
}
