//! Building an SE(3) beam: the shared input ([`FramedRodBuilder`]) with frames at the nodes
//! (clamped nodes hold the exact pose of the curve's end) and one element per node pair.

use nalgebra::SVector;

use crate::assembly::FIXED;
use crate::error::ModelError;
use crate::framed::builder::FramedRodBuilder;
use crate::framed::core::{FrameLayout, FramedCore};
use crate::framed::FramedDofs;
use crate::lie::RelativeRotation;

use super::element::{element_twist, Se3Element};
use super::model::Se3Rod;

/// The SE(3) beam's own options (none yet).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Se3Options;

/// Builds an [`Se3Rod`]: `Se3Builder::new(curve, properties, shear)`, then the setters of
/// [`FramedRodBuilder`].
pub type Se3Builder = FramedRodBuilder<Se3Options>;

fn stencil(a: [usize; 3], b: [usize; 3], c: [usize; 3], d: [usize; 3]) -> [usize; 12] {
    let mut out = [FIXED; 12];
    for (o, v) in out.iter_mut().zip(a.iter().chain(&b).chain(&c).chain(&d)) {
        *o = *v;
    }
    out
}

impl Se3Builder {
    /// Validates the input and builds the beam.
    pub fn build(self) -> Result<Se3Rod, ModelError> {
        let geom = self.geometry()?;
        let n = geom.rest_lengths.len();
        let frames = geom.node_frames(self.natural_twist);
        for j in 0..n {
            let rel = RelativeRotation::new(&frames[j], &frames[j + 1]);
            if !(rel.q[0] > 1e-3) {
                return Err(ModelError::structure(
                    "n_elements",
                    format!("element {j} turns by almost π at rest; use more elements"),
                ));
            }
        }
        let arcs: Vec<f64> = geom
            .curve_arclengths
            .windows(2)
            .map(|w| w[1] - w[0])
            .collect();
        let mut fixed_frames = Vec::new();
        if self.supports.clamp_start {
            fixed_frames.push(0);
        }
        if self.supports.clamp_end {
            fixed_frames.push(n);
        }
        let mut frame_lengths = vec![0.0; n + 1];
        for (j, &l) in arcs.iter().enumerate() {
            frame_lengths[j] += 0.5 * l;
            frame_lengths[j + 1] += 0.5 * l;
        }
        let layout = FrameLayout {
            frames,
            clamp_frames: [None, None],
            fixed_frames,
            frame_arclengths: geom.arclengths.clone(),
            frame_lengths,
            moment_slot: |v, _| v,
            mass_lengths: arcs.clone(),
        };
        let core = FramedCore::new(&self, &geom, layout)?;
        let st = self.properties.stiffness;
        let stiffness = [self.shear.ga1, self.shear.ga2, st.ea, st.ei2, st.ei1, st.gj];
        let dofs = &core.dofs;
        let elements = (0..n)
            .map(|j| {
                let rest: SVector<f64, 6> = element_twist(&core.rest, j);
                Se3Element {
                    element: j,
                    dofs: stencil(
                        dofs.vertex_slots(j),
                        dofs.frame_slots(j),
                        dofs.vertex_slots(j + 1),
                        dofs.frame_slots(j + 1),
                    ),
                    full: stencil(
                        FramedDofs::full_vertex_slots(j),
                        FramedDofs::full_frame_slots(j),
                        FramedDofs::full_vertex_slots(j + 1),
                        FramedDofs::full_frame_slots(j + 1),
                    ),
                    rest_length: arcs[j],
                    stiffness,
                    rest,
                }
            })
            .collect();
        Ok(Se3Rod { core, elements })
    }
}
