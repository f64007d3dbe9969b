//! What the Newton solver needs from a model.

use crate::linalg::SymmetricMatrix;

/// Per-assembly quantities the convergence tests use.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct AssemblyInfo {
    /// Total energy (J) at the load factor: internal minus work of the external loads.
    pub energy: f64,
    /// Σ over terms of |energy term| (J): the scale of round-off in `energy`.
    pub energy_magnitude: f64,
    /// Work of the external loads from the reference configuration to here (J).
    pub external_work: f64,
    /// Largest external nodal force at this load factor (N); moments count as force × length.
    pub external_force: f64,
}

/// A discretized structure whose equilibria the solver finds: an energy over a state with
/// exact gradient and Hessian in the free DOFs. The Hessian storage (banded for rods, sparse
/// for shells) is the problem's choice; the solver only assembles, factors and solves.
///
/// States may carry more than the DOF vector (a rod carries reference frames). Every state a
/// problem hands out is consistent: [`displace`](Self::displace) produces a new state with
/// its frames adapted, and [`assemble`](Self::assemble) is exact at that state.
pub trait EquilibriumProblem {
    /// Configuration type (positions, angles and whatever caches derive from them).
    type State: Clone;

    /// Number of free DOFs.
    fn n_free(&self) -> usize;

    /// Hessian storage and factorization.
    type Hessian: SymmetricMatrix;

    /// A zero Hessian with the problem's pattern (n_free × n_free).
    fn new_hessian(&self) -> Self::Hessian;

    /// Energy (J) at load factor `load` (external loads scaled by it).
    fn energy(&self, state: &Self::State, load: f64) -> f64;

    /// Gradient into `grad` (length [`n_free`](Self::n_free)), Hessian into `hess` (zeroed
    /// here), and Σ_elements |element gradient| per DOF into `abs_grad` (the round-off scale).
    fn assemble(
        &self,
        state: &Self::State,
        load: f64,
        grad: &mut [f64],
        hess: &mut Self::Hessian,
        abs_grad: &mut [f64],
    ) -> AssemblyInfo;

    /// Values of the free DOFs of `state` (m or rad) into `out`.
    fn dof_values(&self, state: &Self::State, out: &mut [f64]);

    /// `out` = `state` moved by `alpha·dx` (free DOFs), with caches adapted.
    fn displace(&self, state: &Self::State, dx: &[f64], alpha: f64, out: &mut Self::State);

    /// Largest α ∈ (0, 1] such that `alpha·dx` respects the model's step caps (e.g. no edge
    /// turns by more than π/4 in one step).
    fn max_step(&self, state: &Self::State, dx: &[f64]) -> f64;

    /// Length (m) that turns the generalized force of DOF `i` into a force: 1 for coordinates,
    /// a characteristic length for angles (whose generalized forces are moments).
    fn force_length(&self, i: usize) -> f64;

    /// Typical magnitude of DOF `i` (m or rad), for the round-off floor of the gradient.
    fn dof_magnitude(&self, state: &Self::State, i: usize) -> f64;

    /// Inertia attached to DOF `i` (kg, or kg m² for angles): the metric in which the smallest
    /// Hessian eigenvalue is reported, so that it is a squared natural frequency (1/s²) and
    /// does not depend on the mesh.
    fn inertia_metric(&self, i: usize) -> f64;

    /// Reference value of eigenvalues (1/s²) used to normalize λ_min (e.g. EI/(ρA L⁴)).
    fn eigenvalue_scale(&self) -> f64;
}
