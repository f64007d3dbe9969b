//! Derivatives of a model's energy at states that move nonlinearly with the unknown: the
//! quadrature nodes xₙ ⊕ s·(y ⊖ xₙ) of the energy-conserving scheme, whose frames turn by
//! e(s·log(y ⊖ xₙ)) from xₙ while Newton moves y by spatial increments.
//!
//! Each node's energy is assembled as usual, but into a [`PulledBack`] record: its Hessian
//! blocks are carried to the unknown's chart as they arrive (a frame's block by the 3×3
//! Jacobian T of its node increment ζ(δ), the chain e(s φ(δ)) with φ the log map,
//! [`crate::lie::LogChart`] and [`crate::lie::ExpChart`]; coordinates by s), and summed over
//! the nodes per pair of DOF groups (a frame's rotation components, or up to three
//! coordinates). Its gradient is kept per node, then carried (Tᵀg) and summed, and its
//! contraction with ζ's second derivative added to each frame's block: the exact derivatives
//! of Σ wᵢ E(nodeᵢ(y))/sᵢ. The sum goes into the caller's assembler once per assembly.

use nalgebra::{Matrix3, SMatrix, SVector, Vector3};

use crate::assembly::{Assembler, FIXED};
use crate::lie::{ExpChart, LogChart};
use crate::linalg::{FactorError, Inertia, SymmetricFactor, SymmetricMatrix};

use super::frames::FrameInertia;

/// How a group's DOFs move per unit of the unknown's: a frame's 3×3 Jacobian, or a scale
/// (coordinates).
#[derive(Clone, Copy, Debug)]
enum Transform {
    Frame(Matrix3<f64>),
    Scale(f64),
}

impl Transform {
    /// Tᵀ B U for the block B between a group with this transform (rows) and one with `u`.
    fn apply(&self, b: &Matrix3<f64>, u: &Transform) -> Matrix3<f64> {
        match (self, u) {
            (Self::Scale(s), Self::Scale(t)) => b * (s * t),
            (Self::Scale(s), Self::Frame(t)) => b * t * *s,
            (Self::Frame(t), Self::Scale(s)) => t.transpose() * b * *s,
            (Self::Frame(t), Self::Frame(u)) => t.transpose() * b * u,
        }
    }

    /// Tᵀ g.
    fn pull(&self, g: &Vector3<f64>) -> Vector3<f64> {
        match self {
            Self::Scale(s) => g * *s,
            Self::Frame(t) => t.transpose() * g,
        }
    }

    /// |T|ᵀ a: the round-off scale carried like the gradient.
    fn pull_abs(&self, a: &Vector3<f64>) -> Vector3<f64> {
        match self {
            Self::Scale(s) => a * s.abs(),
            Self::Frame(t) => t.abs().transpose() * a,
        }
    }
}

/// A symmetric matrix kept as 3×3 blocks per pair of DOF groups (each frame's rotation
/// components; the other DOFs in consecutive runs of up to three), into which the blocks
/// of several assemblies are summed after a per-group [`Transform`]: the record of the
/// quadrature nodes' Hessians. Row `a` holds the blocks (a, b ≤ a), rows of group a and
/// columns of group b. It is never factored (its [`SymmetricFactor`] refuses), and it is
/// cleared by [`PulledBack::begin`] only: [`SymmetricMatrix::set_zero`], which each node's
/// assembler calls, keeps what the earlier nodes added.
#[derive(Clone, Debug)]
pub(crate) struct BlockHessian {
    /// Group and component of every free DOF.
    slot: Vec<(usize, usize)>,
    /// The free DOFs of every group ([`FIXED`] on unused components).
    groups: Vec<[usize; 3]>,
    /// Number of frame groups (the first ones).
    n_frames: usize,
    /// The current node's transform of every group.
    transforms: Vec<Transform>,
    rows: Vec<Vec<(usize, Matrix3<f64>)>>,
}

impl BlockHessian {
    fn new(n: usize, frames: &[FrameInertia]) -> Self {
        let mut slot = vec![(usize::MAX, 0); n];
        let mut groups = Vec::new();
        for f in frames {
            for (k, &i) in f.dofs.iter().enumerate() {
                if i != FIXED {
                    slot[i] = (groups.len(), k);
                }
            }
            groups.push(f.dofs);
        }
        let mut run = [FIXED; 3];
        let mut len = 0;
        for (i, si) in slot.iter_mut().enumerate() {
            if si.0 != usize::MAX {
                continue;
            }
            *si = (groups.len(), len);
            run[len] = i;
            len += 1;
            if len == 3 {
                groups.push(run);
                (run, len) = ([FIXED; 3], 0);
            }
        }
        if len > 0 {
            groups.push(run);
        }
        Self {
            slot,
            transforms: vec![Transform::Scale(1.0); groups.len()],
            rows: vec![Vec::new(); groups.len()],
            n_frames: frames.len(),
            groups,
        }
    }

    fn clear(&mut self) {
        self.rows.iter_mut().for_each(Vec::clear);
    }

    /// The stored block (a, b), a ≥ b, created empty if absent.
    fn block_mut(&mut self, a: usize, b: usize) -> &mut Matrix3<f64> {
        let row = &mut self.rows[a];
        let k = match row.iter().position(|(c, _)| *c == b) {
            Some(k) => k,
            None => {
                row.push((b, Matrix3::zeros()));
                row.len() - 1
            }
        };
        &mut row[k].1
    }

    fn block(&self, a: usize, b: usize) -> Option<&Matrix3<f64>> {
        self.rows[a].iter().find(|(c, _)| *c == b).map(|(_, m)| m)
    }

    /// Adds `b` (rows of group `ga`, columns of `gb`, in the node's chart) carried to the
    /// unknown's.
    fn add_transformed(&mut self, ga: usize, gb: usize, b: &Matrix3<f64>) {
        let m = self.transforms[ga].apply(b, &self.transforms[gb]);
        if ga >= gb {
            *self.block_mut(ga, gb) += m;
        } else {
            *self.block_mut(gb, ga) += m.transpose();
        }
    }

    fn entry(&self, i: usize, j: usize) -> f64 {
        let ((gi, ci), (gj, cj)) = (self.slot[i], self.slot[j]);
        if gi >= gj {
            self.block(gi, gj).map_or(0.0, |b| b[(ci, cj)])
        } else {
            self.block(gj, gi).map_or(0.0, |b| b[(cj, ci)])
        }
    }
}

/// Never built: a [`BlockHessian`] only carries blocks to the pullback.
#[derive(Clone, Debug, Default)]
pub(crate) struct NoFactor;

impl SymmetricFactor<BlockHessian> for NoFactor {
    fn factorize(&mut self, _: &BlockHessian, _: f64) -> Result<Inertia, FactorError> {
        Err(FactorError::Analysis {
            reason: "a record of quadrature nodes is not factored".into(),
        })
    }

    fn try_solve_in_place(&self, _: &mut [f64]) -> Result<(), FactorError> {
        Err(FactorError::NotFactored)
    }
}

impl SymmetricMatrix for BlockHessian {
    type Factor = NoFactor;

    fn dim(&self) -> usize {
        self.slot.len()
    }

    /// Keeps the blocks: the record sums the nodes of one assembly (see the type's docs).
    fn set_zero(&mut self) {}

    fn add(&mut self, i: usize, j: usize, v: f64) {
        let ((gi, ci), (gj, cj)) = (self.slot[i], self.slot[j]);
        let mut b = Matrix3::zeros();
        b[(ci, cj)] += v;
        if gi == gj && i != j {
            b[(cj, ci)] += v;
        }
        self.add_transformed(gi, gj, &b);
    }

    fn add_lower_block<const D: usize>(
        &mut self,
        dofs: &[usize; D],
        value: impl Fn(usize, usize) -> f64,
    ) {
        // The default's additions (one per lower pair of slots, twice for two slots naming
        // one DOF), gathered per pair of groups and carried once per pair.
        let mut group = [usize::MAX; D];
        let mut comp = [0; D];
        for a in 0..D {
            if dofs[a] != FIXED {
                (group[a], comp[a]) = self.slot[dofs[a]];
            }
        }
        let mut distinct = [usize::MAX; D];
        let mut n_distinct = 0;
        for &g in &group {
            if g != usize::MAX && !distinct[..n_distinct].contains(&g) {
                distinct[n_distinct] = g;
                n_distinct += 1;
            }
        }
        for p in 0..n_distinct {
            for q in 0..=p {
                let (g1, g2) = (distinct[p], distinct[q]);
                // Rows of g1, columns of g2.
                let mut b = Matrix3::zeros();
                for x in 0..D {
                    for y in 0..=x {
                        let (gx, gy) = (group[x], group[y]);
                        if gx == g1 && gy == g2 {
                            let v = value(x, y);
                            if g1 == g2 {
                                if dofs[x] == dofs[y] && x != y {
                                    b[(comp[x], comp[x])] += 2.0 * v;
                                } else {
                                    b[(comp[x], comp[y])] += v;
                                    if comp[x] != comp[y] {
                                        b[(comp[y], comp[x])] += v;
                                    }
                                }
                            } else {
                                b[(comp[x], comp[y])] += v;
                            }
                        } else if g1 != g2 && gx == g2 && gy == g1 {
                            b[(comp[y], comp[x])] += value(x, y);
                        }
                    }
                }
                self.add_transformed(g1, g2, &b);
            }
        }
    }

    fn diagonal(&self, i: usize) -> f64 {
        self.entry(i, i)
    }

    fn mul_vec(&self, x: &[f64], y: &mut [f64]) {
        y.fill(0.0);
        for (ga, row) in self.rows.iter().enumerate() {
            for (gb, b) in row {
                let (da, db) = (self.groups[ga], self.groups[*gb]);
                for (r, &i) in da.iter().enumerate() {
                    for (c, &j) in db.iter().enumerate() {
                        if i == FIXED || j == FIXED {
                            continue;
                        }
                        y[i] += b[(r, c)] * x[j];
                        if ga != *gb {
                            y[j] += b[(r, c)] * x[i];
                        }
                    }
                }
            }
        }
    }

    fn gershgorin_bounds(&self) -> (f64, f64) {
        let n = self.dim();
        if n == 0 {
            return (0.0, 0.0);
        }
        let mut radius = vec![0.0; n];
        for (ga, row) in self.rows.iter().enumerate() {
            for (gb, b) in row {
                let (da, db) = (self.groups[ga], self.groups[*gb]);
                for (r, &i) in da.iter().enumerate() {
                    for (c, &j) in db.iter().enumerate() {
                        if i == FIXED || j == FIXED || i == j {
                            continue;
                        }
                        radius[i] += b[(r, c)].abs();
                        if ga != *gb {
                            radius[j] += b[(r, c)].abs();
                        }
                    }
                }
            }
        }
        (0..n).fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), i| {
            let d = self.diagonal(i);
            (lo.min(d - radius[i]), hi.max(d + radius[i]))
        })
    }

    fn first_non_finite(&self) -> Option<usize> {
        self.rows.iter().enumerate().find_map(|(ga, row)| {
            row.iter()
                .any(|(_, b)| b.iter().any(|v| !v.is_finite()))
                .then(|| {
                    self.groups[ga]
                        .into_iter()
                        .find(|&i| i != FIXED)
                        .unwrap_or(0)
                })
        })
    }

    fn congruence_scaled(&self, s: &[f64], out: &mut Self) {
        out.clone_from(self);
        for (ga, row) in out.rows.iter_mut().enumerate() {
            for (gb, b) in row.iter_mut() {
                let (da, db) = (self.groups[ga], self.groups[*gb]);
                for (r, &i) in da.iter().enumerate() {
                    for (c, &j) in db.iter().enumerate() {
                        if i != FIXED && j != FIXED {
                            b[(r, c)] *= s[i] * s[j];
                        }
                    }
                }
            }
        }
    }
}

/// How a node's frame increment ζ depends on the unknown's spatial increment δ of that frame:
/// ζ(δ) = log(e(s φ(δ)) ⊗ ē(s φ₀)), φ(δ) = log(e(δ) ⊗ q₀) the frame's rotation vector from xₙ.
#[derive(Clone, Copy, Debug)]
pub(crate) struct NodeFrameMap {
    /// ∂ζ/∂δ = J_l(s φ₀) · s · J_l(φ₀)⁻¹.
    pub(crate) jac: Matrix3<f64>,
    s: f64,
    log: LogChart,
    exp: ExpChart,
}

impl NodeFrameMap {
    /// The map of node `s` ∈ (0, 1] given the log chart `log` of the frame at the unknown.
    pub(crate) fn new(log: &LogChart, s: f64) -> Self {
        let exp = ExpChart::new(&(log.value * s));
        Self {
            jac: exp.jac * log.jac * s,
            s,
            log: *log,
            exp,
        }
    }

    /// Σ_k g_k ∂²ζ_k/∂δ² (3×3) for the node gradient `g` (in the node's chart).
    pub(crate) fn contracted_hessian(&self, g: &Vector3<f64>) -> Matrix3<f64> {
        let a = self.log.jac * self.s;
        a.transpose() * self.exp.contracted_hessian(g) * a
            + self
                .log
                .contracted_hessian(&(self.exp.jac.transpose() * g * self.s))
    }
}

/// The quadrature nodes of one assembly, summed in the unknown's chart.
#[derive(Clone, Debug)]
pub(crate) struct PulledBack {
    /// The current node's gradient and round-off scale (its own chart).
    pub(crate) node_grad: Vec<f64>,
    pub(crate) node_abs: Vec<f64>,
    /// The nodes' Hessian, carried and summed.
    pub(crate) hess: BlockHessian,
    grad: Vec<f64>,
    abs: Vec<f64>,
}

impl PulledBack {
    pub(crate) fn new(n: usize, frames: &[FrameInertia]) -> Self {
        Self {
            node_grad: vec![0.0; n],
            node_abs: vec![0.0; n],
            hess: BlockHessian::new(n, frames),
            grad: vec![0.0; n],
            abs: vec![0.0; n],
        }
    }

    /// Starts an assembly: nothing recorded.
    pub(crate) fn begin(&mut self) {
        self.hess.clear();
        self.grad.fill(0.0);
        self.abs.fill(0.0);
    }

    /// Sets the transforms of the next node (`maps`: its frames', in order; `s`: its
    /// coordinates'), before the node is assembled into `node_grad`, `node_abs` and `hess`.
    pub(crate) fn set_node(&mut self, maps: &[NodeFrameMap], s: f64) {
        let h = &mut self.hess;
        for (t, m) in h.transforms.iter_mut().zip(maps) {
            *t = Transform::Frame(m.jac);
        }
        for t in h.transforms.iter_mut().skip(h.n_frames) {
            *t = Transform::Scale(s);
        }
    }

    /// After a node's assembly: carries its gradient into the sum and, with `hessian`, adds
    /// the contraction of its frames' gradients with their maps' second derivatives.
    pub(crate) fn end_node(&mut self, maps: &[NodeFrameMap], hessian: bool) {
        let h = &mut self.hess;
        let gather = |v: &[f64], dofs: &[usize; 3]| {
            Vector3::from_fn(|k, _| if dofs[k] == FIXED { 0.0 } else { v[dofs[k]] })
        };
        for g in 0..h.groups.len() {
            let dofs = &h.groups[g];
            let t = h.transforms[g];
            let node = gather(&self.node_grad, dofs);
            let pulled = t.pull(&node);
            let abs = t.pull_abs(&gather(&self.node_abs, dofs));
            for (k, &i) in dofs.iter().enumerate() {
                if i != FIXED {
                    self.grad[i] += pulled[k];
                    self.abs[i] += abs[k];
                }
            }
            let _ = dofs;
            if hessian && g < maps.len() {
                let c = maps[g].contracted_hessian(&node);
                *h.block_mut(g, g) += c;
            }
        }
    }

    /// Adds the summed nodes (gradient, and Hessian if `hessian`) to `asm`.
    pub(crate) fn add_to<M: SymmetricMatrix>(&self, hessian: bool, asm: &mut Assembler<'_, M>) {
        // The gradient as two generalized forces per DOF whose magnitudes sum to its round-off
        // scale (the assembler adds |force| to the scale per call).
        for (i, (&g, &a)) in self.grad.iter().zip(&self.abs).enumerate() {
            let a = a.max(g.abs());
            asm.generalized_force(i, -0.5 * (g + a));
            asm.generalized_force(i, -0.5 * (g - a));
        }
        if !hessian {
            return;
        }
        let groups = &self.hess.groups;
        let zero3 = Vector3::zeros();
        for (ga, row) in self.hess.rows.iter().enumerate() {
            for (gb, b) in row {
                if ga == *gb {
                    asm.local(&groups[ga], 0.0, 0.0, &zero3, b);
                } else {
                    let (da, db) = (groups[ga], groups[*gb]);
                    let stencil = [da[0], da[1], da[2], db[0], db[1], db[2]];
                    let mut m = SMatrix::<f64, 6, 6>::zeros();
                    m.fixed_view_mut::<3, 3>(0, 3).copy_from(b);
                    m.fixed_view_mut::<3, 3>(3, 0).copy_from(&b.transpose());
                    asm.local(&stencil, 0.0, 0.0, &SVector::<f64, 6>::zeros(), &m);
                }
            }
        }
    }
}
