//! Clamps of the strip's ends, exact for a C¹ patch (design.md §3.4): with an open knot
//! vector the boundary curve u = 0 depends only on the first row of control points and the
//! tangent r,u there only on the first two rows, so holding both rows holds the boundary's
//! position and its tangent plane — a clamp, not a hinge, and no element row is stiffened.
//! A clamp at any pose holds the two rows where its rigid motion
//! ([`Clamp`](crate::shell::Clamp)) puts their rest positions.

use serde::{Deserialize, Serialize};

/// An end of the strip.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum StripEnd {
    /// u = 0 (x = 0 at rest).
    Start,
    /// u = L (x = L at rest).
    End,
}

impl StripEnd {
    /// Both ends.
    pub const BOTH: [StripEnd; 2] = [StripEnd::Start, StripEnd::End];

    /// Index into per-end arrays (start 0, end 1).
    pub fn index(self) -> usize {
        match self {
            StripEnd::Start => 0,
            StripEnd::End => 1,
        }
    }

    /// The other end.
    pub fn other(self) -> Self {
        match self {
            StripEnd::Start => StripEnd::End,
            StripEnd::End => StripEnd::Start,
        }
    }

    /// The two control rows a clamp at this end holds, for `n_u` rows along the length.
    pub fn held_rows(self, n_u: usize) -> [usize; 2] {
        match self {
            StripEnd::Start => [0, 1],
            StripEnd::End => [n_u - 2, n_u - 1],
        }
    }
}
