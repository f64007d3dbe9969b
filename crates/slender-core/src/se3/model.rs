//! An SE(3) beam ready to be solved, and the assembly of its elements.

use crate::assembly::{Assembler, TermSet};
use crate::framed::full_stencil::OnFullStencil;
use crate::framed::groups::EXTERNAL;
use crate::framed::{FramedCore, FramedState};
use crate::geometry::Vec3;
use crate::linalg::{SymmetricBandMatrix, SymmetricMatrix};
use crate::rod::SupportReaction;

use super::element::Se3Element;

/// A geometrically exact SE(3) beam (see the module docs). It dereferences to its
/// [`FramedCore`]: supports, loads, masses, rest state, load path and the shared accessors.
#[derive(Clone, Debug)]
pub struct Se3Rod {
    pub(crate) core: FramedCore,
    pub(crate) elements: Vec<Se3Element>,
}

/// What an SE(3) element is evaluated at.
pub struct Se3Context<'a> {
    /// The beam.
    pub rod: &'a Se3Rod,
    /// The state.
    pub state: &'a FramedState,
}

impl std::ops::Deref for Se3Rod {
    type Target = FramedCore;

    fn deref(&self) -> &FramedCore {
        &self.core
    }
}

impl std::ops::DerefMut for Se3Rod {
    fn deref_mut(&mut self) -> &mut FramedCore {
        &mut self.core
    }
}

impl Se3Rod {
    /// Runs every element, then the external loads, through `asm`.
    pub fn assemble_into<M: SymmetricMatrix>(
        &self,
        s: &FramedState,
        load: f64,
        asm: &mut Assembler<'_, M>,
    ) {
        let ctx = Se3Context {
            rod: self,
            state: s,
        };
        asm.terms(&ctx, &self.elements);
        if asm.selects(EXTERNAL) {
            self.core.assemble_loads(s, load, asm, false);
        }
    }

    /// Energy (J) of the selected term groups (see [`crate::framed::groups`]).
    pub fn energy_terms(&self, s: &FramedState, load: f64, terms: TermSet) -> f64 {
        let mut asm = Assembler::<SymmetricBandMatrix>::energy_only(terms);
        self.assemble_into(s, load, &mut asm);
        asm.finish().energy
    }

    /// Reactions of every support at load factor `load`, one per held vertex in increasing
    /// order. Meaningful at an equilibrium.
    pub fn reactions(&self, s: &FramedState, load: f64) -> Vec<SupportReaction> {
        let mut g = vec![0.0; self.core.dofs.n_full() + 6];
        let mut asm = Assembler::<SymmetricBandMatrix>::new(TermSet::ALL, Some(&mut g), None, None);
        let ctx = Se3Context {
            rod: self,
            state: s,
        };
        let el: Vec<_> = self.elements.iter().map(OnFullStencil).collect();
        asm.terms(&ctx, &el);
        self.core.assemble_loads(s, load, &mut asm, true);
        asm.finish();
        self.core.reactions_from_gradient(&g)
    }

    /// Points of the centerline of `s` with `per_element` subdivisions of every element along
    /// its helicoid H_A exp(ξ d), ξ = k/per_element (the element's exact interpolation).
    pub fn centerline(&self, s: &FramedState, per_element: usize) -> Vec<Vec3> {
        let m = per_element.max(1);
        let mut out = Vec::with_capacity(self.n_edges() * m + 1);
        for j in 0..self.n_edges() {
            let d = super::element::element_twist(s, j);
            let (u, t) = (Vec3::new(d[0], d[1], d[2]), Vec3::new(d[3], d[4], d[5]));
            for k in 0..m {
                let xi = k as f64 / m as f64;
                let (_, p) = crate::lie::se3::exp(&(u * xi), &(t * xi));
                out.push(s.positions[j] + s.frames[j] * p);
            }
        }
        out.push(s.positions[self.n_edges()]);
        out
    }
}
