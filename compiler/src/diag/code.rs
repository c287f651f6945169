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
    /// `#define`, `#undef`, `#ifdef` or `#ifndef` without a macro name, or with something else where
    /// the name should be.
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
    /// An `#error` directive was reached (or a `#warning`, reported as a warning).
    ErrorDirective = "E0217",
    /// Macro expansion nested too deeply or produced too many tokens.
    ExpansionLimit = "E0218",
    /// Extra tokens after a directive that takes none (warning).
    ExtraTokens = "E0219",
    /// A source file, or a file with everything it includes, larger than the compiler accepts.
    SourceTooLarge = "E0220",

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
    /// The source nests deeper than the compiler accepts (brackets, statements, operator chains,
    /// `else` chains).
    ResourceLimit = "E0315",

    // Unsupported RenderMan features.
    /// Ray tracing (`trace`, `transmission`, `occlusion`, `indirectdiffuse`, `rayinfo`, `photonmap`,
    /// `caustic`).
    RayTracing = "E0401",
    /// Message passing between shaders (`surface(...)`, `lightsource(...)`, `incident(...)`, ...).
    MessagePassing = "E0402",
    /// The `gather` construct.
    Gather = "E0403",
    /// Renderer queries (`attribute`, `option`, `rendererinfo`, `textureinfo`).
    RendererQuery = "E0404",
    /// A RenderMan feature accepted without its effect (a warning): a texture option no backend
    /// honours, `printf` on the GPU, `bake`.
    IgnoredFeature = "E0405",

    // Names and types.
    /// A name that no declaration, parameter or predefined variable defines.
    UnknownName = "E0501",
    /// A call of a function that neither the source nor the built-ins define.
    UnknownFunction = "E0502",
    /// No overload of a function accepts the arguments.
    NoMatchingOverload = "E0503",
    /// Several overloads fit equally well.
    AmbiguousCall = "E0504",
    /// A value of one type where another is needed, with no implicit conversion.
    TypeMismatch = "E0505",
    /// An operator applied to types it does not take.
    InvalidOperands = "E0506",
    /// An assignment to something that is not a variable (or a read-only one).
    NotAssignable = "E0507",
    /// A name declared twice in one scope, or a function defined twice.
    Redefinition = "E0508",
    /// A `return` whose value does not fit the function, or a missing one.
    InvalidReturn = "E0509",
    /// A function that calls itself (functions are inlined).
    Recursion = "E0510",
    /// A built-in or predefined variable used in a kind of shader that lacks it.
    WrongShaderKind = "E0511",
    /// A per-light variable (`L`, `Cl`) outside `illuminance`, `illuminate` or `solar`.
    OutsideLightLoop = "E0512",
    /// A statement in a place it cannot be (`illuminance` in a light shader, `break` outside a loop).
    MisplacedStatement = "E0513",
    /// A tuple `(a, b, c)` whose type the context does not say.
    UntypedTuple = "E0514",
    /// A constructor with the wrong number or kind of components.
    InvalidConstructor = "E0515",
    /// Indexing something that has no elements, or with a non-integer.
    InvalidIndex = "E0516",
    /// A conversion that does not exist, even explicitly.
    InvalidCast = "E0517",
    /// An unknown coordinate or colour space name.
    UnknownSpace = "E0518",
    /// A qualifier that does not apply where it is written.
    InvalidQualifier = "E0519",
    /// An assignment or `++` inside `?:`, `&&` or `||`, whose evaluation would change.
    EffectInCondition = "E0520",
    /// Calls inlined too deeply, statements nested too deeply once calls are inlined, or a shader
    /// whose inlined code grows past the size limit.
    InlineLimit = "E0521",
    /// An optional `"name", value` argument of a texture lookup that the function does not know (a
    /// warning), or one without its value.
    UnknownOption = "E0522",

    // Rates.
    /// A value of a higher rate stored in a variable declared with a lower one.
    RateTooHigh = "E0601",
    /// RenderMan's form of E0601: a varying value assigned to a uniform variable.
    VaryingToUniform = "E0602",
    /// A per-light value leaving the light loop without `integrate` or `illuminance`.
    PerlightEscape = "E0603",
    /// A screen-space derivative where only a lower rate is allowed.
    DerivativeRate = "E0604",
    /// A store under a condition or loop of a higher rate than the variable's.
    ControlDependence = "E0605",
    /// `integrate` of a value that is not per-light.
    IntegrateNotPerlight = "E0606",
    /// A parameter default that is not constant or primitive-group rate.
    DefaultRate = "E0607",

    // Evaluation.
    /// A built-in that needs something the evaluation was not given (a texture, a light binding)
    /// or that is not implemented by this backend yet.
    NotExecutable = "E0701",
    /// A loop that ran past the iteration budget.
    IterationBudget = "E0702",
    /// A parameter, input or output name that the shader does not have, or a value of the wrong size.
    UnknownInput = "E0703",
    /// More lights bound to a shader than the backends unroll.
    LightLimit = "E0704",
    /// An inconsistency between compiler stages: a bug in Patina, reported with the source position.
    Internal = "E0799",
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
