//! Per-stage wall times of one cut, returned in [`crate::CutResult::phases`] when
//! [`crate::CutOptions::time_phases`] asks for them (the benchmark prints them; the crate itself
//! prints nothing).

/// Per-stage wall times of one cut. Off, it costs a clock read per cut.
pub(crate) struct Phases {
    pub(crate) on: bool,
    start: std::time::Instant,
    pub(crate) last: std::time::Instant,
    marks: Vec<(&'static str, f64)>,
}

impl Phases {
    pub(crate) fn new(on: bool) -> Phases {
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

    /// The stages in the order they ran, after a first `("total", ms)` entry; empty when off.
    pub(crate) fn into_marks(mut self) -> Vec<(&'static str, f64)> {
        if !self.on {
            return Vec::new();
        }
        let total = self.start.elapsed().as_secs_f64() * 1e3;
        self.marks.insert(0, ("total", total));
        self.marks
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
