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
    #[token("surface")]
    Surface,
    #[token("light")]
    Light,
    #[token("displacement")]
    Displacement,
    #[token("volume")]
    Volume,
    #[token("imager")]
    Imager,
    #[token("shader")]
    Shader,

    // Keywords: qualifiers.
    #[token("uniform")]
    Uniform,
    #[token("varying")]
    Varying,
    #[token("output")]
    Output,
    #[token("extern")]
    Extern,
    #[token("constant")]
    Constant,
    #[token("vertex")]
    Vertex,
    #[token("fragment")]
    Fragment,
    #[token("perlight")]
    Perlight,
    /// `primitive group`, the Stanford rate, as one token.
    #[regex(r"primitive[ \t\r\n]+group")]
    PrimitiveGroup,
    /// `primitive` not followed by `group`: only ever an error.
    #[token("primitive")]
    Primitive,

    // Keywords: types.
    #[token("float")]
    Float,
    #[token("color")]
    Color,
    #[token("point")]
    Point,
    #[token("vector")]
    Vector,
    #[token("normal")]
    Normal,
    #[token("matrix")]
    Matrix,
    #[token("string")]
    String,
    #[token("void")]
    Void,
    #[token("float3")]
    Float3,
    #[token("float4")]
    Float4,
    #[token("matrix3")]
    Matrix3,
    #[token("matrix4")]
    Matrix4,
    #[token("bool")]
    Bool,
    #[token("texref")]
    Texref,
    #[token("clampf")]
    Clampf,
    #[token("int")]
    Int,
    #[token("uint")]
    Uint,

    // Keywords: statements and literals.
    #[token("if")]
    If,
    #[token("else")]
    Else,
    #[token("for")]
    For,
    #[token("while")]
    While,
    #[token("break")]
    Break,
    #[token("continue")]
    Continue,
    #[token("return")]
    Return,
    #[token("illuminance")]
    Illuminance,
    #[token("illuminate")]
    Illuminate,
    #[token("solar")]
    Solar,
    #[token("gather")]
    Gather,
    #[token("true")]
    True,
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
    #[token("{")]
    LBrace,
    #[token("}")]
    RBrace,
    #[token("(")]
    LParen,
    #[token(")")]
    RParen,
    #[token("[")]
    LBracket,
    #[token("]")]
    RBracket,
    #[token(";")]
    Semi,
    #[token(",")]
    Comma,
    #[token(".")]
    Dot,
    #[token("?")]
    Question,
    #[token(":")]
    Colon,
    #[token("+")]
    Plus,
    #[token("-")]
    Minus,
    #[token("*")]
    Star,
    #[token("/")]
    Slash,
    #[token("%")]
    Percent,
    #[token("^")]
    Caret,
    #[token("&")]
    Amp,
    #[token("|")]
    Pipe,
    #[token("~")]
    Tilde,
    #[token("!")]
    Bang,
    #[token("<")]
    Lt,
    #[token(">")]
    Gt,
    #[token("<=")]
    Le,
    #[token(">=")]
    Ge,
    #[token("==")]
    EqEq,
    #[token("!=")]
    Ne,
    #[token("&&")]
    AndAnd,
    #[token("||")]
    OrOr,
    #[token("<<")]
    Shl,
    #[token(">>")]
    Shr,
    #[token("=")]
    Eq,
    #[token("+=")]
    PlusEq,
    #[token("-=")]
    MinusEq,
    #[token("*=")]
    StarEq,
    #[token("/=")]
    SlashEq,
    #[token("%=")]
    PercentEq,
    #[token("&=")]
    AmpEq,
    #[token("|=")]
    PipeEq,
    #[token("^=")]
    CaretEq,
    #[token("<<=")]
    ShlEq,
    #[token(">>=")]
    ShrEq,
    #[token("++")]
    PlusPlus,
    #[token("--")]
    MinusMinus,
    #[token("#")]
    Hash,
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
