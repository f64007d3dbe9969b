//! Every scene in `examples/` solved by the binary and checked against something independent
//! of the solver: a closed form, a reference solved here by another method, a symmetry, and
//! the balance of the reported reactions against loads computed here from the scene's data.

use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::Value;
use slender_core::solver::SolverParams;
use slender_validation::cantilever::master_curve::master_ratio;
use slender_validation::cantilever::{end_point_ratio, CantileverCase, MeshKind};
use slender_validation::materials::OMEGA_ROD;
use slender_validation::rod_model::RodModel;

type V3 = [f64; 3];

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn fresh_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("slender-examples-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

/// Runs `slender solve examples/<name>.toml` and returns the output directory.
fn solve(name: &str) -> PathBuf {
    solve_file(name, &repo().join("examples").join(format!("{name}.toml")))
}

/// `slender solve` of the scene file `scene` into a fresh output directory named `name`.
fn solve_file(name: &str, scene: &Path) -> PathBuf {
    let out = fresh_dir(name);
    let o = Command::new(env!("CARGO_BIN_EXE_slender"))
        .arg("solve")
        .arg(scene)
        .arg("--out")
        .arg(&out)
        .arg("--no-preview")
        .output()
        .expect("run slender");
    assert!(
        o.status.success(),
        "{name}: exit {:?}\n{}\n{}",
        o.status.code(),
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    out
}

fn step(out: &Path, k: usize) -> Value {
    let p = out.join(format!("step_{k:03}/result.json"));
    serde_json::from_str(&std::fs::read_to_string(&p).expect("result.json")).unwrap()
}

fn n_steps(out: &Path) -> usize {
    let r: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    assert_eq!(r["converged"], Value::Bool(true), "{}", out.display());
    r["steps"].as_u64().unwrap() as usize
}

fn v3(v: &Value) -> V3 {
    let a = v.as_array().unwrap();
    [0, 1, 2].map(|k| a[k].as_f64().unwrap())
}

fn positions(rod: &Value) -> Vec<V3> {
    rod["positions"]
        .as_array()
        .unwrap()
        .iter()
        .map(v3)
        .collect()
}

fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn scale(a: V3, s: f64) -> V3 {
    [a[0] * s, a[1] * s, a[2] * s]
}
fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn norm(a: V3) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}

/// Lumped vertex masses of a rod with rest vertices `rest` and mass per length `rho_a`: half
/// of each adjacent edge (computed here, not taken from the solver).
fn lumped_masses(rest: &[V3], rho_a: f64) -> Vec<f64> {
    let mut m = vec![0.0; rest.len()];
    for j in 0..rest.len() - 1 {
        let h = 0.5 * rho_a * norm(sub(rest[j + 1], rest[j]));
        m[j] += h;
        m[j + 1] += h;
    }
    m
}

/// Checks Σ reactions + gravity + point forces = 0 in force and in moment about the origin,
/// to `tol` relative to the largest term, with the loads computed here.
fn check_balance(
    what: &str,
    rod: &Value,
    rest: &[V3],
    rho_a: f64,
    gravity: V3,
    forces: &[(usize, V3)],
    tol: f64,
) {
    let x = positions(rod);
    let masses = lumped_masses(rest, rho_a);
    // (force, moment about the origin) of every load and reaction.
    let mut terms: Vec<(V3, V3)> = Vec::new();
    for (v, &mv) in masses.iter().enumerate() {
        let force = scale(gravity, mv);
        terms.push((force, cross(x[v], force)));
    }
    for &(v, force) in forces {
        terms.push((force, cross(x[v], force)));
    }
    for s in rod["supports"].as_array().unwrap() {
        let (p, rf) = (v3(&s["position"]), v3(&s["force"]));
        terms.push((rf, cross(p, rf)));
        terms.push(([0.0; 3], v3(&s["moment"])));
    }
    let f = terms.iter().fold([0.0; 3], |a, t| add(a, t.0));
    let m = terms.iter().fold([0.0; 3], |a, t| add(a, t.1));
    let f_scale: f64 = terms.iter().map(|t| norm(t.0)).sum();
    let m_scale: f64 = terms.iter().map(|t| norm(t.1)).sum();
    let length: f64 = rest.windows(2).map(|w| norm(sub(w[1], w[0]))).sum();
    let f_scale = f_scale.max(m_scale / length);
    assert!(
        norm(f) <= tol * f_scale,
        "{what}: force imbalance {:e} of {:e}",
        norm(f),
        f_scale
    );
    assert!(
        norm(m) <= tol * m_scale,
        "{what}: moment imbalance {:e} of {:e}",
        norm(m),
        m_scale
    );
    // The solver's own bookkeeping agrees.
    assert!(
        rod["relative_force_imbalance"].as_f64().unwrap() <= tol,
        "{what}"
    );
    assert!(
        rod["relative_moment_imbalance"].as_f64().unwrap() <= tol,
        "{what}"
    );
}

fn straight(start: V3, dir: V3, length: f64, n: usize) -> Vec<V3> {
    (0..=n)
        .map(|i| add(start, scale(dir, length * i as f64 / n as f64)))
        .collect()
}

fn circle_area(d: f64) -> f64 {
    std::f64::consts::PI * d * d / 4.0
}

/// Inextensible elastica of a cantilever with a dead tip force P (downward): EI θ'' = P cos θ,
/// θ(0) = 0, θ'(L) = 0, by RK4 shooting on θ'(0) with bisection. Returns the tip (x, z).
fn elastica_tip(p_over_ei: f64, length: f64) -> (f64, f64) {
    let steps = 4000;
    let h = length / steps as f64;
    // State (θ, θ', x, z); z up, force down: θ' decreasing to 0 at the tip means θ'(0) < 0.
    let rhs = |s: [f64; 4]| [s[1], p_over_ei * s[0].cos(), s[0].cos(), s[0].sin()];
    let shoot = |k0: f64| {
        let mut s = [0.0, k0, 0.0, 0.0];
        for _ in 0..steps {
            let k1 = rhs(s);
            let a = |s: [f64; 4], k: [f64; 4], c: f64| [0, 1, 2, 3].map(|i| s[i] + c * k[i]);
            let k2 = rhs(a(s, k1, 0.5 * h));
            let k3 = rhs(a(s, k2, 0.5 * h));
            let k4 = rhs(a(s, k3, h));
            s = [0, 1, 2, 3].map(|i| s[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]));
        }
        s
    };
    // θ'(L) grows monotonically with θ'(0); bracket the root in [−P L/EI, 0].
    let (mut lo, mut hi) = (-p_over_ei * length * 1.01, 0.0);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if shoot(mid)[1] < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let s = shoot(0.5 * (lo + hi));
    (s[2], s[3])
}

#[test]
fn elastica_reference_has_the_small_load_limit() {
    // δ = P L³/(3 EI) when P L²/EI → 0: the shooting reference itself is checked.
    let (_, z) = elastica_tip(1e-4, 1.0);
    assert!((-z / (1e-4 / 3.0) - 1.0).abs() < 1e-4, "{z}");
}

#[test]
fn cantilever_tip_force_matches_the_elastica() {
    let out = solve("cantilever_tip_force");
    assert_eq!(n_steps(&out), 1);
    let rod = &step(&out, 0)["rods"][0];
    let (e, d, p, l): (f64, f64, f64, f64) = (3.0e9, 0.004, 0.02, 1.0);
    let ei = e * std::f64::consts::PI * d.powi(4) / 64.0;
    let x = positions(rod);
    let tip = x[x.len() - 1];
    let (xr, zr) = elastica_tip(p / ei, l);
    // 40 elements: O(h²) discretization error of the discrete rod.
    assert!((tip[2] / zr - 1.0).abs() < 2e-3, "tip z {} vs {zr}", tip[2]);
    assert!((tip[0] - xr).abs() < 2e-3 * l, "tip x {} vs {xr}", tip[0]);
    let s = &rod["supports"][0];
    let rf = v3(&s["force"]);
    assert!(norm(sub(rf, [0.0, 0.0, p])) <= 1e-9 * p, "reaction {rf:?}");
    let rm = v3(&s["moment"]);
    let expected = scale(cross(tip, [0.0, 0.0, -p]), -1.0);
    assert!(
        norm(sub(rm, expected)) <= 1e-9 * p * l,
        "moment {rm:?} vs {expected:?}"
    );
    check_balance(
        "tip force",
        rod,
        &straight([0.0; 3], [1.0, 0.0, 0.0], l, 40),
        1140.0 * circle_area(d),
        [0.0; 3],
        &[(40, [0.0, 0.0, -p])],
        1e-9,
    );
}

#[test]
fn hanging_cable_is_symmetric_and_each_clamp_carries_half_the_weight() {
    let out = solve("hanging_cable");
    let rod = &step(&out, 0)["rods"][0];
    let x = positions(rod);
    let n = x.len() - 1;
    let l = 2.0;
    for i in 0..=n {
        let (a, b) = (x[i], x[n - i]);
        assert!((a[0] + b[0] - l).abs() < 1e-9 * l, "x symmetry at {i}");
        assert!((a[2] - b[2]).abs() < 1e-9 * l, "z symmetry at {i}");
        assert!(a[1].abs() < 1e-12);
    }
    assert!(x[n / 2][2] < 1.0, "it sags");
    let rho_a = 1600.0 * circle_area(0.008);
    let weight = rho_a * 9.81 * l;
    assert!(
        (weight
            / (9.81
                * lumped_masses(&straight([0.0; 3], [1.0, 0.0, 0.0], l, 40), rho_a)
                    .iter()
                    .sum::<f64>())
            - 1.0)
            .abs()
            < 1e-14
    );
    let s = rod["supports"].as_array().unwrap();
    let (f0, f1) = (v3(&s[0]["force"]), v3(&s[1]["force"]));
    assert!((f0[2] / (0.5 * weight) - 1.0).abs() < 1e-9, "{f0:?}");
    assert!((f1[2] / (0.5 * weight) - 1.0).abs() < 1e-9, "{f1:?}");
    assert!(
        (f0[0] + f1[0]).abs() < 1e-9 * weight,
        "horizontal forces mirror"
    );
    let (m0, m1) = (v3(&s[0]["moment"]), v3(&s[1]["moment"]));
    assert!((m0[1] + m1[1]).abs() < 1e-9 * weight * l, "moments mirror");
    check_balance(
        "hanging cable",
        rod,
        &straight([0.0, 0.0, 1.0], [1.0, 0.0, 0.0], l, 40),
        rho_a,
        [0.0, 0.0, -9.81],
        &[],
        1e-9,
    );
}

/// Rest vertices of an arc with the scene's parameters (uniform in arc length).
fn arc(start: V3, t: V3, nrm: V3, r: f64, length: f64, n: usize) -> Vec<V3> {
    (0..=n)
        .map(|i| {
            let phi = length * i as f64 / n as f64 / r;
            add(
                start,
                add(scale(t, r * phi.sin()), scale(nrm, r * (1.0 - phi.cos()))),
            )
        })
        .collect()
}

#[test]
fn u_cable_moved_in_steps_balances_at_every_step() {
    let out = solve("u_cable_moved");
    let steps = n_steps(&out);
    assert_eq!(steps, 11);
    let rest = arc(
        [0.0; 3],
        [0.0, 0.0, -1.0],
        [1.0, 0.0, 0.0],
        0.15,
        0.471_238_898_038_468_97,
        40,
    );
    let rho_a = 1500.0 * circle_area(0.006);
    // The discrete rod's mass is that of its rest chords.
    let weight = lumped_masses(&rest, rho_a).iter().sum::<f64>() * 9.81;
    // Step 0: symmetric about x = 0.15, half the weight on each clamp.
    let rod0 = &step(&out, 0)["rods"][0];
    let x = positions(rod0);
    for i in 0..=40 {
        assert!(
            (x[i][0] + x[40 - i][0] - 0.3).abs() < 1e-9,
            "symmetry at {i}"
        );
        assert!((x[i][2] - x[40 - i][2]).abs() < 1e-9, "symmetry at {i}");
    }
    for s in rod0["supports"].as_array().unwrap() {
        assert!((v3(&s["force"])[2] / (0.5 * weight) - 1.0).abs() < 1e-9);
    }
    let mut end = [0.3, 0.0, 0.0];
    for k in 0..steps {
        let rod = &step(&out, k)["rods"][0];
        check_balance(
            &format!("u cable step {k}"),
            rod,
            &rest,
            rho_a,
            [0.0, 0.0, -9.81],
            &[],
            1e-9,
        );
        // The moved clamp is where the motion put it.
        let p = v3(&rod["supports"][1]["position"]);
        if (1..=5).contains(&k) {
            end = [0.3 + 0.02 * k as f64, 0.0, 0.0];
        } else if k > 5 {
            end = [0.4, 0.0, 0.02 * (k - 5) as f64];
        }
        assert!(
            norm(sub(p, end)) < 1e-12,
            "step {k}: clamp at {p:?}, expected {end:?}"
        );
    }
    let csv = std::fs::read_to_string(out.join("steps.csv")).unwrap();
    assert_eq!(csv.lines().count(), 12, "a summary row per step");
    assert!(csv.lines().next().unwrap().contains("seconds"));
    for k in 0..steps {
        assert!(out.join(format!("step_{k:03}/shape.vtk")).exists());
        assert!(out.join(format!("step_{k:03}/shape.gltf")).exists());
    }
}

#[test]
fn coiled_cable_lifted_stretches_like_a_spring() {
    let out = solve("coiled_cable_lifted");
    let steps = n_steps(&out);
    assert_eq!(steps, 5);
    let (e, nu, d, coil_d, turns): (f64, f64, f64, f64, f64) = (1.0e9, 0.4, 0.002, 0.02, 8.0);
    let g = e / (2.0 * (1.0 + nu));
    let k_spring = g * d.powi(4) / (8.0 * coil_d.powi(3) * turns);
    let (r, pitch, length) = (0.01, 0.005, 0.504_243_862_300_660_7);
    let rise = pitch / (2.0 * std::f64::consts::PI);
    let speed = (r * r + rise * rise).sqrt();
    let rest: Vec<V3> = (0..=400)
        .map(|i| {
            let phi = length * i as f64 / 400.0 / speed;
            [r - r * phi.cos(), r * phi.sin(), rise * phi]
        })
        .collect();
    let rho_a = 1300.0 * circle_area(d);
    for k in 0..steps {
        let rod = &step(&out, k)["rods"][0];
        check_balance(
            &format!("coil step {k}"),
            rod,
            &rest,
            rho_a,
            [0.0; 3],
            &[],
            1e-9,
        );
        let delta = 0.005 * k as f64;
        let fz = v3(&rod["supports"][1]["force"])[2];
        if k > 0 {
            assert!(
                (fz / (k_spring * delta) - 1.0).abs() < 0.1,
                "step {k}: axial force {fz} vs spring law {}",
                k_spring * delta
            );
        }
    }
}

/// Errors of the final flat-cable step against the quarter circle: (largest distance from
/// the arc / R, largest reaction force / (M/R), largest |moment/M − 1|).
fn quarter_circle_errors(out: &Path, n: usize) -> [f64; 3] {
    let steps = n_steps(out);
    assert_eq!(steps, 9);
    let (e, w, h, l): (f64, f64, f64, f64) = (2.0e9, 0.01, 0.002, 0.25);
    let rho_a = 2000.0 * w * h;
    let rest = straight([0.0; 3], [1.0, 0.0, 0.0], l, n);
    for k in 0..steps {
        check_balance(
            &format!("flat cable ({n} elements) step {k}"),
            &step(out, k)["rods"][0],
            &rest,
            rho_a,
            [0.0; 3],
            &[],
            1e-9,
        );
    }
    let rod = &step(out, steps - 1)["rods"][0];
    let radius = 2.0 * l / std::f64::consts::PI;
    let mut dev: f64 = 0.0;
    for p in positions(rod) {
        let dist = (p[0].powi(2) + (p[1] - radius).powi(2)).sqrt();
        dev = dev.max((dist / radius - 1.0).abs());
        assert!(p[2].abs() < 1e-9 * l, "the ribbon left its plane");
    }
    let m = e * w * h.powi(3) / 12.0 / radius;
    let s = rod["supports"].as_array().unwrap();
    let mut force: f64 = 0.0;
    let mut moment: f64 = 0.0;
    for (k, sign) in [(0, -1.0), (1, 1.0)] {
        let rm = v3(&s[k]["moment"]);
        assert!(rm[0].abs() + rm[1].abs() < 1e-9 * m, "moment about z only");
        moment = moment.max((rm[2] / (sign * m) - 1.0).abs());
        force = force.max(norm(v3(&s[k]["force"])) / (m / radius));
    }
    [dev, force, moment]
}

#[test]
fn flat_cable_bent_by_its_clamps_converges_to_a_quarter_circle() {
    // The example (20 elements) and the same scene refined to 40: the closed-form quarter
    // circle is approached at the rate O(h²) of the discrete rod.
    let coarse = quarter_circle_errors(&solve("flat_cable_corner"), 20);
    let text = std::fs::read_to_string(repo().join("examples/flat_cable_corner.toml")).unwrap();
    assert!(text.contains("elements = 20"));
    let fine_scene = fresh_dir("flat_cable_40.toml");
    std::fs::write(&fine_scene, text.replace("elements = 20", "elements = 40")).unwrap();
    let out = fresh_dir("flat_cable_40");
    let o = Command::new(env!("CARGO_BIN_EXE_slender"))
        .args(["solve", "--no-preview", "--out"])
        .arg(&out)
        .arg(&fine_scene)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let fine = quarter_circle_errors(&out, 40);
    assert!(
        coarse[0] < 1e-3 && coarse[1] < 5e-2 && coarse[2] < 1e-2,
        "{coarse:?}"
    );
    for k in 0..3 {
        assert!(
            coarse[k] / fine[k] > 3.5,
            "error {k} does not converge like h²: {coarse:?} → {fine:?}"
        );
    }
}

#[test]
fn cantilever_scene_reproduces_the_benchmark() {
    let out = solve("cantilever_benchmark");
    let rod = &step(&out, 0)["rods"][0];
    let x = positions(rod);
    let (a, b) = (x[0], x[x.len() - 1]);
    let ratio = (a[1] - b[1]) / (b[0] - a[0]);
    let case = CantileverCase {
        material: OMEGA_ROD,
        mesh: MeshKind::Graded,
        n_elements: 20,
        gamma: 10.0,
    };
    // Both solves are run to round-off (the scene solver polishes past the default tolerance),
    // so that they agree on the discrete equilibrium itself.
    let tight = SolverParams {
        force_tolerance: 1e-14,
        energy_tolerance: 1e-30,
        ..SolverParams::default()
    };
    let run = case.run(&tight).unwrap();
    assert!(run.report.converged());
    assert_eq!(end_point_ratio(&run.positions), run.ratio);
    assert!(
        (ratio - run.ratio).abs() <= 1e-10 * run.ratio.abs(),
        "scene Δy/Δx = {ratio}, benchmark {}",
        run.ratio
    );
    let g = OMEGA_ROD.gravity_for_gamma(10.0);
    let rest: Vec<V3> = case
        .build()
        .unwrap()
        .rest_state()
        .positions()
        .iter()
        .map(|p| [p.x, p.y, p.z])
        .collect();
    check_balance(
        "cantilever benchmark",
        rod,
        &rest,
        OMEGA_ROD.properties.linear_density,
        [0.0, -g, 0.0],
        &[],
        1e-9,
    );
}

#[test]
fn rod_models_cantilever_matches_each_models_benchmark_and_the_master_curve() {
    let out = solve("rod_models_cantilever");
    let s0 = step(&out, 0);
    let g = OMEGA_ROD.gravity_for_gamma(10.0);
    let master = master_ratio(10.0).unwrap();
    let shear = OMEGA_ROD.shear();
    let text = std::fs::read_to_string(repo().join("examples/rod_models_cantilever.toml")).unwrap();
    assert!(
        text.contains(&format!("[{:?}, {:?}]", shear.ga1, shear.ga2)),
        "the file's shear stiffness is Ω_rod's solid-circle κGA = {}",
        shear.ga1
    );
    let case = CantileverCase {
        material: OMEGA_ROD,
        mesh: MeshKind::Graded,
        n_elements: 20,
        gamma: 10.0,
    };
    let tight = SolverParams {
        force_tolerance: 1e-14,
        energy_tolerance: 1e-30,
        ..SolverParams::default()
    };
    for (k, model) in [RodModel::Der, RodModel::Cosserat, RodModel::Se3]
        .into_iter()
        .enumerate()
    {
        let rod = &s0["rods"][k];
        assert_eq!(rod["name"].as_str().unwrap(), model.name());
        let x = positions(rod);
        let (a, b) = (x[0], x[x.len() - 1]);
        let ratio = (a[1] - b[1]) / (b[0] - a[0]);
        let run = case.run_with(model, &tight).unwrap();
        assert!(run.report.converged());
        assert!(
            (ratio - run.ratio).abs() <= 1e-10 * run.ratio.abs(),
            "{}: scene Δy/Δx = {ratio}, benchmark {}",
            model.name(),
            run.ratio
        );
        let err = ratio / master - 1.0;
        assert!(
            err.abs() < 5e-3,
            "{}: {err:+.2e} from the master curve",
            model.name()
        );
        assert!(rod["relative_force_imbalance"].as_f64().unwrap() <= 1e-9);
        assert!(rod["relative_moment_imbalance"].as_f64().unwrap() <= 1e-9);
        // The clamp carries the whole weight ρA g L.
        let fy = rod["supports"][0]["force"][1].as_f64().unwrap();
        let weight = OMEGA_ROD.properties.linear_density * g;
        assert!(
            (fy / weight - 1.0).abs() < 1e-9,
            "{}: {fy} vs {weight}",
            model.name()
        );
    }
}

#[test]
fn clipped_cable_with_interior_clamp_balances() {
    let out = solve("clipped_cable");
    let rod = &step(&out, 0)["rods"][0];
    let r = &rod["supports"];
    assert_eq!(r.as_array().unwrap().len(), 4);
    // The solver's balance includes the point moment; check its figures and that the clip and
    // the clamps carry moments while the pin does not.
    assert!(rod["relative_force_imbalance"].as_f64().unwrap() <= 1e-9);
    assert!(rod["relative_moment_imbalance"].as_f64().unwrap() <= 1e-9);
    assert_eq!(norm(v3(&r[3]["moment"])), 0.0, "a pin carries no moment");
    assert!(norm(v3(&r[1]["moment"])) > 0.0, "a clip holds the tangent");
    // Force balance with loads computed here: weight + point force.
    let rest_points = [
        [0.0, 0.0, 0.0],
        [0.5, 0.0, 0.0],
        [0.8, 0.3, 0.0],
        [1.0, 0.3, 0.1],
    ];
    // Rest vertices: 40 uniform steps of arc length along the polyline.
    let seg: Vec<f64> = rest_points
        .windows(2)
        .map(|w| norm(sub(w[1], w[0])))
        .collect();
    let length: f64 = seg.iter().sum();
    let rest: Vec<V3> = (0..=40)
        .map(|i| {
            let mut s = length * i as f64 / 40.0;
            for (k, &l) in seg.iter().enumerate() {
                if s <= l || k == seg.len() - 1 {
                    let t = scale(sub(rest_points[k + 1], rest_points[k]), 1.0 / l);
                    return add(rest_points[k], scale(t, s.min(l)));
                }
                s -= l;
            }
            unreachable!()
        })
        .collect();
    let weight: f64 = lumped_masses(&rest, 1400.0 * circle_area(0.006))
        .iter()
        .sum::<f64>()
        * 9.81;
    let mut f = [0.0, 0.5, -weight];
    let mut f_scale = weight + 0.5;
    for s in r.as_array().unwrap() {
        f = add(f, v3(&s["force"]));
        f_scale += norm(v3(&s["force"]));
    }
    assert!(norm(f) < 1e-9 * f_scale, "force imbalance {f:?}");
}

#[test]
fn a_json_scene_gives_the_same_equilibrium_as_its_toml() {
    let text = std::fs::read_to_string(repo().join("examples/u_cable_moved.toml")).unwrap();
    let value: toml::Value = toml::from_str(&text).unwrap();
    let dir = fresh_dir("json-scene");
    std::fs::create_dir_all(&dir).unwrap();
    let scene = dir.join("u_cable_moved.json");
    std::fs::write(&scene, serde_json::to_string_pretty(&value).unwrap()).unwrap();
    let out = dir.join("out");
    let o = Command::new(env!("CARGO_BIN_EXE_slender"))
        .args(["solve", "--no-preview", "--out"])
        .arg(&out)
        .arg(&scene)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let toml_out = solve("u_cable_moved");
    for k in [0, 10] {
        let a = step(&out, k);
        let b = step(&toml_out, k);
        assert_eq!(
            a["rods"][0]["positions"], b["rods"][0]["positions"],
            "step {k}"
        );
    }
}

#[test]
fn shell_cantilever_scene_matches_the_heavy_elastica_master_curve() {
    use slender_validation::cantilever::master_curve::master_ratio;
    let out = solve("flat_cable_shell_cantilever");
    assert_eq!(n_steps(&out), 1);
    let r = step(&out, 0);
    let sh = &r["shells"][0];
    assert_eq!(sh["converged"], Value::Bool(true));
    // The scene's data (examples/flat_cable_shell_cantilever.toml), ν = 0: D·w = E I.
    let (l, w, h, e, rho, g) = (0.3, 0.03, 0.2e-3, 10530e6, 1000.0, 9.81);
    let d = e * h * h * h / 12.0;
    let gamma = rho * h * g * l * l * l / d;
    let p = positions(sh);
    let [nl, nw] = [15, 2];
    assert_eq!(p.len(), (nl + 1) * (nw + 1));
    // Centre line: the middle column (n_W even).
    let a = p[nw / 2];
    let b = p[nl * (nw + 1) + nw / 2];
    let ratio = (a[1] - b[1]) / (b[0] - a[0]);
    let master = master_ratio(gamma).unwrap();
    let err = (ratio - master) / master;
    eprintln!("Γ = {gamma:.4}: shell Δy/Δx = {ratio:.6}, master {master:.6}, error {err:+.3e}");
    // The shell's documented accuracy at n_L = 15 (README, "Shells"): ≤ 1 %.
    assert!(err.abs() <= 0.01, "relative error {err:e}");
    // The clamp edge did not move; the strip's length is kept (membrane is stiff).
    for q in &p[..=nw] {
        assert!(q[0].abs() < 1e-15 && q[1].abs() < 1e-15, "{q:?}");
    }
    let arc: f64 = (0..nl)
        .map(|i| norm(sub(p[(i + 1) * (nw + 1) + 1], p[i * (nw + 1) + 1])))
        .sum();
    assert!((arc - l).abs() < 1e-5 * l, "centre-line length {arc}");
    // Total load: the weight ρ h w L g, computed here from the scene's data.
    let f = v3(&sh["applied_force"]);
    let weight = rho * h * w * l * g;
    assert!(
        (f[1] + weight).abs() < 1e-12 * weight && f[0] == 0.0 && f[2] == 0.0,
        "{f:?}"
    );
    // The clamp force (differentiated from the energy on the held vertices) carries it.
    let c = v3(&sh["clamp_force"]);
    let off = norm(add(c, [0.0, -weight, 0.0])) / weight;
    eprintln!("clamp force {c:?}, weight {weight:e}, relative imbalance {off:.2e}");
    assert!(off < 1e-6, "clamp force {c:?} vs weight {weight}");
    // The solver report is in solver.csv like a rod's.
    let csv = std::fs::read_to_string(out.join("solver.csv")).unwrap();
    assert!(
        csv.lines().any(|l| l.starts_with("0,strip,0,true,")),
        "{csv}"
    );
}

/// Complete elliptic integrals K(m), E(m) (parameter m = k²) by the arithmetic–geometric mean.
fn elliptic_ke(m: f64) -> (f64, f64) {
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

/// Midspan deflection (m) of Euler's pinned–pinned elastica of length `l` under an axial dead
/// load P with P/P_E = `ratio` > 1 (P_E = π²EI/l²): P/P_E = (2K(k)/π)², deflection = k·l/K(k).
fn pinned_elastica_deflection(l: f64, ratio: f64) -> f64 {
    let (mut lo, mut hi) = (1e-12_f64, 0.999_999_f64);
    for _ in 0..200 {
        let k = 0.5 * (lo + hi);
        let kk = elliptic_ke(k * k).0;
        if (2.0 * kk / std::f64::consts::PI).powi(2) < ratio {
            lo = k;
        } else {
            hi = k;
        }
    }
    let k = 0.5 * (lo + hi);
    k * l / elliptic_ke(k * k).0
}

fn transverse_max(rod: &Value) -> f64 {
    positions(rod)
        .iter()
        .map(|p| (p[1] * p[1] + p[2] * p[2]).sqrt())
        .fold(0.0, f64::max)
}

#[test]
fn pinned_pinned_column_buckles_to_the_elastica() {
    let out = solve("pinned_pinned_column");
    let s = step(&out, 0);
    assert_eq!(s["stable"], Value::Bool(true));
    let rod = &s["rods"][0];
    let w = transverse_max(rod);
    let exact = pinned_elastica_deflection(1.0, 1.2);
    assert!(
        (w / exact - 1.0).abs() < 1e-2,
        "deflection {w} vs elastica {exact}"
    );
    // The slider's reaction has no component along its axis; the pin and slider balance the
    // axial force.
    let sup = rod["supports"].as_array().unwrap();
    let slider = v3(&sup[2]["force"]);
    let load = 1.2 * std::f64::consts::PI.powi(2);
    assert!(
        slider[0].abs() < 1e-8 * load,
        "slider force along its axis {}",
        slider[0]
    );
    let pin = v3(&sup[0]["force"]);
    assert!((pin[0] - load).abs() < 1e-6 * load, "pin {pin:?}");
}

#[test]
fn clamped_pinned_column_buckles_above_its_critical_load() {
    let out = solve("clamped_pinned_column");
    let s = step(&out, 0);
    assert_eq!(s["stable"], Value::Bool(true));
    let st = &s["structures"][0]["stability"];
    assert_eq!(st["followed_unstable_mode"], Value::Bool(true), "{st}");
    assert!(transverse_max(&s["rods"][0]) > 0.05);
    // The critical load 20.1907 EI/L² by the inertia: 2 % below it the straight column is
    // stable, 2 % above it unstable.
    let text = std::fs::read_to_string(repo().join("examples/clamped_pinned_column.toml")).unwrap();
    for (f, stable) in [(0.98, true), (1.02, false)] {
        let p = f * 20.1907;
        let scene = text
            .replace("unstable = \"follow\"", "unstable = \"keep\"")
            .replace("-22.20977", &format!("{:.6}", -p));
        let d = fresh_dir(&format!("clamped-pinned-{f}"));
        std::fs::create_dir_all(&d).unwrap();
        std::fs::write(d.join("s.toml"), scene).unwrap();
        let o = Command::new(env!("CARGO_BIN_EXE_slender"))
            .args(["solve", "--no-preview", "--out"])
            .arg(d.join("out"))
            .arg(d.join("s.toml"))
            .output()
            .unwrap();
        assert_eq!(
            o.status.success(),
            stable,
            "P/Pcr = {f}: exit {:?}",
            o.status.code()
        );
        let s = step(&d.join("out"), 0);
        assert_eq!(s["stable"], Value::Bool(stable), "P/Pcr = {f}");
    }
}

#[test]
fn a_cable_through_a_sliding_clip_balances_and_slides_freely() {
    let out = solve("sliding_clip_cable");
    let s = step(&out, 0);
    let rod = &s["rods"][0];
    assert!(rod["relative_force_imbalance"].as_f64().unwrap() < 1e-9);
    assert!(rod["relative_moment_imbalance"].as_f64().unwrap() < 1e-9);
    let sleeve = v3(&rod["supports"][1]["force"]);
    let weight: f64 = 1400.0 * circle_area(0.006) * 1.2 * 9.81;
    assert!(
        sleeve[2].abs() < 1e-8 * weight,
        "force along the sleeve's axis {}",
        sleeve[2]
    );
    assert!(
        sleeve[1] > 0.1 * weight,
        "the sleeve carries part of the weight: {sleeve:?}"
    );
}

#[test]
fn a_hanging_ring_is_symmetric_and_its_clamp_carries_its_weight() {
    let out = solve("hanging_ring");
    let s = step(&out, 0);
    let rod = &s["rods"][0];
    let x = positions(rod);
    let n = x.len() - 1;
    // Mirror symmetry about the vertical plane x = 0 through the clamp: vertex v ↔ n − v.
    for v in 0..=n {
        let (a, b) = (x[v], x[n - v]);
        assert!(
            (a[0] + b[0]).abs() < 1e-8 && (a[2] - b[2]).abs() < 1e-8,
            "vertex {v}: {a:?} {b:?}"
        );
    }
    // The mass of the discrete ring: its rest polygon of 48 chords inscribed in the circle.
    let perimeter = 96.0 * 0.15 * (std::f64::consts::PI / 48.0).sin();
    let weight = 1200.0 * circle_area(0.004) * perimeter * 9.81;
    let fz: f64 = rod["supports"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| v3(&s["force"])[2])
        .sum();
    assert!(
        (fz / weight - 1.0).abs() < 1e-6,
        "clamp {fz} vs weight {weight}"
    );
    assert_eq!(s["stable"], Value::Bool(true));
}

/// The planar elastica of a cantilever with a follower tip force F perpendicular to the tip
/// tangent: EI θ'' = sin θ F_x − cos θ F_y with F = F(−sin θ_L, cos θ_L), θ(L) = θ_L,
/// θ'(L) = 0, shot from the tip to the clamp on θ_L ∈ [0, `max_turn`] (bisection) so that
/// θ(0) = 0. Returns the tip (x, y).
fn follower_elastica_tip(f_over_ei: f64, length: f64, max_turn: f64) -> (f64, f64) {
    let steps = 4000;
    let h = length / steps as f64;
    // Integrate from the tip (s = L) backward: state (θ, θ', x − x_L, y − y_L).
    let run = |theta_l: f64| {
        let (fx, fy) = (-theta_l.sin() * f_over_ei, theta_l.cos() * f_over_ei);
        let rhs = |s: [f64; 4]| {
            [
                s[1],
                s[0].sin() * fx - s[0].cos() * fy,
                s[0].cos(),
                s[0].sin(),
            ]
        };
        let mut s = [theta_l, 0.0, 0.0, 0.0];
        for _ in 0..steps {
            let a = |s: [f64; 4], k: [f64; 4], c: f64| [0, 1, 2, 3].map(|i| s[i] + c * k[i]);
            let k1 = rhs(s);
            let k2 = rhs(a(s, k1, -0.5 * h));
            let k3 = rhs(a(s, k2, -0.5 * h));
            let k4 = rhs(a(s, k3, -h));
            s = [0, 1, 2, 3].map(|i| s[i] - h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]));
        }
        s
    };
    let (mut lo, mut hi) = (0.0, max_turn);
    assert!(
        run(hi)[0] > 0.0,
        "the bracket [0, {max_turn}] holds no tip angle"
    );
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if run(mid)[0] > 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let s = run(0.5 * (lo + hi));
    // s[2], s[3] are the clamp's coordinates relative to the tip.
    (-s[2], -s[3])
}

#[test]
fn a_follower_loaded_cantilever_matches_the_follower_elastica() {
    let out = solve("follower_cantilever");
    let s = step(&out, 0);
    let x = positions(&s["rods"][0]);
    let tip = x[x.len() - 1];
    let (ex, ey) = follower_elastica_tip(2.0, 1.0, 1.5);
    let err = ((tip[0] - ex).powi(2) + (tip[1] - ey).powi(2)).sqrt();
    // Discretization error of 40 elements (second order, a few 1e-4).
    assert!(err < 2e-3, "tip {tip:?} vs follower elastica ({ex}, {ey})");
    // A dead force of the same size (F L²/EI = 2) leaves the tip near (0.84, 0.49) (Bisshopp
    // & Drucker's tables): the follower load bends it further round.
    assert!(tip[1] > 0.55 && tip[0] < 0.8, "{tip:?}");
}

#[test]
fn a_cantilever_curled_by_a_follower_force_matches_the_follower_elastica() {
    // F L²/EI = 6: the tip turns past π/2. The lagged follower iteration alone contracts
    // about as F L²/EI: it diverges here, and the Anderson mixing of `solver::lagged_loads`
    // is what settles it.
    let text = std::fs::read_to_string(repo().join("examples/follower_cantilever.toml"))
        .unwrap()
        .replace("force = [0.0, 2.0, 0.0]", "force = [0.0, 6.0, 0.0]");
    assert!(text.contains("[0.0, 6.0, 0.0]"));
    let dir = fresh_dir("follower_curled_scene");
    std::fs::create_dir_all(&dir).unwrap();
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, text).unwrap();
    // Curled this far, the frozen-load Hessian has a negative eigenvalue (a dead load of
    // the tip force's direction would swing the tip round): reported, and not followed —
    // its modes say nothing of the follower load's stability.
    let out = fresh_dir("follower_curled");
    let o = Command::new(env!("CARGO_BIN_EXE_slender"))
        .args(["solve", "--no-preview", "--out"])
        .arg(&out)
        .arg(&scene)
        .output()
        .expect("run slender");
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        stderr.contains("follower loads: the Hessian is the frozen loads'"),
        "{stderr}"
    );
    let s = step(&out, 0);
    assert_eq!(s["converged"], Value::Bool(true));
    let x = positions(&s["rods"][0]);
    let tip = x[x.len() - 1];
    let (ex, ey) = follower_elastica_tip(6.0, 1.0, 3.0);
    let err = ((tip[0] - ex).powi(2) + (tip[1] - ey).powi(2)).sqrt();
    eprintln!("F L²/EI = 6: tip {tip:?}, follower elastica ({ex:.6}, {ey:.6}), {err:.2e} apart");
    assert!(err < 5e-3, "tip {tip:?} vs follower elastica ({ex}, {ey})");
    assert!(tip[0] < 0.5, "curled: {tip:?}");
}

#[test]
fn a_branched_harness_stays_joined_and_balances_its_weight() {
    let out = solve("branched_harness");
    let s = step(&out, 0);
    let rods = s["rods"].as_array().unwrap();
    let joint = positions(&rods[0]).last().copied().unwrap();
    for r in &rods[1..] {
        let p = positions(r)[0];
        assert!(
            norm(sub(p, joint)) < 1e-12,
            "{} left the joint: {p:?} vs {joint:?}",
            r["name"]
        );
    }
    let st = &s["structures"][0];
    assert_eq!(st["rods"].as_array().unwrap().len(), 3, "{st}");
    assert!(
        st["relative_force_imbalance"].as_f64().unwrap() < 1e-9,
        "{st}"
    );
    assert!(
        st["relative_moment_imbalance"].as_f64().unwrap() < 1e-9,
        "{st}"
    );
    // The two clamps carry the whole weight, computed here.
    let rho = 1800.0 * 9.81;
    let weight = rho * (circle_area(0.01) * 0.4 + circle_area(0.006) * (0.35 + 0.3));
    let fz: f64 = rods
        .iter()
        .flat_map(|r| r["supports"].as_array().unwrap().iter())
        .map(|s| v3(&s["force"])[2])
        .sum();
    assert!(
        (fz / weight - 1.0).abs() < 1e-6,
        "clamps {fz} vs weight {weight}"
    );
}

#[test]
fn a_swinging_cable_conserves_energy_and_writes_its_frames() {
    let out = solve("swinging_cable");
    let report: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    assert_eq!(report["converged"], Value::Bool(true));
    let time = &report["time"];
    assert_eq!(time["steps"], 500, "{time}");
    assert_eq!(time["steps_taken"], 500, "{time}");
    let frames = time["frames"].as_u64().unwrap() as usize;
    assert_eq!(frames, 101, "frame 0 and every 5th of 500 steps");
    // The data of the scene, repeated here.
    let (length, n, d, rho, g) = (1.0, 30usize, 0.006, 1600.0, 9.81);
    let rho_a = rho * circle_area(d);
    let h = length / n as f64;
    let mass = |i: usize| rho_a * h * if i == 0 || i == n { 0.5 } else { 1.0 };
    let rest_z = 1.0;
    // Gravity energy computed here from the written positions and the lumped masses;
    // energy conserved to 1e-5 of the largest kinetic energy with it.
    let mut max_kinetic: f64 = 0.0;
    let mut max_change: f64 = 0.0;
    let mut lowest_tip: f64 = f64::INFINITY;
    let mut last_t = 0.0;
    for k in 0..frames {
        let s = step(&out, k);
        let tf = &s["time"];
        let e = &tf["energy"];
        let kinetic = e["kinetic"].as_f64().unwrap();
        let elastic = e["elastic"].as_f64().unwrap();
        let p = positions(&s["rods"][0]);
        assert_eq!(p.len(), n + 1);
        assert!(norm(sub(p[0], [0.0, 0.0, 1.0])) < 1e-12, "the clamp moved");
        let gravity: f64 = (0..=n).map(|i| mass(i) * g * (p[i][2] - rest_z)).sum();
        let reported = e["gravity_and_loads"].as_f64().unwrap();
        assert!(
            (gravity - reported).abs() <= 1e-9 * rho_a * g * length * length,
            "frame {k}: gravity energy {gravity} here, {reported} reported"
        );
        max_kinetic = max_kinetic.max(kinetic);
        max_change = max_change.max((kinetic + elastic + gravity).abs());
        lowest_tip = lowest_tip.min(p[n][2]);
        last_t = tf["t"].as_f64().unwrap();
    }
    let drift = max_change / max_kinetic;
    println!(
        "swinging cable: max |E - E0| / max kinetic = {drift:.3e} (max kinetic {max_kinetic:.4e} J)"
    );
    assert!(drift <= 1e-5, "energy drift {drift:.3e}");
    // Each point falls at most its distance from the clamp: the kinetic energy is below the
    // weight times L/2, and the swing is large.
    let bound = rho_a * g * length * length / 2.0;
    assert!(
        max_kinetic < bound && max_kinetic > 0.1 * bound,
        "{max_kinetic} vs {bound}"
    );
    assert!(
        rest_z - lowest_tip > 0.25 * length,
        "tip fell to {lowest_tip}"
    );
    assert!((last_t - 1.0).abs() < 1e-12, "{last_t}");
    // The ParaView collection lists every frame with its time; frames.csv has one row each.
    let pvd = std::fs::read_to_string(out.join("frames.pvd")).unwrap();
    assert_eq!(pvd.matches("<DataSet ").count(), frames);
    assert!(pvd.contains("timestep=\"1e0\" group=\"\" part=\"0\" file=\"step_100/shape.vtp\""));
    assert!(out.join("step_100/shape.vtp").exists() && out.join("step_100/shape.vtk").exists());
    let rows = std::fs::read_to_string(out.join("frames.csv")).unwrap();
    assert_eq!(rows.lines().count(), frames + 1);
    // The animated glTF of the swing.
    let worst = check_animated_gltf(&out, frames);
    println!("swinging cable: frames.gltf centerlines within {worst:.2e} m of the frames'");
}

#[test]
fn a_time_step_that_fails_stops_the_run_and_every_output_says_so() {
    // The swinging cable on 100 elements with steps of 50 ms: the energy-conserving scheme's
    // Newton solve fails once edges turn too far per step (ARCHITECTURE.md, "Dynamics").
    let text = std::fs::read_to_string(repo().join("examples/swinging_cable.toml"))
        .unwrap()
        .replace("elements = 30", "elements = 100")
        .replace("dt = 0.002", "dt = 0.05")
        .replace("duration = 1.0", "duration = 3.0")
        .replace("output_every = 5", "output_every = 1");
    let d = fresh_dir("failing_swing");
    std::fs::create_dir_all(&d).unwrap();
    let scene = d.join("s.toml");
    std::fs::write(&scene, text).unwrap();
    let out = d.join("out");
    let o = Command::new(env!("CARGO_BIN_EXE_slender"))
        .args([
            "solve",
            scene.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ])
        .arg("--no-preview")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("did not converge"), "{stderr}");
    let report: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    assert_eq!(report["converged"], Value::Bool(false));
    let time = &report["time"];
    let taken = time["steps_taken"].as_u64().unwrap() as usize;
    assert!(taken < 60, "{time}");
    assert!(time["failure"]
        .as_str()
        .unwrap()
        .contains("did not converge"));
    // One frame per step taken (and frame 0); none for the failed step.
    let frames = time["frames"].as_u64().unwrap() as usize;
    assert_eq!(frames, taken + 1);
    assert!(out.join(format!("step_{:03}", frames - 1)).exists());
    assert!(!out.join(format!("step_{frames:03}")).exists());
    let pvd = std::fs::read_to_string(out.join("frames.pvd")).unwrap();
    assert_eq!(pvd.matches("<DataSet ").count(), frames);
    assert!(pvd.contains("stopped early"));
    let csv = std::fs::read_to_string(out.join("frames.csv")).unwrap();
    let last = csv.lines().last().unwrap();
    assert!(
        last.contains(",false,") && last.contains("did not converge"),
        "{last}"
    );
    assert_eq!(
        csv.lines().count(),
        frames + 2,
        "header, frames, the failed step"
    );
}

/// The flat cable between two connectors (examples/flat_cable_two_connectors.toml): a shell
/// strip clamped at both ends at poses, then one clamp moved by a motion stage. Its centre
/// line against the equivalent rod (ν = 0: E I = D w; the same clamps, moved to the same
/// poses by motion stages), the clamped edges at the connectors' poses, the balance with the
/// weight, the kept length.
#[test]
fn flat_cable_between_two_connectors_matches_its_rod_limit() {
    use slender_core::scene::{Scene, Session};
    let out = solve("flat_cable_two_connectors");
    assert_eq!(n_steps(&out), 3);
    let (l, w, h, rho, g) = (0.3, 0.02, 0.3e-3, 2000.0, 9.81);
    let [nl, nw] = [30, 2];
    // The equivalent rod: m₁ along the width (z), bending in the xy-plane about the weak axis.
    let rod: Scene = toml::from_str(
        r#"
gravity = [0.0, -9.81, 0.0]
[[rods]]
elements = 30
centerline = { kind = "straight", start = [0.0, 0.0, 0.0], direction = [1.0, 0.0, 0.0], length = 0.3 }
first_director = [0.0, 0.0, 1.0]
section = { shape = "rectangle", width = 0.02, height = 0.3e-3 }
material = { young = 5.0e9, poisson = 0.0, density = 2000.0 }
supports = [{ kind = "clamp", vertex = "start" }, { kind = "clamp", vertex = "end" }]
[[motion]]
rod = 0
support = 1
translate = [-0.08, 0.04, 0.0]
rotate = [0.0, 0.0, 0.6]
steps = 6
[[motion]]
rod = 0
support = 1
translate = [0.0, -0.02, 0.0]
steps = 2
"#,
    )
    .unwrap();
    let mut session = Session::new(rod).unwrap();
    for k in 1..=6 {
        assert!(session.run_motion_step(k).converged);
    }
    let weight = rho * h * w * l * g;
    for k in 0..3 {
        if k > 0 {
            assert!(session.run_motion_step(6 + k).converged);
        }
        let rod = session.results(0, None, 1.0, 1);
        let rp: Vec<V3> = rod.rods[0].positions.clone();
        let r = step(&out, k);
        let sh = &r["shells"][0];
        assert_eq!(sh["converged"], Value::Bool(true), "step {k}");
        let p = positions(sh);
        assert_eq!(p.len(), (nl + 1) * (nw + 1));
        // Centre line: the middle column; the rod's vertices sit at the same rest stations.
        let worst = (0..=nl)
            .map(|i| norm(sub(p[i * (nw + 1) + nw / 2], rp[i])))
            .fold(0.0, f64::max);
        eprintln!(
            "step {k}: strip vs rod, largest distance {:.3e} L",
            worst / l
        );
        assert!(worst < 1e-3 * l, "step {k}: {worst:e} m");
        // The clamped edges: x = 0 at rest, x = L at the connector's pose
        // c + offset + R(x − c), offset (−0.08, 0.04 − 0.01 k, 0): R turns about z, the
        // edge's own line through c, so the edge's points only translate.
        for j in 0..=nw {
            let z = -0.5 * w + w * j as f64 / nw as f64;
            let q0 = p[j];
            assert!(norm(sub(q0, [0.0, 0.0, z])) < 1e-15, "{q0:?}");
            let q1 = p[nl * (nw + 1) + j];
            let want = [l - 0.08, 0.04 - 0.01 * k as f64, z];
            assert!(norm(sub(q1, want)) < 1e-14, "step {k}: {q1:?} vs {want:?}");
        }
        // The centre line keeps its length (the membrane is stiff).
        let arc: f64 = (0..nl)
            .map(|i| norm(sub(p[(i + 1) * (nw + 1) + 1], p[i * (nw + 1) + 1])))
            .sum();
        assert!(
            (arc - l).abs() < 1e-4 * l,
            "step {k}: centre-line length {arc}"
        );
        // The clamps carry the weight, computed here from the scene's data.
        let f = v3(&sh["applied_force"]);
        assert!((f[1] + weight).abs() < 1e-12 * weight, "{f:?}");
        let cf = v3(&sh["clamp_force"]);
        let off = norm(add(cf, [0.0, -weight, 0.0])) / weight;
        assert!(
            off < 1e-6,
            "step {k}: clamp force {cf:?} vs weight {weight}"
        );
    }
}

#[test]
fn a_cable_over_a_bracket_rests_on_its_obstacles_and_balances() {
    let out = solve("cable_over_bracket");
    let n = n_steps(&out);
    assert_eq!(n, 3);
    // The scene's data: a 1.6 m cable, d = 8 mm, ρ = 1500 kg/m³, ĝ = 1e-4 m, floor μ = 0.3.
    let (length, d, rho, g, activation) = (1.6, 0.008, 1500.0, 9.81, 1e-4);
    let weight = rho * circle_area(d) * length * g;
    for k in 0..n {
        let r = step(&out, k);
        assert_eq!(r["converged"], Value::Bool(true), "step {k}");
        let min_gap = r["min_gap"].as_f64().unwrap();
        assert!(
            min_gap > 0.0 && min_gap < activation,
            "step {k}: min gap {min_gap}"
        );
        let mut total = [0.0, 0.0, -weight];
        let mut contacts = 0;
        let mut worst_cone: f64 = 0.0;
        for o in r["obstacles"].as_array().unwrap() {
            let mu = o["friction"].as_f64().unwrap();
            for c in o["contacts"].as_array().unwrap() {
                contacts += 1;
                let gap = c["gap"].as_f64().unwrap();
                assert!(gap > 0.0 && gap < activation, "step {k}: gap {gap}");
                let (f_n, f_t) = (v3(&c["normal_force"]), v3(&c["friction_force"]));
                // A sliding force is μ f_n of the state before the last warm re-solve: within
                // the solver's tolerance of μ times the reported normal force.
                worst_cone = worst_cone.max(norm(f_t) / (mu * norm(f_n)).max(f64::MIN_POSITIVE));
                assert!(
                    norm(f_t) <= mu * norm(f_n) * (1.0 + 1e-5) + 1e-15,
                    "step {k}: friction {} > μ {mu} × {}",
                    norm(f_t),
                    norm(f_n)
                );
                total = add(total, add(f_n, f_t));
            }
        }
        assert!(contacts >= 2, "step {k}: on the bracket and the floor");
        for s in r["rods"][0]["supports"].as_array().unwrap() {
            total = add(total, v3(&s["force"]));
        }
        let err = norm(total) / weight;
        println!("step {k}: {contacts} contacts, min gap {min_gap:.3e} m, |clamp + contacts + weight| / weight = {err:.2e}, largest |f_t| / μ|f_n| = {worst_cone:.12}, relative imbalance {:.2e}", r["rods"][0]["relative_force_imbalance"].as_f64().unwrap());
        assert!(err <= 1e-6, "step {k}: imbalance {err:e}");
        assert!(r["rods"][0]["relative_force_imbalance"].as_f64().unwrap() < 1e-9);
    }
}

#[test]
fn a_flat_cable_over_a_bracket_rests_on_its_obstacles_and_balances() {
    let out = solve("flat_cable_on_bracket");
    let n = n_steps(&out);
    assert_eq!(n, 2);
    // The scene's data: a 0.6 m × 30 mm × 0.2 mm strip, ρ = 1000 kg/m³, ĝ = 1e-5 m, floor
    // μ = 0.3; the weight ρ h w L g computed here, not read from the results.
    let (length, width, h, rho, g, activation) = (0.6, 0.03, 0.2e-3, 1000.0, 9.81, 1e-5);
    let weight = rho * h * width * length * g;
    for k in 0..n {
        let r = step(&out, k);
        assert_eq!(r["converged"], Value::Bool(true), "step {k}");
        let strip = &r["shells"][0];
        let min_gap = r["min_gap"].as_f64().unwrap();
        assert!(
            min_gap > 0.0 && min_gap < activation,
            "step {k}: min gap {min_gap}"
        );
        assert_eq!(strip["min_gap"].as_f64(), Some(min_gap));
        let mut total = [0.0, -weight, 0.0];
        let mut on = [0usize; 2];
        let mut worst_cone: f64 = 0.0;
        for (o, obstacle) in r["obstacles"].as_array().unwrap().iter().enumerate() {
            let mu = obstacle["friction"].as_f64().unwrap();
            for c in obstacle["contacts"].as_array().unwrap() {
                on[o] += 1;
                assert_eq!(c["shell"], Value::Bool(true));
                assert_eq!(c["rod"], Value::String("flat_cable".into()));
                let gap = c["gap"].as_f64().unwrap();
                assert!(gap > 0.0 && gap < activation, "step {k}: gap {gap}");
                // The mid-surface keeps h/2 + gap from the surface: the floor's contacts
                // lie at the floor's height + h/2 + gap.
                if o == 1 {
                    let y = v3(&c["position"])[1];
                    assert!(
                        (y - (-0.08 + 0.5 * h + gap)).abs() < 1e-12,
                        "step {k}: y {y}"
                    );
                }
                let (f_n, f_t) = (v3(&c["normal_force"]), v3(&c["friction_force"]));
                worst_cone = worst_cone.max(norm(f_t) / (mu * norm(f_n)).max(f64::MIN_POSITIVE));
                assert!(
                    norm(f_t) <= mu * norm(f_n) * (1.0 + 1e-5) + 1e-15,
                    "step {k}: friction {} > μ {mu} × {}",
                    norm(f_t),
                    norm(f_n)
                );
                total = add(total, add(f_n, f_t));
            }
        }
        assert!(
            on[0] >= 2 && on[1] >= 2,
            "step {k}: on the bracket and the floor: {on:?}"
        );
        total = add(total, v3(&strip["clamp_force"]));
        let err = norm(total) / weight;
        println!(
            "step {k}: {on:?} contacts (bracket, floor), min gap {min_gap:.3e} m, |clamp + contacts + weight| / weight = {err:.2e}, largest |f_t| / μ|f_n| = {worst_cone:.6}, iterations {}",
            strip["report"]["iterations"]
        );
        assert!(err <= 1e-6, "step {k}: imbalance {err:e}");
        assert!(strip["relative_force_imbalance"].as_f64().unwrap() < 1e-6);
    }
}

/// The floats of accessor `a` of an embedded-buffer glTF (checked: its view and count fit the
/// buffer; FLOAT components only).
fn accessor_floats(g: &Value, bin: &[u8], a: usize) -> Vec<f32> {
    let acc = &g["accessors"][a];
    assert_eq!(acc["componentType"], 5126, "accessor {a}: {acc}");
    let width = match acc["type"].as_str().unwrap() {
        "SCALAR" => 1,
        "VEC3" => 3,
        t => panic!("accessor {a}: type {t}"),
    };
    let count = acc["count"].as_u64().unwrap() as usize;
    let view = &g["bufferViews"][acc["bufferView"].as_u64().unwrap() as usize];
    let offset = view["byteOffset"].as_u64().unwrap() as usize;
    let length = view["byteLength"].as_u64().unwrap() as usize;
    assert_eq!(offset % 4, 0);
    assert_eq!(length, 4 * width * count, "accessor {a}");
    assert!(offset + length <= bin.len(), "accessor {a} past the buffer");
    let v: Vec<f32> = bin[offset..offset + length]
        .chunks(4)
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect();
    // min/max, where given, are those of the data.
    if let (Some(min), Some(max)) = (acc["min"].as_array(), acc["max"].as_array()) {
        for k in 0..width {
            let (lo, hi) = v
                .iter()
                .skip(k)
                .step_by(width)
                .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), &x| {
                    (lo.min(x), hi.max(x))
                });
            assert_eq!(min[k].as_f64().unwrap() as f32, lo, "accessor {a} min");
            assert_eq!(max[k].as_f64().unwrap() as f32, hi, "accessor {a} max");
        }
    }
    v
}

/// Checks `frames.gltf` of a time run in `out` with `frames` frames: a glTF 2.0 document whose
/// accessors fit its embedded buffer with their bounds, one morph target per frame after the
/// first on every mesh, an animation of the weights with the frames' times (s) as keyframes
/// and one-hot LINEAR weights, and each rod's centerline mesh + its target reproducing the
/// frame's centerline (result.json) within 1e-6 m. Returns the largest such error (m).
fn check_animated_gltf(out: &Path, frames: usize) -> f64 {
    use base64::Engine;
    let g: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("frames.gltf")).unwrap()).unwrap();
    assert_eq!(g["asset"]["version"], "2.0");
    let uri = g["buffers"][0]["uri"].as_str().unwrap();
    let data = uri
        .strip_prefix("data:application/octet-stream;base64,")
        .expect("an embedded buffer");
    let bin = base64::engine::general_purpose::STANDARD
        .decode(data)
        .unwrap();
    assert_eq!(
        g["buffers"][0]["byteLength"].as_u64().unwrap() as usize,
        bin.len()
    );
    for a in 0..g["accessors"].as_array().unwrap().len() {
        if g["accessors"][a]["componentType"] == 5126 {
            accessor_floats(&g, &bin, a);
        }
    }
    let targets = frames - 1;
    let meshes = g["meshes"].as_array().unwrap();
    for m in meshes {
        let prim = &m["primitives"][0];
        let base = prim["attributes"]["POSITION"].as_u64().unwrap() as usize;
        let count = &g["accessors"][base]["count"];
        let t = prim["targets"].as_array().unwrap();
        assert_eq!(t.len(), targets, "{}", m["name"]);
        assert_eq!(m["weights"].as_array().unwrap().len(), targets);
        for target in t {
            let p = target["POSITION"].as_u64().unwrap() as usize;
            assert_eq!(&g["accessors"][p]["count"], count);
        }
    }
    // The animation: every node with a mesh is driven; keyframes at the frames' times.
    let anim = &g["animations"][0];
    let times: Vec<f64> = (0..frames)
        .map(|k| step(out, k)["time"]["t"].as_f64().unwrap())
        .collect();
    let channels = anim["channels"].as_array().unwrap();
    let with_mesh = g["nodes"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|n| n.get("mesh").is_some())
        .count();
    assert_eq!(channels.len(), with_mesh);
    for c in channels {
        assert_eq!(c["target"]["path"], "weights");
        let node = &g["nodes"][c["target"]["node"].as_u64().unwrap() as usize];
        assert!(node.get("mesh").is_some());
        let sampler = &anim["samplers"][c["sampler"].as_u64().unwrap() as usize];
        assert_eq!(sampler["interpolation"], "LINEAR");
        let input = accessor_floats(&g, &bin, sampler["input"].as_u64().unwrap() as usize);
        assert_eq!(input.len(), frames);
        for (a, b) in input.iter().zip(&times) {
            assert_eq!(*a, *b as f32, "keyframe time");
        }
        let w = accessor_floats(&g, &bin, sampler["output"].as_u64().unwrap() as usize);
        assert_eq!(w.len(), frames * targets);
        for k in 0..frames {
            for j in 0..targets {
                let one = if k >= 1 && j == k - 1 { 1.0 } else { 0.0 };
                assert_eq!(w[k * targets + j], one, "keyframe {k}, target {j}");
            }
        }
    }
    // Each rod's centerline: base + target of frame k = frame k's centerline.
    let mut worst: f64 = 0.0;
    for m in meshes
        .iter()
        .filter(|m| m["name"].as_str().unwrap().ends_with("centerline"))
    {
        let rod = m["name"].as_str().unwrap().trim_end_matches(" centerline");
        let prim = &m["primitives"][0];
        let base = accessor_floats(
            &g,
            &bin,
            prim["attributes"]["POSITION"].as_u64().unwrap() as usize,
        );
        for k in [1, frames / 2, frames - 1] {
            let target = &prim["targets"][k - 1]["POSITION"];
            let d = accessor_floats(&g, &bin, target.as_u64().unwrap() as usize);
            let r = step(out, k);
            let rr = r["rods"]
                .as_array()
                .unwrap()
                .iter()
                .find(|x| x["name"] == rod)
                .unwrap();
            for (i, p) in positions(rr).iter().enumerate() {
                for c in 0..3 {
                    let x = base[3 * i + c] as f64 + d[3 * i + c] as f64;
                    worst = worst.max((x - p[c]).abs());
                }
            }
        }
    }
    assert!(worst <= 1e-6, "morph targets off by {worst:e} m");
    worst
}

#[test]
fn a_cable_dropped_on_a_bracket_comes_to_rest_on_it_and_balances() {
    let out = solve("cable_dropped_on_bracket");
    let report: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    assert_eq!(report["converged"], Value::Bool(true));
    let frames = report["time"]["frames"].as_u64().unwrap() as usize;
    // The scene's data: a 1.4 m cable, d = 8 mm, ρ = 1500 kg/m³, clamped at (0, 0, 0.3);
    // ĝ = 1e-4 m; the tray's μ = 0.4.
    let (length, d, rho, g, activation) = (1.4, 0.008, 1500.0, 9.81, 1e-4);
    let weight = rho * circle_area(d) * length * g;
    let mut lowest = f64::INFINITY;
    let mut first_touch = None;
    for k in 0..frames {
        let r = step(&out, k);
        let min_gap = r["min_gap"].as_f64().unwrap();
        assert!(min_gap > 0.0, "frame {k}: gap {min_gap}");
        lowest = lowest.min(min_gap);
        let p = positions(&r["rods"][0]);
        assert!(norm(sub(p[0], [0.0, 0.0, 0.3])) < 1e-12, "the clamp moved");
        for o in r["obstacles"].as_array().unwrap() {
            let mu = o["friction"].as_f64().unwrap();
            for c in o["contacts"].as_array().unwrap() {
                first_touch.get_or_insert(k);
                let gap = c["gap"].as_f64().unwrap();
                assert!(gap > 0.0 && gap < activation, "frame {k}: gap {gap}");
                let (f_n, f_t) = (v3(&c["normal_force"]), v3(&c["friction_force"]));
                assert!(
                    norm(f_t) <= mu * norm(f_n) * (1.0 + 1e-5) + 1e-15,
                    "frame {k}: friction {} > μ {mu} × {}",
                    norm(f_t),
                    norm(f_n)
                );
            }
        }
    }
    // It fell: nothing touched at the start.
    assert!(first_touch.is_some_and(|k| k > 0), "{first_touch:?}");
    let last = step(&out, frames - 1);
    let kinetic = last["time"]["energy"]["kinetic"].as_f64().unwrap();
    let mut total = [0.0, 0.0, -weight];
    let mut counts = Vec::new();
    for o in last["obstacles"].as_array().unwrap() {
        let contacts = o["contacts"].as_array().unwrap();
        counts.push(contacts.len());
        for c in contacts {
            total = add(total, add(v3(&c["normal_force"]), v3(&c["friction_force"])));
        }
    }
    for s in last["rods"][0]["supports"].as_array().unwrap() {
        total = add(total, v3(&s["force"]));
    }
    let err = norm(total) / weight;
    let gltf = check_animated_gltf(&out, frames);
    println!(
        "cable dropped on a bracket: {frames} frames, first contact in frame {first_touch:?}, smallest gap {lowest:.3e} m, at rest: kinetic {kinetic:.2e} J, contacts (bracket, tray) {counts:?}, |clamp + contacts + weight| / weight = {err:.2e}; frames.gltf centerlines within {gltf:.2e} m"
    );
    assert!(counts[0] >= 1 && counts[1] >= 3, "{counts:?}");
    assert!(
        kinetic < 1e-12 * weight * length,
        "still moving: {kinetic:e} J"
    );
    assert!(err <= 1e-6, "imbalance {err:e}");
}

/// Where the centerline crosses the plane x = `x` (first crossing): the point and its rest arc
/// length (`h` the edge length).
fn crossing(p: &[V3], x: f64, h: f64) -> (V3, f64) {
    let j = (0..p.len() - 1)
        .find(|&j| p[j][0] <= x && p[j + 1][0] > x)
        .expect("the cable crosses the plane");
    let t = (x - p[j][0]) / (p[j + 1][0] - p[j][0]);
    (add(p[j], scale(sub(p[j + 1], p[j]), t)), (j as f64 + t) * h)
}

#[test]
fn a_cable_slides_through_its_rings_and_never_leaves_them() {
    let out = solve("cable_through_rings");
    let steps = n_steps(&out);
    // Rings at x = 0.35 and 0.85 on the x axis; hole radius 14 mm, the cable's 3 mm.
    let rings = [0.35, 0.85];
    let (hole, radius, h) = (0.02 - 0.006, 0.003, 0.01);
    let mut at_b = Vec::new();
    for k in 0..steps {
        let s = step(&out, k);
        let rod = &s["rods"][0];
        assert!(
            rod["relative_force_imbalance"].as_f64().unwrap() < 1e-9,
            "step {k}"
        );
        let p = positions(rod);
        for (i, &x) in rings.iter().enumerate() {
            // Through the hole, never through the tube. Only vertices touch: an edge passing a
            // tube (section radius ρ = tube + cable radius) may cut into it by its sagitta
            // ρ − √(ρ² − h²/4) (1.5 mm here).
            let (c, s_at) = crossing(&p, x, h);
            let off = (c[1] * c[1] + c[2] * c[2]).sqrt();
            let rho: f64 = 0.006 + radius;
            let sagitta = rho - (rho * rho - h * h / 4.0).sqrt();
            assert!(
                off < hole - radius + sagitta,
                "step {k}: ring {i} crossed at {off} m from its axis"
            );
            if i == 1 {
                at_b.push((s_at, c));
            }
            // Frictionless: the rings push, they do not hold along the cable.
            for contact in s["obstacles"][i]["contacts"].as_array().unwrap() {
                assert_eq!(norm(v3(&contact["friction_force"])), 0.0);
            }
        }
        // The rings carry part of the weight: the clamps' vertical reactions fall short of it.
        let weight = 1400.0 * circle_area(0.006) * 1.2 * 9.81;
        let clamps: f64 = (0..2)
            .map(|i| rod["supports"][i]["force"][2].as_f64().unwrap())
            .sum();
        assert!(
            clamps < 0.9 * weight,
            "step {k}: the clamps hold {clamps} N of {weight} N"
        );
    }
    // Pushing the end clamp in by 15 cm (stage 1, steps 1–6) pushed cable through ring B; pulling
    // it out by 8 cm (stage 2) drew some back: the material at ring B moved by about as much.
    // Between ring B and the end clamp the cable then runs nearly straight, so its length there
    // is the distance between them.
    let (s0, s6, s10) = (at_b[0].0, at_b[6].0, at_b[steps - 1].0);
    println!("cable at ring B: s = {s0:.4} m at rest, {s6:.4} m pushed in, {s10:.4} m pulled out");
    assert!(s6 - s0 > 0.12 && s6 - s10 > 0.06, "{s0} {s6} {s10}");
    for k in [6, steps - 1] {
        let s = step(&out, k);
        let end = v3(&s["rods"][0]["supports"][1]["position"]);
        let (s_at, c) = at_b[k];
        let span = norm(sub(end, c));
        assert!(
            (1.2 - s_at - span).abs() < 5e-3,
            "step {k}: {} m of cable past ring B, {span} m to the clamp",
            1.2 - s_at
        );
    }
}
