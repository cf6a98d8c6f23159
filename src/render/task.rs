//! A computation on a shared worker pool whose result a viewer polls or waits for: render
//! jobs, the window's scene builds, the texture panel's coverage passes and the speed panel's
//! measurements. Dropping the task (or replacing it with a newer one) cancels it: the work sees
//! its flag set and its result is thrown away. A panic inside the work is caught and reported
//! (rayon would abort the process).

use super::pool::PoolError;
#[cfg(not(target_arch = "wasm32"))]
use super::pool::thread_pool;
use rayon::ThreadPool;
use std::panic::AssertUnwindSafe;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Condvar, Mutex, MutexGuard, PoisonError};

/// Where a task is.
#[derive(Debug)]
enum State<T> {
    Running,
    Done(T),
    /// The work returned nothing (it noticed its cancellation) or its result was taken.
    Empty,
    Panicked(String),
}

/// What a task and its viewer share: where it is, and the signal that it ended.
struct Shared<T> {
    state: Mutex<State<T>>,
    ended: Condvar,
}

/// A computation running on a worker pool.
pub struct Task<T> {
    cancel: Arc<AtomicBool>,
    shared: Arc<Shared<T>>,
}

impl<T> std::fmt::Debug for Task<T> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Task")
            .field("running", &self.is_running())
            .finish_non_exhaustive()
    }
}

impl<T: Send + 'static> Task<T> {
    /// Runs `work` on the shared pool of one thread per core; `work` should return `None` soon
    /// after its flag is set. On wasm32 (no threads) the work is queued and runs whole on the
    /// page's thread between frames (`render::run_slices`).
    ///
    /// # Errors
    /// No worker pool could be had.
    pub fn spawn(
        work: impl FnOnce(&AtomicBool) -> Option<T> + Send + 'static,
    ) -> Result<Self, PoolError> {
        #[cfg(not(target_arch = "wasm32"))]
        return thread_pool(0).map(|pool| Self::spawn_on(&pool, work));
        #[cfg(target_arch = "wasm32")]
        {
            let (task, run) = Self::new(work);
            super::slices::queue(Box::new(run));
            Ok(task)
        }
    }

    /// [`Task::spawn`] of work that reads `files`: in a page, where a shipped file may not be
    /// downloaded yet (`input::want`), the work waits in the queue until they are (or their
    /// download failed, which the work's read then reports); elsewhere the files are on disk and
    /// this is [`Task::spawn`].
    ///
    /// # Errors
    /// No worker pool could be had.
    pub fn spawn_reading(
        files: Vec<std::path::PathBuf>,
        work: impl FnOnce(&AtomicBool) -> Option<T> + Send + 'static,
    ) -> Result<Self, PoolError> {
        #[cfg(not(target_arch = "wasm32"))]
        {
            drop(files);
            Self::spawn(work)
        }
        #[cfg(target_arch = "wasm32")]
        {
            crate::input::want(&files);
            let (task, run) = Self::new(work);
            super::slices::queue_after(files, Box::new(run));
            Ok(task)
        }
    }

    /// Runs `work` on `pool` (a pool of [`thread_pool`](super::thread_pool)).
    pub fn spawn_on(
        pool: &ThreadPool,
        work: impl FnOnce(&AtomicBool) -> Option<T> + Send + 'static,
    ) -> Self {
        let (task, run) = Self::new(work);
        pool.spawn(run);
        task
    }

    /// The task of `work` and what runs it: the work, then its result recorded and the viewer
    /// woken.
    fn new(
        work: impl FnOnce(&AtomicBool) -> Option<T> + Send + 'static,
    ) -> (Self, impl FnOnce() + Send + 'static) {
        let cancel = Arc::new(AtomicBool::new(false));
        let shared = Arc::new(Shared {
            state: Mutex::new(State::Running),
            ended: Condvar::new(),
        });
        let (c, s) = (cancel.clone(), shared.clone());
        let run = move || {
            let out = std::panic::catch_unwind(AssertUnwindSafe(|| work(&c)));
            let mut state = s.state.lock().unwrap_or_else(PoisonError::into_inner);
            *state = match out {
                Ok(Some(v)) if !c.load(Ordering::Relaxed) => State::Done(v),
                Ok(_) => State::Empty,
                Err(panic) => State::Panicked(
                    panic
                        .downcast_ref::<&str>()
                        .map(ToString::to_string)
                        .or_else(|| panic.downcast_ref::<String>().cloned())
                        .unwrap_or_else(|| "unknown panic".into()),
                ),
            };
            drop(state);
            s.ended.notify_all();
        };
        (Self { cancel, shared }, run)
    }
}

impl<T> Task<T> {
    fn lock(&self) -> MutexGuard<'_, State<T>> {
        self.shared
            .state
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
    }

    /// Blocks until the work has returned (or unwound). Do not call it from a worker of the
    /// task's own pool.
    pub fn wait(&self) {
        // Without threads, waiting is running the queued work up to this task's.
        #[cfg(target_arch = "wasm32")]
        while self.is_running() && super::slices::run_one(true) {}
        let mut s = self.lock();
        while matches!(*s, State::Running) {
            s = self
                .shared
                .ended
                .wait(s)
                .unwrap_or_else(PoisonError::into_inner);
        }
    }

    /// The result, once (`None` while running, after it was taken, if it was cancelled or if
    /// the work panicked).
    pub fn take(&self) -> Option<T> {
        let mut s = self.lock();
        match std::mem::replace(&mut *s, State::Empty) {
            State::Done(v) => Some(v),
            other => {
                *s = other;
                None
            }
        }
    }

    /// Whether the work has not returned yet.
    #[must_use]
    pub fn is_running(&self) -> bool {
        matches!(*self.lock(), State::Running)
    }

    /// Why the work stopped without a result, when it panicked.
    #[must_use]
    pub fn failure(&self) -> Option<String> {
        match &*self.lock() {
            State::Panicked(what) => Some(what.clone()),
            _ => None,
        }
    }

    /// Asks the work to stop (as dropping the task does); its result will be thrown away.
    pub fn cancel(&self) {
        self.cancel.store(true, Ordering::Relaxed);
    }
}

impl<T> Drop for Task<T> {
    fn drop(&mut self) {
        self.cancel();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::{Duration, Instant};

    fn wait<T>(t: &Task<T>) {
        let start = Instant::now();
        while t.is_running() {
            assert!(start.elapsed() < Duration::from_secs(30), "the task ends");
            std::thread::sleep(Duration::from_millis(1));
        }
    }

    #[test]
    fn a_result_is_taken_once() {
        let t = Task::spawn(|_| Some(42)).unwrap();
        wait(&t);
        assert_eq!(t.take(), Some(42));
        assert_eq!(t.take(), None);
        assert_eq!(t.failure(), None);
    }

    #[test]
    fn a_cancelled_task_leaves_no_result() {
        let (go, wait_go) = std::sync::mpsc::channel::<()>();
        let t = Task::spawn(move |_| {
            let _ = wait_go.recv();
            Some(1)
        })
        .unwrap();
        t.cancel();
        go.send(()).unwrap();
        wait(&t);
        assert_eq!(t.take(), None);
    }

    #[test]
    fn a_panic_is_reported_not_fatal() {
        let t: Task<u8> = Task::spawn(|_| panic!("boom")).unwrap();
        t.wait();
        assert!(!t.is_running());
        assert_eq!(t.take(), None);
        assert_eq!(t.failure().as_deref(), Some("boom"));
    }
}
