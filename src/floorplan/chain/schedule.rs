//! Which kernel to try: the selection probabilities `Φ(W'|W)` of Tab. 3.2, by iteration.

use crate::setting::{require, InvalidSetting};
use serde::{Deserialize, Serialize};

/// The sub-kernels of the five reversible pairs (section 3.5.1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Kernel {
    /// Add a unit drawn from the detectors' candidates.
    Add,
    /// Remove a unit.
    Remove,
    /// Split a unit in two along a detected line.
    Split,
    /// Merge two units into one.
    Merge,
    /// Move one wall of a unit inwards.
    Shrink,
    /// Move one wall of a unit outwards.
    Dilate,
    /// Re-partition two units that form an L shape.
    Interchange,
    /// Assign a detected door to two units.
    Allocate,
    /// Cancel a door.
    Delete,
}

impl Kernel {
    /// All kernels, in the order of Tab. 3.2.
    pub const ALL: [Kernel; 9] = [
        Kernel::Add,
        Kernel::Remove,
        Kernel::Split,
        Kernel::Merge,
        Kernel::Shrink,
        Kernel::Dilate,
        Kernel::Interchange,
        Kernel::Allocate,
        Kernel::Delete,
    ];

    /// Position in [`Kernel::ALL`].
    pub fn index(self) -> usize {
        self as usize
    }

    /// The reverse sub-kernel of the pair.
    pub fn reverse(self) -> Kernel {
        match self {
            Kernel::Add => Kernel::Remove,
            Kernel::Remove => Kernel::Add,
            Kernel::Split => Kernel::Merge,
            Kernel::Merge => Kernel::Split,
            Kernel::Shrink => Kernel::Dilate,
            Kernel::Dilate => Kernel::Shrink,
            Kernel::Interchange => Kernel::Interchange,
            Kernel::Allocate => Kernel::Delete,
            Kernel::Delete => Kernel::Allocate,
        }
    }

    /// Upper-case name as in the papers.
    pub fn name(self) -> &'static str {
        match self {
            Kernel::Add => "ADD",
            Kernel::Remove => "REMOVE",
            Kernel::Split => "SPLIT",
            Kernel::Merge => "MERGE",
            Kernel::Shrink => "SHRINK",
            Kernel::Dilate => "DILATE",
            Kernel::Interchange => "INTERCHANGE",
            Kernel::Allocate => "ALLOCATE",
            Kernel::Delete => "DELETE",
        }
    }
}

/// Selection probabilities of the nine sub-kernels (need not sum to one; they are normalised).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct KernelWeights(pub [f64; 9]);

impl KernelWeights {
    /// The normalised probability of `k`.
    pub fn probability(&self, k: Kernel) -> f64 {
        let t: f64 = self.0.iter().sum();
        if t > 0.0 {
            self.0[k.index()] / t
        } else {
            0.0
        }
    }
}

/// One row block of Tab. 3.2: weights in force up to (and including) iteration `until`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Phase {
    /// Last iteration of the phase; `None` for the final, open-ended phase.
    pub until: Option<u64>,
    /// Kernel weights in the phase.
    pub weights: KernelWeights,
}

/// The kernel schedule: phases by iteration.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Schedule {
    /// Phases in order; the last should have `until: None`.
    pub phases: Vec<Phase>,
}

impl Default for Schedule {
    /// Tab. 3.2: mostly ADD for the first 1000 iterations, then structural kernels, then doors
    /// from iteration 4000 on.
    fn default() -> Self {
        Schedule {
            phases: vec![
                Phase { until: Some(1000), weights: KernelWeights([0.8, 0.2, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]) },
                Phase {
                    until: Some(4000),
                    weights: KernelWeights([0.05, 0.05, 0.15, 0.15, 0.15, 0.15, 0.3, 0.0, 0.0]),
                },
                Phase { until: None, weights: KernelWeights([0.05, 0.05, 0.15, 0.15, 0.15, 0.15, 0.2, 0.05, 0.05]) },
            ],
        }
    }
}

impl Schedule {
    /// One phase forever.
    pub fn constant(weights: KernelWeights) -> Self {
        Schedule { phases: vec![Phase { until: None, weights }] }
    }

    /// The weights in force at `iteration` (1-based, as β in Tab. 3.2).
    pub fn weights_at(&self, iteration: u64) -> &KernelWeights {
        self.phases
            .iter()
            .find(|p| p.until.is_none_or(|u| iteration <= u))
            .or(self.phases.last())
            .map(|p| &p.weights)
            .expect("validated: at least one phase")
    }

    /// Checks weights are finite and non-negative and each phase has some positive weight.
    pub fn validate(&self) -> Result<(), InvalidSetting> {
        require(!self.phases.is_empty(), "phases", "a list of at least one phase")?;
        for p in &self.phases {
            let w = &p.weights.0;
            require(w.iter().all(|w| w.is_finite() && *w >= 0.0), "phases.weights", "finite and non-negative")?;
            require(w.iter().sum::<f64>() > 0.0, "phases.weights", "positive for at least one kernel")?;
        }
        Ok(())
    }
}
