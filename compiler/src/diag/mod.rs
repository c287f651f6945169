//! Diagnostics: what every stage reports, and how it is shown to users.
//!
//! Stages build [`Diagnostic`]s with spans into the [`SourceMap`](crate::source::SourceMap); nothing
//! here knows about any stage. `render` turns them into codespan-reporting's terminal layout or into
//! JSON lines for tools, adding the include and macro-expansion sites of every label.

mod code;
mod render;

pub use code::Code;
pub use render::{render_json, render_text, to_codespan};

use crate::source::Span;

/// How serious a diagnostic is.
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Severity {
    /// Compilation goes on and succeeds.
    Warning,
    /// Compilation fails.
    Error,
}

/// A span with a message; the primary label marks where the problem is.
#[derive(Clone, Debug, PartialEq)]
pub struct Label {
    /// What the label points at.
    pub span: Span,
    /// What it says there (may be empty).
    pub message: String,
    /// Primary labels mark the problem; secondary ones explain it.
    pub primary: bool,
}

/// One problem found in the source.
#[derive(Clone, Debug, PartialEq)]
pub struct Diagnostic {
    /// Error or warning.
    pub severity: Severity,
    /// The stable code for this kind of problem.
    pub code: Code,
    /// The headline.
    pub message: String,
    /// Where: the first label is primary, the rest explain.
    pub labels: Vec<Label>,
    /// Extra facts, shown as `= note:` lines.
    pub notes: Vec<String>,
    /// A fix, shown as a `= help:` line.
    pub help: Option<String>,
}

impl Diagnostic {
    /// An error with a primary label at `span`.
    pub fn error(code: Code, message: impl Into<String>, span: Span, label: impl Into<String>) -> Diagnostic {
        Diagnostic {
            severity: Severity::Error,
            code,
            message: message.into(),
            labels: vec![Label { span, message: label.into(), primary: true }],
            notes: Vec::new(),
            help: None,
        }
    }

    /// A warning with a primary label at `span`.
    pub fn warning(
        code: Code,
        message: impl Into<String>,
        span: Span,
        label: impl Into<String>,
    ) -> Diagnostic {
        Diagnostic { severity: Severity::Warning, ..Diagnostic::error(code, message, span, label) }
    }

    /// Adds a secondary label explaining the problem.
    pub fn with_label(mut self, span: Span, message: impl Into<String>) -> Diagnostic {
        self.labels.push(Label { span, message: message.into(), primary: false });
        self
    }

    /// Adds a note.
    pub fn with_note(mut self, note: impl Into<String>) -> Diagnostic {
        self.notes.push(note.into());
        self
    }

    /// Sets the help line.
    pub fn with_help(mut self, help: impl Into<String>) -> Diagnostic {
        self.help = Some(help.into());
        self
    }

    /// The span of the primary label.
    pub fn primary_span(&self) -> Span {
        self.labels.iter().find(|l| l.primary).map(|l| l.span).unwrap_or_default()
    }

    /// Whether this diagnostic makes compilation fail.
    pub fn is_error(&self) -> bool {
        self.severity == Severity::Error
    }
}

impl std::fmt::Display for Severity {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Severity::Warning => "warning",
            Severity::Error => "error",
        })
    }
}

/// One line, as the headline of [`render_text`] shows it: `error[E0306]: message`. The labels,
/// notes and help need the [`SourceMap`](crate::source::SourceMap), so only the renderers show them.
impl std::fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}[{}]: {}", self.severity, self.code, self.message)
    }
}

impl std::error::Error for Diagnostic {}

/// Collects diagnostics as a stage runs.
#[derive(Default, Debug, Clone)]
pub struct Diagnostics {
    list: Vec<Diagnostic>,
}

impl Diagnostics {
    /// Records a diagnostic.
    pub fn push(&mut self, d: Diagnostic) {
        self.list.push(d);
    }

    /// Whether any recorded diagnostic is an error.
    pub fn has_errors(&self) -> bool {
        self.list.iter().any(Diagnostic::is_error)
    }

    /// How many diagnostics were recorded.
    pub fn len(&self) -> usize {
        self.list.len()
    }

    /// Whether nothing was recorded.
    pub fn is_empty(&self) -> bool {
        self.list.is_empty()
    }

    /// The recorded diagnostics, in the order they were found.
    pub fn iter(&self) -> std::slice::Iter<'_, Diagnostic> {
        self.list.iter()
    }

    /// Takes the recorded diagnostics.
    pub fn into_vec(self) -> Vec<Diagnostic> {
        self.list
    }

    /// Inserts `items` before the diagnostic at `index` (at the end when `index` is the length),
    /// for a stage that can only decide late whether diagnostics it found early stand.
    pub fn insert(&mut self, index: usize, items: impl IntoIterator<Item = Diagnostic>) {
        let index = index.min(self.list.len());
        self.list.splice(index..index, items);
    }

    /// Moves every diagnostic of `other` into `self`.
    pub fn extend(&mut self, other: impl IntoIterator<Item = Diagnostic>) {
        self.list.extend(other);
    }
}

impl<'a> IntoIterator for &'a Diagnostics {
    type Item = &'a Diagnostic;
    type IntoIter = std::slice::Iter<'a, Diagnostic>;
    fn into_iter(self) -> Self::IntoIter {
        self.list.iter()
    }
}

impl IntoIterator for Diagnostics {
    type Item = Diagnostic;
    type IntoIter = std::vec::IntoIter<Diagnostic>;
    fn into_iter(self) -> Self::IntoIter {
        self.list.into_iter()
    }
}

/// One line per diagnostic, each as [`Diagnostic`]'s `Display` shows it, in the order they were
/// found (no line at all when there is none).
impl std::fmt::Display for Diagnostics {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        for (i, d) in self.list.iter().enumerate() {
            if i > 0 {
                f.write_str("\n")?;
            }
            write!(f, "{d}")?;
        }
        Ok(())
    }
}

impl std::error::Error for Diagnostics {}

#[cfg(test)]
mod tests {
    use super::*;

    fn reserved() -> Diagnostic {
        Diagnostic::error(Code::ReservedWord, "`class` is a reserved word", Span::default(), "here")
            .with_note("not shown in one line")
            .with_help("rename it")
    }

    #[test]
    fn a_diagnostic_displays_as_its_headline() {
        assert_eq!(reserved().to_string(), "error[E0306]: `class` is a reserved word");
        let warning = Diagnostic::warning(Code::LightLimit, "too many lights", Span::default(), "");
        assert_eq!(warning.to_string(), "warning[E0704]: too many lights");
    }

    #[test]
    fn diagnostics_display_one_line_each() {
        let mut list = Diagnostics::default();
        assert_eq!(list.to_string(), "");
        list.push(reserved());
        assert_eq!(list.to_string(), "error[E0306]: `class` is a reserved word");
        list.push(Diagnostic::warning(Code::UnknownInput, "no input `Q`", Span::default(), ""));
        assert_eq!(
            list.to_string(),
            "error[E0306]: `class` is a reserved word\nwarning[E0703]: no input `Q`"
        );
    }

    #[test]
    fn diagnostics_are_errors_for_question_marks() {
        fn fails() -> Result<(), Box<dyn std::error::Error>> {
            Err(reserved())?
        }
        fn fails_with_all() -> Result<(), Box<dyn std::error::Error + Send + Sync>> {
            let mut list = Diagnostics::default();
            list.push(reserved());
            Err(list)?
        }
        assert_eq!(fails().unwrap_err().to_string(), "error[E0306]: `class` is a reserved word");
        assert_eq!(fails_with_all().unwrap_err().to_string(), "error[E0306]: `class` is a reserved word");
    }
}
