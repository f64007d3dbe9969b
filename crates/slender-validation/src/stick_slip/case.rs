//! One stick–slip run: a straight rod released at rest on an inclined rough plane, stepped in
//! time with friction updated every step, its motion measured.

use nalgebra::Vector3;
use slender_core::contact::{step_with_friction, ContactParams, ContactProblem, Obstacle, Plane};
use slender_core::dynamics::{DynamicsParams, Scheme, TimeStepper};
use slender_core::rod::{CrossSection, Material, RestCurve, RodBuilder};
use slender_core::ModelError;
use thiserror::Error;

use super::exact_acceleration;
use super::fit::acceleration;

/// Activation distance of the contact barrier, as a fraction of the rod's length: the normal
/// position tolerance of the contact (a sticking contact's elastic deflection at the friction
/// limit is μ·10⁻⁴ of it).
const ACTIVATION: f64 = 1e-6;

/// A rod on an inclined plane (see the module docs of [`super`]).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct StickSlipCase {
    /// Coulomb coefficient μ (≥ 0) of the plane.
    pub mu: f64,
    /// Inclination α (rad) of the plane, in [0, π/2).
    pub alpha: f64,
    /// Rod length L (m).
    pub length: f64,
    /// Elements along the rod.
    pub elements: usize,
    /// Diameter d (m) of the solid circular section.
    pub diameter: f64,
    /// Young's modulus E (Pa).
    pub young: f64,
    /// Density ρ (kg/m³).
    pub density: f64,
    /// Gravity g (m/s²).
    pub gravity: f64,
    /// Time step (s).
    pub dt: f64,
    /// Steps to run.
    pub steps: usize,
}

/// What one run measured.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct StickSlipResult {
    /// True if every step converged.
    pub converged: bool,
    /// Why not, if not.
    pub failure: Option<String>,
    /// True if the rod's contacts were sliding at the end.
    pub slid: bool,
    /// Largest displacement of the rod's centroid from its start over the run (m).
    pub displacement: f64,
    /// Acceleration of the centroid down the slope, fitted to its positions (m/s²).
    pub acceleration: f64,
    /// g (sin α − μ cos α) clamped at 0 (m/s²): Coulomb's law.
    pub exact: f64,
    /// Newton iterations over the run.
    pub iterations: usize,
}

/// A case that cannot be run.
#[derive(Debug, Error)]
pub enum StickSlipError {
    /// Bad parameters (the message names the field).
    #[error("{0}")]
    Model(#[from] ModelError),
}

impl StickSlipCase {
    /// Runs the case: the rod starts at rest on the plane at its normal equilibrium, every
    /// contact sticking where it is; each time step is solved with the current stick/slide
    /// set and re-solved while a contact changes ([`step_with_friction`]).
    pub fn run(&self) -> Result<StickSlipResult, StickSlipError> {
        if !(self.alpha.is_finite() && (0.0..std::f64::consts::FRAC_PI_2).contains(&self.alpha)) {
            return Err(ModelError::parameter("alpha", self.alpha, "in [0, π/2) rad").into());
        }
        let section = CrossSection::Circle {
            diameter: self.diameter,
        };
        let material = Material {
            young: self.young,
            poisson: 0.3,
            density: self.density,
        };
        let props = section.properties(&material)?;
        let radius = 0.5 * self.diameter;
        let activation = ACTIVATION * self.length;
        let q = props.linear_density * self.gravity;
        // The plane is z = 0; gravity is tilted so that the slope runs down along +x.
        let g = Vector3::new(self.alpha.sin(), 0.0, -self.alpha.cos()) * self.gravity;
        let rod = RodBuilder::new(
            RestCurve::Straight {
                // At the gap where the barrier carries the normal load exactly (ĝ/2).
                start: [0.0, 0.0, radius + 0.5 * activation],
                direction: [1.0, 0.0, 0.0],
                length: self.length,
            },
            props,
        )
        .elements(self.elements)
        .allow_rigid_motion()
        .gravity(g)
        .build()?;
        let plane: std::sync::Arc<dyn Obstacle> =
            std::sync::Arc::new(Plane::new(Vector3::zeros(), Vector3::z(), self.mu)?);
        let params = ContactParams::for_line_load(radius, activation, q * self.alpha.cos());
        let start = rod.rest_state().clone();
        let problem = ContactProblem::new(&rod, vec![plane], params, &start)?;
        problem.update_friction(&start, None);
        // Backward Euler: a sticking contact's anchor is a stiff spring whose period is far
        // below any useful step; the scheme damps it within a step, so the anchor carries its
        // static share from the first step instead of ringing with twice of it. Its O(h)
        // error in a uniformly accelerated slide is only a velocity offset, x = ½ a t² +
        // ½ a h t, which the fit of x₀ + v₀ t + ½ a t² separates from a.
        let dynamics = DynamicsParams {
            scheme: Scheme::BackwardEuler,
            ..DynamicsParams::new(self.dt)
        };
        let mut stepper = TimeStepper::at_rest(&problem, start, dynamics)?;
        let centroid = |s: &slender_core::rod::RodState| -> Vector3<f64> {
            s.positions().iter().sum::<Vector3<f64>>() / s.positions().len() as f64
        };
        let c0 = centroid(stepper.state());
        let mut samples = vec![(0.0, 0.0)];
        let mut displacement: f64 = 0.0;
        let mut iterations = 0;
        let mut failure = None;
        for _ in 0..self.steps {
            let report = step_with_friction(&mut stepper, &problem);
            iterations += report.iterations;
            if !report.converged {
                failure = report
                    .failure
                    .or(Some("a time step did not converge".into()));
                break;
            }
            let d = centroid(stepper.state()) - c0;
            displacement = displacement.max(d.norm());
            samples.push((stepper.time(), d.x));
        }
        let slid = problem
            .contact_forces(stepper.state())
            .iter()
            .any(|f| !f.sticking && f.friction != Vector3::zeros());
        Ok(StickSlipResult {
            converged: failure.is_none(),
            failure,
            slid,
            displacement,
            acceleration: acceleration(&samples).unwrap_or(f64::NAN),
            exact: exact_acceleration(self.gravity, self.alpha, self.mu).max(0.0),
            iterations,
        })
    }
}
