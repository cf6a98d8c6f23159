//! The page's driver (wasm32): the tasks queued for the page's thread, the live renders, and
//! the render workers, run between frames by [`run_slices`] and when a worker's message arrives.
use super::{Farm, Port, SlicedRender};
use std::cell::RefCell;
use std::collections::VecDeque;
use std::path::PathBuf;
use std::sync::{Arc, Mutex, PoisonError, Weak};
use std::time::Duration;
use web_time::Instant;

/// Work queued for the page's thread, and the files it reads (it waits for their download).
type Queued = (Vec<PathBuf>, Box<dyn FnOnce()>);

thread_local! {
    /// Tasks not run yet, oldest first.
    static QUEUE: RefCell<VecDeque<Queued>> = RefCell::new(VecDeque::new());
    /// Every render job alive (a dropped job's entry no longer upgrades).
    static RENDERS: RefCell<Vec<Weak<Mutex<SlicedRender>>>> = const { RefCell::new(Vec::new()) };
    /// The page's render workers.
    static FARM: RefCell<Farm> = RefCell::new(Farm::new());
    /// Renders dropped since the farm last heard: their chunks are cancelled in workers.
    static DROPPED: RefCell<Vec<u64>> = const { RefCell::new(Vec::new()) };
}

/// Queues a task's work for [`run_slices`].
pub(in crate::render) fn queue(work: Box<dyn FnOnce()>) {
    queue_after(Vec::new(), work);
}

/// Queues a task's work for [`run_slices`], to run once `files` are downloaded.
pub(in crate::render) fn queue_after(files: Vec<PathBuf>, work: Box<dyn FnOnce()>) {
    QUEUE.with(|q| q.borrow_mut().push_back((files, work)));
}

/// Runs the oldest queued task whose files are in (with `force`, the oldest, files or not:
/// waiting for it cannot wait for a download); false when there was none.
pub(in crate::render) fn run_one(force: bool) -> bool {
    // Out of the borrow: the work may queue more.
    let next = QUEUE.with(|q| {
        let mut q = q.borrow_mut();
        let i = q
            .iter()
            .position(|(files, _)| force || files.iter().all(|f| crate::input::is_ready(f)))?;
        q.remove(i)
    });
    next.map(|(_, work)| work()).is_some()
}

/// Registers a render for [`run_slices`].
pub(in crate::render) fn register(render: SlicedRender) -> Arc<Mutex<SlicedRender>> {
    let render = Arc::new(Mutex::new(render));
    RENDERS.with(|r| r.borrow_mut().push(Arc::downgrade(&render)));
    render
}

/// A render was dropped: its chunks are cancelled at the next chance.
pub(super) fn dropped(job: u64) {
    DROPPED.with(|d| d.borrow_mut().push(job));
}

/// Runs `render` to its end (what waiting for a job means without threads): on the page's
/// thread alone, since a worker's answers come only between the page's tasks.
pub(in crate::render) fn finish(render: &Mutex<SlicedRender>) {
    let mut r = render.lock().unwrap_or_else(PoisonError::into_inner);
    with_farm(|f| f.cancel(r.job));
    r.reclaim();
    let mut alone = Farm::new();
    while r.step(Instant::now() + Duration::from_hours(1), &mut alone) {}
}

fn live() -> Vec<Arc<Mutex<SlicedRender>>> {
    RENDERS.with(|r| {
        let mut r = r.borrow_mut();
        r.retain(|w| w.strong_count() > 0);
        r.iter().filter_map(Weak::upgrade).collect()
    })
}

fn with_farm<T>(f: impl FnOnce(&mut Farm) -> T) -> T {
    FARM.with(|farm| {
        let mut farm = farm.borrow_mut();
        for job in DROPPED.with(|d| std::mem::take(&mut *d.borrow_mut())) {
            farm.cancel(job);
        }
        f(&mut farm)
    })
}

/// Adds a render worker (the page's glue made it); returns its number.
#[must_use]
pub fn add_worker(port: Box<dyn Port>) -> usize {
    with_farm(|f| f.add(port))
}

/// Worker `worker`'s message: answers go into their renders' films, and the workers get
/// more tiles.
///
/// # Errors
/// The bytes are not a worker's message.
pub fn worker_message(worker: usize, bytes: &[u8]) -> Result<(), String> {
    with_farm(|f| f.receive(worker, bytes))?;
    pump();
    Ok(())
}

/// Worker `worker` crashed: its tiles are rendered again elsewhere.
pub fn worker_lost(worker: usize) {
    with_farm(|f| f.lost(worker));
    pump();
}

/// What went wrong in the workers since the last call.
pub fn worker_errors() -> Vec<String> {
    with_farm(Farm::take_errors)
}

/// Each worker's memory in bytes, as it last said, the chunks it rendered, and whether it is
/// alive.
#[must_use]
pub fn worker_memory() -> Vec<(u64, u64, bool)> {
    with_farm(|f| f.memory())
}

/// Takes in the workers' answers and hands out tiles, for every live render.
fn pump() {
    let live = live();
    with_farm(|farm| {
        for render in &live {
            let mut render = render.lock().unwrap_or_else(PoisonError::into_inner);
            render.pump(farm);
        }
    });
}

/// Runs the page's background work for about `budget`: the queued tasks whose files are in
/// (scene builds, coverage passes; each runs whole), then the live renders: their workers'
/// answers taken in and tiles handed out, and the tiles no worker can take rendered here,
/// the time left shared between them. Returns whether work remains for this thread (the
/// caller asks for another frame).
#[must_use]
pub fn run_slices(budget: Duration) -> bool {
    let deadline = Instant::now() + budget;
    while Instant::now() < deadline && run_one(false) {}
    let live = live();
    let busy = with_farm(|farm| {
        farm.forget_unused();
        let mut busy = 0;
        for (i, render) in live.iter().enumerate() {
            let mut render = render.lock().unwrap_or_else(PoisonError::into_inner);
            if render.is_done() {
                continue;
            }
            let left = deadline.saturating_duration_since(Instant::now());
            let share = left / u32::try_from(live.len() - i).unwrap_or(u32::MAX);
            busy += usize::from(render.step(Instant::now() + share, farm));
        }
        busy
    });
    busy > 0
        || QUEUE.with(|q| {
            q.borrow()
                .iter()
                .any(|(files, _)| files.iter().all(|f| crate::input::is_ready(f)))
        })
}
