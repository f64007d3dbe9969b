//! One element (knot span) of the patch as a term of the membrane and bending groups: its
//! (p+1)² control points (3(p+1)² DOF slots: 27 for quadratic, 48 for cubic) and its Gauss
//! points, each with the precomputed basis, rest forms and material matrix. The membrane
//! and the bending terms have their own Gauss rules (see `builder.rs`).

use nalgebra::{Matrix3, SMatrix, SVector, Vector3};

use crate::assembly::{LocalDerivatives, Stencil, StencilTerm, TermSet};
use crate::geometry::Vec3;

use super::bending::{BendingGeometric, BendingKinematics, FunctionGeometry};
use super::forms::{first_form, Forms, SurfaceJet};
use super::groups;
use super::membrane;
use super::patch::TensorBasis;
use super::state::BsplineState;

/// A Gauss point of an element, with everything that does not depend on the deformation.
#[derive(Clone, Debug, PartialEq)]
pub struct QuadraturePoint<const NB: usize> {
    /// Basis of the element's functions at the point.
    pub basis: [TensorBasis; NB],
    /// Rest area it stands for: Gauss weight × rest area element (m²).
    pub area: f64,
    /// Rest first fundamental form (ā₁₁, ā₁₂, ā₂₂).
    pub abar: Vector3<f64>,
    /// Rest second fundamental form (1/m).
    pub bbar: Vector3<f64>,
    /// The term's matrix at the point: K_m (J) of a membrane point, W_m = ½ (a − ā)ᵀ K_m
    /// (a − ā), or K_b (J m²) of a bending point, W_b = ½ (b − b̄)ᵀ K_b (b − b̄).
    pub stiffness: Matrix3<f64>,
}

/// An element term on the stencil of its `NB` = (p+1)² control points, `D` = 3·NB slots
/// (slot 3k + c is coordinate c of the element's k-th control point).
#[derive(Clone, Debug, PartialEq)]
pub struct ElementTerm<const NB: usize, const D: usize> {
    /// Global indices of the element's control points.
    pub controls: [usize; NB],
    /// Free DOF of each slot.
    pub dofs: Stencil<D>,
    /// The Gauss points of the membrane term.
    pub membrane_points: Vec<QuadraturePoint<NB>>,
    /// The Gauss points of the bending term.
    pub bending_points: Vec<QuadraturePoint<NB>>,
    /// Index of the first of its membrane points in the patch-wide numbering (the state's
    /// per-point memory).
    pub first_point: usize,
}

/// What an element term is evaluated at.
pub struct BsplineContext<'a> {
    /// The state.
    pub state: &'a BsplineState,
}

impl<const NB: usize, const D: usize> ElementTerm<NB, D> {
    /// Membrane energy (J) of the second-order strain `remainders` (one per membrane point,
    /// the part of the last step a linearized update does not see): what the mixed-
    /// integration-point merit leaves out (see `shell::mixed_update`).
    pub fn remainder_energy(&self, remainders: &[Vector3<f64>]) -> f64 {
        let n = self.membrane_points.len();
        self.membrane_points
            .iter()
            .zip(&remainders[self.first_point..self.first_point + n])
            .map(|(q, r)| 0.5 * r.dot(&(q.stiffness * r)))
            .sum()
    }

    /// The second-order strain of the step `before` → `after` at each membrane point,
    /// appended to `out`: (Δr,1·Δr,1, Δr,1·Δr,2, Δr,2·Δr,2).
    pub fn remainders(&self, before: &[Vec3], after: &[Vec3], out: &mut Vec<Vector3<f64>>) {
        let d: [Vec3; NB] =
            std::array::from_fn(|k| after[self.controls[k]] - before[self.controls[k]]);
        for q in &self.membrane_points {
            let (d1, d2) = SurfaceJet::of_step(&q.basis, &d);
            out.push(first_form(&d1, &d2));
        }
    }

    // The block loops run over the lower triangle of (k, l) pairs and index several
    // per-function arrays.
    #[allow(clippy::needless_range_loop)]
    /// Membrane energy at the membrane points into `out`, its gradient into `g` and the
    /// lower block triangle of its Hessian into `h`.
    fn membrane(
        &self,
        ctx: &BsplineContext<'_>,
        mut g: Option<&mut SVector<f64, D>>,
        mut h: Option<&mut SMatrix<f64, D, D>>,
    ) -> f64 {
        let points = &ctx.state.control_points;
        let remainders = &ctx.state.membrane_remainder;
        let derivatives = g.is_some() || h.is_some();
        let mut energy = 0.0;
        let mut gm = [Matrix3::<f64>::zeros(); NB];
        let mut fm = [Matrix3::<f64>::zeros(); NB];
        for (iq, q) in self.membrane_points.iter().enumerate() {
            let jet = SurfaceJet::new(&q.basis, &self.controls, points);
            let d = first_form(&jet.r1, &jet.r2) - q.abar;
            let stress = q.stiffness * d;
            energy += 0.5 * d.dot(&stress);
            if !derivatives {
                continue;
            }
            for (k, nk) in q.basis.iter().enumerate() {
                gm[k] = membrane::strain_gradients(nk, &jet.r1, &jet.r2);
                if let Some(g) = g.as_deref_mut() {
                    let mut rows = g.fixed_rows_mut::<3>(3 * k);
                    rows += gm[k] * stress;
                }
            }
            let Some(h) = h.as_deref_mut() else { continue };
            // Mixed-integration-point update: the geometric stiffness uses the stress of the
            // linearly updated strain.
            let geo_stress = match remainders.get(self.first_point + iq) {
                Some(r) => q.stiffness * (d - r),
                None => stress,
            };
            for k in 0..NB {
                fm[k] = gm[k] * q.stiffness;
            }
            for k in 0..NB {
                for l in 0..=k {
                    let mut block = fm[k] * gm[l].transpose();
                    let c = membrane::geometric_coefficient(&q.basis[k], &q.basis[l], &geo_stress);
                    block[(0, 0)] += c;
                    block[(1, 1)] += c;
                    block[(2, 2)] += c;
                    let mut view = h.fixed_view_mut::<3, 3>(3 * k, 3 * l);
                    view += block;
                }
            }
        }
        energy
    }

    #[allow(clippy::needless_range_loop)]
    /// Bending energy at the bending points, as [`Self::membrane`].
    fn bending(
        &self,
        ctx: &BsplineContext<'_>,
        mut g: Option<&mut SVector<f64, D>>,
        mut h: Option<&mut SMatrix<f64, D, D>>,
    ) -> f64 {
        let points = &ctx.state.control_points;
        let derivatives = g.is_some() || h.is_some();
        let mut energy = 0.0;
        let mut gb = [Matrix3::<f64>::zeros(); NB];
        let mut fb = [Matrix3::<f64>::zeros(); NB];
        let mut data: [FunctionGeometry; NB] =
            [(0.0, Matrix3::zeros(), Matrix3::zeros(), Matrix3::zeros()); NB];
        for q in &self.bending_points {
            let jet = SurfaceJet::new(&q.basis, &self.controls, points);
            let forms = Forms::new(&jet);
            let e = forms.b - q.bbar;
            let moments = q.stiffness * e;
            energy += 0.5 * e.dot(&moments);
            if !derivatives {
                continue;
            }
            let kin = BendingKinematics::new(&jet, &forms);
            for (k, nk) in q.basis.iter().enumerate() {
                gb[k] = kin.strain_gradients(nk);
                if let Some(g) = g.as_deref_mut() {
                    let mut rows = g.fixed_rows_mut::<3>(3 * k);
                    rows += gb[k] * moments;
                }
            }
            let Some(h) = h.as_deref_mut() else { continue };
            let geo = BendingGeometric::new(&jet, &forms, &moments);
            for k in 0..NB {
                fb[k] = gb[k] * q.stiffness;
                data[k] = geo.function_data(&q.basis[k]);
            }
            for k in 0..NB {
                for l in 0..=k {
                    let block =
                        fb[k] * gb[l].transpose() + geo.block(&q.basis[k], &data[k], &data[l]);
                    let mut view = h.fixed_view_mut::<3, 3>(3 * k, 3 * l);
                    view += block;
                }
            }
        }
        energy
    }
}

impl<'a, const NB: usize, const D: usize> StencilTerm<BsplineContext<'a>, D>
    for ElementTerm<NB, D>
{
    fn groups(&self) -> TermSet {
        groups::MEMBRANE.set().with(groups::BENDING.set())
    }

    fn stencil(&self) -> &Stencil<D> {
        &self.dofs
    }

    fn evaluate(
        &self,
        ctx: &BsplineContext<'a>,
        selected: TermSet,
        out: &mut LocalDerivatives<'_, D>,
    ) {
        debug_assert_eq!(D, 3 * NB);
        // The assembler hands over zeroed outputs: write into them directly (lower block
        // triangle of the Hessian, mirrored at the end).
        if selected.contains(groups::MEMBRANE) {
            let e = self.membrane(ctx, out.grad.as_deref_mut(), out.hess.as_deref_mut());
            out.add_energy(e);
        }
        if selected.contains(groups::BENDING) {
            let e = self.bending(ctx, out.grad.as_deref_mut(), out.hess.as_deref_mut());
            out.add_energy(e);
        }
        if let Some(h) = out.hess.as_deref_mut() {
            // Mirror the lower block triangle (diagonal blocks are symmetric).
            for a in 0..D {
                for b in 0..a {
                    h[(b, a)] = h[(a, b)];
                }
            }
        }
    }
}
