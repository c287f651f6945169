//! `patina bench` run once on a tiny setting: the files it writes and what they say. (The real
//! sweeps are in docs/error-vs-time.md; this only proves the command works.)

use std::path::{Path, PathBuf};

use patina_runtime::image::Image;

use crate::support::patina;

fn scene(name: &str) -> String {
    format!("{}/examples/scenes/{name}.toml", env!("CARGO_MANIFEST_DIR"))
}

/// A fresh directory for one test's output.
fn scratch(test: &str) -> PathBuf {
    crate::support::scratch_dir("bench", test)
}

/// The CSV's rows as maps from column to value.
fn rows(path: &Path) -> Vec<Vec<(String, String)>> {
    let text = std::fs::read_to_string(path).expect("the CSV exists");
    let mut lines = text.lines();
    let header: Vec<String> = lines.next().expect("a header").split(',').map(str::to_string).collect();
    lines.map(|l| header.iter().cloned().zip(l.split(',').map(str::to_string)).collect()).collect()
}

fn get<'a>(row: &'a [(String, String)], column: &str) -> &'a str {
    &row.iter().find(|(c, _)| c == column).unwrap_or_else(|| panic!("no column {column}")).1
}

#[test]
fn soft_sphere_steps_sweep_writes_its_table_and_plot() {
    let out_dir = scratch("soft");
    let out = patina(&[
        "bench",
        &scene("soft_sphere"),
        "--knob",
        "steps=4,16",
        "--size",
        "16x16",
        "--runs",
        "1",
        "-o",
        out_dir.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    let rows = rows(&out_dir.join("soft_sphere_steps.csv"));
    let gpu = patina_runtime::gpu::adapter_required();
    assert_eq!(rows.len(), if gpu { 4 } else { 2 }, "two settings on each renderer: {rows:?}");
    for backend in if gpu { &["gpu", "cpu"][..] } else { &["cpu"][..] } {
        let error = |steps: &str| -> f64 {
            let row =
                rows.iter().find(|r| get(r, "backend") == *backend && get(r, "setting") == steps).unwrap();
            assert_eq!((get(row, "width"), get(row, "height"), get(row, "runs")), ("16", "16", "1"));
            assert!(get(row, "median_ms").parse::<f64>().unwrap() > 0.0);
            assert_eq!(get(row, "non_finite_pixels"), "0");
            get(row, "rms_error").parse().unwrap()
        };
        // Against 1024 steps, 16 steps are far closer than 4 (second order: about 16 times).
        let (coarse, fine) = (error("4"), error("16"));
        assert!(fine > 0.0 && fine < coarse / 4.0, "{backend}: 4 steps {coarse}, 16 steps {fine}");
        let most_accurate = rows.iter().find(|r| get(r, "backend") == *backend && get(r, "setting") == "16");
        assert_eq!(
            get(most_accurate.unwrap(), "pareto"),
            "true",
            "the most accurate setting is on the front"
        );
    }
    let table = std::fs::read_to_string(out_dir.join("soft_sphere_steps.md")).unwrap();
    assert!(table.contains("| setting | renderer | median ms |"), "{table}");
    assert!(table.contains("patina bench") && table.contains("--knob steps=4,16"), "{table}");
    let svg = std::fs::read_to_string(out_dir.join("soft_sphere_steps.svg")).unwrap();
    assert!(svg.starts_with("<svg") && svg.contains("RMS error"), "an SVG with its axis title");
    let png = Image::read_png(out_dir.join("soft_sphere_steps.png")).unwrap();
    assert_eq!((png.width, png.height), (860, 540));
    let _ = std::fs::remove_dir_all(&out_dir);
}

#[test]
fn unknown_knobs_and_settings_are_one_line_errors() {
    let out_dir = scratch("errors");
    let dir = out_dir.to_str().unwrap();
    let out = patina(&["bench", &scene("soft_sphere"), "--knob", "stride", "-o", dir]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("the scene has no knob `stride` (it has: steps, phase)"), "{stderr}");
    assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
    let out = patina(&["bench", &scene("hart_torus"), "--knob", "antialias=point,3x3", "-o", dir]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("`3x3` is not a setting of `antialias` (one of: point, analytic, 2x2, 4x4)"),
        "{stderr}"
    );
    let out = patina(&["bench", &scene("soft_sphere"), "--size", "16by16", "-o", dir]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("expected WIDTHxHEIGHT"));
    let plain = format!("{}/runtime/tests/scenes/teapot.toml", env!("CARGO_MANIFEST_DIR"));
    let out = patina(&["bench", &plain, "-o", dir]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("declares no `[[knob]]`"));
}
