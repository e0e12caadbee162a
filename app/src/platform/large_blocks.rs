//! Large blocks go back to the system when freed.
//!
//! The window's big allocations are transient and made on several threads: each live re-cut
//! makes walls, patches and contours on the live-cut worker, Preview makes model-sized meshes,
//! and on a software adapter (lavapipe) every GPU buffer is host memory from the same C
//! allocator. glibc serves a block at or above its mmap threshold with a mapping of its own and
//! unmaps it on free, but by default it raises that threshold to the size of every mapped block
//! freed (up to 32 MiB), so after the first few cuts blocks of megabytes come from the per-thread
//! arenas instead, and what is freed there stays resident: the memory test saw the allocator's
//! free space grow from 58 MB to 106 MB (and the resident size by 47 %) while the memory in use
//! stayed at 241 MB. Fixing the threshold at [`LARGE_BLOCK`] keeps every large block mapped on its
//! own, so freeing it returns it.

/// Blocks of this many bytes or more are mapped on their own (and unmapped when freed).
pub const LARGE_BLOCK: usize = 128 << 10;

/// Fixes glibc's mmap threshold at [`LARGE_BLOCK`] for the rest of the process (see the module
/// documentation). Does nothing with other C libraries.
#[allow(unsafe_code)] // glibc's allocator is configured through `mallopt` only
pub fn return_large_blocks_to_the_system() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    {
        /// `M_MMAP_THRESHOLD` of glibc's `malloc.h`.
        const M_MMAP_THRESHOLD: i32 = -3;
        unsafe extern "C" {
            fn mallopt(param: i32, value: i32) -> i32;
        }
        // SAFETY: mallopt only changes glibc's allocation policy; any value is accepted or
        // refused (returns 0), never undefined.
        unsafe {
            mallopt(M_MMAP_THRESHOLD, LARGE_BLOCK as i32);
        }
    }
}
