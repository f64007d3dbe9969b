//! Building a discrete Cosserat rod: the shared input ([`FramedRodBuilder`]) with the
//! Cosserat rod's frames on the edges, clamp frames at the ends and its terms.

use crate::assembly::{Stencil, FIXED};
use crate::error::ModelError;
use crate::framed::builder::FramedRodBuilder;
use crate::framed::core::{FrameLayout, FramedCore};
use crate::framed::FramedDofs;
use crate::lie::{DarbouxMeasure, RelativeRotation};

use super::bend_twist::{BendTwistTerm, FrameRef};
use super::model::CosseratRod;
use super::stretch_shear::StretchShearTerm;

/// The Cosserat rod's own options.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CosseratOptions {
    /// How the vertex terms measure the relative rotation of neighbouring frames.
    pub darboux: DarbouxMeasure,
}

/// Builds a [`CosseratRod`]: `CosseratBuilder::new(curve, properties, shear)`, then the
/// setters of [`FramedRodBuilder`].
pub type CosseratBuilder = FramedRodBuilder<CosseratOptions>;

fn concat<const A: usize, const B: usize, const C: usize, const D: usize>(
    a: [usize; A],
    b: [usize; B],
    c: [usize; C],
) -> [usize; D] {
    let mut out = [FIXED; D];
    for (o, v) in out.iter_mut().zip(a.iter().chain(&b).chain(&c)) {
        *o = *v;
    }
    out
}

impl CosseratBuilder {
    /// The Darboux measure of the vertex terms (default [`DarbouxMeasure::Sine`]).
    pub fn darboux(mut self, measure: DarbouxMeasure) -> Self {
        self.options.darboux = measure;
        self
    }

    /// Validates the input and builds the rod.
    pub fn build(self) -> Result<CosseratRod, ModelError> {
        let geom = self.geometry()?;
        let n = geom.rest_lengths.len();
        let (frames, ends) = geom.edge_frames(self.natural_twist);
        let layout = FrameLayout {
            frame_arclengths: (0..n)
                .map(|j| 0.5 * (geom.arclengths[j] + geom.arclengths[j + 1]))
                .collect(),
            frame_lengths: geom.rest_lengths.clone(),
            mass_lengths: geom.rest_lengths.clone(),
            clamp_frames: [
                self.supports.clamp_start.then_some(ends[0]),
                self.supports.clamp_end.then_some(ends[1]),
            ],
            fixed_frames: Vec::new(),
            frames,
            moment_slot: |v, n| v.min(n - 1),
        };
        let core = FramedCore::new(&self, &geom, layout)?;
        let st = self.properties.stiffness;
        let dofs = &core.dofs;
        let rest = &core.rest;
        let stretch_shear = (0..n)
            .map(|j| {
                let h = geom.rest_lengths[j];
                let r = rest.frames[j].to_rotation_matrix().into_inner();
                StretchShearTerm {
                    edge: j,
                    dofs: concat(
                        dofs.vertex_slots(j),
                        dofs.frame_slots(j),
                        dofs.vertex_slots(j + 1),
                    ),
                    full: concat(
                        FramedDofs::full_vertex_slots(j),
                        FramedDofs::full_frame_slots(j),
                        FramedDofs::full_vertex_slots(j + 1),
                    ),
                    rest_length: h,
                    stiffness: [self.shear.ga1, self.shear.ga2, st.ea],
                    rest_strain: r.transpose() * (rest.positions[j + 1] - rest.positions[j]) / h,
                }
            })
            .collect();
        let measure = self.options.darboux;
        let free_of = |f: FrameRef| -> [usize; 3] {
            match f {
                FrameRef::Edge(j) => dofs.frame_slots(j),
                FrameRef::Clamp(_) => [FIXED; 3],
            }
        };
        let full_of = |f: FrameRef| -> [usize; 3] {
            match f {
                FrameRef::Edge(j) => FramedDofs::full_frame_slots(j),
                FrameRef::Clamp(end) => dofs.clamp_frame_slots(end),
            }
        };
        let mut topology = Vec::new();
        if self.supports.clamp_start {
            topology.push((
                0,
                FrameRef::Clamp(0),
                FrameRef::Edge(0),
                0.5 * geom.rest_lengths[0],
            ));
        }
        for i in 1..n {
            topology.push((
                i,
                FrameRef::Edge(i - 1),
                FrameRef::Edge(i),
                0.5 * (geom.rest_lengths[i - 1] + geom.rest_lengths[i]),
            ));
        }
        if self.supports.clamp_end {
            topology.push((
                n,
                FrameRef::Edge(n - 1),
                FrameRef::Clamp(1),
                0.5 * geom.rest_lengths[n - 1],
            ));
        }
        let mut bend_twist = Vec::with_capacity(topology.len());
        for (vertex, a, b, length) in topology {
            let rel = RelativeRotation::new(&a.of(rest), &b.of(rest));
            if measure == DarbouxMeasure::Tangent && !(rel.q[0] > 1e-3) {
                return Err(ModelError::structure(
                    "n_elements",
                    format!("the rest frames at vertex {vertex} turn by almost π; the tangent Darboux measure needs a finer mesh"),
                ));
            }
            let dofs6: Stencil<6> = concat(free_of(a), free_of(b), []);
            let full6: Stencil<6> = concat(full_of(a), full_of(b), []);
            bend_twist.push(BendTwistTerm {
                vertex,
                frames: (a, b),
                dofs: dofs6,
                full: full6,
                length,
                stiffness: [st.ei2, st.ei1, st.gj],
                rest: measure.evaluate(&rel.q).value,
                measure,
            });
        }
        Ok(CosseratRod {
            core,
            stretch_shear,
            bend_twist,
            measure,
        })
    }
}
