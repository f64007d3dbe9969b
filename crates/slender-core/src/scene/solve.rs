//! Solving a scene file: the loaded equilibrium, then each prescribed-motion step, through the
//! [`Session`] (the same code path as interactive editing).

use super::compile::CompiledScene;
use super::result::SceneStep;
use super::session::Session;
use super::spec::Scene;

/// A scene file's solve: step 0, then the motion steps in order.
pub struct SceneSolver {
    session: Session,
}

impl SceneSolver {
    /// Solves the loaded scene (step 0) of `scene`, compiled from `spec`.
    pub fn new(spec: &Scene, scene: &CompiledScene) -> (Self, SceneStep) {
        let session = Session::from_compiled(spec.clone(), scene.clone());
        let step = session.results(0, None, 1.0, 1);
        (Self { session }, step)
    }

    /// Number of motion steps over all stages.
    pub fn motion_steps(&self) -> usize {
        self.session.motion_steps()
    }

    /// Runs step `step` (1-based over all stages) of the prescribed motion. Steps must be run
    /// in order; after a failed step the structures keep their last equilibrium and say so.
    ///
    /// # Panics
    /// If `step` is 0 or larger than [`Self::motion_steps`].
    pub fn run_motion_step(&mut self, step: usize) -> SceneStep {
        self.session.run_motion_step(step)
    }

    /// The session underneath.
    pub fn session(&self) -> &Session {
        &self.session
    }
}
