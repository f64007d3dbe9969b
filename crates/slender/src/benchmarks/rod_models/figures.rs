//! The figures, printed summary and findings of the rod-model comparison.

use std::path::Path;

use anyhow::Result;
use slender_validation::bend_twist::sweep::BendTwistSweep;
use slender_validation::cantilever::{MeshKind, CABLE_RANGE};
use slender_validation::model_comparison::{
    shear_tension_limit, ModelCantileverRecord, ModelCantileverSweep, ModelConvergence,
};
use slender_validation::rod_model::RodModel;

use super::RodModelRecords;
use crate::benchmarks::words;
use crate::plot::{plot_lines, plot_relative_error, Curve, LineAxes, Scale};

/// Caption of a figure of the section.
pub(super) fn caption(stem: &str) -> String {
    if let Some(rest) = stem.strip_prefix("error_") {
        format!(
            "Counterpart of the seed's Fig. 5: relative error of Δy/Δx of every rod model \
             against the heavy elastica ({}); the band marks Γ ∈ [10, 10³].",
            words(rest)
        )
    } else if stem == "convergence" {
        "|Δy/Δx error| against N on the graded mesh for every rod model at Γ = 1 and 100 \
         (log–log; the slope is the order of convergence)."
            .into()
    } else {
        words(stem)
    }
}

/// One figure per mesh family and N: the error of every model against Γ.
pub(super) fn plot_errors(
    sweep: &ModelCantileverSweep,
    records: &[ModelCantileverRecord],
    out: &Path,
) -> Result<()> {
    for &mesh in &sweep.meshes {
        for &n in &sweep.element_counts {
            let curves: Vec<Curve> = sweep
                .models
                .iter()
                .map(|m| Curve {
                    label: m.label().into(),
                    points: records
                        .iter()
                        .filter(|r| {
                            r.model == m.name()
                                && r.mesh == mesh.name()
                                && r.n_elements == n
                                && r.converged
                        })
                        .map(|r| (r.gamma, 100.0 * r.rel_error))
                        .collect(),
                    dashed: *m == RodModel::CosseratTangent,
                    markers: true,
                })
                .collect();
            plot_relative_error(
                &out.join(format!("error_{}_n{n:02}", mesh.name())),
                &format!(
                    "Cantilever, {}, {} mesh, N = {n}: Δy/Δx error (%) of each rod model",
                    sweep.material.label,
                    mesh.name()
                ),
                &curves,
                Some(CABLE_RANGE),
            )?;
        }
    }
    Ok(())
}

/// |error| against N (graded mesh) per model and Γ, log–log.
pub(super) fn plot_orders(orders: &[ModelConvergence], out: &Path) -> Result<()> {
    let curves: Vec<Curve> = orders
        .iter()
        .map(|o| Curve {
            label: format!("{}, Γ = {} (slope {:.2})", o.model, o.gamma, o.slope),
            points: o
                .element_counts
                .iter()
                .zip(&o.errors)
                .map(|(&n, &e)| (n as f64, e.abs()))
                .collect(),
            dashed: o.gamma > 10.0,
            markers: true,
        })
        .collect();
    plot_lines(
        &out.join("convergence"),
        "Cantilever, graded mesh: |Δy/Δx error| against N for each rod model",
        LineAxes {
            x_desc: "elements N",
            y_desc: "|relative error|",
            x_scale: Scale::Log,
            y_scale: Scale::Log,
        },
        &curves,
    )
}

/// Prints the per-model summary.
pub(super) fn print_summary(c: &RodModelRecords) {
    println!("\nrod models (Ω_rod cantilever; graded/uniform; worst |error| %, mean iterations, mean ms per solve):");
    for s in c
        .summary
        .iter()
        .filter(|s| s.mesh == MeshKind::Graded.name() || s.n_elements == 5)
    {
        println!(
            "  {:<13} {:<8} N={:>2}: worst {:>8.3} % (Γ = {:.3e}), cable range {:>8.3} %, {:.1} it, {:.3} ms{}",
            s.model,
            s.mesh,
            s.n_elements,
            s.worst_percent,
            s.worst_at_gamma,
            s.worst_cable_percent,
            s.mean_iterations,
            s.mean_milliseconds,
            if s.not_converged > 0 {
                format!(", {} not converged", s.not_converged)
            } else {
                String::new()
            }
        );
    }
    for o in &c.orders {
        println!(
            "  {:<13} order at Γ = {:>5}: slope {:.3} (N = 40…80: {:.3})",
            o.model, o.gamma, o.slope, o.finest_slope
        );
    }
    for (m, g) in &c.greenhill {
        println!("  {:<13} Greenhill Γ_c = {g:.5}", m.name());
    }
    for b in &c.scores {
        println!(
            "  {:<13} bend–twist: {}/{} correct by stability, {}/{} by the protocol, {} unclassified, {} flagged (out of regime), {} scored beyond the shear-tension limit ({} wrong there)",
            b.model,
            b.correct,
            b.scored,
            b.protocol_correct,
            b.scored,
            b.unclassified,
            b.flagged,
            b.beyond_shear_limit,
            b.wrong_beyond_shear_limit
        );
    }
}

/// The section's description, with the findings read off this run.
pub(super) fn findings(c: &RodModelRecords, bend_twist: &BendTwistSweep) -> String {
    let limit = shear_tension_limit(&slender_validation::materials::OMEGA_ROD);
    let worst = |model: &str, mesh: &str, n: usize| {
        c.summary
            .iter()
            .find(|s| s.model == model && s.mesh == mesh && s.n_elements == n)
            .map_or(f64::NAN, |s| s.worst_signed_percent)
    };
    let order = |model: &str, gamma: f64| {
        c.orders
            .iter()
            .find(|o| o.model == model && o.gamma == gamma)
            .map_or((f64::NAN, f64::NAN, f64::NAN), |o| {
                (
                    o.slope,
                    o.finest_slope,
                    o.errors.last().copied().unwrap_or(f64::NAN),
                )
            })
    };
    let (der_slope, der_fine, _) = order("der", 100.0);
    let (_, se3_fine, se3_last) = order("se3", 1.0);
    format!(
        "The seed's comparison of rod formulations (§2, Fig. 5) on slender's one solver: the discrete \
         elastic rod (Kirchhoff), the discrete Cosserat rod with Lang et al.'s quaternion (sine) \
         Darboux vector and with the tangent one, and the SE(3) beam with helicoidal elements, \
         all with the exact clamp pose, lumped gravity and κGA of a solid circle. Cantilever \
         (Ω_rod): error against Γ for N ∈ {{5, 10, 20, 50}} on uniform and graded meshes \
         (error_*.png), order of convergence (convergence.png, convergence.json), iterations and \
         time per solve (cantilever_summary.csv); Greenhill's heavy column by inertia \
         (greenhill.csv); the bend–twist grid ({nx} × {ny}, {k}·Y elements) per model \
         (bend-twist-*/, bend_twist.csv). \
         Findings. (1) Five uniform elements: the SE(3) beam is too stiff at large Γ ({se3_u5:+.0} % \
         at worst), the seed's Odin behaviour: its first element bends with constant curvature over \
         h = L/5 ≫ ℓ_b = L/√Γ, so the hanging part starts too far out; the hinge models concentrate \
         the clamp turn at the clamp vertex and sag too much (discrete elastic rod {der_u5:+.0} %, \
         Cosserat {cos_u5:+.0} %). (2) The sine Darboux vector 2 sin(φ/2) softens large kinks: the \
         Cosserat rod misses the coarse-mesh targets (graded N = 5: {cos_g5:+.1} %, N = 20: \
         {cos_g20:+.2} %), the IPS-like over-prediction; with the tangent vector it matches the \
         discrete elastic rod to within the shear correction. (3) The discrete elastic rod's \
         least-squares slope at Γ = 100 over N = 10…80 is {der_slope:.3} because N = 10 is \
         pre-asymptotic; over N = 40…80 it is {der_fine:.2}. (4) The SE(3) beam at Γ = 1 reaches, by \
         N = 80 (error {se3_last:+.1e}), the continuum's own shear and extension correction \
         against the Kirchhoff master curve (≈ 4EI/(κGA L²) = {timo:.1e}), so its N = 40…80 \
         slope ({se3_fine:.2}) measures that floor. (5) Bend–twist points out of the master curve's \
         regime (clamp axial strain > 2 %, under-resolved, λ_min out of range) are flagged and not \
         scored, as in the bend–twist section (up to {flagged} per model); they include the points \
         whose clamp tension exceeds κGA/(1 − κGA/EA) = {limit:.3e} N, where the shearable rods \
         are unstable in shear (a property of the Cosserat rod with a linear constitutive law, \
         see shear_limit.rs; {beyond} such points scored). Wrong or unclassified stability \
         decisions among the scored points, all models: {elsewhere}.",
        nx = bend_twist.xs.len(),
        ny = bend_twist.ys.len(),
        k = bend_twist.elements_per_turn,
        se3_u5 = worst("se3", "uniform", 5),
        der_u5 = worst("der", "uniform", 5),
        cos_u5 = worst("cosserat", "uniform", 5),
        cos_g5 = worst("cosserat", "graded", 5),
        cos_g20 = worst("cosserat", "graded", 20),
        timo = 4.0 * slender_validation::materials::OMEGA_ROD.properties.stiffness.ei_min()
            / slender_validation::materials::OMEGA_ROD.shear().ga1,
        flagged = c.scores.iter().map(|b| b.flagged).max().unwrap_or(0),
        beyond = c.scores.iter().map(|b| b.beyond_shear_limit).max().unwrap_or(0),
        elsewhere = c
            .scores
            .iter()
            .map(|b| b.scored - b.correct + b.unclassified)
            .sum::<usize>(),
    )
}
