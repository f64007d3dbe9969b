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
//! Dry Coulomb friction ([`friction`](super::friction)) adds, per contact, a tangential anchor
//! while it sticks or the kinetic force while it slides; [`ContactProblem::update_friction`]
//! is the active-set step between solves. Each contact's normal and friction force is
//! reported ([`ContactProblem::contact_forces`]).

use std::cell::RefCell;

use nalgebra::{Matrix3, Vector3};

use crate::assembly::{Assembler, TermGroup};
use crate::error::{require_non_negative, require_positive};
use crate::solver::{EquilibriumProblem, MassMetric};
use crate::ModelError;

use super::barrier::barrier;
use super::friction::{Friction, FrictionUpdate};
use super::obstacle::Obstacle;
use super::sites::{ContactSite, ContactSites};

/// The term group of the contact energy (the top bit, which no model uses).
pub const CONTACT: TermGroup = TermGroup {
    bit: 31,
    name: "contact",
};

/// The term group of the friction terms (anchors of sticking contacts, forces of sliding ones).
pub const FRICTION: TermGroup = TermGroup {
    bit: 30,
    name: "friction",
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
    /// Stiffness k_t (N/m², > 0) per unit length of the anchor that holds a sticking contact
    /// tangentially: at the friction limit μ q it deflects by μ q / k_t (a bounded elastic
    /// deflection, never a creep).
    pub stick_stiffness: f64,
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
            // The tangential deflection at the friction limit, μ q / k_t, stays below
            // μ · 10⁻⁴ ĝ: far below the normal position tolerance.
            stick_stiffness: line_load / (1e-4 * activation),
        }
    }

    /// Checks every field; errors name it and its valid range.
    pub fn validate(&self) -> Result<(), ModelError> {
        require_non_negative("radius", self.radius)?;
        require_positive("activation", self.activation)?;
        require_positive("stiffness", self.stiffness)?;
        require_positive("stick_stiffness", self.stick_stiffness)?;
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
    /// Normal force on the structure (N), along `normal`.
    pub force: Vector3<f64>,
    /// Friction force on the structure (N), tangential: the anchor's pull while sticking,
    /// the kinetic force while sliding, zero on a frictionless surface.
    pub friction: Vector3<f64>,
    /// True while the contact sticks.
    pub sticking: bool,
}

/// `model` in contact with `obstacles` (see the module docs).
#[derive(Debug)]
pub struct ContactProblem<'m, P: ContactSites> {
    model: &'m P,
    obstacles: Vec<Box<dyn Obstacle>>,
    params: ContactParams,
    sites: Vec<ContactSite>,
    groups: Vec<TermGroup>,
    /// Per (site, obstacle) pair, at index site·n_obstacles + obstacle: what friction does
    /// there. Changed between solves only ([`Self::update_friction`]), through a shared
    /// reference so that a time stepper holding the problem can update it.
    friction: RefCell<Vec<Friction>>,
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
        if model.term_groups().iter().any(|g| g.bit == FRICTION.bit) {
            return Err(ModelError::structure(
                "obstacles",
                "the model already uses the friction term group's bit",
            ));
        }
        let mut groups = model.term_groups().to_vec();
        groups.push(CONTACT);
        groups.push(FRICTION);
        let pairs = sites.len() * obstacles.len();
        Ok(Self {
            model,
            obstacles,
            params,
            sites,
            groups,
            friction: RefCell::new(vec![Friction::Free; pairs]),
        })
    }

    /// The friction state of the contact of site `site` with obstacle `obstacle`.
    pub fn friction(&self, site: usize, obstacle: usize) -> Friction {
        self.friction.borrow()[site * self.obstacles.len() + obstacle]
    }

    /// Normal gap (m), outward normal and normal force (N, ≥ 0) of a site at `p` against
    /// obstacle `o`, with `length` (m) the centerline the site stands for.
    fn normal_contact(&self, p: &Vector3<f64>, o: usize, length: f64) -> (f64, Vector3<f64>, f64) {
        let s = self.obstacles[o].surface(p);
        let gap = s.distance - self.params.radius;
        let force = if gap < self.params.activation {
            -self.params.stiffness * length * barrier(gap, self.params.activation).1
        } else {
            0.0
        };
        (gap, s.normal, force)
    }

    /// The active-set step of Coulomb friction at `state`, an equilibrium (or time step)
    /// solved with the current friction set; `previous` is the state before that solve (to
    /// detect slides that stopped). A contact on a rough surface starts to stick where it is;
    /// a sticking contact whose anchor pulls harder than μ f_n slides against μ f_n along
    /// that pull; a sliding contact whose slip since `previous` runs against its friction
    /// force no more (it stopped or reversed) sticks again; a contact that opened is freed.
    /// Sliding forces are refreshed to μ times the current normal force. When the update says
    /// [`changed`](FrictionUpdate::changed), solve again from `previous`.
    pub fn update_friction(&self, state: &P::State, previous: Option<&P::State>) -> FrictionUpdate {
        let mut update = FrictionUpdate::default();
        let mut friction = self.friction.borrow_mut();
        let n_obstacles = self.obstacles.len();
        for (k, site) in self.sites.iter().enumerate() {
            let x = self.model.site_position(state, site);
            for o in 0..n_obstacles {
                let slot = &mut friction[k * n_obstacles + o];
                let mu = self.obstacles[o].friction();
                let (_, normal, f_n) = self.normal_contact(&x, o, site.length);
                if f_n <= 0.0 || mu == 0.0 {
                    if *slot != Friction::Free {
                        update.released += 1;
                        *slot = Friction::Free;
                    }
                    continue;
                }
                let limit = mu * f_n;
                *slot = match *slot {
                    Friction::Free => {
                        update.stuck += 1;
                        Friction::Stick { anchor: x, normal }
                    }
                    stick @ Friction::Stick { .. } => {
                        let pull = stick.force(&x, site.length, self.params.stick_stiffness);
                        let magnitude = pull.norm();
                        if magnitude > limit {
                            update.slipped += 1;
                            Friction::Slide {
                                force: pull * (limit / magnitude),
                            }
                        } else {
                            stick
                        }
                    }
                    Friction::Slide { force } => {
                        let direction = force.normalize();
                        let slip = previous.map_or(Vector3::zeros(), |p| {
                            let d = x - self.model.site_position(p, site);
                            d - normal * normal.dot(&d)
                        });
                        if previous.is_some() && slip.dot(&direction) >= 0.0 {
                            // Kinetic friction opposes the slip: a slip along the force means
                            // the contact stopped (or reversed) within the solve.
                            update.stuck += 1;
                            Friction::Stick { anchor: x, normal }
                        } else {
                            Friction::Slide {
                                force: direction * limit,
                            }
                        }
                    }
                };
            }
        }
        update
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
                    let friction = self.friction(k, o);
                    out.push(ContactForce {
                        site: k,
                        obstacle: o,
                        gap,
                        normal: s.normal,
                        force: s.normal * (-self.params.stiffness * site.length * slope),
                        friction: friction.force(&p, site.length, self.params.stick_stiffness),
                        sticking: matches!(friction, Friction::Stick { .. }),
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

    /// The contact and friction energy (J) of `state`.
    fn contact_energy(&self, state: &P::State) -> f64 {
        let mut e = 0.0;
        let friction = self.friction.borrow();
        for (k, site) in self.sites.iter().enumerate() {
            let p = self.model.site_position(state, site);
            for (o, obstacle) in self.obstacles.iter().enumerate() {
                let gap = obstacle.surface(&p).distance - self.params.radius;
                if gap < self.params.activation {
                    e += self.params.stiffness
                        * site.length
                        * barrier(gap, self.params.activation).0;
                }
                let f = friction[k * self.obstacles.len() + o];
                if let Some((energy, _, _)) =
                    f.derivatives(&p, site.length, self.params.stick_stiffness)
                {
                    e += energy;
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
        if asm.selects(FRICTION) {
            let friction = self.friction.borrow();
            for (k, site) in self.sites.iter().enumerate() {
                let p = self.model.site_position(state, site);
                for o in 0..self.obstacles.len() {
                    let f = friction[k * self.obstacles.len() + o];
                    if let Some((energy, grad, hess)) =
                        f.derivatives(&p, site.length, self.params.stick_stiffness)
                    {
                        let mut part = asm.part(&site.dofs);
                        part.local(&[0, 1, 2], energy, energy.abs(), &grad, &hess);
                        let info = part.finish();
                        asm.absorb(info);
                    }
                }
            }
        }
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

impl<P: ContactSites + crate::dynamics::FlatDofs> crate::dynamics::FlatDofs
    for ContactProblem<'_, P>
{
    fn has_flat_dofs(&self) -> bool {
        self.model.has_flat_dofs()
    }
}
