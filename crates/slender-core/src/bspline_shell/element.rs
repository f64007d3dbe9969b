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
    /// The elements' Hessian factors, one element at a time, in buffers the model keeps
    /// between assemblies.
    scratch: std::cell::RefCell<&'a mut ElementScratch>,
}

impl<'a> BsplineContext<'a> {
    /// The context of an assembly at `state`, with the model's element buffers.
    pub fn new(state: &'a BsplineState, scratch: &'a mut ElementScratch) -> Self {
        Self {
            state,
            scratch: std::cell::RefCell::new(scratch),
        }
    }
}

/// The buffers of one element's Hessian factors (see [`BsplineContext`]).
#[derive(Default)]
pub struct ElementScratch {
    membrane: Vec<MembraneFactors>,
    stresses: Vec<Vector3<f64>>,
    bending: Vec<BendingFactors>,
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

    /// Membrane energy at the membrane points; its gradient is added to `g`, and the
    /// per-point Hessian factors (point-major, `NB` per point) and geometric stresses are
    /// appended to `hess` for [`Self::hessian_blocks`].
    fn membrane(
        &self,
        ctx: &BsplineContext<'_>,
        mut g: Option<&mut SVector<f64, D>>,
        mut hess: Option<(&mut Vec<MembraneFactors>, &mut Vec<Vector3<f64>>)>,
    ) -> f64 {
        let points = &ctx.state.control_points;
        let remainders = &ctx.state.membrane_remainder;
        let derivatives = g.is_some() || hess.is_some();
        let mut energy = 0.0;
        for (iq, q) in self.membrane_points.iter().enumerate() {
            let jet = SurfaceJet::new(&q.basis, &self.controls, points);
            let d = first_form(&jet.r1, &jet.r2) - q.abar;
            let stress = q.stiffness * d;
            energy += 0.5 * d.dot(&stress);
            if !derivatives {
                continue;
            }
            let (mut factors, stresses) = match hess.as_mut() {
                Some((f, s)) => (Some(&mut **f), Some(&mut **s)),
                None => (None, None),
            };
            for (k, nk) in q.basis.iter().enumerate() {
                let gm = membrane::strain_gradients(nk, &jet.r1, &jet.r2);
                if let Some(g) = g.as_deref_mut() {
                    let mut rows = g.fixed_rows_mut::<3>(3 * k);
                    rows += gm * stress;
                }
                if let Some(f) = factors.as_deref_mut() {
                    f.push(MembraneFactors {
                        f: gm * q.stiffness,
                        g: gm,
                    });
                }
            }
            if let Some(s) = stresses {
                // Mixed-integration-point update: the geometric stiffness uses the stress of
                // the linearly updated strain.
                s.push(match remainders.get(self.first_point + iq) {
                    Some(r) => q.stiffness * (d - r),
                    None => stress,
                });
            }
        }
        energy
    }

    /// Bending energy at the bending points, as [`Self::membrane`].
    fn bending(
        &self,
        ctx: &BsplineContext<'_>,
        mut g: Option<&mut SVector<f64, D>>,
        mut hess: Option<&mut Vec<BendingFactors>>,
    ) -> f64 {
        let points = &ctx.state.control_points;
        let derivatives = g.is_some() || hess.is_some();
        let mut energy = 0.0;
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
            let geo = hess
                .is_some()
                .then(|| BendingGeometric::new(&jet, &forms, &moments));
            for (k, nk) in q.basis.iter().enumerate() {
                let gb = kin.strain_gradients(nk);
                if let Some(g) = g.as_deref_mut() {
                    let mut rows = g.fixed_rows_mut::<3>(3 * k);
                    rows += gb * moments;
                }
                if let (Some(f), Some(geo)) = (hess.as_deref_mut(), &geo) {
                    f.push(BendingFactors {
                        f: gb * q.stiffness,
                        g: gb,
                        geometric: geo.function_data(nk),
                    });
                }
            }
        }
        energy
    }

    /// Writes the Hessian from the per-point factors of both terms (either list may be
    /// empty): each 3×3 block (k, l), k ≥ l, is summed over the membrane then the bending
    /// points in registers and stored once with its mirror, instead of being added into
    /// `h` point by point (the same sums in the same order).
    fn hessian_blocks(
        &self,
        membrane: &[MembraneFactors],
        stresses: &[Vector3<f64>],
        bending: &[BendingFactors],
        h: &mut SMatrix<f64, D, D>,
    ) {
        let membrane_points = &self.membrane_points[..stresses.len()];
        let bending_points = &self.bending_points[..bending.len() / NB];
        for k in 0..NB {
            for l in 0..=k {
                let mut acc = Matrix3::<f64>::zeros();
                for ((q, s), m) in membrane_points
                    .iter()
                    .zip(stresses)
                    .zip(membrane.chunks_exact(NB))
                {
                    let mut block = m[k].f * m[l].g.transpose();
                    let c = membrane::geometric_coefficient(&q.basis[k], &q.basis[l], s);
                    block[(0, 0)] += c;
                    block[(1, 1)] += c;
                    block[(2, 2)] += c;
                    acc += block;
                }
                for (q, b) in bending_points.iter().zip(bending.chunks_exact(NB)) {
                    acc += b[k].f * b[l].g.transpose()
                        + BendingGeometric::block(&q.basis[k], &b[k].geometric, &b[l].geometric);
                }
                if k == l {
                    // Diagonal blocks are symmetric: the lower triangle stands for both.
                    for a in 0..3 {
                        for b in 0..=a {
                            h[(3 * k + a, 3 * k + b)] = acc[(a, b)];
                            h[(3 * k + b, 3 * k + a)] = acc[(a, b)];
                        }
                    }
                } else {
                    h.fixed_view_mut::<3, 3>(3 * k, 3 * l).copy_from(&acc);
                    h.fixed_view_mut::<3, 3>(3 * l, 3 * k).tr_copy_from(&acc);
                }
            }
        }
    }
}

/// What the Hessian blocks need of function k at a membrane point: G_k = ∂a/∂P_k and
/// F_k = G_k K_m (block (k, l) = F_k G_lᵀ + c_kl I).
#[derive(Clone, Copy, Debug)]
struct MembraneFactors {
    f: Matrix3<f64>,
    g: Matrix3<f64>,
}

/// What the Hessian blocks need of function k at a bending point: G_k = ∂b/∂P_k, F_k =
/// G_k K_b and the geometric per-function matrices.
#[derive(Clone, Copy, Debug)]
struct BendingFactors {
    f: Matrix3<f64>,
    g: Matrix3<f64>,
    geometric: FunctionGeometry,
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
        let want_hess = out.hess.is_some();
        let mut scratch = ctx.scratch.borrow_mut();
        let ElementScratch {
            membrane,
            stresses,
            bending,
        } = &mut **scratch;
        membrane.clear();
        stresses.clear();
        bending.clear();
        if selected.contains(groups::MEMBRANE) {
            if want_hess {
                membrane.reserve(NB * self.membrane_points.len());
                stresses.reserve(self.membrane_points.len());
            }
            let hess = want_hess.then_some((&mut *membrane, &mut *stresses));
            let e = self.membrane(ctx, out.grad.as_deref_mut(), hess);
            out.add_energy(e);
        }
        if selected.contains(groups::BENDING) {
            if want_hess {
                bending.reserve(NB * self.bending_points.len());
            }
            let e = self.bending(
                ctx,
                out.grad.as_deref_mut(),
                want_hess.then_some(&mut *bending),
            );
            out.add_energy(e);
        }
        if let Some(h) = out.hess.as_deref_mut() {
            self.hessian_blocks(membrane, stresses, bending, h);
        }
    }
}
