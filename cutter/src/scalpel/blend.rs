//! The path correction at a point, blended from the corrections at the cut segments' ends
//! within the support (see [`super::dffd`]), and the blends of a walk measured on a second
//! thread while the walk goes on.
//!
//! The opening's walk asks for the blend at every vertex whose blend a step may have changed:
//! a thousand and more on a crossing of two grooves, each over the hundred or two segments the
//! cut grid lists around the point ([`Near::near`]). That was a fifth of a step. Two things
//! make it cheaper:
//! - [`Blend`] lays out the ends of the segments around each cell once per walk, in segment
//!   order, with their corrections, and runs down that list: the same ends in the same order,
//!   so the same sum bit for bit (a segment whose bounding ball is out of reach, which the walk
//!   used to skip first, has no end within reach either);
//! - [`with_blends`] measures them on a second thread, in batches, while the walk itself (a
//!   breadth-first search over the mesh, bound by memory, not by arithmetic) goes on; the walk
//!   writes the blends into its field when it is done. A blend depends on its point alone, so
//!   the field is the same bit for bit whichever thread measured what. The helper is started
//!   for the walk, not taken from a pool: rayon's workers, asleep between two steps, woke too
//!   late to share a walk of a millisecond or two, and the walk was no faster
//!   (`benches/blends.rs` measures both).

use std::ops::Range;
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};

use glam::DVec3;

use super::cut_grid::{Cell, CutGrid, Near, cell_of};
use super::step::CutSegment;
use csg::fast_hash::FastMap;

/// Blends asked for per batch handed to the second thread (about 20 microseconds of work).
const BATCH: usize = 32;

/// Batches a walk queues before a second thread is started for it. Starting a thread costs
/// what measuring a few batches does (more, and now and then milliseconds, in a process that
/// has started few): a walk on a knee's patella asks for 8 to 11 batches and was slower with
/// one, a walk across a crossing of grooves on a 2M-triangle sphere asks for 25 to 57.
const START_AT: usize = 16;

/// Checks for a batch a waiting helper spins through before it sleeps (a few microseconds).
const SPINS: u32 = 256;

/// What a blend is measured from: the cut grid, the segments and their ends' corrections, the
/// support radius.
#[derive(Clone, Copy)]
pub struct BlendInputs<'a> {
    pub grid: &'a CutGrid,
    pub segments: &'a [CutSegment],
    pub corrections: &'a [[DVec3; 2]],
    pub r: f64,
}

/// The segments' ends around the cells asked about, with their corrections (see the module
/// doc), for one walk's inputs and one thread.
#[derive(Default)]
pub struct Blend {
    near: Near,
    /// Per cell, its range in `ends`.
    cells: FastMap<Cell, Range<usize>>,
    ends: Vec<(DVec3, DVec3)>,
    last: Option<(Cell, Range<usize>)>,
}

impl Blend {
    /// The correction at `p`: the corrections at the ends of the segments near it within the
    /// support, weighted by inverse squared distance; the correction of an end at `p` itself.
    pub fn correction_at(&mut self, inputs: &BlendInputs, p: DVec3) -> DVec3 {
        let c0 = cell_of(p, inputs.grid.size());
        let range = match &self.last {
            Some((c, range)) if *c == c0 => range.clone(),
            _ => {
                let (ends, near) = (&mut self.ends, &mut self.near);
                let range = self
                    .cells
                    .entry(c0)
                    .or_insert_with(|| {
                        let start = ends.len();
                        for &i in near.near(inputs.grid, p) {
                            let s = &inputs.segments[i];
                            ends.push((s.pa, inputs.corrections[i][0]));
                            ends.push((s.pb, inputs.corrections[i][1]));
                        }
                        start..ends.len()
                    })
                    .clone();
                self.last = Some((c0, range.clone()));
                range
            }
        };
        let (mut sum, mut weight) = (DVec3::ZERO, 0.0);
        let r2 = inputs.r * inputs.r;
        for &(end, c) in &self.ends[range] {
            let d2 = end.distance_squared(p);
            if d2 == 0.0 {
                return c;
            }
            if d2 < r2 {
                let k = d2.recip();
                sum += c * k;
                weight += k;
            }
        }
        if weight > 0.0 {
            sum / weight
        } else {
            DVec3::ZERO
        }
    }
}

/// The blends a walk asks for: which of its field entries, at which point.
type Asked = Vec<(u32, DVec3)>;

impl Blend {
    /// Adds to `out` the blend of every entry of `asked`, with its entry.
    fn measure(&mut self, inputs: &BlendInputs, asked: Asked, out: &mut Vec<(u32, DVec3)>) {
        out.extend(
            asked
                .into_iter()
                .map(|(k, p)| (k, self.correction_at(inputs, p))),
        );
    }
}

/// Batches of blends waiting for a thread, and whether more may come.
struct Queue {
    batches: Mutex<Vec<Asked>>,
    closed: AtomicBool,
}

impl Queue {
    fn take(&self) -> Option<Asked> {
        self.batches.lock().unwrap_or_else(|e| e.into_inner()).pop()
    }
}

/// Measures the batches of `queue` until it is closed and empty.
fn serve(queue: &Queue, inputs: &BlendInputs) -> Vec<(u32, DVec3)> {
    let mut blend = Blend::default();
    let mut out = Vec::new();
    let mut idle = 0u32;
    loop {
        if let Some(batch) = queue.take() {
            blend.measure(inputs, batch, &mut out);
            idle = 0;
            continue;
        }
        if queue.closed.load(Ordering::Acquire) {
            // Everything was queued before the close: one more look.
            match queue.take() {
                Some(batch) => blend.measure(inputs, batch, &mut out),
                None => return out,
            }
            continue;
        }
        // Waits for the next batch: a short spin (batches come every few tens of
        // microseconds), then asleep until the walk hands one over or closes the queue, so that
        // a waiting helper never takes the core the walk needs.
        idle += 1;
        if idle < SPINS {
            std::hint::spin_loop();
        } else {
            std::thread::park();
        }
    }
}

/// Where a walk asks for blends ([`with_blends`]).
pub struct Blends<'scope, 'env> {
    inputs: BlendInputs<'env>,
    queue: &'env Queue,
    scope: &'scope std::thread::Scope<'scope, 'env>,
    helper: Option<std::thread::ScopedJoinHandle<'scope, Vec<(u32, DVec3)>>>,
    /// No second thread could be started.
    alone: bool,
    /// Batches queued so far.
    queued: usize,
    pending: Asked,
}

impl Blends<'_, '_> {
    /// No more batches will come: the helper, if any, finishes what is queued and ends.
    fn close(&self) {
        self.queue.closed.store(true, Ordering::Release);
        if let Some(helper) = &self.helper {
            helper.thread().unpark();
        }
    }

    /// Asks for the blend at `p`, for entry `k` of the walk's field.
    pub fn ask(&mut self, k: u32, p: DVec3) {
        self.pending.push((k, p));
        if self.pending.len() == BATCH {
            let batch = std::mem::replace(&mut self.pending, Vec::with_capacity(BATCH));
            self.queue
                .batches
                .lock()
                .unwrap_or_else(|e| e.into_inner())
                .push(batch);
            self.queued += 1;
            if let Some(helper) = &self.helper {
                helper.thread().unpark();
            } else if !self.alone && self.queued >= START_AT {
                let (queue, inputs) = (self.queue, self.inputs);
                // Without a second thread (the system refused one) this thread measures them
                // all when the walk is done.
                match std::thread::Builder::new()
                    .spawn_scoped(self.scope, move || serve(queue, &inputs))
                {
                    Ok(helper) => self.helper = Some(helper),
                    Err(_) => self.alone = true,
                }
            }
        }
    }
}

/// A walk that panics leaves through here too: the helper must end, or the scope would wait
/// for it forever.
impl Drop for Blends<'_, '_> {
    fn drop(&mut self) {
        self.close();
    }
}

/// Runs `walk`, which asks for blends ([`Blends::ask`]), and gives what it returns with every
/// blend it asked for (entry, correction), in no order. The blends are measured on a second
/// thread as they are asked for, in batches, and on this one once `walk` returns (see the
/// module doc).
pub fn with_blends<R>(
    inputs: BlendInputs,
    walk: impl FnOnce(&mut Blends) -> R,
) -> (R, Vec<(u32, DVec3)>) {
    let queue = Queue {
        batches: Mutex::new(Vec::new()),
        closed: AtomicBool::new(false),
    };
    std::thread::scope(|scope| {
        let mut blends = Blends {
            inputs,
            queue: &queue,
            scope,
            helper: None,
            alone: false,
            queued: 0,
            pending: Vec::with_capacity(BATCH),
        };
        let out = walk(&mut blends);
        let mut measured: Vec<(u32, DVec3)> = Vec::new();
        let mut blend = Blend::default();
        blend.measure(&inputs, std::mem::take(&mut blends.pending), &mut measured);
        blends.close();
        while let Some(batch) = queue.take() {
            blend.measure(&inputs, batch, &mut measured);
        }
        if let Some(helper) = blends.helper.take() {
            match helper.join() {
                Ok(theirs) => measured.extend(theirs),
                Err(panic) => std::panic::resume_unwind(panic),
            }
        }
        (out, measured)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blends_measured_on_two_threads_are_those_measured_on_one() {
        let mut rng = csg::testkit::SplitMix(31);
        let mut random = || rng.next_f64();
        let mut points = vec![DVec3::ZERO];
        for _ in 0..200 {
            let last = *points.last().unwrap();
            points.push(last + DVec3::new(0.4, random() - 0.5, 0.1 * (random() - 0.5)));
        }
        let segments: Vec<CutSegment> = points
            .windows(2)
            .map(|w| CutSegment::between(w[0], w[1]))
            .collect();
        let corrections: Vec<[DVec3; 2]> = (0..segments.len())
            .map(|_| {
                [
                    DVec3::new(random(), random(), random()),
                    DVec3::splat(random()),
                ]
            })
            .collect();
        let r = 3.0;
        let grid = CutGrid::new(&segments, 2, r);
        let inputs = BlendInputs {
            grid: &grid,
            segments: &segments,
            corrections: &corrections,
            r,
        };
        let asked: Vec<DVec3> = (0..3000)
            .map(|k| {
                let q = points[k % points.len()];
                if k % 7 == 0 {
                    q
                } else {
                    q + (DVec3::new(random(), random(), random()) - 0.5) * 4.0
                }
            })
            .collect();
        let mut one = Blend::default();
        let want: Vec<DVec3> = asked
            .iter()
            .map(|&p| one.correction_at(&inputs, p))
            .collect();
        let ((), mut got) = with_blends(inputs, |blends| {
            for (k, &p) in asked.iter().enumerate() {
                blends.ask(k as u32, p);
            }
        });
        got.sort_by_key(|g| g.0);
        assert_eq!(got.len(), asked.len());
        for (k, c) in got {
            assert_eq!(
                c.to_array().map(f64::to_bits),
                want[k as usize].to_array().map(f64::to_bits)
            );
        }
        // Points at an end take its correction.
        assert_eq!(one.correction_at(&inputs, points[5]), corrections[4][1]);
    }

    #[test]
    fn a_walk_that_panics_ends_the_helper_and_panics() {
        // On its own thread, so that a walk that never ends fails the test instead of hanging it.
        let (done, ended) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let segments = vec![CutSegment::between(DVec3::ZERO, DVec3::X)];
            let corrections = vec![[DVec3::X, DVec3::Y]];
            let grid = CutGrid::new(&segments, 2, 1.0);
            let inputs = BlendInputs {
                grid: &grid,
                segments: &segments,
                corrections: &corrections,
                r: 1.0,
            };
            let walked = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                with_blends(inputs, |blends| {
                    // Enough batches for the helper to start, then wait for more.
                    for k in 0..(START_AT + 2) * BATCH {
                        blends.ask(k as u32, DVec3::new(0.5, 0.1, 0.0));
                    }
                    std::thread::sleep(std::time::Duration::from_millis(20));
                    panic!("the walk fails");
                })
            }));
            let _ = done.send(walked.is_err());
        });
        let panicked = ended.recv_timeout(std::time::Duration::from_secs(30));
        assert_eq!(panicked, Ok(true), "the walk did not end, or did not panic");
    }
}
