//! The generic derivative checker.

use nalgebra::Rotation3;

use crate::assembly::{Assembler, TermSet};
use crate::geometry::Vec3;
use crate::linalg::SymmetricMatrix;
use crate::solver::EquilibriumProblem;

use super::rng::Rng;

/// What the rigid-motion and rest-shape checks need beyond [`EquilibriumProblem`].
pub trait RigidMotion: EquilibriumProblem {
    /// `state` moved rigidly: x ↦ R x + c for every point, every frame and prescribed DOF
    /// rotated by R. The internal energy must not change.
    fn rigidly_moved(
        &self,
        state: &Self::State,
        rotation: &Rotation3<f64>,
        offset: &Vec3,
    ) -> Self::State;

    /// The stress-free state.
    fn rest(&self) -> Self::State;

    /// The term groups of the internal (elastic) energy.
    fn internal_terms(&self) -> TermSet;
}

/// Relative errors of directional finite differences over decreasing ε (gradient: gᵀv;
/// Hessian: uᵀHv), relative to the size of the exact derivatives.
#[derive(Clone, Debug, PartialEq)]
pub struct FdErrors {
    /// The step sizes ε.
    pub eps: Vec<f64>,
    /// |FD − gᵀv| / scale, per ε.
    pub gradient: Vec<f64>,
    /// |FD − uᵀHv| / scale, per ε.
    pub hessian: Vec<f64>,
    /// True if the exact uᵀHv and Hu are exactly zero (a linear term).
    pub linear: bool,
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Finite-difference errors of the selected groups at `state` along directions `u`, `v` (in the
/// free DOFs, scaled by the caller to a sensible size).
///
/// Both derivatives use *energy* differences at states `chart(state, a u + b v)`: that is the
/// function whose derivatives the model claims (for a rod, trial states get frames transported
/// from `state`; differencing gradients at displaced states would mix charts that agree only to
/// first order).
pub fn fd_errors<P: EquilibriumProblem>(
    problem: &P,
    state: &P::State,
    load: f64,
    terms: TermSet,
    u: &[f64],
    v: &[f64],
) -> FdErrors {
    let n = problem.n_free();
    let mut g = vec![0.0; n];
    let mut h = problem.new_hessian();
    let mut asm = Assembler::new(terms, Some(&mut g), Some(&mut h), None);
    problem.assemble_selected(state, load, &mut asm);
    asm.finish();
    let mut hv = vec![0.0; n];
    h.mul_vec(v, &mut hv);
    let mut hu = vec![0.0; n];
    h.mul_vec(u, &mut hu);
    let gv = dot(&g, v);
    let uhv = dot(u, &hv);
    let scale_g = gv.abs().max(norm(&g) * norm(v) * 1e-3).max(1e-300);
    let scale_h = uhv.abs().max(norm(&hu) * norm(v) * 1e-3).max(1e-300);
    let linear = hu.iter().all(|x| *x == 0.0) && hv.iter().all(|x| *x == 0.0);
    let mut trial = state.clone();
    let mut w = vec![0.0; n];
    let mut energy_at = |a: f64, b: f64| {
        for i in 0..n {
            w[i] = a * u[i] + b * v[i];
        }
        problem.chart(state, &w, &mut trial);
        let mut asm = Assembler::<P::Hessian>::energy_only(terms);
        problem.assemble_selected(&trial, load, &mut asm);
        asm.finish().energy
    };
    let eps = vec![2e-3, 6e-4, 2e-4, 6e-5, 2e-5];
    let mut out = FdErrors {
        eps: eps.clone(),
        gradient: Vec::new(),
        hessian: Vec::new(),
        linear,
    };
    for e in eps {
        let d1 = (energy_at(0.0, e) - energy_at(0.0, -e)) / (2.0 * e);
        out.gradient.push((d1 - gv).abs() / scale_g);
        let d2 = (energy_at(e, e) - energy_at(e, -e) - energy_at(-e, e) + energy_at(-e, -e))
            / (4.0 * e * e);
        // A linear term has no Hessian: measure its second differences against the gradient
        // scale (they are round-off).
        let s = if linear { scale_g } else { scale_h };
        out.hessian.push((d2 - uhv).abs() / s);
    }
    out
}

/// Over a decade of ε the error must fall by ~100 (30 allowed) until it reaches round-off, and
/// its smallest value must be below 1e-5.
fn second_order(errors: &[f64], what: &str) -> Result<(), String> {
    let (e0, e2) = (errors[0], errors[2]);
    if !(e2 < e0 / 30.0 || e2 < 1e-9) {
        return Err(format!("{what}: not O(ε²): errors {errors:?}"));
    }
    if !(errors.iter().cloned().fold(f64::INFINITY, f64::min) < 1e-5) {
        return Err(format!("{what}: errors {errors:?}"));
    }
    Ok(())
}

/// Checks the gradient and Hessian of `terms` at `state` along two random directions drawn
/// from `rng`, scaled per DOF by `scale(i)` (e.g. smaller for coordinates than for angles).
pub fn check_derivatives<P: EquilibriumProblem>(
    problem: &P,
    state: &P::State,
    load: f64,
    terms: TermSet,
    rng: &mut Rng,
    scale: impl Fn(usize) -> f64,
    what: &str,
) -> Result<(), String> {
    let n = problem.n_free();
    let u: Vec<f64> = (0..n).map(|i| rng.uniform() * scale(i)).collect();
    let v: Vec<f64> = (0..n).map(|i| rng.uniform() * scale(i)).collect();
    let e = fd_errors(problem, state, load, terms, &u, &v);
    second_order(&e.gradient, &format!("{what}: gradient"))?;
    if e.linear {
        // A linear term: second differences are round-off.
        if !(e.hessian.iter().cloned().fold(f64::INFINITY, f64::min) < 1e-6) {
            return Err(format!(
                "{what}: linear term with curvature {:?}",
                e.hessian
            ));
        }
        return Ok(());
    }
    second_order(&e.hessian, &format!("{what}: Hessian"))
}

/// Every term group on its own and all together, at every state.
pub fn check_model_derivatives<P: EquilibriumProblem>(
    problem: &P,
    states: &[P::State],
    load: f64,
    rng: &mut Rng,
    scale: impl Fn(usize) -> f64 + Copy,
    name: &str,
) -> Result<(), String> {
    for (k, s) in states.iter().enumerate() {
        for group in problem.term_groups() {
            check_derivatives(
                problem,
                s,
                load,
                group.set(),
                rng,
                scale,
                &format!("{name}, state {k}, {}", group.name),
            )?;
        }
        check_derivatives(
            problem,
            s,
            load,
            TermSet::ALL,
            rng,
            scale,
            &format!("{name}, state {k}, all terms"),
        )?;
    }
    Ok(())
}

/// The internal energy of every state is unchanged (to `1e-12` relative) by random rigid
/// motions; the states must be deformed.
pub fn check_rigid_invariance<P: RigidMotion>(
    problem: &P,
    states: &[P::State],
    rng: &mut Rng,
    name: &str,
) -> Result<(), String> {
    let internal = problem.internal_terms();
    let energy = |s: &P::State| {
        let mut asm = Assembler::<P::Hessian>::energy_only(internal);
        problem.assemble_selected(s, 1.0, &mut asm);
        asm.finish().energy
    };
    for (k, s) in states.iter().enumerate() {
        let e0 = energy(s);
        if !(e0.abs() > 0.0) {
            return Err(format!(
                "{name}, state {k}: not deformed (internal energy {e0})"
            ));
        }
        for _ in 0..5 {
            let axis = Vec3::new(rng.uniform(), rng.uniform(), rng.uniform());
            let rot = Rotation3::new(axis * 3.0);
            let offset = Vec3::new(rng.uniform(), 2.0 * rng.uniform(), -rng.uniform());
            let e1 = energy(&problem.rigidly_moved(s, &rot, &offset));
            if !((e1 - e0).abs() <= 1e-12 * e0.abs()) {
                return Err(format!(
                    "{name}, state {k}: rigid motion changed the internal energy {e0:e} to {e1:e}"
                ));
            }
        }
    }
    Ok(())
}

/// At the rest state the internal energy is zero and its gradient vanishes (relative to the
/// internal forces of a unit deformation, `force_scale`).
pub fn check_rest<P: RigidMotion>(problem: &P, force_scale: f64, name: &str) -> Result<(), String> {
    let rest = problem.rest();
    let n = problem.n_free();
    let mut g = vec![0.0; n];
    let mut asm = Assembler::<P::Hessian>::new(problem.internal_terms(), Some(&mut g), None, None);
    problem.assemble_selected(&rest, 0.0, &mut asm);
    let e = asm.finish().energy;
    let gmax = g.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    if !(e.abs() <= 1e-28 * force_scale.max(1.0) && gmax <= 1e-13 * force_scale.max(1.0)) {
        return Err(format!(
            "{name}: rest energy {e:e}, largest rest gradient {gmax:e}"
        ));
    }
    Ok(())
}

/// All checks: derivatives of every group and of the sum at `states`, rigid-motion invariance
/// there, and the rest shape.
pub fn check_model<P: RigidMotion>(
    problem: &P,
    states: &[P::State],
    load: f64,
    rng: &mut Rng,
    scale: impl Fn(usize) -> f64 + Copy,
    force_scale: f64,
    name: &str,
) -> Result<(), String> {
    check_model_derivatives(problem, states, load, rng, scale, name)?;
    check_rigid_invariance(problem, states, rng, name)?;
    check_rest(problem, force_scale, name)
}
