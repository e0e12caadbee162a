//! The peak resident memory of one case: the process's high-water mark (`VmHWM`), reset when a
//! case starts (writing 5 to `/proc/self/clear_refs`, Linux). A case runs alone in its process
//! (one per child of `cutaway batch`, one per Dask or process-pool worker with one thread), so
//! the mark is the case's own.

/// Resets the process's peak resident size to its current size (no effect where unsupported).
pub fn reset_peak() {
    std::fs::write("/proc/self/clear_refs", "5").ok();
}

/// The process's peak resident size since the last [`reset_peak`], in MiB.
pub fn peak_mb() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib / 1024.0)
}
