//! The documents the editor has open: their text and version, and their last analysis.

use std::collections::HashMap;
use std::path::Path;

use lsp_types::{Range, TextDocumentContentChangeEvent, Uri};
use patina_compiler::diag::Code;
use patina_compiler::source::SourceMap;

use super::analysis::Analysis;
use super::{position, uri};

/// One open document.
pub struct Document {
    /// The name the compiler sees it under (its path, or its URI; see [`uri::file_name`]).
    pub name: String,
    /// The editor's version of the text.
    pub version: i32,
    /// The text as the editor has it (saved or not).
    pub text: String,
    /// The analysis of this version of the text; `None` after a change, until it is checked again.
    pub analysis: Option<Analysis>,
    /// The last analysis of an earlier text that went through the semantic stage, kept while the
    /// current one has not (see `view.rs`).
    pub earlier: Option<Analysis>,
}

impl Document {
    /// Marks the analysis out of date, keeping it as the earlier one if it has semantic results.
    pub fn invalidate(&mut self) {
        if let Some(old) = self.analysis.take()
            && old.has_semantics()
        {
            self.earlier = Some(old);
        }
    }

    /// Records the analysis of the current text (the earlier one is dropped once this one has
    /// semantic results of its own).
    pub fn analysed(&mut self, analysis: Analysis) {
        if analysis.has_semantics() {
            self.earlier = None;
        }
        self.analysis = Some(analysis);
    }
}

/// Every open document, by URI.
#[derive(Default)]
pub struct Documents {
    by_uri: HashMap<Uri, Document>,
}

impl Documents {
    /// Opens (or reopens) a document.
    pub fn open(&mut self, uri: Uri, version: i32, text: String) {
        let name = uri::file_name(&uri);
        self.by_uri.insert(uri, Document { name, version, text, analysis: None, earlier: None });
    }

    /// Applies the editor's changes, in order; a change without a range replaces the whole text.
    /// Returns `false` for a document that is not open.
    pub fn change(&mut self, uri: &Uri, version: i32, changes: Vec<TextDocumentContentChangeEvent>) -> bool {
        let Some(doc) = self.by_uri.get_mut(uri) else { return false };
        for change in changes {
            match change.range {
                None => doc.text = change.text,
                Some(range) => replace(&mut doc.text, range, &change.text),
            }
        }
        doc.version = version;
        doc.invalidate();
        true
    }

    /// Closes a document.
    pub fn close(&mut self, uri: &Uri) -> Option<Document> {
        self.by_uri.remove(uri)
    }

    /// The open document `uri`.
    pub fn get(&self, uri: &Uri) -> Option<&Document> {
        self.by_uri.get(uri)
    }

    /// The open document `uri`, to update its analysis.
    pub fn get_mut(&mut self, uri: &Uri) -> Option<&mut Document> {
        self.by_uri.get_mut(uri)
    }

    /// The text of the open document at `path` (as a loader names it), if there is one: what an
    /// `#include` of it must read instead of the disk.
    pub fn text_at(&self, path: &Path) -> Option<&str> {
        let path = uri::normalize(path);
        self.by_uri.values().find(|d| Path::new(&d.name) == path).map(|d| d.text.as_str())
    }

    /// The URI of the file the compiler names `name`: the open document's own when it is one
    /// (whatever the client's spelling), else [`uri::for_file_name`].
    pub fn uri_of(&self, name: &str) -> Option<Uri> {
        let path = uri::normalize(Path::new(name));
        let open = self.by_uri.iter().find(|(_, d)| d.name == name || Path::new(&d.name) == path);
        open.map(|(u, _)| u.clone()).or_else(|| uri::for_file_name(name))
    }

    /// The open documents whose last analysis read the file `name` through an `#include`, or
    /// found an `#include` it could not read (which may be `name`, now open): they must be checked
    /// again when it changes.
    pub fn includers(&self, name: &str) -> Vec<Uri> {
        let path = uri::normalize(Path::new(name));
        let includes = |a: &Analysis| {
            a.reads(&path) || a.checked.diagnostics.iter().any(|d| d.code == Code::IncludeNotFound)
        };
        self.by_uri
            .iter()
            .filter(|(_, d)| d.name != name && d.analysis.as_ref().is_some_and(includes))
            .map(|(u, _)| u.clone())
            .collect()
    }
}

/// Replaces the text of `range` (protocol positions, clamped to the text) with `new`.
fn replace(text: &mut String, range: Range, new: &str) {
    let mut map = SourceMap::new();
    let file = map.add_file("", text.as_str(), None);
    let file = map.file(file);
    let end_of_text = text.len();
    let start = position::offset(file, range.start).unwrap_or(end_of_text);
    let end = position::offset(file, range.end).unwrap_or(end_of_text).max(start);
    text.replace_range(start..end, new);
}

#[cfg(test)]
mod tests {
    use std::str::FromStr;

    use lsp_types::Position;

    use super::*;

    #[test]
    fn ranged_changes_apply_in_order_and_full_ones_replace() {
        let uri = Uri::from_str("file:///t/a.sl").unwrap();
        let mut docs = Documents::default();
        docs.open(uri.clone(), 1, "float é = 1;\n".into());
        let at = |line, character| Position { line, character };
        let edit = |start, end, text: &str| TextDocumentContentChangeEvent {
            range: Some(Range { start, end }),
            range_length: None,
            text: text.into(),
        };
        // `é` is one UTF-16 unit: column 7 is just after it.
        assert!(docs.change(&uri, 2, vec![edit(at(0, 6), at(0, 7), "x"), edit(at(0, 10), at(0, 11), "2")]));
        assert_eq!(docs.get(&uri).unwrap().text, "float x = 2;\n");
        // Past the end: appended.
        assert!(docs.change(&uri, 3, vec![edit(at(9, 0), at(9, 0), "// end")]));
        assert_eq!(docs.get(&uri).unwrap().text, "float x = 2;\n// end");
        let full = TextDocumentContentChangeEvent { range: None, range_length: None, text: "new".into() };
        assert!(docs.change(&uri, 4, vec![full]));
        assert_eq!((docs.get(&uri).unwrap().text.as_str(), docs.get(&uri).unwrap().version), ("new", 4));
        assert!(!docs.change(&Uri::from_str("file:///t/other.sl").unwrap(), 1, Vec::new()));
    }

    #[test]
    fn an_open_document_is_found_by_any_spelling_of_its_path() {
        let mut docs = Documents::default();
        docs.open(Uri::from_str("file:///t/inc.h").unwrap(), 1, "// unsaved".into());
        assert_eq!(docs.text_at(Path::new("/t/sub/../inc.h")), Some("// unsaved"));
        assert_eq!(docs.text_at(Path::new("/t/other.h")), None);
    }
}
