//! A rod whose bending double precision cannot resolve is refused when the scene compiles
//! (`scene/compile/precision.rs`), and every rod the check accepts is resolved.

use slender_core::scene::{Scene, Session};

/// A 1 m cantilever along x from `x0`, `n` elements, a stiffness section with EI = 0.05 and
/// GJ = 0.04 N m², hanging under gravity.
fn cantilever(ea: f64, n: usize, x0: f64) -> Scene {
    toml::from_str(&format!(
        r#"
gravity = [0.0, -9.81, 0.0]
[[rods]]
name = "cantilever"
elements = {n}
centerline = {{ kind = "straight", start = [{x0}, 0.0, 0.0], direction = [1.0, 0.0, 0.0], length = 1.0 }}
section = {{ shape = "stiffness", ea = {ea:e}, ei1 = 0.05, ei2 = 0.05, gj = 0.04, linear_density = 0.1 }}
supports = [{{ kind = "clamp", vertex = "start" }}]
"#
    ))
    .unwrap()
}

/// The largest EA the check accepts for `cantilever(_, n, x0)`, computed from its definition:
/// EA·ε·|x|max/ℓmin ≤ min(EI, GJ)/L² (limit 1).
fn largest_accepted(n: usize, x0: f64) -> f64 {
    let reach = (x0 + 1.0_f64).abs().max(x0.abs());
    0.04 * (1.0 / n as f64) / (f64::EPSILON * reach)
}

/// The error of a scene that must be refused.
fn refused(scene: Scene) -> slender_core::scene::SceneError {
    match Session::new(scene) {
        Ok(_) => panic!("the scene was accepted"),
        Err(e) => e,
    }
}

fn tip(session: &Session) -> [f64; 3] {
    *session.results(0, None, 1.0, 1).rods[0]
        .positions
        .last()
        .unwrap()
}

#[test]
fn a_section_beyond_double_precision_is_refused_naming_the_field_and_the_bound() {
    // EA = 1e30 N against EI = 0.05 N m²: a scene solve of this cantilever used to report a
    // stable equilibrium with a clamp force of 1.1e14 N against a weight of 0.98 N.
    let e = refused(cantilever(1e30, 20, 0.0));
    assert_eq!(e.path, "rods[0].section.ea", "{e}");
    assert!(
        e.message.contains("beyond double precision") && e.message.contains("valid here"),
        "{e}"
    );

    // A geometric section: a 0.1 µm fibre 1 m long (EA/EI = 16/d²).
    let fibre: Scene = toml::from_str(
        r#"
[[rods]]
elements = 100
centerline = { kind = "straight", start = [0.0, 0.0, 0.0], direction = [1.0, 0.0, 0.0], length = 1.0 }
section = { shape = "circle", diameter = 1e-7 }
material = { young = 1e9, poisson = 0.4, density = 1000.0 }
supports = [{ kind = "clamp", vertex = "start" }]
"#,
    )
    .unwrap();
    let e = refused(fibre);
    assert_eq!(e.path, "rods[0].section", "{e}");

    // A Cosserat rod whose shear stiffness is the absurd one.
    let sheared: Scene = toml::from_str(
        r#"
[[rods]]
model = "cosserat"
elements = 20
centerline = { kind = "straight", start = [0.0, 0.0, 0.0], direction = [1.0, 0.0, 0.0], length = 1.0 }
section = { shape = "stiffness", ea = 1e6, ei1 = 0.05, ei2 = 0.05, gj = 0.04, linear_density = 0.1 }
shear_stiffness = [1e25, 1e25]
supports = [{ kind = "clamp", vertex = "start" }]
"#,
    )
    .unwrap();
    let e = refused(sheared);
    assert_eq!(e.path, "rods[0].shear_stiffness", "{e}");
}

#[test]
fn every_section_the_check_accepts_is_resolved() {
    // Just inside the bound the hanging cantilever converges and its tip lies where the
    // EA = 1e6 N one's does (measured: within 4.7e-7 m, mostly the softer rod's stretch, at
    // relative residuals up to 1.7 whose round-off lies along the stiff stretching); just
    // outside, it is refused. Both at the origin and 100 m from it, where coordinates round
    // 100 times coarser.
    for (n, x0) in [(20, 0.0), (100, 0.0), (100, 100.0)] {
        let bound = largest_accepted(n, x0);
        let reference = Session::new(cantilever(1e6, n, x0)).unwrap();
        let near = Session::new(cantilever(0.9 * bound, n, x0))
            .unwrap_or_else(|e| panic!("n {n}, x0 {x0}: EA {:e} refused: {e}", 0.9 * bound));
        let r = near.report(0);
        assert!(r.converged(), "n {n}, x0 {x0}, EA {:e}: {r:?}", 0.9 * bound);
        let (a, b) = (tip(&near), tip(&reference));
        let d = ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt();
        assert!(d <= 1e-6, "n {n}, x0 {x0}: tip {d:e} m from EA = 1e6 N's");
        let e = refused(cantilever(1.1 * bound, n, x0));
        assert_eq!(e.path, "rods[0].section.ea", "{e}");
    }
}
