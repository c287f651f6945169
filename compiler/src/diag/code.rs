//! The error codes: one per kind of diagnostic, stable across releases.
//!
//! Codes are grouped by the stage that reports them: `E01xx` lexical, `E02xx` preprocessor,
//! `E03xx` syntax, `E04xx` unsupported RenderMan features. Keeping them in one enum keeps them unique
//! and gives `docs/language.md` one list to point at.

macro_rules! codes {
    ($($(#[doc = $doc:literal])* $name:ident = $code:literal,)*) => {
        /// A stable identifier for one kind of diagnostic.
        #[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
        pub enum Code {
            $($(#[doc = $doc])* $name,)*
        }

        impl Code {
            /// Every code, in numeric order.
            pub const ALL: &'static [Code] = &[$(Code::$name,)*];

            /// The code as users see it, e.g. `E0301`.
            pub fn as_str(self) -> &'static str {
                match self {
                    $(Code::$name => $code,)*
                }
            }
        }
    };
}

codes! {
    // Lexical.
    /// A character that starts no token.
    UnknownCharacter = "E0101",
    /// A `/*` comment without its `*/`.
    UnterminatedComment = "E0102",
    /// A string literal without its closing quote.
    UnterminatedString = "E0103",
    /// A backslash escape a string literal cannot contain.
    InvalidEscape = "E0104",
    /// A number with a malformed exponent, suffix or digits.
    MalformedNumber = "E0105",
    /// An integer literal that does not fit in 32 bits.
    IntegerTooLarge = "E0106",
    /// A float literal that rounds to infinity in f32.
    FloatTooLarge = "E0107",

    // Preprocessor.
    /// A `#` directive the preprocessor does not know.
    UnknownDirective = "E0201",
    /// `#include` of a file found in no search path.
    IncludeNotFound = "E0202",
    /// `#include` without a `"file"` or `<file>` operand.
    MalformedInclude = "E0203",
    /// Includes nested too deeply (usually a file including itself).
    IncludeDepth = "E0204",
    /// An included file that cannot be read or is not UTF-8.
    IncludeUnreadable = "E0205",
    /// `#else`, `#elif` or `#endif` with no open `#if`.
    UnmatchedConditional = "E0206",
    /// An `#if` whose `#endif` never comes.
    UnterminatedConditional = "E0207",
    /// `#elif` or `#else` after the `#else` of the same `#if`.
    ConditionalAfterElse = "E0208",
    /// An `#if`/`#elif` operand that is not an integer constant expression.
    InvalidConditionExpr = "E0209",
    /// `#define` or `#undef` without a macro name.
    MissingMacroName = "E0210",
    /// A function-like macro whose parameter list is malformed.
    MalformedMacroParams = "E0211",
    /// A function-like macro called with the wrong number of arguments.
    MacroArity = "E0212",
    /// A function-like macro call whose `)` never comes.
    UnterminatedMacroCall = "E0213",
    /// A `#define` that changes an existing macro (warning).
    MacroRedefined = "E0214",
    /// `##` at the edge of a macro body, or a paste that does not form one token.
    InvalidPaste = "E0215",
    /// `#` in a function-like macro not followed by a parameter.
    InvalidStringize = "E0216",
    /// An `#error` directive was reached.
    ErrorDirective = "E0217",
    /// Macro expansion nested too deeply or produced too many tokens.
    ExpansionLimit = "E0218",
    /// Extra tokens after a directive that takes none (warning).
    ExtraTokens = "E0219",

    // Syntax.
    /// A token the grammar does not allow here.
    UnexpectedToken = "E0301",
    /// The file ends in the middle of a construct.
    UnexpectedEof = "E0302",
    /// A statement or declaration without its `;`.
    MissingSemicolon = "E0303",
    /// A `(`, `[` or `{` that is never closed.
    UnclosedDelimiter = "E0304",
    /// A `)`, `]` or `}` that closes nothing, or closes the wrong kind of bracket.
    UnexpectedCloser = "E0305",
    /// A reserved word used as a name.
    ReservedWord = "E0306",
    /// `primitive` not followed by `group`.
    PrimitiveWithoutGroup = "E0307",
    /// Two storage or rate qualifiers that contradict each other.
    ConflictingQualifiers = "E0308",
    /// An array size that is not a positive integer literal.
    InvalidArraySize = "E0309",
    /// A vector constructor `{...}` closed before its last components.
    StrayBrace = "E0310",
    /// An empty vector constructor `{}`.
    EmptyConstructor = "E0311",
    /// A C construct the language does not have (`switch`, `do`, `struct`, `goto`, ...).
    UnsupportedSyntax = "E0312",
    /// A `break`/`continue` level that is not a positive integer literal.
    InvalidLoopLevel = "E0313",
    /// `else` with no `if` before it.
    ElseWithoutIf = "E0314",
    /// The source is larger or more deeply nested than the compiler accepts.
    ResourceLimit = "E0315",

    // Unsupported RenderMan features.
    /// Ray tracing (`trace`, `transmission`, `occlusion`, `indirectdiffuse`, `environment` lookups by ray).
    RayTracing = "E0401",
    /// Message passing between shaders (`surface(...)`, `lightsource(...)`, `incident`, ...).
    MessagePassing = "E0402",
    /// The `gather` construct.
    Gather = "E0403",
    /// Renderer queries (`attribute`, `option`, `rendererinfo`, `textureinfo`).
    RendererQuery = "E0404",
}

impl std::fmt::Display for Code {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_are_unique_and_sorted() {
        let strings: Vec<&str> = Code::ALL.iter().map(|c| c.as_str()).collect();
        let mut sorted = strings.clone();
        sorted.sort();
        sorted.dedup();
        assert_eq!(strings, sorted, "codes must be unique and listed in numeric order");
    }
}
