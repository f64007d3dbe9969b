//! One element (knot span) of the patch as a term of the membrane and bending groups: its
//! (p+1)² control points (3(p+1)² DOF slots: 27 for quadratic, 48 for cubic) and its Gauss
//! points, each with the precomputed basis, rest forms and material matrices.

use nalgebra::{Matrix3, SMatrix, SVector, Vector3};

use crate::assembly::{LocalDerivatives, Stencil, StencilTerm, TermSet};
use crate::geometry::Vec3;

use super::bending::{BendingGeometric, BendingKinematics};
use super::forms::{Forms, SurfaceJet};
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
    /// Membrane matrix K_m (J): W_m = ½ (a − ā)ᵀ K_m (a − ā).
    pub membrane: Matrix3<f64>,
    /// Bending matrix K_b (J m²): W_b = ½ (b − b̄)ᵀ K_b (b − b̄).
    pub bending: Matrix3<f64>,
}

/// An element term on the stencil of its `NB` = (p+1)² control points, `D` = 3·NB slots
/// (slot 3k + c is coordinate c of the element's k-th control point).
#[derive(Clone, Debug, PartialEq)]
pub struct ElementTerm<const NB: usize, const D: usize> {
    /// Global indices of the element's control points.
    pub controls: [usize; NB],
    /// Free DOF of each slot.
    pub dofs: Stencil<D>,
    /// The Gauss points.
    pub points: Vec<QuadraturePoint<NB>>,
    /// Index of the first of its Gauss points in the patch-wide numbering (the state's
    /// per-point memory).
    pub first_point: usize,
}

/// What an element term is evaluated at.
pub struct BsplineContext<'a> {
    /// The state.
    pub state: &'a BsplineState,
}

impl<const NB: usize, const D: usize> ElementTerm<NB, D> {
    /// Membrane energy (J) of the second-order strain `remainders` (one per Gauss point, the
    /// part of the last step a linearized update does not see): what the mixed-integration-
    /// point merit leaves out (see `mixed_update`).
    pub fn remainder_energy(&self, remainders: &[Vector3<f64>]) -> f64 {
        self.points
            .iter()
            .zip(&remainders[self.first_point..self.first_point + self.points.len()])
            .map(|(q, r)| 0.5 * r.dot(&(q.membrane * r)))
            .sum()
    }

    /// The second-order strain of the step `before` → `after` at each Gauss point, appended
    /// to `out`: (Δr,1·Δr,1, Δr,1·Δr,2, Δr,2·Δr,2).
    pub fn remainders(&self, before: &[Vec3], after: &[Vec3], out: &mut Vec<Vector3<f64>>) {
        let d: [Vec3; NB] =
            std::array::from_fn(|k| after[self.controls[k]] - before[self.controls[k]]);
        for q in &self.points {
            let (d1, d2) = SurfaceJet::of_step(&q.basis, &d);
            out.push(super::forms::first_form(&d1, &d2));
        }
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
        let points = &ctx.state.control_points;
        let remainders = &ctx.state.membrane_remainder;
        let with_membrane = selected.contains(groups::MEMBRANE);
        let with_bending = selected.contains(groups::BENDING);
        let want_grad = out.wants_gradient();
        let want_hess = out.wants_hessian();
        let mut g = SVector::<f64, D>::zeros();
        let mut h = SMatrix::<f64, D, D>::zeros();
        let mut gm = [Matrix3::<f64>::zeros(); NB];
        let mut gb = [Matrix3::<f64>::zeros(); NB];
        let mut fm = [Matrix3::<f64>::zeros(); NB];
        let mut fb = [Matrix3::<f64>::zeros(); NB];
        let mut bend_data = [(0.0, Matrix3::<f64>::zeros(), Vec3::zeros(), Vec3::zeros()); NB];
        for (iq, q) in self.points.iter().enumerate() {
            let jet = SurfaceJet::new(&q.basis, &self.controls, points);
            let forms = Forms::new(&jet);
            let mut stress = Vector3::zeros();
            let mut geo_stress = Vector3::zeros();
            if with_membrane {
                let d = forms.a - q.abar;
                stress = q.membrane * d;
                out.add_energy(0.5 * d.dot(&stress));
                // Mixed-integration-point update: the geometric stiffness uses the stress of
                // the linearly updated strain.
                geo_stress = match remainders.get(self.first_point + iq) {
                    Some(r) => q.membrane * (d - r),
                    None => stress,
                };
            }
            let mut moments = Vector3::zeros();
            let kin = with_bending.then(|| BendingKinematics::new(&jet, &forms));
            if kin.is_some() {
                let e = forms.b - q.bbar;
                moments = q.bending * e;
                out.add_energy(0.5 * e.dot(&moments));
            }
            if !(want_grad || want_hess) {
                continue;
            }
            for k in 0..NB {
                let nk = &q.basis[k];
                let mut gk = Vec3::zeros();
                if with_membrane {
                    gm[k] = membrane::strain_gradients(nk, &jet.r1, &jet.r2);
                    gk += gm[k] * stress;
                }
                if let Some(kin) = &kin {
                    gb[k] = kin.strain_gradients(nk);
                    gk += gb[k] * moments;
                }
                if want_grad {
                    let mut rows = g.fixed_rows_mut::<3>(3 * k);
                    rows += gk;
                }
            }
            if !want_hess {
                continue;
            }
            let geometric = kin
                .as_ref()
                .map(|_| BendingGeometric::new(&jet, &forms, &moments));
            for k in 0..NB {
                if with_membrane {
                    fm[k] = gm[k] * q.membrane;
                }
                if let (Some(kin), Some(geo)) = (&kin, &geometric) {
                    fb[k] = gb[k] * q.bending;
                    bend_data[k] = geo.function_data(kin, &q.basis[k]);
                }
            }
            for k in 0..NB {
                for l in 0..=k {
                    let mut block = Matrix3::zeros();
                    if with_membrane {
                        block += fm[k] * gm[l].transpose();
                        let c =
                            membrane::geometric_coefficient(&q.basis[k], &q.basis[l], &geo_stress);
                        block[(0, 0)] += c;
                        block[(1, 1)] += c;
                        block[(2, 2)] += c;
                    }
                    if let Some(geo) = &geometric {
                        block += fb[k] * gb[l].transpose();
                        block += geo.block(&q.basis[k], &q.basis[l], &bend_data[k], &bend_data[l]);
                    }
                    let mut view = h.fixed_view_mut::<3, 3>(3 * k, 3 * l);
                    view += block;
                }
            }
        }
        if let Some(grad) = out.grad.as_deref_mut() {
            *grad += g;
        }
        if let Some(hess) = out.hess.as_deref_mut() {
            // Mirror the lower block triangle.
            for a in 0..D {
                for b in 0..a {
                    h[(b, a)] = h[(a, b)];
                }
            }
            *hess += h;
        }
    }
}
