//! The time stepper: state, velocity and time, advanced one implicit step at a time.

use crate::error::ModelError;
use crate::solver::{newton, NewtonWorkspace};

use super::energy::MechanicalEnergy;
use super::flat::FlatDofs;
use super::incremental::IncrementalProblem;
use super::mass::LumpedMass;
use super::params::DynamicsParams;
use super::report::StepReport;

/// Integrates the motion of `model` in time (see the module docs for the schemes).
///
/// Supports stay where the initial state has them (the load path is not driven), and loads
/// act at the constant load factor `params.load`. A step whose Newton solve fails leaves
/// state, velocity and time unchanged and says why in its report (a smaller `dt`, see
/// [`Self::set_dt`], is the usual remedy).
pub struct TimeStepper<'m, P: FlatDofs> {
    problem: IncrementalProblem<'m, P>,
    params: DynamicsParams,
    mass: LumpedMass,
    state: P::State,
    velocity: Vec<f64>,
    time: f64,
    /// The Newton iterate (the stage y).
    stage: P::State,
    /// y ⊖ xₙ of the last step.
    increment: Vec<f64>,
    ws: NewtonWorkspace<P::State, P::Hessian>,
}

// By hand: the derive would ask `P: Clone`, and the model is only borrowed.
impl<P: FlatDofs> Clone for TimeStepper<'_, P> {
    fn clone(&self) -> Self {
        Self {
            problem: self.problem.clone(),
            params: self.params,
            mass: self.mass.clone(),
            state: self.state.clone(),
            velocity: self.velocity.clone(),
            time: self.time,
            stage: self.stage.clone(),
            increment: self.increment.clone(),
            ws: self.ws.clone(),
        }
    }
}

impl<'m, P: FlatDofs> TimeStepper<'m, P> {
    /// A stepper starting at `state` with free-DOF velocity `velocity` (m/s for coordinates,
    /// rad/s for angles and for the spatial angular velocity of a frame on its three rotation
    /// DOFs; length [`EquilibriumProblem::n_free`](crate::solver::EquilibriumProblem::n_free))
    /// at time 0.
    ///
    /// Errors name the field: `dt`, `rayleigh_mass`, `rayleigh_stiffness`, `load`, a solver
    /// tolerance, `velocity` (wrong length or not finite), `inertia_metric[i]` (a DOF without
    /// mass), `frames[f]…` (a frame's inertia or DOFs, see [`LumpedMass::of`]) or `model`
    /// (rotation DOFs that are not listed as frames, see [`FlatDofs`]).
    pub fn new(
        model: &'m P,
        state: P::State,
        velocity: Vec<f64>,
        params: DynamicsParams,
    ) -> Result<Self, ModelError> {
        params.validate()?;
        if !model.has_flat_dofs() && model.frames().is_empty() {
            return Err(ModelError::structure(
                "model",
                "time stepping needs coordinates and listed frames (FlatDofs::frames); this \
                 model has rotation DOFs it does not list as frames (a wrapper of a Cosserat rod \
                 or SE(3) beam that does not forward them)",
            ));
        }
        let n = model.n_free();
        if velocity.len() != n {
            return Err(ModelError::structure(
                "velocity",
                format!(
                    "has {} entries, the model has {n} free DOFs",
                    velocity.len()
                ),
            ));
        }
        if let Some((i, &v)) = velocity.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(ModelError::parameter(
                format!("velocity[{i}]"),
                v,
                "finite (m/s or rad/s)",
            ));
        }
        let mass = LumpedMass::of(model)?;
        let mut problem = IncrementalProblem::new(
            model,
            params.scheme,
            state.clone(),
            velocity.clone(),
            mass.diagonal().to_vec(),
            params.dt,
            (params.rayleigh_mass, params.rayleigh_stiffness),
            params.quadrature_points,
        );
        problem.restart(&state, &velocity, params.load);
        let ws = NewtonWorkspace::new(&problem, &state);
        Ok(Self {
            problem,
            params,
            mass,
            stage: state.clone(),
            state,
            velocity,
            time: 0.0,
            increment: vec![0.0; n],
            ws,
        })
    }

    /// A stepper starting at rest at `state`.
    pub fn at_rest(
        model: &'m P,
        state: P::State,
        params: DynamicsParams,
    ) -> Result<Self, ModelError> {
        let n = model.n_free();
        Self::new(model, state, vec![0.0; n], params)
    }

    /// The current state.
    pub fn state(&self) -> &P::State {
        &self.state
    }

    /// The current free-DOF velocity (m/s, rad/s).
    pub fn velocity(&self) -> &[f64] {
        &self.velocity
    }

    /// The current time (s).
    pub fn time(&self) -> f64 {
        self.time
    }

    /// The parameters.
    pub fn params(&self) -> &DynamicsParams {
        &self.params
    }

    /// The mass matrix (diagonal).
    pub fn mass(&self) -> &LumpedMass {
        &self.mass
    }

    /// Changes the time step (s) for the following steps; errors (field `dt`) unless finite
    /// and > 0.
    pub fn set_dt(&mut self, dt: f64) -> Result<(), ModelError> {
        DynamicsParams { dt, ..self.params }.validate()?;
        self.params.dt = dt;
        self.problem.set_dt(dt);
        Ok(())
    }

    /// Kinetic and potential energy (J) of the current state and velocity (with the frames'
    /// rotary kinetic energy ½ ωᵀ I ω at their current orientations).
    pub fn energy(&self) -> MechanicalEnergy {
        let model = self.problem.model();
        let mut kinetic = self.mass.kinetic_energy(&self.velocity);
        if !self.mass.frames().is_empty() {
            let mut orientations = Vec::new();
            model.frame_orientations(&self.state, &mut orientations);
            kinetic += self
                .mass
                .frames()
                .iter()
                .zip(&orientations)
                .map(|(f, q)| f.kinetic_energy(q, &f.angular_velocity(&self.velocity)))
                .sum::<f64>();
        }
        MechanicalEnergy {
            kinetic,
            potential: model.energy(&self.state, self.params.load),
        }
    }

    /// The spatial angular momentum I ω (kg m²/s) of every frame (in the order of
    /// [`LumpedMass::frames`]) at the current state and velocity; empty without frames.
    pub fn frame_momenta(&self) -> Vec<nalgebra::Vector3<f64>> {
        let mut orientations = Vec::new();
        self.problem
            .model()
            .frame_orientations(&self.state, &mut orientations);
        self.mass
            .frames()
            .iter()
            .zip(&orientations)
            .map(|(f, q)| f.momentum(q, &f.angular_velocity(&self.velocity)))
            .collect()
    }

    /// Advances by one time step: solves the scheme's equation by Newton from the inertial
    /// target xₙ ⊕ (stage·vₙ), then forms x_{n+1} and v_{n+1} by the scheme.
    pub fn step(&mut self) -> StepReport {
        let model = self.problem.model();
        let tau = self.problem.stage();
        if model.caps_predictor() {
            // A contact model's step caps hold for the first guess too: the inertial target
            // of a cable falling onto an obstacle lies beyond its surface (where the barrier
            // is infinite) or, past a thin part, on its far side. `increment` is scratch here.
            for (d, v) in self.increment.iter_mut().zip(&self.velocity) {
                *d = tau * v;
            }
            let alpha = model.max_step(&self.state, &self.increment);
            model.displace(&self.state, &self.increment, alpha, &mut self.stage);
        } else {
            model.displace(&self.state, &self.velocity, tau, &mut self.stage);
        }
        let outcome = newton(
            &self.problem,
            &mut self.stage,
            self.params.load,
            &self.params.solver,
            &mut self.ws,
        );
        // A start already at the solution up to round-off (a rigid spin of stiff elements:
        // no force anywhere, the residual is the rounding of their strains) can stop with no
        // descent left at its first iterate, before the convergence test has a second residual
        // to compare; its residual under the round-off floor makes it converged all the same.
        let at_roundoff = outcome.last.residual <= outcome.last.floor;
        if !(outcome.converged || at_roundoff) {
            return StepReport {
                converged: false,
                iterations: outcome.iterations,
                residual: outcome.last.residual,
                time: self.time,
                failure: outcome.failure,
            };
        }
        self.problem.finish_step(
            &self.stage,
            &mut self.increment,
            &mut self.velocity,
            &mut self.state,
        );
        self.time += self.params.dt;
        self.problem
            .restart(&self.state, &self.velocity, self.params.load);
        StepReport {
            converged: true,
            iterations: outcome.iterations,
            residual: outcome.last.residual,
            time: self.time,
            failure: None,
        }
    }
}
