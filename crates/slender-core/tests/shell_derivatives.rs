//! The shell's energy terms against independent references: gradients and Hessians against
//! central finite differences (error falling like O(ε²)), zero gradient of the flat strip,
//! invariance under rigid motions, and the closed-form energy of cylindrical bending.

use nalgebra::Vector3;
use slender_core::assembly::TermSet;
use slender_core::linalg::{SparseSymmetricMatrix, SymmetricBandMatrix};
use slender_core::rod::Grading;
use slender_core::shell::groups::BENDING;
use slender_core::shell::{Shell, ShellBuilder, ShellProperties, ShellState};
use slender_core::solver::EquilibriumProblem;
use slender_core::testing::{check_model, Rng};

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
    let shell: &Shell = shell;
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
    terms: TermSet,
) -> (f64, Vec<f64>, SparseSymmetricMatrix) {
    let n = shell.n_free();
    let mut g = vec![0.0; n];
    let mut h = shell.sparse_hessian();
    let e = shell
        .assemble_terms(s, 1.0, terms, Some(&mut g), Some(&mut h), None)
        .energy;
    (e, g, h)
}

#[test]
fn every_term_passes_the_derivative_checker() {
    // Membrane, bending with the clamp's director term, gravity (linear: no Hessian) and their
    // sum against finite differences; rigid motions (the clamp moves with the state); the flat
    // unloaded strip.
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    for (k, mut shell) in shells().into_iter().enumerate() {
        let states: Vec<ShellState> = (0..3).map(|_| random_state(&mut shell, &mut rng)).collect();
        check_model(
            &shell,
            &states,
            1.0,
            &mut rng,
            |_| 1.0,
            1.0,
            &format!("shell {k}"),
        )
        .unwrap_or_else(|e| panic!("{e}"));
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
        let e = shell.energy_terms(&s, 0.0, BENDING.set());
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
        shell.assemble_terms(&s, 1.0, TermSet::ALL, Some(&mut g), Some(&mut band), None);
        let (_, _, sparse) = assemble(&shell, &s, TermSet::ALL);
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
