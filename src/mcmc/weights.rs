//! Drawing one element by weight: normalise (eq. 3.15), accumulate (eq. 3.16), and take the
//! first element whose cumulative weight reaches a uniform draw (eq. 3.17).

use super::Rng;

/// Cumulative weights over a list of elements, for repeated draws in O(log n).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Cumulative {
    sums: Vec<f64>,
}

impl Cumulative {
    /// Builds the cumulative table. Negative and non-finite weights count as zero.
    pub fn new(weights: impl IntoIterator<Item = f64>) -> Self {
        let mut total = 0.0;
        let sums = weights
            .into_iter()
            .map(|w| {
                if w.is_finite() && w > 0.0 {
                    total += w;
                }
                total
            })
            .collect();
        Cumulative { sums }
    }

    /// Reuses the allocation for new weights.
    pub fn rebuild(&mut self, weights: impl IntoIterator<Item = f64>) {
        self.sums.clear();
        let mut total = 0.0;
        for w in weights {
            if w.is_finite() && w > 0.0 {
                total += w;
            }
            self.sums.push(total);
        }
    }

    /// Number of elements.
    pub fn len(&self) -> usize {
        self.sums.len()
    }

    /// Whether there are no elements.
    pub fn is_empty(&self) -> bool {
        self.sums.is_empty()
    }

    /// The sum of all weights.
    pub fn total(&self) -> f64 {
        self.sums.last().copied().unwrap_or(0.0)
    }

    /// The weight of element `i`.
    pub fn weight(&self, i: usize) -> f64 {
        let prev = if i == 0 { 0.0 } else { self.sums[i - 1] };
        self.sums[i] - prev
    }

    /// The normalised weight `ω'_i` of eq. 3.15: the probability that [`Cumulative::draw`]
    /// returns `i`.
    pub fn probability(&self, i: usize) -> f64 {
        let t = self.total();
        if t > 0.0 {
            self.weight(i) / t
        } else {
            0.0
        }
    }

    /// Draws an index with probability proportional to its weight (eq. 3.17); `None` when all
    /// weights are zero.
    pub fn draw(&self, rng: &mut Rng) -> Option<usize> {
        let t = self.total();
        if t <= 0.0 {
            return None;
        }
        let k = rng.uniform() * t;
        // First index whose cumulative sum exceeds k; zero-weight elements are never chosen.
        let i = self.sums.partition_point(|&s| s <= k);
        Some(i.min(self.sums.len() - 1))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn draws_follow_the_weights() {
        let c = Cumulative::new([1.0, 0.0, 3.0, f64::NAN, -2.0, 4.0]);
        assert_eq!(c.total(), 8.0);
        assert_eq!(c.probability(2), 3.0 / 8.0);
        let mut rng = Rng::seed(1);
        let mut counts = [0u32; 6];
        let n = 80_000;
        for _ in 0..n {
            counts[c.draw(&mut rng).unwrap()] += 1;
        }
        assert_eq!(counts[1] + counts[3] + counts[4], 0, "zero weights are never drawn");
        for (i, w) in [(0, 1.0), (2, 3.0), (5, 4.0)] {
            let f = counts[i] as f64 / n as f64;
            // Binomial standard deviation is below 0.002; allow 4 sigma.
            assert!((f - w / 8.0).abs() < 0.008, "element {i}: {f}");
        }
        assert_eq!(Cumulative::new([0.0, 0.0]).draw(&mut rng), None);
        assert_eq!(Cumulative::default().draw(&mut rng), None);
    }
}
