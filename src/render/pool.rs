//! The worker pools: one long-lived rayon pool per thread count, built on first use and shared
//! by every render job, the command line and the tests. An orbit drag restarts a job on each
//! mouse move; building a pool (and its threads) for each of them cost a thread start per
//! worker per restart.

use rayon::ThreadPool;
use std::sync::{Arc, Mutex, PoisonError};

/// Each render worker's stack (address space reserved, touched only as deep as a render goes).
#[cfg(not(target_arch = "wasm32"))]
const WORKER_STACK: usize = 16 << 20;

/// The most worker threads a user may ask for. More threads than this only add start-up time and
/// memory (a render uses at most one tile of 8 rows per thread); `--threads 100000` would take
/// minutes to start.
pub const MAX_THREADS: usize = 1024;

/// Why no pool could be had.
#[derive(Debug, thiserror::Error)]
pub enum PoolError {
    /// The count is above [`MAX_THREADS`].
    #[error("{threads} worker threads asked for; at most {MAX_THREADS} are allowed")]
    TooMany {
        /// The count asked for.
        threads: usize,
    },
    /// The operating system refused to start the threads.
    #[error("cannot start {threads} worker threads: {source}")]
    Build {
        /// The count asked for (0: one per core).
        threads: usize,
        /// What rayon reported.
        source: rayon::ThreadPoolBuildError,
    },
}

/// Pools built so far, by requested thread count (0: one per core).
static POOLS: Mutex<Vec<(usize, Arc<ThreadPool>)>> = Mutex::new(Vec::new());

/// The shared pool of `threads` workers (0: one per core), built on the first call for that
/// count and kept for the life of the process.
///
/// # Errors
/// `threads` is above [`MAX_THREADS`], or the threads could not be started.
pub fn thread_pool(threads: usize) -> Result<Arc<ThreadPool>, PoolError> {
    if threads > MAX_THREADS {
        return Err(PoolError::TooMany { threads });
    }
    let mut pools = POOLS.lock().unwrap_or_else(PoisonError::into_inner);
    if let Some((_, pool)) = pools.iter().find(|(n, _)| *n == threads) {
        return Ok(pool.clone());
    }
    #[cfg(not(target_arch = "wasm32"))]
    // The kernel traces mirrors and clip maps as nested packets, a call level each (up to the
    // 64 bounces `reflection_depth` allows, times the clip layers): room for that, reserved
    // (not committed) per worker.
    let builder = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .stack_size(WORKER_STACK)
        .thread_name(|i| format!("texplore-worker-{i}"));
    // A page has one thread: the pool is that thread, so `install` and parallel iterators run
    // their work in place. One such pool serves every count (a thread joins one pool only).
    #[cfg(target_arch = "wasm32")]
    let builder = {
        if let Some((_, pool)) = pools.first() {
            return Ok(pool.clone());
        }
        rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .use_current_thread()
    };
    let pool = builder
        .build()
        .map_err(|source| PoolError::Build { threads, source })?;
    let pool = Arc::new(pool);
    pools.push((threads, pool.clone()));
    Ok(pool)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_pool_per_count_is_shared() {
        let a = thread_pool(3).unwrap();
        let b = thread_pool(3).unwrap();
        assert!(Arc::ptr_eq(&a, &b));
        assert_eq!(a.current_num_threads(), 3);
        assert!(!Arc::ptr_eq(&a, &thread_pool(1).unwrap()));
    }

    #[test]
    fn absurd_counts_are_refused_with_the_limit() {
        let e = thread_pool(100_000).unwrap_err();
        assert_eq!(
            e.to_string(),
            "100000 worker threads asked for; at most 1024 are allowed"
        );
    }
}
