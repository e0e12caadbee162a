//! What the application needs from the machine, below every other layer: background jobs, the
//! priority of threads that work ahead of need, the replaying thread's CPU clock, the
//! allocator's handling of large blocks and free pages, the memory census and the one-line
//! error form.

pub mod background;
pub mod errors;
pub mod free_pages;
pub mod jobs;
pub mod large_blocks;
pub mod memory_census;
pub mod thread_time;
