//! The decision rule of section 4.10.1: a query's probability read as true, false or
//! undecided. The chain decides with it and the scene graph records its answers.

use serde::{Deserialize, Serialize};

/// The decision rule of section 4.10.1.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct DecisionRule {
    /// A query above this is true (default 0.6).
    pub true_above: f64,
    /// A query below this is false (default 0.4); between the two it is undecided.
    pub false_below: f64,
}

impl Default for DecisionRule {
    fn default() -> Self {
        DecisionRule { true_above: 0.6, false_below: 0.4 }
    }
}

/// The answer to a query under the [`DecisionRule`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Decision {
    /// The probability is above `true_above`.
    True,
    /// The probability is below `false_below`.
    False,
    /// In between: the knowledge cannot tell.
    Undecided,
}

impl DecisionRule {
    /// The decision for probability `p`.
    ///
    /// ```
    /// use ksmcmc::tabletop::{Decision, DecisionRule};
    /// let rule = DecisionRule::default();
    /// assert_eq!(rule.decide(0.91), Decision::True);
    /// assert_eq!(rule.decide(0.5), Decision::Undecided);
    /// assert_eq!(rule.decide(0.05), Decision::False);
    /// ```
    pub fn decide(&self, p: f64) -> Decision {
        if p > self.true_above {
            Decision::True
        } else if p < self.false_below {
            Decision::False
        } else {
            Decision::Undecided
        }
    }
}
