//! A discrete Cosserat rod ready to be solved, and the assembly of its terms.

use crate::assembly::{Assembler, TermSet};
use crate::framed::full_stencil::OnFullStencil;
use crate::framed::groups::EXTERNAL;
use crate::framed::{FramedCore, FramedState};
use crate::lie::DarbouxMeasure;
use crate::linalg::{SymmetricBandMatrix, SymmetricMatrix};
use crate::rod::SupportReaction;

use super::bend_twist::BendTwistTerm;
use super::stretch_shear::StretchShearTerm;

/// A discrete Cosserat rod (see the module docs). It dereferences to its [`FramedCore`]:
/// supports, loads, masses, rest state, load path and the shared accessors.
#[derive(Clone, Debug)]
pub struct CosseratRod {
    pub(crate) core: FramedCore,
    pub(crate) stretch_shear: Vec<StretchShearTerm>,
    pub(crate) bend_twist: Vec<BendTwistTerm>,
    pub(crate) measure: DarbouxMeasure,
}

/// What a Cosserat term is evaluated at.
pub struct CosseratContext<'a> {
    /// The rod.
    pub rod: &'a CosseratRod,
    /// The state.
    pub state: &'a FramedState,
}

impl std::ops::Deref for CosseratRod {
    type Target = FramedCore;

    fn deref(&self) -> &FramedCore {
        &self.core
    }
}

impl std::ops::DerefMut for CosseratRod {
    fn deref_mut(&mut self) -> &mut FramedCore {
        &mut self.core
    }
}

impl CosseratRod {
    /// The Darboux measure of the vertex terms.
    pub fn darboux_measure(&self) -> DarbouxMeasure {
        self.measure
    }

    /// Runs every term group through `asm`: extension and shear per edge, bending and twist
    /// per vertex, then the external loads.
    pub fn assemble_into<M: SymmetricMatrix>(
        &self,
        s: &FramedState,
        load: f64,
        asm: &mut Assembler<'_, M>,
    ) {
        let ctx = CosseratContext {
            rod: self,
            state: s,
        };
        asm.terms(&ctx, &self.stretch_shear);
        asm.terms(&ctx, &self.bend_twist);
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
        let ctx = CosseratContext {
            rod: self,
            state: s,
        };
        let ss: Vec<_> = self.stretch_shear.iter().map(OnFullStencil).collect();
        let bt: Vec<_> = self.bend_twist.iter().map(OnFullStencil).collect();
        asm.terms(&ctx, &ss);
        asm.terms(&ctx, &bt);
        self.core.assemble_loads(s, load, &mut asm, true);
        asm.finish();
        self.core.reactions_from_gradient(&g)
    }
}
