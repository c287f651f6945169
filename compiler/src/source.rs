//! Source files, spans, and the expansion contexts the preprocessor creates.
//!
//! Every token and every AST node carries a [`Span`]: a byte range in one [`SourceFile`] plus the
//! macro expansion ([`ExpnId`]) it came from. Each inclusion of a file gets its own `FileId`, so the
//! include chain of a span is a property of its file, and the expansion chain is a property of its
//! `ExpnId`. Diagnostics walk both chains to show where an included file or a macro was used.

use std::ops::Range;
use std::sync::Arc;

use smol_str::SmolStr;

/// Identifies one inclusion of a source file in a [`SourceMap`].
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Default)]
pub struct FileId(u32);

impl FileId {
    /// The position of this file in its source map.
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// Identifies one macro expansion; [`ExpnId::ROOT`] is "not from a macro".
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, Default)]
pub struct ExpnId(u32);

impl ExpnId {
    /// Text that was written directly in a file, not produced by a macro.
    pub const ROOT: ExpnId = ExpnId(0);

    /// Whether this span's text came out of a macro expansion.
    pub fn is_macro(self) -> bool {
        self != Self::ROOT
    }
}

/// A byte range in one file, tagged with the macro expansion that produced it.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, Default)]
pub struct Span {
    /// The file (inclusion) the bytes are in.
    pub file: FileId,
    /// Start byte offset.
    pub start: u32,
    /// End byte offset (exclusive).
    pub end: u32,
    /// The macro expansion these bytes were produced by, or [`ExpnId::ROOT`].
    pub expn: ExpnId,
}

impl Span {
    /// A span of `range` in `file`, outside any macro expansion.
    pub fn new(file: FileId, range: Range<usize>) -> Span {
        Span { file, start: range.start as u32, end: range.end as u32, expn: ExpnId::ROOT }
    }

    /// The byte range of this span.
    pub fn range(self) -> Range<usize> {
        self.start as usize..self.end as usize
    }

    /// The empty span just after this one (where a missing token would go).
    pub fn end_point(self) -> Span {
        Span { start: self.end, ..self }
    }

    /// Whether `offset` lies within this span (end inclusive, so empty spans contain their point).
    pub fn contains_offset(self, offset: u32) -> bool {
        self.start <= offset && offset <= self.end
    }
}

/// One inclusion of a source file.
#[derive(Debug, Clone)]
pub struct SourceFile {
    /// The name shown in diagnostics (the path as given, or `<stdlib>/name.sl`).
    pub name: String,
    /// The file's text.
    pub text: Arc<str>,
    /// The `#include` directive that brought this file in, if any.
    pub included_from: Option<Span>,
    line_starts: Vec<u32>,
}

impl SourceFile {
    /// The zero-based line containing `offset`.
    pub fn line_index(&self, offset: usize) -> usize {
        match self.line_starts.binary_search(&(offset as u32)) {
            Ok(line) => line,
            Err(next) => next - 1,
        }
    }

    /// The byte range of the zero-based line `line`, including its terminator.
    pub fn line_range(&self, line: usize) -> Option<Range<usize>> {
        let start = *self.line_starts.get(line)? as usize;
        let end = self.line_starts.get(line + 1).map_or(self.text.len(), |&e| e as usize);
        Some(start..end)
    }

    /// One-based line and column (in characters) of `offset`.
    pub fn line_column(&self, offset: usize) -> (usize, usize) {
        let line = self.line_index(offset);
        let start = self.line_starts[line] as usize;
        let offset = offset.min(self.text.len());
        let column = self.text.get(start..offset).map_or(offset - start, |s| s.chars().count());
        (line + 1, column + 1)
    }
}

/// The `//` comment block directly above byte `start` of `text`: a definition's documentation,
/// as the standard library writes it. Lines come top to bottom, each without its slashes and the
/// space after them; a blank line (or any line that is not a comment) ends the block, and the
/// definition's own indentation does not count as a line. Empty when there is none (or `start`
/// is not a character boundary of `text`).
pub fn comment_above(text: &str, start: usize) -> Vec<&str> {
    let Some(head) = text.get(..start.min(text.len())) else { return Vec::new() };
    let mut lines: Vec<&str> = head
        .trim_end_matches([' ', '\t'])
        .lines()
        .rev()
        .map(str::trim)
        .take_while(|l| l.starts_with("//"))
        .map(|l| {
            let body = l.trim_start_matches('/');
            body.strip_prefix(' ').unwrap_or(body).trim_end()
        })
        .collect();
    lines.reverse();
    lines
}

/// What a macro expansion was: which macro, defined where, used where.
#[derive(Debug, Clone)]
pub struct Expansion {
    /// The macro's name.
    pub name: SmolStr,
    /// The macro's name in its `#define`.
    pub definition: Span,
    /// The use of the macro (name and arguments) that was replaced.
    pub call_site: Span,
}

/// All source text of one compilation, and the expansions the preprocessor made.
#[derive(Debug, Clone)]
pub struct SourceMap {
    files: Vec<SourceFile>,
    expansions: Vec<Expansion>,
}

impl Default for SourceMap {
    fn default() -> Self {
        Self::new()
    }
}

impl SourceMap {
    /// An empty source map.
    pub fn new() -> SourceMap {
        // Slot 0 of `expansions` stands for ExpnId::ROOT and is never read.
        let root =
            Expansion { name: SmolStr::default(), definition: Span::default(), call_site: Span::default() };
        SourceMap { files: Vec::new(), expansions: vec![root] }
    }

    /// Adds a file, brought in by the `#include` at `included_from` if that is given.
    pub fn add_file(
        &mut self,
        name: impl Into<String>,
        text: impl Into<Arc<str>>,
        included_from: Option<Span>,
    ) -> FileId {
        let text: Arc<str> = text.into();
        let line_starts =
            std::iter::once(0).chain(text.match_indices('\n').map(|(i, _)| i as u32 + 1)).collect();
        let id = FileId(self.files.len() as u32);
        self.files.push(SourceFile { name: name.into(), text, included_from, line_starts });
        id
    }

    /// Records a macro expansion and returns its id.
    pub fn add_expansion(&mut self, expansion: Expansion) -> ExpnId {
        let id = ExpnId(self.expansions.len() as u32);
        self.expansions.push(expansion);
        id
    }

    /// The file `id` refers to.
    pub fn file(&self, id: FileId) -> &SourceFile {
        &self.files[id.index()]
    }

    /// All files, in the order they were added.
    pub fn files(&self) -> impl Iterator<Item = (FileId, &SourceFile)> {
        self.files.iter().enumerate().map(|(i, f)| (FileId(i as u32), f))
    }

    /// The expansion `id` refers to; `None` for [`ExpnId::ROOT`].
    pub fn expansion(&self, id: ExpnId) -> Option<&Expansion> {
        id.is_macro().then(|| &self.expansions[id.0 as usize])
    }

    /// The text a span covers.
    pub fn text(&self, span: Span) -> &str {
        self.file(span.file).text.get(span.range()).unwrap_or("")
    }

    /// How many macro expansions deep a span is.
    fn depth(&self, span: Span) -> usize {
        let mut depth = 0;
        let mut expn = span.expn;
        while let Some(e) = self.expansion(expn) {
            depth += 1;
            expn = e.call_site.expn;
        }
        depth
    }

    /// Lifts a span out of its macro expansion to the use of the macro.
    pub fn call_site(&self, span: Span) -> Span {
        self.expansion(span.expn).map_or(span, |e| e.call_site)
    }

    /// The smallest span covering `a` and `b`. When the two come from different expansions, both are
    /// first lifted to the innermost context they share, so that a node built partly from a macro's
    /// body covers the macro's use. If they are in different files, `a` wins.
    pub fn join(&self, mut a: Span, mut b: Span) -> Span {
        if a.expn != b.expn {
            let (mut da, mut db) = (self.depth(a), self.depth(b));
            while da > db {
                a = self.call_site(a);
                da -= 1;
            }
            while db > da {
                b = self.call_site(b);
                db -= 1;
            }
            while a.expn != b.expn {
                a = self.call_site(a);
                b = self.call_site(b);
            }
        }
        if a.file != b.file {
            return a;
        }
        Span { start: a.start.min(b.start), end: a.end.max(b.end), ..a }
    }
}

impl<'a> codespan_reporting::files::Files<'a> for SourceMap {
    type FileId = FileId;
    type Name = &'a str;
    type Source = &'a str;

    fn name(&'a self, id: FileId) -> Result<&'a str, codespan_reporting::files::Error> {
        self.files
            .get(id.index())
            .map(|f| f.name.as_str())
            .ok_or(codespan_reporting::files::Error::FileMissing)
    }

    fn source(&'a self, id: FileId) -> Result<&'a str, codespan_reporting::files::Error> {
        self.files.get(id.index()).map(|f| &*f.text).ok_or(codespan_reporting::files::Error::FileMissing)
    }

    fn line_index(
        &'a self,
        id: FileId,
        byte_index: usize,
    ) -> Result<usize, codespan_reporting::files::Error> {
        let file = self.files.get(id.index()).ok_or(codespan_reporting::files::Error::FileMissing)?;
        Ok(file.line_index(byte_index))
    }

    fn line_range(
        &'a self,
        id: FileId,
        line_index: usize,
    ) -> Result<Range<usize>, codespan_reporting::files::Error> {
        let file = self.files.get(id.index()).ok_or(codespan_reporting::files::Error::FileMissing)?;
        file.line_range(line_index).ok_or(codespan_reporting::files::Error::LineTooLarge {
            given: line_index,
            max: file.line_starts.len() - 1,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::comment_above;

    #[test]
    fn the_comment_block_directly_above_is_read_top_to_bottom() {
        let text = "// far\n\n// The fbm.\n///   indented\n    float f();\n";
        assert_eq!(comment_above(text, text.find("float").unwrap()), ["The fbm.", "  indented"]);
        assert!(comment_above(text, text.find("// The").unwrap()).is_empty());
        // Inside a character: nothing (and no panic); past the end: the end.
        assert_eq!(comment_above("// é\nx", 6), ["é"]);
        assert!(comment_above("// é\nx", 4).is_empty());
        assert_eq!(comment_above("// é\n", 99), ["é"]);
    }
}
