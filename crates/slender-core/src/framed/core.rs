//! What a discrete Cosserat rod and an SE(3) beam share besides their elastic terms: the DOF
//! map, supports, masses, loads, the rest state and what the load factor drives.

use nalgebra::UnitQuaternion;

use crate::error::ModelError;
use crate::geometry::Vec3;
use crate::rod::{RodLoadPath, RodProperties, SavedLoads, Supports};

use super::builder::{FramedRodBuilder, RestGeometry};
use super::layout::FramedDofs;
use super::moment::FrameMoment;
use super::section::ShearStiffness;
use super::state::FramedState;

/// The non-elastic part of a rod with material frames.
#[derive(Clone, Debug)]
pub struct FramedCore {
    pub(crate) properties: RodProperties,
    pub(crate) shear: ShearStiffness,
    /// Length of the rest polygon (m).
    pub(crate) length: f64,
    /// Rest element lengths (m).
    pub(crate) rest_lengths: Vec<f64>,
    /// Arc length (m) of every vertex along the rest polygon.
    pub(crate) arclengths: Vec<f64>,
    /// Arc length (m) where each frame sits (edge midpoint or node).
    pub(crate) frame_arclengths: Vec<f64>,
    /// Length (m) of rod each frame stands for (its rotational inertia).
    pub(crate) frame_lengths: Vec<f64>,
    pub(crate) dofs: FramedDofs,
    pub(crate) supports: Supports,
    /// Vertices whose positions are held, sorted.
    pub(crate) fixed_vertices: Vec<usize>,
    /// Frame slots whose rotations are held (clamped nodes of an SE(3) beam).
    pub(crate) fixed_frames: Vec<usize>,
    pub(crate) vertex_masses: Vec<f64>,
    /// Dead nodal forces (N) at load factor 1: gravity plus point forces.
    pub(crate) nodal_forces: Vec<Vec3>,
    /// Dead nodal forces (N) on at every load factor (preload gravity).
    pub(crate) preload_forces: Vec<Vec3>,
    pub(crate) moments: Vec<FrameMoment>,
    /// The frame slot a point moment on a vertex acts on (the layout's map), for edits.
    pub(crate) moment_slot: fn(vertex: usize, n_elements: usize) -> usize,
    pub(crate) gravity: Vec3,
    pub(crate) rest: FramedState,
    pub(crate) load_path: RodLoadPath,
    /// The dead loads before a gravity change (see `FramedCore::save_loads`).
    pub(crate) saved_loads: SavedLoads,
}

/// Where a model keeps its frames.
pub(crate) struct FrameLayout {
    /// Rest frames of the frame slots.
    pub frames: Vec<UnitQuaternion<f64>>,
    /// Frames held by clamps outside the slots (Cosserat), per end.
    pub clamp_frames: [Option<UnitQuaternion<f64>>; 2],
    /// Slots whose rotations clamps hold (SE(3) beam), sorted.
    pub fixed_frames: Vec<usize>,
    /// Arc length of each slot.
    pub frame_arclengths: Vec<f64>,
    /// Length of rod each slot stands for.
    pub frame_lengths: Vec<f64>,
    /// The slot a point moment at a vertex acts on.
    pub moment_slot: fn(vertex: usize, n_elements: usize) -> usize,
    /// Length (m) of each element whose mass is lumped on its two vertices: the chord for a
    /// rod whose centerline is the polygon, the arc for one whose centerline is curved.
    pub mass_lengths: Vec<f64>,
}

impl FramedCore {
    /// Assembles the shared part from validated input.
    pub(crate) fn new<K>(
        b: &FramedRodBuilder<K>,
        geom: &RestGeometry,
        layout: FrameLayout,
    ) -> Result<Self, ModelError> {
        let n = geom.rest_lengths.len();
        let dofs = FramedDofs::new(
            n + 1,
            layout.frames.len(),
            &geom.fixed_vertices,
            &layout.fixed_frames,
            b.supports.planar_axis,
        );
        let moments: Vec<FrameMoment> = b
            .point_moments
            .iter()
            .map(|pm| {
                let slot = (layout.moment_slot)(pm.vertex, n);
                FrameMoment::new(slot, pm.moment, layout.frames[slot])
            })
            .collect();
        let rest = FramedState {
            positions: geom.positions.clone(),
            frames: layout.frames,
            clamp_frames: layout.clamp_frames,
            moment_angles: vec![[0.0; 2]; moments.len()],
        };
        let rho_a = b.properties.linear_density;
        let mut vertex_masses = vec![0.0; n + 1];
        for (j, &l) in layout.mass_lengths.iter().enumerate() {
            vertex_masses[j] += 0.5 * rho_a * l;
            vertex_masses[j + 1] += 0.5 * rho_a * l;
        }
        let mut nodal_forces: Vec<Vec3> = vertex_masses.iter().map(|&m| b.gravity * m).collect();
        for pf in &b.point_forces {
            nodal_forces[pf.vertex] += pf.force;
        }
        let preload_forces = vertex_masses
            .iter()
            .map(|&m| b.preload_gravity * m)
            .collect();
        Ok(Self {
            properties: b.properties,
            shear: b.shear,
            length: geom.length,
            rest_lengths: geom.rest_lengths.clone(),
            arclengths: geom.arclengths.clone(),
            frame_arclengths: layout.frame_arclengths,
            frame_lengths: layout.frame_lengths,
            dofs,
            supports: Supports {
                pins: geom.pins.clone(),
                ..b.supports.clone()
            },
            fixed_vertices: geom.fixed_vertices.clone(),
            fixed_frames: layout.fixed_frames,
            vertex_masses,
            nodal_forces,
            preload_forces,
            moments,
            moment_slot: layout.moment_slot,
            gravity: b.gravity,
            rest,
            load_path: RodLoadPath::default(),
            saved_loads: SavedLoads::default(),
        })
    }

    /// Number of elements (edges).
    pub fn n_edges(&self) -> usize {
        self.rest_lengths.len()
    }

    /// Length of the rest centerline polygon (m).
    pub fn length(&self) -> f64 {
        self.length
    }

    /// Section properties.
    pub fn properties(&self) -> &RodProperties {
        &self.properties
    }

    /// Shear stiffnesses.
    pub fn shear(&self) -> &ShearStiffness {
        &self.shear
    }

    /// Rest element lengths (m).
    pub fn rest_lengths(&self) -> &[f64] {
        &self.rest_lengths
    }

    /// Supports.
    pub fn supports(&self) -> &Supports {
        &self.supports
    }

    /// Gravitational acceleration (m/s²) at load factor 1.
    pub fn gravity(&self) -> Vec3 {
        self.gravity
    }

    /// The DOF map.
    pub fn dofs(&self) -> &FramedDofs {
        &self.dofs
    }

    /// The stress-free state (also the default initial state).
    pub fn rest_state(&self) -> &FramedState {
        &self.rest
    }

    /// Lumped vertex masses (kg).
    pub fn vertex_masses(&self) -> &[f64] {
        &self.vertex_masses
    }

    /// Vertices whose positions supports hold, sorted.
    pub fn fixed_vertices(&self) -> &[usize] {
        &self.fixed_vertices
    }

    /// Values of the free DOFs relative to the rest state: displacements (m) and rotation
    /// vectors from rest (rad, principal values), into `out`.
    pub fn displacement_from_rest(&self, s: &FramedState, out: &mut [f64]) {
        self.difference(s, &self.rest, out);
    }

    /// A state of this rod from positions (m) and frame quaternions, e.g. an initial guess.
    /// The quaternions must have unit norm (to 1e-10; they are not silently normalized), the
    /// counts must match the rod's, the supported vertices and clamped frames must be at their
    /// rest values. Moment-load angles are continued from rest along the shortest rotation.
    pub fn state_from(
        &self,
        positions: Vec<Vec3>,
        frames: Vec<nalgebra::Quaternion<f64>>,
    ) -> Result<FramedState, ModelError> {
        if positions.len() != self.rest.positions.len() {
            return Err(ModelError::structure(
                "positions",
                format!(
                    "got {} positions; the rod has {} vertices",
                    positions.len(),
                    self.rest.positions.len()
                ),
            ));
        }
        if frames.len() != self.rest.frames.len() {
            return Err(ModelError::structure(
                "frames",
                format!(
                    "got {} frames; the rod has {}",
                    frames.len(),
                    self.rest.frames.len()
                ),
            ));
        }
        if positions.iter().any(|p| p.iter().any(|c| !c.is_finite())) {
            return Err(ModelError::structure("positions", "must be finite"));
        }
        let mut units = Vec::with_capacity(frames.len());
        for (j, q) in frames.iter().enumerate() {
            let norm = q.norm();
            if !(norm.is_finite() && (norm - 1.0).abs() <= 1e-10) {
                return Err(ModelError::structure(
                    "frames",
                    format!("quaternion {j} has norm {norm}; frames must be unit quaternions (|q| = 1 to 1e-10)"),
                ));
            }
            units.push(UnitQuaternion::new_unchecked(*q));
        }
        let scale = self.length;
        for &v in &self.fixed_vertices {
            if (positions[v] - self.rest.positions[v]).norm() > 1e-12 * scale {
                return Err(ModelError::structure(
                    "positions",
                    format!("vertex {v} is held by a support and must stay at its rest position"),
                ));
            }
        }
        for &j in &self.fixed_frames {
            if units[j].angle_to(&self.rest.frames[j]) > 1e-10 {
                return Err(ModelError::structure(
                    "frames",
                    format!("frame {j} is held by a clamp and must keep its rest orientation"),
                ));
            }
        }
        for w in positions.windows(2) {
            if !((w[1] - w[0]).norm() > 1e-12 * scale) {
                return Err(ModelError::structure(
                    "positions",
                    "consecutive vertices coincide (degenerate element)",
                ));
            }
        }
        let mut state = FramedState {
            positions,
            frames: units,
            clamp_frames: self.rest.clamp_frames,
            moment_angles: Vec::new(),
        };
        state.moment_angles = self
            .moments
            .iter()
            .map(|m| m.updated_angles(&m.rest, &state.frames[m.frame], [0.0; 2]))
            .collect();
        Ok(state)
    }

    /// A state with the given positions (m), frames and clamp frames taken as they are (no
    /// check that supports are at rest: a carried equilibrium has its supports where they were
    /// moved), moment-load angles continued from rest along the shortest rotation.
    pub(crate) fn carried_state(
        &self,
        positions: Vec<Vec3>,
        frames: Vec<UnitQuaternion<f64>>,
        clamp_frames: [Option<UnitQuaternion<f64>>; 2],
    ) -> FramedState {
        let mut state = FramedState {
            positions,
            frames,
            clamp_frames,
            moment_angles: Vec::new(),
        };
        state.moment_angles = self
            .moments
            .iter()
            .map(|m| m.updated_angles(&m.rest, &state.frames[m.frame], [0.0; 2]))
            .collect();
        state
    }

    /// What the load factor drives.
    pub fn load_path(&self) -> &RodLoadPath {
        &self.load_path
    }

    /// Sets what the load factor drives. Errors if a motion names a vertex no support holds or
    /// is not finite, or a load factor is not finite.
    pub fn set_load_path(&mut self, path: RodLoadPath) -> Result<(), ModelError> {
        for m in &path.motions {
            for &v in &m.vertices {
                if !self.fixed_vertices.contains(&v) {
                    return Err(ModelError::structure(
                        "support_motion.vertices",
                        format!("vertex {v} is not held by a support; only supports can be moved"),
                    ));
                }
            }
            let finite = m
                .pivot
                .iter()
                .chain(m.rotation.iter())
                .chain(m.translation.iter())
                .all(|c| c.is_finite());
            if !finite {
                return Err(ModelError::structure(
                    "support_motion",
                    "pivot, rotation and translation must be finite",
                ));
            }
        }
        path.check_changes(self.vertex_masses.len())?;
        // Follower loads act on discrete elastic rods only.
        path.check_follower_change(0)?;
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

    /// The dead nodal force (N) on vertex `v` at load factor `load`: the ramped loads, the
    /// preload, and, while gravity or a point force changes along the load path, the
    /// transition (see `RodLoadPath::transition_force`).
    pub(crate) fn nodal_force(&self, v: usize, load: f64) -> Vec3 {
        let factor = self.load_path.load_factor(load);
        let mut f = self.nodal_forces[v] * factor + self.preload_forces[v];
        let path = &self.load_path;
        if path.gravity_from.is_some() || path.force_change.is_some() {
            f += path.transition_force(v, self.vertex_masses[v], self.gravity, load);
        }
        f
    }

    /// Changes the dead point force on vertex `v` from `old` to `new` (N), as
    /// `Rod::set_force_change` does (returns the nodal force before the change).
    pub fn set_force_change(&mut self, v: usize, old: Vec3, new: Vec3) -> Result<Vec3, ModelError> {
        self.end_moment_change();
        self.load_path
            .change_force(&mut self.nodal_forces, v, old, new)
    }

    /// Undoes `set_force_change` exactly: vertex `v`'s nodal force back to `before` (N), the
    /// load path cleared.
    pub fn undo_force_change(&mut self, v: usize, before: Vec3) {
        self.nodal_forces[v] = before;
        self.clear_load_path();
    }

    /// Inertia attached to free DOF `i`: the vertex mass for a coordinate, ρA r_g² ℓ for a
    /// rotation component of a frame standing for a length ℓ (r_g² = (EI₁+EI₂)/EA).
    pub(crate) fn inertia_metric(&self, i: usize) -> f64 {
        match self.dofs.slot(i) {
            super::layout::DofSlot::Position { v, .. } => self.vertex_masses[v],
            super::layout::DofSlot::Rotation { j, .. } => {
                self.properties.linear_density
                    * self.properties.stiffness.gyration_radius_sq()
                    * self.frame_lengths[j]
            }
        }
    }

    /// EI_min/(ρA L⁴) (1/s²).
    pub(crate) fn eigenvalue_scale(&self) -> f64 {
        self.properties.stiffness.ei_min() / (self.properties.linear_density * self.length.powi(4))
    }

    /// 1 for coordinates, L for rotations (whose generalized forces are moments).
    pub(crate) fn force_length(&self, i: usize) -> f64 {
        if self.dofs.is_rotation(i) {
            self.length
        } else {
            1.0
        }
    }

    /// Typical magnitude of DOF `i` (m or rad).
    pub(crate) fn dof_magnitude(&self, s: &FramedState, i: usize) -> f64 {
        match self.dofs.slot(i) {
            super::layout::DofSlot::Position { v, .. } => s.positions[v].amax().max(self.length),
            super::layout::DofSlot::Rotation { .. } => std::f64::consts::PI,
        }
    }
}
