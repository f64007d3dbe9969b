//! Gravity on a rod as the exact integral of the potential over the polyline.
//!
//! For straight edges with uniform mass per length ρA, ∫ ρA g·x ds over edge j equals
//! ρA |ē_j| g·(x_j + x_{j+1})/2, so lumping half of each edge's rest mass on its end vertices
//! gives the exact potential of the discrete centerline (mass is attached to the rest length,
//! so stretching does not create mass).

/// Mass (kg) lumped on each vertex: half of each adjacent edge's rest mass.
pub fn lumped_vertex_masses(rest_lengths: &[f64], linear_density: f64) -> Vec<f64> {
    let mut m = vec![0.0; rest_lengths.len() + 1];
    for (j, &l) in rest_lengths.iter().enumerate() {
        let half = 0.5 * linear_density * l;
        m[j] += half;
        m[j + 1] += half;
    }
    m
}
