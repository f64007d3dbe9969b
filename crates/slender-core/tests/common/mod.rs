//! Shared references of the scene tests: Euler's elastica by elliptic integrals; the
//! dropped rod of the time-stepped contact tests ([`dropped_rod`]); the distance between two
//! equilibria.

#![allow(dead_code)]

pub mod dropped_rod;

/// Largest distance (m) between corresponding points of two shapes.
pub fn max_distance(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(p, q)| (0..3).map(|k| (p[k] - q[k]).powi(2)).sum::<f64>().sqrt())
        .fold(0.0, f64::max)
}

/// Complete elliptic integrals K(m), E(m) of parameter m = k² by the arithmetic–geometric mean.
pub fn elliptic_ke(m: f64) -> (f64, f64) {
    let (mut a, mut b) = (1.0_f64, (1.0 - m).sqrt());
    let mut c2_sum = 0.5 * m;
    let mut pow = 0.5;
    for _ in 0..40 {
        let an = 0.5 * (a + b);
        let bn = (a * b).sqrt();
        let cn = 0.5 * (a - b);
        pow *= 2.0;
        c2_sum += pow * cn * cn;
        a = an;
        b = bn;
    }
    let k = std::f64::consts::FRAC_PI_2 / a;
    (k, k * (1.0 - c2_sum))
}

/// Midspan deflection (m) of an inextensible clamped–clamped elastica of length `l` whose ends
/// are brought `shortening` (m) closer: it is four quarter-waves of Euler's elastica, so with
/// k = sin(α/2), shortening/l = 2(1 − E(k)/K(k)) and the midspan deflection is l·k/K(k)·… ;
/// here deflection = 2 × the pinned elastica of length l/2, i.e. l·k/K(k).
pub fn clamped_elastica_deflection(l: f64, shortening: f64) -> f64 {
    let target = shortening / l;
    let (mut lo, mut hi) = (1e-12_f64, 0.999_f64);
    for _ in 0..200 {
        let k = 0.5 * (lo + hi);
        let (kk, ee) = elliptic_ke(k * k);
        if 2.0 * (1.0 - ee / kk) < target {
            lo = k;
        } else {
            hi = k;
        }
    }
    let k = 0.5 * (lo + hi);
    l * k / elliptic_ke(k * k).0
}
