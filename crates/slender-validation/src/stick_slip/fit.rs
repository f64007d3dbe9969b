//! The acceleration of a uniformly accelerated motion from samples of its position.

/// Least-squares fit of x(t) = x₀ + v₀ t + ½ a t² to the samples (t, x); returns a (m/s²).
/// `None` with fewer than three samples or coincident times.
pub fn acceleration(samples: &[(f64, f64)]) -> Option<f64> {
    if samples.len() < 3 {
        return None;
    }
    // Normal equations of the basis (1, t, t²/2), centred on the mean time for conditioning.
    let n = samples.len() as f64;
    let tm = samples.iter().map(|s| s.0).sum::<f64>() / n;
    let mut a = nalgebra::Matrix3::<f64>::zeros();
    let mut b = nalgebra::Vector3::<f64>::zeros();
    for &(t, x) in samples {
        let u = t - tm;
        let phi = nalgebra::Vector3::new(1.0, u, 0.5 * u * u);
        a += phi * phi.transpose();
        b += phi * x;
    }
    a.cholesky().map(|c| c.solve(&b)[2])
}

#[cfg(test)]
mod tests {
    #[test]
    fn recovers_a_parabola() {
        let samples: Vec<(f64, f64)> = (0..50)
            .map(|k| {
                let t = k as f64 * 0.01;
                (t, 0.3 - 0.2 * t + 0.5 * 1.7 * t * t)
            })
            .collect();
        let a = super::acceleration(&samples).unwrap();
        assert!((a - 1.7).abs() < 1e-9, "{a}");
        assert!(super::acceleration(&samples[..2]).is_none());
    }
}
