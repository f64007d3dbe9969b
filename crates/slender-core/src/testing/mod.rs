//! Test support shared by every model (feature `testing`): the generic derivative checker and
//! a deterministic random generator.
//!
//! Every model must pass [`check_model`]: each term group's gradient and Hessian (and all of
//! them together) against central finite differences of the energy, with the error falling
//! like O(ε²); invariance of the internal energy under rigid motions; zero gradient and energy
//! at the rest shape. A new model implements [`RigidMotion`] and gets these checks for free.

pub mod derivatives;
pub mod rng;

pub use derivatives::{
    check_derivatives, check_model, check_rest, check_rigid_invariance, fd_errors, FdErrors,
    RigidMotion,
};
pub use rng::Rng;
