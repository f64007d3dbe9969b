//! The geometrically exact beam on SE(3) (Sonneville, Cardona & Brüls 2014; design.md §2.3;
//! the formulation of Odin): every node carries a pose H = (R, x) ∈ SE(3); each element
//! interpolates its two end poses by the SE(3) exponential, H(ξ) = H_A exp(ξ d) with
//! d = log(H_A⁻¹ H_B), so its strain ε = d/L₀ is constant and any configuration of constant
//! strain (straight, circle, helix) is represented exactly, whatever the number of elements.
//!
//! Energy per element: ½ L₀ (ε − ε̄)ᵀ C (ε − ε̄) with C = diag(κGA₁, κGA₂, EA, EI₂, EI₁, GJ)
//! (translation part first: shear along d₁, d₂, extension; then rotation about d₁, d₂, d₃),
//! ε̄ the rest strain of the element. Clamps hold the exact pose of the curve's end at their
//! node. The exact Hessian comes from the chain rule through the second-order expansions of
//! the relative rotation, its logarithm and the translational part of the SE(3) logarithm
//! ([`crate::lie`]), in the chart x ← x + δx, R ← exp([ω]×)R.

pub mod builder;
pub mod element;
pub mod equilibrium;
pub mod model;
pub mod strains;

pub use builder::{Se3Builder, Se3Options};
pub use model::{Se3Context, Se3Rod};
pub use strains::ElementStrain;

/// Half-bandwidth of an SE(3) beam's Hessian: an element spans [x_A, ω_A, x_B, ω_B], 12
/// consecutive entries.
pub const SE3_HALF_BANDWIDTH: usize = 11;
