//! The incremental potential of one implicit step, as an [`EquilibriumProblem`] wrapping the
//! model: what makes a time step a minimization the unchanged Newton solver can do.

use std::cell::RefCell;

use nalgebra::{Matrix3, SMatrix, SVector, UnitQuaternion, Vector3};

use crate::assembly::{Assembler, TermGroup, TermSet, FIXED};
use crate::lie::quaternion::{conj, from_unit, mul};
use crate::lie::{left_jacobian, LogChart};
use crate::linalg::SymmetricMatrix;
use crate::solver::{EquilibriumProblem, MassMetric};

use super::flat::FlatDofs;
use super::frames::FrameInertia;
use super::pullback::{NodeFrameMap, PulledBack};
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
///
/// **Frames** ([`FlatDofs::frames`]: the rotations of a Cosserat rod's or an SE(3) beam's
/// material frames). A frame's d is its rotation vector φ = log(p_y p̄ₙ) from xₙ, and its
/// inertia I = R J Rᵀ turns with it, so its inertial term is written with the spatial angular
/// momentum πₙ = Iₙ ωₙ of the start (ωₙ the spatial angular velocity, the velocity of its
/// DOFs):
///
/// K(φ) = (μ/2) φᵀ Ĩ φ − μ h_v πₙ·φ + (α_c/2) φᵀ Ĩ φ − b ∇E(xₙ)·φ,
///
/// with Ĩ the inertia at the predicted mid-step orientation e((h/2) ωₙ) pₙ (h the full step):
/// Ĩ ωₙ = πₙ + (h/2) ωₙ × πₙ + O(h²), which puts the gyroscopic term ω × Iω of Euler's
/// equations into the step at the order the schemes need (with Iₙ the step would turn a free
/// frame about ωₙ: a first-order error in its precession). A gyroscopic term does no work
/// and is not the gradient of any function of y, so it can only enter the minimization
/// through start data like these; the step stays a minimization. Newton moves the frame by
/// spatial increments δ, in which
/// φ has the Jacobian dexp⁻¹ = J_l(φ)⁻¹ and a second derivative ([`LogChart`]): K's gradient
/// and Hessian go through both, so they are exact. After the step the momentum is balanced,
/// π_{n+1} = πₙ + h T, with T the frame's torque (elastic, load and damping) at the unknown
/// (backward Euler, midpoint: by stationarity T = J_l(φ)⁻ᵀ μ(Ĩφ − h_v πₙ)), or its average
/// along the step carried to space at the mid-step (energy-conserving: J_l(φ/2)⁻ᵀ μ(Ĩφ − hπₙ)),
/// and ω_{n+1} = I_{n+1}⁻¹ π_{n+1}. The midpoint rule then conserves the angular momentum of
/// a free structure exactly (all forces act at one state); a free frame keeps πₙ under every
/// scheme. The energy-conserving scheme's average runs along xₙ ⊕ s d, whose frames turn by
/// e(sφ) from xₙ: each node's derivatives are carried to the unknown's chart through that map
/// (`pullback.rs`). Its energy is exact when the frames turn about principal axes fixed in
/// space (planar motion, spin about the rod's axis); when they precess, the turning inertia
/// (Ĩ ≠ Iₙ, I_{n+1}) leaves an O(h³) error per step, as for any second-order scheme.
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
    /// The frames whose rotations are DOFs (empty for a flat model).
    frames: Vec<FrameInertia>,
    /// True on the free DOFs that turn a frame (their inertia is the frame's block).
    frame_dof: Vec<bool>,
    /// What each frame starts the step with.
    frame_start: Vec<FrameStart>,
    /// Frame orientations of the state being assembled.
    orientations: RefCell<Vec<UnitQuaternion<f64>>>,
    /// A quadrature node's assembly before its pullback (energy-conserving scheme, frames).
    record: RefCell<Option<PulledBack>>,
}

/// A frame at the start of a step.
#[derive(Clone, Debug)]
struct FrameStart {
    /// Orientation pₙ.
    orientation: UnitQuaternion<f64>,
    /// Spatial angular momentum πₙ = Iₙ ωₙ (kg m²/s).
    momentum: Vector3<f64>,
    /// Inertia Ĩ (kg m²) at the mid-step orientation e((h/2) ωₙ) pₙ, held rows zeroed.
    inertia: Matrix3<f64>,
    /// The frame's part of ∇E(xₙ) (N m) when β > 0, else 0.
    gradient: Vector3<f64>,
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
            frames: self.frames.clone(),
            frame_dof: self.frame_dof.clone(),
            frame_start: self.frame_start.clone(),
            orientations: self.orientations.clone(),
            record: self.record.clone(),
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
    /// The velocity of a frame's rotation DOFs is its spatial angular velocity, and `mass` is
    /// 0 there (the frames' inertia comes from [`FlatDofs::frames`]). Inputs are not checked
    /// here ([`TimeStepper::new`](super::TimeStepper::new) checks them). Call
    /// [`Self::restart`] before use when β > 0 (it computes ∇E(xₙ)).
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
        let frames = if model.has_flat_dofs() {
            Vec::new()
        } else {
            model.frames()
        };
        let mut frame_dof = vec![false; n];
        for f in &frames {
            for &i in f.dofs.iter().filter(|&&i| i != FIXED) {
                frame_dof[i] = true;
            }
        }
        let mut problem = Self {
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
            frames,
            frame_dof,
            frame_start: Vec::new(),
            orientations: RefCell::new(Vec::new()),
            record: RefCell::new(None),
        };
        problem.prepare_frames();
        problem
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
        // The mid-step inertia depends on h.
        self.prepare_frames();
    }

    /// The frames whose rotations are DOFs.
    pub fn frames(&self) -> &[FrameInertia] {
        &self.frames
    }

    /// Computes each frame's start data from the start state, velocity, h and ∇E(xₙ).
    fn prepare_frames(&mut self) {
        if self.frames.is_empty() {
            return;
        }
        let mut orientations = self.orientations.borrow_mut();
        self.model
            .frame_orientations(&self.start, &mut orientations);
        let h = self.dt;
        self.frame_start.clear();
        for (f, p) in self.frames.iter().zip(orientations.iter()) {
            let omega = f.angular_velocity(&self.velocity);
            let momentum = f.momentum(p, &omega);
            let mid = UnitQuaternion::from_scaled_axis(omega * (0.5 * h)) * p;
            let inertia = f.masked(&f.spatial(&mid));
            let gradient = if self.start_gradient.is_empty() {
                Vector3::zeros()
            } else {
                f.masked_vector(&f.angular_velocity(&self.start_gradient))
            };
            self.frame_start.push(FrameStart {
                orientation: *p,
                momentum,
                inertia,
                gradient,
            });
        }
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
        self.prepare_frames();
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
        // moves by s per unit of d on coordinates: the assembler scales them by s and s².
        // Frames turn by e(s φ(y)) from xₙ, nonlinearly in y: their nodes are pulled back.
        if !self.frames.is_empty() && (asm.wants_gradient() || asm.wants_hessian()) {
            self.add_pulled_back_nodes(state, d, scaled, weight, load, asm);
            return;
        }
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

    /// The energy-conserving scheme's average with frames: each node assembled into a
    /// record that carries it to y's chart ([`PulledBack`]), the sum added to `asm` once.
    fn add_pulled_back_nodes<M: SymmetricMatrix>(
        &self,
        state: &P::State,
        d: &[f64],
        scaled: &mut [f64],
        weight: f64,
        load: f64,
        asm: &mut Assembler<'_, M>,
    ) {
        let hessian = asm.wants_hessian();
        let charts = self.frame_charts(state);
        let mut record = self.record.borrow_mut();
        let record =
            record.get_or_insert_with(|| PulledBack::new(self.model.n_free(), &self.frames));
        record.begin();
        let mut nodes = self.nodes.borrow_mut();
        let mut maps = Vec::with_capacity(charts.len());
        for (&(s, w), z) in self.rule.iter().zip(nodes.iter_mut()) {
            for (o, di) in scaled.iter_mut().zip(d) {
                *o = s * di;
            }
            self.model.chart(&self.start, scaled, z);
            maps.clear();
            maps.extend(charts.iter().map(|c| NodeFrameMap::new(c, s)));
            record.set_node(&maps, s);
            let PulledBack {
                node_grad,
                node_abs,
                hess,
                ..
            } = record;
            let mut inner = Assembler::new(
                asm.selection(),
                Some(node_grad.as_mut_slice()),
                hessian.then_some(hess),
                Some(node_abs.as_mut_slice()),
            );
            let mut part = inner.rescaled(weight * w / s, 1.0);
            self.model.assemble_selected(z, load, &mut part);
            let info = part.finish();
            asm.absorb(info);
            record.end_node(&maps, hessian);
        }
        record.add_to(hessian, asm);
    }

    /// The log chart of every frame at `state`: φ = log(p p̄ₙ) and its derivatives in the
    /// spatial increment of p.
    fn frame_charts(&self, state: &P::State) -> Vec<LogChart> {
        let mut orientations = self.orientations.borrow_mut();
        self.model.frame_orientations(state, &mut orientations);
        orientations
            .iter()
            .zip(&self.frame_start)
            .map(|(p, start)| {
                LogChart::new(&mul(&from_unit(p), &conj(&from_unit(&start.orientation))))
            })
            .collect()
    }

    /// Adds each frame's inertial and damping term K(φ) (see the type's docs) at `state`.
    /// Written as ½ (φ − φ*)ᵀ M (φ − φ*) with M = (μ + α_c) Ĩ and φ* = M⁻¹(μ h_v πₙ + b ∇E(xₙ))
    /// (K up to a constant), so that its value, like the coordinates', is small near the
    /// solution and its round-off scale is that of the step.
    fn add_rotary_inertia<M: SymmetricMatrix>(&self, state: &P::State, asm: &mut Assembler<'_, M>) {
        if self.frames.is_empty() {
            return;
        }
        let c = self.coefficients();
        let charts = self.frame_charts(state);
        for ((frame, start), chart) in self.frames.iter().zip(&self.frame_start).zip(&charts) {
            let m = start.inertia * (c.mu + c.damping);
            let b = start.momentum * (c.mu * c.lag) + start.gradient * c.stiffness;
            let target = frame.solve_free(&m, &b);
            let r = frame.masked_vector(&chart.value) - target;
            let w = m * r;
            let energy = 0.5 * r.dot(&w);
            let grad = chart.jac.transpose() * w;
            let hess = chart.jac.transpose() * m * chart.jac + chart.contracted_hessian(&w);
            let magnitude = energy.abs()
                + (0..3)
                    .filter(|&k| frame.dofs[k] != FIXED)
                    .map(|k| grad[k].abs() * self.model.dof_magnitude(state, frame.dofs[k]))
                    .sum::<f64>();
            asm.local(&frame.dofs, energy, magnitude, &grad, &hess);
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
            if self.frame_dof[i] {
                continue; // a frame's rotation: add_rotary_inertia
            }
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
        self.finish_frames(stage, velocity, out);
    }

    /// The frames' angular velocities after a converged step from y = `stage` to x_{n+1} =
    /// `out`: the momentum balance π_{n+1} = πₙ + h T (see the type's docs), then
    /// ω_{n+1} = I_{n+1}⁻¹ π_{n+1}, written into `velocity`.
    fn finish_frames(&self, stage: &P::State, velocity: &mut [f64], out: &P::State) {
        if self.frames.is_empty() {
            return;
        }
        let c = self.coefficients();
        let h = self.dt;
        let charts = self.frame_charts(stage);
        let mut orientations = self.orientations.borrow_mut();
        self.model.frame_orientations(out, &mut orientations);
        for (((frame, start), chart), p) in self
            .frames
            .iter()
            .zip(&self.frame_start)
            .zip(&charts)
            .zip(orientations.iter())
        {
            let phi = frame.masked_vector(&chart.value);
            // −(the torque on the frame in φ's chart): the inertial term's gradient.
            let u = (start.inertia * phi - start.momentum * c.lag) * c.mu;
            let torque = match self.scheme {
                Scheme::BackwardEuler | Scheme::ImplicitMidpoint => chart.jac.transpose() * u,
                Scheme::EnergyConserving => left_jacobian(&(phi * 0.5))
                    .transpose()
                    .lu()
                    .solve(&u)
                    .unwrap_or(u),
            };
            let momentum = frame.masked_vector(&(start.momentum + torque * h));
            let omega = frame.solve_free(&frame.spatial(p), &momentum);
            for (k, &i) in frame.dofs.iter().enumerate() {
                if i != FIXED {
                    velocity[i] = omega[k];
                }
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
        self.add_rotary_inertia(state, asm);
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
