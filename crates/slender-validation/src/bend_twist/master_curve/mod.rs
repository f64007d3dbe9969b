//! Master curve of the bend–twist benchmark: the stability boundaries of the planar
//! equilibrium of a heavy, naturally curved Kirchhoff rod, computed independently of any rod
//! discretization (design.md §1.2, seed §4).
//!
//! # Problem
//!
//! An inextensible, unshearable rod of length `L`, isotropic bending stiffness `EI`, twisting
//! stiffness `GJ = c·EI` and weight `ρAg` per length has a stress-free shape that is a circle
//! of radius `R` (possibly more than one turn). It is clamped at `s = 0` with its tangent along
//! gravity (`−e_z`) and its curvature plane `xz`; the other end is free. Lengths are scaled by
//! `L` (`S = s/L`), moments by `EI/L`, forces by `EI/L²`. The two benchmark parameters are
//!
//! ```text
//! X = (R/L) Γ^{1/3},   Y = L/(2πR),   so   Γ = ρAgL³/EI = (2πXY)³,   L/R = 2πY.
//! ```
//!
//! With a free end the internal force is known in every configuration,
//! `n(S) = Γ(1 − S) ĝ` (force of the lower part on the upper part, `ĝ = −e_z`).
//!
//! # Where each part lives (files of this folder)
//!
//! * `planar.rs`: the planar equilibrium `θ'' = Γ(1 − S) sin θ`, solved by single shooting in
//!   Prüfer form.
//! * `out_of_plane.rs`: the linearized out-of-plane system and its stability function
//!   `f = δm_x(1)`, zero where the planar state is critical.
//! * `morse_index.rs`: the number of unstable modes (Maslov angle out of plane, Prüfer count
//!   in plane).
//! * `general.rs`: the general 6-D linearization ([`general_free_end_moments`]), a check of the
//!   reduced system.
//! * `continuation.rs`: pseudo-arclength continuation of the planar branch and the refinement
//!   of its events (root finding and minimization from [`crate::numerics`]).
//! * `boundaries.rs`: `X_c1`, `X_c2` and the tongue tip; `branch.rs`: the planar equilibrium at
//!   one `X` and the full trace of the branch.
//! * `domain.rs`, `types.rs`, `error.rs`: valid inputs, results and errors.
//!
//! All ODEs use the crate's Dormand–Prince integrator ([`crate::ode`]).
//!
//! # Results
//!
//! Along the branch the Morse index goes 0 → 1 → … → 1 → 0: one loss of stability at
//! `X_c1(Y)` (out-of-plane: the loaded coil twists out of its plane) and one recovery at
//! `X_c2(Y)` (the hanging curl becomes stable again). All in-plane folds (snaps; none at
//! `Y = 1`, two at `Y = 1.2`) and every other change of the index lie between them, where every planar
//! equilibrium of the branch is unstable (up to 10 unstable modes at `Y = 10`). For
//! `c = 0.77`: below `Y* = 0.931984` the branch is stable for every `X`; the tongue tip is at
//! `X* = 0.44056` and the window opens like `√(Y − Y*)`; `X_c1` falls monotonically (with a
//! modulation of period ≈1 in `Y`, one per added turn), e.g. 0.3818, 0.2727, 0.1011 at
//! `Y = 1, 2, 10`; `X_c2` rises to its large-`Y` limit 0.580557 (reached to 1e-8 by `Y ≈ 3`: the
//! mode lives in the tip curl of length `Γ^{-1/3}`, and the rest of the rod only matters
//! through `e^{−⅔(2πXY)^{3/2}}`). Cheaper twisting widens the window: the limit of `X_c2` is
//! 0.7114 at `c = 0.5` and 0.5165 at `c = 1`, and `Y*` is 0.7874 and 1.0172.
//!
//! The discrete rod model (DER with 100·Y elements) reproduces both boundaries to ~0.03 %
//! (tests), and there both bifurcations are supercritical (the 3-D amplitude grows like the
//! square root of the distance into the window; no 3-D state was found just outside it).

mod boundaries;
mod branch;
mod continuation;
mod domain;
mod error;
mod general;
mod morse_index;
mod out_of_plane;
mod planar;
mod types;

pub use boundaries::{
    critical_boundaries, critical_boundaries_with, planar_stable, threshold_y, tongue_tip,
};
pub use branch::{planar_branch, planar_equilibrium, stability_function};
pub use domain::{C_MAX, C_MIN, GAMMA_MAX, Y_MAX, Y_MIN};
pub use error::BendTwistError;
pub use general::{general_free_end_moments, GeneralBase};
pub use types::{
    BranchEvent, EventKind, PlanarBranch, PlanarEquilibrium, Settings, StabilityBoundary,
};
