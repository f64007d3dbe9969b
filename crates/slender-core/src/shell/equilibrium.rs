//! The shell as an [`EquilibriumProblem`]: step caps, scales and the mass metric.

use crate::assembly::{Assembler, TermGroup};
use crate::linalg::{SparseSymmetricMatrix, SymmetricMatrix};
use crate::solver::problem::{EquilibriumProblem, MassMetric};

use super::dofs::DofKind;
use super::groups::ALL_GROUPS;
use super::load_path::LoadPath;
use super::mixed_update::{membrane_remainders, remainder_energy};
use super::model::Shell;
use super::state::ShellState;
use super::strip_guess::both_ends_guess;

/// Largest change of an edge angle φ (rad) in one Newton step: keeps α = θ/2 ± φ away from
/// the tan barrier at π/2.
const MAX_ANGLE_STEP: f64 = std::f64::consts::FRAC_PI_4;
/// Largest relative change of an edge vector in one Newton step (no triangle inversion).
const MAX_EDGE_CHANGE: f64 = 0.5;

impl EquilibriumProblem for Shell {
    type State = ShellState;
    type Hessian = SparseSymmetricMatrix;

    fn n_free(&self) -> usize {
        self.dofs.n_free()
    }

    fn new_hessian(&self) -> SparseSymmetricMatrix {
        self.sparse_hessian()
    }

    fn term_groups(&self) -> &[TermGroup] {
        &ALL_GROUPS
    }

    fn assemble_selected<M: SymmetricMatrix>(
        &self,
        state: &ShellState,
        load: f64,
        asm: &mut Assembler<'_, M>,
    ) {
        self.assemble_into(state, load, asm);
    }

    fn difference(&self, a: &ShellState, b: &ShellState, out: &mut [f64]) {
        for (i, o) in out.iter_mut().enumerate() {
            *o = match self.dofs.split(self.dofs.full(i)) {
                DofKind::Position(v, c) => a.positions[v][c] - b.positions[v][c],
                DofKind::Angle(e) => a.angles[e] - b.angles[e],
            };
        }
    }

    fn displace(&self, state: &ShellState, dx: &[f64], alpha: f64, out: &mut ShellState) {
        out.clone_from(state);
        for (i, d) in dx.iter().enumerate() {
            match self.dofs.split(self.dofs.full(i)) {
                DofKind::Position(v, c) => out.positions[v][c] += alpha * d,
                DofKind::Angle(e) => out.angles[e] += alpha * d,
            }
        }
        membrane_remainders(
            &self.mesh.faces,
            &state.positions,
            &out.positions,
            &mut out.membrane_remainder,
        );
    }

    fn merit(&self, trial: &ShellState, load: f64) -> f64 {
        let (lambda, mu) = self.properties.lame();
        let h = self.properties.thickness;
        let left_out: f64 = trial
            .membrane_remainder
            .iter()
            .zip(&self.rest)
            .map(|(r, rest)| remainder_energy(rest, h, lambda, mu, r))
            .sum();
        self.energy(trial, load) - left_out
    }

    fn secant_predictor(&self) -> bool {
        // Turning a strip held at one end: the first guess turns it rigidly with its clamp,
        // while a secant step extrapolates the turn linearly and stretches the membrane at
        // second order (measured in the lateral-buckling protocol: from a rigid turn a step
        // converges in about 5 iterations, from the secant its Hessian has tens of negative
        // pivots and the step fails).
        match &self.load_path {
            LoadPath::Gravity => true,
            LoadPath::ClampRotation { .. } => false,
            LoadPath::ClampMotion(motions) => motions
                .iter()
                .flatten()
                .any(|m| self.is_clamped(m.end.other())),
        }
    }

    fn impose_load(&self, state: &mut ShellState, from: f64, to: f64, guess: bool) {
        if let LoadPath::ClampMotion(motions) = &self.load_path {
            for m in motions.iter().flatten() {
                if guess {
                    if self.is_clamped(m.end.other()) {
                        // Held at both ends: the length-preserving guess (`strip_guess`).
                        let columns = self.mesh.n_width + 1;
                        let (length, n_length) = (self.properties.length, self.mesh.n_length);
                        let rest = &self.mesh.rest_positions;
                        self.guess.with(|rows| {
                            rows.stations.clear();
                            rows.stations
                                .extend((0..=n_length).map(|i| rest[i * columns].x / length));
                            rows.held.clear();
                            rows.held.resize(n_length + 1, false);
                            rows.held[0] = true;
                            rows.held[n_length] = true;
                            both_ends_guess(&mut state.positions, columns, m, from, to, rows);
                        });
                    } else {
                        // Held at one end only, the strip turns rigidly with its clamp: exact
                        // for the unloaded strip, and no membrane stretch for a loaded one.
                        for p in state.positions.iter_mut() {
                            *p = m.carry(p, from, to, 1.0);
                        }
                    }
                    state.membrane_remainder.clear();
                }
                let e = m.end.index();
                state.clamps[e] = m.move_clamp(&state.clamps[e], from, to);
            }
            self.apply_clamp(state);
            return;
        }
        let (Some(old), Some(new)) = (self.load_path.clamp_at(from), self.load_path.clamp_at(to))
        else {
            return;
        };
        if guess {
            // First guess: the whole strip turns rigidly with its clamp (a linearized guess
            // would stretch the membrane at second order, see `mixed_update`).
            let turn = new.rotation * old.rotation.inverse();
            for p in state.positions.iter_mut() {
                *p = turn * (*p - old.translation) + new.translation;
            }
            state.membrane_remainder.clear();
        }
        self.set_clamp(new, state);
    }

    fn turn_free(&self, from: f64, to: f64, v: &mut [f64], inverse: bool) -> bool {
        // Only the clamp rotation's first guess is one rigid turn of the whole strip; the
        // membrane and bending energies are invariant under it, the edge angles (measured
        // from the faces) do not turn, and gravity is linear in the positions.
        let (Some(old), Some(new)) = (self.load_path.clamp_at(from), self.load_path.clamp_at(to))
        else {
            return false;
        };
        let turn = new.rotation * old.rotation.inverse();
        let turn = if inverse { turn.inverse() } else { turn };
        crate::shell::turn_vertex_blocks(
            v.len(),
            |i| match self.dofs.split(self.dofs.full(i)) {
                DofKind::Position(vertex, c) => Some((vertex, c)),
                DofKind::Angle(_) => None,
            },
            &turn,
            v,
        )
    }

    fn max_step(&self, state: &ShellState, dx: &[f64]) -> f64 {
        let mut alpha: f64 = 1.0;
        for (i, d) in dx.iter().enumerate() {
            if self.dofs.is_angle(i) && d.abs() > MAX_ANGLE_STEP {
                alpha = alpha.min(MAX_ANGLE_STEP / d.abs());
            }
        }
        // A vertex's step (0 for a held coordinate), looked up rather than gathered into a
        // copy of the state.
        let step = |v: usize| -> crate::geometry::Vec3 {
            crate::geometry::Vec3::from_fn(|c, _| self.dofs.vertex(v, c).map_or(0.0, |i| dx[i]))
        };
        for [a, b] in &self.mesh.edges {
            let e = state.positions[*b] - state.positions[*a];
            let de = (step(*b) - step(*a)).norm();
            let change = de / e.norm();
            if change > MAX_EDGE_CHANGE {
                alpha = alpha.min(MAX_EDGE_CHANGE / change);
            }
        }
        alpha
    }

    fn force_length(&self, i: usize) -> f64 {
        if self.dofs.is_angle(i) {
            self.properties.length
        } else {
            1.0
        }
    }

    fn dof_magnitude(&self, state: &ShellState, i: usize) -> f64 {
        match self.dofs.split(self.dofs.full(i)) {
            DofKind::Position(v, _) => state.positions[v].amax().max(self.properties.length),
            DofKind::Angle(e) => state.angles[e].abs().max(std::f64::consts::PI),
        }
    }
}

impl MassMetric for Shell {
    fn inertia_metric(&self, i: usize) -> f64 {
        match self.dofs.split(self.dofs.full(i)) {
            DofKind::Position(v, _) => self.vertex_masses[v],
            DofKind::Angle(e) => self.edge_inertia[e],
        }
    }

    fn eigenvalue_scale(&self) -> f64 {
        let p = &self.properties;
        p.bending_stiffness() / (p.density * p.thickness * p.length.powi(4))
    }
}

#[cfg(feature = "testing")]
impl crate::testing::RigidMotion for Shell {
    fn rigidly_moved(
        &self,
        state: &ShellState,
        rotation: &nalgebra::Rotation3<f64>,
        offset: &crate::geometry::Vec3,
    ) -> ShellState {
        ShellState {
            positions: state
                .positions
                .iter()
                .map(|x| rotation * x + offset)
                .collect(),
            angles: state.angles.clone(),
            clamps: [
                state.clamps[0].moved(rotation, offset),
                state.clamps[1].moved(rotation, offset),
            ],
            membrane_remainder: Vec::new(),
        }
    }

    fn rest(&self) -> ShellState {
        self.rest_state()
    }

    fn internal_terms(&self) -> crate::assembly::TermSet {
        super::groups::INTERNAL
    }
}
