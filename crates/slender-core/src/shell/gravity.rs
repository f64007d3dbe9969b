//! Dead load of self-weight: lumped vertex masses (a third of each adjacent face's mass).

use crate::geometry::Vec3;

use super::membrane::FaceRest;

/// Mass (kg) lumped at each vertex: ρ h Ā_f / 3 from every face f touching it.
pub fn lumped_vertex_masses(
    n_vertices: usize,
    faces: &[[usize; 3]],
    rest: &[FaceRest],
    areal_density: f64,
) -> Vec<f64> {
    let mut m = vec![0.0; n_vertices];
    for (tri, r) in faces.iter().zip(rest) {
        for &v in tri {
            m[v] += areal_density * r.area / 3.0;
        }
    }
    m
}

/// Potential energy (J) of the weight: −Σ m_v g·x_v at acceleration `g` (m/s²).
pub fn gravity_energy(masses: &[f64], positions: &[Vec3], g: &Vec3) -> f64 {
    -masses
        .iter()
        .zip(positions)
        .map(|(m, x)| m * g.dot(x))
        .sum::<f64>()
}
