//! Positions: the protocol's (line, UTF-16 column) against the compiler's byte offsets.
//!
//! The compiler's spans are byte ranges into a [`SourceFile`], whose line table is reused here;
//! the protocol counts columns in UTF-16 code units (its default encoding, the only one every
//! client supports), so a character outside the Basic Multilingual Plane counts two.

use std::ops::Range;

use lsp_types::Position;
use patina_compiler::source::SourceFile;

/// The protocol position of byte `offset` of `file` (clamped to the file's end, and moved back to
/// the start of a character it falls inside).
pub fn position(file: &SourceFile, offset: usize) -> Position {
    let text = &*file.text;
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let line = file.line_index(offset);
    let start = file.line_range(line).map_or(0, |r| r.start);
    let character = text[start..offset].encode_utf16().count();
    Position { line: saturate(line), character: saturate(character) }
}

/// The protocol range of the byte range `range` of `file`.
pub fn range(file: &SourceFile, range: Range<usize>) -> lsp_types::Range {
    lsp_types::Range { start: position(file, range.start), end: position(file, range.end) }
}

/// The byte offset of a protocol position in `file`, or `None` for a line past the last. A column
/// past the end of its line means the end of the line (as the protocol says), and one inside a
/// character's two UTF-16 units means that character's start.
pub fn offset(file: &SourceFile, position: Position) -> Option<usize> {
    let text = &*file.text;
    let line = file.line_range(position.line as usize)?;
    let content = text[line.clone()].trim_end_matches(['\n', '\r']);
    let mut units = 0usize;
    for (at, c) in content.char_indices() {
        units += c.len_utf16();
        if units > position.character as usize {
            return Some(line.start + at);
        }
    }
    Some(line.start + content.len())
}

fn saturate(n: usize) -> u32 {
    u32::try_from(n).unwrap_or(u32::MAX)
}

#[cfg(test)]
mod tests {
    use patina_compiler::source::SourceMap;

    use super::*;

    fn file(text: &str) -> SourceFile {
        let mut map = SourceMap::new();
        let id = map.add_file("t.sl", text, None);
        map.file(id).clone()
    }

    fn at(line: u32, character: u32) -> Position {
        Position { line, character }
    }

    #[test]
    fn ascii_columns_are_bytes() {
        let f = file("float x;\nx = 1;\n");
        assert_eq!(position(&f, 0), at(0, 0));
        assert_eq!(position(&f, 6), at(0, 6));
        assert_eq!(position(&f, 9), at(1, 0));
        assert_eq!(offset(&f, at(1, 4)), Some(13));
    }

    #[test]
    fn columns_count_utf16_units() {
        // `é` is two bytes and one unit; `𝔽` (outside the BMP) four bytes and two units.
        let f = file("// é𝔽 x\ny");
        let x = f.text.find('x').unwrap();
        assert_eq!(x, 10);
        assert_eq!(position(&f, x), at(0, 7));
        assert_eq!(offset(&f, at(0, 7)), Some(x));
        assert_eq!(offset(&f, at(0, 4)), Some(5)); // just after `é`: the start of `𝔽`
        assert_eq!(position(&f, 5), at(0, 4));
    }

    #[test]
    fn a_column_inside_a_surrogate_pair_is_the_character_start() {
        let f = file("𝔽x");
        assert_eq!(offset(&f, at(0, 1)), Some(0));
        assert_eq!(offset(&f, at(0, 2)), Some(4));
        // A byte offset inside the character moves back to its start.
        assert_eq!(position(&f, 2), at(0, 0));
    }

    #[test]
    fn positions_past_the_end_are_clamped_or_refused() {
        let f = file("ab\r\ncd");
        assert_eq!(offset(&f, at(0, 99)), Some(2)); // the end of the line, before `\r\n`
        assert_eq!(offset(&f, at(1, 99)), Some(6));
        assert_eq!(offset(&f, at(2, 0)), None);
        assert_eq!(offset(&f, at(u32::MAX, u32::MAX)), None);
        assert_eq!(position(&f, 999), at(1, 2));
    }

    #[test]
    fn an_empty_file_has_one_empty_line() {
        let f = file("");
        assert_eq!(offset(&f, at(0, 5)), Some(0));
        assert_eq!(position(&f, 0), at(0, 0));
    }
}
