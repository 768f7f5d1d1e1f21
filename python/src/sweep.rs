//! Long sweeps from Python: the units of work (the levels of an OAS, the pulse durations of an
//! OC) run in parallel on rayon with the GIL released, while the calling thread waits for them
//! and, every [`POLL`], takes the GIL back briefly to check for signals (Ctrl-C raises
//! `KeyboardInterrupt` there) and to report progress. On an interrupt no new unit starts, the
//! running ones finish, and the exception is raised.
//!
//! Every unit is computed independently of the others and the results are collected in their
//! order, so the answer does not depend on the number of threads (the library's determinism).

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::mpsc;
use std::time::Duration;

use pyo3::prelude::*;
use rayon::prelude::*;

use crate::errors::value_error;

/// How often the waiting thread checks for signals and reports progress.
const POLL: Duration = Duration::from_millis(50);

/// The most threads a sweep starts (the library's, as the CLI's `--threads`).
pub use rocking::validate::MAX_THREADS;

/// The most points a grid count (`levels=`, `sizes=`, `ptp=`, `radius_n=`, …) asks for (the
/// library's, as the CLI's grid counts).
pub use rocking::validate::MAX_GRID_POINTS as MAX_COUNT;

/// A grid count `n` (already ≥ 1) within [`MAX_COUNT`], named.
pub fn check_count(name: &str, n: usize) -> PyResult<usize> {
    if n > MAX_COUNT {
        return Err(value_error(format!(
            "{name} = {n}: a grid of at most {MAX_COUNT} points (one simulation or more each)"
        )));
    }
    Ok(n)
}

/// How a sweep runs: on how many threads, and whom it tells how far it got.
pub struct Runner {
    /// Threads (`None`: rayon's global pool, every core).
    pub threads: Option<usize>,
    /// A Python callable `progress(done, total)`, called from the calling thread as units finish.
    pub progress: Option<Py<PyAny>>,
}

impl Runner {
    /// `(0..n).map(work)` in parallel, interruptible between units; the results in order.
    pub fn map<T, F>(&self, py: Python<'_>, n: usize, work: F) -> PyResult<Vec<T>>
    where
        T: Send,
        F: Fn(usize) -> T + Sync,
    {
        let pool = match self.threads {
            Some(t) if !(1..=MAX_THREADS).contains(&t) => {
                return Err(value_error(format!(
                    "threads = {t}: must be in 1..={MAX_THREADS}"
                )))
            }
            Some(t) => Some(
                rayon::ThreadPoolBuilder::new()
                    .num_threads(t)
                    .build()
                    .map_err(|e| value_error(format!("threads = {t}: {e}")))?,
            ),
            None => None,
        };
        let cancel = AtomicBool::new(false);
        let done = AtomicUsize::new(0);
        let unit = |i: usize| {
            if cancel.load(Ordering::Relaxed) {
                return None;
            }
            let r = work(i);
            done.fetch_add(1, Ordering::Relaxed);
            Some(r)
        };
        let all = || -> Vec<Option<T>> { (0..n).into_par_iter().map(unit).collect() };
        let (results, stopped) = py.detach(|| {
            std::thread::scope(|s| {
                let (tx, rx) = mpsc::channel::<()>();
                let worker = s.spawn(move || {
                    let r = match &pool {
                        Some(p) => p.install(all),
                        None => all(),
                    };
                    // The receiver lives until the join below.
                    let _ = tx.send(());
                    r
                });
                let mut stopped: Option<PyErr> = None;
                let mut reported = usize::MAX;
                loop {
                    let finished = rx.recv_timeout(POLL).is_ok();
                    if stopped.is_none() {
                        stopped = Python::attach(|py| self.poll(py, &done, n, &mut reported)).err();
                        if stopped.is_some() {
                            cancel.store(true, Ordering::Relaxed);
                        }
                    }
                    if finished {
                        break;
                    }
                }
                // A panic in the library is a bug: pass it on as a panic (pyo3 turns it into
                // `PanicException`).
                let results = worker
                    .join()
                    .unwrap_or_else(|p| std::panic::resume_unwind(p));
                (results, stopped)
            })
        });
        if let Some(e) = stopped {
            return Err(e);
        }
        Ok(results
            .into_iter()
            .map(|r| r.expect("every unit ran without an interrupt"))
            .collect())
    }

    /// Signals (Ctrl-C), then the progress callback when something new finished.
    fn poll(
        &self,
        py: Python<'_>,
        done: &AtomicUsize,
        total: usize,
        reported: &mut usize,
    ) -> PyResult<()> {
        py.check_signals()?;
        if let Some(cb) = &self.progress {
            let d = done.load(Ordering::Relaxed);
            if d != *reported {
                *reported = d;
                cb.call1(py, (d, total))?;
            }
        }
        Ok(())
    }
}

/// What the progress callback of an [`interruptible`] run unwinds with after Ctrl-C.
struct Interrupted;

/// Runs `work` on a thread of its own with the GIL released, handing it a progress callback;
/// this thread takes the GIL back every [`POLL`] to check for signals. On Ctrl-C the callback
/// unwinds the run at its next report (the simulations report every 1 % of their steps) and
/// the `KeyboardInterrupt` is raised: a drum column through a whole record takes seconds to
/// minutes, and Ctrl-C waited for its end. Returns what `work` returned and its wall time (s).
pub fn interruptible<T, F>(py: Python<'_>, work: F) -> PyResult<(T, f64)>
where
    T: Send,
    F: FnOnce(&mut dyn FnMut(f64)) -> T + Send,
{
    let cancel = AtomicBool::new(false);
    let (result, stopped) = py.detach(|| {
        std::thread::scope(|s| {
            let (tx, rx) = mpsc::channel::<()>();
            let cancel = &cancel;
            // The stack of a main thread (8 MiB), where the run went before, not a spawned
            // thread's 2 MiB.
            let worker = std::thread::Builder::new()
                .stack_size(8 << 20)
                .spawn_scoped(s, move || {
                    let mut progress = |_: f64| {
                        if cancel.load(Ordering::Relaxed) {
                            // Not a panic: no hook runs, nothing is printed.
                            std::panic::resume_unwind(Box::new(Interrupted));
                        }
                    };
                    let started = std::time::Instant::now();
                    let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                        work(&mut progress)
                    }));
                    let wall = started.elapsed().as_secs_f64();
                    // The receiver lives until the join below.
                    let _ = tx.send(());
                    r.map(|t| (t, wall))
                });
            let worker = match worker {
                Ok(w) => w,
                Err(e) => return Err(value_error(format!("cannot start the run's thread: {e}"))),
            };
            let mut stopped: Option<PyErr> = None;
            loop {
                let finished = rx.recv_timeout(POLL).is_ok();
                if stopped.is_none() {
                    stopped = Python::attach(|py| py.check_signals()).err();
                    if stopped.is_some() {
                        cancel.store(true, Ordering::Relaxed);
                    }
                }
                if finished {
                    break;
                }
            }
            let result = worker
                .join()
                .unwrap_or_else(|p| std::panic::resume_unwind(p));
            Ok((result, stopped))
        })
    })?;
    match result {
        // A run that finished before the signal was seen: the signal still interrupts.
        Ok(r) => match stopped {
            Some(e) => Err(e),
            None => Ok(r),
        },
        Err(payload) if payload.is::<Interrupted>() => {
            Err(stopped.expect("interrupted only after a signal"))
        }
        // A panic in the library is a bug: pass it on (pyo3 turns it into `PanicException`).
        Err(payload) => std::panic::resume_unwind(payload),
    }
}
