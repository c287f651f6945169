//! The generator of `generated.rs`: a well-typed surface shader (source text) as a deterministic
//! function of a string of choice bytes.
//!
//! Every decision reads one byte (`Choices::pick`); a byte string that runs out reads zeros, and
//! choice 0 is always the simplest option (a literal, no further statement, no loop), so
//! proptest's shrinking of the bytes (dropping them, moving them towards 0) shrinks the program.
//!
//! Types and rates are tracked so that every program is well typed by construction:
//! - every value has a type ([`Ty`]) and a rate ([`Rate`]); a store needs the value's rate and the
//!   rate of the conditions and loops around it at or below the variable's (RenderMan's uniform
//!   locals, Stanford's declared rates); per-light values (`L`, `Cl`) exist only inside
//!   `illuminance` (RenderMan, stored into varying variables) or as Stanford `perlight` locals
//!   summed with `integrate`;
//! - every value is *exact* or not ([`E::exact`]): exact values are computed only with operations
//!   both backends round identically (the "exact" rows of docs/numerics.md: `+ - * /`, `sqrt`,
//!   `floor`, `mix`, `min`, `length`, `normalize`, ...), from inputs and literals. Discontinuous
//!   operations (`floor`, `fract`, `mod`, `step`, comparisons, casts to `int`, `cellnoise`,
//!   `pulse`) take exact operands only: an operand carrying a transcendental's error of a few ulp
//!   could cross a discontinuity on one backend and not the other, which no tolerance can absorb.
//!   Conditions are therefore exact too, so both backends take the same branches.

use std::fmt::Write as _;

#[path = "expressions.rs"]
mod expressions;
#[path = "statements.rs"]
mod statements;

/// The choice bytes, read front to back; zeros once they run out.
pub struct Choices<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl Choices<'_> {
    /// One of `n` options, 0 the simplest.
    fn pick(&mut self, n: usize) -> usize {
        let b = self.bytes.get(self.at).copied().unwrap_or(0);
        self.at += 1;
        if n <= 1 { 0 } else { b as usize % n }
    }

    /// True with probability `num`/`den` (false once the bytes run out).
    fn chance(&mut self, num: usize, den: usize) -> bool {
        let b = self.bytes.get(self.at).copied().unwrap_or(0);
        self.at += 1;
        // Byte 0 is "no"; the others are spread over the den slots.
        b != 0 && (b as usize - 1) % den < num
    }
}

/// The two surface styles.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Style {
    RenderMan,
    Stanford,
}

/// The value types the generator uses.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Ty {
    Float,
    Color,
    Point,
    Vector,
    Normal,
    Float3,
    Int,
    Bool,
}

impl Ty {
    fn name(self) -> &'static str {
        match self {
            Ty::Float => "float",
            Ty::Color => "color",
            Ty::Point => "point",
            Ty::Vector => "vector",
            Ty::Normal => "normal",
            Ty::Float3 => "float3",
            Ty::Int => "int",
            Ty::Bool => "bool",
        }
    }

    fn triple(self) -> bool {
        matches!(self, Ty::Color | Ty::Point | Ty::Vector | Ty::Normal | Ty::Float3)
    }

    /// The float components of a value of this type.
    pub fn width(self) -> usize {
        if self.triple() { 3 } else { 1 }
    }
}

/// Rates, lowest first. `Perlight` is one value per bound light.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Debug)]
pub enum Rate {
    Constant,
    Uniform,
    Varying,
    Perlight,
}

/// A generated expression.
#[derive(Clone, Debug)]
struct E {
    s: String,
    rate: Rate,
    /// Computed by operations both backends round alike (see the module documentation).
    exact: bool,
}

impl E {
    fn lit(s: impl Into<String>) -> E {
        E { s: s.into(), rate: Rate::Constant, exact: true }
    }
}

/// A variable in scope.
#[derive(Clone, Debug)]
struct Var {
    name: String,
    ty: Ty,
    rate: Rate,
    exact: bool,
    writable: bool,
    /// The length of an array.
    len: Option<usize>,
}

/// A user function already written.
#[derive(Clone, Debug)]
struct Func {
    name: String,
    /// Each parameter's type and whether the body treats it as exact (callers pass exact values).
    params: Vec<(Ty, bool)>,
    /// The `output float` parameter, if any (always last), exact when the function is.
    output: bool,
    ret: Ty,
    exact: bool,
}

/// A parameter of the generated surface: what the runner feeds it.
#[derive(Clone, Debug)]
pub struct Param {
    /// Its name.
    pub name: String,
    /// Its default (components), used when `defaulted`.
    pub default: Vec<f64>,
    /// Whether the runner leaves it at its default (the interpreter evaluates the default; the
    /// kernel, which has no defaults, is given the same values).
    pub defaulted: bool,
}

/// A generated program (its `Debug` form is its source, which is what a failure shows).
#[derive(Clone)]
pub struct Program {
    /// The source: the surface first, then its lights.
    pub source: String,
    /// The surface's parameters.
    pub params: Vec<Param>,
    /// The outputs to compare, with whether each of their components is exact (see the module
    /// documentation).
    pub outputs: Vec<(String, Vec<bool>)>,
    /// How many lights to bind (1 to 3).
    pub lights: usize,
}

impl Program {
    /// A program written by hand (or a generated one edited): its outputs are found in the
    /// source (`output varying` parameters and `Ci`, or a Stanford result) and marked exact, so
    /// that the summary's largest error on exact outputs covers them all; every parameter is fed.
    pub fn from_source(source: String) -> Program {
        let style = if source.contains("surface shader") { Style::Stanford } else { Style::RenderMan };
        let lights = source.matches("\nlight ").count() + usize::from(source.starts_with("light "));
        let mut outputs = Vec::new();
        let words = |ty: &str| if ty == "float" { 1 } else { 3 };
        for decl in source.split(['(', ';', ',']).map(str::trim) {
            let parts: Vec<&str> = decl.split_whitespace().collect();
            if parts.len() >= 4 && parts[0] == "output" && parts[1] == "varying" {
                outputs.push((parts[3].to_string(), vec![true; words(parts[2])]));
            }
        }
        match style {
            Style::RenderMan if source.contains("Ci =") => outputs.push(("Ci".into(), vec![true; 3])),
            Style::RenderMan => {}
            Style::Stanford => outputs.push(("result".into(), vec![true; 4])),
        }
        Program { source, params: Vec::new(), outputs, lights }
    }
}

impl std::fmt::Debug for Program {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        writeln!(f, "{} light(s) bound; source:", self.lights)?;
        for (i, line) in self.source.lines().enumerate() {
            writeln!(f, "{:4} | {line}", i + 1)?;
        }
        Ok(())
    }
}

const FLOATS: &[&str] = &["1", "0.5", "2", "0.25", "3", "1.5", "0.75", "-1", "0.125", "-0.5", "4", "0.3"];

struct Gen<'a> {
    c: Choices<'a>,
    style: Style,
    scopes: Vec<Vec<Var>>,
    next: usize,
    /// The highest rate of the conditions and loops around the statement being written.
    control: Rate,
    /// Inside `illuminance` (RenderMan): `L` and `Cl` exist.
    in_light: bool,
    /// Inside a user function: its result type and whether its returns must be exact.
    in_func: Option<(Ty, bool)>,
    funcs: Vec<Func>,
    /// The rates of the loops around the statement, innermost last (a `break` or `continue` may
    /// depend only on values of the innermost loop's rate, or it would raise the loop's rate).
    loops: Vec<Rate>,
    /// Statements written so far (a budget keeps programs small).
    statements: usize,
    includes: [bool; 3],
    /// Inside an operand of `?:`, `&&` or `||` when non-zero.
    conditional: u32,
    out: String,
    indent: usize,
}

/// The generated program for `bytes`.
pub fn generate(bytes: &[u8]) -> Program {
    let mut c = Choices { bytes, at: 0 };
    let style = if c.pick(2) == 0 { Style::RenderMan } else { Style::Stanford };
    let lights = 1 + c.pick(3);
    let mut g = Gen {
        c,
        style,
        scopes: vec![Vec::new()],
        next: 0,
        control: Rate::Constant,
        in_light: false,
        in_func: None,
        funcs: Vec::new(),
        loops: Vec::new(),
        statements: 0,
        includes: [false; 3],
        conditional: 0,
        out: String::new(),
        indent: 1,
    };
    let mut functions = String::new();
    for _ in 0..g.c.pick(3) {
        functions.push_str(&g.function());
    }
    let (signature, params, outputs) = g.surface();
    let mut source = String::new();
    for (used, name) in g.includes.iter().zip(["noise", "fractal", "pattern"]) {
        if *used {
            writeln!(source, "#include <{name}.sl>").unwrap();
        }
    }
    source.push_str(&functions);
    source.push_str(&signature);
    source.push_str(&light_shaders(lights));
    Program { source, params, outputs, lights }
}

/// The bound lights' shaders (for the render path's module; the compute kernel reads the lights'
/// `L` and `Cl` as inputs). RenderMan lights for both styles: Stanford-style light shaders cannot
/// be bound on the GPU yet (`wgsl::compile` says so).
fn light_shaders(n: usize) -> String {
    let mut s = String::new();
    for k in 0..n {
        s.push_str(match k {
            0 => {
                "light gen_point(float intensity = 1; color lightcolor = color(1, 0.5, 0.25);\n    \
                 point from = point(1, 2, -3))\n{\n    illuminate(from) { Cl = intensity * lightcolor / (L . L); }\n}\n"
            }
            1 => {
                "light gen_distant(float intensity = 1; color lightcolor = 1; vector dir = vector(0, -1, 1))\n{\n    \
                 solar(dir, 0) { Cl = intensity * lightcolor; }\n}\n"
            }
            _ => {
                "light gen_spot(float intensity = 2; point from = point(-1, 1, -2))\n{\n    \
                 illuminate(from, vector(1, -1, 2), 0.5) { Cl = intensity * color(0.5, 1, 0.75) / (L . L); }\n}\n"
            }
        });
    }
    s
}

impl Gen<'_> {
    fn fresh(&mut self, prefix: &str) -> String {
        self.next += 1;
        format!("{prefix}{}", self.next)
    }

    fn line(&mut self, text: &str) {
        for _ in 0..self.indent {
            self.out.push_str("    ");
        }
        self.out.push_str(text);
        self.out.push('\n');
    }

    fn declare(&mut self, v: Var) {
        self.scopes.last_mut().expect("a scope").push(v);
    }

    fn vars(&self) -> impl Iterator<Item = &Var> {
        self.scopes.iter().flatten()
    }

    /// The highest rate an expression stored into `v` may have here.
    fn store_rate(&self, v: &Var) -> Rate {
        if self.style == Style::RenderMan && self.in_light && v.rate == Rate::Varying {
            Rate::Perlight
        } else {
            v.rate
        }
    }

    fn float_lit(&mut self) -> String {
        FLOATS[self.c.pick(FLOATS.len())].to_string()
    }

    /// A literal of `ty`.
    fn literal(&mut self, ty: Ty) -> E {
        match ty {
            Ty::Float => E::lit(self.float_lit()),
            Ty::Int => E::lit(["1", "0", "2", "3", "-2", "7"][self.c.pick(6)]),
            Ty::Bool => E::lit(["true", "false"][self.c.pick(2)]),
            _ => {
                let parts: Vec<String> = (0..3).map(|_| self.float_lit()).collect();
                E::lit(self.construct(ty, &parts))
            }
        }
    }

    /// A triple built from three component texts.
    fn construct(&self, ty: Ty, parts: &[String]) -> String {
        match self.style {
            Style::Stanford => format!("{{{}}}", parts.join(", ")),
            Style::RenderMan => format!("{}({})", ty.name(), parts.join(", ")),
        }
    }

    /// A variable of `ty` usable under the constraints, if any.
    fn variable(&mut self, ty: Ty, max: Rate, exact: bool) -> Option<E> {
        let found: Vec<Var> = self
            .vars()
            .filter(|v| v.ty == ty && v.rate <= max && (v.exact || !exact) && v.len.is_none())
            .cloned()
            .collect();
        if found.is_empty() {
            return None;
        }
        let v = &found[self.c.pick(found.len())];
        Some(E { s: v.name.clone(), rate: v.rate, exact: v.exact })
    }

    /// The predefined variables of `ty` (surface body only).
    fn predefined(&self, ty: Ty) -> Vec<(&'static str, Rate, bool)> {
        if self.in_func.is_some() {
            return Vec::new();
        }
        let v = Rate::Varying;
        match (self.style, ty) {
            (Style::RenderMan, Ty::Float) => vec![("s", v, true), ("t", v, true), ("u", v, true)],
            (Style::RenderMan, Ty::Point) => vec![("P", v, true)],
            (Style::RenderMan, Ty::Normal) => vec![("N", v, true)],
            (Style::RenderMan, Ty::Vector) if self.in_light => {
                vec![("I", v, true), ("L", Rate::Perlight, false)]
            }
            (Style::RenderMan, Ty::Vector) => vec![("I", v, true)],
            (Style::RenderMan, Ty::Color) if self.in_light => {
                vec![("Cs", v, true), ("Cl", Rate::Perlight, false)]
            }
            (Style::RenderMan, Ty::Color) => vec![("Cs", v, true)],
            (Style::Stanford, Ty::Float3) => {
                vec![
                    ("N", v, true),
                    ("E", v, true),
                    ("L", Rate::Perlight, false),
                    ("rgb(Cl)", Rate::Perlight, false),
                ]
            }
            _ => Vec::new(),
        }
    }

    /// A leaf of `ty`: a variable, a predefined variable or a literal.
    fn leaf(&mut self, ty: Ty, max: Rate, exact: bool) -> E {
        match self.c.pick(4) {
            1 | 2 => {
                if let Some(e) = self.variable(ty, max, exact) {
                    return e;
                }
            }
            3 => {
                let pre: Vec<_> =
                    self.predefined(ty).into_iter().filter(|(_, r, x)| *r <= max && (*x || !exact)).collect();
                if !pre.is_empty() {
                    let (name, rate, x) = pre[self.c.pick(pre.len())];
                    return E { s: name.to_string(), rate, exact: x };
                }
            }
            _ => {}
        }
        self.literal(ty)
    }
}

/// `text` as the operand of a postfix `[k]`: a name as it is, anything else in parentheses (so
/// that `color(1, 2, 3)[0]` is not read as a cast of `(1, 2, 3)[0]`).
fn operand(text: &str) -> String {
    if text.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
        text.to_string()
    } else {
        format!("({text})")
    }
}
