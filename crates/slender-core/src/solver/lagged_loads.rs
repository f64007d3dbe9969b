//! Lagged loads (follower loads): frozen during each Newton solve, refreshed from the new
//! state after it, and re-solved until they no longer change — a fixed-point iteration
//! u ← G(u) on the frozen values u, G being "solve with u frozen, then read the loads off the
//! new state" (see `rod/follower.rs`).
//!
//! Plain, that iteration contracts only while the loads turn the structure little: its rate
//! grows with the load (about F L²/EI for a follower tip force), so a cantilever curled by a
//! follower force crawls through hundreds of re-solves, and beyond F L²/EI of a few it
//! diverges although the equilibrium exists. The loop below accelerates it by Anderson mixing
//! (Walker & Ni, SIAM J. Numer. Anal. 49 (2011)): the next frozen values combine the last
//! few G(u) with the weights that best cancel their residuals G(u) − u in least squares — a
//! secant method on the few numbers the lagged loads are (ten per follower load), which
//! converges where the plain iteration diverges. Written by hand: it is a dozen lines on top
//! of a small least-squares solve (nalgebra's SVD), and no crate offers it for this loop.

use nalgebra::{DMatrix, DVector};

use super::newton::{newton, NewtonOutcome, NewtonWorkspace};
use super::params::SolverParams;
use super::problem::EquilibriumProblem;

/// Relative change of lagged (follower) loads below which they are settled.
pub(crate) const LOAD_SETTLED: f64 = 1e-11;
/// Newton re-solves allowed for lagged loads to settle, per load step.
pub(crate) const LOAD_REFRESHES: usize = 200;
/// Past iterates the Anderson mixing combines (besides the last).
const ANDERSON_DEPTH: usize = 5;

/// After a converged Newton solve, refreshes the model's lagged loads (follower loads) and
/// re-solves until they stop changing; returns the outcome (iterations accumulated). Models
/// without lagged loads return after one refresh that finds nothing to change (no
/// allocation); the others allocate the mixing's few short vectors.
pub(crate) fn settle_loads<P: EquilibriumProblem>(
    problem: &P,
    state: &mut P::State,
    load: f64,
    params: &SolverParams,
    ws: &mut NewtonWorkspace<P::State, P::Hessian>,
    mut out: NewtonOutcome,
) -> NewtonOutcome {
    let mut mixing = AndersonMixing::default();
    // The frozen values the last solve used (before its refresh), once known.
    let mut used: Vec<f64> = Vec::new();
    let mut fresh: Vec<f64> = Vec::new();
    for refresh in 0..LOAD_REFRESHES {
        if !out.converged {
            return out;
        }
        if refresh > 0 {
            problem.lagged_loads(state, &mut used);
        }
        if problem.refresh_loads(state) <= LOAD_SETTLED {
            return out;
        }
        // Refreshed: the state now holds G(used). The first refresh's `used` is unknown (read
        // only once the loads prove to be lagged), so mixing starts with the second.
        if refresh > 0 {
            problem.lagged_loads(state, &mut fresh);
            if fresh.len() == used.len() && !fresh.is_empty() {
                if let Some(next) = mixing.next(&used, &fresh) {
                    problem.set_lagged_loads(state, &next);
                }
            }
        }
        let next = newton(problem, state, load, params, ws);
        out = NewtonOutcome {
            iterations: out.iterations + next.iterations,
            ..next
        };
    }
    NewtonOutcome {
        converged: false,
        failure: Some(format!(
            "follower loads did not settle in {LOAD_REFRESHES} re-solves"
        )),
        ..out
    }
}

/// The history of an Anderson-mixed fixed-point iteration u ← G(u).
#[derive(Default)]
struct AndersonMixing {
    /// G(u) of the past iterates, oldest first.
    g: Vec<Vec<f64>>,
    /// Their residuals G(u) − u.
    r: Vec<Vec<f64>>,
}

impl AndersonMixing {
    /// Records the iterate `u` with its image `g` = G(u) and returns the mixed next iterate,
    /// or `None` (take `g` itself) while there is no history yet or the least-squares problem
    /// says nothing.
    fn next(&mut self, u: &[f64], g: &[f64]) -> Option<Vec<f64>> {
        let r: Vec<f64> = g.iter().zip(u).map(|(g, u)| g - u).collect();
        self.g.push(g.to_vec());
        self.r.push(r);
        if self.g.len() > ANDERSON_DEPTH + 1 {
            self.g.remove(0);
            self.r.remove(0);
        }
        let m = self.g.len() - 1;
        if m == 0 {
            return None;
        }
        // min_γ |r_k − ΔR γ|, ΔR's columns the differences of successive residuals; the next
        // iterate is g_k − ΔG γ.
        let n = g.len();
        let last = m;
        let dr = DMatrix::from_fn(n, m, |i, j| self.r[j + 1][i] - self.r[j][i]);
        let rk = DVector::from_fn(n, |i, _| self.r[last][i]);
        let svd = dr.svd(true, true);
        let tol = 1e-12 * svd.singular_values.max();
        let gamma = svd.solve(&rk, tol).ok()?;
        if gamma.iter().any(|x| !x.is_finite()) {
            return None;
        }
        let mut next = self.g[last].clone();
        for (j, gj) in gamma.iter().enumerate() {
            for (x, (a, b)) in next.iter_mut().zip(self.g[j + 1].iter().zip(&self.g[j])) {
                *x -= gj * (a - b);
            }
        }
        Some(next)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Anderson mixing solves a linear fixed point u = A u + b whose plain iteration diverges
    /// (spectral radius 3) in at most dim + 1 mixed steps.
    #[test]
    fn mixing_converges_where_the_plain_iteration_diverges() {
        let a = [[2.0, 1.0, 0.0], [0.5, -3.0, 0.2], [0.0, 0.3, 1.5]];
        let b = [1.0, -2.0, 0.5];
        let map = |u: &[f64]| -> Vec<f64> {
            (0..3)
                .map(|i| (0..3).map(|j| a[i][j] * u[j]).sum::<f64>() + b[i])
                .collect()
        };
        // The fixed point, from (I − A) u = b by Cramer's rule on the 3 × 3 system.
        let m = |i: usize, j: usize| f64::from(u8::from(i == j)) - a[i][j];
        let det3 = |c: [[f64; 3]; 3]| {
            c[0][0] * (c[1][1] * c[2][2] - c[1][2] * c[2][1])
                - c[0][1] * (c[1][0] * c[2][2] - c[1][2] * c[2][0])
                + c[0][2] * (c[1][0] * c[2][1] - c[1][1] * c[2][0])
        };
        let base = [
            [m(0, 0), m(0, 1), m(0, 2)],
            [m(1, 0), m(1, 1), m(1, 2)],
            [m(2, 0), m(2, 1), m(2, 2)],
        ];
        let d = det3(base);
        let exact: Vec<f64> = (0..3)
            .map(|k| {
                let mut c = base;
                for i in 0..3 {
                    c[i][k] = b[i];
                }
                det3(c) / d
            })
            .collect();
        let mut mixing = AndersonMixing::default();
        let mut u = vec![0.0; 3];
        let mut plain = u.clone();
        for _ in 0..6 {
            let g = map(&u);
            u = mixing.next(&u, &g).unwrap_or(g);
            plain = map(&plain);
        }
        let err = u
            .iter()
            .zip(&exact)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max);
        let plain_err = plain
            .iter()
            .zip(&exact)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max);
        assert!(err < 1e-10, "mixed: {u:?} against {exact:?}");
        assert!(plain_err > 1.0, "the plain iteration diverges: {plain:?}");
    }
}
