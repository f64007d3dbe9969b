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
    /// Prescribed support motion, in stages run one after the other after the initial solve.
    #[serde(default)]
    pub motion: Vec<MotionStage>,
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
}

/// Rest centerline generators.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum Centerline {
    /// Straight segment.
    Straight {
        /// First point (m).
        start: [f64; 3],
        /// Direction (normalized internally).
        direction: [f64; 3],
        /// Length (m).
        length: f64,
    },
    /// Circular arc (may exceed one turn).
    Arc {
        /// First point (m).
        start: [f64; 3],
        /// Tangent at the start.
        tangent: [f64; 3],
        /// Direction toward the center at the start.
        normal: [f64; 3],
        /// Radius (m).
        radius: f64,
        /// Arc length (m).
        length: f64,
    },
    /// Circular helix.
    Helix {
        /// First point (m).
        start: [f64; 3],
        /// Axis direction.
        axis: [f64; 3],
        /// Direction from the start point toward the axis.
        normal: [f64; 3],
        /// Radius (m).
        radius: f64,
        /// Rise per turn (m); negative for left-handed.
        pitch: f64,
        /// Arc length (m).
        length: f64,
    },
    /// Polygonal line through points (m).
    Polyline {
        /// At least two points, consecutive points distinct.
        points: Vec<[f64; 3]>,
    },
}

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
}

/// A support on one vertex.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct SupportSpec {
    /// Clamp, pin or clip.
    pub kind: SupportKind,
    /// The held vertex.
    pub vertex: VertexRef,
}

/// A dead point force.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct PointForceSpec {
    /// Loaded vertex.
    pub vertex: VertexRef,
    /// Force (N).
    pub force: [f64; 3],
}

/// A point moment (acts on the edge that starts at the vertex; the last edge at the end).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct PointMomentSpec {
    /// Loaded vertex.
    pub vertex: VertexRef,
    /// Moment (N m).
    pub moment: [f64; 3],
}

/// One stage of prescribed motion: a support moved rigidly, in equal steps, each solved
/// from the previous equilibrium.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct MotionStage {
    /// Index of the rod in `rods`.
    pub rod: usize,
    /// Index of the support in that rod's `supports`.
    pub support: usize,
    /// Translation of the support over the whole stage (m). Default 0.
    #[serde(default)]
    pub translate: [f64; 3],
    /// Rotation vector (axis × angle, rad) of the support about its vertex over the whole
    /// stage. Clamps and clips only. Default 0.
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
/// along its edge x = 0 (exact director clamp). That is the only support the shell model has.
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
    /// Support: only `"clamp_start"` (the edge x = 0 clamped), the default.
    #[serde(default)]
    pub support: Option<String>,
}
