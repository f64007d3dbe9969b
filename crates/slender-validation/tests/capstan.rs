//! The capstan benchmark (`slender_validation::capstan` and its scene): a cable laid over a rough bar, θ = π, pulled by one
//! clamp and then by the other, for two friction coefficients. Sliding, every contact's
//! friction must sit on Coulomb's cone against the slide, and the legs' tension ratio must be
//! e^{μπ}: 1.602 for μ = 0.15, 2.566 for μ = 0.3 (a linear law, 1 + μπ, would give 1.47 and
//! 1.94).

use slender_core::scene::Scene;
use slender_validation::capstan::{capstan_ratio, run, SCENE, TOLERANCE};

#[test]
fn a_cable_sliding_over_a_rough_bar_obeys_the_capstan_equation() {
    assert!(SCENE.contains("\nfriction = 0.3\n"));
    for mu in [0.15, 0.3] {
        let text = SCENE.replace("\nfriction = 0.3\n", &format!("\nfriction = {mu}\n"));
        let scene: Scene = toml::from_str(&text).expect("the scene parses");
        let pulls = run(scene).expect("solves");
        assert_eq!(pulls.len(), 2);
        // The end clamp pulled first, then the start clamp: the slide changes sides.
        assert_eq!(pulls.iter().map(|p| p.0).collect::<Vec<_>>(), [1, 0]);
        let capstan = capstan_ratio(mu, std::f64::consts::PI);
        for (clamp, m) in &pulls {
            println!(
                "μ = {mu}, clamp {clamp} pulled: legs {:.6} N (held) and {:.6} N (pulled), ratio {:.5} vs e^(μπ) = {capstan:.5} ({:.1e} off); wrap over the contacts {:.5} rad; {} of {} contacts sliding against the slide",
                m.held, m.pulled, m.ratio(), m.relative_error(), m.wrap, m.sliding_against_the_slide, m.contacts
            );
            // The top half of the bar at 5 mm edges: about 32 contacts, every one sliding.
            assert!(m.contacts >= 28, "{} contacts", m.contacts);
            assert_eq!(m.sliding_against_the_slide, m.contacts);
            assert!(
                m.wrap > 3.1 && m.wrap <= std::f64::consts::PI,
                "wrap {}",
                m.wrap
            );
            assert!(
                m.relative_error() < TOLERANCE,
                "μ = {mu}, clamp {clamp}: ratio {} vs e^(μπ) = {capstan}",
                m.ratio()
            );
        }
    }
}
