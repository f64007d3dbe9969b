//! The seed's comparison of rod formulations (§2, Fig. 5): the same benchmarks on the discrete
//! elastic rod, the discrete Cosserat rod (with its sine and with the tangent Darboux vector)
//! and the SE(3) beam, side by side — the cantilever's error against Γ on uniform and graded
//! meshes, the observed order of convergence, Newton iterations and time per solve, the
//! bend–twist decisions on a grid, and Greenhill's heavy column by inertia.

pub mod cantilever;
pub mod checks;
pub mod greenhill;
pub mod shear_limit;

pub use cantilever::{
    convergence_orders, order_cases, orders_from_records, run_model_case, summarize_models,
    ModelCantileverRecord, ModelCantileverSweep, ModelConvergence, ModelSummary,
};
pub use checks::{bend_twist_model_score, model_checks, BendTwistModelScore};
pub use greenhill::{greenhill_threshold, GREENHILL};
pub use shear_limit::shear_tension_limit;
