//! Moving a state along a step: the exponential map on the frames, a linear or a
//! rotation-preserving update of the positions, the log-map difference of two states, and the
//! step caps.

use nalgebra::UnitQuaternion;

use crate::assembly::FIXED;
use crate::geometry::Vec3;
use crate::lie::darboux::rotation_log;
use crate::lie::quaternion::from_unit;

use super::core::FramedCore;
use super::state::FramedState;

/// Largest rotation (rad) of a frame or of an element's chord in one Newton step.
const MAX_TURN: f64 = std::f64::consts::FRAC_PI_4;
/// Largest relative change of an element's chord in one Newton step.
const MAX_CHORD_CHANGE: f64 = 0.5;

/// The principal rotation vector of the unit quaternion `q` (|·| ≤ π), accurate for small
/// angles.
pub fn rotation_vector(q: &UnitQuaternion<f64>) -> Vec3 {
    let mut v = from_unit(q);
    if v[0] < 0.0 {
        v = -v;
    }
    rotation_log(&v).value
}

impl FramedCore {
    /// The spatial rotation increment of frame `j` in `dx` (FIXED components are 0).
    pub(crate) fn frame_step(&self, dx: &[f64], j: usize, alpha: f64) -> Vec3 {
        let mut w = Vec3::zeros();
        for (k, &i) in self.dofs.frame_slots(j).iter().enumerate() {
            if i != FIXED {
                w[k] = alpha * dx[i];
            }
        }
        w
    }

    /// The displacement of vertex `v` in `dx`.
    pub(crate) fn vertex_step(&self, dx: &[f64], v: usize, alpha: f64) -> Vec3 {
        let mut d = Vec3::zeros();
        for (k, &i) in self.dofs.vertex_slots(v).iter().enumerate() {
            if i != FIXED {
                d[k] = alpha * dx[i];
            }
        }
        d
    }

    /// Frames of `out` = exp(α ω_j) ⊗ frames of `state`; moment angles continued.
    fn turn_frames(&self, state: &FramedState, dx: &[f64], alpha: f64, out: &mut FramedState) {
        out.frames.clear();
        out.frames
            .extend(state.frames.iter().enumerate().map(|(j, p)| {
                let w = self.frame_step(dx, j, alpha);
                let mut q = UnitQuaternion::from_scaled_axis(w) * p;
                q.renormalize();
                q
            }));
        out.clamp_frames = state.clamp_frames;
        self.continue_moment_angles(state, out);
    }

    /// Continues the moment loads' unwrapped angles from `old` to the frames of `out`.
    pub(crate) fn continue_moment_angles(&self, old: &FramedState, out: &mut FramedState) {
        out.moment_angles.clear();
        for (m, &a) in self.moments.iter().zip(&old.moment_angles) {
            let j = m.frame;
            out.moment_angles
                .push(m.updated_angles(&old.frames[j], &out.frames[j], a));
        }
    }

    /// The chart: x ← x + α dx, p ← e(α ω) p. The energy's derivatives are those of this map.
    pub(crate) fn displace_linear(
        &self,
        state: &FramedState,
        dx: &[f64],
        alpha: f64,
        out: &mut FramedState,
    ) {
        out.positions.clone_from(&state.positions);
        for (v, x) in out.positions.iter_mut().enumerate() {
            *x += self.vertex_step(dx, v, alpha);
        }
        self.turn_frames(state, dx, alpha, out);
    }

    /// The retraction the solver uses: frames by the exponential map; positions rebuilt by
    /// walking the elements away from the supports, each chord given by the model's
    /// `new_chord(j)` (the chord of element j after the step α dx, which must agree with
    /// x_{j+1} − x_j + α(δx_{j+1} − δx_j) to first order). The models carry each chord with
    /// its element's frames so that the stiff shear and extension strains change linearly
    /// along the step: with them, the chart's linear position update would create
    /// second-order strains that make line searches crawl. Between two supports the walks from
    /// both ends are blended linearly in arc length, so supports stay exact.
    pub(crate) fn retract_with(
        &self,
        state: &FramedState,
        dx: &[f64],
        alpha: f64,
        out: &mut FramedState,
        new_edge: impl Fn(usize) -> Vec3,
    ) {
        let x = &state.positions;
        let disp = |v: usize| self.vertex_step(dx, v, alpha);
        let n = self.n_edges();
        let p = &mut out.positions;
        p.clone_from(x);
        let fixed = &self.fixed_vertices;
        if fixed.is_empty() {
            for (v, pv) in p.iter_mut().enumerate() {
                *pv += disp(v);
            }
        } else {
            let first = fixed[0];
            let last = fixed[fixed.len() - 1];
            for j in (0..first).rev() {
                p[j] = p[j + 1] - new_edge(j);
            }
            for j in last..n {
                p[j + 1] = p[j] + new_edge(j);
            }
            // Between two supports: blend the walks from both ends linearly in arc length.
            for w in fixed.windows(2) {
                let (a, b) = (w[0], w[1]);
                if b <= a + 1 {
                    continue;
                }
                // The forward walk is kept in p (no buffer), then blended in place.
                let mut forward = x[a];
                for j in a..b - 1 {
                    forward += new_edge(j);
                    p[j + 1] = forward;
                }
                let mut backward = x[b];
                let s_total: f64 = self.rest_lengths[a..b].iter().sum();
                let mut s_from_b = 0.0;
                for j in (a..b).rev() {
                    backward -= new_edge(j);
                    s_from_b += self.rest_lengths[j];
                    if j > a {
                        let wb = 1.0 - s_from_b / s_total;
                        p[j] = p[j] * (1.0 - wb) + backward * wb;
                    }
                }
            }
        }
        self.turn_frames(state, dx, alpha, out);
    }

    /// `out` = a ⊖ b: position differences and the spatial rotation vectors log(p_a p̄_b).
    pub(crate) fn difference(&self, a: &FramedState, b: &FramedState, out: &mut [f64]) {
        for (i, o) in out.iter_mut().enumerate() {
            *o = match self.dofs.slot(i) {
                super::layout::DofSlot::Position { v, k } => a.positions[v][k] - b.positions[v][k],
                super::layout::DofSlot::Rotation { j, k } => {
                    // Each frame's rotation vector is needed three times; k = 0 is the first.
                    rotation_vector(&(a.frames[j] * b.frames[j].inverse()))[k]
                }
            };
        }
    }

    /// Largest α ∈ (0, 1] such that α dx turns no frame and no chord by more than π/4 and
    /// changes no chord by more than half its length.
    pub(crate) fn max_step(&self, s: &FramedState, dx: &[f64]) -> f64 {
        let mut alpha: f64 = 1.0;
        for j in 0..s.frames.len() {
            let w = self.frame_step(dx, j, 1.0).norm();
            if w > MAX_TURN {
                alpha = alpha.min(MAX_TURN / w);
            }
        }
        for j in 0..self.n_edges() {
            let e = s.positions[j + 1] - s.positions[j];
            let de = self.vertex_step(dx, j + 1, 1.0) - self.vertex_step(dx, j, 1.0);
            let new = e + de;
            let turn = e.cross(&new).norm().atan2(e.dot(&new));
            if turn > MAX_TURN {
                alpha = alpha.min(MAX_TURN / turn);
            }
            let change = de.norm() / e.norm();
            if change > MAX_CHORD_CHANGE {
                alpha = alpha.min(MAX_CHORD_CHANGE / change);
            }
        }
        alpha
    }
}
