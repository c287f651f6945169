//! The error-against-time plot of a sweep (plotters): log-log, one colour per renderer, each
//! setting labelled, the Pareto front joined by a line. Written as SVG and PNG.

use std::path::Path;

use patina_runtime::image::Image;
use patina_runtime::render::Backend;
use patina_runtime::sweep::{Row, Sweep, backend_name};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::{FontStyle, register_font};

/// The plot's size in pixels (SVG units).
const SIZE: (u32, u32) = (860, 540);

/// The font every label is drawn in, embedded so that the plot looks the same on every machine
/// (DejaVu Sans Mono; its licence is in assets/fonts/LICENSE).
static FONT: &[u8] = include_bytes!("../../assets/fonts/DejaVuSansMono.ttf");

/// Writes the plot as `stem.svg` and `stem.png`.
pub fn write(sweep: &Sweep, stem: &Path) -> Result<(), String> {
    // Registering twice (a second sweep in one run) replaces the font with itself.
    register_font("sans-serif", FontStyle::Normal, FONT)
        .map_err(|_| "the embedded font is invalid".to_string())?;
    let svg = stem.with_extension("svg");
    {
        let root = SVGBackend::new(&svg, SIZE).into_drawing_area();
        draw(&root, sweep).map_err(|e| format!("{}: {e}", svg.display()))?;
        root.present().map_err(|e| format!("{}: {e}", svg.display()))?;
    }
    let png = stem.with_extension("png");
    let mut rgb = vec![0u8; (SIZE.0 * SIZE.1 * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, SIZE).into_drawing_area();
        draw(&root, sweep).map_err(|e| format!("{}: {e}", png.display()))?;
        root.present().map_err(|e| format!("{}: {e}", png.display()))?;
    }
    let pixels =
        rgb.chunks_exact(3).map(|p| [p[0], p[1], p[2]].map(|c| f32::from(c) / 255.0)).collect::<Vec<_>>();
    let image = Image {
        width: SIZE.0,
        height: SIZE.1,
        pixels: pixels.into_iter().map(|[r, g, b]| [r, g, b, 1.0]).collect(),
    };
    image.write_png(&png).map_err(|e| format!("{}: {e}", png.display()))
}

/// A renderer's colour.
fn colour(backend: Backend) -> RGBColor {
    match backend {
        Backend::Gpu => RGBColor(0x1f, 0x77, 0xb4),
        Backend::Cpu => RGBColor(0xd6, 0x27, 0x28),
    }
}

/// A row's point: median milliseconds and RMS error, the error raised to `floor` so that an exact
/// setting (error 0) still shows on the log axis.
fn point(row: &Row, floor: f64) -> (f64, f64) {
    ((row.median.as_secs_f64() * 1e3).max(1e-3), row.rms_error.max(floor))
}

fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    sweep: &Sweep,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    root.fill(&WHITE)?;
    let positive = sweep.rows.iter().map(|r| r.rms_error).filter(|e| *e > 0.0);
    let floor = positive.clone().fold(f64::INFINITY, f64::min).min(1.0) / 10.0;
    let floor = if floor.is_finite() { floor } else { 1e-6 };
    let points: Vec<(f64, f64)> = sweep.rows.iter().map(|r| point(r, floor)).collect();
    let (t0, t1) = bounds(points.iter().map(|p| p.0));
    let (e0, e1) = bounds(points.iter().map(|p| p.1));
    let name = sweep.scene.file_stem().map_or("scene".into(), |s| s.to_string_lossy().into_owned());
    let title = format!("{name}: {} ({}) against {}", sweep.knob, sweep.kind.name(), sweep.reference);
    let mut chart = ChartBuilder::on(root)
        .caption(title, ("sans-serif", 20))
        .margin(16)
        .x_label_area_size(44)
        .y_label_area_size(72)
        .build_cartesian_2d((t0..t1).log_scale(), (e0..e1).log_scale())?;
    chart
        .configure_mesh()
        .x_desc(format!("median time per frame (ms), {}x{}, {} runs", sweep.width, sweep.height, sweep.runs))
        .y_desc("RMS error (rgba)")
        .label_style(("sans-serif", 13))
        .axis_desc_style(("sans-serif", 15))
        .x_labels(12)
        .y_labels(12)
        .light_line_style(RGBColor(238, 238, 238))
        .x_label_formatter(&|x| short(*x))
        .y_label_formatter(&|y| format!("{y:.0e}"))
        .draw()?;
    for backend in [Backend::Gpu, Backend::Cpu] {
        let rows: Vec<(&Row, (f64, f64))> =
            sweep.rows.iter().zip(points.iter().copied()).filter(|(r, _)| r.backend == backend).collect();
        if rows.is_empty() {
            continue;
        }
        let c = colour(backend);
        let mut front: Vec<(f64, f64)> = rows.iter().filter(|(r, _)| r.pareto).map(|(_, p)| *p).collect();
        front.sort_by(|a, b| a.0.total_cmp(&b.0));
        chart
            .draw_series(LineSeries::new(front, c.stroke_width(2)))?
            .label(match sweep.convergence_order(backend) {
                Some(order) => format!("{} (line: Pareto front), order {order:.2}", backend_name(backend)),
                None => format!("{} (line: Pareto front)", backend_name(backend)),
            })
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], c.stroke_width(2)));
        chart.draw_series(rows.iter().map(|(r, p)| {
            let style = if r.pareto { c.filled() } else { c.stroke_width(2) };
            Circle::new(*p, 5, style)
        }))?;
        chart.draw_series(rows.iter().map(|(r, p)| {
            Text::new(format!(" {}", r.setting), *p, ("sans-serif", 12).into_font().color(&c))
        }))?;
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()?;
    Ok(())
}

/// A log axis range around the values, a little wider on each side.
fn bounds(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values.fold((f64::INFINITY, 0.0f64), |(lo, hi), v| (lo.min(v), hi.max(v)));
    if !lo.is_finite() || hi <= 0.0 {
        return (1e-3, 1.0);
    }
    (lo / 1.6, hi * 1.6)
}

/// A tick label: three significant digits at most, no trailing zeros.
fn short(x: f64) -> String {
    let digits = if x >= 100.0 {
        0
    } else if x >= 10.0 {
        1
    } else {
        2
    };
    let text = format!("{x:.digits$}");
    if text.contains('.') { text.trim_end_matches('0').trim_end_matches('.').to_string() } else { text }
}
