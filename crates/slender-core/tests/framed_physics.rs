//! Physics of the discrete Cosserat rod and the SE(3) beam against closed forms and against
//! the discrete elastic rod: exact constant-strain configurations of the SE(3) element, the
//! Kirchhoff limit of the Cosserat rod (GA → ∞), the Timoshenko shear correction, Greenhill's
//! heavy column by inertia, force and moment balance, the log-map secant predictor, support
//! motion along the load path.

use nalgebra::{SVector, UnitQuaternion, Vector3};
use slender_core::assembly::{Assembler, TermSet};
use slender_core::cosserat::{CosseratBuilder, CosseratRod};
use slender_core::framed::groups::INTERNAL;
use slender_core::framed::{FramedDofs, FramedState, ShearStiffness};
use slender_core::geometry::Vec3;
use slender_core::lie::DarbouxMeasure;
use slender_core::linalg::SymmetricBandMatrix;
use slender_core::rod::{
    RestCurve, RodBuilder, RodLoadPath, RodProperties, SectionStiffness, SupportMotion,
};
use slender_core::se3::Se3Builder;
use slender_core::solver::{EquilibriumProblem, EquilibriumSolver, SolverParams};

fn props(ea: f64, ei: f64, gj: f64) -> RodProperties {
    RodProperties {
        stiffness: SectionStiffness::isotropic(ea, ei, gj),
        linear_density: 0.2,
    }
}

fn line(direction: [f64; 3], length: f64) -> RestCurve {
    RestCurve::Straight {
        start: [0.0; 3],
        direction,
        length,
    }
}

fn tight() -> SolverParams {
    SolverParams {
        force_tolerance: 1e-11,
        energy_tolerance: 1e-20,
        polish_iterations: Some(3),
        ..Default::default()
    }
}

fn solve<P: EquilibriumProblem<State = FramedState, Hessian = SymmetricBandMatrix>>(
    p: &P,
    start: &FramedState,
    params: SolverParams,
) -> FramedState {
    let sol = EquilibriumSolver::new(p, start, params).solve(p, start, 0.0, 1.0);
    assert!(sol.report.converged(), "{:?}", sol.report.status);
    sol.state
}

fn sag(p: &[Vec3]) -> f64 {
    let (a, b) = (p[0], p[p.len() - 1]);
    (a.y - b.y) / (b.x - a.x)
}

#[test]
fn se3_pure_end_moment_gives_the_exact_arc_with_two_elements() {
    // M about z rolls the rod into an arc of radius EI/M; three quarters of a circle.
    let (ei, l) = (2.0, 1.5);
    let m = 1.5 * std::f64::consts::PI * ei / l;
    let r = ei / m;
    let exact = Vec3::new(r * (l / r).sin(), r * (1.0 - (l / r).cos()), 0.0);
    for n in [2, 3, 7] {
        let rod = Se3Builder::new(
            line([1.0, 0.0, 0.0], l),
            props(1e4, ei, 1.5),
            ShearStiffness::isotropic(3e3),
        )
        .elements(n)
        .clamp_start()
        .point_moment(n, Vec3::new(0.0, 0.0, m))
        .build()
        .unwrap();
        let s = solve(&rod, rod.rest_state(), tight());
        let err = (s.positions()[n] - exact).norm() / l;
        assert!(err < 1e-9, "N = {n}: tip error {err:e}");
        // Every node lies on the circle too.
        for p in s.positions() {
            let d = (p - Vec3::new(0.0, r, 0.0)).norm();
            assert!(
                (d - r).abs() < 1e-9 * l,
                "N = {n}: node off the circle by {}",
                d - r
            );
        }
    }
}

/// A constant body strain ε = (v, κ) of a straight, isotropic, shearable rod that an end
/// wrench holds in equilibrium: n ∥ κ and κ × m + v × n = 0 (n = C_Γ(v − e₃), m = C_K κ).
fn helix_strain(
    ea: f64,
    ga: f64,
    ei: f64,
    gj: f64,
    k1: f64,
    k2: f64,
    k3: f64,
) -> (Vector3<f64>, Vector3<f64>, f64) {
    let a = k3 * (1.0 / ga - 1.0 / ea);
    let c = (gj - ei) * k3;
    // μ² a − μ + c = 0, the root that vanishes with c.
    let mu = if a.abs() < 1e-300 {
        c
    } else {
        (1.0 - (1.0 - 4.0 * a * c).sqrt()) / (2.0 * a)
    };
    let kappa = Vector3::new(k1, k2, k3);
    let v = Vector3::new(mu * k1 / ga, mu * k2 / ga, 1.0 + mu * k3 / ea);
    (v, kappa, mu)
}

#[test]
fn se3_helix_under_its_end_wrench_is_an_equilibrium_for_any_element_count() {
    let (ea, ga, ei, gj, l) = (50.0, 30.0, 1.0, 0.7, 2.0);
    // |κ| L = 2.3 rad: one element turns by less than π (the logarithm's range).
    let (v, kappa, mu) = helix_strain(ea, ga, ei, gj, 0.4, -0.6, 0.9);
    let n_body = kappa * mu;
    let m_body = Vector3::new(ei * kappa[0], ei * kappa[1], gj * kappa[2]);
    // Residual of the continuous equations: κ×n = 0, κ×m + v×n = 0.
    assert!(kappa.cross(&n_body).norm() < 1e-14);
    assert!((kappa.cross(&m_body) + v.cross(&n_body)).norm() < 1e-13);
    for n in [1, 2, 3, 7, 20] {
        let rod = Se3Builder::new(
            line([1.0, 0.0, 0.0], l),
            props(ea, ei, gj),
            ShearStiffness::isotropic(ga),
        )
        .elements(n)
        .clamp_start()
        .build()
        .unwrap();
        let rest = rod.rest_state();
        let (p0, x0) = (rest.frames()[0], rest.positions()[0]);
        let s_of = |s: f64| slender_core::lie::se3::exp(&(v * s), &(kappa * s));
        let positions: Vec<Vec3> = (0..=n)
            .map(|i| {
                let (_, t) = s_of(l * i as f64 / n as f64);
                x0 + p0 * t
            })
            .collect();
        let frames: Vec<_> = (0..=n)
            .map(|i| (p0 * s_of(l * i as f64 / n as f64).0).into_inner())
            .collect();
        let state = rod.state_from(positions, frames).unwrap();
        // Internal generalized forces over the free DOFs.
        let nf = rod.n_free();
        let mut g = vec![0.0; nf];
        let mut asm = Assembler::<SymmetricBandMatrix>::new(INTERNAL, Some(&mut g), None, None);
        rod.assemble_selected(&state, 1.0, &mut asm);
        asm.finish();
        // The end wrench in space: R_L (n, m).
        let r_end = state.frames()[n];
        let force = r_end * n_body;
        let moment = r_end * m_body;
        let dofs = rod.dofs();
        let mut worst: f64 = 0.0;
        for (i, gi) in g.iter().enumerate() {
            let applied = match dofs.slot(i) {
                slender_core::framed::DofSlot::Position { v, k } if v == n => force[k],
                slender_core::framed::DofSlot::Rotation { j, k } if j == n => moment[k],
                _ => 0.0,
            };
            let scale = if dofs.is_rotation(i) {
                moment.norm()
            } else {
                force.norm()
            };
            worst = worst.max((gi - applied).abs() / scale);
        }
        eprintln!("helix, N = {n}: relative residual {worst:e}");
        assert!(worst < 1e-11, "N = {n}: relative residual {worst:e}");
        // And every element has the same strain.
        for e in rod.element_strains(&state) {
            let exact = SVector::<f64, 6>::new(v[0], v[1], v[2], kappa[0], kappa[1], kappa[2]);
            assert!((e.strain - exact).norm() < 1e-12, "N = {n}");
        }
    }
}

fn cantilever_ratio_der(n: usize, gamma: f64, ea: f64) -> f64 {
    let p = props(ea, 1.0, 0.8);
    let rod = RodBuilder::new(line([1.0, 0.0, 0.0], 1.0), p)
        .elements(n)
        .first_director(Vec3::z())
        .clamp_start()
        .gravity(Vec3::new(0.0, -gamma / p.linear_density, 0.0))
        .build()
        .unwrap();
    let sol = EquilibriumSolver::new(&rod, rod.rest_state(), tight()).solve(
        &rod,
        rod.rest_state(),
        0.0,
        1.0,
    );
    assert!(sol.report.converged());
    sag(sol.state.positions())
}

fn cantilever_cosserat(
    n: usize,
    gamma: f64,
    ea: f64,
    ga: f64,
    measure: DarbouxMeasure,
) -> CosseratRod {
    let p = props(ea, 1.0, 0.8);
    CosseratBuilder::new(line([1.0, 0.0, 0.0], 1.0), p, ShearStiffness::isotropic(ga))
        .darboux(measure)
        .elements(n)
        .first_director(Vec3::z())
        .clamp_start()
        .gravity(Vec3::new(0.0, -gamma / p.linear_density, 0.0))
        .build()
        .unwrap()
}

fn cantilever_ratio_cosserat(
    n: usize,
    gamma: f64,
    ea: f64,
    ga: f64,
    measure: DarbouxMeasure,
) -> f64 {
    let rod = cantilever_cosserat(n, gamma, ea, ga, measure);
    sag(solve(&rod, rod.rest_state(), tight()).positions())
}

#[test]
fn cosserat_tends_to_the_discrete_elastic_rod_like_one_over_ga() {
    // With the tangent Darboux measure and no shear, the Cosserat rod's energy is the discrete
    // elastic rod's (same curvature 2 tan(φ/2), Voronoi lengths, clamp half cell, stretching
    // and gravity), so the difference is the shear compliance alone: O(EI/(GA L²)).
    let (n, gamma, ea) = (12, 10.0, 1e6);
    let der = cantilever_ratio_der(n, gamma, ea);
    let gas = [1e3, 1e4, 1e5, 1e6];
    let diffs: Vec<f64> = gas
        .iter()
        .map(|&ga| cantilever_ratio_cosserat(n, gamma, ea, ga, DarbouxMeasure::Tangent) / der - 1.0)
        .collect();
    eprintln!("Cosserat (tangent) vs DER, GA = {gas:?}: relative differences {diffs:?}");
    for w in diffs.windows(2).zip(gas.windows(2)) {
        let (d, g) = w;
        let slope = (d[1].abs() / d[0].abs()).ln() / (g[1] / g[0]).ln();
        assert!(
            (slope + 1.0).abs() < 0.05,
            "differences {diffs:?}: slope {slope}"
        );
    }
    assert!(diffs[3].abs() < 1e-5, "{diffs:?}");
}

#[test]
fn cosserat_shear_correction_matches_timoshenko() {
    // Small load (linear regime): the shear adds q L²/(2 GA) to the tip deflection q L⁴/(8 EI),
    // a relative correction 4 EI/(GA L²). Compared against the same rod with GA ×10⁶.
    let (n, gamma, ea, ei) = (40, 0.01, 1e8, 1.0);
    for ga in [400.0, 4000.0] {
        let stiff = cantilever_ratio_cosserat(n, gamma, ea, ga * 1e6, DarbouxMeasure::Sine);
        let soft = cantilever_ratio_cosserat(n, gamma, ea, ga, DarbouxMeasure::Sine);
        let measured = soft / stiff - 1.0;
        let timoshenko = 4.0 * ei / ga;
        eprintln!("GA = {ga}: shear correction {measured:e}, Timoshenko {timoshenko:e}");
        assert!(
            (measured / timoshenko - 1.0).abs() < 0.02,
            "GA = {ga}: measured {measured:e}, Timoshenko {timoshenko:e}"
        );
    }
}

/// Smallest Γ (bisection) at which the upright heavy column clamped at its foot is unstable
/// (negative Hessian eigenvalue), for a model built by `build(Γ)`.
fn greenhill<P, F>(build: F) -> f64
where
    P: EquilibriumProblem<State = FramedState, Hessian = SymmetricBandMatrix>,
    F: Fn(f64) -> P,
    P: std::ops::Deref<Target = slender_core::framed::FramedCore>,
{
    let stable = |gamma: f64| {
        let rod = build(gamma);
        let params = SolverParams {
            compute_lambda_min: false,
            ..Default::default()
        };
        let sol = EquilibriumSolver::new(&rod, rod.rest_state(), params).solve(
            &rod,
            rod.rest_state(),
            0.0,
            1.0,
        );
        assert!(sol.report.converged());
        sol.report.stable().unwrap()
    };
    let (mut lo, mut hi) = (6.0, 10.0);
    assert!(stable(lo) && !stable(hi));
    while hi - lo > 1e-4 * lo {
        let mid = 0.5 * (lo + hi);
        if stable(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

#[test]
fn greenhill_threshold_by_inertia() {
    const GREENHILL: f64 = 7.837_347;
    let p = RodProperties {
        stiffness: SectionStiffness::isotropic(1e5, 1.0, 0.77),
        linear_density: 0.2,
    };
    let shear = ShearStiffness::solid_circle(&p.stiffness).unwrap();
    let up = line([0.0, 0.0, 1.0], 1.0);
    let cos = greenhill(|gamma: f64| {
        CosseratBuilder::new(up.clone(), p, shear)
            .elements(40)
            .clamp_start()
            .gravity(Vec3::new(0.0, 0.0, -gamma / p.linear_density))
            .build()
            .unwrap()
    });
    let se3 = greenhill(|gamma: f64| {
        Se3Builder::new(up.clone(), p, shear)
            .elements(40)
            .clamp_start()
            .gravity(Vec3::new(0.0, 0.0, -gamma / p.linear_density))
            .build()
            .unwrap()
    });
    for (name, g) in [("cosserat", cos), ("se3", se3)] {
        eprintln!(
            "Greenhill, {name}, N = 40: Γ_c = {g:.5} ({:+.3} %)",
            100.0 * (g / GREENHILL - 1.0)
        );
        assert!((g / GREENHILL - 1.0).abs() < 5e-3, "{name}: Γ_c = {g}");
    }
}

fn check_balance<P>(rod: &P, s: &FramedState, reactions: &[slender_core::rod::SupportReaction])
where
    P: std::ops::Deref<Target = slender_core::framed::FramedCore>,
{
    let applied = rod.applied_loads(s, 1.0);
    let mut force = applied.force;
    let mut moment = applied.moment;
    for r in reactions {
        force += r.force;
        moment += r.moment + s.positions()[r.vertex].cross(&r.force);
    }
    let scale = applied.force.norm() + applied.moment.norm();
    assert!(force.norm() < 1e-9 * scale, "force imbalance {force}");
    assert!(moment.norm() < 1e-9 * scale, "moment imbalance {moment}");
}

#[test]
fn reactions_balance_the_applied_loads() {
    let p = props(1e4, 1.0, 0.8);
    let shear = ShearStiffness::isotropic(5e3);
    let curve = RestCurve::Helix {
        start: [0.0; 3],
        axis: [0.0, 0.0, 1.0],
        normal: [1.0, 0.0, 0.0],
        radius: 0.3,
        pitch: 0.4,
        length: 1.5,
    };
    let cos = CosseratBuilder::new(curve.clone(), p, shear)
        .elements(15)
        .clamp_start()
        .pin(15)
        .gravity(Vec3::new(0.3, -20.0, -5.0))
        .point_force(7, Vec3::new(0.5, 0.2, -0.4))
        .point_moment(10, Vec3::new(0.1, 0.3, -0.2))
        .build()
        .unwrap();
    let s = solve(&cos, cos.rest_state(), tight());
    check_balance(&cos, &s, &cos.reactions(&s, 1.0));
    let se3 = Se3Builder::new(curve, p, shear)
        .elements(15)
        .clamp_start()
        .clamp_end()
        .gravity(Vec3::new(0.3, -20.0, -5.0))
        .point_force(7, Vec3::new(0.5, 0.2, -0.4))
        .point_moment(10, Vec3::new(0.1, 0.3, -0.2))
        .build()
        .unwrap();
    let s = solve(&se3, se3.rest_state(), tight());
    check_balance(&se3, &s, &se3.reactions(&s, 1.0));
}

/// The frames of `rod`'s rest state turned rigidly about the rod's own axis (x) by `angle`
/// (positions on the axis do not move).
fn twisted(rod: &slender_core::framed::FramedCore, angle: f64) -> FramedState {
    let r = nalgebra::Rotation3::from_axis_angle(&Vec3::x_axis(), angle);
    rod.rest_state().rigidly_transformed(&r, &Vec3::zeros())
}

#[test]
fn secant_prediction_follows_large_rigid_rotations() {
    // Two states a large rigid rotation apart; the predictor extrapolates
    // displace(s₁, difference(s₁, s₀)) and must land on the next state of the rotation.
    // Extrapolating the frames' absolute rotation vectors linearly (a plain difference of
    // "DOF values") misses it by O(1).
    let p = props(1e4, 1.0, 0.8);
    let cos = CosseratBuilder::new(
        line([1.0, 0.0, 0.0], 1.0),
        p,
        ShearStiffness::isotropic(5e3),
    )
    .elements(4)
    .pin(0)
    .pin(1)
    .pin(4)
    .build()
    .unwrap();
    let step = 1.2;
    let (s0, s1, s2) = (
        twisted(&cos, step),
        twisted(&cos, 2.0 * step),
        twisted(&cos, 3.0 * step),
    );
    let mut d = vec![0.0; cos.n_free()];
    cos.difference(&s1, &s0, &mut d);
    let mut predicted = s1.clone();
    cos.displace(&s1, &d, 1.0, &mut predicted);
    for (j, (a, b)) in predicted.frames().iter().zip(s2.frames()).enumerate() {
        assert!(a.angle_to(b) < 1e-12, "frame {j}: off by {}", a.angle_to(b));
        let log = |q: &UnitQuaternion<f64>| q.scaled_axis();
        let linear = log(&s1.frames()[j]) * 2.0 - log(&s0.frames()[j]);
        let wrong = UnitQuaternion::from_scaled_axis(linear);
        assert!(
            wrong.angle_to(b) > 0.1,
            "frame {j}: a linear extrapolation would be right"
        );
    }
    for (a, b) in predicted.positions().iter().zip(s2.positions()) {
        assert!((a - b).norm() < 1e-14);
    }
}

#[test]
fn clamp_rotation_along_the_load_path_twists_the_rod_uniformly() {
    // Turning the end clamp of a straight rod by T about its axis twists it uniformly: the
    // end clamp must hold it with the moment GJ·angle/L about the axis.
    let (gj, l, angle) = (0.8_f64, 1.0_f64, 2.5_f64);
    let p = props(1e4, 1.0, gj);
    let shear = ShearStiffness::isotropic(5e3);
    let motion = SupportMotion {
        vertices: vec![10],
        pivot: Vec3::new(l, 0.0, 0.0),
        rotation: Vec3::new(angle, 0.0, 0.0),
        translation: Vec3::zeros(),
    };
    let mut cos = CosseratBuilder::new(line([1.0, 0.0, 0.0], l), p, shear)
        .elements(10)
        .clamp_start()
        .clamp_end()
        .build()
        .unwrap();
    cos.set_load_path(RodLoadPath::support_motion(vec![motion.clone()]))
        .unwrap();
    let s = solve(&cos, cos.rest_state(), tight());
    // The sine Darboux measure makes the torque GJ sin(φ)/h̄ for a twist φ per cell: a
    // relative error φ²/6 ≈ 1 % with 10 elements, which vanishes like 1/N².
    let m = cos.reactions(&s, 1.0)[1].moment;
    assert!(
        (m.x / (gj * angle / l) - 1.0).abs() < 1.2e-2,
        "cosserat end moment {m}"
    );
    let mut se3 = Se3Builder::new(line([1.0, 0.0, 0.0], l), p, shear)
        .elements(10)
        .clamp_start()
        .clamp_end()
        .build()
        .unwrap();
    se3.set_load_path(RodLoadPath::support_motion(vec![motion]))
        .unwrap();
    let s = solve(&se3, se3.rest_state(), tight());
    let m = se3.reactions(&s, 1.0)[1].moment;
    assert!(
        (m.x / (gj * angle / l) - 1.0).abs() < 1e-9,
        "se3 end moment {m}"
    );
}

#[test]
fn full_dof_layout_interleaves_positions_and_frames() {
    assert_eq!(FramedDofs::full_vertex_slots(2), [12, 13, 14]);
    assert_eq!(FramedDofs::full_frame_slots(2), [15, 16, 17]);
    let _ = TermSet::ALL;
}
