//! Documents' URIs against the file names the compiler's loaders use.
//!
//! The loaders name a file by its path as a string (`dir/inc.h`) and the standard library's files
//! `<stdlib>/NAME.sl`; the protocol names them `file://` URIs. A document that is not a file (an
//! unsaved `untitled:` buffer) or whose path is not UTF-8 is named by its URI instead: it still
//! checks, and its `#include`s search the include directories and the standard library.

use std::path::{Component, Path, PathBuf};
use std::str::FromStr;

use lsp_types::Uri;

/// The local path of a `file:` URI, if it is one whose path is UTF-8 once decoded.
pub fn to_path(uri: &Uri) -> Option<PathBuf> {
    if !uri.scheme().is_some_and(|s| s.as_str().eq_ignore_ascii_case("file")) {
        return None;
    }
    let decoded = uri.path().as_estr().decode().into_string().ok()?;
    let decoded: &str = &decoded;
    // `file:///C:/x` on Windows: the drive letter follows the slash.
    #[cfg(windows)]
    let decoded = match decoded.strip_prefix('/') {
        Some(rest) if rest.as_bytes().get(1) == Some(&b':') => rest,
        _ => decoded,
    };
    Some(normalize(Path::new(decoded)))
}

/// The name the compiler sees a document under: its path, or else its URI.
pub fn file_name(uri: &Uri) -> String {
    match to_path(uri) {
        Some(path) => path.to_string_lossy().into_owned(),
        None => uri.as_str().to_string(),
    }
}

/// The `file:` URI of an absolute path.
pub fn from_path(path: &Path) -> Option<Uri> {
    let text = path.to_str()?;
    let mut uri = String::from("file://");
    if !text.starts_with('/') {
        uri.push('/');
    }
    for byte in text.bytes() {
        match byte {
            b'A'..=b'Z' | b'a'..=b'z' | b'0'..=b'9' | b'-' | b'.' | b'_' | b'~' | b'/' => {
                uri.push(byte as char)
            }
            b'\\' if cfg!(windows) => uri.push('/'),
            _ => uri.push_str(&format!("%{byte:02X}")),
        }
    }
    Uri::from_str(&uri).ok()
}

/// The URI of a file as the compiler names it (a path, `<stdlib>/NAME.sl`, or the URI of a
/// document that is not a file). The standard library's files are those of the compiler's
/// source tree; a relative path is taken from the server's working directory, as the command
/// line takes it.
pub fn for_file_name(name: &str) -> Option<Uri> {
    if let Some(path) = patina_compiler::stdlib::path(name) {
        return path.exists().then(|| from_path(&path)).flatten();
    }
    let path = Path::new(name);
    if path.is_absolute() {
        return from_path(&normalize(path));
    }
    if let Ok(uri) = Uri::from_str(name)
        && uri.scheme().is_some()
    {
        return Some(uri);
    }
    from_path(&normalize(&std::env::current_dir().ok()?.join(path)))
}

/// `path` without `.` and with each `name/..` removed, as text (no file system access: the file
/// may exist only in the editor). `#include "../x.h"` and the document `x.h` then compare equal.
pub fn normalize(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for part in path.components() {
        match part {
            Component::CurDir => {}
            Component::ParentDir if matches!(out.components().next_back(), Some(Component::Normal(_))) => {
                out.pop();
            }
            other => out.push(other),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn uri(text: &str) -> Uri {
        Uri::from_str(text).unwrap()
    }

    #[test]
    fn file_uris_round_trip_through_paths() {
        let path = Path::new("/tmp/a dir/shäder.sl");
        let u = from_path(path).unwrap();
        assert_eq!(u.as_str(), "file:///tmp/a%20dir/sh%C3%A4der.sl");
        assert_eq!(to_path(&u).as_deref(), Some(path));
    }

    #[test]
    fn other_uris_are_named_by_themselves() {
        assert_eq!(to_path(&uri("untitled:Untitled-1")), None);
        assert_eq!(file_name(&uri("untitled:Untitled-1")), "untitled:Untitled-1");
        // A path whose bytes are not UTF-8.
        let bad = uri("file:///tmp/%FF.sl");
        assert_eq!(to_path(&bad), None);
        assert_eq!(file_name(&bad), "file:///tmp/%FF.sl");
    }

    #[test]
    fn paths_are_normalized_as_text() {
        assert_eq!(normalize(Path::new("/a/./b/../c.sl")), Path::new("/a/c.sl"));
        assert_eq!(normalize(Path::new("../x.h")), Path::new("../x.h"));
        assert_eq!(to_path(&uri("file:///a/b/../c.sl")).as_deref(), Some(Path::new("/a/c.sl")));
    }
}
