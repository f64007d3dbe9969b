//! The scene format: what a user writes in a TOML (or JSON) file, as Rust types.
//!
//! Every struct denies unknown keys, so a typo is an error rather than a silently ignored
//! setting. Units are SI (m, N, Pa, kg/m³, rad). The JSON Schema is generated from these types
//! (feature `schema`).

use serde::{Deserialize, Deserializer, Serialize, Serializer};

use crate::rod::Grading;
use crate::solver::SolverParams;

/// A whole scene: rods and shell strips, gravity, prescribed support motion and solver
/// parameters.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// Gravitational acceleration (m/s²), e.g. [0, 0, -9.81]. Default: none.
    #[serde(default)]
    pub gravity: [f64; 3],
    /// Solver parameters; every field optional with the documented default.
    #[serde(default)]
    pub solver: SolverParams,
    /// The rods (independent of each other).
    #[serde(default)]
    pub rods: Vec<RodSpec>,
    /// Shell strips, each clamped along its edge x = 0 (independent of each other and of the
    /// rods: structures in one scene do not interact).
    #[serde(default)]
    pub shells: Vec<ShellSpec>,
    /// Rigid connections between rod ends (branch points, splices).
    #[serde(default)]
    pub joints: Vec<JointSpec>,
    /// Prescribed support motion, in stages run one after the other after the initial solve.
    #[serde(default)]
    pub motion: Vec<MotionStage>,
    /// What to do when an equilibrium is unstable (a negative Hessian eigenvalue): `"follow"`
    /// (default) follows the unstable mode to a stable equilibrium and reports both; `"keep"`
    /// keeps the unstable one (and says so).
    #[serde(default)]
    pub unstable: UnstablePolicy,
    /// Time stepping: with this table `slender solve` integrates the motion of the rods in
    /// time from rest instead of solving for equilibria (see [`TimeSpec`]). Default: none
    /// (equilibria only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub time: Option<TimeSpec>,
    /// Rigid obstacles the rods rest on and slide along (barrier contact with Coulomb
    /// friction). Default: none.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub obstacles: Vec<ObstacleSpec>,
    /// How contacts act (activation distance, barrier stiffness, self-contact). Default: the
    /// documented defaults when the scene has obstacles; none otherwise.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub contact: Option<ContactSpec>,
}

/// A rigid obstacle: its surface and its Coulomb friction coefficient.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct ObstacleSpec {
    /// Name reported with its contacts (default `obstacle<i>`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Coulomb friction coefficient μ (finite, ≥ 0; static = kinetic). Default 0
    /// (frictionless).
    #[serde(default)]
    pub friction: f64,
    /// The obstacle's shape.
    pub shape: ObstacleShapeSpec,
}

/// The shape of an obstacle (m; the solid side is the obstacle).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum ObstacleShapeSpec {
    /// The half-space below the plane through `point` with outward normal `normal`.
    Plane {
        /// A point of the plane (m).
        point: [f64; 3],
        /// Outward normal (any non-zero length).
        normal: [f64; 3],
    },
    /// A solid ball.
    Sphere {
        /// Centre (m).
        center: [f64; 3],
        /// Radius (m, > 0).
        radius: f64,
    },
    /// An infinite solid round bar around the line through `point` along `axis`.
    Cylinder {
        /// A point of the axis (m).
        point: [f64; 3],
        /// Axis direction (any non-zero length).
        axis: [f64; 3],
        /// Radius (m, > 0).
        radius: f64,
    },
    /// A solid box of edge lengths `size` along its own axes, turned by `rotate` about its
    /// centre.
    Box {
        /// Centre (m).
        center: [f64; 3],
        /// Edge lengths (m, each > 0) along the box's axes.
        size: [f64; 3],
        /// Rotation vector (axis × angle, rad) of the box's axes from the global ones.
        /// Default 0.
        #[serde(default)]
        rotate: [f64; 3],
    },
    /// A solid ring (torus) a cable runs through and slides in: a sliding clip, a grommet, an
    /// eyelet. Only the cable's vertices touch obstacles: near the ring keep its elements
    /// shorter than `2 × (tube_radius + the cable's contact radius)`, or an edge could straddle
    /// the tube; an edge of length h may cut into the tube by its sagitta ρ − √(ρ² − h²/4),
    /// ρ = tube_radius + contact radius.
    Torus {
        /// Centre (m).
        center: [f64; 3],
        /// Axis (any non-zero length): the direction a cable runs through the ring.
        axis: [f64; 3],
        /// Radius (m, > 0) from the centre to the tube's centre circle.
        radius: f64,
        /// Radius of the tube (m, > 0 and < `radius`); the hole's radius is
        /// `radius − tube_radius`.
        tube_radius: f64,
    },
    /// A triangle mesh (contact with its surface, from either side), inline or from a file.
    Mesh {
        /// An STL (ASCII or binary) or OBJ file, relative to the scene file, whose triangles
        /// replace `vertices` and `triangles` when the `slender` binary reads the scene
        /// (`slender solve`, `slender view`). Default: none (the mesh is inline).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        file: Option<String>,
        /// Vertex positions (m).
        #[serde(default)]
        vertices: Vec<[f64; 3]>,
        /// Triangles: vertex index triples (0-based).
        #[serde(default)]
        triangles: Vec<[usize; 3]>,
    },
}

/// The `[contact]` table.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct ContactSpec {
    /// Activation distance ĝ (m, > 0): contacts rest within this gap of a surface (the
    /// position tolerance of contacts). Default 1e-6 × the longest rod's or strip's length.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub activation: Option<f64>,
    /// Contact of the rods with themselves and with each other: every rod of the scene is then
    /// solved in one structure (so separate cables touch); each keeps its own contact radius
    /// (two cables touch at the sum of theirs). Default false. Refused in a scene with shell
    /// strips (they touch obstacles only).
    #[serde(default)]
    pub self_contact: bool,
    /// Barrier stiffness κ of the rods' contacts (N/m², > 0; a strip's: `shell_stiffness`).
    /// Default: the stiffness at which the heaviest rod's
    /// weight per length under the scene's gravity rests a cable at ĝ/2; without gravity the
    /// line load EI/L³ of the stiffest rod (its largest bending stiffness over its length
    /// cubed) instead.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stiffness: Option<f64>,
    /// Barrier stiffness of the shell strips' contacts, per unit area of mid-surface
    /// (N/m³, > 0). Default: the stiffness at which the heaviest strip's weight per area
    /// ρ h |g| rests it at ĝ/2; without gravity the pressure D/L³ of the stiffest strip (its
    /// bending stiffness D = E h³/(12(1 − ν²)) over its length cubed) instead.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shell_stiffness: Option<f64>,
}

/// The `[time]` table: implicit time stepping of the scene's rods (every model; the Cosserat
/// rods' and SE(3) beams' frames carry the sections' rotary inertia), starting from the rest
/// state at rest (velocity 0) with gravity and the loads acting
/// from t = 0 — a cable released from its rest shape —, in contact with the obstacles, with
/// itself and with the other rods (self-contact) when the scene has them.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct TimeSpec {
    /// Time step h (s), finite and > 0.
    pub dt: f64,
    /// Duration (s), finite and ≥ `dt`: the run takes ⌈duration/dt⌉ steps (within 1e-9) and
    /// ends at that many times `dt`.
    pub duration: f64,
    /// `"energy_conserving"` (average-vector-field, second order, conserves energy; the
    /// default), `"midpoint"` (implicit midpoint rule, second order, symplectic; refused with
    /// obstacles or self-contact) or `"backward_euler"` (first order, dissipative, robust; the
    /// choice for impacts and friction).
    #[serde(default)]
    pub scheme: TimeSchemeSpec,
    /// Mass-proportional Rayleigh damping α (1/s), finite and ≥ 0: force α M v. Default 0.
    #[serde(default)]
    pub rayleigh_mass: f64,
    /// Stiffness-proportional Rayleigh damping β (s), finite and ≥ 0: force β K v. Default 0.
    #[serde(default)]
    pub rayleigh_stiffness: f64,
    /// Time steps between written frames (≥ 1). Default: ⌈steps/200⌉ (at most ~200 frames).
    /// Frame 0 (t = 0) and the last step are always written.
    #[serde(default)]
    pub output_every: Option<usize>,
}

/// The time-integration scheme of a scene.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "snake_case")]
pub enum TimeSchemeSpec {
    /// The energy-conserving average-vector-field scheme (3 Gauss nodes).
    #[default]
    EnergyConserving,
    /// The implicit midpoint rule (also `"implicit_midpoint"`).
    #[serde(alias = "implicit_midpoint")]
    Midpoint,
    /// Backward Euler.
    BackwardEuler,
}

impl TimeSchemeSpec {
    /// The dynamics scheme.
    pub fn scheme(self) -> crate::dynamics::Scheme {
        match self {
            Self::EnergyConserving => crate::dynamics::Scheme::EnergyConserving,
            Self::Midpoint => crate::dynamics::Scheme::ImplicitMidpoint,
            Self::BackwardEuler => crate::dynamics::Scheme::BackwardEuler,
        }
    }

    /// The name in scene files.
    pub fn name(self) -> &'static str {
        match self {
            Self::EnergyConserving => "energy_conserving",
            Self::Midpoint => "midpoint",
            Self::BackwardEuler => "backward_euler",
        }
    }
}

/// What a scene solve does with an unstable equilibrium.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "snake_case")]
pub enum UnstablePolicy {
    /// Follow the lowest unstable mode to a stable equilibrium (branch switching).
    #[default]
    Follow,
    /// Keep the unstable equilibrium and report it as unstable.
    Keep,
}

/// A rigid connection of rod ends at one point (their rest positions must coincide). The
/// cable continues through it: bending and twisting are carried across, between the first end
/// and each of the others.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct JointSpec {
    /// The joined ends (at least two). A support at the joint goes on the first end's vertex.
    pub ends: Vec<JointEndSpec>,
}

/// One rod end at a joint.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct JointEndSpec {
    /// The rod: its name.
    pub rod: String,
    /// Which end.
    pub end: RodEnd,
}

/// One rod: centerline, section, material, mesh, supports and loads.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct RodSpec {
    /// Name used in output files (default `rod<i>`): letters, digits, `-` and `_`.
    #[serde(default)]
    pub name: Option<String>,
    /// Rest (stress-free) centerline.
    pub centerline: Centerline,
    /// Cross-section (geometry, or stiffnesses directly).
    pub section: SectionSpec,
    /// Material; required for geometric sections, not allowed with `shape = "stiffness"`.
    #[serde(default)]
    pub material: Option<MaterialSpec>,
    /// Number of elements (edges), ≥ 1. Default 20; for a polyline without it, the nodes are
    /// the polyline's points.
    #[serde(default)]
    pub elements: Option<usize>,
    /// Node distribution along the arc length from the start (default uniform).
    #[serde(default)]
    pub grading: Option<Grading>,
    /// Direction of the first material director m₁ at the start (width direction of a
    /// rectangle), made orthogonal to the tangent. Default: any.
    #[serde(default)]
    pub first_director: Option<[f64; 3]>,
    /// Supports; vertices are numbered 0 … elements from the start.
    #[serde(default)]
    pub supports: Vec<SupportSpec>,
    /// Dead point forces.
    #[serde(default)]
    pub forces: Vec<PointForceSpec>,
    /// Point moments.
    #[serde(default)]
    pub moments: Vec<PointMomentSpec>,
    /// Distributed dead loads per unit length, besides gravity.
    #[serde(default)]
    pub line_loads: Vec<LineLoadSpec>,
    /// The centerline is a closed loop (ring): its end must coincide with its start, where the
    /// two ends are joined and the cable continues. Default false.
    #[serde(default)]
    pub closed: bool,
    /// Smallest bend radius the cable allows (m): segments bent tighter are reported (and
    /// highlighted by `slender view`). Default: none.
    #[serde(default)]
    pub min_bend_radius: Option<f64>,
    /// Rod formulation: `"der"` (discrete elastic rod, inextensible-shear Kirchhoff; the
    /// default), `"cosserat"` (discrete Cosserat rod, sine Darboux measure), `"cosserat_tan"`
    /// (its tangent measure) or `"se3"` (geometrically exact beam on SE(3)). The Cosserat and
    /// SE(3) rods add shear; they take clamps, pins, clips, point forces and moments, line
    /// loads and prescribed motion (not joints, closed loops, sliders, twist holds or follower
    /// loads).
    #[serde(default)]
    pub model: RodModelSpec,
    /// Shear stiffnesses [κGA₁, κGA₂] (N) of the Cosserat and SE(3) rods, along m₁ and m₂.
    /// Default from the section: κ = 6(1+ν)/(7+6ν) for a circle, 10(1+ν)/(12+11ν) for a
    /// rectangle (Timoshenko); required with `shape = "stiffness"`; not allowed with
    /// `model = "der"`.
    #[serde(default)]
    pub shear_stiffness: Option<[f64; 2]>,
    /// Radius (m, > 0) of the cable in contacts: its centerline keeps this distance from
    /// obstacles, twice it from itself and r + r' from another cable of radius r' with
    /// self-contact (each rod keeps its own, also in a structure of several rods; where
    /// joined rods meet, the larger radius holds against obstacles). Default from the
    /// section: d/2 for a circle, max(width, height)/2 for a rectangle; required with
    /// `shape = "stiffness"` when the scene has obstacles or self-contact.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub contact_radius: Option<f64>,
}

/// The formulation of a rod.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "snake_case")]
pub enum RodModelSpec {
    /// Discrete elastic rod (Kirchhoff: no shear, centerline + twist angles).
    #[default]
    Der,
    /// Discrete Cosserat rod, frames on the edges, sine Darboux measure.
    Cosserat,
    /// Discrete Cosserat rod with the tangent (Cayley) Darboux measure (also `"cosserat-tan"`,
    /// as on the command line).
    #[serde(alias = "cosserat-tan")]
    CosseratTan,
    /// Geometrically exact beam on SE(3), helicoidal elements.
    Se3,
}

impl RodModelSpec {
    /// The name in scene files.
    pub fn name(self) -> &'static str {
        match self {
            Self::Der => "der",
            Self::Cosserat => "cosserat",
            Self::CosseratTan => "cosserat_tan",
            Self::Se3 => "se3",
        }
    }
}

/// A distributed dead load per unit rest length (N/m): uniform over [`from`, `to`], or varying
/// linearly between the rows of `table`. It is lumped on the vertices exactly (the integral of
/// the piecewise-linear load against each vertex's hat function).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct LineLoadSpec {
    /// Uniform load (N/m).
    #[serde(default)]
    pub force_per_length: Option<[f64; 3]>,
    /// Start of a uniform load (m of rest arc length from vertex 0). Default 0.
    #[serde(default)]
    pub from: Option<f64>,
    /// End of a uniform load (m). Default: the rod's length.
    #[serde(default)]
    pub to: Option<f64>,
    /// Varying load: rows [s (m), fx, fy, fz (N/m)] with increasing s; linear in between, zero
    /// outside.
    #[serde(default)]
    pub table: Option<Vec<[f64; 4]>>,
}

/// Rest centerline of a rod in a scene: the model's own [`RestCurve`] (straight, arc, helix,
/// polyline).
pub type Centerline = crate::rod::RestCurve;

/// Cross-section.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(tag = "shape", rename_all = "snake_case", deny_unknown_fields)]
pub enum SectionSpec {
    /// Solid circle.
    Circle {
        /// Diameter d (m).
        diameter: f64,
    },
    /// Solid rectangle: `width` along m₁, `height` along m₂.
    Rectangle {
        /// Width w (m).
        width: f64,
        /// Height h (m).
        height: f64,
    },
    /// Stiffnesses given directly (no material).
    Stiffness {
        /// Axial stiffness EA (N).
        ea: f64,
        /// Bending stiffness EI₁ (N m²): bending that moves the centerline along m₁.
        ei1: f64,
        /// Bending stiffness EI₂ (N m²): bending along m₂.
        ei2: f64,
        /// Torsional stiffness GJ (N m²).
        gj: f64,
        /// Mass per length ρA (kg/m).
        linear_density: f64,
        /// Radius (m) drawn in VTK/glTF output (default: 1 % of the rod length).
        #[serde(default)]
        display_radius: Option<f64>,
    },
}

/// Isotropic material: E with exactly one of ν or G, and the density.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct MaterialSpec {
    /// Young's modulus E (Pa).
    pub young: f64,
    /// Poisson's ratio ν ∈ (−1, 0.5].
    #[serde(default)]
    pub poisson: Option<f64>,
    /// Shear modulus G (Pa), instead of ν.
    #[serde(default)]
    pub shear_modulus: Option<f64>,
    /// Density ρ (kg/m³).
    pub density: f64,
}

/// A vertex of a rod: its index (0 … elements) or `"start"` / `"end"`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[cfg_attr(feature = "schema", serde(untagged))]
pub enum VertexRef {
    /// Vertex index.
    Index(usize),
    /// `"start"` (vertex 0) or `"end"` (the last vertex).
    Named(RodEnd),
}

/// A rod end.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "snake_case")]
pub enum RodEnd {
    /// Vertex 0.
    Start,
    /// The last vertex.
    End,
}

impl VertexRef {
    /// The vertex index on a rod with `n_edges` edges (may be out of range: check it).
    pub fn index(self, n_edges: usize) -> usize {
        match self {
            Self::Index(v) => v,
            Self::Named(RodEnd::Start) => 0,
            Self::Named(RodEnd::End) => n_edges,
        }
    }
}

impl Serialize for VertexRef {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            Self::Index(v) => s.serialize_u64(*v as u64),
            Self::Named(e) => e.serialize(s),
        }
    }
}

impl<'de> Deserialize<'de> for VertexRef {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Visitor;
        const EXPECTED: &str = "a vertex index >= 0, \"start\" or \"end\"";
        impl serde::de::Visitor<'_> for Visitor {
            type Value = VertexRef;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str(EXPECTED)
            }
            fn visit_u64<E: serde::de::Error>(self, v: u64) -> Result<VertexRef, E> {
                usize::try_from(v)
                    .map(VertexRef::Index)
                    .map_err(|_| E::custom(format!("vertex {v} is too large")))
            }
            fn visit_i64<E: serde::de::Error>(self, v: i64) -> Result<VertexRef, E> {
                if v < 0 {
                    Err(E::custom(format!("vertex {v}: expected {EXPECTED}")))
                } else {
                    self.visit_u64(v as u64)
                }
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<VertexRef, E> {
                match v {
                    "start" => Ok(VertexRef::Named(RodEnd::Start)),
                    "end" => Ok(VertexRef::Named(RodEnd::End)),
                    _ => Err(E::custom(format!("vertex \"{v}\": expected {EXPECTED}"))),
                }
            }
        }
        d.deserialize_any(Visitor)
    }
}

/// What a support holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "snake_case")]
pub enum SupportKind {
    /// Position and orientation (material frame) of the vertex fixed. At an interior vertex
    /// the rod is split there into two independently clamped parts.
    Clamp,
    /// Position fixed, rotation free.
    Pin,
    /// Position and tangent fixed, twist free, no sliding: holds the vertex and its next
    /// vertex (the previous one at the rod's end), so that edge keeps its rest length.
    Clip,
    /// Sliding support (roller, sleeve, sliding clip): the vertex is held across the straight
    /// `axis` through it and slides freely along it; rotation free.
    Slider,
    /// Twist-only hold: the material angle of the edge starting at the vertex (the last edge
    /// at the rod's end) is held; its position is free.
    TwistHold,
}

/// A support on one vertex.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct SupportSpec {
    /// Clamp, pin, clip, slider or twist hold.
    pub kind: SupportKind,
    /// The held vertex (or give `at`).
    #[serde(default)]
    pub vertex: Option<VertexRef>,
    /// Where the support is, as rest arc length (m) from vertex 0 (instead of `vertex`): a
    /// vertex is inserted there unless one lies within 1e-6 of the rod length.
    #[serde(default)]
    pub at: Option<f64>,
    /// Slider axis (any non-zero length). Default: the rod's rest tangent at the vertex.
    #[serde(default)]
    pub axis: Option<[f64; 3]>,
}

/// A dead point force.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct PointForceSpec {
    /// Loaded vertex.
    pub vertex: VertexRef,
    /// Force (N): fixed in space, or, with `follower`, given in the rest frame of the rod at
    /// the vertex and turning with the rod there.
    pub force: [f64; 3],
    /// The force turns with the rod's material frame at the vertex (a follower load). Default
    /// false.
    #[serde(default)]
    pub follower: bool,
}

/// A point moment (acts on the edge that starts at the vertex; the last edge at the end).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct PointMomentSpec {
    /// Loaded vertex.
    pub vertex: VertexRef,
    /// Moment (N m): fixed in space, or, with `follower`, given in the rest frame of the rod
    /// at the vertex and turning with the rod there.
    pub moment: [f64; 3],
    /// The moment turns with the rod's material frame at the vertex. Default false.
    #[serde(default)]
    pub follower: bool,
}

/// One stage of prescribed motion: a support of a rod (`rod`) or a clamp of a shell strip
/// (`shell`) moved rigidly, in equal steps, each solved from the previous equilibrium.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct MotionStage {
    /// Index of the rod in `rods` (give exactly one of `rod`, `shell` and `obstacle`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rod: Option<usize>,
    /// Index of the strip in `shells` (give exactly one of `rod`, `shell` and `obstacle`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shell: Option<usize>,
    /// Index of the obstacle in `obstacles` (give exactly one of `rod`, `shell` and
    /// `obstacle`): moved rigidly, turned by `rotate` about its reference point (a plane's or
    /// cylinder's `point`, a sphere's, box's or torus's `center`, a mesh's bounding-box
    /// centre) and shifted by `translate`; the cables it sweeps are carried along.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub obstacle: Option<usize>,
    /// Index of the support in that rod's `supports`, or of the clamp in that strip's
    /// `clamps` (0 for a strip without `clamps`: its start clamp); unused for an obstacle.
    /// Default 0.
    #[serde(default)]
    pub support: usize,
    /// Translation of the support over the whole stage (m). Default 0.
    #[serde(default)]
    pub translate: [f64; 3],
    /// Rotation vector (axis × angle, rad) of the support about its vertex (a strip's clamp:
    /// about the centre of its clamped edge) over the whole stage. Clamps and clips only.
    /// Default 0.
    #[serde(default)]
    pub rotate: [f64; 3],
    /// Number of equilibrium steps (≥ 1), each with a shape file. Default 1.
    #[serde(default = "one")]
    pub steps: usize,
}

fn one() -> usize {
    1
}

/// A rectangular shell strip (Kirchhoff–Love shell, `slender_core::shell`): length along x,
/// width along z centred on z = 0, mid-surface in the plane y = 0 (rest normal +y), clamped
/// along its edge x = 0 (the default), its edge x = L, or both, each clamp at any pose.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct ShellSpec {
    /// Name used in output files (default `shell<i>`): letters, digits, `-` and `_`.
    #[serde(default)]
    pub name: Option<String>,
    /// Length L along x (m).
    pub length: f64,
    /// Width w along z (m).
    pub width: f64,
    /// Thickness h (m).
    pub thickness: f64,
    /// Material: E with ν (or G), and the density. ν ∈ (−1, 0.5).
    pub material: MaterialSpec,
    /// Elements along the length n_L (≥ 1). Default 15.
    #[serde(default)]
    pub elements: Option<usize>,
    /// Elements across the width n_W (≥ 1). Default round(n_L·w/L), at least 2.
    #[serde(default)]
    pub width_elements: Option<usize>,
    /// Stations along the length (default: power grading s = L(i/n)² toward the clamp).
    #[serde(default)]
    pub grading: Option<Grading>,
    /// Support of the older files: only `"clamp_start"` (the edge x = 0 clamped at rest, the
    /// default without `clamps`). Not together with `clamps`.
    #[serde(default)]
    pub support: Option<String>,
    /// Clamps (at least one; at most one per end): each holds the positions and the tangent
    /// plane of its end edge at a pose. Default: the start edge clamped at rest.
    #[serde(default)]
    pub clamps: Option<Vec<ShellClampSpec>>,
    /// Dead point forces at vertices of the strip's grid (scaled with gravity in the load
    /// ramp).
    #[serde(default)]
    pub forces: Vec<ShellForceSpec>,
    /// Shell model: `"midedge"` (triangles, mid-edge directors; the default) or `"bspline"`
    /// (a C¹ cubic B-spline patch).
    #[serde(default)]
    pub model: Option<ShellModelSpec>,
}

/// The shell formulation of a strip.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "snake_case")]
pub enum ShellModelSpec {
    /// Discrete Kirchhoff–Love shell on triangles with mid-edge directors.
    #[default]
    Midedge,
    /// C¹ Kirchhoff–Love shell on one cubic B-spline patch.
    Bspline,
}

/// A clamp of a strip's end edge at a pose: the edge's rest points x are held at
/// c + offset + R(x − c), c the edge's rest centre ((0, 0, 0) at the start, (L, 0, 0) at the
/// end), R = exp(rotate): the positions and the tangent plane of the edge (mid-edge: the edge
/// vertices and the exact director clamp; B-spline: the two control rows at that end).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct ShellClampSpec {
    /// The clamped edge: `"start"` (x = 0) or `"end"` (x = L).
    pub edge: RodEnd,
    /// Translation (m) of the edge's centre from its rest position, |offset| ≤ 2 L. Default 0.
    #[serde(default)]
    pub offset: [f64; 3],
    /// Rotation vector (axis × angle, rad) of the edge about its centre, angle ≤ 2π. Default
    /// 0.
    #[serde(default)]
    pub rotate: [f64; 3],
}

/// A dead point force at a vertex of a strip's grid (the points of the result grid: station
/// i along the length, column j across the width).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct ShellForceSpec {
    /// Station along the length, 0 (x = 0) … elements (x = L).
    pub station: usize,
    /// Column across the width, 0 (z = −w/2) … width_elements (z = w/2).
    pub column: usize,
    /// Force (N), fixed in space.
    pub force: [f64; 3],
}
