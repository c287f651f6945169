//! Token kinds, as recognised by the logos-generated scanner.

use logos::Logos;

/// The kind of a token. Identifiers and literals keep no payload: their text is read back through
/// the token's span, so tokens stay `Copy` and small.
#[derive(Logos, Copy, Clone, Debug, PartialEq, Eq, Hash)]
#[logos(skip r"[ \t\r\x0c]+")]
#[logos(skip r"\\\r?\n")]
#[logos(skip(r"//[^\n]*", allow_greedy = true))]
#[logos(skip r"/\*([^*]|\*+[^*/])*\*+/")]
pub enum TokenKind {
    /// A line break; the preprocessor uses these to end directives and never passes them on.
    #[token("\n")]
    Newline,
    /// A `/*` comment that runs to the end of the file.
    #[regex(r"/\*([^*]|\*+[^*/])*\**")]
    UnterminatedComment,
    /// A string literal missing its closing quote before the end of the line.
    #[regex(r#""([^"\\\n]|\\[^\n])*\\?"#)]
    UnterminatedString,

    /// A name.
    #[regex(r"[A-Za-z_][A-Za-z0-9_]*")]
    Ident,
    /// A number in C's "preprocessing number" form; [`classify_number`] refines it.
    #[regex(r"\.?[0-9]([0-9A-Za-z_.]|[eE][+-])*")]
    Number,
    /// An integer literal (after classification).
    IntLit,
    /// A float literal (after classification).
    FloatLit,
    /// A string literal, quotes included.
    #[regex(r#""([^"\\\n]|\\[^\n])*""#)]
    StringLit,

    // Keywords: shader kinds.
    /// `surface`: a shader kind. Inside a RenderMan-style definition, a name unless `(` follows
    /// (`surface(...)` is message passing).
    #[token("surface")]
    Surface,
    /// `light`: a shader kind; in a RenderMan-style definition a name unless `(` follows.
    #[token("light")]
    Light,
    /// `displacement`: a shader kind; in a RenderMan-style definition a name unless `(` follows.
    #[token("displacement")]
    Displacement,
    /// `volume`: a shader kind; in a RenderMan-style definition a name unless `(` follows.
    #[token("volume")]
    Volume,
    /// `imager`: a shader kind; in a RenderMan-style definition a name unless `(` follows.
    #[token("imager")]
    Imager,
    /// `shader`: follows the kind in a Stanford shader (`surface shader float4 name(...)`).
    #[token("shader")]
    Shader,

    // Keywords: qualifiers.
    /// `uniform`: RenderMan's storage class for one value per primitive group.
    #[token("uniform")]
    Uniform,
    /// `varying`: RenderMan's storage class for a value that varies over the surface (per vertex
    /// for a parameter, per fragment for a variable).
    #[token("varying")]
    Varying,
    /// `output`: a parameter the shader or function writes (both styles).
    #[token("output")]
    Output,
    /// `extern`: a variable of an enclosing scope (both styles).
    #[token("extern")]
    Extern,
    /// `constant`: the lowest Stanford rate, one value for every primitive group; a keyword only in
    /// the Stanford style (a RenderMan-style file may use it as a name).
    #[token("constant")]
    Constant,
    /// `vertex`: the Stanford per-vertex rate; a keyword only in the Stanford style (a
    /// RenderMan-style file may use it as a name).
    #[token("vertex")]
    Vertex,
    /// `fragment`: the Stanford per-fragment rate; a keyword only in the Stanford style (a
    /// RenderMan-style file may use it as a name).
    #[token("fragment")]
    Fragment,
    /// `perlight`: Stanford's one instance per bound light; a keyword only in the Stanford style (a
    /// RenderMan-style file may use it as a name).
    #[token("perlight")]
    Perlight,
    /// `primitive group`, the Stanford rate, as one token.
    #[regex(r"primitive[ \t\r\n]+group")]
    PrimitiveGroup,
    /// `primitive` not followed by `group`: only ever an error.
    #[token("primitive")]
    Primitive,

    // Keywords: types.
    /// `float`: a type word in both styles.
    #[token("float")]
    Float,
    /// `color`: RenderMan's contextual type word: a type in type position, elsewhere a name.
    #[token("color")]
    Color,
    /// `point`: RenderMan's contextual type word: a type in type position, elsewhere a name.
    #[token("point")]
    Point,
    /// `vector`: RenderMan's contextual type word: a type in type position, elsewhere a name.
    #[token("vector")]
    Vector,
    /// `normal`: RenderMan's contextual type word: a type in type position, elsewhere a name.
    #[token("normal")]
    Normal,
    /// `matrix`: RenderMan's contextual type word for the 4×4 matrix: a type in type position,
    /// elsewhere a name.
    #[token("matrix")]
    Matrix,
    /// `string`: RenderMan's contextual type word: a type in type position, elsewhere a name.
    #[token("string")]
    String,
    /// `void`: the result type of a function that returns nothing (both styles).
    #[token("void")]
    Void,
    /// `float3`: Stanford's plain 3-vector type; a keyword only in the Stanford style (a
    /// RenderMan-style file may use it as a name).
    #[token("float3")]
    Float3,
    /// `float4`: Stanford's four-float type; a keyword only in the Stanford style (a
    /// RenderMan-style file may use it as a name).
    #[token("float4")]
    Float4,
    /// `matrix3`: Stanford's 3×3 matrix type; a keyword only in the Stanford style (a
    /// RenderMan-style file may use it as a name).
    #[token("matrix3")]
    Matrix3,
    /// `matrix4`: Stanford's 4×4 matrix type (RenderMan's `matrix`); a keyword only in the Stanford
    /// style (a RenderMan-style file may use it as a name).
    #[token("matrix4")]
    Matrix4,
    /// `bool`: the type of comparisons; a keyword only in the Stanford style (a RenderMan-style
    /// file may use it as a name).
    #[token("bool")]
    Bool,
    /// `texref`: Stanford's texture reference type; a keyword only in the Stanford style (a
    /// RenderMan-style file may use it as a name).
    #[token("texref")]
    Texref,
    /// `clampf`: Stanford's float kept in [0, 1]; a keyword only in the Stanford style (a
    /// RenderMan-style file may use it as a name).
    #[token("clampf")]
    Clampf,
    /// `int`: the 32-bit signed integer type (both styles have it); a keyword only in the Stanford
    /// style (a RenderMan-style file may use it as a name).
    #[token("int")]
    Int,
    /// `uint`: the 32-bit unsigned integer type (both styles have it); a keyword only in the
    /// Stanford style (a RenderMan-style file may use it as a name).
    #[token("uint")]
    Uint,

    // Keywords: statements and literals.
    /// `if`.
    #[token("if")]
    If,
    /// `else`, which belongs to the nearest `if`.
    #[token("else")]
    Else,
    /// `for`.
    #[token("for")]
    For,
    /// `while`.
    #[token("while")]
    While,
    /// `break`, optionally followed by the number of loops to leave (`break 2`).
    #[token("break")]
    Break,
    /// `continue`, optionally followed by the number of the loop to continue (`continue 2`).
    #[token("continue")]
    Continue,
    /// `return`.
    #[token("return")]
    Return,
    /// `illuminance`: RenderMan's loop over the bound lights.
    #[token("illuminance")]
    Illuminance,
    /// `illuminate`: a RenderMan light's emission from a position.
    #[token("illuminate")]
    Illuminate,
    /// `solar`: a RenderMan light's emission along a direction.
    #[token("solar")]
    Solar,
    /// `gather`: parsed only to be rejected (E0403, it needs ray tracing).
    #[token("gather")]
    Gather,
    /// `true`: a `bool` literal (1 in `#if`).
    #[token("true")]
    True,
    /// `false`: a `bool` literal (0 in `#if`).
    #[token("false")]
    False,

    /// Words of C that the language reserves and rejects with a dedicated diagnostic.
    #[token("struct")]
    #[token("switch")]
    #[token("case")]
    #[token("do")]
    #[token("goto")]
    #[token("typedef")]
    #[token("const")]
    #[token("union")]
    #[token("enum")]
    #[token("sizeof")]
    Reserved,

    // Punctuation.
    /// `{`: opens a block or a braced constructor.
    #[token("{")]
    LBrace,
    /// `}`.
    #[token("}")]
    RBrace,
    /// `(`.
    #[token("(")]
    LParen,
    /// `)`.
    #[token(")")]
    RParen,
    /// `[`: opens an array size or an index.
    #[token("[")]
    LBracket,
    /// `]`.
    #[token("]")]
    RBracket,
    /// `;`: ends a statement or declaration, and separates RenderMan parameter groups.
    #[token(";")]
    Semi,
    /// `,`: separates arguments, declarators, tuple components and Stanford parameters.
    #[token(",")]
    Comma,
    /// `.`: the dot product.
    #[token(".")]
    Dot,
    /// `?` of the conditional `c ? a : b`.
    #[token("?")]
    Question,
    /// `:` of the conditional `c ? a : b`.
    #[token(":")]
    Colon,
    /// `+`, binary or unary.
    #[token("+")]
    Plus,
    /// `-`, binary or unary.
    #[token("-")]
    Minus,
    /// `*`.
    #[token("*")]
    Star,
    /// `/`.
    #[token("/")]
    Slash,
    /// `%`: the remainder of integers.
    #[token("%")]
    Percent,
    /// `^`: the cross product of vectors or the exclusive or of integers; binds tighter than `+`.
    #[token("^")]
    Caret,
    /// `&`: bitwise and.
    #[token("&")]
    Amp,
    /// `|`: bitwise or.
    #[token("|")]
    Pipe,
    /// `~`: bitwise not.
    #[token("~")]
    Tilde,
    /// `!`: logical not.
    #[token("!")]
    Bang,
    /// `<`.
    #[token("<")]
    Lt,
    /// `>`.
    #[token(">")]
    Gt,
    /// `<=`.
    #[token("<=")]
    Le,
    /// `>=`.
    #[token(">=")]
    Ge,
    /// `==`.
    #[token("==")]
    EqEq,
    /// `!=`.
    #[token("!=")]
    Ne,
    /// `&&`: logical and.
    #[token("&&")]
    AndAnd,
    /// `||`: logical or.
    #[token("||")]
    OrOr,
    /// `<<`: shift left.
    #[token("<<")]
    Shl,
    /// `>>`: shift right.
    #[token(">>")]
    Shr,
    /// `=`: assignment, and a declarator's initialiser or a parameter's default.
    #[token("=")]
    Eq,
    /// `+=`.
    #[token("+=")]
    PlusEq,
    /// `-=`.
    #[token("-=")]
    MinusEq,
    /// `*=`.
    #[token("*=")]
    StarEq,
    /// `/=`.
    #[token("/=")]
    SlashEq,
    /// `%=`.
    #[token("%=")]
    PercentEq,
    /// `&=`.
    #[token("&=")]
    AmpEq,
    /// `|=`.
    #[token("|=")]
    PipeEq,
    /// `^=`.
    #[token("^=")]
    CaretEq,
    /// `<<=`.
    #[token("<<=")]
    ShlEq,
    /// `>>=`.
    #[token(">>=")]
    ShrEq,
    /// `++`, prefix or postfix.
    #[token("++")]
    PlusPlus,
    /// `--`, prefix or postfix.
    #[token("--")]
    MinusMinus,
    /// `#`: starts a preprocessor directive at the start of a line; in a macro body, makes a string
    /// of a parameter's argument.
    #[token("#")]
    Hash,
    /// `##`: in a macro body, pastes the tokens on either side into one.
    #[token("##")]
    HashHash,
}

impl TokenKind {
    /// How diagnostics name this kind of token.
    pub fn describe(self) -> &'static str {
        use TokenKind::*;
        match self {
            Newline => "end of line",
            UnterminatedComment => "unterminated comment",
            UnterminatedString | StringLit => "string literal",
            Ident => "identifier",
            Number | IntLit | FloatLit => "number",
            PrimitiveGroup => "`primitive group`",
            Reserved => "reserved word",
            _ => self.spelling().unwrap_or("token"),
        }
    }

    /// The fixed text of keywords and punctuation.
    pub fn spelling(self) -> Option<&'static str> {
        use TokenKind::*;
        Some(match self {
            Surface => "surface",
            Light => "light",
            Displacement => "displacement",
            Volume => "volume",
            Imager => "imager",
            Shader => "shader",
            Uniform => "uniform",
            Varying => "varying",
            Output => "output",
            Extern => "extern",
            Constant => "constant",
            Vertex => "vertex",
            Fragment => "fragment",
            Perlight => "perlight",
            PrimitiveGroup => "primitive group",
            Primitive => "primitive",
            Float => "float",
            Color => "color",
            Point => "point",
            Vector => "vector",
            Normal => "normal",
            Matrix => "matrix",
            String => "string",
            Void => "void",
            Float3 => "float3",
            Float4 => "float4",
            Matrix3 => "matrix3",
            Matrix4 => "matrix4",
            Bool => "bool",
            Texref => "texref",
            Clampf => "clampf",
            Int => "int",
            Uint => "uint",
            If => "if",
            Else => "else",
            For => "for",
            While => "while",
            Break => "break",
            Continue => "continue",
            Return => "return",
            Illuminance => "illuminance",
            Illuminate => "illuminate",
            Solar => "solar",
            Gather => "gather",
            True => "true",
            False => "false",
            LBrace => "{",
            RBrace => "}",
            LParen => "(",
            RParen => ")",
            LBracket => "[",
            RBracket => "]",
            Semi => ";",
            Comma => ",",
            Dot => ".",
            Question => "?",
            Colon => ":",
            Plus => "+",
            Minus => "-",
            Star => "*",
            Slash => "/",
            Percent => "%",
            Caret => "^",
            Amp => "&",
            Pipe => "|",
            Tilde => "~",
            Bang => "!",
            Lt => "<",
            Gt => ">",
            Le => "<=",
            Ge => ">=",
            EqEq => "==",
            Ne => "!=",
            AndAnd => "&&",
            OrOr => "||",
            Shl => "<<",
            Shr => ">>",
            Eq => "=",
            PlusEq => "+=",
            MinusEq => "-=",
            StarEq => "*=",
            SlashEq => "/=",
            PercentEq => "%=",
            AmpEq => "&=",
            PipeEq => "|=",
            CaretEq => "^=",
            ShlEq => "<<=",
            ShrEq => ">>=",
            PlusPlus => "++",
            MinusMinus => "--",
            Hash => "#",
            HashHash => "##",
            _ => return None,
        })
    }

    /// Whether this is an operator (unary, binary, assignment, `?`, `++`): each can add a level to
    /// an expression tree.
    pub fn is_operator(self) -> bool {
        use TokenKind::*;
        matches!(
            self,
            Question
                | Plus
                | Minus
                | Star
                | Slash
                | Percent
                | Caret
                | Amp
                | Pipe
                | Tilde
                | Bang
                | Lt
                | Gt
                | Le
                | Ge
                | EqEq
                | Ne
                | AndAnd
                | OrOr
                | Shl
                | Shr
                | Eq
                | PlusEq
                | MinusEq
                | StarEq
                | SlashEq
                | PercentEq
                | AmpEq
                | PipeEq
                | CaretEq
                | ShlEq
                | ShrEq
                | PlusPlus
                | MinusMinus
                | Dot
        )
    }

    /// Whether this is a keyword (a word that cannot be a name).
    pub fn is_keyword(self) -> bool {
        use TokenKind::*;
        !matches!(self, Ident | Number | IntLit | FloatLit | StringLit | Reserved)
            && self.spelling().is_some_and(|s| s.starts_with(|c: char| c.is_ascii_alphabetic()))
    }
}

/// What a preprocessing number turned out to be.
#[derive(Debug, PartialEq, Eq)]
pub enum NumberClass {
    /// A decimal or hexadecimal integer, optionally with a `u` suffix.
    Int,
    /// A float, optionally with an `f` suffix.
    Float,
    /// Not a number; the string says why.
    Malformed(&'static str),
}

/// Decides whether the text of a [`TokenKind::Number`] is an integer, a float or malformed.
pub fn classify_number(text: &str) -> NumberClass {
    let bytes = text.as_bytes();
    if let Some(hex) = text.strip_prefix("0x").or_else(|| text.strip_prefix("0X")) {
        let digits = hex.strip_suffix(['u', 'U']).unwrap_or(hex);
        if digits.is_empty() {
            return NumberClass::Malformed("hexadecimal literal has no digits");
        }
        if !digits.bytes().all(|b| b.is_ascii_hexdigit()) {
            return NumberClass::Malformed("invalid digit in hexadecimal literal");
        }
        return NumberClass::Int;
    }
    let body = text.strip_suffix(['u', 'U']);
    if let Some(digits) = body {
        return if !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit()) {
            NumberClass::Int
        } else {
            NumberClass::Malformed("the `u` suffix only applies to integer literals")
        };
    }
    let body = text.strip_suffix(['f', 'F']).unwrap_or(text);
    let (mantissa, exponent) = match body.find(['e', 'E']) {
        Some(i) => (&body[..i], Some(&body[i + 1..])),
        None => (body, None),
    };
    let dots = mantissa.bytes().filter(|&b| b == b'.').count();
    if dots > 1 {
        return NumberClass::Malformed("a number has at most one decimal point");
    }
    if !mantissa.bytes().all(|b| b.is_ascii_digit() || b == b'.')
        || !mantissa.bytes().any(|b| b.is_ascii_digit())
    {
        return NumberClass::Malformed("invalid character in number");
    }
    if let Some(exponent) = exponent {
        let digits = exponent.strip_prefix(['+', '-']).unwrap_or(exponent);
        if digits.is_empty() {
            return NumberClass::Malformed("exponent has no digits");
        }
        if !digits.bytes().all(|b| b.is_ascii_digit()) {
            return NumberClass::Malformed("invalid character in exponent");
        }
    }
    let is_float = dots == 1 || exponent.is_some() || body.len() != text.len();
    if is_float {
        NumberClass::Float
    } else if bytes.iter().all(u8::is_ascii_digit) {
        NumberClass::Int
    } else {
        NumberClass::Malformed("invalid character in number")
    }
}

/// The value of an integer literal's text (decimal or hexadecimal, optional `u` suffix); `None` when
/// it does not fit in 63 bits or is malformed.
pub fn int_value(text: &str) -> Option<i64> {
    let text = text.strip_suffix(['u', 'U']).unwrap_or(text);
    match text.strip_prefix("0x").or_else(|| text.strip_prefix("0X")) {
        Some(hex) => i64::from_str_radix(hex, 16).ok(),
        None => text.parse().ok(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_classified() {
        for int in ["0", "42", "0x1F", "0xffffffffu", "7u"] {
            assert_eq!(classify_number(int), NumberClass::Int, "{int}");
        }
        for float in ["1.", ".5", "1.5", "1e3", "1.5e-3", "2E+10", "3.0f", "1f", ".5e2"] {
            assert_eq!(classify_number(float), NumberClass::Float, "{float}");
        }
        for bad in ["1e", "1e+", "0x", "0xg", "1.2.3", "12abc", "1.5u", "1e5x"] {
            assert!(matches!(classify_number(bad), NumberClass::Malformed(_)), "{bad}");
        }
    }

    #[test]
    fn keywords_are_recognised() {
        assert!(TokenKind::Surface.is_keyword());
        assert!(TokenKind::Float4.is_keyword());
        assert!(!TokenKind::Ident.is_keyword());
        assert!(!TokenKind::Plus.is_keyword());
    }
}
