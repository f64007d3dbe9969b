//! What the load factor λ drives on a rod: the loads' scale and the rigid motion of supports.
//!
//! The fixed DOFs of a rod live in its state (positions of held vertices, clamp frames), so a
//! support moving with λ is a change of the state that the solver asks for before each step
//! ([`EquilibriumProblem::impose_load`](crate::solver::EquilibriumProblem::impose_load)): the
//! support's vertices move exactly, a clamp's ghost edge turns with it, and, as a first guess
//! when no secant predictor exists yet, the free vertices move by a blend of the same rigid
//! motion (weight 1 next to the moving support, 0 next to a support that stays, linear in arc
//! length between them). Continuation then gives support motion the same adaptive steps and
//! predictor as a gravity ramp: there is one step controller for both.

use nalgebra::Rotation3;

use crate::error::ModelError;
use crate::geometry::Vec3;

use super::model::Rod;
use super::state::RodState;

/// A rigid motion of one support over the load path: at load factor λ ∈ [0, 1] a point x₀ of
/// the support is at `pivot + λ·translation + exp(λ·rotation)·(x₀ − pivot)`, x₀ being its
/// position at λ = 0.
#[derive(Clone, Debug, PartialEq)]
pub struct SupportMotion {
    /// The support's held vertices (one for a clamp or pin, two for a clip).
    pub vertices: Vec<usize>,
    /// Centre of the rotation at λ = 0 (m), usually the support's vertex.
    pub pivot: Vec3,
    /// Rotation vector (rad) at λ = 1: axis × angle.
    pub rotation: Vec3,
    /// Translation (m) at λ = 1.
    pub translation: Vec3,
}

impl SupportMotion {
    /// Where a point at `x` at load factor `from` is at `to`, for a fraction `w` ∈ [0, 1] of
    /// the motion (1 for the support itself, less for the blended guess of free vertices).
    pub(crate) fn carry(&self, x: &Vec3, from: f64, to: f64, w: f64) -> Vec3 {
        let centre = self.pivot + self.translation * from;
        let d = (to - from) * w;
        centre + self.translation * d + Rotation3::new(self.rotation * d) * (x - centre)
    }

    fn check(&self, rod: &Rod) -> Result<(), ModelError> {
        for &v in &self.vertices {
            if !rod.fixed_vertices.contains(&v) {
                return Err(ModelError::structure(
                    "support_motion.vertices",
                    format!("vertex {v} is not held by a support; only supports can be moved"),
                ));
            }
        }
        let finite = self
            .pivot
            .iter()
            .chain(self.rotation.iter())
            .chain(self.translation.iter())
            .all(|c| c.is_finite());
        if !finite {
            return Err(ModelError::structure(
                "support_motion",
                "pivot, rotation and translation must be finite",
            ));
        }
        Ok(())
    }
}

/// What the load factor λ of a [`Rod`] drives.
#[derive(Clone, Debug, PartialEq)]
pub struct RodLoadPath {
    /// Factor on the loads (gravity, point forces and moments) at λ = 0 and at λ = 1, linear
    /// in between. Default [0, 1]: λ ramps the loads.
    pub loads: [f64; 2],
    /// Supports moved rigidly as λ goes from 0 to 1. Default none.
    pub motions: Vec<SupportMotion>,
    /// Gravity (m/s²) at λ = 0 when gravity changes along the path to the rod's own at λ = 1
    /// (e.g. an interactive edit). Default none.
    pub gravity_from: Option<Vec3>,
    /// A dead point force changing along the path (an interactive edit): (vertex, its force
    /// at λ = 0 minus its force at λ = 1 (N)). The vertex carries that difference times
    /// (1 − λ) on top of its loads at λ = 1. Default none.
    pub force_change: Option<(usize, Vec3)>,
    /// A follower force changing along the path (an interactive edit): (index of the rod's
    /// follower load, its force at λ = 0 minus its force at λ = 1, both given at rest (N)).
    /// The vertex carries that difference, turned with the rod, times (1 − λ) on top of the
    /// follower's force (see `follower.rs`). Default none.
    pub follower_change: Option<(usize, Vec3)>,
    /// A follower moment changing along the path (an interactive edit): (index of the rod's
    /// follower load, its moment at λ = 0 minus at λ = 1, both given at rest (N m)). The edge
    /// carries that difference, turned with the rod, times (1 − λ) on top of the follower's
    /// moment. Default none.
    pub follower_moment_change: Option<(usize, Vec3)>,
    /// A dead point moment changing along the path (an interactive edit): the index of the
    /// changed moment in the model's moment list, which then holds the new moment at that
    /// index, weighted λ, and the old one appended last, weighted 1 − λ (see
    /// `moment_change.rs`). Default none.
    pub moment_change: Option<usize>,
}

impl Default for RodLoadPath {
    fn default() -> Self {
        Self {
            loads: [0.0, 1.0],
            motions: Vec::new(),
            gravity_from: None,
            force_change: None,
            follower_change: None,
            follower_moment_change: None,
            moment_change: None,
        }
    }
}

impl RodLoadPath {
    /// Makes this path full loads with the one support motion given, in place: the vectors of
    /// the path are reused, so that an interactive drag, which sets a motion per edit,
    /// allocates nothing here. Not checked against a model.
    pub fn set_single_motion(
        &mut self,
        vertices: &[usize],
        pivot: Vec3,
        rotation: Vec3,
        translation: Vec3,
    ) {
        self.loads = [1.0, 1.0];
        self.gravity_from = None;
        self.force_change = None;
        self.follower_change = None;
        self.follower_moment_change = None;
        self.moment_change = None;
        self.motions.truncate(1);
        if self.motions.is_empty() {
            self.motions.push(SupportMotion {
                vertices: Vec::new(),
                pivot,
                rotation,
                translation,
            });
        }
        let m = &mut self.motions[0];
        m.vertices.clear();
        m.vertices.extend_from_slice(vertices);
        m.pivot = pivot;
        m.rotation = rotation;
        m.translation = translation;
    }

    /// Back to the plain load ramp, in place (the vectors kept for reuse: a motion that holds
    /// no vertex moves nothing).
    pub fn clear(&mut self) {
        self.loads = Self::default().loads;
        self.gravity_from = None;
        self.force_change = None;
        self.follower_change = None;
        self.follower_moment_change = None;
        self.moment_change = None;
        for m in self.motions.iter_mut() {
            m.vertices.clear();
            m.rotation = Vec3::zeros();
            m.translation = Vec3::zeros();
        }
    }

    /// Full loads, the supports moved by `motions` as λ goes from 0 to 1.
    pub fn support_motion(motions: Vec<SupportMotion>) -> Self {
        Self {
            loads: [1.0, 1.0],
            motions,
            gravity_from: None,
            force_change: None,
            follower_change: None,
            follower_moment_change: None,
            moment_change: None,
        }
    }

    /// Full loads, gravity changing from `from` (m/s²) to the rod's own.
    pub fn gravity_change(from: Vec3) -> Self {
        Self {
            loads: [1.0, 1.0],
            motions: Vec::new(),
            gravity_from: Some(from),
            force_change: None,
            follower_change: None,
            follower_moment_change: None,
            moment_change: None,
        }
    }

    /// Makes this path full loads with the dead point force on `vertex` changing from `from`
    /// to `to` (N), in place (the vectors kept for reuse). Not checked against a model.
    pub fn set_force_change(&mut self, vertex: usize, from: Vec3, to: Vec3) {
        self.clear();
        self.loads = [1.0, 1.0];
        self.force_change = Some((vertex, from - to));
    }

    /// The extra dead force (N) on vertex `v` at load factor `load` while gravity (vertex mass
    /// `mass`, the rod's gravity `g` at λ = 1) or a point force changes along the path: zero
    /// at λ = 1.
    pub(crate) fn transition_force(&self, v: usize, mass: f64, g: Vec3, load: f64) -> Vec3 {
        let mut f = match self.gravity_from {
            Some(g0) => (g0 - g) * (mass * (1.0 - load)),
            None => Vec3::zeros(),
        };
        if let Some((vertex, delta)) = self.force_change {
            if vertex == v {
                f += delta * (1.0 - load);
            }
        }
        f
    }

    /// Makes this path the change of the dead point force on vertex `v` from `old` to `new`
    /// (N) and moves that vertex's entry of `nodal_forces` (the forces at λ = 1) to `new`.
    /// Returns the entry before the change (to undo it exactly). Errors (the path cleared,
    /// the forces unchanged) if `v` is not a vertex or a force is not finite.
    pub(crate) fn change_force(
        &mut self,
        nodal_forces: &mut [Vec3],
        v: usize,
        old: Vec3,
        new: Vec3,
    ) -> Result<Vec3, ModelError> {
        self.set_force_change(v, old, new);
        if let Err(e) = self.check_changes(nodal_forces.len()) {
            self.clear();
            return Err(e);
        }
        let before = nodal_forces[v];
        nodal_forces[v] += new - old;
        Ok(before)
    }

    /// Errors if the gravity or force change is not finite or names a vertex beyond
    /// `n_vertices`.
    pub(crate) fn check_changes(&self, n_vertices: usize) -> Result<(), ModelError> {
        if self
            .gravity_from
            .is_some_and(|g| g.iter().any(|c| !c.is_finite()))
        {
            return Err(ModelError::structure("gravity_from", "must be finite"));
        }
        if let Some((v, delta)) = self.force_change {
            if v >= n_vertices {
                return Err(ModelError::structure(
                    "force_change.vertex",
                    format!("vertex {v} is beyond the rod's {n_vertices} vertices"),
                ));
            }
            if delta.iter().any(|c| !c.is_finite()) {
                return Err(ModelError::structure("force_change", "must be finite"));
            }
        }
        Ok(())
    }

    /// Errors if the follower change names a follower beyond the model's `n_followers` (none
    /// for the rod models without follower loads) or is not finite.
    pub(crate) fn check_follower_change(&self, n_followers: usize) -> Result<(), ModelError> {
        for (field, change) in [
            ("follower_change", self.follower_change),
            ("follower_moment_change", self.follower_moment_change),
        ] {
            if let Some((i, delta)) = change {
                if i >= n_followers {
                    return Err(ModelError::structure(
                        field,
                        format!("follower load {i} does not exist (the rod has {n_followers})"),
                    ));
                }
                if delta.iter().any(|c| !c.is_finite()) {
                    return Err(ModelError::structure(field, "must be finite"));
                }
            }
        }
        Ok(())
    }

    /// Errors if the path carries a moment change: only the model's `set_moment_change`
    /// makes one, since it also appends the old moment the path weights.
    pub(crate) fn check_moment_change(&self) -> Result<(), ModelError> {
        if let Some(i) = self.moment_change {
            return Err(ModelError::structure(
                "moment_change",
                format!(
                    "moment {i}: a moment change is made by set_moment_change, not set in a path"
                ),
            ));
        }
        Ok(())
    }

    /// Makes this path the change of moment `i` of `moments` (any model's moment loads) to
    /// `after`, in place: full loads, `after` at `i` (weighted λ), the old value appended last
    /// (weighted 1 − λ), and `angles` (the state's per-moment angles) likewise: `after_angle`
    /// at `i`, the old angle appended. A change still pending is ended first.
    pub(crate) fn begin_moment_change<T, A: Copy>(
        &mut self,
        moments: &mut Vec<T>,
        angles: &mut Vec<A>,
        i: usize,
        after: T,
        after_angle: A,
    ) {
        self.end_moment_change(moments);
        self.clear();
        self.loads = [1.0, 1.0];
        self.moment_change = Some(i);
        let before = std::mem::replace(&mut moments[i], after);
        moments.push(before);
        let before_angle = std::mem::replace(&mut angles[i], after_angle);
        angles.push(before_angle);
    }

    /// Ends a moment change with the new moment: the old one, appended last, dropped from
    /// `moments` (a state's extra angle is then ignored and dropped by its next update). Every
    /// change of a model's load path calls it first, so a model never keeps a stale old moment
    /// at full weight. Does nothing without a change.
    pub(crate) fn end_moment_change<T>(&mut self, moments: &mut Vec<T>) {
        if self.moment_change.take().is_some() {
            moments.pop();
        }
    }

    /// Undoes a moment change of moment `i`: the old value, appended last, back in its place.
    /// Does nothing without a change.
    pub(crate) fn undo_moment_change<T>(&mut self, moments: &mut Vec<T>, i: usize) {
        if self.moment_change.take().is_some() {
            if let Some(old) = moments.pop() {
                moments[i] = old;
            }
        }
    }

    /// The factor on moment `i` of `n_moments` at path parameter `lambda`, given the factor
    /// `load` on all loads: while moment `k` changes, `load·λ` on it (the new value) and
    /// `load·(1 − λ)` on the last moment (the old value); `load` otherwise.
    pub(crate) fn moment_factor(&self, i: usize, n_moments: usize, load: f64, lambda: f64) -> f64 {
        match self.moment_change {
            Some(k) if k == i => load * lambda,
            Some(_) if i + 1 == n_moments => load * (1.0 - lambda),
            _ => load,
        }
    }

    /// Factor on the loads at load factor `load`.
    pub fn load_factor(&self, load: f64) -> f64 {
        self.loads[0] + load * (self.loads[1] - self.loads[0])
    }
}

/// A rod's dead loads kept before a gravity change, put back bit for bit if the change does
/// not converge (adding −Δg·m back would leave x + Δ − Δ, an ulp off). The buffer is reused:
/// only the first save allocates.
#[derive(Clone, Debug, Default)]
pub struct SavedLoads {
    nodal_forces: Vec<Vec3>,
    gravity: Vec3,
}

impl SavedLoads {
    /// Keeps `nodal_forces` (N) and `gravity` (m/s²).
    pub(crate) fn save(&mut self, nodal_forces: &[Vec3], gravity: Vec3) {
        self.nodal_forces.clear();
        self.nodal_forces.extend_from_slice(nodal_forces);
        self.gravity = gravity;
    }

    /// Writes back what [`Self::save`] kept (the same number of vertices).
    pub(crate) fn restore(&self, nodal_forces: &mut [Vec3], gravity: &mut Vec3) {
        nodal_forces.copy_from_slice(&self.nodal_forces);
        *gravity = self.gravity;
    }
}

impl Rod {
    /// The extra nodal force (N) on vertex `v` at load factor `load` while gravity or a point
    /// force changes along the path (see [`RodLoadPath::transition_force`]); zero at λ = 1.
    pub(super) fn load_transition(&self, v: usize, load: f64) -> Vec3 {
        self.load_path
            .transition_force(v, self.vertex_masses[v], self.gravity, load)
    }

    /// Keeps the dead loads for [`Self::restore_loads`] (before a gravity change).
    pub fn save_loads(&mut self) {
        self.saved_loads.save(&self.nodal_forces, self.gravity);
    }

    /// Puts back the dead loads [`Self::save_loads`] kept, bit for bit, and the plain load
    /// ramp.
    pub fn restore_loads(&mut self) {
        self.saved_loads
            .restore(&mut self.nodal_forces, &mut self.gravity);
        self.clear_load_path();
    }

    /// Sets gravity (m/s²) at load factor 1 (the nodal forces follow).
    pub fn set_gravity(&mut self, g: Vec3) {
        for (f, &m) in self.nodal_forces.iter_mut().zip(&self.vertex_masses) {
            *f += (g - self.gravity) * m;
        }
        self.gravity = g;
    }

    /// What the load factor drives.
    pub fn load_path(&self) -> &RodLoadPath {
        &self.load_path
    }

    /// Sets what the load factor drives. Errors if a motion names a vertex no support holds or
    /// is not finite, or a load factor is not finite.
    pub fn set_load_path(&mut self, path: RodLoadPath) -> Result<(), ModelError> {
        for m in &path.motions {
            m.check(self)?;
        }
        path.check_changes(self.vertex_masses.len())?;
        path.check_follower_change(self.followers.len())?;
        path.check_moment_change()?;
        for (k, f) in path.loads.iter().enumerate() {
            if !f.is_finite() {
                return Err(ModelError::parameter(
                    if k == 0 { "loads[0]" } else { "loads[1]" },
                    *f,
                    "finite",
                ));
            }
        }
        self.end_moment_change();
        self.load_path = path;
        Ok(())
    }

    /// Sets the load path to full loads with one support motion (the vectors of the current
    /// path are reused: an interactive drag allocates nothing here).
    pub fn set_support_motion(
        &mut self,
        vertices: &[usize],
        pivot: Vec3,
        rotation: Vec3,
        translation: Vec3,
    ) -> Result<(), ModelError> {
        self.end_moment_change();
        let mut path = std::mem::take(&mut self.load_path);
        path.set_single_motion(vertices, pivot, rotation, translation);
        let checked = path.motions[0].check(self);
        if checked.is_ok() {
            self.load_path = path;
        } else {
            self.clear_load_path();
        }
        checked
    }

    /// Changes the dead point force on vertex `v` from `old` to `new` (N): at load factor 1 from
    /// now on, along the load path (λ = 0: `old`) for the next solve. Returns the vertex's
    /// nodal force before the change (for [`Self::undo_force_change`]). Errors (nothing
    /// changed) if `v` is not a vertex or a force is not finite.
    pub fn set_force_change(&mut self, v: usize, old: Vec3, new: Vec3) -> Result<Vec3, ModelError> {
        self.end_moment_change();
        self.load_path
            .change_force(&mut self.nodal_forces, v, old, new)
    }

    /// Undoes [`Self::set_force_change`] exactly: vertex `v`'s nodal force back to `before`
    /// (N), the load path cleared.
    pub fn undo_force_change(&mut self, v: usize, before: Vec3) {
        self.nodal_forces[v] = before;
        self.clear_load_path();
    }

    /// Back to the plain load ramp (vectors kept for reuse). A moment change still on the
    /// path ends with the new moment (see [`Self::finish_moment_change`]).
    pub fn clear_load_path(&mut self) {
        self.end_moment_change();
        self.load_path.clear();
    }

    /// A state like `state` with the support moved by the whole of `motion` (λ from 0 to 1),
    /// the free vertices moved by the blended guess. The result is not an equilibrium; solve
    /// from it. Rotations per call should stay well below π so that the reference twists can be
    /// continued.
    pub fn with_support_moved(
        &self,
        state: &RodState,
        motion: &SupportMotion,
    ) -> Result<RodState, ModelError> {
        motion.check(self)?;
        let mut out = state.clone();
        self.move_support(&mut out, motion, 0.0, 1.0, true);
        Ok(out)
    }

    /// Moves the supports of `state` along the load path from `from` to `to` (see
    /// [`EquilibriumProblem::impose_load`](crate::solver::EquilibriumProblem::impose_load)).
    pub(super) fn impose_path(&self, state: &mut RodState, from: f64, to: f64, guess: bool) {
        for m in &self.load_path.motions {
            if !m.vertices.is_empty() {
                self.move_support(state, m, from, to, guess);
            }
        }
    }

    /// Weight of vertex `v` in the blended guess of `motion`: 1 on the moved support, 0 on the
    /// others, interpolated in arc length between consecutive supports and constant past the
    /// outermost ones.
    fn blend_weight(&self, motion: &SupportMotion, v: usize) -> f64 {
        let weight_of = |u: usize| f64::from(u8::from(motion.vertices.contains(&u)));
        let fixed = &self.fixed_vertices;
        let left = fixed.iter().rev().find(|&&f| f <= v).copied();
        let right = fixed.iter().find(|&&f| f >= v).copied();
        let s = &self.arclengths;
        match (left, right) {
            (Some(a), Some(b)) if a == b => weight_of(a),
            (Some(a), Some(b)) => {
                let u = (s[v] - s[a]) / (s[b] - s[a]);
                weight_of(a) * (1.0 - u) + weight_of(b) * u
            }
            (Some(a), None) => weight_of(a),
            (None, Some(b)) => weight_of(b),
            (None, None) => 0.0,
        }
    }

    /// Moves `motion`'s support in `state` from load factor `from` to `to` (and, with `guess`,
    /// the free vertices by the blend), in place: ghost frames turned with their clamp, the
    /// other frames transported to the new tangents, reference twists continued, moment
    /// angles updated. Allocates nothing.
    fn move_support(
        &self,
        state: &mut RodState,
        motion: &SupportMotion,
        from: f64,
        to: f64,
        guess: bool,
    ) {
        let n = self.n_edges();
        let weight = |v: usize| {
            if motion.vertices.contains(&v) {
                1.0
            } else if guess {
                self.blend_weight(motion, v)
            } else {
                0.0
            }
        };
        // Moment loads' unwrapped angles follow their edges' material frames: the frames
        // before the move are kept (inline for up to four moments) to continue from.
        let before: smallvec::SmallVec<[[Vec3; 3]; 4]> = self
            .moments
            .iter()
            .map(|m| state.material_frame(m.edge))
            .collect();
        for v in 0..=n {
            let w = weight(v);
            if w != 0.0 {
                state.positions[v] = motion.carry(&state.positions[v], from, to, w);
            }
        }
        // A clamp's ghost edge turns with its support; the reference twists of the clamp hinges
        // are then continued across the rotation by the transport below.
        let r = Rotation3::new(motion.rotation * (to - from));
        self.turn_clamps(state, &motion.vertices, &r);
        state
            .frames
            .transport_in_place(&state.positions, &self.hinge_edges);
        for (k, m) in self.moments.iter().enumerate() {
            let now = state.material_frame(m.edge);
            state.load_angles[k] = m.updated_angles(&before[k], &now, state.load_angles[k]);
        }
    }
}
