//! What the floor-plan chain did: the recorded trace points and acceptance window of
//! [`crate::mcmc`], plus proposals and acceptances per kernel of Tab. 3.2.

use super::schedule::Kernel;
use crate::mcmc::{AcceptanceWindow, TracePoint};
use serde::Serialize;

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
    #[serde(skip)]
    window: AcceptanceWindow,
}

impl Trace {
    /// An empty trace with an acceptance window of `window` proposals, recording every `every`.
    pub fn new(window: usize, every: u64) -> Self {
        Trace {
            proposed: [0; 9],
            accepted: [0; 9],
            points: Vec::new(),
            every: every.max(1),
            window: AcceptanceWindow::new(window),
        }
    }

    /// Records one proposal's outcome.
    pub fn record(&mut self, kernel: Kernel, accepted: bool) {
        self.proposed[kernel.index()] += 1;
        if accepted {
            self.accepted[kernel.index()] += 1;
        }
        self.window.record(accepted);
    }

    /// Acceptance rate over the window.
    pub fn acceptance(&self) -> f64 {
        self.window.rate()
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
