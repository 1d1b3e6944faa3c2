//! Work shared among the machine's cores, natively; one after another in WebAssembly, where a
//! page runs the library in one worker.
//!
//! Every use gives the same result on any number of threads: the work is split so that what
//! each thread returns does not depend on how many there are, and is put together in a fixed
//! order. Thread counts decide only how long it takes.

/// How many threads a stage shares `work` among, natively: the machine's cores, at most four,
/// and at least `per_thread` of the work each (starting a thread costs tens of microseconds);
/// 1 when there is too little to share or one core.
#[cfg(not(target_arch = "wasm32"))]
pub(crate) fn threads_for(work: usize, per_thread: usize) -> usize {
    let cores = std::thread::available_parallelism().map_or(1, |p| p.get().min(4));
    cores.min(work / per_thread.max(1)).max(1)
}

/// Runs `a` and `b` and returns both results: side by side natively when the machine has more
/// than one core, `a` then `b` otherwise. A panic in either is a panic here, as it would be
/// had they run in turn.
pub(crate) fn join<A: Send, B: Send>(a: impl FnOnce() -> A + Send, b: impl FnOnce() -> B) -> (A, B) {
    #[cfg(not(target_arch = "wasm32"))]
    if threads_for(2, 1) > 1 {
        return std::thread::scope(|s| {
            let a = s.spawn(a);
            let b = b();
            (a.join().unwrap_or_else(|p| std::panic::resume_unwind(p)), b)
        });
    }
    let a = a();
    (a, b())
}

#[cfg(test)]
mod tests {
    #[test]
    fn join_returns_both_results_in_their_places() {
        let v = [1u64, 2, 3];
        let (a, b) = super::join(|| v.iter().sum::<u64>(), || v.len());
        assert_eq!((a, b), (6, 3));
    }

    #[test]
    #[should_panic(expected = "from a")]
    fn a_panic_on_the_other_thread_is_a_panic_here() {
        let _ = super::join(|| -> u8 { panic!("from a") }, || 1);
    }
}
