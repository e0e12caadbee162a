//! Per-stage wall times of one cut, for profiling the benchmark.

/// Per-stage wall times of one cut, printed to stderr when the environment variable
/// `CUTAWAY_CUT_PHASES` is set (for profiling the benchmark; never in tests). Off, it costs a
/// clock read per cut.
pub(crate) struct Phases {
    pub(crate) on: bool,
    start: std::time::Instant,
    pub(crate) last: std::time::Instant,
    marks: Vec<(&'static str, f64)>,
}

impl Phases {
    pub(crate) fn new() -> Phases {
        static ON: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
        let on = *ON.get_or_init(|| std::env::var_os("CUTAWAY_CUT_PHASES").is_some());
        let now = std::time::Instant::now();
        Phases {
            on,
            start: now,
            last: now,
            marks: Vec::new(),
        }
    }

    /// Ends the stage `name` (started at the previous mark).
    pub(crate) fn mark(&mut self, name: &'static str) {
        if self.on {
            let now = std::time::Instant::now();
            self.marks
                .push((name, (now - self.last).as_secs_f64() * 1e3));
            self.last = now;
        }
    }

    /// Appends the stages of `other` (timed on another thread).
    pub(crate) fn append(&mut self, other: &Phases) {
        if self.on {
            self.marks.extend_from_slice(&other.marks);
        }
    }

    /// Records a duration measured elsewhere (a stage that ran beside another).
    pub(crate) fn record(&mut self, name: &'static str, ms: f64) {
        if self.on {
            self.marks.push((name, ms));
        }
    }

    pub(crate) fn print(&self) {
        if self.on {
            let total = self.start.elapsed().as_secs_f64() * 1e3;
            let parts: Vec<String> = self
                .marks
                .iter()
                .map(|(n, ms)| format!("{n} {ms:.3}"))
                .collect();
            eprintln!("cut phases ms: total {total:.3} | {}", parts.join(" | "));
        }
    }
}

/// Wall time of `f` in ms when `on`.
pub(crate) fn timed<R>(on: bool, f: impl FnOnce() -> R) -> (R, f64) {
    if on {
        let t = std::time::Instant::now();
        let r = f();
        (r, t.elapsed().as_secs_f64() * 1e3)
    } else {
        (f(), 0.0)
    }
}
