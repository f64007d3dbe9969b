//! Results as JSON text: the step exactly as `slender solve` writes `result.json`, plus the
//! internal loads of every rod from its constitutive law.
//!
//! Internal loads (the discrete elastic rod's conjugate stresses): the axial force of edge j
//! is EA·ε_j (N, ε the edge's axial strain); the bending moments at a vertex are
//! (EI₁ (κ₁ − κ̄₁), EI₂ (κ₂ − κ̄₂)) and the twisting moment GJ (τ − τ̄) (N m), with the
//! curvatures and twist rate per unit length of the hinge's Voronoi cell and κ̄, τ̄ their
//! rest values: the derivative of the hinge's energy ½ EI/l (Δκ l)² with respect to the
//! integrated curvature. Their components are in the material frame (m₁, m₂, t); free ends
//! carry none (0). At a vertex shared by two parts (an interior clamp) the two half hinges
//! are averaged, as the curvature output is.

use serde_json::Value;
use slender_core::scene::{SceneStep, Session};

/// Axial force per edge (N), bending moments (M₁, M₂) and twisting moment per vertex (N m)
/// of rod `r` in the session's current equilibrium.
fn rod_internal_loads(session: &Session, r: usize) -> (Vec<f64>, Vec<[f64; 2]>, Vec<f64>) {
    let scene = session.compiled();
    let rod = &scene.rods[r];
    let nv = rod.n_edges + 1;
    let mut axial = Vec::with_capacity(rod.n_edges);
    let mut bending = vec![[0.0; 2]; nv];
    let mut twisting = vec![0.0; nv];
    let mut hits = vec![0usize; nv];
    for part in &rod.parts {
        let member = scene.structures[part.structure].members()[part.member].as_der();
        let state = session.state(part.structure).members[part.member].as_der();
        let (Some(member), Some(state)) = (member, state) else {
            continue;
        };
        let k = member.properties().stiffness;
        axial.extend(member.edge_strains(state).into_iter().map(|e| k.ea * e));
        for h in member.hinge_strains(state) {
            let v = part.first_vertex + h.vertex;
            bending[v][0] += k.ei1 * (h.curvature[0] - h.rest_curvature[0]);
            bending[v][1] += k.ei2 * (h.curvature[1] - h.rest_curvature[1]);
            twisting[v] += k.gj * (h.twist - h.rest_twist);
            hits[v] += 1;
        }
    }
    for v in 0..nv {
        if hits[v] > 1 {
            let w = 1.0 / hits[v] as f64;
            bending[v][0] *= w;
            bending[v][1] *= w;
            twisting[v] *= w;
        }
    }
    (axial, bending, twisting)
}

/// The step as JSON text: `result.json`'s content, each rod with `axial_force`,
/// `bending_moment` and `twisting_moment` added.
pub fn step_json(session: &Session, step: &SceneStep) -> String {
    let mut value = serde_json::to_value(step).expect("a scene step serializes");
    if let Some(Value::Array(rods)) = value.get_mut("rods") {
        for (r, rod) in rods.iter_mut().enumerate() {
            let (axial, bending, twisting) = rod_internal_loads(session, r);
            if let Value::Object(map) = rod {
                map.insert("axial_force".into(), serde_json::json!(axial));
                map.insert("bending_moment".into(), serde_json::json!(bending));
                map.insert("twisting_moment".into(), serde_json::json!(twisting));
            }
        }
    }
    value.to_string()
}
