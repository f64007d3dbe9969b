//! One piece of the warm drag of `drag_loop` at a time, repeated at the drag scene's
//! equilibrium, for instruction counts per piece:
//! `PART=gradient N=1000 valgrind --tool=callgrind target/release/examples/assembly_parts`
//! (PART: hessian, gradient, energy, displace, factor, solve, block3). Prints the wall time per call.

use slender_core::assembly::{Assembler, TermSet};
use slender_core::linalg::{SymmetricFactor, SymmetricMatrix};
use slender_core::scene::{Scene, Session};
use slender_core::solver::EquilibriumProblem;
use slender_core::structure::Structure;

type Hessian = <Structure as EquilibriumProblem>::Hessian;

fn main() {
    let scene: Scene = toml::from_str(
        r#"
gravity = [0.0, 0.0, -9.81]
[[rods]]
name = "cable"
elements = 100
centerline = { kind = "straight", start = [0.0, 0.0, 0.0], direction = [1.0, 0.0, 0.0], length = 1.0 }
section = { shape = "circle", diameter = 0.006 }
material = { young = 1.0e9, poisson = 0.4, density = 1400.0 }
supports = [ { kind = "clamp", vertex = "start" }, { kind = "clamp", vertex = "end" } ]
"#,
    )
    .expect("the embedded scene parses");
    let session = Session::new(scene).expect("the embedded scene solves");
    let problem = &session.compiled().structures[0];
    let state = session.state(0).clone();
    let n = problem.n_free();
    let reps: usize = std::env::var("N")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1000);
    let part = std::env::var("PART").unwrap_or_else(|_| "hessian".into());
    let (mut grad, mut abs) = (vec![0.0; n], vec![0.0; n]);
    let mut hess = problem.new_hessian();
    let load = 1.0;
    problem.assemble(&state, load, &mut grad, &mut hess, &mut abs);
    let mut ldlt = <Hessian as SymmetricMatrix>::Factor::default();
    ldlt.factorize(&hess, 0.0)
        .expect("the equilibrium's Hessian factors");
    let dx: Vec<f64> = (0..n)
        .map(|i| 1e-6 * ((i as f64 * 0.7548).fract() - 0.5))
        .collect();
    let mut out = state.clone();
    let mut b = vec![0.0; n];
    let (mut b1, mut b2) = (vec![0.0; n], vec![0.0; n]);
    let mut acc = 0.0;
    let t = std::time::Instant::now();
    for _ in 0..reps {
        match part.as_str() {
            "hessian" => {
                acc += problem
                    .assemble(&state, load, &mut grad, &mut hess, &mut abs)
                    .energy
            }
            "gradient" => {
                let mut asm =
                    Assembler::<Hessian>::new(TermSet::ALL, Some(&mut grad), None, Some(&mut abs));
                problem.assemble_selected(&state, load, &mut asm);
                acc += asm.finish().energy;
            }
            "energy" => acc += problem.energy(&state, load),
            "displace" => problem.displace(&state, &dx, 1.0, &mut out),
            "factor" => {
                ldlt.factorize(&hess, 0.0).expect("factors");
            }
            "solve" => {
                b.copy_from_slice(&grad);
                ldlt.solve_in_place(&mut b);
                acc += b[0];
            }
            "block3" => {
                b.copy_from_slice(&grad);
                b1.copy_from_slice(&grad);
                b2.copy_from_slice(&dx);
                ldlt.solve_block_in_place([&mut b[..], &mut b1[..], &mut b2[..]]);
                acc += b[0] + b1[0] + b2[0];
            }
            "dump" => {
                let mut moved = state.clone();
                let big: Vec<f64> = dx.iter().map(|d| d * 3e4).collect();
                problem.displace(&state, &big, 1.0, &mut moved);
                let e = problem
                    .assemble(&moved, load, &mut grad, &mut hess, &mut abs)
                    .energy;
                let v: Vec<f64> = (0..n).map(|i| (i as f64 * 0.618).fract() - 0.3).collect();
                let mut hv = vec![0.0; n];
                hess.mul_vec(&v, &mut hv);
                println!("E {e:e}");
                for i in 0..n {
                    println!("{i} {:e} {:e} {:e}", grad[i], hv[i], hess.diagonal(i));
                }
                return;
            }
            other => panic!("unknown PART {other}"),
        }
    }
    println!(
        "{part}: {:.2} us per call (checksum {acc:e})",
        t.elapsed().as_secs_f64() / reps as f64 * 1e6
    );
}
