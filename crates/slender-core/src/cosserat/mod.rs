//! The discrete Cosserat rod (Lang, Linn & Arnold 2011; design.md §2.2): vertex positions,
//! one material frame per edge (a staggered grid), extension and both shears on the edges,
//! bending and twist from the discrete Darboux vector of neighbouring frames at the vertices,
//! natural strains from the rest shape, and clamps that hold the exact frame of the curve's end
//! (a half cell between the clamp frame and the first edge's frame).
//!
//! Energy, with d = (d₁, d₂, d₃) the frame of edge j and h its rest length:
//! * extension and shear: ½ h (Γ − Γ̄)ᵀ diag(κGA₁, κGA₂, EA) (Γ − Γ̄), Γ = Rᵀ(x_{j+1} − x_j)/h;
//! * bending and twist: (1/2h̄)(g − ḡ)ᵀ diag(EI₂, EI₁, GJ)(g − ḡ) at each vertex, where
//!   g = h̄ K is the Darboux vector of the relative rotation of the two frames in the first
//!   one's coordinates ([`DarbouxMeasure`](crate::lie::DarbouxMeasure)) and h̄ the distance
//!   between the frames' positions (edge midpoints; half an edge next to a clamp).
//!
//! The model shares the solver, load stepping, stability analysis and loads with the discrete
//! elastic rod through [`EquilibriumProblem`](crate::solver::EquilibriumProblem).

pub mod bend_twist;
pub mod builder;
pub mod equilibrium;
pub mod model;
pub mod strains;
pub mod stretch_shear;

pub use builder::{CosseratBuilder, CosseratOptions};
pub use model::{CosseratContext, CosseratRod};
pub use strains::{DarbouxStrain, EdgeStrain};

/// Half-bandwidth of a Cosserat rod's Hessian: an edge term spans [x_j, ω_j, x_{j+1}] (9
/// consecutive entries), a vertex term [ω_{j−1}, x_j, ω_j] (ω's only, 9 apart at most).
pub const COSSERAT_HALF_BANDWIDTH: usize = 8;
