//! L-BFGS (Nocedal 1980; Liu and Nocedal 1989) with a backtracking (Armijo) line search, for
//! weight learning. Deterministic: no random restarts, the same steps on every platform.
//!
//! The learning objectives are smooth and concave, so the plain variant suffices: a memory
//! of the last [`MEMORY`] steps approximates the inverse Hessian by the two-loop recursion;
//! a pair that fails the curvature condition `s · y > 0` is not stored, and a direction that
//! is not a descent direction is replaced by the gradient's.

/// Steps remembered.
const MEMORY: usize = 10;
/// Sufficient decrease: `f(x + t d) <= f(x) + C1 t g · d`.
const C1: f64 = 1e-4;
/// Halvings of the step before the line search gives up.
const MAX_HALVINGS: usize = 60;

/// The outcome of [`minimise`].
pub(crate) struct Run {
    pub x: Vec<f64>,
    pub value: f64,
    /// Largest absolute gradient component at `x`.
    pub gradient: f64,
    pub iterations: usize,
    pub converged: bool,
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |m, x| m.max(x.abs()))
}

/// The two-loop recursion: `-H g` for the inverse-Hessian approximation `H` of the memory.
fn direction(g: &[f64], memory: &[(Vec<f64>, Vec<f64>, f64)]) -> Vec<f64> {
    let mut q: Vec<f64> = g.to_vec();
    let mut alpha = vec![0.0; memory.len()];
    for (i, (s, y, rho)) in memory.iter().enumerate().rev() {
        alpha[i] = rho * dot(s, &q);
        for (qj, yj) in q.iter_mut().zip(y) {
            *qj -= alpha[i] * yj;
        }
    }
    let gamma = memory.last().map_or(1.0, |(s, y, _)| dot(s, y) / dot(y, y));
    for qj in &mut q {
        *qj *= gamma;
    }
    for (i, (s, y, rho)) in memory.iter().enumerate() {
        let beta = rho * dot(y, &q);
        for (qj, sj) in q.iter_mut().zip(s) {
            *qj += (alpha[i] - beta) * sj;
        }
    }
    q.iter().map(|x| -x).collect()
}

/// Minimises `f` (value and gradient) from `x`, for at most `iterations` steps or until no
/// gradient component exceeds `tolerance * max(1, |f(x)|)`: relative, since the learning
/// objectives are sums over ground atoms, whose rounding error grows with their number.
pub(crate) fn minimise(
    mut f: impl FnMut(&[f64]) -> (f64, Vec<f64>),
    mut x: Vec<f64>,
    iterations: usize,
    tolerance: f64,
) -> Run {
    let (mut value, mut g) = f(&x);
    let mut memory: Vec<(Vec<f64>, Vec<f64>, f64)> = Vec::new();
    let mut done = 0;
    while done < iterations && max_abs(&g) > tolerance * value.abs().max(1.0) && value.is_finite() {
        let mut d = direction(&g, &memory);
        let mut slope = dot(&g, &d);
        if slope.is_nan() || slope >= 0.0 {
            memory.clear();
            d = g.iter().map(|x| -x).collect();
            slope = dot(&g, &d);
        }
        // The first step is scaled to move the weights by at most 1.
        let mut t = if memory.is_empty() { 1.0 / max_abs(&d).max(1.0) } else { 1.0 };
        let mut accepted = None;
        for _ in 0..MAX_HALVINGS {
            let xn: Vec<f64> = x.iter().zip(&d).map(|(a, b)| a + t * b).collect();
            let (vn, gn) = f(&xn);
            if vn.is_finite() && vn <= value + C1 * t * slope {
                accepted = Some((xn, vn, gn));
                break;
            }
            t *= 0.5;
        }
        let Some((xn, vn, gn)) = accepted else {
            break; // no decrease along the direction: at the optimum up to rounding
        };
        let s: Vec<f64> = xn.iter().zip(&x).map(|(a, b)| a - b).collect();
        let y: Vec<f64> = gn.iter().zip(&g).map(|(a, b)| a - b).collect();
        let sy = dot(&s, &y);
        if sy > 1e-12 * dot(&s, &s).sqrt() * dot(&y, &y).sqrt() && sy > 0.0 {
            if memory.len() == MEMORY {
                memory.remove(0);
            }
            memory.push((s, y, 1.0 / sy));
        }
        (x, value, g) = (xn, vn, gn);
        done += 1;
    }
    let gradient = max_abs(&g);
    Run { x, value, gradient, iterations: done, converged: gradient <= tolerance * value.abs().max(1.0) }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_the_minimum_of_a_badly_scaled_quadratic_and_of_rosenbrock() {
        // f = (x - 1)^2 + 100 (y + 2)^2
        let quad = |v: &[f64]| {
            let (a, b) = (v[0] - 1.0, v[1] + 2.0);
            (a * a + 100.0 * b * b, vec![2.0 * a, 200.0 * b])
        };
        let run = minimise(quad, vec![0.0, 0.0], 100, 1e-10);
        assert!(run.converged, "gradient {}", run.gradient);
        assert!((run.x[0] - 1.0).abs() < 1e-9 && (run.x[1] + 2.0).abs() < 1e-9, "{:?}", run.x);
        let rosenbrock = |v: &[f64]| {
            let (x, y) = (v[0], v[1]);
            let value = (1.0 - x).powi(2) + 100.0 * (y - x * x).powi(2);
            (value, vec![-2.0 * (1.0 - x) - 400.0 * x * (y - x * x), 200.0 * (y - x * x)])
        };
        let run = minimise(rosenbrock, vec![-1.2, 1.0], 500, 1e-8);
        assert!(run.converged, "gradient {} after {}", run.gradient, run.iterations);
        assert!((run.x[0] - 1.0).abs() < 1e-6 && (run.x[1] - 1.0).abs() < 1e-6, "{:?}", run.x);
    }
}
