//! Hot reload: [`Watcher`] recompiles a shader when it or anything it includes changes on disk,
//! and [`FileWatcher`], the primitive under it, reports changes to a set of files (what
//! `patina watch` uses for a scene and all its shaders).
//!
//! Both watch the *directories* of the files, not the files: most editors save by writing a new
//! file and renaming it over the old one, and a watch on the old file would end with it (or, on
//! some systems, follow it to wherever it was moved). Events are debounced, because one save is
//! several events (truncate, write, write, close, or create, rename, attributes).

use std::collections::{BTreeMap, BTreeSet};
use std::fmt;
use std::path::{Path, PathBuf};
use std::sync::mpsc::{self, Receiver, RecvTimeoutError, TryRecvError};
use std::time::{Duration, Instant};

use notify::event::{AccessKind, AccessMode};
use notify::{EventKind, RecursiveMode, Watcher as _};

use super::compiler::{CompileError, Compiled, Compiler};

/// A burst that never goes quiet (a file written continuously) is still reported this many
/// debounce periods after it began, so that a busy file cannot hold back reloading for ever.
const MAX_BURST_PERIODS: u32 = 10;

/// Why watching could not start or go on. Compile errors are not watch errors: they are
/// reported as [`Update::Failed`].
#[derive(Debug)]
#[non_exhaustive]
pub enum WatchError {
    /// The operating system's file watcher could not be started.
    Start {
        /// What the watcher reported.
        source: Box<dyn std::error::Error + Send + Sync>,
    },
    /// A directory could not be watched (for example, the system's limit on watches was reached).
    Watch {
        /// The directory.
        path: PathBuf,
        /// What the watcher reported.
        source: Box<dyn std::error::Error + Send + Sync>,
    },
    /// The operating system's watcher stopped delivering events.
    Stopped,
}

impl fmt::Display for WatchError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            WatchError::Start { source } => write!(f, "cannot watch files: {source}"),
            WatchError::Watch { path, source } => write!(f, "cannot watch `{}`: {source}", path.display()),
            WatchError::Stopped => f.write_str("the file watcher stopped"),
        }
    }
}

impl std::error::Error for WatchError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            WatchError::Start { source } | WatchError::Watch { source, .. } => Some(source.as_ref()),
            WatchError::Stopped => None,
        }
    }
}

/// A set of files watched for changes (writes, replacement by rename, deletion, creation), and
/// optionally every file directly inside some directories; [`wait`](FileWatcher::wait) reports
/// which changed, one debounced burst at a time.
///
/// ```
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// # let dir = std::env::temp_dir().join(format!("patina-doc-filewatcher-{}", std::process::id()));
/// # std::fs::create_dir_all(&dir)?;
/// let scene = dir.join("scene.toml");
/// std::fs::write(&scene, "")?;
/// let mut files = patina::FileWatcher::new()?;
/// files.set([scene.clone()], [])?;
/// std::fs::write(&scene, "# edited")?;
/// let changed = files.wait(std::time::Duration::from_secs(10))?;
/// assert_eq!(changed, Some(vec![scene]));
/// # Ok(())
/// # }
/// ```
pub struct FileWatcher {
    os: notify::RecommendedWatcher,
    events: Receiver<notify::Result<notify::Event>>,
    /// The watched files, by [`identity`], each with the path it was given as (what is reported).
    files: BTreeMap<PathBuf, PathBuf>,
    /// Directories (by identity) every file of which is watched.
    dirs: BTreeSet<PathBuf>,
    /// Directories (by identity) the operating system is watching for us.
    watching: BTreeSet<PathBuf>,
    /// Changes seen and not yet reported.
    pending: BTreeSet<PathBuf>,
    /// When the pending burst began and when its last event came.
    burst: Option<(Instant, Instant)>,
    debounce: Duration,
}

impl fmt::Debug for FileWatcher {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("FileWatcher")
            .field("files", &self.files.values().collect::<Vec<_>>())
            .field("dirs", &self.dirs)
            .field("pending", &self.pending)
            .finish_non_exhaustive()
    }
}

impl FileWatcher {
    /// How long a burst of events must have been quiet before it is reported, unless set with
    /// [`FileWatcher::debounce`]: long enough for an editor's several writes of one save, short
    /// enough not to be felt.
    pub const DEFAULT_DEBOUNCE: Duration = Duration::from_millis(100);

    /// A watcher of nothing yet; give it files with [`set`](FileWatcher::set).
    pub fn new() -> Result<FileWatcher, WatchError> {
        let (sender, events) = mpsc::channel();
        let os = notify::recommended_watcher(sender).map_err(|e| WatchError::Start { source: e.into() })?;
        Ok(FileWatcher {
            os,
            events,
            files: BTreeMap::new(),
            dirs: BTreeSet::new(),
            watching: BTreeSet::new(),
            pending: BTreeSet::new(),
            burst: None,
            debounce: FileWatcher::DEFAULT_DEBOUNCE,
        })
    }

    /// Reports a burst of events once it has been quiet for `quiet` ([`FileWatcher::DEFAULT_DEBOUNCE`] unless
    /// set).
    pub fn debounce(mut self, quiet: Duration) -> FileWatcher {
        self.debounce = quiet;
        self
    }

    /// Watches exactly `files`, and every file directly inside `dirs` (not in their
    /// subdirectories), in place of what was watched before. Files need not exist: one that is
    /// created later is reported. A directory that does not exist is not watched until a later
    /// `set` finds it (the operating system cannot watch what is not there); changes already
    /// seen and not yet reported are kept.
    pub fn set(
        &mut self,
        files: impl IntoIterator<Item = PathBuf>,
        dirs: impl IntoIterator<Item = PathBuf>,
    ) -> Result<(), WatchError> {
        self.files.clear();
        for given in files {
            // The first path given for a file is the one reported.
            self.files.entry(identity(&given)).or_insert(given);
        }
        self.dirs = dirs.into_iter().map(|d| identity(&d)).collect();
        let needed: BTreeSet<PathBuf> = self
            .files
            .keys()
            .filter_map(|f| f.parent().map(Path::to_path_buf))
            .chain(self.dirs.clone())
            .collect();
        for dir in self.watching.difference(&needed).cloned().collect::<Vec<_>>() {
            // Failing to drop a watch (its directory is gone) only costs events we ignore.
            let _ = self.os.unwatch(&dir);
            self.watching.remove(&dir);
        }
        for dir in needed.difference(&self.watching).cloned().collect::<Vec<_>>() {
            match self.os.watch(&dir, RecursiveMode::NonRecursive) {
                Ok(()) => {
                    self.watching.insert(dir);
                }
                Err(e) if is_not_found(&e) => {}
                Err(e) => return Err(WatchError::Watch { path: dir, source: e.into() }),
            }
        }
        Ok(())
    }

    /// The watched files, as they were given to [`set`](FileWatcher::set).
    pub fn files(&self) -> impl Iterator<Item = &Path> {
        self.files.values().map(PathBuf::as_path)
    }

    /// Waits up to `timeout` for changes and returns the files that changed, sorted, once their
    /// burst of events has been quiet for the debounce time: watched files as they were given to
    /// [`set`](FileWatcher::set), other files of watched directories as the system names them.
    /// `None` when the time ran out first (a burst still settling is kept for the next call), so
    /// `wait(Duration::ZERO)` polls without blocking. A lost event (the system's queue overflowed)
    /// counts as a change of every watched file, so that nothing is missed.
    pub fn wait(&mut self, timeout: Duration) -> Result<Option<Vec<PathBuf>>, WatchError> {
        // `None`: no deadline (a timeout too long to add to the clock).
        let deadline = Instant::now().checked_add(timeout);
        loop {
            loop {
                match self.events.try_recv() {
                    Ok(event) => self.note(event),
                    Err(TryRecvError::Empty) => break,
                    Err(TryRecvError::Disconnected) => return Err(WatchError::Stopped),
                }
            }
            let now = Instant::now();
            let due = self.due();
            if due.is_some_and(|due| now >= due) {
                self.burst = None;
                return Ok(Some(std::mem::take(&mut self.pending).into_iter().collect()));
            }
            if deadline.is_some_and(|deadline| now >= deadline) {
                return Ok(None);
            }
            let wake = match (due, deadline) {
                (Some(a), Some(b)) => Some(a.min(b)),
                (a, b) => a.or(b),
            };
            let event = match wake {
                Some(wake) => match self.events.recv_timeout(wake.saturating_duration_since(now)) {
                    Ok(event) => event,
                    Err(RecvTimeoutError::Timeout) => continue,
                    Err(RecvTimeoutError::Disconnected) => return Err(WatchError::Stopped),
                },
                None => self.events.recv().map_err(|_| WatchError::Stopped)?,
            };
            self.note(event);
        }
    }

    /// When the pending burst is to be reported, if there is one.
    fn due(&self) -> Option<Instant> {
        let (first, last) = self.burst?;
        let quiet = last.checked_add(self.debounce);
        let longest = self.debounce.checked_mul(MAX_BURST_PERIODS).and_then(|d| first.checked_add(d));
        match (quiet, longest) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        }
    }

    /// Records what an event changed among the watched files; any relevant event, even one for
    /// a file already pending, extends the burst.
    fn note(&mut self, event: notify::Result<notify::Event>) {
        let relevant = match event {
            // An error in the stream, or a queue overflow, means events may have been lost.
            Err(_) => self.mark_all(),
            Ok(event) if event.need_rescan() => self.mark_all(),
            Ok(event) if !changes(&event.kind) => false,
            Ok(event) => {
                let mut relevant = false;
                for path in &event.paths {
                    let id = identity(path);
                    if matches!(event.kind, EventKind::Remove(_)) && self.watching.remove(&id) {
                        // A watched directory went away: its files are gone, and it must be
                        // watched again (by a later `set`) once it is back.
                        let gone: Vec<PathBuf> = self
                            .files
                            .iter()
                            .filter(|(file, _)| file.parent() == Some(id.as_path()))
                            .map(|(_, given)| given.clone())
                            .collect();
                        relevant |= !gone.is_empty();
                        self.pending.extend(gone);
                    }
                    if let Some(given) = self.files.get(&id) {
                        self.pending.insert(given.clone());
                        relevant = true;
                    } else if id.parent().is_some_and(|dir| self.dirs.contains(dir)) {
                        self.pending.insert(path.clone());
                        relevant = true;
                    }
                }
                relevant
            }
        };
        if relevant {
            let now = Instant::now();
            self.burst = Some((self.burst.map_or(now, |(first, _)| first), now));
        }
    }

    /// Counts every watched file as changed; whether there are any.
    fn mark_all(&mut self) -> bool {
        self.pending.extend(self.files.values().cloned());
        !self.files.is_empty()
    }
}

/// Whether an event of this kind can change a file's contents (opening and reading, which
/// compiling itself does, cannot).
fn changes(kind: &EventKind) -> bool {
    match kind {
        EventKind::Access(AccessKind::Close(AccessMode::Write)) => true,
        EventKind::Access(_) => false,
        _ => true,
    }
}

fn is_not_found(e: &notify::Error) -> bool {
    match &e.kind {
        notify::ErrorKind::PathNotFound => true,
        notify::ErrorKind::Io(io) => io.kind() == std::io::ErrorKind::NotFound,
        _ => false,
    }
}

/// One name per file, whatever path it was reached by: the canonical directory (symbolic links,
/// `..` and relative paths resolved, as the system reports events under it) and the file's name.
/// The file itself is not resolved, because it may not exist (deleted, or not yet created).
fn identity(path: &Path) -> PathBuf {
    let absolute = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
    match (absolute.parent(), absolute.file_name()) {
        (Some(dir), Some(name)) => std::fs::canonicalize(dir).map_or(absolute.clone(), |dir| dir.join(name)),
        _ => absolute,
    }
}

/// A shader compiled again whenever its file, or a file it includes, or a light or displacement
/// shader it binds, changes on disk.
///
/// An edit that breaks the shader is reported as [`Update::Failed`] with its diagnostics, and
/// the last program that compiled stays available from [`last_good`](Watcher::last_good): **the
/// previous pipeline keeps working** until an edit compiles again. Nothing a user does to the
/// files (a syntax error, a deleted file, a missing include) panics or stops the watcher.
///
/// ```no_run
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// use std::time::Duration;
/// use patina::{Compiler, Light, Update, Watcher};
///
/// let compiler = Compiler::new().light(Light::stdlib("shaders.sl", "pointlight"));
/// let mut shader = Watcher::new(compiler, "shaders/plastic.sl")?;
/// let mut pipeline = shader.current().ok().map(|c| c.wgsl.clone()); // make your pipeline here
/// loop {
///     // Once per frame: returns at once when nothing has changed.
///     match shader.poll()? {
///         Some(Update::Compiled(compiled)) => pipeline = Some(compiled.wgsl.clone()),
///         Some(Update::Failed(error)) => eprintln!("{error}"), // the old pipeline is kept
///         _ => {}
///     }
///     # let _ = &pipeline; std::thread::sleep(Duration::from_millis(16));
/// }
/// # }
/// ```
#[derive(Debug)]
pub struct Watcher {
    compiler: Compiler,
    path: PathBuf,
    files: FileWatcher,
    state: State,
}

/// The latest compile's outcome.
#[derive(Debug)]
enum State {
    Good(Compiled),
    Failed { error: CompileError, previous: Option<Compiled> },
}

/// What a change on disk led to, from [`Watcher::wait`]: the program compiled anew, or the
/// reason it did not.
#[derive(Debug)]
#[non_exhaustive]
pub enum Update<'a> {
    /// The shader compiled: make its pipeline anew.
    Compiled(&'a Compiled),
    /// The shader no longer compiles; [`Watcher::last_good`] still has the previous program.
    Failed(&'a CompileError),
}

impl Watcher {
    /// Compiles the shader at `path` with `compiler` and watches it. A shader that does not
    /// compile (or is not there yet) is not an error here: the watcher starts anyway, with the
    /// diagnostics in [`current`](Watcher::current), and reports the first edit that fixes it.
    /// The error is only that the files cannot be watched (or the shader's directory does not
    /// exist).
    pub fn new(compiler: Compiler, path: impl Into<PathBuf>) -> Result<Watcher, WatchError> {
        Watcher::with_files(compiler, path.into(), FileWatcher::new()?)
    }

    /// As [`new`](Watcher::new), reporting a burst of events once it has been quiet for `quiet`
    /// ([`FileWatcher::DEFAULT_DEBOUNCE`] otherwise).
    pub fn with_debounce(
        compiler: Compiler,
        path: impl Into<PathBuf>,
        quiet: Duration,
    ) -> Result<Watcher, WatchError> {
        Watcher::with_files(compiler, path.into(), FileWatcher::new()?.debounce(quiet))
    }

    fn with_files(compiler: Compiler, path: PathBuf, mut files: FileWatcher) -> Result<Watcher, WatchError> {
        // Nothing would ever be reported: the system cannot watch a directory that is not there.
        let dir = directory(&path);
        if !dir.is_dir() {
            let source = std::io::Error::new(std::io::ErrorKind::NotFound, "no such directory");
            return Err(WatchError::Watch { path: dir.to_path_buf(), source: source.into() });
        }
        // Watch before compiling, so that an edit made while it compiles is not missed.
        files.set([path.clone()], [])?;
        let state = match compiler.compile_file(&path) {
            Ok(compiled) => State::Good(compiled),
            Err(error) => State::Failed { error, previous: None },
        };
        let mut watcher = Watcher { compiler, path, files, state };
        watcher.rewatch()?;
        Ok(watcher)
    }

    /// The latest compile's result: the program, or why the latest edit does not compile.
    pub fn current(&self) -> Result<&Compiled, &CompileError> {
        match &self.state {
            State::Good(compiled) => Ok(compiled),
            State::Failed { error, .. } => Err(error),
        }
    }

    /// The newest program that compiled (the current one, or the one before a failed edit);
    /// `None` while the shader has never compiled.
    pub fn last_good(&self) -> Option<&Compiled> {
        match &self.state {
            State::Good(compiled) => Some(compiled),
            State::Failed { previous, .. } => previous.as_ref(),
        }
    }

    /// The files being watched: the shader's and, from its newest program, every file it was
    /// compiled from ([`Compiled::files`]).
    pub fn files(&self) -> impl Iterator<Item = &Path> {
        self.files.files()
    }

    /// Waits up to `timeout` for a change, compiles the shader again and reports the outcome;
    /// `None` when nothing changed in time. A failure with the same diagnostics as the one
    /// before is not reported again.
    pub fn wait(&mut self, timeout: Duration) -> Result<Option<Update<'_>>, WatchError> {
        let deadline = Instant::now().checked_add(timeout);
        loop {
            let left = deadline.map_or(Duration::MAX, |d| d.saturating_duration_since(Instant::now()));
            if self.files.wait(left)?.is_none() {
                return Ok(None);
            }
            let reported = self.recompile();
            self.rewatch()?;
            if reported {
                return Ok(Some(match &self.state {
                    State::Good(compiled) => Update::Compiled(compiled),
                    State::Failed { error, .. } => Update::Failed(error),
                }));
            }
            if deadline.is_some_and(|d| Instant::now() >= d) {
                return Ok(None);
            }
        }
    }

    /// As [`wait`](Watcher::wait) without waiting: for a render loop, once per frame.
    pub fn poll(&mut self) -> Result<Option<Update<'_>>, WatchError> {
        self.wait(Duration::ZERO)
    }

    /// Compiles the shader again; whether the outcome is news.
    fn recompile(&mut self) -> bool {
        let error = match self.compiler.compile_file(&self.path) {
            Ok(compiled) => {
                self.state = State::Good(compiled);
                return true;
            }
            Err(error) => error,
        };
        let news = match &self.state {
            State::Good(_) => true,
            State::Failed { error: before, .. } => error.to_string() != before.to_string(),
        };
        let previous = match std::mem::replace(&mut self.state, State::Failed { error, previous: None }) {
            State::Good(compiled) => Some(compiled),
            State::Failed { previous, .. } => previous,
        };
        if let State::Failed { previous: kept, .. } = &mut self.state {
            *kept = previous;
        }
        news
    }

    /// Watches the files of the newest program (while the shader fails, also every file in their
    /// directories: the fix may be in a file it has just begun to include, which no program has
    /// listed yet).
    fn rewatch(&mut self) -> Result<(), WatchError> {
        let mut files = vec![self.path.clone()];
        files.extend(self.last_good().into_iter().flat_map(|c| c.files.iter().cloned()));
        let dirs: Vec<PathBuf> = match self.state {
            State::Good(_) => Vec::new(),
            State::Failed { .. } => files.iter().map(|f| directory(f).to_path_buf()).collect(),
        };
        self.files.set(files, dirs)
    }
}

/// The directory a file is in (`.` for a bare file name).
fn directory(file: &Path) -> &Path {
    match file.parent() {
        Some(dir) if !dir.as_os_str().is_empty() => dir,
        _ => Path::new("."),
    }
}
