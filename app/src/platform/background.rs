//! Background threads that yield the cores to the foreground work.
//!
//! Some work is started ahead of need on a thread of its own: the indexes of the scalpel's rest
//! mesh after a stroke commits (a second or more on millions of triangles), so that the next
//! press rarely waits. While it runs the user is often already drawing the next stroke, whose
//! every step must fit in a frame and uses both cores of a small machine (the opening blends on
//! a second thread). Run at the normal priority, the index build took a core from those steps:
//! on the 2M-triangle sphere most replays of the crossing stroke had a step of 4–7 ms, against
//! 3.6 ms at most without it. [`yield_to_foreground`] makes the calling thread the last to get
//! a core the foreground wants (the lowest priority, nice 19); alone it still runs at full
//! speed.

/// Lowers the calling thread's priority to the lowest (see the module doc). Where threads have
/// no priority of their own (other than Linux), nothing changes.
pub fn yield_to_foreground() {
    #[cfg(target_os = "linux")]
    {
        // SAFETY: `gettid` and `setpriority` take plain integers and touch no memory of ours.
        #[allow(unsafe_code)] // a thread's own priority is only reachable through libc
        unsafe {
            let tid = libc::syscall(libc::SYS_gettid) as libc::id_t;
            // Raising one's own nice value needs no privilege; a failure leaves it as it was.
            libc::setpriority(libc::PRIO_PROCESS, tid, LOWEST);
        }
    }
}

/// The nice value of a thread that yields (the lowest priority).
pub const LOWEST: i32 = 19;

#[cfg(test)]
mod tests {
    use super::*;

    /// The calling thread's nice value.
    #[cfg(target_os = "linux")]
    fn this_threads_nice() -> i32 {
        // SAFETY: `gettid` and `getpriority` take plain integers and touch no memory of ours.
        #[allow(unsafe_code)] // a thread's own priority is only reachable through libc
        unsafe {
            let tid = libc::syscall(libc::SYS_gettid) as libc::id_t;
            libc::getpriority(libc::PRIO_PROCESS, tid)
        }
    }

    #[cfg(not(target_os = "linux"))]
    fn this_threads_nice() -> i32 {
        0
    }

    #[test]
    fn a_thread_that_yields_gets_the_lowest_priority_and_only_it() {
        let before = this_threads_nice();
        let theirs = std::thread::spawn(|| {
            yield_to_foreground();
            this_threads_nice()
        })
        .join()
        .unwrap();
        if cfg!(target_os = "linux") {
            assert_eq!(theirs, LOWEST);
        } else {
            println!("skipped: threads have no priority of their own here");
        }
        assert_eq!(this_threads_nice(), before, "the caller's priority changed");
    }
}
