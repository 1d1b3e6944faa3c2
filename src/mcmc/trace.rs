//! What a chain did: log posterior over time, acceptance over a sliding window, per-kernel
//! counts. Small and allocation-free per step, so a frame loop can read it every frame.

use super::Kernel;
use serde::Serialize;

/// One recorded point of the trace.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TracePoint {
    /// Iteration number.
    pub iteration: u64,
    /// Log posterior of the current state.
    pub log_posterior: f64,
    /// Acceptance rate over the recent window.
    pub acceptance: f64,
    /// Number of units (or objects) in the current state.
    pub size: u32,
}

/// Chain statistics.
#[derive(Debug, Clone, Serialize)]
pub struct Trace {
    /// Proposals per kernel, in [`Kernel::ALL`] order.
    pub proposed: [u64; 9],
    /// Accepted proposals per kernel.
    pub accepted: [u64; 9],
    /// Recorded points (one every `every` iterations).
    pub points: Vec<TracePoint>,
    /// Record a point every this many iterations.
    pub every: u64,
    window: Vec<bool>,
    /// The window's size, kept apart from the vector's capacity, which a clone does not keep.
    window_size: usize,
    window_pos: usize,
    window_accepted: u32,
}

impl Trace {
    /// An empty trace with an acceptance window of `window` proposals, recording every `every`.
    pub fn new(window: usize, every: u64) -> Self {
        Trace {
            proposed: [0; 9],
            accepted: [0; 9],
            points: Vec::new(),
            every: every.max(1),
            window: Vec::with_capacity(window.max(1)),
            window_size: window.max(1),
            window_pos: 0,
            window_accepted: 0,
        }
    }

    /// Records one proposal's outcome.
    pub fn record(&mut self, kernel: Kernel, accepted: bool) {
        self.proposed[kernel.index()] += 1;
        if accepted {
            self.accepted[kernel.index()] += 1;
        }
        let cap = self.window_size;
        if self.window.len() < cap {
            self.window.push(accepted);
        } else {
            if self.window[self.window_pos] {
                self.window_accepted -= 1;
            }
            self.window[self.window_pos] = accepted;
            self.window_pos = (self.window_pos + 1) % cap;
        }
        if accepted {
            self.window_accepted += 1;
        }
    }

    /// Acceptance rate over the window.
    pub fn acceptance(&self) -> f64 {
        if self.window.is_empty() {
            0.0
        } else {
            self.window_accepted as f64 / self.window.len() as f64
        }
    }

    /// Total proposals.
    pub fn total_proposed(&self) -> u64 {
        self.proposed.iter().sum()
    }

    /// Total accepted.
    pub fn total_accepted(&self) -> u64 {
        self.accepted.iter().sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cloned_trace_keeps_its_window() {
        let mut t = Trace::new(4, 10);
        for i in 0..10 {
            t.record(Kernel::Add, i % 2 == 0);
        }
        assert_eq!(t.acceptance(), 0.5);
        let mut c = t.clone();
        for _ in 0..4 {
            c.record(Kernel::Remove, true);
        }
        assert_eq!(c.acceptance(), 1.0);
        assert_eq!(c.total_proposed(), 14);
        assert_eq!(t.total_proposed(), 10);
    }
}
