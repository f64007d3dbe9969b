//! The shell's energy terms against independent references: gradients and Hessians against
//! central finite differences (error falling like O(ε²)), zero gradient of the flat strip,
//! invariance under rigid motions, and the closed-form energy of cylindrical bending.

use nalgebra::{Rotation3, Vector3};
use slender_core::linalg::{SparseSymmetricMatrix, SymmetricBandMatrix, SymmetricMatrix};
use slender_core::rod::Grading;
use slender_core::shell::{Shell, ShellBuilder, ShellProperties, ShellState, ShellTerms};
use slender_core::solver::EquilibriumProblem;

/// Deterministic xorshift generator.
struct Rng(u64);
impl Rng {
    fn uniform(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }
    fn vector(&mut self, n: usize) -> Vec<f64> {
        (0..n).map(|_| self.uniform()).collect()
    }
}

fn properties(poisson: f64) -> ShellProperties {
    ShellProperties {
        length: 1.0,
        width: 0.3,
        thickness: 0.01,
        young: 2.0e5,
        poisson,
        density: 800.0,
    }
}

fn shells() -> Vec<Shell> {
    vec![
        ShellBuilder::new(properties(0.3))
            .elements(3, 2)
            .gravity(Vector3::new(0.3, -9.8, 1.1))
            .build()
            .expect("shell"),
        ShellBuilder::new(properties(0.0))
            .elements(4, 1)
            .grading(Grading::Uniform)
            .gravity(Vector3::new(0.0, 0.0, -9.8))
            .build()
            .expect("shell"),
    ]
}

/// A bent, stretched and twisted state with a rotated clamp, so that every term (including
/// the clamp's director term and the tan of large angles) is exercised away from zero.
fn random_state(shell: &mut Shell, rng: &mut Rng) -> ShellState {
    let mut s = shell.rest_state();
    shell.set_clamp_rotation(0.2 * rng.uniform(), &mut s);
    let clamped = shell.mesh().clamp_vertices.clone();
    for (v, p) in s.positions.iter_mut().enumerate() {
        if clamped.contains(&v) {
            continue;
        }
        let x = p.x;
        // Bend the strip (curvature ~1/L) and twist it a little, then jitter.
        *p = Vector3::new(
            x.sin(),
            1.0 - x.cos() + 0.2 * x * p.z,
            p.z * (1.0 + 0.1 * x),
        ) + Vector3::new(rng.uniform(), rng.uniform(), rng.uniform()) * 0.01;
    }
    for a in s.angles.iter_mut() {
        *a = 0.2 * rng.uniform();
    }
    shell.apply_clamp(&mut s);
    s
}

/// Energy, gradient and Hessian in the sparse storage the solver uses.
fn assemble(
    shell: &Shell,
    s: &ShellState,
    terms: ShellTerms,
) -> (f64, Vec<f64>, SparseSymmetricMatrix) {
    let n = shell.n_free();
    let mut g = vec![0.0; n];
    let mut h = shell.sparse_hessian();
    let e = shell
        .assemble_terms(s, 1.0, terms, Some(&mut g), Some(&mut h), None)
        .energy;
    (e, g, h)
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// (gradient errors, Hessian errors) of directional derivatives over decreasing ε, relative
/// to the size of the exact derivatives.
fn fd_errors(
    shell: &Shell,
    s: &ShellState,
    terms: ShellTerms,
    u: &[f64],
    v: &[f64],
) -> (Vec<f64>, Vec<f64>) {
    let (_, g, h) = assemble(shell, s, terms);
    let mut hv = vec![0.0; v.len()];
    h.mul_vec(v, &mut hv);
    let mut hu = vec![0.0; u.len()];
    h.mul_vec(u, &mut hu);
    let gv: f64 = g.iter().zip(v).map(|(a, b)| a * b).sum();
    let uhv: f64 = u.iter().zip(&hv).map(|(a, b)| a * b).sum();
    let scale_g = gv.abs().max(norm(&g) * norm(v) * 1e-3).max(1e-300);
    let scale_h = uhv.abs().max(norm(&hu) * norm(v) * 1e-3).max(1e-300);
    let mut trial = s.clone();
    let mut energy_at = |a: f64, b: f64| {
        let w: Vec<f64> = u.iter().zip(v).map(|(x, y)| a * x + b * y).collect();
        shell.displace(s, &w, 1.0, &mut trial);
        shell.energy_terms(&trial, 1.0, terms)
    };
    let (mut err_g, mut err_h) = (Vec::new(), Vec::new());
    for eps in [1e-3, 3e-4, 1e-4, 3e-5, 1e-5] {
        let d1 = (energy_at(0.0, eps) - energy_at(0.0, -eps)) / (2.0 * eps);
        err_g.push((d1 - gv).abs() / scale_g);
        let d2 = (energy_at(eps, eps) - energy_at(eps, -eps) - energy_at(-eps, eps)
            + energy_at(-eps, -eps))
            / (4.0 * eps * eps);
        err_h.push((d2 - uhv).abs() / scale_h);
    }
    (err_g, err_h)
}

fn assert_second_order(errors: &[f64], what: &str) {
    // Over a decade of ε the error must fall by ~100 (allow 30) until it reaches round-off.
    assert!(
        errors[2] < errors[0] / 30.0 || errors[2] < 1e-9,
        "{what}: not O(ε²): errors {errors:?}"
    );
    assert!(
        errors.iter().cloned().fold(f64::INFINITY, f64::min) < 1e-5,
        "{what}: {errors:?}"
    );
}

fn check(terms: ShellTerms, name: &str) {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    for (k, mut shell) in shells().into_iter().enumerate() {
        for trial in 0..3 {
            let s = random_state(&mut shell, &mut rng);
            let u = rng.vector(shell.n_free());
            let v = rng.vector(shell.n_free());
            let (eg, eh) = fd_errors(&shell, &s, terms, &u, &v);
            assert_second_order(&eg, &format!("{name} gradient, shell {k}, trial {trial}"));
            if terms == ShellTerms::GRAVITY {
                // A dead load is linear: its Hessian must vanish and its second differences
                // are round-off.
                let (_, _, h) = assemble(&shell, &s, terms);
                let mut hu = vec![0.0; u.len()];
                h.mul_vec(&u, &mut hu);
                assert!(hu.iter().all(|x| *x == 0.0));
            } else {
                assert_second_order(&eh, &format!("{name} Hessian, shell {k}, trial {trial}"));
            }
        }
    }
}

#[test]
fn membrane_derivatives_match_finite_differences() {
    check(ShellTerms::MEMBRANE, "membrane");
}

#[test]
fn bending_and_clamp_derivatives_match_finite_differences() {
    check(ShellTerms::BENDING, "bending");
}

#[test]
fn gravity_derivatives_match_finite_differences() {
    check(ShellTerms::GRAVITY, "gravity");
}

#[test]
fn total_energy_derivatives_match_finite_differences() {
    check(ShellTerms::ALL, "total");
}

#[test]
fn flat_unloaded_strip_has_zero_gradient_and_energy() {
    for shell in shells() {
        let s = shell.rest_state();
        let n = shell.n_free();
        let mut g = vec![0.0; n];
        let e = shell
            .assemble_terms::<SparseSymmetricMatrix>(
                &s,
                0.0,
                ShellTerms::ALL,
                Some(&mut g),
                None,
                None,
            )
            .energy;
        assert_eq!(e, 0.0);
        assert!(norm(&g) == 0.0, "gradient {}", norm(&g));
    }
}

#[test]
fn rigid_motions_change_no_internal_energy() {
    let mut rng = Rng(0x1234_5678_9ABC_DEF1);
    for mut shell in shells() {
        let s = random_state(&mut shell, &mut rng);
        let membrane = shell.energy_terms(&s, 0.0, ShellTerms::MEMBRANE);
        let bending = shell.energy_terms(&s, 0.0, ShellTerms::BENDING);
        assert!(membrane > 0.0 && bending > 0.0);
        // Any rotation and translation leaves the membrane energy unchanged.
        let r = Rotation3::from_euler_angles(0.4, -1.1, 2.3);
        let t = Vector3::new(0.3, -2.0, 5.0);
        let mut moved = s.clone();
        for p in moved.positions.iter_mut() {
            *p = r * *p + t;
        }
        let m2 = shell.energy_terms(&moved, 0.0, ShellTerms::MEMBRANE);
        assert!(
            (m2 - membrane).abs() <= 1e-9 * membrane,
            "{m2} vs {membrane}"
        );
        // Bending involves the clamp normal: rotate about x together with the clamp, and
        // translate along x (which keeps the clamp line on the x axis).
        let sigma = shell.clamp().sigma;
        let r = Rotation3::from_axis_angle(&Vector3::x_axis(), 0.7);
        let mut moved = s.clone();
        for p in moved.positions.iter_mut() {
            *p = r * *p;
        }
        let mut dummy = moved.clone();
        shell.set_clamp_rotation(sigma + 0.7, &mut dummy);
        let b2 = shell.energy_terms(&moved, 0.0, ShellTerms::BENDING);
        assert!((b2 - bending).abs() <= 1e-9 * bending, "{b2} vs {bending}");
        let m3 = shell.energy_terms(&moved, 0.0, ShellTerms::MEMBRANE);
        assert!((m3 - membrane).abs() <= 1e-9 * membrane);
    }
}

#[test]
fn cylindrical_bending_energy_matches_closed_form() {
    // Roll the strip about z: curvature κ along the length, none across. Vertices sit on the
    // cylinder; every director is set (through φ) to the cylinder's normal at its edge, and
    // the clamp normal +y is the cylinder's normal at x = 0. Expected bending energy ½·D·w·L·κ²
    // (ν ≠ 0 exercises the λ(tr N)² coupling). Coarse mesh: 8 × 2, also graded.
    for (poisson, kappa, grading) in [
        (0.3, 1.0, Grading::Uniform),
        (0.0, 2.0, Grading::Uniform),
        (0.45, 0.5, Grading::Power { exponent: 2.0 }),
    ] {
        let p = properties(poisson);
        let shell = ShellBuilder::new(p)
            .elements(8, 2)
            .grading(grading)
            .build()
            .expect("shell");
        let mesh = shell.mesh();
        let mut s = shell.rest_state();
        let on_cylinder = |x: f64, z: f64| {
            Vector3::new(
                (kappa * x).sin() / kappa,
                (1.0 - (kappa * x).cos()) / kappa,
                z,
            )
        };
        for p in s.positions.iter_mut() {
            *p = on_cylinder(p.x, p.z);
        }
        for (f, tri) in mesh.faces.iter().enumerate() {
            let n_f = (s.positions[tri[1]] - s.positions[tri[0]])
                .cross(&(s.positions[tri[2]] - s.positions[tri[0]]))
                .normalize();
            for (k, fe) in mesh.face_edges[f].iter().enumerate() {
                if mesh.clamp_edges.contains(&fe.edge) {
                    continue;
                }
                let (a, b) = (tri[(k + 1) % 3], tri[(k + 2) % 3]);
                let axis = (s.positions[b] - s.positions[a]).normalize();
                let xm = 0.5 * (mesh.rest_positions[a].x + mesh.rest_positions[b].x);
                let target = Vector3::new(-(kappa * xm).sin(), (kappa * xm).cos(), 0.0);
                let alpha = n_f.cross(&target).dot(&axis).atan2(n_f.dot(&target));
                // Dihedral angle θ (0 on a free edge); the director angle is θ/2 + σφ.
                let theta = fe.opposite_vertex.map_or(0.0, |p| {
                    let n_g = (s.positions[a] - s.positions[b])
                        .cross(&(s.positions[p] - s.positions[b]))
                        .normalize();
                    n_f.cross(&n_g).dot(&axis).atan2(n_f.dot(&n_g))
                });
                s.angles[fe.edge] = (alpha - 0.5 * theta) / fe.orientation;
            }
        }
        let e = shell.energy_terms(&s, 0.0, ShellTerms::BENDING);
        let expected = 0.5 * p.bending_stiffness() * p.width * p.length * kappa * kappa;
        let rel = (e - expected) / expected;
        assert!(
            rel.abs() < 0.01,
            "ν = {poisson}, κ = {kappa}: {e} vs {expected} ({rel:+.4})"
        );
    }
}

#[test]
fn sparse_and_banded_assembly_agree() {
    // The free DOFs are numbered along the length, so the band holds the Hessian too: both
    // storages must receive the same entries (a check of the sparse pattern's completeness).
    let mut rng = Rng(0x0DDB_1A5E_5BAD_5EED);
    for mut shell in shells() {
        let s = random_state(&mut shell, &mut rng);
        let n = shell.n_free();
        let mut g = vec![0.0; n];
        let mut band = SymmetricBandMatrix::new(n, shell.half_bandwidth());
        shell.assemble_terms(
            &s,
            1.0,
            ShellTerms::ALL,
            Some(&mut g),
            Some(&mut band),
            None,
        );
        let (_, _, sparse) = assemble(&shell, &s, ShellTerms::ALL);
        let mut max: f64 = 0.0;
        for i in 0..n {
            for j in 0..n {
                assert_eq!(band.get(i, j), sparse.get(i, j), "entry ({i}, {j})");
                max = max.max(band.get(i, j).abs());
            }
        }
        assert!(max > 0.0);
    }
}
