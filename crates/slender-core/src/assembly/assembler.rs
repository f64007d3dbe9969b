//! The assembler: zeroing, scatter into any Hessian storage, round-off bookkeeping and term
//! selection, shared by every model.

use nalgebra::{SMatrix, SVector};

use crate::linalg::{ScatterPlan, SymmetricMatrix};

use super::stencil::{Stencil, FIXED};
use super::term::{LocalDerivatives, StencilTerm, TermGroup, TermSet};

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

/// Collects the energy, gradient, Hessian and round-off scales of one assembly.
///
/// Created with the outputs wanted (each optional) and the term groups to include; the
/// outputs are zeroed on creation. Models add their terms ([`Self::terms`]), precomputed
/// local contributions ([`Self::local`]) and linear loads ([`Self::load`]); [`Self::finish`]
/// returns the scalar measures.
pub struct Assembler<'o, M: SymmetricMatrix> {
    selection: TermSet,
    grad: Option<&'o mut [f64]>,
    hess: Option<&'o mut M>,
    abs_grad: Option<&'o mut [f64]>,
    info: AssemblyInfo,
    /// For a part of a larger system: the global DOF and coefficient of each of the part's
    /// own free DOFs (see [`Self::part`]).
    remap: Option<&'o [MapSlot]>,
    /// Factor on everything added (energies, loads, derivatives): 1 except in a
    /// [`Self::rescaled`] assembly (e.g. stiffness-proportional damping scales the energy).
    weight: f64,
    /// Scale of the chart the derivatives are taken in: gradients are multiplied by it and
    /// Hessians by its square (1 except in a [`Self::rescaled`] assembly).
    chart_scale: f64,
    /// The term groups whose Hessian is kept apart (see [`Self::lagging`]); none by default.
    lagged: TermSet,
    /// Where the Hessians of the terms made only of `lagged` groups go: into this matrix, or
    /// nowhere (not evaluated) when `None`.
    lagged_hess: Option<&'o mut M>,
}

/// Where one free DOF of a part (a member of a composite structure) goes in the whole: the
/// global free DOF it moves with and the coefficient (the part's DOF = `coef` × the global
/// one; e.g. a vertex coordinate on a slider is the slider's DOF times an axis component).
/// `dof` = [`FIXED`] drops it (held by a structure-level support).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MapSlot {
    /// Global free DOF, or [`FIXED`].
    pub dof: usize,
    /// Coefficient.
    pub coef: f64,
}

impl<'o, M: SymmetricMatrix> Assembler<'o, M> {
    /// An assembly of the groups in `selection` into the given outputs, which are zeroed here
    /// (`abs_grad` receives Σ over terms of |term gradient| per DOF, the round-off scale).
    pub fn new(
        selection: TermSet,
        mut grad: Option<&'o mut [f64]>,
        mut hess: Option<&'o mut M>,
        mut abs_grad: Option<&'o mut [f64]>,
    ) -> Self {
        if let Some(g) = grad.as_deref_mut() {
            g.fill(0.0);
        }
        if let Some(a) = abs_grad.as_deref_mut() {
            a.fill(0.0);
        }
        if let Some(h) = hess.as_deref_mut() {
            h.set_zero();
        }
        Self {
            selection,
            grad,
            hess,
            abs_grad,
            info: AssemblyInfo::default(),
            remap: None,
            weight: 1.0,
            chart_scale: 1.0,
            lagged: TermSet::NONE,
            lagged_hess: None,
        }
    }

    /// Keeps the Hessians of the terms made only of the groups in `groups` out of the
    /// Hessian output: into `into` (zeroed here), or, with `None`, not evaluated at all (their
    /// energies and gradients are assembled as usual). The Newton solver uses it to reuse the
    /// slowly varying part of a Hessian (a rod's bending and twisting) from an earlier
    /// assembly while the fast part (stretching, loads) is fresh; `add_same_pattern` puts the
    /// two together.
    pub fn lagging(mut self, groups: TermSet, mut into: Option<&'o mut M>) -> Self {
        if let Some(h) = into.as_deref_mut() {
            h.set_zero();
        }
        self.lagged = groups;
        self.lagged_hess = into;
        self
    }

    /// An assembler for a part of the system (a member of a composite structure) whose own
    /// free DOFs go to the global ones through `remap`; it writes into this assembler's
    /// outputs (not zeroed again). Add its measures back with [`Self::absorb`].
    pub fn part<'r>(&'r mut self, remap: &'r [MapSlot]) -> Assembler<'r, M> {
        debug_assert!(self.remap.is_none(), "parts of parts are not supported");
        // A map that sends each DOF to itself with coefficient 1 (a lone member) is no map:
        // the direct scatter adds the same values to the same entries.
        let identity = remap
            .iter()
            .enumerate()
            .all(|(i, m)| m.dof == i && m.coef == 1.0);
        Assembler {
            selection: self.selection,
            grad: self.grad.as_deref_mut(),
            hess: self.hess.as_deref_mut(),
            abs_grad: self.abs_grad.as_deref_mut(),
            info: AssemblyInfo::default(),
            remap: (!identity).then_some(remap),
            weight: self.weight,
            chart_scale: self.chart_scale,
            lagged: self.lagged,
            lagged_hess: self.lagged_hess.as_deref_mut(),
        }
    }

    /// An assembler into this one's outputs (not zeroed again) for the energy `weight`·E(z)
    /// of a state z that moves by `chart_scale` per unit of the caller's chart (z = x ⊕ c·dx):
    /// energies and loads are multiplied by `weight`, gradients by `weight`·c and Hessians by
    /// `weight`·c². E.g. (1 + β/τ)·E for stiffness-proportional damping (c = 1), or a
    /// quadrature node E(xₙ + s d)/s of an average along a step (c = s). Add its measures back
    /// with [`Self::absorb`] (they are weighted already).
    pub fn rescaled<'r>(&'r mut self, weight: f64, chart_scale: f64) -> Assembler<'r, M> {
        Assembler {
            selection: self.selection,
            grad: self.grad.as_deref_mut(),
            hess: self.hess.as_deref_mut(),
            abs_grad: self.abs_grad.as_deref_mut(),
            info: AssemblyInfo::default(),
            remap: self.remap,
            weight: self.weight * weight,
            chart_scale: self.chart_scale * chart_scale,
            lagged: self.lagged,
            lagged_hess: self.lagged_hess.as_deref_mut(),
        }
    }

    /// Adds the measures of a part's assembly (see [`Self::part`]).
    pub fn absorb(&mut self, part: AssemblyInfo) {
        self.info.energy += part.energy;
        self.info.energy_magnitude += part.energy_magnitude;
        self.info.external_work += part.external_work;
        self.info.external_force = self.info.external_force.max(part.external_force);
    }

    /// An energy-only assembly.
    pub fn energy_only(selection: TermSet) -> Self {
        Self::new(selection, None, None, None)
    }

    /// True if `group` is selected.
    pub fn selects(&self, group: TermGroup) -> bool {
        self.selection.contains(group)
    }

    /// The selected groups.
    pub fn selection(&self) -> TermSet {
        self.selection
    }

    /// True if gradients are wanted (for the gradient or its round-off scale).
    pub fn wants_gradient(&self) -> bool {
        self.grad.is_some() || self.abs_grad.is_some()
    }

    /// True if the Hessian is wanted.
    pub fn wants_hessian(&self) -> bool {
        self.hess.is_some()
    }

    /// Evaluates every term of a group list whose groups are selected, in order, and scatters
    /// its derivatives.
    pub fn terms<C: ?Sized, T: StencilTerm<C, D>, const D: usize>(&mut self, ctx: &C, terms: &[T]) {
        self.terms_planned(ctx, terms, None);
    }

    /// [`Self::terms`] with the positions of the terms' Hessian entries precomputed for the
    /// Hessian's storage (used when the Hessian has the plan's pattern and no part map
    /// applies; the same additions either way).
    pub fn terms_planned<C: ?Sized, T: StencilTerm<C, D>, const D: usize>(
        &mut self,
        ctx: &C,
        terms: &[T],
        plan: Option<&ScatterPlan>,
    ) {
        let want_grad = self.wants_gradient();
        let want_hess = self.wants_hessian();
        let mut g = SVector::<f64, D>::zeros();
        let mut h = SMatrix::<f64, D, D>::zeros();
        for (index, term) in terms.iter().enumerate() {
            let selected = TermSet(term.groups().0 & self.selection.0);
            if selected == TermSet::NONE {
                continue;
            }
            let lagged =
                self.lagged != TermSet::NONE && selected.without(self.lagged) == TermSet::NONE;
            let term_hess = want_hess && !(lagged && self.lagged_hess.is_none());
            // Whole-matrix assignment: vector stores (nalgebra's `fill` walks the entries).
            if want_grad {
                g = SVector::zeros();
            }
            if term_hess && !T::OVERWRITES_HESSIAN {
                h = SMatrix::zeros();
            }
            let mut out = LocalDerivatives {
                energy: 0.0,
                magnitude: 0.0,
                grad: want_grad.then_some(&mut g),
                hess: term_hess.then_some(&mut h),
            };
            term.evaluate(ctx, selected, &mut out);
            let (energy, magnitude) = (out.energy, out.magnitude);
            let plan = plan.map(|p| (p, index));
            self.local_planned(term.stencil(), energy, magnitude, &g, &h, plan, lagged);
        }
    }

    /// Adds a term's energy (J), its round-off magnitude, and its stencil gradient and Hessian
    /// (ignored when not wanted). Slots marked [`FIXED`] are dropped; two slots naming the same
    /// DOF are summed (off-diagonal pairs count twice on that DOF's diagonal).
    pub fn local<const D: usize>(
        &mut self,
        stencil: &Stencil<D>,
        energy: f64,
        magnitude: f64,
        g: &SVector<f64, D>,
        h: &SMatrix<f64, D, D>,
    ) {
        self.local_planned(stencil, energy, magnitude, g, h, None, false);
    }

    /// [`Self::local`] for term `plan.1` of a scatter plan.
    #[allow(clippy::too_many_arguments)] // the term's outputs, its plan and its Hessian's target
    fn local_planned<const D: usize>(
        &mut self,
        stencil: &Stencil<D>,
        energy: f64,
        magnitude: f64,
        g: &SVector<f64, D>,
        h: &SMatrix<f64, D, D>,
        plan: Option<(&ScatterPlan, usize)>,
        lagged: bool,
    ) {
        // Factors of 1 multiply exactly: plain assemblies are bit-for-bit unchanged.
        let (w, gw, hw) = self.factors();
        self.info.energy += w * energy;
        self.info.energy_magnitude += w.abs() * magnitude;
        if let Some(remap) = self.remap {
            self.scatter_mapped(stencil, remap, g, h, lagged);
            return;
        }
        // Unit factors (a plain assembly) take a path without the multiplications by them,
        // which are exact: the same values either way.
        if gw == 1.0 {
            self.scatter_gradient(stencil, |a| g[a]);
        } else {
            self.scatter_gradient(stencil, |a| gw * g[a]);
        }
        let target = if lagged {
            self.lagged_hess.as_deref_mut()
        } else {
            self.hess.as_deref_mut()
        };
        if let Some(hm) = target {
            // Lower triangle of the stencil (b ≤ a): each unordered pair once, read from the
            // upper one (column a, rows b ≤ a: contiguous in nalgebra's column-major storage,
            // where row a is strided; the local Hessian is symmetric).
            if hw == 1.0 {
                let value = |a, b| h[(b, a)];
                match plan {
                    Some((plan, term)) => hm.add_lower_block_planned(plan, term, stencil, value),
                    None => hm.add_lower_block(stencil, value),
                }
            } else {
                let value = |a, b| hw * h[(b, a)];
                match plan {
                    Some((plan, term)) => hm.add_lower_block_planned(plan, term, stencil, value),
                    None => hm.add_lower_block(stencil, value),
                }
            }
        }
    }

    /// Adds the stencil gradient `g(a)` (already weighted) into the gradient and its
    /// magnitude into the round-off scale.
    #[inline(always)]
    fn scatter_gradient<const D: usize>(&mut self, stencil: &Stencil<D>, g: impl Fn(usize) -> f64) {
        for (a, &i) in stencil.iter().enumerate() {
            if i == FIXED {
                continue;
            }
            if let Some(gr) = self.grad.as_deref_mut() {
                gr[i] += g(a);
            }
            if let Some(ab) = self.abs_grad.as_deref_mut() {
                ab[i] += g(a).abs();
            }
        }
    }

    /// [`Self::local`]'s scatter through a part's DOF map.
    fn scatter_mapped<const D: usize>(
        &mut self,
        stencil: &Stencil<D>,
        remap: &[MapSlot],
        g: &SVector<f64, D>,
        h: &SMatrix<f64, D, D>,
        lagged: bool,
    ) {
        let (_, gw, hw) = self.factors();
        let slot = |a: usize| -> Option<MapSlot> {
            let i = stencil[a];
            if i == FIXED {
                return None;
            }
            let m = remap[i];
            (m.dof != FIXED).then_some(m)
        };
        let mut dofs = [FIXED; D];
        let mut coefs = [0.0; D];
        for a in 0..D {
            let Some(ma) = slot(a) else { continue };
            let i = ma.dof;
            (dofs[a], coefs[a]) = (i, ma.coef);
            if let Some(gr) = self.grad.as_deref_mut() {
                gr[i] += gw * ma.coef * g[a];
            }
            if let Some(ab) = self.abs_grad.as_deref_mut() {
                ab[i] += (gw * ma.coef * g[a]).abs();
            }
        }
        let target = if lagged {
            self.lagged_hess.as_deref_mut()
        } else {
            self.hess.as_deref_mut()
        };
        if let Some(hm) = target {
            // Unit coefficients (every DOF but a slider's) multiply exactly: skip them.
            if coefs
                .iter()
                .zip(&dofs)
                .all(|(&c, &d)| c == 1.0 || d == FIXED)
            {
                hm.add_lower_block(&dofs, |a, b| hw * h[(a, b)]);
            } else {
                hm.add_lower_block(&dofs, |a, b| hw * coefs[a] * coefs[b] * h[(a, b)]);
            }
        }
    }

    /// A conservative external load doing work `work` (J) from the reference configuration:
    /// the energy falls by it. `max_force` (N; moments count as force × length) updates the
    /// largest external nodal force, the scale of the force convergence test.
    pub fn load(&mut self, work: f64, max_force: f64) {
        let (w, gw, _) = self.factors();
        let (work, max_force) = (w * work, gw.abs() * max_force);
        self.info.energy -= work;
        self.info.energy_magnitude += work.abs();
        self.info.external_work += work;
        self.info.external_force = self.info.external_force.max(max_force);
    }

    /// A generalized force `force` (N or N m) on DOF `dof` from a linear load: the gradient
    /// falls by it (no Hessian). [`FIXED`] DOFs are ignored.
    pub fn generalized_force(&mut self, dof: usize, force: f64) {
        if dof == FIXED {
            return;
        }
        let (dof, force) = match self.remap {
            Some(remap) => {
                let m = remap[dof];
                if m.dof == FIXED {
                    return;
                }
                (m.dof, m.coef * force)
            }
            None => (dof, force),
        };
        let force = self.weight * self.chart_scale * force;
        if let Some(gr) = self.grad.as_deref_mut() {
            gr[dof] -= force;
        }
        if let Some(a) = self.abs_grad.as_deref_mut() {
            a[dof] += force.abs();
        }
    }

    /// Adds a potential energy (J) that is part of the external loads (e.g. an absolute
    /// gravity potential) without its derivatives; see [`Self::generalized_force`].
    pub fn external_energy(&mut self, energy: f64, work: f64) {
        let (energy, work) = (self.weight * energy, self.weight * work);
        self.info.energy += energy;
        self.info.energy_magnitude += energy.abs();
        self.info.external_work += work;
    }

    /// Raises the largest external nodal force (N) to at least `force`.
    pub fn external_force(&mut self, force: f64) {
        let gw = self.weight * self.chart_scale;
        self.info.external_force = self.info.external_force.max(gw.abs() * force);
    }

    /// The factors on energies, gradients and Hessians (see [`Self::rescaled`]).
    fn factors(&self) -> (f64, f64, f64) {
        let w = self.weight;
        let c = self.chart_scale;
        (w, w * c, w * c * c)
    }

    /// The scalar measures of the assembly.
    pub fn finish(self) -> AssemblyInfo {
        self.info
    }
}
