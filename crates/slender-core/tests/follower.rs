//! Follower loads on a rod against closed forms (the end-moment circle) and against the same
//! load applied dead (the follower and dead answers must differ by the turned direction).

use nalgebra::Vector3;
use slender_core::rod::{RestCurve, Rod, RodBuilder, RodProperties, SectionStiffness};
use slender_core::solver::{EquilibriumSolver, SolverParams};

const EI: f64 = 1.0;

fn cantilever(n: usize, follower: bool, force: Vector3<f64>, moment: Vector3<f64>) -> Rod {
    let b = RodBuilder::new(
        RestCurve::Straight {
            start: [0.0; 3],
            direction: [1.0, 0.0, 0.0],
            length: 1.0,
        },
        RodProperties {
            stiffness: SectionStiffness {
                ea: 1e6,
                ei1: EI,
                ei2: EI,
                gj: 0.77,
            },
            linear_density: 0.1,
        },
    )
    .elements(n)
    .clamp_start();
    let b = if follower {
        b.follower_load(n, force, moment)
    } else {
        b.point_force(n, force).point_moment(n, moment)
    };
    b.build().expect("rod")
}

fn solve(rod: &Rod) -> Vector3<f64> {
    let start = rod.rest_state();
    let sol =
        EquilibriumSolver::new(rod, start, SolverParams::default()).solve(rod, start, 0.0, 1.0);
    assert!(sol.report.converged(), "{:?}", sol.report);
    *sol.state.positions().last().unwrap()
}

#[test]
fn a_follower_end_moment_bends_the_cantilever_into_a_circle() {
    // An end moment M (follower or not) bends the rod into an arc of radius EI/M; take the
    // three-quarter circle so that the tip is far from where a dead force would put it.
    let m = 1.5 * std::f64::consts::PI * EI;
    let r = EI / m;
    let exact = Vector3::new(r * (1.0 / r).sin(), r * (1.0 - (1.0 / r).cos()), 0.0);
    let error = |n| {
        (solve(&cantilever(
            n,
            true,
            Vector3::zeros(),
            Vector3::new(0.0, 0.0, m),
        )) - exact)
            .norm()
    };
    let (coarse, fine) = (error(40), error(80));
    // Second order in the element length (the discrete curvature 2 tan(φ/2)/ℓ).
    assert!(
        coarse < 1e-2 && fine < 0.3 * coarse,
        "tip errors {coarse:.2e} (40), {fine:.2e} (80)"
    );
}

#[test]
fn a_follower_force_turns_with_the_tip_and_a_dead_one_does_not() {
    let f = Vector3::new(0.0, 2.0, 0.0);
    let follower = solve(&cantilever(40, true, f, Vector3::zeros()));
    let dead = solve(&cantilever(40, false, f, Vector3::zeros()));
    // Under a force kept normal to the tip the cantilever curls further than under a dead
    // force, whose lever arm shrinks as the tip turns toward it.
    assert!(
        follower.y > dead.y + 0.02,
        "follower {follower:?}, dead {dead:?}"
    );
    assert!(
        follower.x < dead.x - 0.02,
        "follower {follower:?}, dead {dead:?}"
    );
}

/// The gradient of `rod` at `state` and path parameter `load` (N or N m).
fn gradient(rod: &Rod, state: &slender_core::rod::RodState, load: f64) -> Vec<f64> {
    use slender_core::solver::EquilibriumProblem;
    let n = rod.n_free();
    let (mut g, mut a) = (vec![0.0; n], vec![0.0; n]);
    let mut h = rod.new_hessian();
    rod.assemble(state, load, &mut g, &mut h, &mut a);
    g
}

fn max_gap(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .fold(0.0, |m: f64, (x, y)| m.max((x - y).abs()))
}

#[test]
fn a_follower_force_change_path_starts_at_the_old_load_and_ends_at_the_new() {
    // The path of an interactive edit (`Rod::set_follower_force_change`): at λ = 0 the bent
    // equilibrium under the old follower force is still an equilibrium (the old force, turned
    // with the tip, is what the vertex carries); at λ = 1 the rod carries the new force, turned
    // the same way: its gradient there is that of a rod built with the new force.
    let (old, new) = (Vector3::new(0.0, 2.0, 0.0), Vector3::new(0.0, 1.0, 0.5));
    let mut rod = cantilever(40, true, old, Vector3::zeros());
    let start = rod.rest_state();
    let sol =
        EquilibriumSolver::new(&rod, start, SolverParams::default()).solve(&rod, start, 0.0, 1.0);
    assert!(sol.report.converged());
    let mut state = sol.state;
    let before = gradient(&rod, &state, 1.0);
    let i = rod
        .set_follower_force_change(&mut state, 40, old, new)
        .expect("the follower on vertex 40");
    assert_eq!(i, 0);
    let start_of_path = max_gap(&gradient(&rod, &state, 0.0), &before);
    assert!(
        start_of_path <= 1e-14,
        "λ = 0: {start_of_path:e} from the old load's gradient"
    );
    // Against the new force applied from the start: the same state, frozen loads refreshed.
    let other = cantilever(40, true, new, Vector3::zeros());
    let mut same = state.clone();
    use slender_core::solver::EquilibriumProblem;
    other.refresh_loads(&mut same);
    let end_of_path = max_gap(&gradient(&rod, &state, 1.0), &gradient(&other, &same, 1.0));
    assert!(
        end_of_path <= 1e-14,
        "λ = 1: {end_of_path:e} from the new force's gradient"
    );
    let unbalanced = max_gap(&gradient(&rod, &state, 1.0), &before);
    assert!(
        unbalanced > 0.1,
        "the change moves the load: {unbalanced:e}"
    );
    // No such follower force: refused, nothing changed.
    assert!(rod
        .set_follower_force_change(&mut state, 40, old, new)
        .is_err());
    assert!(rod
        .set_follower_force_change(&mut state, 39, new, old)
        .is_err());
    // A path naming a follower the rod does not have is refused by name.
    let bad = slender_core::rod::RodLoadPath {
        follower_change: Some((1, new)),
        ..Default::default()
    };
    let e = rod.set_load_path(bad).unwrap_err().to_string();
    assert!(e.contains("follower_change"), "{e}");
}
