//! What a chain did, for a frame loop to read every frame: recorded points of the log posterior,
//! and the acceptance rate over a sliding window. Small and allocation-free per step.

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

/// The acceptance rate over the last `size` proposals.
///
/// ```
/// use ksmcmc::mcmc::AcceptanceWindow;
/// let mut w = AcceptanceWindow::new(2);
/// for accepted in [true, false, false] {
///     w.record(accepted);
/// }
/// assert_eq!(w.rate(), 0.0); // the first outcome has left the window
/// ```
#[derive(Debug, Clone)]
pub struct AcceptanceWindow {
    window: Vec<bool>,
    /// The window's size, kept apart from the vector's capacity, which a clone does not keep.
    size: usize,
    pos: usize,
    accepted: u32,
}

impl AcceptanceWindow {
    /// An empty window over `size` proposals (at least one).
    pub fn new(size: usize) -> Self {
        AcceptanceWindow { window: Vec::with_capacity(size.max(1)), size: size.max(1), pos: 0, accepted: 0 }
    }

    /// Records one proposal's outcome.
    pub fn record(&mut self, accepted: bool) {
        let cap = self.size;
        if self.window.len() < cap {
            self.window.push(accepted);
        } else {
            if self.window[self.pos] {
                self.accepted -= 1;
            }
            self.window[self.pos] = accepted;
            self.pos = (self.pos + 1) % cap;
        }
        if accepted {
            self.accepted += 1;
        }
    }

    /// Acceptance rate over the window; 0 before the first proposal.
    pub fn rate(&self) -> f64 {
        if self.window.is_empty() {
            0.0
        } else {
            self.accepted as f64 / self.window.len() as f64
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cloned_window_keeps_its_size() {
        let mut w = AcceptanceWindow::new(4);
        for i in 0..10 {
            w.record(i % 2 == 0);
        }
        assert_eq!(w.rate(), 0.5);
        let mut c = w.clone();
        for _ in 0..4 {
            c.record(true);
        }
        assert_eq!(c.rate(), 1.0);
        assert_eq!(w.rate(), 0.5);
    }
}
