//! The wire: `Content-Length`-framed JSON-RPC messages over a byte stream.
//!
//! `lsp-server`'s own stdio transport ends the session at the first malformed message (its reader
//! thread returns the error) and sizes its buffer from the header before reading, so a garbage
//! `Content-Length` can exhaust memory. This reader answers a bad message with an error and reads
//! on; `lsp-server`'s message types and writer are used as they are.

use std::io::{self, BufRead, Read, Write};

use lsp_server::{ErrorCode, Message, Notification, Request, RequestId, Response};

/// The largest message body read. A document of 5,000 lines is about 200 KB; anything near this
/// is a mistake, and is skipped rather than held in memory.
const MAX_BODY: usize = 64 << 20;

/// The longest header line kept; the rest of a longer one is skipped.
const MAX_HEADER_LINE: u64 = 4096;

/// What came in: a message, or one that could not be understood.
#[derive(Debug)]
pub enum Incoming {
    /// A well-formed JSON-RPC message.
    Message(Message),
    /// A message that was not JSON-RPC: the error to answer it with.
    Malformed {
        /// The request's id when it could be read, else `null` is answered (JSON-RPC 2.0, §5).
        id: Option<RequestId>,
        /// `ParseError` for bytes that are not JSON, `InvalidRequest` for JSON that is not a message.
        code: ErrorCode,
        /// What was wrong.
        message: String,
    },
}

/// Reads the next message; `Ok(None)` at the end of the stream (or when it ends inside one).
pub fn read(input: &mut impl BufRead) -> io::Result<Option<Incoming>> {
    let mut length = None;
    let mut saw_header = false;
    loop {
        let mut line = Vec::new();
        let n = input.by_ref().take(MAX_HEADER_LINE).read_until(b'\n', &mut line)?;
        if n == 0 {
            return Ok(None);
        }
        if !line.ends_with(b"\n") {
            // Longer than any real header: skip to its end and go on.
            let mut rest = Vec::new();
            input.read_until(b'\n', &mut rest)?;
            saw_header = true;
            continue;
        }
        let line = String::from_utf8_lossy(&line);
        let line = line.trim_end_matches(['\r', '\n']);
        if line.is_empty() {
            // Stray blank lines between messages are not headers.
            if saw_header {
                break;
            }
            continue;
        }
        saw_header = true;
        if let Some((name, value)) = line.split_once(':')
            && name.trim().eq_ignore_ascii_case("content-length")
        {
            length = value.trim().parse::<usize>().ok();
        }
    }
    let Some(length) = length else {
        return Ok(Some(malformed(None, ErrorCode::ParseError, "no valid Content-Length header")));
    };
    if length > MAX_BODY {
        let skipped = io::copy(&mut input.by_ref().take(length as u64), &mut io::sink())?;
        if skipped < length as u64 {
            return Ok(None);
        }
        let message = format!("a message of {length} bytes is over the limit of {MAX_BODY}");
        return Ok(Some(malformed(None, ErrorCode::InvalidRequest, &message)));
    }
    let mut body = vec![0; length];
    match input.read_exact(&mut body) {
        Ok(()) => {}
        Err(e) if e.kind() == io::ErrorKind::UnexpectedEof => return Ok(None),
        Err(e) => return Err(e),
    }
    Ok(Some(parse(&body)))
}

/// Understands one message body.
fn parse(body: &[u8]) -> Incoming {
    let value: serde_json::Value = match serde_json::from_slice(body) {
        Ok(value) => value,
        Err(e) => return malformed(None, ErrorCode::ParseError, &format!("the body is not JSON: {e}")),
    };
    // The id, if there is a usable one, so that even a malformed request gets its answer.
    let id = match value.get("id") {
        Some(serde_json::Value::Number(n)) => {
            n.as_i64().and_then(|n| i32::try_from(n).ok()).map(RequestId::from)
        }
        Some(serde_json::Value::String(s)) => Some(RequestId::from(s.clone())),
        _ => None,
    };
    // `Message` is untagged and would take any object with an id for a response: each kind is
    // read as itself, so that a request with a bad method is answered, not dropped as an answer.
    let has = |key: &str| value.get(key).is_some();
    let parsed = match (has("method"), has("id")) {
        (true, true) => serde_json::from_value::<Request>(value).map(Message::Request),
        (true, false) => serde_json::from_value::<Notification>(value).map(Message::Notification),
        (false, _) if has("result") || has("error") => {
            serde_json::from_value::<Response>(value).map(Message::Response)
        }
        (false, _) => {
            return malformed(
                id,
                ErrorCode::InvalidRequest,
                "neither a request, a notification nor a response",
            );
        }
    };
    match parsed {
        Ok(message) => Incoming::Message(message),
        Err(e) => malformed(id, ErrorCode::InvalidRequest, &format!("not a JSON-RPC message: {e}")),
    }
}

fn malformed(id: Option<RequestId>, code: ErrorCode, message: &str) -> Incoming {
    Incoming::Malformed { id, code, message: message.to_string() }
}

/// Writes one message.
pub fn write(output: &mut impl Write, message: Message) -> io::Result<()> {
    message.write(output)
}

/// Writes an error response to a message whose id could not be read (`"id": null`), which
/// `lsp-server`'s `Response` cannot express.
pub fn write_error_without_id(output: &mut impl Write, code: ErrorCode, message: &str) -> io::Result<()> {
    let body = serde_json::json!({
        "jsonrpc": "2.0",
        "id": null,
        "error": { "code": code as i32, "message": message },
    })
    .to_string();
    write!(output, "Content-Length: {}\r\n\r\n{body}", body.len())?;
    output.flush()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame(body: &str) -> String {
        format!("Content-Length: {}\r\n\r\n{body}", body.len())
    }

    fn read_all(stream: &str) -> Vec<Incoming> {
        let mut input = io::Cursor::new(stream.as_bytes().to_vec());
        std::iter::from_fn(|| read(&mut input).unwrap()).collect()
    }

    #[test]
    fn a_bad_message_is_answered_and_the_next_one_read() {
        let good = r#"{"jsonrpc":"2.0","id":7,"method":"shutdown"}"#;
        let stream = [frame("{not json"), frame(r#"{"id":3,"method":5}"#), frame(good)].concat();
        let got = read_all(&stream);
        assert_eq!(got.len(), 3);
        assert!(matches!(&got[0], Incoming::Malformed { id: None, code: ErrorCode::ParseError, .. }));
        assert!(
            matches!(&got[1], Incoming::Malformed { id: Some(id), code: ErrorCode::InvalidRequest, .. } if *id == 3.into())
        );
        assert!(matches!(&got[2], Incoming::Message(Message::Request(r)) if r.method == "shutdown"));
    }

    #[test]
    fn a_huge_length_is_refused_without_allocating_it() {
        let stream = "Content-Length: 99999999999999\r\n\r\n{}";
        assert!(read_all(stream).is_empty()); // the stream ends before the body does
        let stream = format!("Content-Length: x\r\n\r\n{}", frame("{}"));
        let got = read_all(&stream);
        assert!(matches!(&got[0], Incoming::Malformed { code: ErrorCode::ParseError, .. }));
    }

    #[test]
    fn the_end_of_the_stream_inside_a_message_ends_reading() {
        assert!(read_all("Content-Length: 10\r\n\r\n{}").is_empty());
        assert!(read_all("").is_empty());
    }
}
