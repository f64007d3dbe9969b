//! Moving a rod state along a step: the linear update and the rotation-preserving retraction
//! the solver uses, with frames and load angles carried along.

use crate::geometry::Vec3;

use super::dofs::FIXED;
use super::model::Rod;
use super::state::RodState;

impl Rod {
    /// Continues the moment loads' unwrapped angles from `old` to the frames of `out`, and
    /// carries the frozen follower loads over unchanged (they change only when refreshed, so a
    /// trial state's energy is measured under the same loads as the state it left).
    pub(super) fn update_load_angles(&self, old: &RodState, out: &mut RodState) {
        out.followers.clone_from(&old.followers);
        out.load_angles.clear();
        for (m, &angles) in self.moments.iter().zip(&old.load_angles) {
            let j = m.edge;
            let updated = m.updated_angles(&old.material_frame(j), &out.material_frame(j), angles);
            out.load_angles.push(updated);
        }
    }

    /// `out` = `state` + `alpha·dx` in the plain linear sense (x ← x + α dx, θ ← θ + α dθ),
    /// with frames transported. The solver uses [`Rod::retract`]; this is the map whose
    /// derivatives the energy's gradient and Hessian are (finite-difference tests use it).
    pub fn displace_linear(&self, state: &RodState, dx: &[f64], alpha: f64, out: &mut RodState) {
        self.displace_linear_by(state, |i| dx[i], alpha, out);
    }

    /// As [`Self::displace_linear`] with the step of free DOF `i` given by `dx(i)` (for a rod
    /// that is a member of a larger structure, whose step lives in the structure's DOFs).
    pub fn displace_linear_by(
        &self,
        state: &RodState,
        dx: impl Fn(usize) -> f64,
        alpha: f64,
        out: &mut RodState,
    ) {
        out.positions.clone_from(&state.positions);
        out.thetas.clone_from(&state.thetas);
        for i in 0..self.dofs.n_free() {
            let d = dx(i);
            let f = self.dofs.full_index(i);
            if f % 4 == 3 {
                out.thetas[f / 4] += alpha * d;
            } else {
                out.positions[f / 4][f % 4] += alpha * d;
            }
        }
        state
            .frames
            .transport_into(&out.positions, &self.hinge_edges, &mut out.frames);
        self.update_load_angles(state, out);
    }

    /// `out` = `state` moved along `alpha·dx` by a rotation-preserving retraction: each edge's
    /// step is applied as a rotation (by its transverse part) and an axial change (by its
    /// tangential part), and positions are rebuilt by walking the edges away from the
    /// supports. It agrees with x + α dx to first order, so Newton's convergence is unchanged,
    /// but a rotation no longer stretches edges at second order — with EA L²/EI ≈ 10⁷ that
    /// second-order stretch would otherwise force line searches to crawl.
    ///
    /// Between two fixed vertices the walks from both ends are blended linearly in arc length,
    /// so supports stay exact and only the O(|dx|²) closure gap is spread along the segment.
    pub fn retract(&self, state: &RodState, dx: &[f64], alpha: f64, out: &mut RodState) {
        self.retract_by(state, |i| dx[i], alpha, out);
    }

    /// As [`Self::retract`] with the step of free DOF `i` given by `dx(i)`. The walks start
    /// from the *anchors*: the fixed vertices and any vertex a structure moves linearly (a
    /// joint shared with another member, a slider), so that such vertices move by exactly
    /// their step and members sharing them stay joined.
    pub fn retract_by(
        &self,
        state: &RodState,
        dx: impl Fn(usize) -> f64,
        alpha: f64,
        out: &mut RodState,
    ) {
        out.thetas.clone_from(&state.thetas);
        for j in 0..self.n_edges() {
            let i = self.dofs.theta(j);
            if i != FIXED {
                out.thetas[j] += alpha * dx(i);
            }
        }
        let x = &state.positions;
        let disp = |v: usize| -> Vec3 {
            let mut d = Vec3::zeros();
            for k in 0..3 {
                let i = self.dofs.vertex(v, k);
                if i != FIXED {
                    d[k] = alpha * dx(i);
                }
            }
            d
        };
        // Edge j's new vector from its end vertices' steps `dj` and `dj1` (each vertex's step
        // is computed once and carried along the walks below).
        let new_edge = |j: usize, dj: Vec3, dj1: Vec3| -> Vec3 {
            let e = x[j + 1] - x[j];
            let de = dj1 - dj;
            let len = e.norm();
            let inv_len = 1.0 / len;
            let t = e * inv_len;
            let along = t.dot(&de);
            let across = de - t * along;
            let across_len = across.norm();
            let turn = across_len * inv_len;
            let dir = if turn > 0.0 {
                let axis = t.cross(&across) * (1.0 / across_len);
                crate::geometry::rotate_about_axis(&t, &axis, turn)
            } else {
                t
            };
            dir * (len + along)
        };
        let n = self.n_edges();
        let p = &mut out.positions;
        p.clone_from(x);
        let fixed = &self.anchors;
        if fixed.is_empty() {
            for (v, pv) in p.iter_mut().enumerate() {
                *pv += disp(v);
            }
        } else {
            for &a in fixed {
                p[a] += disp(a);
            }
            let first = fixed[0];
            let last = fixed[fixed.len() - 1];
            // Free tail before the first support: walk backward.
            let mut d_hi = disp(first);
            for j in (0..first).rev() {
                let d_lo = disp(j);
                p[j] = p[j + 1] - new_edge(j, d_lo, d_hi);
                d_hi = d_lo;
            }
            // Free tail after the last support: walk forward.
            let mut d_lo = disp(last);
            for j in last..n {
                let d_hi = disp(j + 1);
                p[j + 1] = p[j] + new_edge(j, d_lo, d_hi);
                d_lo = d_hi;
            }
            // Segments between supports: blend the two walks.
            for w in fixed.windows(2) {
                let (a, b) = (w[0], w[1]);
                if b <= a + 1 {
                    continue;
                }
                // The forward walk is written into p. The backward walk from b is the same
                // walk shifted by its closure gap p_b − (p_a + Σ e), so the blend adds the gap
                // in proportion to the arc length from a (each edge is computed once).
                let mut forward = p[a];
                let mut d_lo = disp(a);
                for j in a..b - 1 {
                    let d_hi = disp(j + 1);
                    forward += new_edge(j, d_lo, d_hi);
                    p[j + 1] = forward;
                    d_lo = d_hi;
                }
                let gap = p[b] - (forward + new_edge(b - 1, d_lo, disp(b)));
                let s_total: f64 = self.rest_lengths[a..b].iter().sum();
                let mut s_from_b = 0.0;
                for j in (a + 1..b).rev() {
                    s_from_b += self.rest_lengths[j];
                    let wb = 1.0 - s_from_b / s_total;
                    p[j] += gap * wb;
                }
            }
        }
        state
            .frames
            .transport_into(&out.positions, &self.hinge_edges, &mut out.frames);
        self.update_load_angles(state, out);
    }

    /// The largest edge-angle rotation (rad) that `alpha·dx` would cause, for the step cap.
    pub(super) fn max_edge_rotation(&self, s: &RodState, dx: impl Fn(usize) -> f64) -> (f64, f64) {
        let n = self.n_edges();
        let disp = |v: usize| -> Vec3 {
            let mut d = Vec3::zeros();
            for k in 0..3 {
                let i = self.dofs.vertex(v, k);
                if i != FIXED {
                    d[k] = dx(i);
                }
            }
            d
        };
        // The largest turn and the largest relative change are found without a square root
        // or a division per edge, from squared lengths; both are taken once, for the winners.
        // A turn θ ∈ [0, π] with sin θ ∝ |e × (e + de)| = s and cos θ ∝ e·(e + de) = c is
        // larger when cot θ·|cot θ| = c|c|/s² is smaller, compared cross-multiplied.
        let (mut best_s2, mut best_c) = (0.0_f64, 1.0_f64);
        let mut best_reversed = false;
        let (mut best_de2, mut best_e2) = (0.0_f64, 1.0_f64);
        let mut d_lo = disp(0);
        for j in 0..n {
            let e = s.positions[j + 1] - s.positions[j];
            let d_hi = disp(j + 1);
            let de = d_hi - d_lo;
            d_lo = d_hi;
            let new = e + de;
            let (s2, c) = (e.cross(&new).norm_squared(), e.dot(&new));
            // A reversed edge (sin = 0, cos < 0) is the largest turn, π.
            if !best_reversed {
                if s2 == 0.0 && c < 0.0 {
                    (best_s2, best_c, best_reversed) = (s2, c, true);
                } else if c * c.abs() * best_s2 < best_c * best_c.abs() * s2 {
                    (best_s2, best_c) = (s2, c);
                }
            }
            let (de2, e2) = (de.norm_squared(), e.norm_squared());
            if de2 * best_e2 > best_de2 * e2 {
                (best_de2, best_e2) = (de2, e2);
            }
        }
        let max_stretch = best_de2.sqrt() / best_e2.sqrt();
        (best_s2.sqrt().atan2(best_c), max_stretch)
    }
}
