//! How far a render has got, for callers that show it (the command line draws a progress bar).

/// What a render's work is counted in.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Unit {
    /// Fragments shaded by the CPU reference (counted exactly before shading starts).
    Fragments,
    /// Draw submissions on the GPU, which reports nothing until a submission is done.
    Draws,
}

/// Told the size of a render's work once, then each part as it is done. Called from the thread
/// that renders.
pub trait Progress: Sync {
    /// The total work, called once before any [`Progress::advance`].
    fn start(&self, total: u64, unit: Unit);
    /// `done` more units are finished.
    fn advance(&self, done: u64);
}

/// A [`Progress`] that shows nothing.
pub struct Silent;

impl Progress for Silent {
    fn start(&self, _total: u64, _unit: Unit) {}
    fn advance(&self, _done: u64) {}
}
