//! A mid-edge shell strip of a scene with obstacles: solved as a [`ContactProblem`] around
//! the strip (its vertices held h/2 off every obstacle, see `contact::shell_sites`) for every
//! solve — the loaded strip, its clamps' moves, gravity edits —, friction settled as for rods
//! (`contact_solve`), and the friction state of its contacts kept across solves.

use std::sync::Arc;

use crate::assembly::FIXED;
use crate::bspline_shell::ClampMotion;
use crate::contact::edge_penetration::{deepest_point_inside_triangle, segment_crossing};
use crate::contact::{ContactForce, ContactParams, ContactProblem, Friction, Obstacle};
use crate::geometry::Vec3;
use crate::linalg::AdaptiveMatrix;
use crate::shell::{Shell, ShellState};
use crate::solver::{EquilibriumSolver, SolveReport, SolverParams};

use super::contact_solve::solve_with_contact;
use super::session::unsolved;
use super::shell_run::{StripLoad, StripProblem};

/// What a strip touches: the scene's obstacles and the strip's contact parameters.
#[derive(Clone, Debug)]
pub(crate) struct StripContact {
    /// The obstacles (shared with the rods' solves).
    pub obstacles: Vec<Arc<dyn Obstacle>>,
    /// Radius h/2, activation distance, stiffness per unit area (N/m³).
    pub params: ContactParams,
}

/// The contacts of a strip at its equilibrium, for the results.
#[derive(Clone, Debug, Default)]
pub(crate) struct StripContacts {
    /// Every active contact at a free vertex with its force, its vertex and the vertex's
    /// position (m). Contacts at clamped vertices are left out: the clamp takes their force,
    /// as a rod's support does (the strip's clamp force is that of its own energy).
    pub contacts: Vec<(ContactForce, usize, Vec3)>,
    /// Smallest gap (m) of any vertex (clamped ones included) to any obstacle: distance
    /// minus h/2.
    pub min_gap: f64,
    /// Faces whose mid-surface runs through an obstacle between their vertices.
    pub through: Vec<FaceThrough>,
}

/// A face of a strip whose mid-surface passes through an obstacle (see
/// [`deepest_point_inside_triangle`]).
#[derive(Clone, Debug)]
pub(crate) struct FaceThrough {
    /// The face (index in the strip's mesh) and its three vertices.
    pub face: usize,
    pub vertices: [usize; 3],
    /// The obstacle (index in the scene's obstacles).
    pub obstacle: usize,
    /// The deepest point of the mid-surface inside the obstacle (m).
    pub position: Vec3,
    /// How deep (m) that point is inside the obstacle's surface (> 0; 0 across a mesh).
    pub depth: f64,
}

/// A strip in contact: state, backup, solver, last report, friction state.
#[derive(Clone)]
pub(crate) struct ContactStripRun {
    pub(crate) state: ShellState,
    backup: ShellState,
    solver: EquilibriumSolver<ShellState, AdaptiveMatrix>,
    pub(crate) report: SolveReport,
    contact: StripContact,
    /// The friction state of the contacts at `state` (empty: every contact free).
    friction: Vec<Friction>,
    backup_friction: Vec<Friction>,
}

impl ContactStripRun {
    /// The strip loaded from flat (loads ramped from 0, clamps at rest) in contact. No rod
    /// predictor here: the rod's equilibrium knows no obstacles and may start the strip inside
    /// one.
    pub(crate) fn new(shell: &Shell, contact: StripContact, params: &SolverParams) -> Self {
        let flat = shell.rest_state();
        // The solver's template: the Hessian's pattern is the strip's (obstacle contacts touch
        // one vertex at a time), whatever the obstacles and parameters; without obstacles and
        // with valid parameters the problem always builds.
        let template = ContactProblem::new(
            shell,
            Vec::new(),
            ContactParams::for_area_load(0.0, 1.0, 1.0),
            &flat,
        )
        .expect("valid parameters and no obstacle");
        let solver = EquilibriumSolver::new(&template, &flat, *params);
        let mut run = Self {
            state: flat.clone(),
            backup: flat,
            solver,
            report: unsolved(String::new()),
            contact,
            friction: Vec::new(),
            backup_friction: Vec::new(),
        };
        // Contacts within ĝ of a rough surface at the start stick where they are.
        if let Ok(p) = run.problem(shell) {
            p.update_friction(&run.state, None);
            run.friction = p.friction_state();
        }
        run.report = run.solve(shell, 0.0, 1.0);
        run.save();
        run
    }

    /// The contact problem around `shell` with the current friction state.
    pub(crate) fn problem<'a>(
        &self,
        shell: &'a Shell,
    ) -> Result<ContactProblem<'a, Shell>, String> {
        ContactProblem::new(
            shell,
            self.contact.obstacles.clone(),
            self.contact.params,
            &self.state,
        )
        .inspect(|p| p.set_friction_state(&self.friction))
        .map_err(|e| format!("contact: {e}"))
    }

    /// Solves from load `from` to `to` in place, the friction state updated if it converged.
    fn solve(&mut self, shell: &Shell, from: f64, to: f64) -> SolveReport {
        let problem = match self.problem(shell) {
            Ok(p) => p,
            Err(e) => return unsolved(e),
        };
        let report = solve_with_contact(&problem, &mut self.solver, &mut self.state, from, to);
        if report.converged() {
            self.friction = problem.friction_state();
        }
        report
    }

    /// Obstacle `o` replaced by `moved` (an obstacle moved in a session); the state is not
    /// re-solved.
    pub(crate) fn set_obstacle(&mut self, o: usize, moved: Arc<dyn Obstacle>) {
        self.contact.obstacles[o] = moved;
    }

    /// The state and the friction state of its contacts, for an obstacle move to carry along
    /// (see `Session::move_obstacle_to`).
    pub(crate) fn state_and_friction(&mut self) -> (&mut ShellState, &mut Vec<Friction>) {
        (&mut self.state, &mut self.friction)
    }

    /// Re-solves at full load, warm from the current state, with the long Newton budget of a
    /// snap (a contact pressed by a moved obstacle settles on its barrier by many short
    /// steps); the state stays where the solve leaves it, converged or not.
    pub(crate) fn resolve(&mut self, shell: &Shell) -> SolveReport {
        let user = self.solver.params;
        self.solver.params.max_iterations = user.snap_iterations.max(user.max_iterations);
        self.report = self.solve(shell, 1.0, 1.0);
        self.solver.params = user;
        self.report.clone()
    }

    fn save(&mut self) {
        self.backup.clone_from(&self.state);
        self.backup_friction.clone_from(&self.friction);
    }

    fn restore(&mut self) {
        self.state.clone_from(&self.backup);
        self.friction.clone_from(&self.backup_friction);
    }

    /// Moves the clamps by `motions` in at least `steps` load steps, warm from the current
    /// state; if the solve does not converge, the state goes back to where it was.
    pub(crate) fn move_clamps(
        &mut self,
        model: &mut Shell,
        motions: &[ClampMotion],
        steps: f64,
    ) -> SolveReport {
        self.save();
        model.set_motions(motions);
        let user = self.solver.params;
        let piece = 1.0 / steps;
        self.solver.params.initial_load_step = user.initial_load_step.min(piece);
        self.solver.params.max_load_step = user.max_load_step.min(piece);
        let report = self.solve(model, 0.0, 1.0);
        self.solver.params = user;
        model.clear_motions();
        if !report.converged() {
            self.restore();
        }
        report
    }

    /// A load changed from `old` to `new` (gravity or a point force): one solve warm from the
    /// current state; if it does not converge, the load and the state go back.
    pub(crate) fn change_load(
        &mut self,
        model: &mut Shell,
        old: StripLoad,
        new: StripLoad,
    ) -> SolveReport {
        self.save();
        model.set_load(new);
        let report = self.solve(model, 1.0, 1.0);
        if !report.converged() {
            model.set_load(old);
            self.restore();
        }
        report
    }

    /// Undoes the last [`Self::change_load`] that converged.
    pub(crate) fn undo_load(&mut self, model: &mut Shell, old: StripLoad) {
        model.set_load(old);
        self.restore();
    }

    /// The contacts at the current state (see [`StripContacts`]); `None` if the problem could
    /// not be built (the report says why).
    pub(crate) fn contacts(&self, shell: &Shell) -> Option<StripContacts> {
        let p = self.problem(shell).ok()?;
        let contacts = p
            .contact_forces(&self.state)
            .into_iter()
            .filter_map(|f| {
                let site = p.sites()[f.site];
                if site.dofs.iter().all(|d| d.dof == FIXED) {
                    return None;
                }
                Some((f, site.vertex, self.state.positions[site.vertex]))
            })
            .collect();
        Some(StripContacts {
            contacts,
            min_gap: p.min_gap(&self.state),
            through: self.faces_through(shell),
        })
    }

    /// Every face whose mid-surface runs through an obstacle at the current state: into a
    /// solid, or across a mesh (one of the face's edges through the mesh, or one of the mesh's
    /// edges through the face: a panel's corner poking through its interior).
    fn faces_through(&self, shell: &Shell) -> Vec<FaceThrough> {
        let x = &self.state.positions;
        let mut through = Vec::new();
        for (face, &[a, b, c]) in shell.mesh().faces.iter().enumerate() {
            for (obstacle, o) in self.contact.obstacles.iter().enumerate() {
                let found = if o.signed() {
                    let surface = |p: &Vec3| o.surface(p).distance;
                    deepest_point_inside_triangle(surface, [x[a], x[b], x[c]])
                } else {
                    [(a, b), (b, c), (c, a)]
                        .into_iter()
                        .find_map(|(i, j)| {
                            segment_crossing(o.as_ref(), &x[i], &x[j])
                                .map(|t| (x[i] + (x[j] - x[i]) * t, 0.0))
                        })
                        .or_else(|| {
                            o.edge_through_triangle(&[x[a], x[b], x[c]])
                                .map(|p| (p, 0.0))
                        })
                };
                if let Some((position, d)) = found {
                    through.push(FaceThrough {
                        face,
                        vertices: [a, b, c],
                        obstacle,
                        position,
                        depth: d.abs(),
                    });
                }
            }
        }
        through
    }
}
