//! Strain measures of a Cosserat rod state for output.

use nalgebra::Vector3;

use crate::framed::FramedState;

use super::model::CosseratRod;

/// Extension and shear of one edge.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EdgeStrain {
    /// The edge.
    pub edge: usize,
    /// Γ − e₃ = Rᵀe/h − e₃ in the edge's frame: shear along d₁, d₂ and axial strain.
    pub strain: Vector3<f64>,
    /// The rest value of `strain`.
    pub rest: Vector3<f64>,
}

/// Curvature and twist at one vertex.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DarbouxStrain {
    /// The vertex.
    pub vertex: usize,
    /// K = g/h̄ (1/m): curvature about d₁ and d₂ and twist about d₃ of the first frame.
    pub darboux: Vector3<f64>,
    /// The rest value of `darboux`.
    pub rest: Vector3<f64>,
}

impl CosseratRod {
    /// Extension and shear of every edge of `s`.
    pub fn edge_strains(&self, s: &FramedState) -> Vec<EdgeStrain> {
        self.stretch_shear
            .iter()
            .map(|t| {
                let j = t.edge;
                let r = s.frames[j].to_rotation_matrix().into_inner();
                let v = r.transpose() * (s.positions[j + 1] - s.positions[j]) / t.rest_length;
                EdgeStrain {
                    edge: j,
                    strain: v - Vector3::z(),
                    rest: t.rest_strain - Vector3::z(),
                }
            })
            .collect()
    }

    /// Curvature and twist at every vertex term of `s` (interior vertices and clamped ends),
    /// in increasing vertex order.
    pub fn darboux_strains(&self, s: &FramedState) -> Vec<DarbouxStrain> {
        self.bend_twist
            .iter()
            .map(|t| DarbouxStrain {
                vertex: t.vertex,
                darboux: t.darboux(s) / t.length,
                rest: t.rest / t.length,
            })
            .collect()
    }
}
