//! The incremental potential of one implicit step, as an [`EquilibriumProblem`] wrapping the
//! model: what makes a time step a minimization the unchanged Newton solver can do.

use std::cell::RefCell;

use nalgebra::{SMatrix, SVector};

use crate::assembly::{Assembler, TermGroup, TermSet};
use crate::linalg::SymmetricMatrix;
use crate::solver::{EquilibriumProblem, MassMetric};

use super::flat::FlatDofs;
use super::quadrature::gauss_legendre_unit;
use super::scheme::Scheme;

/// Π(y) = (1 + b)·W(d) − b ∇E(xₙ)ᵀd + (μ/2)‖d − h_v vₙ‖²_M + (α_c/2)‖d‖²_M  (J),
/// d = y ⊖ xₙ, with, by scheme (h the time step, α and β the Rayleigh coefficients):
///
/// | scheme | unknown y | W(d) | μ | h_v | α_c | b |
/// |---|---|---|---|---|---|---|
/// | backward Euler | x_{n+1} | E(y) | 1/h² | h | α/h | β/h |
/// | implicit midpoint | x_{n+½} | E(y) | 4/h² | h/2 | 2α/h | 2β/h |
/// | energy-conserving | x_{n+1} | ∫₀¹ (E(xₙ + s d) − E(xₙ))/s ds | 2/h² | h | α/h | 2β/h |
///
/// Its stationarity is the scheme's update: M (v_{n+1} − vₙ)/h + C v̄ + F = 0 with F = ∇E(y)
/// for the first two and the average ∫₀¹ ∇E(xₙ + s d) ds for the third (∇W is that average,
/// since d/dd [E(xₙ + s d)/s] = ∇E(xₙ + s d)); the β-term is the secant
/// β (F − ∇E(xₙ))/(stage), equal to β K v̄ for a linear system. The Hessian
/// (1 + b)∇²W + (μ + α_c) M is positive definite for small enough h even where the stiffness
/// is not (a buckled state), so a step rarely needs the solver's shift.
///
/// `difference`, `displace`, `chart`, step caps and scales are the model's.
#[derive(Debug)]
pub struct IncrementalProblem<'m, P: FlatDofs> {
    model: &'m P,
    scheme: Scheme,
    start: P::State,
    velocity: Vec<f64>,
    mass: Vec<f64>,
    dt: f64,
    rayleigh_mass: f64,
    rayleigh_stiffness: f64,
    /// Gauss–Legendre (node, weight) pairs of the energy-conserving scheme's average.
    rule: Vec<(f64, f64)>,
    /// ∇E(xₙ) (N or N m) when β > 0, else empty.
    start_gradient: Vec<f64>,
    /// d = y ⊖ xₙ and s·d, reused across assemblies (no allocation per Newton iteration).
    scratch: RefCell<(Vec<f64>, Vec<f64>)>,
    /// The states xₙ ⊕ s d at the quadrature nodes.
    nodes: RefCell<Vec<P::State>>,
}

// By hand: the derive would ask `P: Clone`, and the model is only borrowed (a problem
// holding obstacles is not cloneable, its steppers are).
impl<P: FlatDofs> Clone for IncrementalProblem<'_, P> {
    fn clone(&self) -> Self {
        Self {
            model: self.model,
            scheme: self.scheme,
            start: self.start.clone(),
            velocity: self.velocity.clone(),
            mass: self.mass.clone(),
            dt: self.dt,
            rayleigh_mass: self.rayleigh_mass,
            rayleigh_stiffness: self.rayleigh_stiffness,
            rule: self.rule.clone(),
            start_gradient: self.start_gradient.clone(),
            scratch: self.scratch.clone(),
            nodes: self.nodes.clone(),
        }
    }
}

/// The scheme-dependent coefficients of Π (see [`IncrementalProblem`]).
#[derive(Clone, Copy, Debug)]
struct Coefficients {
    mu: f64,
    lag: f64,
    damping: f64,
    stiffness: f64,
}

impl<'m, P: FlatDofs> IncrementalProblem<'m, P> {
    /// The step of `scheme` over `dt` (s) from `start` with free-DOF velocity `velocity`
    /// (m/s, rad/s), mass `mass` (the diagonal, kg or kg m²), Rayleigh damping α (1/s) and
    /// β (s), and a `quadrature_points`-point average for the energy-conserving scheme.
    /// Inputs are not checked here ([`TimeStepper::new`](super::TimeStepper::new) checks
    /// them). Call [`Self::restart`] before use when β > 0 (it computes ∇E(xₙ)).
    ///
    /// # Panics
    ///
    /// If the scheme is energy-conserving and `quadrature_points` is not in
    /// 1..=[`MAX_QUADRATURE_POINTS`](super::quadrature::MAX_QUADRATURE_POINTS).
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        model: &'m P,
        scheme: Scheme,
        start: P::State,
        velocity: Vec<f64>,
        mass: Vec<f64>,
        dt: f64,
        rayleigh: (f64, f64),
        quadrature_points: usize,
    ) -> Self {
        let n = model.n_free();
        let rule = match scheme {
            Scheme::EnergyConserving => gauss_legendre_unit(quadrature_points),
            _ => Vec::new(),
        };
        Self {
            model,
            scheme,
            nodes: RefCell::new(vec![start.clone(); rule.len()]),
            start,
            velocity,
            mass,
            dt,
            rayleigh_mass: rayleigh.0,
            rayleigh_stiffness: rayleigh.1,
            rule,
            start_gradient: Vec::new(),
            scratch: RefCell::new((vec![0.0; n], vec![0.0; n])),
        }
    }

    /// The wrapped model.
    pub fn model(&self) -> &'m P {
        self.model
    }

    /// The state xₙ the step starts from.
    pub fn start(&self) -> &P::State {
        &self.start
    }

    /// The velocity vₙ (free DOFs) the step starts with.
    pub fn velocity(&self) -> &[f64] {
        &self.velocity
    }

    /// The time step h (s).
    pub fn dt(&self) -> f64 {
        self.dt
    }

    pub(crate) fn set_dt(&mut self, dt: f64) {
        self.dt = dt;
    }

    /// The time (s) from xₙ to the unknown: h, or h/2 for the implicit midpoint rule. The
    /// unknown's inertial target is xₙ ⊕ (this × vₙ), the solver's first guess.
    pub fn stage(&self) -> f64 {
        self.coefficients().lag
    }

    fn coefficients(&self) -> Coefficients {
        let h = self.dt;
        let (alpha, beta) = (self.rayleigh_mass, self.rayleigh_stiffness);
        match self.scheme {
            Scheme::BackwardEuler => Coefficients {
                mu: 1.0 / (h * h),
                lag: h,
                damping: alpha / h,
                stiffness: beta / h,
            },
            Scheme::ImplicitMidpoint => Coefficients {
                mu: 4.0 / (h * h),
                lag: 0.5 * h,
                damping: 2.0 * alpha / h,
                stiffness: 2.0 * beta / h,
            },
            Scheme::EnergyConserving => Coefficients {
                mu: 2.0 / (h * h),
                lag: h,
                damping: alpha / h,
                stiffness: 2.0 * beta / h,
            },
        }
    }

    /// Moves the step's start to `state` with `velocity`, and refreshes ∇E(xₙ) if
    /// stiffness-proportional damping needs it.
    pub fn restart(&mut self, state: &P::State, velocity: &[f64], load: f64) {
        self.start.clone_from(state);
        self.velocity.copy_from_slice(velocity);
        if self.rayleigh_stiffness > 0.0 {
            self.start_gradient.resize(self.model.n_free(), 0.0);
            let mut asm = Assembler::<P::Hessian>::new(
                TermSet::ALL,
                Some(&mut self.start_gradient),
                None,
                None,
            );
            self.model.assemble_selected(&self.start, load, &mut asm);
            asm.finish();
        }
    }

    /// Adds W(d) weighted by `weight` to `asm`, for the step d = `d` that `state` is at.
    fn add_potential<M: SymmetricMatrix>(
        &self,
        state: &P::State,
        d: &[f64],
        scaled: &mut [f64],
        weight: f64,
        load: f64,
        asm: &mut Assembler<'_, M>,
    ) {
        if self.rule.is_empty() {
            if weight == 1.0 {
                self.model.assemble_selected(state, load, asm);
            } else {
                let mut part = asm.rescaled(weight, 1.0);
                self.model.assemble_selected(state, load, &mut part);
                let info = part.finish();
                asm.absorb(info);
            }
            return;
        }
        // ∫₀¹ E(xₙ + s d)/s ds by quadrature; the constant −E(xₙ)/s is left out (it does
        // not move the minimizer). Each node's derivatives are in the chart at xₙ + s d, which
        // moves by s per unit of d: the assembler scales them by s and s².
        let mut nodes = self.nodes.borrow_mut();
        for (&(s, w), z) in self.rule.iter().zip(nodes.iter_mut()) {
            for (o, di) in scaled.iter_mut().zip(d) {
                *o = s * di;
            }
            self.model.chart(&self.start, scaled, z);
            let mut part = asm.rescaled(weight * w / s, s);
            self.model.assemble_selected(z, load, &mut part);
            let info = part.finish();
            asm.absorb(info);
        }
    }

    /// Adds the inertial and damping terms for the step `d` (taken at `state`) to `asm`.
    fn add_inertia<M: SymmetricMatrix>(
        &self,
        state: &P::State,
        d: &[f64],
        asm: &mut Assembler<'_, M>,
    ) {
        let c = self.coefficients();
        for (i, (&di, &m)) in d.iter().zip(&self.mass).enumerate() {
            let lag = di - c.lag * self.velocity[i];
            let mut energy = 0.5 * c.mu * m * lag * lag + 0.5 * c.damping * m * di * di;
            let mut grad = c.mu * m * lag + c.damping * m * di;
            if c.stiffness > 0.0 {
                let secant = c.stiffness * self.start_gradient[i];
                energy -= secant * di;
                grad -= secant;
            }
            // The round-off of these energies is that of d = y ⊖ xₙ (ε × the DOF's size)
            // times their force, far above ε × their value near convergence, where d − h_v vₙ
            // is a small difference: the line search must know that noise to stop ranking
            // trial points below it.
            let magnitude = energy.abs() + grad.abs() * self.model.dof_magnitude(state, i);
            asm.local(
                &[i],
                energy,
                magnitude,
                &SVector::<f64, 1>::new(grad),
                &SMatrix::<f64, 1, 1>::new((c.mu + c.damping) * m),
            );
        }
    }

    /// The state after a converged step and its velocity: `stage` is the solver's solution y,
    /// `increment` receives y ⊖ xₙ, `velocity` (vₙ on entry) becomes v_{n+1}, `out` x_{n+1}.
    pub(crate) fn finish_step(
        &self,
        stage: &P::State,
        increment: &mut [f64],
        velocity: &mut [f64],
        out: &mut P::State,
    ) {
        self.model.difference(stage, &self.start, increment);
        let h = self.dt;
        match self.scheme {
            Scheme::BackwardEuler => {
                for (v, d) in velocity.iter_mut().zip(increment.iter()) {
                    *v = d / h;
                }
                out.clone_from(stage);
            }
            Scheme::ImplicitMidpoint => {
                // v_{n+½} = 2d/h; x_{n+1} = y ⊕ d (exactly 2y − xₙ on flat DOFs).
                for (v, d) in velocity.iter_mut().zip(increment.iter()) {
                    *v = 4.0 * d / h - *v;
                }
                self.model.chart(stage, increment, out);
            }
            Scheme::EnergyConserving => {
                // (x_{n+1} − xₙ)/h = (vₙ + v_{n+1})/2. The new state is the end of the
                // straight path the force was averaged over (xₙ ⊕ d, frames carried from
                // xₙ), so that the energy balance holds for the state handed on.
                for (v, d) in velocity.iter_mut().zip(increment.iter()) {
                    *v = 2.0 * d / h - *v;
                }
                self.model.chart(&self.start, increment, out);
            }
        }
    }
}

impl<P: FlatDofs> MassMetric for IncrementalProblem<'_, P> {
    fn inertia_metric(&self, i: usize) -> f64 {
        self.model.inertia_metric(i)
    }

    fn eigenvalue_scale(&self) -> f64 {
        self.model.eigenvalue_scale()
    }
}

impl<P: FlatDofs> EquilibriumProblem for IncrementalProblem<'_, P> {
    type State = P::State;
    type Hessian = P::Hessian;

    fn n_free(&self) -> usize {
        self.model.n_free()
    }

    fn new_hessian(&self) -> P::Hessian {
        self.model.new_hessian()
    }

    fn term_groups(&self) -> &[TermGroup] {
        self.model.term_groups()
    }

    /// The model's selected terms (weighted by 1 + b) and, always, the inertial and damping
    /// terms: they are what makes this a time step, whatever subset of the model is chosen.
    fn assemble_selected<M: SymmetricMatrix>(
        &self,
        state: &P::State,
        load: f64,
        asm: &mut Assembler<'_, M>,
    ) {
        let mut scratch = self.scratch.borrow_mut();
        let (d, scaled) = &mut *scratch;
        self.model.difference(state, &self.start, d);
        let weight = 1.0 + self.coefficients().stiffness;
        self.add_potential(state, d, scaled, weight, load, asm);
        self.add_inertia(state, d, asm);
    }

    fn difference(&self, a: &P::State, b: &P::State, out: &mut [f64]) {
        self.model.difference(a, b, out);
    }

    fn displace(&self, state: &P::State, dx: &[f64], alpha: f64, out: &mut P::State) {
        self.model.displace(state, dx, alpha, out);
    }

    fn chart(&self, state: &P::State, dx: &[f64], out: &mut P::State) {
        self.model.chart(state, dx, out);
    }

    fn max_step(&self, state: &P::State, dx: &[f64]) -> f64 {
        self.model.max_step(state, dx)
    }

    fn force_length(&self, i: usize) -> f64 {
        self.model.force_length(i)
    }

    fn dof_magnitude(&self, state: &P::State, i: usize) -> f64 {
        self.model.dof_magnitude(state, i)
    }
}
