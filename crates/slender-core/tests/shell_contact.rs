//! Contact of the mid-edge shell strip with rigid obstacles (`contact::shell_sites`): exact
//! derivatives of the strip's contact energy against finite differences, and equilibria
//! against independent references — a flat cable clamped above a floor touches down where
//! small-deflection beam theory says, a flat cable draped over a round bar wraps it — with
//! the mid-surface kept h/2 from every surface and the reactions balancing the weight.

use std::sync::Arc;

use nalgebra::Vector3;
use slender_core::assembly::TermSet;
use slender_core::contact::{
    ContactParams, ContactProblem, ContactSites, Cylinder, Obstacle, Plane, Sphere, CONTACT,
};
use slender_core::rod::Grading;
use slender_core::shell::{Shell, ShellBuilder, ShellProperties, ShellState};
use slender_core::solver::{EquilibriumProblem, EquilibriumSolver, SolverParams};
use slender_core::testing::{check_derivatives, Rng};

/// The flat cable of `examples/flat_cable_shell_cantilever.toml`: L = 0.3 m, w = 0.03 m,
/// h = 0.2 mm, E = 10530 MPa, ν = 0 (so D·w = EI of the section), ρ = 1000 kg/m³.
fn flat_cable() -> ShellProperties {
    ShellProperties {
        length: 0.3,
        width: 0.03,
        thickness: 0.2e-3,
        young: 10530e6,
        poisson: 0.0,
        density: 1000.0,
    }
}

const G: f64 = 9.81;

fn boxed(o: impl Obstacle + 'static) -> Arc<dyn Obstacle> {
    Arc::new(o)
}

/// Σ over the clamped vertices of ∂E/∂x (N): the force the clamp applies to the strip, by
/// central differences of the strip's own energy (elastic and gravity; no contact), with
/// steps h and 2h Richardson-extrapolated. Independent of the contact code.
fn clamp_force(shell: &Shell, state: &ShellState) -> Vector3<f64> {
    let mut s = state.clone();
    s.membrane_remainder.clear();
    let h = 1e-8 * shell.properties().length;
    let mut f = Vector3::zeros();
    for &v in &shell.mesh().clamp_vertices {
        for c in 0..3 {
            let x = s.positions[v][c];
            let mut central = |step: f64| {
                s.positions[v][c] = x + step;
                let up = shell.energy_terms(&s, 1.0, TermSet::ALL);
                s.positions[v][c] = x - step;
                let down = shell.energy_terms(&s, 1.0, TermSet::ALL);
                s.positions[v][c] = x;
                (up - down) / (2.0 * step)
            };
            let (d1, d2) = (central(h), central(2.0 * h));
            f[c] += (4.0 * d1 - d2) / 3.0;
        }
    }
    f
}

#[test]
fn contact_derivatives_match_finite_differences_for_every_obstacle() {
    let props = ShellProperties {
        length: 1.0,
        width: 0.3,
        thickness: 0.02,
        young: 2.0e5,
        poisson: 0.3,
        density: 800.0,
    };
    let shell = ShellBuilder::new(props)
        .elements(6, 2)
        .gravity(Vector3::new(0.0, -9.8, 0.0))
        .build()
        .unwrap();
    let mut rng = Rng(5);
    let n = shell.n_free();
    let dx: Vec<f64> = (0..n)
        .map(|i| rng.uniform() * if shell.dofs().is_angle(i) { 0.2 } else { 0.004 })
        .collect();
    let rest = shell.rest_state();
    let mut state = rest.clone();
    shell.displace(&rest, &dx, 1.0, &mut state);
    state.membrane_remainder.clear();
    // Every free vertex within the activation distance of the floor, several of the ball and
    // of the bar, none within a perturbation of any surface (the barrier's third derivative
    // jumps at g = ĝ and would spoil the O(ε²) decay).
    let obstacles = vec![
        boxed(Plane::new(Vector3::new(0.0, -0.04, 0.0), Vector3::y(), 0.0).unwrap()),
        boxed(Sphere::new(Vector3::new(0.5, 0.08, 0.0), 0.04, 0.0).unwrap()),
        boxed(Cylinder::new(Vector3::new(0.8, -0.07, 0.0), Vector3::z(), 0.03, 0.0).unwrap()),
    ];
    let params = ContactParams {
        radius: 0.5 * props.thickness,
        activation: 0.5,
        stiffness: 30.0,
        stick_stiffness: 50.0,
        self_contact: false,
    };
    let problem = ContactProblem::new(&shell, obstacles, params, &state).unwrap();
    let active = problem.contact_forces(&state).len();
    assert!(active >= 30, "only {active} active contacts");
    let scale = |i: usize| if shell.dofs().is_angle(i) { 1.0 } else { 0.1 };
    check_derivatives(
        &problem,
        &state,
        1.0,
        CONTACT.set(),
        &mut rng,
        scale,
        "contact",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    check_derivatives(&problem, &state, 1.0, TermSet::ALL, &mut rng, scale, "all")
        .unwrap_or_else(|e| panic!("{e}"));
}

/// Solves `shell` against `obstacles` from the flat strip, loads ramped.
fn solve(
    shell: &Shell,
    obstacles: Vec<Arc<dyn Obstacle>>,
    params: ContactParams,
) -> (ContactProblem<'_, Shell>, ShellState, usize) {
    let rest = shell.rest_state();
    let problem = ContactProblem::new(shell, obstacles, params, &rest).unwrap();
    let mut solver = EquilibriumSolver::new(&problem, &rest, SolverParams::default());
    let solution = solver.solve(&problem, &rest, 0.0, 1.0);
    assert!(solution.report.converged(), "{:?}", solution.report);
    let mut state = solution.state;
    state.membrane_remainder.clear();
    (problem, state, solution.report.iterations)
}

#[test]
fn flat_cable_clamped_above_a_floor_touches_down_where_beam_theory_says() {
    // Clamped horizontally with its mid-surface δ above the floor's surface plus h/2, a heavy
    // flat cable lies on the floor beyond a suspended length a = (72 EI δ / q)^(1/4) (small
    // deflection, δ/a ≈ 1 %: w = w' = w'' = 0 at touchdown); the clamp carries 2qa/3 of its
    // weight, the floor the rest. ν = 0: the strip bends as a beam of EI = D w.
    let props = flat_cable();
    let (n_l, n_w) = (60, 4);
    let shell = ShellBuilder::new(props)
        .elements(n_l, n_w)
        .grading(Grading::Uniform)
        .gravity(Vector3::new(0.0, -G, 0.0))
        .build()
        .unwrap();
    let half = 0.5 * props.thickness;
    let delta = 2e-3;
    let floor =
        boxed(Plane::new(Vector3::new(0.0, -delta - half, 0.0), Vector3::y(), 0.0).unwrap());
    let q = props.density * props.thickness * props.width * G; // N/m
    let p = props.density * props.thickness * G; // N/m²
    let activation = 1e-6 * props.length;
    let params = ContactParams::for_area_load(half, activation, p);
    let (problem, state, iterations) = solve(&shell, vec![floor], params);
    // No penetration: every vertex's mid-surface point keeps h/2 from the floor (the
    // barrier's promise), and every contact rests within ĝ.
    let gap = problem.min_gap(&state);
    let lowest = state
        .positions
        .iter()
        .map(|x| x.y)
        .fold(f64::INFINITY, f64::min);
    let distance = lowest - (-delta - half);
    assert!(gap > 0.0 && gap < activation, "min gap {gap:e}");
    assert!(
        distance >= half,
        "mid-surface {distance:e} m from the floor, h/2 = {half:e}"
    );
    let forces = problem.contact_forces(&state);
    for f in &forces {
        assert!(f.gap > 0.0 && f.gap < activation, "{f:?}");
    }
    let floor_force: Vector3<f64> = forces.iter().map(|f| f.force).sum();
    let weight = q * props.length;
    let clamp = clamp_force(&shell, &state);
    let balance = clamp + floor_force - Vector3::new(0.0, weight, 0.0);
    // The reference: the suspended length and the clamp's share of the weight.
    let a = (72.0 * props.young * props.thickness.powi(3) / 12.0
        * props.width
        * (delta - 0.5 * activation)
        / q)
        .powf(0.25);
    let expected_clamp = 2.0 * q * a / 3.0;
    let rel = (clamp.y - expected_clamp) / expected_clamp;
    println!(
        "flat cable on a floor: {iterations} iterations, {} contacts, min gap {gap:.3e} m (ĝ {activation:.1e}), mid-surface ≥ {distance:.4e} m from the floor (h/2 {half:.1e}); clamp force {:.6e} N vs 2qa/3 = {expected_clamp:.6e} N (rel. {rel:.2e}, a = {a:.4} m), floor {:.6e} N, weight {weight:.6e} N, |balance|/W = {:.2e}",
        forces.len(),
        clamp.y,
        floor_force.y,
        balance.norm() / weight
    );
    assert!(rel.abs() < 2e-2, "clamp force off by {rel:e}");
    assert!(
        balance.norm() <= 1e-6 * weight,
        "{balance:?} (clamp {clamp:?}, floor {floor_force:?})"
    );
    // The floor pushes only along its normal (frictionless).
    assert!(floor_force.x.abs() + floor_force.z.abs() <= 1e-12 * weight);
}

#[test]
fn flat_cable_draped_over_a_round_bar_wraps_it_without_penetrating() {
    // Clamped horizontally 5 mm above the top of a round bar across its width, a limp flat
    // cable (E a hundred times lower than the example's: Γ = ρhgL³/D ≈ 750, its bending
    // length √(EI/T) under the clamp's pull T about a tenth of the bar's radius) comes down on
    // the bar and hangs over it, wrapping it along an arc (the example's cable, Γ ≈ 7.5,
    // touches a bar this size along one line only): its vertices lie on the bar's surface
    // offset by h/2 within ĝ, never inside, the mid-surface between them no closer than the
    // chord sag allows, and the clamp and the bar carry its weight.
    let props = ShellProperties {
        young: 0.01 * flat_cable().young,
        ..flat_cable()
    };
    let (n_l, n_w) = (120, 4);
    let shell = ShellBuilder::new(props)
        .elements(n_l, n_w)
        .grading(Grading::Uniform)
        .gravity(Vector3::new(0.0, -G, 0.0))
        .build()
        .unwrap();
    let half = 0.5 * props.thickness;
    let bar_radius = 0.1;
    let centre = Vector3::new(0.1, -0.005 - half - bar_radius, 0.0);
    let bar = boxed(Cylinder::new(centre, Vector3::z(), bar_radius, 0.0).unwrap());
    let p = props.density * props.thickness * G;
    let activation = 1e-6 * props.length;
    let params = ContactParams::for_area_load(half, activation, p);
    let (problem, state, iterations) = solve(&shell, vec![bar], params);
    let gap = problem.min_gap(&state);
    assert!(gap > 0.0 && gap < activation, "min gap {gap:e}");
    let forces = problem.contact_forces(&state);
    let q = props.density * props.thickness * props.width * G;
    let across = |x: &Vector3<f64>| {
        let r = x - centre;
        (r - Vector3::z() * r.z).norm()
    };
    for f in &forces {
        let x = state.positions[problem.sites()[f.site].vertex];
        let d = across(&x) - bar_radius - half;
        assert!(d > 0.0 && d < activation, "vertex {d:e} m off the surface");
        // Frictionless: the force is along the bar's radius.
        assert!(f.force.cross(&f.normal).norm() <= 1e-12 * f.force.norm());
    }
    let carried: Vec<_> = forces
        .iter()
        .filter(|f| f.force.norm() > 1e-3 * q * props.length / n_l as f64)
        .collect();
    let angle = |f: &&slender_core::contact::ContactForce| f.normal.y.atan2(f.normal.x);
    let (a0, a1) = carried
        .iter()
        .map(angle)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), a| {
            (lo.min(a), hi.max(a))
        });
    // Between vertices: the midpoint m = (a + b)/2 of a mesh edge has, across the bar's
    // axis, |m|² = (|a|² + |b|²)/2 − |a − b|²/4, so it keeps at least √(r² − c²/4) from the
    // axis, r the nearer end's distance and c the edge's chord across the axis: the surface
    // offset by h/2 less the chord sag (≈ c²/(8r), the bound of `contact::shell_sites`).
    let mut worst_midpoint = f64::INFINITY;
    for &[i, j] in &shell.mesh().edges {
        let (x, y) = (state.positions[i], state.positions[j]);
        let r = across(&x).min(across(&y));
        let chord = {
            let d = y - x;
            (d - Vector3::z() * d.z).norm()
        };
        let bound = (r * r - 0.25 * chord * chord).sqrt();
        let m = across(&(0.5 * (x + y)));
        if m - bar_radius - half < 1e-3 {
            assert!(
                m >= bound * (1.0 - 1e-12),
                "edge {i}-{j}: midpoint {m:e} below {bound:e}"
            );
            worst_midpoint = worst_midpoint.min(m - bar_radius - half);
        }
    }
    let weight = q * props.length;
    let bar_force: Vector3<f64> = forces.iter().map(|f| f.force).sum();
    let clamp = clamp_force(&shell, &state);
    let balance = clamp + bar_force - Vector3::new(0.0, weight, 0.0);
    println!(
        "flat cable over a bar: {iterations} iterations, {} contacts ({} carrying), wrapped from {:.1}° to {:.1}°, min gap {gap:.3e} m, worst edge midpoint {worst_midpoint:.2e} m from h/2, bar force {:?} N, clamp {:?} N, weight {weight:.6e} N, |balance|/W = {:.2e}",
        forces.len(),
        carried.len(),
        a0.to_degrees(),
        a1.to_degrees(),
        bar_force,
        clamp,
        balance.norm() / weight
    );
    assert!(
        carried.len() >= 5 * (n_w + 1),
        "{} contacts carrying: not wrapped",
        carried.len()
    );
    assert!(a1 - a0 > 0.2, "wrap angle {} rad", a1 - a0);
    assert!(balance.norm() <= 1e-6 * weight, "{balance:?}");
    // Every contact's site is a vertex of the strip, all across the width (the bar is
    // parallel to the clamp: the strip bends as a beam, every column touches).
    let columns: std::collections::BTreeSet<usize> = carried
        .iter()
        .map(|f| problem.sites()[f.site].vertex % (n_w + 1))
        .collect();
    assert_eq!(columns.len(), n_w + 1);
    assert_eq!(problem.sites().len(), shell.contact_sites().len());
}
