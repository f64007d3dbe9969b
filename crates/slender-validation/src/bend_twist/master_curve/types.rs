//! The results of the master curve (stability boundaries, branch events, planar equilibria)
//! and its numerical settings.

/// The stability boundaries of the planar equilibrium at one `Y`.
///
/// The planar equilibrium is unstable (the rod buckles out of plane: "3-D") exactly for
/// `lower < X < upper`, and stable ("2-D") for all `X` when both are `None` (`Y < Y*`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StabilityBoundary {
    /// `Y = L/(2πR)` (dimensionless).
    pub y: f64,
    /// `X_c1 = (R/L)Γ^{1/3}` where the coil, loaded from `Γ = 0`, loses stability
    /// (dimensionless).
    pub lower: Option<f64>,
    /// `X_c2`, above which the hanging curl is stable again (dimensionless).
    pub upper: Option<f64>,
}

impl StabilityBoundary {
    /// True if the planar equilibrium at `x` is stable (outside the open window
    /// `(lower, upper)`).
    pub fn planar_stable(&self, x: f64) -> bool {
        match (self.lower, self.upper) {
            (Some(l), Some(u)) => !(x > l && x < u),
            _ => true,
        }
    }
}

/// Numerical settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// Relative tolerance of every ODE integration (dimensionless; the absolute tolerance is
    /// `1e-6·rtol` in the scaled units). Default `1e-10`; the boundaries then move by < 1e-8
    /// relative when it is halved. Must be in `[1e-13, 1e-6]`.
    pub rtol: f64,
}

impl Default for Settings {
    fn default() -> Self {
        Self { rtol: 1e-10 }
    }
}

/// Kind of a change of stability along the planar branch.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EventKind {
    /// An out-of-plane eigenvalue crosses zero (`f = 0`): a bifurcation to 3-D shapes.
    OutOfPlane,
    /// An in-plane eigenvalue crosses zero: a fold of the planar branch in `X` (snap).
    InPlaneFold,
}

/// A point of the planar branch where an eigenvalue of the second variation crosses zero.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BranchEvent {
    /// `X` at the event (dimensionless).
    pub x: f64,
    /// What crosses zero.
    pub kind: EventKind,
    /// `(in-plane, out-of-plane)` number of unstable modes just before the event (along the
    /// branch, coming from `X → 0`).
    pub index_before: (u32, u32),
    /// The same just after the event.
    pub index_after: (u32, u32),
}

/// The planar branch at one `Y`, traced from the stress-free coil to a given `X`.
#[derive(Clone, Debug, PartialEq)]
pub struct PlanarBranch {
    /// `Y` (dimensionless).
    pub y: f64,
    /// `c = GJ/EI`.
    pub c: f64,
    /// Every change of stability, in order along the branch.
    pub events: Vec<BranchEvent>,
    /// Number of continuation points.
    pub points: usize,
    /// `(in-plane, out-of-plane)` index at the last point.
    pub final_index: (u32, u32),
}

impl PlanarBranch {
    /// Number of separate stretches of the branch on which the planar state is stable.
    pub fn stable_stretches(&self) -> usize {
        let mut stable = true;
        let mut count = 1;
        for e in &self.events {
            let now = e.index_after == (0, 0);
            if now && !stable {
                count += 1;
            }
            stable = now;
        }
        count
    }
}

/// A planar equilibrium (on the branch continued from the stress-free coil).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlanarEquilibrium {
    /// `X` (dimensionless).
    pub x: f64,
    /// `Y` (dimensionless).
    pub y: f64,
    /// `Γ = (2πXY)³`.
    pub gamma: f64,
    /// Clamp curvature `θ'(0)` in units of `1/L` (may underflow to 0 for the hanging rod).
    pub clamp_curvature: f64,
    /// `ln θ'(0)`, finite even where `θ'(0)` underflows.
    pub ln_clamp_curvature: f64,
    /// Clamp bending moment `m_y(0) = 2πY − θ'(0)` in units of `EI/L`.
    pub clamp_moment: f64,
    /// Tip angle `θ(1)` (rad) from the downward vertical.
    pub tip_angle: f64,
    /// Normalized stability function `f̂` (sign of `f = δm_x(1)`).
    pub stability_function: f64,
    /// `(in-plane, out-of-plane)` number of unstable modes.
    pub index: (u32, u32),
}
