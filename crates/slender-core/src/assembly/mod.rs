//! The term/assembler layer: every model is a DOF map, a list of term groups and a retraction.
//!
//! A *term* is one energy contribution on a local stencil of DOF slots (a rod hinge, a shell
//! face, an edge's stretching, a dead load on a vertex); it returns its energy and, on request,
//! its gradient and Hessian on that stencil as fixed-size nalgebra types ([`StencilTerm`]).
//! The [`Assembler`] owns everything around the terms that every model needs and no model
//! should write again: zeroing the outputs, scattering local derivatives into the global
//! gradient and any [`SymmetricMatrix`](crate::linalg::SymmetricMatrix) storage, the round-off
//! bookkeeping (`energy_magnitude`, `abs_grad`) and the selection of term groups
//! ([`TermSet`]) that tests use to check one term at a time.
//!
//! The layers above: a model implements [`EquilibriumProblem`](crate::solver::EquilibriumProblem)
//! by running its term groups through an assembler; the solver factors and steps; the load
//! path ([`crate::solver::continuation`]) moves the load parameter.

pub mod assembler;
pub mod stencil;
pub mod term;

pub use assembler::{Assembler, AssemblyInfo, MapSlot};
pub use stencil::{Stencil, FIXED};
pub use term::{LocalDerivatives, StencilTerm, TermGroup, TermSet};
