//! Contact of slender structures with their surroundings (issue 14).
//!
//! [`obstacle`] is the one interface every rigid obstacle implements (closest-point queries with
//! the derivatives an exact Hessian needs); [`plane`] is the first obstacle. Enforcement of
//! non-penetration and Coulomb friction on top of the solver, the other obstacle shapes and
//! segment–segment (self and cable–cable) proximity live in their own files beside these.

pub mod obstacle;
pub mod plane;

pub use obstacle::{Obstacle, SurfacePoint};
pub use plane::Plane;
