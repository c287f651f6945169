//! The session's state: the open documents, checked lazily, and which of them owe the editor
//! their diagnostics.
//!
//! A change marks the document and the open documents that include it as stale; nothing else is
//! checked again. A stale document is checked when a request needs it or when the messages
//! waiting have all been read ([`Session::publish`]), so a burst of keystrokes costs one check.

use std::collections::HashSet;

use lsp_types::{PublishDiagnosticsParams, TextDocumentContentChangeEvent, Uri};
use patina_compiler::syntax::preprocess::FsLoader;

use super::analysis::Analysis;
use super::diagnostics;
use super::documents::Documents;
use super::loader::EditorLoader;
use super::view::View;

/// What the server holds between messages.
pub struct Session {
    documents: Documents,
    /// The command line's loader: the include directories.
    loader: FsLoader,
    /// The documents whose current diagnostics the editor has not been sent.
    unpublished: HashSet<Uri>,
    /// The documents just closed, whose diagnostics must be cleared.
    closed: Vec<Uri>,
    /// Whether the client can watch files for the server (`workspace/didChangeWatchedFiles`
    /// registered dynamically), so that includes changed outside the editor are seen.
    pub client_watches_files: bool,
}

impl Session {
    /// A session that searches `loader`'s include directories.
    pub fn new(loader: FsLoader) -> Session {
        Session {
            documents: Documents::default(),
            loader,
            unpublished: HashSet::new(),
            closed: Vec::new(),
            client_watches_files: false,
        }
    }

    /// Adds include directories (from the client's initialization options).
    pub fn add_include_dirs(&mut self, dirs: impl IntoIterator<Item = std::path::PathBuf>) {
        self.loader.include_dirs.extend(dirs);
    }

    /// A document was opened: it, and the documents that include it (which must now read the
    /// buffer rather than the disk), are stale.
    pub fn open(&mut self, uri: Uri, version: i32, text: String) {
        self.documents.open(uri.clone(), version, text);
        self.touched(&uri);
    }

    /// A document changed.
    pub fn change(&mut self, uri: &Uri, version: i32, changes: Vec<TextDocumentContentChangeEvent>) {
        if self.documents.change(uri, version, changes) {
            self.touched(uri);
        }
    }

    /// A document was closed: its includers read the disk again, and its diagnostics are cleared.
    pub fn close(&mut self, uri: &Uri) {
        let name = self.documents.get(uri).map(|d| d.name.clone());
        if let Some(name) = name {
            self.stale_includers(&name);
            self.documents.close(uri);
            self.unpublished.remove(uri);
            self.closed.push(uri.clone());
        }
    }

    /// A file changed on disk (the client watches them for us): the documents that include it
    /// are stale, unless it is open, whose buffer they read instead.
    pub fn changed_on_disk(&mut self, uri: &Uri) {
        let name = super::uri::file_name(uri);
        if self.documents.get(uri).is_none() {
            self.stale_includers(&name);
        }
    }

    /// Marks `uri` and the documents including it stale.
    fn touched(&mut self, uri: &Uri) {
        self.unpublished.insert(uri.clone());
        if let Some(name) = self.documents.get(uri).map(|d| d.name.clone()) {
            self.stale_includers(&name);
        }
    }

    fn stale_includers(&mut self, name: &str) {
        for includer in self.documents.includers(name) {
            if let Some(doc) = self.documents.get_mut(&includer) {
                doc.invalidate();
            }
            self.unpublished.insert(includer);
        }
    }

    /// Runs `f` on the view of `uri` to answer from (its current text checked first if it is
    /// stale; see `view.rs`) and a function naming the compiler's files as URIs (an open
    /// document by its own URI); `None` for a document that is not open.
    pub fn with<R>(
        &mut self,
        uri: &Uri,
        f: impl FnOnce(&View<'_>, &dyn Fn(&str) -> Option<Uri>) -> R,
    ) -> Option<R> {
        let doc = self.documents.get(uri)?;
        if doc.analysis.is_none() {
            let loader = EditorLoader { fs: &self.loader, documents: &self.documents };
            let analysis = Analysis::run(&doc.name, &doc.text, &loader);
            self.documents.get_mut(uri)?.analysed(analysis);
        }
        let documents = &self.documents;
        let doc = documents.get(uri)?;
        let view = View::new(doc.analysis.as_ref()?, doc.earlier.as_ref());
        Some(f(&view, &|name| documents.uri_of(name)))
    }

    /// The diagnostics owed to the editor, checking the stale documents they belong to.
    pub fn publish(&mut self) -> Vec<PublishDiagnosticsParams> {
        let mut out: Vec<PublishDiagnosticsParams> = std::mem::take(&mut self.closed)
            .into_iter()
            .map(|uri| PublishDiagnosticsParams { uri, diagnostics: Vec::new(), version: None })
            .collect();
        let mut owed: Vec<Uri> = self.unpublished.drain().collect();
        owed.sort();
        for uri in owed {
            let version = self.documents.get(&uri).map(|d| d.version);
            if let Some(diagnostics) = self.with(&uri, |view, uri_of| diagnostics::of(view.now(), uri_of)) {
                out.push(PublishDiagnosticsParams { uri, diagnostics, version });
            }
        }
        out
    }
}
