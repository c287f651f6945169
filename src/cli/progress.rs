//! Progress bars (indicatif) for renders and sweeps: drawn on stderr only once the work has taken
//! longer than a second, and only on a terminal, so quick commands and scripts see nothing.

use std::sync::mpsc::{self, RecvTimeoutError};
use std::time::Duration;

use indicatif::{MultiProgress, ProgressBar, ProgressDrawTarget, ProgressStyle};
use patina_runtime::render::{Progress, Unit};

/// How long work runs before its bars appear.
const QUIET_FOR: Duration = Duration::from_secs(1);

/// Runs `work` with a set of bars that it adds to; they appear after [`QUIET_FOR`] and are cleared
/// when it returns.
pub fn with_bars<T>(work: impl FnOnce(&MultiProgress) -> T) -> T {
    let bars = MultiProgress::with_draw_target(ProgressDrawTarget::hidden());
    let (finished, wait) = mpsc::channel::<()>();
    std::thread::scope(|scope| {
        let shown = bars.clone();
        scope.spawn(move || {
            if wait.recv_timeout(QUIET_FOR) == Err(RecvTimeoutError::Timeout) {
                shown.set_draw_target(ProgressDrawTarget::stderr());
            }
        });
        let result = work(&bars);
        // The watcher may have given up waiting already; then there is no one to tell.
        let _ = finished.send(());
        let _ = bars.clear();
        result
    })
}

/// A bar counting renders (or any other steps) of a sweep.
pub fn steps(bars: &MultiProgress, total: u64) -> ProgressBar {
    let bar = bars.add(ProgressBar::new(total));
    bar.set_style(style("{prefix:>12} [{bar:30}] {pos}/{len} {msg} ({elapsed})"));
    bar.set_prefix("rendering");
    bar.enable_steady_tick(Duration::from_millis(200));
    bar
}

/// One render's bar: fragments shaded on the CPU, a spinner while the GPU draws.
pub struct RenderBar {
    bar: ProgressBar,
}

impl RenderBar {
    /// A bar for one render, labelled `label`, in `bars`.
    pub fn new(bars: &MultiProgress, label: &str) -> RenderBar {
        let bar = bars.add(ProgressBar::new(0));
        bar.set_prefix(label.to_string());
        RenderBar { bar }
    }
}

impl Drop for RenderBar {
    fn drop(&mut self) {
        self.bar.finish_and_clear();
    }
}

impl Progress for RenderBar {
    fn start(&self, total: u64, unit: Unit) {
        self.bar.set_length(total);
        match unit {
            Unit::Fragments => self.bar.set_style(style(
                "{prefix:>12} [{bar:30}] {percent:>3}% of {len} fragments, {eta} left ({elapsed})",
            )),
            Unit::Draws => self.bar.set_style(style("{prefix:>12} {spinner} drawing on the GPU ({elapsed})")),
        }
        self.bar.enable_steady_tick(Duration::from_millis(100));
    }

    fn advance(&self, done: u64) {
        self.bar.inc(done);
    }
}

/// A bar style from a template that is known to be valid.
fn style(template: &str) -> ProgressStyle {
    ProgressStyle::with_template(template)
        .unwrap_or_else(|_| ProgressStyle::default_bar())
        .progress_chars("=> ")
}
