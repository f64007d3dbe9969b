//! The mechanical energy of a moving state.

/// Kinetic and potential energy (J) of a state and velocity.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MechanicalEnergy {
    /// ½ vᵀ M v (J).
    pub kinetic: f64,
    /// The model's energy at the stepper's load factor (J): elastic energy minus the work of
    /// the loads from the reference configuration (gravity's potential included).
    pub potential: f64,
}

impl MechanicalEnergy {
    /// Kinetic + potential (J); constant in an undamped motion.
    pub fn total(&self) -> f64 {
        self.kinetic + self.potential
    }
}
