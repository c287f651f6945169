//! `patina lsp`: a Language Server Protocol server over stdio.
//!
//! Every answer comes from the compiler's own front end, run on the editor's text as `patina check`
//! runs it on a file (`analysis.rs`); this module reads messages, keeps the session and answers.
//! A reader thread frames messages (`transport.rs`) into a channel; the main loop handles every
//! message already waiting before it checks the documents that changed, so a burst of edits is
//! checked once. Bad input gets an error answer and the session goes on.

mod analysis;
mod completion;
mod definition;
mod diagnostics;
mod documents;
mod functions;
mod hover;
mod inlay_hints;
mod loader;
mod position;
mod scope;
mod semantic_tokens;
mod session;
mod symbols;
mod transport;
mod uri;
mod view;

use std::io::{self, BufRead, Write};
use std::panic::{self, AssertUnwindSafe};
use std::path::PathBuf;
use std::sync::mpsc;

use lsp_server::{ErrorCode, Message, Notification, Request, Response};
use lsp_types::notification::{
    DidChangeTextDocument, DidChangeWatchedFiles, DidCloseTextDocument, DidOpenTextDocument, Initialized,
    Notification as _, PublishDiagnostics,
};
use lsp_types::request::{
    Completion, GotoDefinition, HoverRequest, InlayHintRequest, RegisterCapability, Request as _,
    SemanticTokensFullRequest,
};
use lsp_types::{
    CompletionOptions, HoverProviderCapability, InitializeParams, InitializeResult, OneOf,
    SemanticTokensFullOptions, SemanticTokensOptions, SemanticTokensResult, SemanticTokensServerCapabilities,
    ServerCapabilities, ServerInfo, TextDocumentSyncCapability, TextDocumentSyncKind,
};
use patina_compiler::syntax::preprocess::FsLoader;

use session::Session;
use transport::Incoming;

/// Where the session is in the protocol's life cycle.
#[derive(Copy, Clone, PartialEq, Eq)]
enum State {
    /// Waiting for `initialize`.
    Starting,
    /// Answering.
    Running,
    /// `shutdown` answered: only `exit` is expected.
    ShutDown,
}

/// Serves one session: reads messages from `input` until `exit` (or the end of the stream) and
/// writes answers to `output`. Returns whether the session ended as the protocol asks (`exit`
/// after `shutdown`), which decides the exit status.
pub fn serve(
    input: impl BufRead + Send + 'static,
    mut output: impl Write,
    loader: FsLoader,
) -> io::Result<bool> {
    let (sender, messages) = mpsc::channel();
    // The reader blocks on input; it stops at the end of the stream or when the loop is gone.
    std::thread::spawn(move || {
        let mut input = input;
        while let Ok(Some(incoming)) = transport::read(&mut input) {
            if sender.send(incoming).is_err() {
                break;
            }
        }
    });
    let mut session = Session::new(loader);
    let mut state = State::Starting;
    while let Ok(first) = messages.recv() {
        let mut next = Some(first);
        while let Some(incoming) = next {
            match incoming {
                Incoming::Message(Message::Request(request)) => {
                    let response = answer(&mut session, &mut state, request);
                    transport::write(&mut output, response.into())?;
                }
                Incoming::Message(Message::Notification(n)) if n.method == "exit" => {
                    return Ok(state == State::ShutDown);
                }
                Incoming::Message(Message::Notification(n))
                    if n.method == Initialized::METHOD && session.client_watches_files =>
                {
                    transport::write(&mut output, watch_includes().into())?;
                }
                Incoming::Message(Message::Notification(n)) if state == State::Running => {
                    // A notification has no answer to carry an error: a bug here loses the one
                    // notification, not the session.
                    let _ = panic::catch_unwind(AssertUnwindSafe(|| notify(&mut session, n)));
                }
                // Before `initialize`, after `shutdown`, and answers to requests never made: ignored.
                Incoming::Message(_) => {}
                Incoming::Malformed { id: Some(id), code, message } => {
                    transport::write(&mut output, Response::new_err(id, code as i32, message).into())?;
                }
                Incoming::Malformed { id: None, code, message } => {
                    transport::write_error_without_id(&mut output, code, &message)?;
                }
            }
            next = messages.try_recv().ok();
        }
        let owed = panic::catch_unwind(AssertUnwindSafe(|| session.publish())).unwrap_or_default();
        for params in owed {
            let notification = Notification::new(PublishDiagnostics::METHOD.to_string(), params);
            transport::write(&mut output, notification.into())?;
        }
    }
    Ok(false)
}

/// The capabilities this server has.
fn capabilities() -> ServerCapabilities {
    ServerCapabilities {
        text_document_sync: Some(TextDocumentSyncCapability::Kind(TextDocumentSyncKind::FULL)),
        hover_provider: Some(HoverProviderCapability::Simple(true)),
        definition_provider: Some(OneOf::Left(true)),
        completion_provider: Some(CompletionOptions::default()),
        inlay_hint_provider: Some(OneOf::Left(true)),
        semantic_tokens_provider: Some(SemanticTokensServerCapabilities::SemanticTokensOptions(
            SemanticTokensOptions {
                legend: semantic_tokens::legend(),
                full: Some(SemanticTokensFullOptions::Bool(true)),
                ..SemanticTokensOptions::default()
            },
        )),
        ..ServerCapabilities::default()
    }
}

/// The answer to a request.
fn answer(session: &mut Session, state: &mut State, request: Request) -> Response {
    let Request { id, method, params } = request;
    match (*state, method.as_str()) {
        (State::Starting, "initialize") => {
            let params: InitializeParams = match serde_json::from_value(params) {
                Ok(params) => params,
                Err(e) => return Response::new_err(id, ErrorCode::InvalidParams as i32, e.to_string()),
            };
            session.add_include_dirs(include_dirs(&params));
            let watched =
                params.capabilities.workspace.as_ref().and_then(|w| w.did_change_watched_files.as_ref());
            session.client_watches_files = watched.and_then(|w| w.dynamic_registration) == Some(true);
            *state = State::Running;
            let result = InitializeResult {
                capabilities: capabilities(),
                server_info: Some(ServerInfo {
                    name: "patina".to_string(),
                    version: Some(env!("CARGO_PKG_VERSION").to_string()),
                }),
            };
            Response::new_ok(id, result)
        }
        (State::Starting, _) => Response::new_err(
            id,
            ErrorCode::ServerNotInitialized as i32,
            "`initialize` comes first".to_string(),
        ),
        (State::ShutDown, _) => {
            Response::new_err(id, ErrorCode::InvalidRequest as i32, "the server is shut down".to_string())
        }
        (State::Running, "initialize") => {
            Response::new_err(id, ErrorCode::InvalidRequest as i32, "already initialized".to_string())
        }
        (State::Running, "shutdown") => {
            *state = State::ShutDown;
            Response::new_ok(id, ())
        }
        (State::Running, HoverRequest::METHOD) => handle::<HoverRequest>(id, params, |p| {
            let at = p.text_document_position_params;
            session.with(&at.text_document.uri, |view, _| view.hover(at.position)).flatten()
        }),
        (State::Running, GotoDefinition::METHOD) => handle::<GotoDefinition>(id, params, |p| {
            let at = p.text_document_position_params;
            let uri = &at.text_document.uri;
            session.with(uri, |view, uri_of| view.definition(at.position, uri, uri_of)).flatten()
        }),
        (State::Running, Completion::METHOD) => handle::<Completion>(id, params, |p| {
            let at = p.text_document_position;
            session
                .with(&at.text_document.uri, |view, _| completion::complete(view.now(), at.position))
                .flatten()
        }),
        (State::Running, InlayHintRequest::METHOD) => handle::<InlayHintRequest>(id, params, |p| {
            session.with(&p.text_document.uri, |view, _| view.hints(p.range))
        }),
        (State::Running, SemanticTokensFullRequest::METHOD) => {
            handle::<SemanticTokensFullRequest>(id, params, |p| {
                session.with(&p.text_document.uri, |view, _| SemanticTokensResult::Tokens(view.tokens()))
            })
        }
        (State::Running, _) => {
            Response::new_err(id, ErrorCode::MethodNotFound as i32, format!("no method `{method}`"))
        }
    }
}

/// Answers a request of kind `R`: its parameters read (or an `InvalidParams` error), then `f`,
/// with a panic in `f` answered as an internal error rather than ending the session.
fn handle<R: lsp_types::request::Request>(
    id: lsp_server::RequestId,
    params: serde_json::Value,
    f: impl FnOnce(R::Params) -> R::Result,
) -> Response {
    let params: R::Params = match serde_json::from_value(params) {
        Ok(params) => params,
        Err(e) => {
            return Response::new_err(id, ErrorCode::InvalidParams as i32, format!("{}: {e}", R::METHOD));
        }
    };
    match panic::catch_unwind(AssertUnwindSafe(|| f(params))) {
        Ok(result) => Response::new_ok(id, result),
        Err(_) => Response::new_err(id, ErrorCode::InternalError as i32, format!("{} failed", R::METHOD)),
    }
}

/// Handles a notification; those of no interest (and malformed ones, which cannot be answered)
/// are ignored.
fn notify(session: &mut Session, notification: Notification) {
    let Notification { method, params } = notification;
    match method.as_str() {
        DidOpenTextDocument::METHOD => {
            if let Ok(p) = serde_json::from_value::<lsp_types::DidOpenTextDocumentParams>(params) {
                session.open(p.text_document.uri, p.text_document.version, p.text_document.text);
            }
        }
        DidChangeTextDocument::METHOD => {
            if let Ok(p) = serde_json::from_value::<lsp_types::DidChangeTextDocumentParams>(params) {
                session.change(&p.text_document.uri, p.text_document.version, p.content_changes);
            }
        }
        DidCloseTextDocument::METHOD => {
            if let Ok(p) = serde_json::from_value::<lsp_types::DidCloseTextDocumentParams>(params) {
                session.close(&p.text_document.uri);
            }
        }
        DidChangeWatchedFiles::METHOD => {
            if let Ok(p) = serde_json::from_value::<lsp_types::DidChangeWatchedFilesParams>(params) {
                p.changes.iter().for_each(|change| session.changed_on_disk(&change.uri));
            }
        }
        _ => {}
    }
}

/// Asks the client to report changes to the shader files on disk, which includes may read (its
/// answer needs no reading: a client that refuses simply sends nothing).
fn watch_includes() -> Request {
    let options = lsp_types::DidChangeWatchedFilesRegistrationOptions {
        watchers: ["**/*.sl", "**/*.h"]
            .into_iter()
            .map(|glob| lsp_types::FileSystemWatcher { glob_pattern: glob.to_string().into(), kind: None })
            .collect(),
    };
    let registration = lsp_types::Registration {
        id: "patina-includes".to_string(),
        method: DidChangeWatchedFiles::METHOD.to_string(),
        register_options: serde_json::to_value(options).ok(),
    };
    let params = lsp_types::RegistrationParams { registrations: vec![registration] };
    Request::new("patina-watch".to_string().into(), RegisterCapability::METHOD.to_string(), params)
}

/// The include directories the client names in its initialization options
/// (`{"includeDirs": ["include", "/abs/dir"]}`), relative ones from the workspace's root.
fn include_dirs(params: &InitializeParams) -> Vec<PathBuf> {
    let root = params
        .workspace_folders
        .as_ref()
        .and_then(|folders| folders.first())
        .and_then(|folder| uri::to_path(&folder.uri));
    #[allow(deprecated)] // `rootUri`: older clients send only this.
    let root = root.or_else(|| params.root_uri.as_ref().and_then(uri::to_path));
    let Some(dirs) = params.initialization_options.as_ref().and_then(|o| o.get("includeDirs")) else {
        return Vec::new();
    };
    let dirs = dirs.as_array().map(Vec::as_slice).unwrap_or_default();
    dirs.iter()
        .filter_map(|d| d.as_str())
        .map(|d| match &root {
            Some(root) => root.join(d),
            None => PathBuf::from(d),
        })
        .collect()
}
