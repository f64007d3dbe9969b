//! The B-spline shell as an [`EquilibriumProblem`]: the retraction with its Newton-update
//! memory, the merit, the clamp motions of the load path, step caps, scales and the mass
//! metric.

use crate::assembly::{Assembler, TermGroup};
use crate::linalg::{SparseSymmetricMatrix, SymmetricMatrix};
use crate::solver::problem::{EquilibriumProblem, MassMetric};

use super::clamp::StripEnd;
use super::groups::ALL_GROUPS;
use super::model::{with_elements, BsplineShell, Elements};
use super::state::BsplineState;
use crate::shell::strip_guess::both_ends_guess;

/// Largest relative change of a control-net edge in one Newton step (keeps the surface from
/// folding over within a step, as the mid-edge shell's edge cap does).
const MAX_EDGE_CHANGE: f64 = 0.5;

impl EquilibriumProblem for BsplineShell {
    type State = BsplineState;
    type Hessian = SparseSymmetricMatrix;

    fn n_free(&self) -> usize {
        self.full_of_free.len()
    }

    fn new_hessian(&self) -> SparseSymmetricMatrix {
        self.sparse_hessian()
    }

    fn term_groups(&self) -> &[TermGroup] {
        &ALL_GROUPS
    }

    fn assemble_selected<M: SymmetricMatrix>(
        &self,
        state: &BsplineState,
        load: f64,
        asm: &mut Assembler<'_, M>,
    ) {
        self.assemble_into(state, load, asm);
    }

    fn difference(&self, a: &BsplineState, b: &BsplineState, out: &mut [f64]) {
        for (o, &f) in out.iter_mut().zip(&self.full_of_free) {
            *o = a.control_points[f / 3][f % 3] - b.control_points[f / 3][f % 3];
        }
    }

    fn displace(&self, state: &BsplineState, dx: &[f64], alpha: f64, out: &mut BsplineState) {
        out.control_points.clone_from(&state.control_points);
        out.clamps = state.clamps;
        for (d, &f) in dx.iter().zip(&self.full_of_free) {
            out.control_points[f / 3][f % 3] += alpha * d;
        }
        // Memory of the mixed-integration-point update (see `shell::mixed_update`).
        out.membrane_remainder.clear();
        out.membrane_remainder.reserve(self.n_points);
        with_elements!(&self.elements, terms => {
            for t in terms {
                t.remainders(&state.control_points, &out.control_points, &mut out.membrane_remainder);
            }
        });
    }

    fn merit(&self, trial: &BsplineState, load: f64) -> f64 {
        let left_out: f64 = if trial.membrane_remainder.len() == self.n_points {
            with_elements!(&self.elements, terms => terms
                .iter()
                .map(|t| t.remainder_energy(&trial.membrane_remainder))
                .sum())
        } else {
            0.0
        };
        self.energy(trial, load) - left_out
    }

    fn secant_predictor(&self) -> bool {
        // As for the mid-edge shell: a strip held at one end turns rigidly with its clamp in
        // the first guess; the secant step would stretch it at second order.
        let motions = &self.load_path.motions;
        motions.is_empty() || motions.iter().any(|m| self.is_clamped(m.end.other()))
    }

    fn impose_load(&self, state: &mut BsplineState, from: f64, to: f64, guess: bool) {
        let motions = &self.load_path.motions;
        if motions.is_empty() {
            return;
        }
        if guess {
            let (n_u, n_v) = (self.patch.n_u(), self.patch.n_v());
            let length = self.properties.length;
            let knots = &self.patch.knots_u;
            self.guess.with(|rows| {
                rows.stations.clear();
                rows.stations
                    .extend((0..n_u).map(|i| knots.greville_at(i) / length));
                rows.held.clear();
                rows.held.resize(n_u, false);
                for end in StripEnd::BOTH {
                    if self.is_clamped(end) {
                        for r in end.held_rows(n_u) {
                            rows.held[r] = true;
                        }
                    }
                }
                for m in motions {
                    if self.is_clamped(m.end.other()) {
                        // Held at both ends: the length-preserving guess
                        // (`shell::strip_guess`).
                        both_ends_guess(&mut state.control_points, n_v, m, from, to, rows);
                    } else {
                        // Held at one end only, the strip turns rigidly with its clamp.
                        for p in state.control_points.iter_mut() {
                            *p = m.carry(p, from, to, 1.0);
                        }
                    }
                }
            });
            state.membrane_remainder.clear();
        }
        for m in motions {
            let e = m.end.index();
            state.clamps[e] = m.move_clamp(&state.clamps[e], from, to);
        }
        self.apply_clamps(state);
    }

    fn turn_free(&self, from: f64, to: f64, v: &mut [f64], inverse: bool) -> bool {
        // The first guess is one rigid turn of every control point only for a strip held at
        // one end, moved by one clamp motion; the energy is invariant under it and the loads
        // are linear in the control points.
        let [m] = self.load_path.motions.as_slice() else {
            return false;
        };
        if self.is_clamped(m.end.other()) {
            return false;
        }
        let turn = m.turn(from, to);
        let turn = if inverse { turn.inverse() } else { turn };
        crate::shell::turn_vertex_blocks(
            v.len(),
            |i| Some((self.full_of_free[i] / 3, self.full_of_free[i] % 3)),
            &turn,
            v,
        )
    }

    fn max_step(&self, state: &BsplineState, dx: &[f64]) -> f64 {
        self.step_scratch.with(|step| {
            step.clear();
            step.resize(state.control_points.len(), crate::geometry::Vec3::zeros());
            for (d, &f) in dx.iter().zip(&self.full_of_free) {
                step[f / 3][f % 3] = *d;
            }
            let (n_u, n_v) = (self.patch.n_u(), self.patch.n_v());
            let mut alpha: f64 = 1.0;
            let mut edge = |a: usize, b: usize| {
                let e = (state.control_points[b] - state.control_points[a]).norm();
                let de = (step[b] - step[a]).norm();
                if de > MAX_EDGE_CHANGE * e {
                    alpha = alpha.min(MAX_EDGE_CHANGE * e / de);
                }
            };
            for i in 0..n_u {
                for j in 0..n_v {
                    let c = self.patch.control(i, j);
                    if i + 1 < n_u {
                        edge(c, self.patch.control(i + 1, j));
                    }
                    if j + 1 < n_v {
                        edge(c, self.patch.control(i, j + 1));
                    }
                }
            }
            alpha
        })
    }

    fn force_length(&self, _i: usize) -> f64 {
        1.0
    }

    fn dof_magnitude(&self, state: &BsplineState, i: usize) -> f64 {
        let k = self.full_of_free[i] / 3;
        state.control_points[k].amax().max(self.properties.length)
    }
}

impl MassMetric for BsplineShell {
    fn inertia_metric(&self, i: usize) -> f64 {
        self.masses[self.full_of_free[i] / 3]
    }

    fn eigenvalue_scale(&self) -> f64 {
        let p = &self.properties;
        p.bending_stiffness() / (p.density * p.thickness * p.length.powi(4))
    }
}

#[cfg(feature = "testing")]
impl crate::testing::RigidMotion for BsplineShell {
    fn rigidly_moved(
        &self,
        state: &BsplineState,
        rotation: &nalgebra::Rotation3<f64>,
        offset: &crate::geometry::Vec3,
    ) -> BsplineState {
        BsplineState {
            control_points: state
                .control_points
                .iter()
                .map(|x| rotation * x + offset)
                .collect(),
            clamps: [
                state.clamps[0].moved(rotation, offset),
                state.clamps[1].moved(rotation, offset),
            ],
            membrane_remainder: Vec::new(),
        }
    }

    fn rest(&self) -> BsplineState {
        self.rest_state()
    }

    fn internal_terms(&self) -> crate::assembly::TermSet {
        super::groups::INTERNAL
    }
}
