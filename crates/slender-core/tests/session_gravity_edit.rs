//! Changing gravity in a session (`Session::set_gravity`): the warm re-solve ends where a cold
//! solve of the scene with the new gravity ends (a different path: loads ramped from rest), for
//! every rod model; a change that does not converge keeps the equilibrium and puts the loads
//! back exactly, so that later edits end where they end in a session that never tried it.

use crate::common;

use common::max_distance;
use slender_core::scene::{Scene, Session};

/// A 1 m cantilever (d = 6 mm, E = 1 GPa, ρ = 1400 kg/m³) of `model` with `elements`
/// elements, clamped at the start, under gravity `g` (m/s²).
fn cantilever(model: &str, elements: usize, g: [f64; 3]) -> Scene {
    toml::from_str(&format!(
        r#"
gravity = {g:?}
[[rods]]
name = "beam"
model = "{model}"
elements = {elements}
centerline = {{ kind = "straight", start = [0.0, 0.0, 0.0], direction = [1.0, 0.0, 0.0], length = 1.0 }}
section = {{ shape = "circle", diameter = 0.006 }}
material = {{ young = 1.0e9, poisson = 0.4, density = 1400.0 }}
supports = [ {{ kind = "clamp", vertex = "start" }} ]
"#
    ))
    .expect("the scene parses")
}

fn positions(s: &Session) -> Vec<[f64; 3]> {
    s.results(0, None, 1.0, 1).rods[0].positions.clone()
}

#[test]
fn a_gravity_edit_ends_where_a_cold_solve_with_that_gravity_ends() {
    let (from, to) = ([0.0, 0.0, -9.81], [0.0, 4.0, -20.0]);
    for model in ["der", "cosserat", "se3"] {
        let mut s = Session::new(cantilever(model, 20, from)).unwrap();
        let r = s.set_gravity(to).expect("a valid request");
        assert!(r.converged, "{model}: {r:?}");
        assert_eq!(s.spec().gravity, to);
        let cold = Session::new(cantilever(model, 20, to)).unwrap();
        let (here, there) = (positions(&s), positions(&cold));
        let d = max_distance(&here, &there);
        let sag = -there.last().unwrap()[2];
        eprintln!("{model}: gravity edit vs cold solve {d:.1e} m (tip sag {sag:.3} m)");
        assert!(sag > 0.1, "{model}: a large deflection ({sag} m)");
        assert!(d <= 1e-9, "{model}: {d:e} m");
    }
}

#[test]
fn a_gravity_change_that_does_not_converge_keeps_the_equilibrium_and_puts_the_loads_back() {
    // Four Newton iterations per load step and load steps of at least a quarter: a faint
    // gravity converges, one 3·10⁵ times stronger cannot.
    let g0 = [0.0, 1e-5, -1e-4];
    for model in ["der", "cosserat", "se3"] {
        let mut scene = cantilever(model, 20, g0);
        scene.solver.max_iterations = 4;
        scene.solver.min_load_step = 0.25;
        let mut s = Session::new(scene.clone()).unwrap();
        assert!(s.report(0).converged(), "{model}: {:?}", s.report(0));
        let before = s.results(0, None, 1.0, 1);
        let r = s.set_gravity([0.0, 3.0, -30.0]).expect("a valid request");
        assert!(!r.converged, "{model}: {r:?}");
        assert_eq!(s.spec().gravity, g0, "{model}");
        let after = s.results(0, None, 1.0, 1);
        let (a, b) = (&after.rods[0], &before.rods[0]);
        assert_eq!(a.positions, b.positions, "{model}");
        assert_eq!(a.supports, b.supports, "{model}");
        // The loads are back bit for bit, not as x + Δ − Δ (which leaves their sum and the
        // balance of the reactions an ulp off).
        assert_eq!(a.applied_force, b.applied_force, "{model}");
        assert_eq!(a.force_imbalance, b.force_imbalance, "{model}");
        assert_eq!(a.moment_imbalance, b.moment_imbalance, "{model}");
        // And the session goes on: a small change ends where a session that never tried the
        // large one ends (their warm starts differ: to the solver's tolerance).
        let mut fresh = Session::new(scene).unwrap();
        for t in [&mut s, &mut fresh] {
            let r = t.set_gravity([0.0, 2e-5, -2e-4]).unwrap();
            assert!(r.converged, "{model}: {r:?}");
        }
        let (here, there) = (positions(&s), positions(&fresh));
        let d = max_distance(&here, &there);
        let sag = -there.last().unwrap()[2];
        eprintln!(
            "{model}: after a failed edit: {d:.1e} m from a fresh session, tip sag {sag:.3e} m"
        );
        assert!(d <= 1e-6 * sag, "{model}: {d:e} m, tip sag {sag:e} m");
    }
}
