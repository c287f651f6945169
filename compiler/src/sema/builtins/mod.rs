//! Built-in functions: their overloads, written as signatures the way the RenderMan and Stanford
//! specifications print them, parsed once into [`Builtin`] records.
//!
//! Each line of `table::SIGNATURES` is one overload, or a family of them:
//!
//! ```text
//! [for T in TYPE|TYPE|...:] RET NAME(PARAM, PARAM, ...) [attr, attr]
//! ```
//!
//! A parameter is `[output] TYPE`, `TYPE[]` for an array of any length, or `TYPE...` for any number
//! (zero or more) of further arguments of that type; `T` stands for each type of the `for` list in
//! turn. `@numeric` abbreviates `float|color|point|vector|normal|float3|float4` and `@triple`
//! `color|point|vector|normal|float3`. Attributes say how the result's rate is decided (see
//! [`RateRule`]) and where the function may be used (see [`Context`]). The records, like the ids,
//! are the IR's (`ir/builtin.rs`); this module owns the table and the lookups.

mod table;

use std::sync::OnceLock;

use rustc_hash::FxHashMap;

use crate::ir::builtin::{Builtin, BuiltinId, BuiltinParam, Context, RateRule};
use crate::ir::types::{Base, Type};

/// All built-ins, by name.
#[derive(Debug, Default)]
pub struct Builtins {
    by_name: FxHashMap<&'static str, Vec<Builtin>>,
}

impl Builtins {
    /// The overloads of `name` (empty if there is no such built-in).
    pub fn overloads(&self, name: &str) -> &[Builtin] {
        self.by_name.get(name).map_or(&[], Vec::as_slice)
    }

    /// Every built-in name.
    pub fn names(&self) -> impl Iterator<Item = &'static str> + '_ {
        self.by_name.keys().copied()
    }
}

/// The optional `"name", value` arguments a built-in accepts after its positional ones (RI 3.2,
/// section 15.7), each with whether its value is a string (`"filter"`) rather than a float; `None`
/// for a built-in that takes none.
pub fn options(id: BuiltinId) -> Option<&'static [(&'static str, bool)]> {
    const TEXTURE: &[(&str, bool)] = &[
        ("blur", false),
        ("width", false),
        ("swidth", false),
        ("twidth", false),
        ("samples", false),
        ("fill", false),
        ("filter", true),
    ];
    const SHADOW: &[(&str, bool)] = &[
        ("blur", false),
        ("width", false),
        ("swidth", false),
        ("twidth", false),
        ("samples", false),
        ("bias", false),
    ];
    match id {
        BuiltinId::Texture | BuiltinId::Environment => Some(TEXTURE),
        BuiltinId::Shadow => Some(SHADOW),
        _ => None,
    }
}

/// The options of [`options`] that some backend implements for `id`; a call naming any other is
/// warned about (E0405). The passes that implement an option read it from the call's arguments
/// after the positional ones (`opt/textures.rs`, `opt/shadow.rs`): update this table with them.
pub fn honoured_options(id: BuiltinId) -> &'static [&'static str] {
    match id {
        BuiltinId::Environment => &["blur", "width"],
        BuiltinId::Shadow => &["samples", "blur", "bias", "width"],
        _ => &[],
    }
}

/// One value `printf` or `format` prints.
#[derive(Clone, Debug, PartialEq)]
pub enum PrintValue {
    /// A number or the components of a point, colour or matrix.
    Numbers(Vec<f64>),
    /// A string.
    Text(String),
}

/// The conversions of a `printf` format, in order (`%%` is none): `f`, `g`, `e`, `d`, `i` print a
/// number, `p`, `v`, `n`, `c` a triple, `m` a matrix, `s` a string. Flags, width and precision
/// (`%5.2f`) are accepted and skipped. An unknown conversion character is returned as it is.
pub fn printf_conversions(format: &str) -> Vec<char> {
    let mut out = Vec::new();
    let mut chars = format.chars();
    while let Some(c) = chars.next() {
        if c != '%' {
            continue;
        }
        let conv = chars.by_ref().find(|c| !matches!(c, '0'..='9' | '.' | '-' | '+' | ' ' | '#'));
        match conv {
            Some('%') | None => {}
            Some(c) => out.push(c),
        }
    }
    out
}

/// `format` applied to `values` (one per conversion of [`printf_conversions`]): numbers print with
/// six decimals as C's `%f` does, `%d` rounds toward zero, triples and matrices print their
/// components separated by spaces.
pub fn printf_format(format: &str, values: &[PrintValue]) -> String {
    let mut out = String::new();
    let mut values = values.iter();
    let mut chars = format.chars().peekable();
    while let Some(c) = chars.next() {
        if c != '%' {
            out.push(c);
            continue;
        }
        let mut spec = String::new();
        while let Some(&d) = chars.peek() {
            if !matches!(d, '0'..='9' | '.' | '-' | '+' | ' ' | '#') {
                break;
            }
            spec.push(d);
            chars.next();
        }
        let precision = spec.split_once('.').and_then(|(_, p)| p.parse::<usize>().ok()).unwrap_or(6);
        match chars.next() {
            Some('%') => out.push('%'),
            None => out.push('%'),
            Some(conv) => match values.next() {
                Some(PrintValue::Text(s)) => out.push_str(s),
                Some(PrintValue::Numbers(xs)) => {
                    let parts: Vec<String> = xs
                        .iter()
                        .map(|x| match conv {
                            'd' | 'i' => format!("{}", x.trunc() as i64),
                            'e' => format!("{x:.precision$e}"),
                            'g' => format!("{x}"),
                            _ => format!("{x:.precision$}"),
                        })
                        .collect();
                    out.push_str(&parts.join(" "));
                }
                None => {}
            },
        }
    }
    out
}

/// The built-in table, parsed on first use.
pub fn builtins() -> &'static Builtins {
    static TABLE: OnceLock<Builtins> = OnceLock::new();
    TABLE.get_or_init(|| {
        let mut by_name: FxHashMap<&'static str, Vec<Builtin>> = FxHashMap::default();
        for line in table::SIGNATURES {
            for b in parse_line(line).unwrap_or_else(|e| panic!("built-in table: {e} in `{line}`")) {
                by_name.entry(b.name()).or_default().push(b);
            }
        }
        Builtins { by_name }
    })
}

/// The overload of `id` whose parameters are exactly `params` (no conversions): for later stages
/// that build calls themselves. An array parameter of any length (`T[]`) takes any array of `T`,
/// and a variadic overload takes any number of further arguments of its type.
pub fn find(id: BuiltinId, params: &[Type]) -> Option<&'static Builtin> {
    let fits = |want: Type, got: Type| {
        want == got || (want.array == Some(0) && got.array.is_some() && want.base == got.base)
    };
    builtins().overloads(id.name()).iter().find(|b| {
        b.accepts_count(params.len())
            && params.iter().enumerate().all(|(i, &got)| b.param_type(i).is_some_and(|p| fits(p.ty, got)))
    })
}

fn base_named(name: &str) -> Option<Base> {
    Some(match name {
        "void" => Base::Void,
        "bool" => Base::Bool,
        "int" => Base::Int,
        "uint" => Base::Uint,
        "float" => Base::Float,
        "clampf" => Base::Clampf,
        "color" => Base::Color,
        "point" => Base::Point,
        "vector" => Base::Vector,
        "normal" => Base::Normal,
        "float3" => Base::Float3,
        "float4" => Base::Float4,
        "matrix3" => Base::Matrix3,
        "matrix" | "matrix4" => Base::Matrix4,
        "string" => Base::String,
        "texref" => Base::Texref,
        _ => return None,
    })
}

fn expand_set(list: &str) -> Vec<&str> {
    list.split('|')
        .flat_map(|t| match t.trim() {
            "@numeric" => vec!["float", "color", "point", "vector", "normal", "float3", "float4"],
            "@triple" => vec!["color", "point", "vector", "normal", "float3"],
            other => vec![other],
        })
        .collect()
}

/// Replaces the whole word `word` (not parts of longer names) in `text`.
fn replace_word(text: &str, word: &str, with: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(i) = rest.find(word) {
        let before = rest[..i].chars().next_back();
        let after = rest[i + word.len()..].chars().next();
        let is_word = |c: Option<char>| c.is_some_and(|c| c.is_alphanumeric() || c == '_');
        out.push_str(&rest[..i]);
        out.push_str(if is_word(before) || is_word(after) { word } else { with });
        rest = &rest[i + word.len()..];
    }
    out.push_str(rest);
    out
}

/// Parses one table line into its overloads.
fn parse_line(line: &'static str) -> Result<Vec<Builtin>, String> {
    let (generic, sig) = match line.strip_prefix("for T in ") {
        Some(rest) => {
            let (list, sig) = rest.split_once(':').ok_or("missing `:` after the type list")?;
            (expand_set(list), sig.trim())
        }
        None => (vec![""], line.trim()),
    };
    // Attributes follow the parameter list: `(...) [a, b]`.
    let close = sig.rfind(')').ok_or("missing `)`")?;
    let (sig, attrs) = match sig[close..].find('[') {
        Some(i) => (sig[..close + i].trim(), sig[close + i + 1..].trim_end().trim_end_matches(']')),
        None => (sig, ""),
    };
    let mut rate = RateRule::Max;
    let mut context = Context::Any;
    for attr in attrs.split(',').map(str::trim).filter(|a| !a.is_empty()) {
        match attr {
            "deriv" => rate = RateRule::Derivative,
            "fragment" => rate = RateRule::Fragment,
            "uniform" => rate = RateRule::Uniform,
            "lights" => rate = RateRule::Lights,
            "integrate" => rate = RateRule::Integrate,
            "surface" => context = Context::Surface,
            "light" => context = Context::Light,
            "light_or_volume" => context = Context::LightOrVolume,
            "illuminance" => context = Context::Illuminance,
            other => return Err(format!("unknown attribute `{other}`")),
        }
    }
    let open = sig.find('(').ok_or("missing `(`")?;
    let close = sig.rfind(')').ok_or("missing `)`")?;
    let head: Vec<&str> = sig[..open].split_whitespace().collect();
    let [ret, name] = head.as_slice() else { return Err("expected `RET NAME(`".into()) };
    let id = BuiltinId::from_name(name).ok_or_else(|| format!("`{name}` has no `BuiltinId`"))?;
    let params_text = sig[open + 1..close].trim();
    let mut out = Vec::new();
    for t in generic {
        let resolve = |word: &str| -> Result<Base, String> {
            let word = if word == "T" { t } else { word };
            base_named(word).ok_or_else(|| format!("unknown type `{word}`"))
        };
        let mut params = Vec::new();
        let mut rest = None;
        if !params_text.is_empty() {
            for p in params_text.split(',').map(str::trim) {
                let (output, p) = match p.strip_prefix("output ") {
                    Some(p) => (true, p.trim()),
                    None => (false, p),
                };
                if let Some(variadic) = p.strip_suffix("...") {
                    rest = Some(Type::of(resolve(variadic.trim())?));
                } else if let Some(elem) = p.strip_suffix("[]") {
                    params.push(BuiltinParam {
                        ty: Type { base: resolve(elem.trim())?, array: Some(0) },
                        output,
                    });
                } else {
                    params.push(BuiltinParam { ty: Type::of(resolve(p)?), output });
                }
            }
        }
        let signature = if t.is_empty() { sig.to_string() } else { replace_word(sig, "T", t) };
        out.push(Builtin { id, ret: Type::of(resolve(ret)?), params, rest, rate, context, signature });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_parses() {
        let table = builtins();
        assert!(table.overloads("sin").iter().any(|b| b.params.len() == 1 && b.ret == Type::FLOAT));
        let mix: Vec<String> = table.overloads("mix").iter().map(|b| b.ret.to_string()).collect();
        assert!(mix.contains(&"color".to_string()) && mix.contains(&"float4".to_string()), "{mix:?}");
        let du = &table.overloads("Du")[0];
        assert_eq!(du.rate, RateRule::Derivative);
    }

    #[test]
    fn find_matches_parameter_types_exactly() {
        let (float, color, point) = (Type::FLOAT, Type::of(Base::Color), Type::of(Base::Point));
        assert_eq!(find(BuiltinId::Mix, &[color, color, float]).map(|b| b.ret), Some(color));
        assert!(find(BuiltinId::Mix, &[color, color, color]).is_none(), "no conversions");
        assert_eq!(find(BuiltinId::Min, &[float, float, float, float]).map(|b| b.ret), Some(float));
        let knots = Type { base: Base::Vector, array: Some(4) };
        assert_eq!(find(BuiltinId::Spline, &[float, knots]).map(|b| b.ret), Some(Type::of(Base::Vector)));
        assert_eq!(find(BuiltinId::Transform, &[Type::STRING, point]).map(|b| b.ret), Some(point));
        assert!(find(BuiltinId::Mix, &[]).is_none());
    }

    #[test]
    fn lines_parse_into_overloads() {
        let b = parse_line("for T in float|color: T spline(float, T, T, T, T, T...) [deriv]").unwrap();
        assert_eq!(b.len(), 2);
        assert_eq!(b[1].ret, Type::of(Base::Color));
        assert_eq!(b[1].params.len(), 5);
        assert_eq!(b[1].rest, Some(Type::of(Base::Color)));
        assert!(b[1].accepts_count(7) && !b[1].accepts_count(4));
        assert_eq!(b[1].signature, "color spline(float, color, color, color, color, color...)");
        let f = parse_line("void fresnel(vector, normal, float, output float, output float)").unwrap();
        assert!(f[0].params[3].output && !f[0].params[2].output);
        let a = parse_line("float spline(float, float[])").unwrap();
        assert_eq!(a[0].params[1].ty.array, Some(0));
        assert!(parse_line("float nope(flot)").is_err());
    }

    #[test]
    fn every_table_name_has_an_id_and_back() {
        let table = builtins();
        for name in table.names() {
            let id = BuiltinId::from_name(name).unwrap_or_else(|| panic!("`{name}` has no BuiltinId"));
            assert_eq!(id.name(), name);
            assert!(table.overloads(name).iter().all(|b| b.id == id), "`{name}`'s overloads carry its id");
        }
        for &id in BuiltinId::ALL {
            assert!(!table.overloads(id.name()).is_empty(), "`{id}` is in no line of the table");
            assert_eq!(BuiltinId::from_name(id.name()), Some(id));
        }
        assert_eq!(table.names().count(), BuiltinId::ALL.len());
        assert_eq!(BuiltinId::from_name("trace"), None);
    }
}
