//! Error against run time: a scene rendered at several settings of one quality knob, each timed
//! on the GPU and the CPU reference (the median of warm runs) and measured against the knob's
//! reference image on the rgba32float images, with the settings that no other beats on both counts
//! (the Pareto front) marked.
//!
//! The reference is drawn by the CPU reference renderer, once: the same scene at the knob's
//! reference setting, or the reference scene the knob names (a closed form or an exact box
//! filter). Every setting's image, GPU or CPU, is measured against it, so the GPU's rows include
//! the GPU's own differences from the CPU (usually far below the knob's error).

mod pareto;

use std::path::PathBuf;
use std::time::{Duration, Instant};

use crate::gpu::Gpu;
use crate::image::{Image, Thresholds, compare};
use crate::render::{self, Backend, Cache, Options, Progress, RenderError};
use crate::scene::{Knob, KnobKind, Reference, Scene, Setting};
pub use pareto::pareto_front;

/// What to measure.
#[derive(Clone, Debug)]
pub struct Plan {
    /// The settings, in the order to report them.
    pub settings: Vec<Setting>,
    /// The renderers to time.
    pub backends: Vec<Backend>,
    /// Timed runs per setting and renderer, after one untimed warm-up run (at least 1).
    pub runs: usize,
    /// Render at this size instead of the scene's (the reference too).
    pub size: Option<(u32, u32)>,
}

/// Told about each render of a sweep as it starts.
pub trait Observer {
    /// A render of `what` is starting; its progress goes to the returned reporter.
    fn render(&self, what: &str) -> Box<dyn Progress + '_>;
}

/// An observer that ignores everything.
pub struct Quiet;

impl Observer for Quiet {
    fn render(&self, _: &str) -> Box<dyn Progress + '_> {
        Box::new(render::Silent)
    }
}

/// One setting on one renderer.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// The setting's label.
    pub setting: String,
    /// The renderer.
    pub backend: Backend,
    /// Compiling the setting's shaders (binding, both backends), once.
    pub compile: Duration,
    /// The timed runs, in order.
    pub times: Vec<Duration>,
    /// The median of `times`.
    pub median: Duration,
    /// The root mean square of the channel differences from the reference.
    pub rms_error: f64,
    /// The largest channel difference from the reference.
    pub max_error: f64,
    /// Pixels with a NaN or infinity (left out of the errors).
    pub non_finite: usize,
    /// Whether no other setting on the same renderer is both faster and more accurate.
    pub pareto: bool,
}

/// A measured sweep.
#[derive(Clone, Debug)]
pub struct Sweep {
    /// The scene file.
    pub scene: PathBuf,
    /// The knob's name and kind.
    pub knob: String,
    /// See `knob`.
    pub kind: KnobKind,
    /// The reference's label.
    pub reference: String,
    /// How long the CPU reference took to draw (one run).
    pub reference_time: Duration,
    /// The image size.
    pub width: u32,
    /// See `width`.
    pub height: u32,
    /// Timed runs per row.
    pub runs: usize,
    /// One row per setting and renderer, settings in the plan's order.
    pub rows: Vec<Row>,
}

/// Measures `plan`'s settings of `knob` on `scene`.
pub fn run(
    scene: &Scene,
    knob: &Knob,
    plan: &Plan,
    gpu: Option<&Gpu>,
    observer: &dyn Observer,
) -> Result<Sweep, RenderError> {
    let sized = |s: Scene| match plan.size {
        Some((width, height)) => Scene { output: crate::scene::Output { width, height, ..s.output }, ..s },
        None => s,
    };
    let (reference_scene, reference_label) = match &knob.reference {
        Reference::Setting(s) => (scene.with_setting(s), s.label.clone()),
        Reference::Scene { path, label } => {
            let loaded = Scene::load(path).map_err(|e| RenderError::Input(e.to_string()))?;
            (loaded, label.clone())
        }
    };
    let reference_scene = sized(reference_scene);
    let mut cache = Cache::new();
    let prepared = render::prepare_cached(&reference_scene, Options::default(), &mut cache)?;
    let start = Instant::now();
    let what = format!("reference {reference_label}");
    let reference = render::render_with_progress(&prepared, Backend::Cpu, None, &*observer.render(&what))?;
    let reference_time = start.elapsed();
    drop(prepared);

    let mut rows = Vec::new();
    for setting in &plan.settings {
        let scene = sized(scene.with_setting(setting));
        if (scene.output.width, scene.output.height) != (reference.width, reference.height) {
            return Err(RenderError::Input(format!(
                "the reference is {}x{} but the scene is {}x{}",
                reference.width, reference.height, scene.output.width, scene.output.height
            )));
        }
        let start = Instant::now();
        let prepared = render::prepare_cached(&scene, Options::default(), &mut cache)?;
        let compile = start.elapsed();
        for &backend in &plan.backends {
            let label = format!("{} {} ({})", knob.name, setting.label, backend_name(backend));
            let (image, times) = timed(&prepared, backend, gpu, plan.runs.max(1), &label, observer)?;
            let c = compare(&image, &reference, &Thresholds::default())
                .map_err(|e| RenderError::Input(format!("{label}: {e}")))?;
            rows.push(Row {
                setting: setting.label.clone(),
                backend,
                compile,
                median: median(&times),
                times,
                rms_error: f64::from(c.rms_error),
                max_error: f64::from(c.max_error),
                non_finite: c.nan_pixels,
                pareto: false,
            });
        }
    }
    for backend in &plan.backends {
        let mine: Vec<usize> = (0..rows.len()).filter(|&i| rows[i].backend == *backend).collect();
        let points: Vec<(f64, f64)> =
            mine.iter().map(|&i| (rows[i].median.as_secs_f64(), rows[i].rms_error)).collect();
        for (&i, on) in mine.iter().zip(pareto_front(&points)) {
            rows[i].pareto = on;
        }
    }
    Ok(Sweep {
        scene: scene.file.clone(),
        knob: knob.name.clone(),
        kind: knob.kind,
        reference: reference_label,
        reference_time,
        width: reference.width,
        height: reference.height,
        runs: plan.runs.max(1),
        rows,
    })
}

impl Sweep {
    /// The empirical order of convergence on `backend`: the least-squares slope of log RMS error
    /// against log step count (negated) or log step size, for a knob of steps, step sizes or
    /// samples whose settings are numbers; `None` for other knobs or fewer than two usable rows.
    /// Settings whose error is at the reference's own level (below 1e-6) are left out: there the
    /// error is rounding, not truncation.
    pub fn convergence_order(&self, backend: Backend) -> Option<f64> {
        let sign = match self.kind {
            KnobKind::Steps | KnobKind::Samples => -1.0,
            KnobKind::StepSize => 1.0,
            _ => return None,
        };
        let points: Vec<(f64, f64)> = (self.rows.iter())
            .filter(|r| r.backend == backend && r.rms_error > 1e-6)
            .filter_map(|r| {
                Some((r.setting.parse::<f64>().ok().filter(|v| *v > 0.0)?.ln(), r.rms_error.ln()))
            })
            .collect();
        if points.len() < 2 {
            return None;
        }
        let n = points.len() as f64;
        let (mx, my) =
            (points.iter().map(|p| p.0).sum::<f64>() / n, points.iter().map(|p| p.1).sum::<f64>() / n);
        let sxy: f64 = points.iter().map(|(x, y)| (x - mx) * (y - my)).sum();
        let sxx: f64 = points.iter().map(|(x, _)| (x - mx) * (x - mx)).sum();
        (sxx > 0.0).then(|| sign * sxy / sxx)
    }
}

/// A renderer's name in tables and plots.
pub fn backend_name(backend: Backend) -> &'static str {
    match backend {
        Backend::Gpu => "gpu",
        Backend::Cpu => "cpu",
    }
}

/// Renders once untimed (shader modules, pipelines and caches warm up), then `runs` timed
/// times; returns the last image and the times.
fn timed(
    prepared: &render::Prepared,
    backend: Backend,
    gpu: Option<&Gpu>,
    runs: usize,
    label: &str,
    observer: &dyn Observer,
) -> Result<(Image, Vec<Duration>), RenderError> {
    let mut image = render::render_with_progress(prepared, backend, gpu, &*observer.render(label))?;
    let mut times = Vec::with_capacity(runs);
    for _ in 0..runs {
        let progress = observer.render(label);
        let start = Instant::now();
        image = render::render_with_progress(prepared, backend, gpu, &*progress)?;
        times.push(start.elapsed());
    }
    Ok((image, times))
}

/// The median (the mean of the middle two for an even count); zero for none.
pub fn median(times: &[Duration]) -> Duration {
    let mut sorted = times.to_vec();
    sorted.sort();
    match sorted.len() {
        0 => Duration::ZERO,
        n if n % 2 == 1 => sorted[n / 2],
        n => (sorted[n / 2 - 1] + sorted[n / 2]) / 2,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(setting: &str, backend: Backend, rms_error: f64) -> Row {
        let t = Duration::from_millis(1);
        Row {
            setting: setting.into(),
            backend,
            compile: t,
            times: vec![t],
            median: t,
            rms_error,
            max_error: rms_error,
            non_finite: 0,
            pareto: true,
        }
    }

    #[test]
    fn convergence_order_is_the_slope_of_the_log_error() {
        // Error 3 n^-2 on the CPU; the GPU's rows have another slope and do not mix in.
        let mut rows: Vec<Row> =
            [4.0, 8.0, 16.0].iter().map(|n: &f64| row(&n.to_string(), Backend::Cpu, 3.0 / (n * n))).collect();
        rows.push(row("4", Backend::Gpu, 0.5));
        rows.push(row("16", Backend::Gpu, 0.5 / 4.0));
        // At the reference's rounding level: left out.
        rows.push(row("1024", Backend::Cpu, 1e-7));
        let mut sweep = Sweep {
            scene: "s.toml".into(),
            knob: "steps".into(),
            kind: KnobKind::Steps,
            reference: "exact".into(),
            reference_time: Duration::ZERO,
            width: 1,
            height: 1,
            runs: 1,
            rows,
        };
        assert!((sweep.convergence_order(Backend::Cpu).unwrap() - 2.0).abs() < 1e-12);
        assert!((sweep.convergence_order(Backend::Gpu).unwrap() - 1.0).abs() < 1e-12);
        sweep.kind = KnobKind::Octaves;
        assert_eq!(sweep.convergence_order(Backend::Cpu), None);
    }

    #[test]
    fn median_of_odd_and_even_counts() {
        let ms = |v: &[u64]| v.iter().map(|&m| Duration::from_millis(m)).collect::<Vec<_>>();
        assert_eq!(median(&ms(&[30, 10, 20])), Duration::from_millis(20));
        assert_eq!(median(&ms(&[40, 10, 30, 20])), Duration::from_millis(25));
        assert_eq!(median(&[]), Duration::ZERO);
    }
}
