//! Working memory that a model or a factor keeps between calls of its `&self` methods (an
//! assembly, a first guess, a solve), so that a warm re-solve allocates nothing.
//!
//! Why a mutex: those methods take `&self`, and the models and factors must stay `Sync` (the
//! validation crate solves cases on several threads; pyo3 requires it). The buffers hold no
//! state between calls, only capacity, so:
//! - a clone starts empty (it would only copy garbage);
//! - a poisoned lock is taken over (a panic cannot leave the buffers inconsistent);
//! - a call that finds the memory in use on another thread works in fresh memory instead of
//!   waiting (correct, only not allocation-free, and never a deadlock).

use std::sync::{Mutex, TryLockError};

/// Reusable working memory of type `T` (see the module docs). `Debug` shows the type only.
#[derive(Default)]
pub struct Scratch<T>(Mutex<T>);

impl<T: Default> Scratch<T> {
    /// Runs `f` on the kept memory (on fresh memory if another thread holds it now).
    pub fn with<R>(&self, f: impl FnOnce(&mut T) -> R) -> R {
        match self.0.try_lock() {
            Ok(mut kept) => f(&mut kept),
            Err(TryLockError::Poisoned(poisoned)) => f(&mut poisoned.into_inner()),
            Err(TryLockError::WouldBlock) => f(&mut T::default()),
        }
    }

    /// The kept memory, through exclusive access (no lock taken).
    pub fn get_mut(&mut self) -> &mut T {
        self.0
            .get_mut()
            .unwrap_or_else(|poisoned| poisoned.into_inner())
    }
}

impl<T: Default> Clone for Scratch<T> {
    fn clone(&self) -> Self {
        Self::default()
    }
}

impl<T> std::fmt::Debug for Scratch<T> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Scratch<{}>", std::any::type_name::<T>())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn memory_is_kept_between_calls_and_not_cloned() {
        let s = Scratch::<Vec<f64>>::default();
        s.with(|v| v.extend([1.0, 2.0]));
        assert_eq!(s.with(|v| v.len()), 2);
        assert_eq!(s.clone().with(|v| v.len()), 0);
    }

    #[test]
    fn a_call_inside_a_call_gets_fresh_memory_instead_of_a_deadlock() {
        let s = Scratch::<Vec<f64>>::default();
        s.with(|outer| {
            outer.push(1.0);
            assert_eq!(s.with(|inner| inner.len()), 0);
        });
        assert_eq!(s.with(|v| v.len()), 1);
    }
}
