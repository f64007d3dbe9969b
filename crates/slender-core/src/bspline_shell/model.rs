//! The B-spline shell model: patch, material, clamps, loads, and assembly of energy,
//! gradient and Hessian over the free DOFs (3 per free control point).

use crate::assembly::AssemblyInfo;
use crate::assembly::{Assembler, TermSet};
use crate::error::ModelError;
use crate::geometry::Vec3;
use crate::linalg::{ScatterPlan, SparseSymmetricMatrix, SymmetricMatrix};
use crate::rod::Grading;
use crate::scratch::Scratch;
use crate::shell::strip_guess::StripGuess;
use crate::shell::{Clamp, ShellProperties};

use super::clamp::StripEnd;
use super::element::{BsplineContext, ElementScratch, ElementTerm};
use super::gravity::add_gravity;
use super::groups;
use super::load_path::BsplineLoadPath;
use super::loads::PointLoadTerm;
use super::patch::StripPatch;
use super::state::BsplineState;

/// The element terms, by degree (the stencil size is a type parameter).
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Elements {
    /// p = 2: 9 control points, 27 slots.
    Quadratic(Vec<ElementTerm<9, 27>>),
    /// p = 3: 16 control points, 48 slots.
    Cubic(Vec<ElementTerm<16, 48>>),
    /// p = 4: 25 control points, 75 slots.
    Quartic(Vec<ElementTerm<25, 75>>),
}

/// Runs `$body` with `$t` bound to the element vector, whatever the degree.
macro_rules! with_elements {
    ($elements:expr, $t:ident => $body:expr) => {
        match $elements {
            Elements::Quadratic($t) => $body,
            Elements::Cubic($t) => $body,
            Elements::Quartic($t) => $body,
        }
    };
}
pub(crate) use with_elements;

/// A Kirchhoff–Love shell strip discretized by one tensor-product B-spline patch (C¹ for
/// degree ≥ 2), clamped at one or both ends (see the module docs of `bspline_shell`).
#[derive(Clone, Debug)]
pub struct BsplineShell {
    pub(crate) patch: StripPatch,
    pub(crate) properties: ShellProperties,
    pub(crate) grading: Grading,
    /// Which ends are clamped (indexed by [`StripEnd::index`]).
    pub(crate) clamped: [bool; 2],
    /// Clamp poses of the rest state.
    pub(crate) initial_clamps: [Clamp; 2],
    /// Free DOF of coordinate c of control point k at 3k + c (None: held by a clamp).
    pub(crate) free_of_full: Vec<Option<usize>>,
    /// Full index (3k + c) of each free DOF.
    pub(crate) full_of_free: Vec<usize>,
    pub(crate) elements: Elements,
    /// Where the elements' Hessian entries go in [`Self::sparse_hessian`]'s pattern.
    pub(crate) scatter: ScatterPlan,
    /// Gauss points in the whole patch.
    pub(crate) n_points: usize,
    /// Control-point masses m_c = ∫ρh N_c dA (kg).
    pub(crate) masses: Vec<f64>,
    pub(crate) gravity: Vec3,
    pub(crate) point_loads: Vec<PointLoadTerm>,
    pub(crate) load_path: BsplineLoadPath,
    /// Working memory of the assembly, the step cap and the first guess, kept between calls.
    pub(crate) element_scratch: Scratch<ElementScratch>,
    pub(crate) step_scratch: Scratch<Vec<Vec3>>,
    pub(crate) guess: Scratch<StripGuess>,
}

impl BsplineShell {
    /// Material and geometry.
    pub fn properties(&self) -> &ShellProperties {
        &self.properties
    }

    /// The patch (knot vectors and rest control net).
    pub fn patch(&self) -> &StripPatch {
        &self.patch
    }

    /// Degree of the B-splines.
    pub fn degree(&self) -> usize {
        self.patch.degree()
    }

    /// Elements along the length and across the width.
    pub fn elements(&self) -> (usize, usize) {
        self.patch.n_elements()
    }

    /// Distribution of the element boundaries along the length.
    pub fn grading(&self) -> Grading {
        self.grading
    }

    /// Gravity (m/s²) at load factor 1.
    pub fn gravity(&self) -> Vec3 {
        self.gravity
    }

    /// Sets gravity (m/s²) at load factor 1.
    pub fn set_gravity(&mut self, g: Vec3) {
        self.gravity = g;
    }

    /// Sets point load `k` (in the order they were built) to `force` (N at load factor 1).
    ///
    /// # Panics
    /// If there is no point load `k` (callers check the index against the scene).
    pub fn set_point_force(&mut self, k: usize, force: Vec3) {
        self.point_loads[k].force = force;
    }

    /// Sum of the point loads (N at load factor 1).
    pub fn point_load_total(&self) -> Vec3 {
        self.point_loads.iter().map(|l| l.force).sum()
    }

    /// Whether `end` is clamped.
    pub fn is_clamped(&self, end: StripEnd) -> bool {
        self.clamped[end.index()]
    }

    /// Control-point masses (kg).
    pub fn masses(&self) -> &[f64] {
        &self.masses
    }

    /// Number of free DOFs.
    pub fn n_free(&self) -> usize {
        self.full_of_free.len()
    }

    /// Free DOF index of coordinate `c` of control point `k`, if free.
    pub fn dof(&self, k: usize, c: usize) -> Option<usize> {
        self.free_of_full[3 * k + c]
    }

    /// What the load factor drives.
    pub fn load_path(&self) -> &BsplineLoadPath {
        &self.load_path
    }

    /// Sets what the load factor drives. Errors if a motion moves an end that is not clamped
    /// or is not finite, or a load factor is not finite.
    pub fn set_load_path(&mut self, path: BsplineLoadPath) -> Result<(), ModelError> {
        for m in &path.motions {
            if !self.is_clamped(m.end) {
                return Err(ModelError::structure(
                    "clamp_motion.end",
                    format!(
                        "the {:?} end is not clamped; only clamps can be moved",
                        m.end
                    ),
                ));
            }
            if !m.is_finite() {
                return Err(ModelError::structure(
                    "clamp_motion",
                    "pivot, rotation and translation must be finite",
                ));
            }
        }
        for (k, f) in path.loads.iter().enumerate() {
            if !f.is_finite() {
                return Err(ModelError::parameter(
                    if k == 0 { "loads[0]" } else { "loads[1]" },
                    *f,
                    "finite",
                ));
            }
        }
        self.load_path = path;
        Ok(())
    }

    /// Puts the clamp of `end` in `state` at pose `clamp` and moves its two control rows
    /// there. Errors if `end` is not clamped.
    pub fn set_clamp(
        &self,
        end: StripEnd,
        clamp: Clamp,
        state: &mut BsplineState,
    ) -> Result<(), ModelError> {
        if !self.is_clamped(end) {
            return Err(ModelError::structure(
                "clamp",
                format!("the {end:?} end is not clamped"),
            ));
        }
        state.clamps[end.index()] = clamp;
        self.apply_clamps(state);
        Ok(())
    }

    /// Puts the clamped control rows of `state` where its clamps hold them.
    pub fn apply_clamps(&self, state: &mut BsplineState) {
        let (n_u, n_v) = (self.patch.n_u(), self.patch.n_v());
        for end in StripEnd::BOTH {
            if !self.is_clamped(end) {
                continue;
            }
            let clamp = state.clamps[end.index()];
            for i in end.held_rows(n_u) {
                for j in 0..n_v {
                    let c = self.patch.control(i, j);
                    state.control_points[c] = clamp.position(&self.patch.rest_points[c]);
                }
            }
        }
    }

    /// The rest state: the flat strip placed rigidly by the start clamp's pose (by the end
    /// clamp's if the start is free), the clamped rows where their clamps hold them.
    pub fn rest_state(&self) -> BsplineState {
        let placement = if self.is_clamped(StripEnd::Start) {
            self.initial_clamps[0]
        } else {
            self.initial_clamps[1]
        };
        let mut s = BsplineState {
            control_points: self
                .patch
                .rest_points
                .iter()
                .map(|p| placement.position(p))
                .collect(),
            clamps: self.initial_clamps,
            membrane_remainder: Vec::new(),
        };
        self.apply_clamps(&mut s);
        s
    }

    /// The surface point at rest parameters (u, v) (m; u ∈ [0, L] along the length, v ∈
    /// [−w/2, w/2] across) of `state`.
    pub fn point(&self, state: &BsplineState, u: f64, v: f64) -> Vec3 {
        self.patch.point(&state.control_points, u, v)
    }

    /// A triangulation of the surface of `state` for pictures: `per_element` × `per_element`
    /// quads per element (each split in two), vertices by rows along the length.
    pub fn tessellate(
        &self,
        state: &BsplineState,
        per_element: usize,
    ) -> (Vec<Vec3>, Vec<[usize; 3]>) {
        let k = per_element.max(1);
        let params = |bp: &[f64]| -> Vec<f64> {
            let mut out = Vec::new();
            for w in bp.windows(2) {
                for s in 0..k {
                    out.push(w[0] + (w[1] - w[0]) * s as f64 / k as f64);
                }
            }
            out.push(*bp.last().expect("at least two breakpoints"));
            out
        };
        let us = params(self.patch.knots_u.breakpoints());
        let vs = params(self.patch.knots_v.breakpoints());
        let positions: Vec<Vec3> = us
            .iter()
            .flat_map(|&u| vs.iter().map(move |&v| (u, v)))
            .map(|(u, v)| self.point(state, u, v))
            .collect();
        let nv = vs.len();
        let mut triangles = Vec::new();
        for i in 0..us.len() - 1 {
            for j in 0..nv - 1 {
                let (a, b, c, d) = (
                    i * nv + j,
                    (i + 1) * nv + j,
                    (i + 1) * nv + j + 1,
                    i * nv + j + 1,
                );
                // Counter-clockwise about the rest normal +y.
                triangles.push([a, d, c]);
                triangles.push([a, c, b]);
            }
        }
        (positions, triangles)
    }

    /// A zero sparse Hessian whose pattern holds every pair of free DOFs of an element (the
    /// pattern of the model's scatter plan).
    pub fn sparse_hessian(&self) -> SparseSymmetricMatrix {
        SparseSymmetricMatrix::zeros_of(&self.scatter)
    }

    /// The zero Hessian of `elements` over `n_free` DOFs and the plan of the elements' scatter
    /// into it (built once with the model).
    pub(crate) fn hessian_plan(elements: &Elements, n_free: usize) -> ScatterPlan {
        let mut pairs = Vec::new();
        with_elements!(elements, terms => {
            for t in terms {
                let idx: Vec<usize> = t.dofs.iter().copied().filter(|&i| i != crate::assembly::FIXED).collect();
                for (a, &i) in idx.iter().enumerate() {
                    for &j in &idx[..a] {
                        pairs.push((i, j));
                    }
                }
            }
        });
        let hessian = SparseSymmetricMatrix::from_pattern(n_free, pairs);
        with_elements!(elements, terms => hessian.scatter_plan(terms.iter().map(|t| &t.dofs)))
    }

    /// Energy (J) of the selected term groups at load factor `load`.
    pub fn energy_terms(&self, s: &BsplineState, load: f64, terms: TermSet) -> f64 {
        let mut asm = Assembler::<SparseSymmetricMatrix>::energy_only(terms);
        self.assemble_into(s, load, &mut asm);
        asm.finish().energy
    }

    /// Energy, gradient (free DOFs) and Hessian of the selected term groups at load factor
    /// `load`. `grad` and `abs_grad` are overwritten; `hess` is zeroed first.
    pub fn assemble_terms<M: SymmetricMatrix>(
        &self,
        s: &BsplineState,
        load: f64,
        terms: TermSet,
        grad: Option<&mut [f64]>,
        hess: Option<&mut M>,
        abs_grad: Option<&mut [f64]>,
    ) -> AssemblyInfo {
        let mut asm = Assembler::new(terms, grad, hess, abs_grad);
        self.assemble_into(s, load, &mut asm);
        asm.finish()
    }

    /// Runs the term groups through `asm`: membrane and bending per element, then the
    /// self-weight and the point loads.
    pub fn assemble_into<M: SymmetricMatrix>(
        &self,
        s: &BsplineState,
        load: f64,
        asm: &mut Assembler<'_, M>,
    ) {
        let factor = self.load_path.load_factor(load);
        self.element_scratch.with(|scratch| {
            let ctx = BsplineContext::new(s, scratch);
            with_elements!(&self.elements, terms => asm.terms_planned(&ctx, terms, Some(&self.scatter)));
        });
        let points = &s.control_points;
        if asm.selects(groups::GRAVITY) {
            let g = self.gravity * factor;
            add_gravity(
                asm,
                &self.masses,
                points,
                &self.patch.rest_points,
                &g,
                |k, c| self.dof(k, c),
            );
        }
        if asm.selects(groups::POINT_LOADS) {
            for load in &self.point_loads {
                let f = load.force * factor;
                asm.external_force(f.amax());
                for &(k, w) in &load.weights {
                    asm.load(w * f.dot(&(points[k] - self.patch.rest_points[k])), 0.0);
                    for c in 0..3 {
                        if let Some(i) = self.dof(k, c) {
                            asm.generalized_force(i, w * f[c]);
                        }
                    }
                }
            }
        }
    }
}
