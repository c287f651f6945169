//! Scene errors as one line each: `file:line:column: field: message`.
//!
//! toml reports where an error is (a byte span) and what went wrong, but not which field; the
//! field is recovered by finding the smallest key or value of the document's spanned tree that
//! holds the span. Semantic checks go the other way, from a field to its span.

use std::fmt;
use std::ops::Range;
use toml::Spanned;
use toml::de::{DeArray, DeTable, DeValue};

/// What kind of problem a [`SceneError`] reports.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SceneErrorKind {
    /// The file could not be read.
    Read,
    /// The text is not TOML.
    Syntax,
    /// A field is unknown, missing or of the wrong type.
    Schema,
    /// A value is well typed but unusable (out of range, empty, contradictory).
    Invalid,
}

/// A problem with a scene file, displayed as one line naming the file, the position (1-based line
/// and column, in characters) and the field, e.g.
/// `scenes/bad.toml:12:7: camera.fov: expected a number, found a string`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SceneError {
    /// The scene file as it was named to [`crate::scene::Scene::load`] or `parse`.
    pub file: String,
    /// What kind of problem this is.
    pub kind: SceneErrorKind,
    /// 1-based line and column, where known.
    pub position: Option<(usize, usize)>,
    /// The field, as a TOML path with array indices: `object[1].transform[0].rotate.axis`.
    pub field: Option<String>,
    /// What is wrong.
    pub message: String,
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.kind == SceneErrorKind::Read {
            return write!(f, "cannot read {}: {}", self.file, self.message);
        }
        write!(f, "{}", self.file)?;
        if let Some((line, column)) = self.position {
            write!(f, ":{line}:{column}")?;
        }
        if let Some(field) = &self.field {
            write!(f, ": {field}")?;
        }
        write!(f, ": {}", self.message)
    }
}

impl std::error::Error for SceneError {}

/// An I/O error's message without Rust's " (os error N)" suffix.
pub(crate) fn io_message(e: &std::io::Error) -> String {
    let text = e.to_string();
    match text.rfind(" (os error ") {
        Some(at) if text.ends_with(')') => text[..at].to_string(),
        _ => text,
    }
}

/// One step of a field path.
#[derive(Clone, Debug)]
pub(crate) enum Seg {
    Key(String),
    Index(usize),
}

/// A field path such as `object[1].shader`.
#[derive(Clone, Debug, Default)]
pub(crate) struct Field(pub Vec<Seg>);

impl Field {
    pub fn key(&self, key: &str) -> Field {
        let mut segs = self.0.clone();
        segs.push(Seg::Key(key.to_string()));
        Field(segs)
    }

    pub fn index(&self, index: usize) -> Field {
        let mut segs = self.0.clone();
        segs.push(Seg::Index(index));
        Field(segs)
    }
}

/// A path from its keys, e.g. `field(&["camera", "fov"])`.
pub(crate) fn field(keys: &[&str]) -> Field {
    Field(keys.iter().map(|k| Seg::Key(k.to_string())).collect())
}

impl fmt::Display for Field {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, seg) in self.0.iter().enumerate() {
            match seg {
                Seg::Key(k) if i == 0 => write!(f, "{k}")?,
                Seg::Key(k) => write!(f, ".{k}")?,
                Seg::Index(n) => write!(f, "[{n}]")?,
            }
        }
        Ok(())
    }
}

/// Positions and fields of one scene text.
pub(crate) struct Locator<'a> {
    pub file: String,
    pub text: &'a str,
    pub root: Option<&'a Spanned<DeTable<'a>>>,
}

impl Locator<'_> {
    /// 1-based line and column (in characters) of a byte offset.
    pub fn position(&self, offset: usize) -> (usize, usize) {
        let mut offset = offset.min(self.text.len());
        while !self.text.is_char_boundary(offset) {
            offset -= 1;
        }
        let before = &self.text[..offset];
        let line_start = before.rfind('\n').map_or(0, |i| i + 1);
        (before.matches('\n').count() + 1, before[line_start..].chars().count() + 1)
    }

    /// An error at `span` (if any) on `field` (if known).
    pub fn error(
        &self,
        kind: SceneErrorKind,
        span: Option<Range<usize>>,
        field: Option<String>,
        message: String,
    ) -> SceneError {
        let position = span.map(|s| self.position(s.start));
        SceneError { file: self.file.clone(), kind, position, field, message }
    }

    /// A toml error, with its field found from its span and its message made plain.
    pub fn toml_error(&self, kind: SceneErrorKind, e: &toml::de::Error) -> SceneError {
        let root_span = self.root.map(|r| r.span());
        let span = e.span().filter(|s| Some(s) != root_span.as_ref());
        let mut field = span.as_ref().and_then(|s| self.field_at(s));
        if kind == SceneErrorKind::Syntax && field.is_none() {
            field = span.as_ref().and_then(|s| self.syntax_field(s, e.message()));
        }
        let field = field.map(|f| f.to_string()).filter(|f| !f.is_empty());
        let message = plain_message(e.message());
        match (kind, span.is_some()) {
            (SceneErrorKind::Syntax, _) => self.error(kind, span, field, format!("invalid TOML: {message}")),
            // Only a table the scene must have is reported about the whole document.
            (_, false) => match e.message().strip_prefix("missing field `") {
                Some(name) => {
                    let message = format!("the scene has no [{}] table", name.trim_end_matches('`'));
                    self.error(kind, None, None, message)
                }
                None => self.error(kind, None, None, message),
            },
            _ => self.error(kind, span, field, message),
        }
    }

    /// A semantic error on `field`, placed at its value (or, when it was left out, at the nearest
    /// enclosing table that was written).
    pub fn invalid(&self, at: &Field, message: impl Into<String>) -> SceneError {
        let span = self.span_of(at);
        self.error(SceneErrorKind::Invalid, span, Some(at.to_string()), message.into())
    }

    /// The span of the value at `field`, or of its nearest written ancestor.
    pub fn span_of(&self, field: &Field) -> Option<Range<usize>> {
        self.find(field).0
    }

    /// Whether `field` is written in the file (rather than left to its default).
    pub fn is_written(&self, field: &Field) -> bool {
        self.find(field).1
    }

    fn find(&self, field: &Field) -> (Option<Range<usize>>, bool) {
        let Some(root) = self.root else { return (None, false) };
        let mut node = (root.span(), Some(root.get_ref()), None::<&DeArray>);
        let mut span = None;
        for seg in &field.0 {
            let next = match (seg, node) {
                (Seg::Key(k), (_, Some(table), _)) => {
                    table.iter().find(|(key, _)| key.get_ref().as_ref() == k.as_str()).map(|(_, v)| v)
                }
                (Seg::Index(i), (_, _, Some(array))) => array.get(*i),
                _ => None,
            };
            let Some(next) = next else { return (span, false) };
            node = (next.span(), next.get_ref().as_table(), next.get_ref().as_array());
            span = Some(node.0.clone());
        }
        (span, true)
    }

    /// The field of a syntax error at `span`, from the tree parsed around it: a bad value's key
    /// usually precedes it on its line, and a duplicate key's table is that of the key before it.
    fn syntax_field(&self, span: &Range<usize>, message: &str) -> Option<Field> {
        if message == "duplicate key" {
            let mut table = self.key_before(span.start, 0)?;
            table.0.pop();
            let name = self.text.get(span.clone())?.trim().trim_matches(|c| c == '"' || c == '\'');
            return Some(table.key(name));
        }
        let line_start = self.text.get(..span.start)?.rfind('\n').map_or(0, |i| i + 1);
        self.key_before(span.start, line_start)
    }

    /// The path of the last key written between `from` and `offset`.
    fn key_before(&self, offset: usize, from: usize) -> Option<Field> {
        let mut best: Option<(usize, Field)> = None;
        search_keys(self.root?.get_ref(), &Field::default(), &mut |span, path| {
            if (from..offset).contains(&span.start) && best.as_ref().is_none_or(|(b, _)| span.start > *b) {
                best = Some((span.start, path.clone()));
            }
        });
        best.map(|(_, f)| f)
    }

    /// The path of the smallest key or value whose span holds `span`.
    fn field_at(&self, span: &Range<usize>) -> Option<Field> {
        let mut best: Option<(usize, Field)> = None;
        search_table(self.root?.get_ref(), &Field::default(), span, &mut best);
        best.map(|(_, f)| f)
    }
}

fn search_keys(table: &DeTable, path: &Field, visit: &mut dyn FnMut(Range<usize>, &Field)) {
    for (key, value) in table.iter() {
        let path = path.key(key.get_ref());
        visit(key.span(), &path);
        let mut nested = |v: &Spanned<DeValue>, path: &Field| {
            if let DeValue::Table(t) = v.get_ref() {
                search_keys(t, path, visit);
            }
        };
        match value.get_ref() {
            DeValue::Array(a) => a.iter().enumerate().for_each(|(i, item)| nested(item, &path.index(i))),
            _ => nested(value, &path),
        }
    }
}

fn holds(outer: &Range<usize>, inner: &Range<usize>) -> bool {
    outer.start <= inner.start && inner.end <= outer.end
}

fn consider(candidate: Range<usize>, path: &Field, span: &Range<usize>, best: &mut Option<(usize, Field)>) {
    let size = candidate.len();
    if holds(&candidate, span) && best.as_ref().is_none_or(|(b, _)| size <= *b) {
        *best = Some((size, path.clone()));
    }
}

// Every node is visited: a `[table]`'s span is only its header, so its entries lie outside it.
fn search_table(table: &DeTable, path: &Field, span: &Range<usize>, best: &mut Option<(usize, Field)>) {
    for (key, value) in table.iter() {
        let path = path.key(key.get_ref());
        consider(key.span(), &path, span, best);
        search_value(value, &path, span, best);
    }
}

fn search_value(
    value: &Spanned<DeValue>,
    path: &Field,
    span: &Range<usize>,
    best: &mut Option<(usize, Field)>,
) {
    consider(value.span(), path, span, best);
    match value.get_ref() {
        DeValue::Table(t) => search_table(t, path, span, best),
        DeValue::Array(a) => {
            for (i, item) in a.iter().enumerate() {
                search_value(item, &path.index(i), span, best);
            }
        }
        _ => {}
    }
}

/// serde's messages in the scene's vocabulary: "expected a number, found a string" rather than
/// "invalid type: string \"x\", expected f32".
pub(crate) fn plain_message(message: &str) -> String {
    let message = message.trim_end();
    if let Some(rest) =
        message.strip_prefix("invalid type: ").or_else(|| message.strip_prefix("invalid value: "))
        && let Some((found, expected)) = rest.split_once(", expected ")
    {
        return format!("expected {}, found {}", plain_expected(expected), plain_found(found));
    }
    if let Some(rest) = message.strip_prefix("invalid length ")
        && let Some((n, expected)) = rest.split_once(", expected ")
    {
        let found = if n == "1" { "1 element".to_string() } else { format!("{n} elements") };
        return format!("expected {}, found {found}", plain_expected(expected));
    }
    if let Some(rest) = message.strip_prefix("unknown field ") {
        return match rest.split_once(", expected ") {
            Some((name, allowed)) => format!("unknown field {name}; allowed fields: {}", plain_list(allowed)),
            None => match rest.split_once(", there are no fields") {
                Some((name, _)) => format!("unknown field {name}; this table has no fields"),
                None => message.to_string(),
            },
        };
    }
    if let Some(rest) = message.strip_prefix("unexpected keys in table: ")
        && let Some((names, allowed)) = rest.split_once(", available keys: ")
    {
        let names: Vec<_> = names.split(", ").map(|n| format!("`{n}`")).collect();
        let plural = if names.len() == 1 { "" } else { "s" };
        return format!("unknown field{plural} {}; allowed fields: {allowed}", names.join(", "));
    }
    if let Some(rest) = message.strip_prefix("unknown variant ")
        && let Some((name, allowed)) = rest.split_once(", expected ")
    {
        // The scene's enumerations are the transformation steps and the knob kinds.
        let what = if allowed.contains("`translate`") { "transformation" } else { "kind" };
        return format!("unknown {what} {name}; expected {}", plain_list(allowed));
    }
    if message.starts_with("wanted exactly 1 element") {
        return "expected a table with exactly one key, e.g. { translate = [0, 1, 0] }".into();
    }
    message.to_string()
}

/// "one of `a`, `b`, `c`" or "`a` or `b`" or "`a`" as "a, b, c".
fn plain_list(list: &str) -> String {
    let list = list.strip_prefix("one of ").unwrap_or(list);
    list.replace(" or ", ", ").replace('`', "")
}

fn plain_expected(expected: &str) -> String {
    match expected {
        "f32" | "f64" => "a number".into(),
        "i8" | "i16" | "i32" | "i64" | "u8" | "u16" | "u32" | "u64" | "usize" => "an integer".into(),
        "a sequence" => "an array".into(),
        "a map" => "a table".into(),
        "a borrowed string" => "a string".into(),
        e if e.starts_with("struct ") || e.starts_with("enum ") => "a table".into(),
        e if e.starts_with("an array of length ") => format!("an array of {} numbers", &e[19..]),
        e => e.into(),
    }
}

fn plain_found(found: &str) -> String {
    let value = found.split_once(' ').map(|(_, v)| v.trim_matches('`')).unwrap_or("");
    match found.split(' ').next().unwrap_or(found) {
        "string" => "a string".into(),
        "integer" => format!("the integer {value}"),
        "floating" => format!("the number {}", found.trim_start_matches("floating point ").trim_matches('`')),
        "boolean" => "a boolean".into(),
        "sequence" => "an array".into(),
        "map" => "a table".into(),
        _ => found.into(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn serde_messages_are_rewritten() {
        let cases = [
            ("invalid type: string \"x\", expected f32", "expected a number, found a string"),
            ("invalid type: floating point `2.5`, expected i64", "expected an integer, found the number 2.5"),
            ("invalid type: integer `3`, expected struct Cam", "expected a table, found the integer 3"),
            (
                "invalid length 2, expected an array of length 3",
                "expected an array of 3 numbers, found 2 elements",
            ),
            (
                "unknown field `foo`, expected `fov` or `from`",
                "unknown field `foo`; allowed fields: fov, from",
            ),
            (
                "unknown field `x`, expected one of `a`, `b`, `c`",
                "unknown field `x`; allowed fields: a, b, c",
            ),
            ("missing field `from`", "missing field `from`"),
            (
                "unexpected keys in table: axes, available keys: angle, axis",
                "unknown field `axes`; allowed fields: angle, axis",
            ),
        ];
        for (raw, plain) in cases {
            assert_eq!(plain_message(raw), plain);
        }
    }

    #[test]
    fn positions_count_lines_and_characters() {
        let loc = Locator { file: "f".into(), text: "ab\nçd = 1\n", root: None };
        assert_eq!(loc.position(0), (1, 1));
        assert_eq!(loc.position(3), (2, 1));
        assert_eq!(loc.position(5), (2, 2), "ç is two bytes, one column");
        assert_eq!(loc.position(100), (3, 1));
    }

    #[test]
    fn os_error_numbers_are_dropped() {
        let e = std::io::Error::from(std::io::ErrorKind::NotFound);
        assert!(!io_message(&e).contains("os error"));
        let e = std::io::Error::from_raw_os_error(2);
        assert_eq!(io_message(&e), "No such file or directory");
    }
}
