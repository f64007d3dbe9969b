//! slender-validation: the seed's benchmarks, their master curves and the sweeps.
//!
//! Master curves are computed here by methods that share nothing with the rod model
//! (ODE shooting and finite-difference boundary-value solves), so that comparing the model
//! against them is a real test.

// `!(x <= limit)` is deliberate: it is true for NaN, which must count as a failure.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod bend_twist;
pub mod cantilever;
pub mod capstan;
pub mod lateral_buckling;
pub mod lateral_sweep;
pub mod materials;
pub mod model_comparison;
pub mod numerics;
pub mod ode;
pub mod rod_model;
pub mod shell_model;
pub mod stick_slip;
