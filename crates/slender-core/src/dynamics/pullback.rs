//! Derivatives of a model's energy at a state that moves nonlinearly with the unknown: the
//! quadrature nodes xₙ ⊕ s·(y ⊖ xₙ) of the energy-conserving scheme, whose frames turn by
//! e(s·log(y ⊖ xₙ)) from xₙ while Newton moves y by spatial increments.
//!
//! A node's energy is assembled as usual into a [`BlockHessian`] (the model's local blocks
//! summed per pair of DOF groups: a frame's three rotation components, or one coordinate),
//! then carried to the unknown's chart: a coordinate moves by s per unit of its own, a frame
//! by the 3×3 Jacobian T of its node increment ζ(δ) (the chain e(s φ(δ)) with φ the log map,
//! [`crate::lie::LogChart`] and [`crate::lie::ExpChart`]). The Hessian becomes Tᵀ H T plus
//! the contraction of the node's gradient with ζ's second derivative on each frame's block,
//! the gradient Tᵀ g: the exact derivatives of the node energy as a function of y.

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

use nalgebra::{Matrix3, SMatrix, SVector, Vector3};

use crate::assembly::{Assembler, FIXED};
use crate::lie::{ExpChart, LogChart};
use crate::linalg::{FactorError, Inertia, SymmetricFactor, SymmetricMatrix};

use super::frames::FrameInertia;

/// A cheap hasher for pairs of group indices (the blocks are keyed by them, and hashed once
/// per pair of groups a term touches).
#[derive(Clone, Copy, Debug, Default)]
struct PairHasher(u64);

impl Hasher for PairHasher {
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(u64::from(b));
        }
    }

    fn write_u64(&mut self, i: u64) {
        self.0 = (self.0.rotate_left(5) ^ i).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }

    fn write_usize(&mut self, i: usize) {
        self.write_u64(i as u64);
    }

    fn finish(&self) -> u64 {
        self.0
    }
}

type Blocks = HashMap<(usize, usize), [f64; 9], BuildHasherDefault<PairHasher>>;

/// A symmetric matrix kept as dense 3×3 blocks per pair of DOF groups (a frame's rotation
/// components, or one coordinate as a 1×1 block): what a node's assembly is recorded in before
/// its pullback. Block (a, b) with a ≥ b holds rows of group a and columns of group b;
/// the matrix is never factored (its [`SymmetricFactor`] refuses).
#[derive(Clone, Debug)]
pub(crate) struct BlockHessian {
    /// Group and component of every free DOF.
    slot: Vec<(usize, usize)>,
    /// The free DOFs of every group ([`FIXED`] on unused components).
    groups: Vec<[usize; 3]>,
    blocks: Blocks,
}

impl BlockHessian {
    /// Groups: each frame of `frames` (in order), then every DOF of `n` that no frame holds.
    pub(crate) fn new(n: usize, frames: &[FrameInertia]) -> Self {
        let mut slot = vec![(usize::MAX, 0); n];
        let mut groups = Vec::with_capacity(n);
        for f in frames {
            for (k, &i) in f.dofs.iter().enumerate() {
                if i != FIXED {
                    slot[i] = (groups.len(), k);
                }
            }
            groups.push(f.dofs);
        }
        for (i, s) in slot.iter_mut().enumerate() {
            if s.0 == usize::MAX {
                *s = (groups.len(), 0);
                groups.push([i, FIXED, FIXED]);
            }
        }
        Self {
            slot,
            groups,
            blocks: Blocks::default(),
        }
    }

    /// Adds v to entry (i, j) of the block of their groups (and (j, i) inside one group).
    fn add_entry(&mut self, i: usize, j: usize, v: f64) {
        let ((gi, ci), (gj, cj)) = (self.slot[i], self.slot[j]);
        if gi == gj {
            let b = self.blocks.entry((gi, gi)).or_insert([0.0; 9]);
            b[3 * ci + cj] += v;
            if ci != cj {
                b[3 * cj + ci] += v;
            }
        } else if gi > gj {
            self.blocks.entry((gi, gj)).or_insert([0.0; 9])[3 * ci + cj] += v;
        } else {
            self.blocks.entry((gj, gi)).or_insert([0.0; 9])[3 * cj + ci] += v;
        }
    }

    fn entry(&self, i: usize, j: usize) -> f64 {
        let ((gi, ci), (gj, cj)) = (self.slot[i], self.slot[j]);
        let (key, idx) = if gi >= gj {
            ((gi, gj), 3 * ci + cj)
        } else {
            ((gj, gi), 3 * cj + ci)
        };
        self.blocks.get(&key).map_or(0.0, |b| b[idx])
    }
}

/// Never built: a [`BlockHessian`] only carries blocks to the pullback.
#[derive(Clone, Debug, Default)]
pub(crate) struct NoFactor;

impl SymmetricFactor<BlockHessian> for NoFactor {
    fn factorize(&mut self, _: &BlockHessian, _: f64) -> Result<Inertia, FactorError> {
        Err(FactorError::Analysis {
            reason: "a block record of a quadrature node is not factored".into(),
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

    fn set_zero(&mut self) {
        // Keys change with the state's pattern of contributions; the map keeps its capacity.
        self.blocks.clear();
    }

    fn add(&mut self, i: usize, j: usize, v: f64) {
        self.add_entry(i, j, v);
    }

    fn add_lower_block<const D: usize>(
        &mut self,
        dofs: &[usize; D],
        value: impl Fn(usize, usize) -> f64,
    ) {
        // The default's additions (one per lower pair of slots, twice for two slots naming
        // one DOF), with the block looked up once per pair of groups instead of per entry.
        let mut group = [usize::MAX; D];
        let mut comp = [0; D];
        for a in 0..D {
            if dofs[a] != FIXED {
                (group[a], comp[a]) = self.slot[dofs[a]];
            }
        }
        // Distinct groups of the stencil, in order of first appearance.
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
                let (hi, lo) = if g1 >= g2 { (g1, g2) } else { (g2, g1) };
                let block = self.blocks.entry((hi, lo)).or_insert([0.0; 9]);
                for a in 0..D {
                    for b in 0..=a {
                        let (ga, gb) = (group[a], group[b]);
                        if !((ga == g1 && gb == g2) || (ga == g2 && gb == g1)) {
                            continue;
                        }
                        let v = value(a, b);
                        if hi == lo {
                            if dofs[a] == dofs[b] && a != b {
                                block[3 * comp[a] + comp[a]] += 2.0 * v;
                            } else {
                                block[3 * comp[a] + comp[b]] += v;
                                if comp[a] != comp[b] {
                                    block[3 * comp[b] + comp[a]] += v;
                                }
                            }
                        } else if ga == hi {
                            block[3 * comp[a] + comp[b]] += v;
                        } else {
                            block[3 * comp[b] + comp[a]] += v;
                        }
                    }
                }
            }
        }
    }

    fn diagonal(&self, i: usize) -> f64 {
        self.entry(i, i)
    }

    fn mul_vec(&self, x: &[f64], y: &mut [f64]) {
        y.fill(0.0);
        for (&(ga, gb), b) in &self.blocks {
            let (da, db) = (self.groups[ga], self.groups[gb]);
            for (r, &i) in da.iter().enumerate() {
                if i == FIXED {
                    continue;
                }
                for (c, &j) in db.iter().enumerate() {
                    if j == FIXED {
                        continue;
                    }
                    let v = b[3 * r + c];
                    y[i] += v * x[j];
                    if ga != gb {
                        y[j] += v * x[i];
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
        for (&(ga, gb), b) in &self.blocks {
            let (da, db) = (self.groups[ga], self.groups[gb]);
            for (r, &i) in da.iter().enumerate() {
                for (c, &j) in db.iter().enumerate() {
                    if i == FIXED || j == FIXED || i == j {
                        continue;
                    }
                    let v = b[3 * r + c].abs();
                    radius[i] += v;
                    if ga != gb {
                        radius[j] += v;
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
        self.blocks.iter().find_map(|(&(ga, _), b)| {
            b.iter()
                .any(|v| !v.is_finite())
                .then(|| self.groups[ga].into_iter().find(|&i| i != FIXED).unwrap_or(0))
        })
    }

    fn congruence_scaled(&self, s: &[f64], out: &mut Self) {
        out.clone_from(self);
        for (&(ga, gb), b) in out.blocks.iter_mut() {
            let (da, db) = (self.groups[ga], self.groups[gb]);
            for (r, &i) in da.iter().enumerate() {
                for (c, &j) in db.iter().enumerate() {
                    if i != FIXED && j != FIXED {
                        b[3 * r + c] *= s[i] * s[j];
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
            + self.log.contracted_hessian(&(self.exp.jac.transpose() * g * self.s))
    }
}

/// Scratch outputs of one node's assembly.
#[derive(Clone, Debug)]
pub(crate) struct NodeRecord {
    pub(crate) grad: Vec<f64>,
    pub(crate) abs_grad: Vec<f64>,
    pub(crate) hess: BlockHessian,
}

/// Adds gradient `g` with round-off scale `a` (≥ |g| per slot) on `dofs` to `asm`: the
/// assembler adds |g| to its scale per call, so the gradient goes in as two halves whose
/// magnitudes sum to `a`.
fn add_gradient<M: SymmetricMatrix, const D: usize>(
    asm: &mut Assembler<'_, M>,
    dofs: &[usize; D],
    g: &SVector<f64, D>,
    a: &SVector<f64, D>,
) {
    let a = a.zip_map(g, |a, g| a.max(g.abs()));
    let zero = SMatrix::<f64, D, D>::zeros();
    asm.local(dofs, 0.0, 0.0, &((g + a) * 0.5), &zero);
    asm.local(dofs, 0.0, 0.0, &((g - a) * 0.5), &zero);
}

impl NodeRecord {
    pub(crate) fn new(n: usize, frames: &[FrameInertia]) -> Self {
        Self {
            grad: vec![0.0; n],
            abs_grad: vec![0.0; n],
            hess: BlockHessian::new(n, frames),
        }
    }

    /// The group transforms: a frame's node map, or s on a coordinate (as a 3×3 whose (0, 0)
    /// entry is used).
    fn transform(&self, group: usize, maps: &[NodeFrameMap], s: f64) -> Matrix3<f64> {
        if group < maps.len() {
            maps[group].jac
        } else {
            Matrix3::from_diagonal(&Vector3::new(s, 0.0, 0.0))
        }
    }

    /// Adds the recorded node (gradient, and Hessian if `hessian`) to `asm`, carried to the
    /// unknown's chart: coordinates scaled by `s`, frame f by `maps[f]`.
    pub(crate) fn add_to<M: SymmetricMatrix>(
        &self,
        maps: &[NodeFrameMap],
        s: f64,
        hessian: bool,
        asm: &mut Assembler<'_, M>,
    ) {
        let groups = &self.hess.groups;
        let gather = |v: &[f64], dofs: &[usize; 3]| {
            Vector3::from_fn(|k, _| if dofs[k] == FIXED { 0.0 } else { v[dofs[k]] })
        };
        // Frames: gradient Tᵀg, and the diagonal block Tᵀ H T + Σ g_k ∂²ζ_k.
        for (f, map) in maps.iter().enumerate() {
            let dofs = &groups[f];
            let g = gather(&self.grad, dofs);
            let a = gather(&self.abs_grad, dofs);
            let t = map.jac;
            add_gradient(asm, dofs, &(t.transpose() * g), &(t.abs().transpose() * a));
            if hessian {
                let mut h = match self.hess.blocks.get(&(f, f)) {
                    Some(b) => t.transpose() * Matrix3::from_row_slice(b) * t,
                    None => Matrix3::zeros(),
                };
                h += map.contracted_hessian(&g);
                asm.local(dofs, 0.0, 0.0, &Vector3::zeros(), &h);
            }
        }
        // Coordinates: gradient s·g.
        for (group, dofs) in groups.iter().enumerate().skip(maps.len()) {
            let i = dofs[0];
            let _ = group;
            add_gradient(
                asm,
                &[i],
                &SVector::<f64, 1>::new(s * self.grad[i]),
                &SVector::<f64, 1>::new(s * self.abs_grad[i]),
            );
        }
        if !hessian {
            return;
        }
        for (&(ga, gb), b) in &self.hess.blocks {
            if ga == gb && ga < maps.len() {
                continue; // a frame's own block, done above
            }
            let h = self.transform(ga, maps, s).transpose()
                * Matrix3::from_row_slice(b)
                * self.transform(gb, maps, s);
            if ga == gb {
                asm.local(&groups[ga], 0.0, 0.0, &Vector3::zeros(), &h);
            } else {
                let (da, db) = (groups[ga], groups[gb]);
                let stencil = [da[0], da[1], da[2], db[0], db[1], db[2]];
                let mut m = SMatrix::<f64, 6, 6>::zeros();
                m.fixed_view_mut::<3, 3>(3, 0).copy_from(&h.transpose());
                m.fixed_view_mut::<3, 3>(0, 3).copy_from(&h);
                asm.local(&stencil, 0.0, 0.0, &SVector::<f64, 6>::zeros(), &m);
            }
        }
    }
}
