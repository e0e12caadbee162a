//! CPU time of the calling thread: a work budget that does not depend on how busy the machine is.
//!
//! A bound such as "a gesture replay stops after 1.5 s" is meant to stop runaway work (thousands of
//! moves that each re-fit a large cutter), not to fail a valid replay because other processes
//! share the cores. Wall-clock time grows with the machine's load; the thread's own CPU time
//! does not, so the same input gives the same answer on a quiet laptop and on a loaded CI runner.
//! Where the platform has no per-thread clock, wall-clock time since the first call stands in.

use std::time::Duration;

/// CPU time the calling thread has used so far (see the module documentation).
pub fn thread_cpu_time() -> Duration {
    #[cfg(unix)]
    {
        let mut ts = libc::timespec {
            tv_sec: 0,
            tv_nsec: 0,
        };
        // SAFETY: `ts` is a valid, writable timespec; the call only writes it.
        #[allow(unsafe_code)] // the per-thread CPU clock is only reachable through libc
        let rc = unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut ts) };
        if rc == 0 {
            return Duration::new(ts.tv_sec as u64, ts.tv_nsec as u32);
        }
    }
    wall_clock_since_first_call()
}

fn wall_clock_since_first_call() -> Duration {
    static START: std::sync::OnceLock<std::time::Instant> = std::sync::OnceLock::new();
    START.get_or_init(std::time::Instant::now).elapsed()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Busy work advances the clock; sleeping does not (a CPU clock, not a wall clock).
    #[test]
    fn counts_work_not_waiting() {
        let start = thread_cpu_time();
        std::thread::sleep(Duration::from_millis(200));
        let slept = thread_cpu_time() - start;
        let mut x = 0u64;
        let busy_start = thread_cpu_time();
        while thread_cpu_time() - busy_start < Duration::from_millis(50) {
            x = x.wrapping_mul(6364136223846793005).wrapping_add(1);
        }
        std::hint::black_box(x);
        assert!(
            slept < Duration::from_millis(100),
            "sleeping used {slept:?} of CPU"
        );
        assert!(thread_cpu_time() - busy_start >= Duration::from_millis(50));
    }
}
