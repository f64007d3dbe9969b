//! Where a rod is held: clamps at its ends, pins, and the optional restriction to a plane;
//! their validation, the fixed vertices and the DOF map they leave.

use crate::error::ModelError;
use crate::geometry::Vec3;

/// Where a rod is held.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Supports {
    /// Clamp at vertex 0: position and material frame fixed (ghost edge, half Voronoi cell).
    pub clamp_start: bool,
    /// Clamp at the last vertex.
    pub clamp_end: bool,
    /// Pinned vertices: position fixed, rotation free.
    pub pins: Vec<usize>,
    /// If `Some(k)`: motion restricted to the plane ⊥ e_k through the rest shape (coordinate k
    /// of every vertex and every twist angle fixed). For following symmetric equilibria of
    /// planar problems; the rest curve must lie in that plane.
    pub planar_axis: Option<usize>,
}

impl Supports {
    /// Checks that every pinned vertex exists on a rod of `n` edges.
    pub(super) fn validate(&self, n: usize) -> Result<(), ModelError> {
        for v in &self.pins {
            if *v > n {
                return Err(ModelError::structure(
                    "pins",
                    format!("vertex {v} does not exist; valid vertices are 0..={n}"),
                ));
            }
        }
        if let Some(k) = self.planar_axis {
            if k > 2 {
                return Err(ModelError::structure(
                    "planar_axis",
                    format!("got {k}; valid axes are 0 (x), 1 (y), 2 (z)"),
                ));
            }
        }
        Ok(())
    }

    /// The supports with sorted, unique pins; errors if they leave a rigid-body motion.
    pub(super) fn normalized(&self, allow_rigid_motion: bool) -> Result<Self, ModelError> {
        let mut pins = self.pins.clone();
        pins.sort_unstable();
        pins.dedup();
        let n_clamps = usize::from(self.clamp_start) + usize::from(self.clamp_end);
        if n_clamps == 0 && pins.len() < 3 && !allow_rigid_motion {
            return Err(ModelError::structure(
                "supports",
                "the rod can move as a rigid body; add a clamp, or pin at least three non-collinear vertices",
            ));
        }
        Ok(Self {
            pins,
            ..self.clone()
        })
    }

    /// Vertices whose positions are fixed (clamped or pinned), sorted, on a rod of `n` edges.
    pub(super) fn fixed_vertices(&self, n: usize) -> Vec<usize> {
        let mut fixed = self.pins.clone();
        if self.clamp_start {
            fixed.push(0);
        }
        if self.clamp_end {
            fixed.push(n);
        }
        fixed.sort_unstable();
        fixed.dedup();
        fixed
    }

    /// Errors if a planar restriction is asked for a rest shape out of that plane (`total`:
    /// the rod length, the scale of the tolerance).
    pub(super) fn check_plane(&self, positions: &[Vec3], total: f64) -> Result<(), ModelError> {
        if let Some(k) = self.planar_axis {
            let c0 = positions[0][k];
            if positions.iter().any(|p| (p[k] - c0).abs() > 1e-12 * total) {
                return Err(ModelError::structure(
                    "planar_axis",
                    "the rest curve does not lie in the plane of motion",
                ));
            }
        }
        Ok(())
    }
}
