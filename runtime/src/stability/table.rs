//! The sweep's report as a table: aligned plain text for a terminal, Markdown and CSV.

use super::{BACKENDS, Row};

/// The columns of the table.
const HEADER: [&str; 9] = [
    "file",
    "subject",
    "points",
    "non-finite f64",
    "non-finite f32",
    "non-finite gpu",
    "err f32-f64",
    "err gpu-f32",
    "err fast-f64",
];

/// A table's cells, one row per subject (a subject not swept shows why in its last cell).
fn cells(rows: &[Row]) -> Vec<[String; 9]> {
    let count = |c: Option<usize>| c.map_or("-".to_string(), |n| n.to_string());
    let error = |e: f64| if e == 0.0 { "0".to_string() } else { format!("{e:.1e}") };
    rows.iter()
        .map(|row| {
            let mut cell = [
                row.file.clone(),
                row.label.clone(),
                row.points.to_string(),
                String::new(),
                String::new(),
                String::new(),
                String::new(),
                String::new(),
                String::new(),
            ];
            match &row.outcome {
                Ok(m) => {
                    for k in 0..BACKENDS.len() {
                        cell[3 + k] = count(m.nonfinite[k]);
                    }
                    cell[6] = error(m.f32_vs_f64);
                    cell[7] = match (&m.gpu_error, m.gpu_vs_f32) {
                        (Some(_), _) => "GPU error".into(),
                        (None, Some(e)) => error(e),
                        (None, None) => "-".into(),
                    };
                    cell[8] = match (&m.gpu_error, m.fast_vs_f64) {
                        (Some(_), _) => "GPU error".into(),
                        (None, Some(e)) => error(e),
                        (None, None) => "-".into(),
                    };
                }
                Err(why) => cell[8] = why.clone(),
            }
            cell
        })
        .collect()
}

/// Aligned plain text, numbers right-aligned.
pub fn plain(rows: &[Row]) -> String {
    let body = cells(rows);
    let mut width = HEADER.map(str::len);
    for row in &body {
        for (k, (w, c)) in width.iter_mut().zip(row).enumerate() {
            // A reason in the last column (not a number) runs on past it and sets no width.
            if k < HEADER.len() - 1 || c.len() <= 12 {
                *w = (*w).max(c.chars().count());
            }
        }
    }
    let line = |row: &[String]| -> String {
        let mut out = String::new();
        for (k, c) in row.iter().enumerate() {
            let pad = " ".repeat(width[k].saturating_sub(c.chars().count()));
            if k < 2 {
                out.push_str(&format!("{c}{pad}  "));
            } else {
                out.push_str(&format!("{pad}{c}  "));
            }
        }
        out.trim_end().to_string() + "\n"
    };
    let mut out = line(&HEADER.map(String::from));
    for row in &body {
        out.push_str(&line(row));
    }
    out
}

/// A Markdown table.
pub fn markdown(rows: &[Row]) -> String {
    let line = |row: &[String]| {
        format!("| {} |\n", row.iter().map(|c| c.replace('|', "\\|")).collect::<Vec<_>>().join(" | "))
    };
    let mut out = line(&HEADER.map(String::from));
    out.push_str(&format!(
        "|{}\n",
        ["---|", "---|", "---:|", "---:|", "---:|", "---:|", "---:|", "---:|", "---:|"].concat()
    ));
    for row in cells(rows) {
        out.push_str(&line(&row));
    }
    out
}

/// CSV (RFC 4180 quoting), with the header as its first line.
pub fn csv(rows: &[Row]) -> String {
    let quote = |c: &String| {
        if c.contains([',', '"', '\n']) { format!("\"{}\"", c.replace('"', "\"\"")) } else { c.clone() }
    };
    let line = |row: &[String]| row.iter().map(quote).collect::<Vec<_>>().join(",") + "\n";
    let mut out = line(&HEADER.map(String::from));
    for row in cells(rows) {
        out.push_str(&line(&row));
    }
    out
}
