//! Running a pipeline of many short parallel steps on rayon's pool with its other
//! workers kept awake.
//!
//! A rayon worker with nothing to do sleeps after a few dozen polls, and waking it takes
//! tens of microseconds. A pipeline whose parallel steps last a fraction of a
//! millisecond, with short sequential steps between them (the levels of a subdivision),
//! pays that wake-up at every step. Here the other workers poll for work until the
//! pipeline ends, as OpenMP runtimes keep theirs spinning for a while, and the thread
//! running the pipeline keeps looking for work whenever it waits for a job it handed out.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::{Duration, Instant};

/// Sets the flag when dropped, so that the pollers stop even if the body panics.
struct DoneOnDrop<'a>(&'a AtomicBool);

impl Drop for DoneOnDrop<'_> {
    fn drop(&mut self) {
        self.0.store(true, Ordering::Release);
    }
}

/// Runs `body` on a worker of rayon's current pool while every other worker of the pool
/// polls for work (taking any job the body hands out) instead of sleeping. Costs the
/// other workers' idle time while `body` runs; on a pool of one thread it only moves
/// `body` onto that thread. The result is the same as `body()`.
///
/// ```
/// use rayon::prelude::*;
/// let sum: u64 = qmesh::awake_pool::with_workers_awake(|| (0..1000u64).into_par_iter().sum());
/// assert_eq!(sum, 499_500);
/// ```
pub fn with_workers_awake<R: Send>(body: impl FnOnce() -> R + Send) -> R {
    let done = Arc::new(AtomicBool::new(false));
    // The worker that runs `body`: a poller that lands there (taken back while the body
    // waits for a job) must return at once, or the body would never resume.
    let owner = AtomicUsize::new(usize::MAX);
    rayon::scope(|_| {
        owner.store(rayon::current_thread_index().unwrap_or(usize::MAX), Ordering::Relaxed);
        let pollers = rayon::current_num_threads() - 1;
        if pollers == 0 {
            return body();
        }
        let (result, ()) = rayon::join(
            || {
                let _done = DoneOnDrop(&done);
                stay_awake(Arc::clone(&done), owner.load(Ordering::Relaxed));
                body()
            },
            || {
                use rayon::prelude::*;
                (0..pollers).into_par_iter().with_max_len(1).for_each(|_| poll_until(&done, &owner));
            },
        );
        result
    })
}

/// How long the body's thread looks for work each time it finds nothing to do (see
/// [`stay_awake`]).
const AWAKE_SLICE: Duration = Duration::from_micros(5);

/// Keeps the body's thread (`owner`) from falling asleep while it waits for a job it
/// handed out, until `done`. A rayon worker that finds no work for a few dozen polls
/// sleeps, and on a virtual machine whose idle cores halt, waking it takes 30-150 µs
/// (`perf sched timehist`); the body's thread waits like that at the end of most
/// parallel steps. Here a job waits in that thread's broadcast queue, which it looks at
/// when its own queue is empty, before stealing: the job looks for work (stealing, as
/// the wait would) for [`AWAKE_SLICE`], then puts a new one there and returns, so that
/// the waiting thread checks whether its wait is over.
fn stay_awake(done: Arc<AtomicBool>, owner: usize) {
    rayon::spawn_broadcast(move |ctx| {
        if ctx.index() != owner || done.load(Ordering::Acquire) {
            return;
        }
        let start = Instant::now();
        while !done.load(Ordering::Acquire) && start.elapsed() < AWAKE_SLICE {
            if rayon::yield_now() != Some(rayon::Yield::Executed) {
                (0..64).for_each(|_| std::hint::spin_loop());
            }
        }
        if !done.load(Ordering::Acquire) {
            stay_awake(Arc::clone(&done), owner);
        }
    });
}

/// Runs the pool's pending jobs, one at a time, until `done` (at once on the `owner`'s
/// thread).
fn poll_until(done: &AtomicBool, owner: &AtomicUsize) {
    if rayon::current_thread_index() == Some(owner.load(Ordering::Relaxed)) {
        return;
    }
    while !done.load(Ordering::Acquire) {
        if rayon::yield_now() != Some(rayon::Yield::Executed) {
            // Back off a little between polls, so as not to keep the body's queue's
            // cache line busy.
            (0..64).for_each(|_| std::hint::spin_loop());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rayon::prelude::*;

    /// The body's parallel work gives the same result on pools of 1 to 4 threads, the
    /// body runs on a worker, and every poller stops when it ends.
    #[test]
    fn the_body_runs_on_a_worker_and_the_pollers_stop() {
        for threads in 1..=4 {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            for _ in 0..20 {
                let (on_worker, sum) = pool.install(|| {
                    with_workers_awake(|| {
                        let nested: u64 = (0..10_000u64)
                            .into_par_iter()
                            .map(|i| rayon::join(|| i, || i).0 + (0..i % 7).into_par_iter().sum::<u64>())
                            .sum();
                        (rayon::current_thread_index().is_some(), nested)
                    })
                });
                let expected: u64 = (0..10_000u64).map(|i| i + (0..i % 7).sum::<u64>()).sum();
                assert!(on_worker);
                assert_eq!(sum, expected, "{threads} threads");
            }
        }
    }

    /// A panic in the body reaches the caller: the pollers stop instead of waiting for
    /// ever.
    #[test]
    fn a_panicking_body_does_not_hang() {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build().unwrap();
        let caught = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            pool.install(|| with_workers_awake(|| panic!("body fails")))
        }));
        assert!(caught.is_err());
    }
}
