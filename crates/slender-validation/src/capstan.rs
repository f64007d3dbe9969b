//! The capstan equation (Euler–Eytelwein) as a benchmark of contact with friction: a cable
//! sliding over a rough cylinder it wraps by θ carries, on the side it slides toward, e^{μθ}
//! times the tension of the other side.
//!
//! The scene is [`SCENE`] (`capstan.toml` beside this file): a weightless cable laid over a bar
//! (θ = π, both legs hanging straight down), then pulled down by one clamp and by the other.
//! [`measure_pull`] reads an equilibrium at the end of a pull: the legs' tensions, the turn of
//! the cable over its contacts, and whether every contact slides on Coulomb's cone against the
//! slide; [`capstan_ratio`] is the closed form it is scored against.
//!
//! What the discrete cable adds: with vertex contacts turning it by Δθ each, a sliding vertex
//! balances T₊/T₋ = (1 + μ tan(Δθ/2))/(1 − μ tan(Δθ/2)), which over θ/Δθ vertices is e^{μθ}
//! to within μθΔθ²(1 + μ²)/12, 1e-3 at the scene's Δθ ≈ 0.1. Bending shows only where the
//! cable leaves the bar (a straight cable wrapping a bar has the same curvature all along the
//! wrap, so sliding does not change its bending energy). [`TOLERANCE`] is five times the
//! discrete capstan's error; the scene measures 3.5e-6 to 7.6e-4.

use slender_core::geometry::Vec3;
use slender_core::scene::{Scene, SceneStep, Session};

/// The benchmark's scene (TOML).
pub const SCENE: &str = include_str!("capstan.toml");

/// Relative tolerance on the tension ratio: five times the discrete capstan's error at the
/// scene's mesh (see the module's documentation).
pub const TOLERANCE: f64 = 5e-3;

/// The capstan equation: the ratio of the tensions on either side of a cable sliding over a
/// rough surface it wraps by `wrap` (rad), with friction coefficient `mu`.
pub fn capstan_ratio(mu: f64, wrap: f64) -> f64 {
    (mu * wrap).exp()
}

/// What an equilibrium at the end of a pull shows.
#[derive(Clone, Debug, PartialEq)]
pub struct PullMeasure {
    /// Axial force (N) of the held leg and of the pulled leg: each leg's mean EA·ε over its
    /// edges below the bar and more than 2 cm from the clamps.
    pub held: f64,
    /// See `held`.
    pub pulled: f64,
    /// The bar's friction coefficient.
    pub mu: f64,
    /// Turn (rad) of the cable over its contact vertices, Σφ (π less what the two vertices
    /// leaving the bar turn).
    pub wrap: f64,
    /// Contacts with the bar.
    pub contacts: usize,
    /// Contacts whose friction is μ times their normal force (to 1e-6) and opposes the slide.
    pub sliding_against_the_slide: usize,
}

impl PullMeasure {
    /// pulled / held.
    pub fn ratio(&self) -> f64 {
        self.pulled / self.held
    }

    /// |ratio / e^{μπ} − 1|.
    pub fn relative_error(&self) -> f64 {
        (self.ratio() / capstan_ratio(self.mu, std::f64::consts::PI) - 1.0).abs()
    }
}

/// Measures `step`, an equilibrium of the scene in which clamp `pulled` (0: the cable's start,
/// 1: its end) was just pulled: rod 0 over obstacle 0, a cylinder of radius `bar` (m) along y
/// through the origin, EA = `ea` (N). Errors say what is missing.
pub fn measure_pull(
    step: &SceneStep,
    pulled: usize,
    bar: f64,
    ea: f64,
) -> Result<PullMeasure, String> {
    let rod = step.rods.first().ok_or("the scene has no rod")?;
    let obstacle = step.obstacles.first().ok_or("the scene has no obstacle")?;
    let p: Vec<Vec3> = rod.positions.iter().map(|&x| Vec3::from(x)).collect();
    let n = p.len();
    let lowest_clamp = p[0].z.max(p[n - 1].z);
    let leg = |side: f64| -> Result<f64, String> {
        let forces: Vec<f64> = (0..n - 1)
            .filter(|&j| {
                p[j].z.max(p[j + 1].z) < -bar
                    && p[j].z.min(p[j + 1].z) > lowest_clamp + 0.02
                    && p[j].x * side > 0.0
            })
            .map(|j| ea * rod.edge_strain[j])
            .collect();
        if forces.len() < 10 {
            return Err(format!(
                "only {} edges of the leg on side {side} hang below the bar",
                forces.len()
            ));
        }
        Ok(forces.iter().sum::<f64>() / forces.len() as f64)
    };
    let (start, end) = (leg(-1.0)?, leg(1.0)?);
    let mu = obstacle.friction;
    let (mut wrap, mut sliding) = (0.0, 0);
    for c in &obstacle.contacts {
        let v = c.vertex;
        if v == 0 || v + 1 >= n {
            return Err(format!("vertex {v}, an end of the cable, touches the bar"));
        }
        wrap += (p[v] - p[v - 1]).angle(&(p[v + 1] - p[v]));
        let friction = Vec3::from(c.friction_force);
        let normal = Vec3::from(c.normal_force).norm();
        // The cable slides toward the pulled clamp; friction on it points the other way.
        let toward_end = p[v + 1] - p[v - 1];
        let against = if pulled == 1 { -1.0 } else { 1.0 };
        if (friction.norm() / normal - mu).abs() < 1e-6 * mu
            && against * friction.dot(&toward_end) > 0.0
        {
            sliding += 1;
        }
    }
    let (held, pulled_leg) = if pulled == 1 {
        (start, end)
    } else {
        (end, start)
    };
    Ok(PullMeasure {
        held,
        pulled: pulled_leg,
        mu,
        wrap,
        contacts: obstacle.contacts.len(),
        sliding_against_the_slide: sliding,
    })
}

/// The scene's last two motion stages, the pulls: (stage index, clamp pulled).
pub fn pull_stages(scene: &Scene) -> Result<Vec<(usize, usize)>, String> {
    let stages = scene.motion.len();
    if stages < 2 {
        return Err("the scene has fewer than two motion stages".into());
    }
    Ok((stages - 2..stages)
        .map(|k| (k, scene.motion[k].support))
        .collect())
}

/// Measures the end of each pull among `steps`, the solved steps of `scene` whose rod has
/// EA = `ea` (N): `(clamp pulled, measure)`, in order.
pub fn measure_steps(
    scene: &Scene,
    ea: f64,
    steps: &[SceneStep],
) -> Result<Vec<(usize, PullMeasure)>, String> {
    let bar = bar_radius(scene)?;
    let mut out = Vec::new();
    for (stage, support) in pull_stages(scene)? {
        let end = steps
            .iter()
            .find(|s| s.stage == Some(stage) && s.stage_fraction == 1.0)
            .ok_or_else(|| format!("no step ends motion stage {stage}"))?;
        if !end.converged {
            return Err(format!(
                "the step ending motion stage {stage} did not converge"
            ));
        }
        out.push((support, measure_pull(end, support, bar, ea)?));
    }
    Ok(out)
}

/// Solves `scene` (the benchmark's, or a variant of it) step by step as `slender solve` does
/// and measures the end of each pull; an error if a step does not converge.
pub fn run(scene: Scene) -> Result<Vec<(usize, PullMeasure)>, String> {
    let mut session = Session::new(scene.clone()).map_err(|e| e.to_string())?;
    let ea = session.compiled().rods[0].properties.stiffness.ea;
    let mut steps = Vec::with_capacity(session.motion_steps());
    for k in 1..=session.motion_steps() {
        let step = session.run_motion_step(k);
        if !step.converged {
            return Err(format!("motion step {k} did not converge"));
        }
        steps.push(step);
    }
    measure_steps(&scene, ea, &steps)
}

/// The radius (m) of the scene's first obstacle, which must be a cylinder.
pub fn bar_radius(scene: &Scene) -> Result<f64, String> {
    use slender_core::scene::spec::ObstacleShapeSpec;
    match scene.obstacles.first().map(|o| &o.shape) {
        Some(ObstacleShapeSpec::Cylinder { radius, .. }) => Ok(*radius),
        _ => Err("the scene's first obstacle is not a cylinder".into()),
    }
}
