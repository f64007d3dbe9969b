//! A model in contact with rigid obstacles, as one [`EquilibriumProblem`] for the unchanged
//! solver: the model's energy plus a barrier energy of every site's gap to every obstacle.
//!
//! Each centerline vertex (a [`ContactSite`]) at distance d from an obstacle's surface has the
//! gap g = d − r (r the cable's radius) and adds κ·w·b(g), with b the barrier of
//! [`barrier`](super::barrier), w the centerline length the vertex stands for and κ the
//! barrier stiffness (N/m²). Its exact gradient and Hessian follow from the obstacle's
//! distance derivatives (κw(b′ n, b″ n nᵀ + b′ ∂n/∂p)). The step cap stops every site short of
//! its obstacle (a tenth of its gap is kept), and the line search never accepts the infinite
//! energy of a penetration, so no gap ever closes: contacts rest within the activation
//! distance ĝ of the surface, which is the stated position tolerance of the contact.
//!
//! Contacts here are frictionless; each contact's normal force is reported
//! ([`ContactProblem::contact_forces`]).

use nalgebra::{Matrix3, Vector3};

use crate::assembly::{Assembler, TermGroup};
use crate::error::{require_non_negative, require_positive};
use crate::solver::{EquilibriumProblem, MassMetric};
use crate::ModelError;

use super::barrier::barrier;
use super::obstacle::Obstacle;
use super::sites::{ContactSite, ContactSites};

/// The term group of the contact energy (the top bit, which no model uses).
pub const CONTACT: TermGroup = TermGroup {
    bit: 31,
    name: "contact",
};

/// Fraction of a site's gap that a step must leave open.
const KEEP_GAP: f64 = 0.1;

/// How contacts act.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactParams {
    /// Radius (m) of the cable's section: the centerline keeps this distance from surfaces.
    pub radius: f64,
    /// Activation distance ĝ (m, > 0): a site within this gap of a surface is in contact, and
    /// at equilibrium every contact rests within it (the position tolerance of contacts).
    pub activation: f64,
    /// Barrier stiffness κ (N/m², > 0): a line load q (N/m) pressing a cable on a surface
    /// rests it at the gap where −κ b′(g) = q (about ĝ/2 for κ = q/(1.19 ĝ); see
    /// [`Self::for_line_load`]). Larger loads only close the gap further, never through.
    pub stiffness: f64,
}

impl ContactParams {
    /// Parameters under which a line load `line_load` (N/m) rests a cable of radius `radius`
    /// (m) at half the activation distance `activation` (m).
    pub fn for_line_load(radius: f64, activation: f64, line_load: f64) -> Self {
        // −b′(ĝ/2) = ĝ (1/2 + ln 2).
        let slope = activation * (0.5 + std::f64::consts::LN_2);
        Self {
            radius,
            activation,
            stiffness: line_load / slope,
        }
    }

    /// Checks every field; errors name it and its valid range.
    pub fn validate(&self) -> Result<(), ModelError> {
        require_non_negative("radius", self.radius)?;
        require_positive("activation", self.activation)?;
        require_positive("stiffness", self.stiffness)?;
        Ok(())
    }
}

/// The force one obstacle applies to one site.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactForce {
    /// Index of the site in [`ContactProblem::sites`].
    pub site: usize,
    /// Index of the obstacle.
    pub obstacle: usize,
    /// Gap g = distance − radius (m), in (0, ĝ).
    pub gap: f64,
    /// Outward unit normal of the surface at the contact.
    pub normal: Vector3<f64>,
    /// Force on the structure (N): the normal force, along `normal`.
    pub force: Vector3<f64>,
}

/// `model` in contact with `obstacles` (see the module docs).
#[derive(Debug)]
pub struct ContactProblem<'m, P: ContactSites> {
    model: &'m P,
    obstacles: Vec<Box<dyn Obstacle>>,
    params: ContactParams,
    sites: Vec<ContactSite>,
    groups: Vec<TermGroup>,
}

impl<'m, P: ContactSites> ContactProblem<'m, P> {
    /// `model` with `obstacles`. Errors: invalid parameters, a model that already uses the
    /// contact group's bit, or a site of `start` that is not outside every obstacle by more
    /// than the radius (the cable would start inside; the field names the obstacle).
    pub fn new(
        model: &'m P,
        obstacles: Vec<Box<dyn Obstacle>>,
        params: ContactParams,
        start: &P::State,
    ) -> Result<Self, ModelError> {
        params.validate()?;
        if model.term_groups().iter().any(|g| g.bit == CONTACT.bit) {
            return Err(ModelError::structure(
                "obstacles",
                "the model already uses the contact term group's bit",
            ));
        }
        let sites = model.contact_sites();
        for (o, obstacle) in obstacles.iter().enumerate() {
            for site in &sites {
                let gap =
                    obstacle.surface(&model.site_position(start, site)).distance - params.radius;
                if !(gap > 0.0) {
                    return Err(ModelError::structure(
                        format!("obstacles[{o}]"),
                        format!(
                            "vertex {} of member {} starts inside the obstacle (gap {gap:.3e} m with radius {} m): move the obstacle or the cable",
                            site.vertex, site.member, params.radius
                        ),
                    ));
                }
            }
        }
        let mut groups = model.term_groups().to_vec();
        groups.push(CONTACT);
        Ok(Self {
            model,
            obstacles,
            params,
            sites,
            groups,
        })
    }

    /// The model.
    pub fn model(&self) -> &P {
        self.model
    }

    /// The contact sites.
    pub fn sites(&self) -> &[ContactSite] {
        &self.sites
    }

    /// The parameters.
    pub fn params(&self) -> &ContactParams {
        &self.params
    }

    /// Every active contact (gap below the activation distance) of `state` with its force.
    pub fn contact_forces(&self, state: &P::State) -> Vec<ContactForce> {
        let mut out = Vec::new();
        for (k, site) in self.sites.iter().enumerate() {
            let p = self.model.site_position(state, site);
            for (o, obstacle) in self.obstacles.iter().enumerate() {
                let s = obstacle.surface(&p);
                let gap = s.distance - self.params.radius;
                if gap < self.params.activation {
                    let (_, slope, _) = barrier(gap, self.params.activation);
                    out.push(ContactForce {
                        site: k,
                        obstacle: o,
                        gap,
                        normal: s.normal,
                        force: s.normal * (-self.params.stiffness * site.length * slope),
                    });
                }
            }
        }
        out
    }

    /// Smallest gap (m) of any site to any obstacle in `state` (negative: penetration).
    pub fn min_gap(&self, state: &P::State) -> f64 {
        let mut g = f64::INFINITY;
        for site in &self.sites {
            let p = self.model.site_position(state, site);
            for obstacle in &self.obstacles {
                g = g.min(obstacle.surface(&p).distance - self.params.radius);
            }
        }
        g
    }

    /// The contact energy (J) of `state`.
    fn contact_energy(&self, state: &P::State) -> f64 {
        let mut e = 0.0;
        for site in &self.sites {
            let p = self.model.site_position(state, site);
            for obstacle in &self.obstacles {
                let gap = obstacle.surface(&p).distance - self.params.radius;
                if gap < self.params.activation {
                    e += self.params.stiffness
                        * site.length
                        * barrier(gap, self.params.activation).0;
                }
            }
        }
        e
    }
}

impl<P: ContactSites> MassMetric for ContactProblem<'_, P> {
    fn inertia_metric(&self, i: usize) -> f64 {
        self.model.inertia_metric(i)
    }

    fn eigenvalue_scale(&self) -> f64 {
        self.model.eigenvalue_scale()
    }
}

impl<P: ContactSites> EquilibriumProblem for ContactProblem<'_, P> {
    type State = P::State;
    type Hessian = P::Hessian;

    fn n_free(&self) -> usize {
        self.model.n_free()
    }

    fn new_hessian(&self) -> P::Hessian {
        self.model.new_hessian()
    }

    fn term_groups(&self) -> &[TermGroup] {
        &self.groups
    }

    fn assemble_selected<M: crate::linalg::SymmetricMatrix>(
        &self,
        state: &P::State,
        load: f64,
        asm: &mut Assembler<'_, M>,
    ) {
        self.model.assemble_selected(state, load, asm);
        if !asm.selects(CONTACT) {
            return;
        }
        let (kappa, activation) = (self.params.stiffness, self.params.activation);
        for site in &self.sites {
            let p = self.model.site_position(state, site);
            for obstacle in &self.obstacles {
                let s = obstacle.surface(&p);
                let gap = s.distance - self.params.radius;
                if gap >= activation {
                    continue;
                }
                let (b, db, ddb) = barrier(gap, activation);
                let weight = kappa * site.length;
                let energy = weight * b;
                let grad = s.normal * (weight * db);
                let hess: Matrix3<f64> =
                    (s.normal * s.normal.transpose() * ddb + s.normal_derivative * db) * weight;
                let mut part = asm.part(&site.dofs);
                part.local(&[0, 1, 2], energy, energy.abs(), &grad, &hess);
                let info = part.finish();
                asm.absorb(info);
            }
        }
    }

    fn merit(&self, trial: &P::State, load: f64) -> f64 {
        self.model.merit(trial, load) + self.contact_energy(trial)
    }

    fn difference(&self, a: &P::State, b: &P::State, out: &mut [f64]) {
        self.model.difference(a, b, out)
    }

    fn displace(&self, state: &P::State, dx: &[f64], alpha: f64, out: &mut P::State) {
        self.model.displace(state, dx, alpha, out)
    }

    fn chart(&self, state: &P::State, dx: &[f64], out: &mut P::State) {
        self.model.chart(state, dx, out)
    }

    fn impose_load(&self, state: &mut P::State, from: f64, to: f64, guess: bool) {
        self.model.impose_load(state, from, to, guess)
    }

    fn refresh_loads(&self, state: &mut P::State) -> f64 {
        self.model.refresh_loads(state)
    }

    fn max_step(&self, state: &P::State, dx: &[f64]) -> f64 {
        let mut alpha = self.model.max_step(state, dx);
        for site in &self.sites {
            let mut dp = Vector3::zeros();
            for (c, d) in site.dofs.iter().enumerate() {
                if d.dof != crate::assembly::FIXED {
                    dp[c] = d.coef * dx[d.dof];
                }
            }
            if dp == Vector3::zeros() {
                continue;
            }
            let p = self.model.site_position(state, site);
            for obstacle in &self.obstacles {
                let gap = obstacle.surface(&p).distance - self.params.radius;
                let clearance = self.params.radius + KEEP_GAP * gap.max(0.0);
                alpha = alpha.min(obstacle.time_of_impact(&p, &(dp * alpha), clearance) * alpha);
            }
        }
        alpha
    }

    fn force_length(&self, i: usize) -> f64 {
        self.model.force_length(i)
    }

    fn dof_magnitude(&self, state: &P::State, i: usize) -> f64 {
        self.model.dof_magnitude(state, i)
    }
}
