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

    /// An expression of `ty` whose rate is at most `max` (exact if `exact`), `depth` levels deep
    /// at most.
    fn expr(&mut self, ty: Ty, max: Rate, exact: bool, depth: u32) -> E {
        if depth == 0 {
            return self.leaf(ty, max, exact);
        }
        let d = depth - 1;
        match ty {
            Ty::Float => self.float_expr(max, exact, d),
            Ty::Int => self.int_expr(max, d),
            Ty::Bool => self.bool_expr(max, d),
            _ => self.triple_expr(ty, max, exact, d),
        }
    }

    fn join(op: impl FnOnce(&[String]) -> String, parts: &[E]) -> E {
        let texts: Vec<String> = parts.iter().map(|e| e.s.clone()).collect();
        E {
            s: op(&texts),
            rate: parts.iter().map(|e| e.rate).max().unwrap_or(Rate::Constant),
            exact: parts.iter().all(|e| e.exact),
        }
    }

    /// `e` marked inexact (a transcendental, a light sum, a library function).
    fn inexact(mut e: E) -> E {
        e.exact = false;
        e
    }

    fn float_expr(&mut self, max: Rate, exact: bool, d: u32) -> E {
        let f = Ty::Float;
        match self.c.pick(20) {
            1 => {
                let op = ["+", "-", "*"][self.c.pick(3)];
                let (a, b) = (self.expr(f, max, exact, d), self.expr(f, max, exact, d));
                Self::join(|t| format!("({} {op} {})", t[0], t[1]), &[a, b])
            }
            2 => {
                let (a, b) = (self.expr(f, max, exact, d), self.expr(f, max, exact, d));
                Self::join(|t| format!("({} / (abs({}) + 0.5))", t[0], t[1]), &[a, b])
            }
            3 => {
                let a = self.expr(f, max, exact, d);
                Self::join(|t| format!("-({})", t[0]), &[a])
            }
            4 => {
                let ty = self.triple_ty();
                let v = self.expr(ty, max, exact, d);
                let k = self.c.pick(3);
                match (self.style, ty, self.c.pick(2)) {
                    (Style::RenderMan, Ty::Point | Ty::Vector | Ty::Normal, 1) => {
                        Self::join(|t| format!("{}comp({})", ["x", "y", "z"][k], t[0]), &[v])
                    }
                    (Style::RenderMan, Ty::Color, 1) => Self::join(|t| format!("comp({}, {k})", t[0]), &[v]),
                    _ => Self::join(|t| format!("{}[{k}]", operand(&t[0])), &[v]),
                }
            }
            5 => {
                let ty = self.geometric_ty();
                let (a, b) = (self.expr(ty, max, exact, d), self.expr(ty, max, exact, d));
                match self.style {
                    Style::RenderMan => Self::join(|t| format!("({} . {})", t[0], t[1]), &[a, b]),
                    Style::Stanford => Self::join(|t| format!("dot({}, {})", t[0], t[1]), &[a, b]),
                }
            }
            6 => {
                let ty = self.geometric_ty();
                let a = self.expr(ty, max, exact, d);
                Self::join(|t| format!("length({})", t[0]), &[a])
            }
            7 => {
                let a = self.expr(f, max, exact, d);
                let name = ["abs", "sqrt(abs", "sin(clamp", "cos(clamp", "exp(clamp"][self.c.pick(5)];
                let e = match name {
                    "abs" => Self::join(|t| format!("abs({})", t[0]), &[a]),
                    "sqrt(abs" => Self::join(|t| format!("sqrt(abs({}))", t[0]), &[a]),
                    _ => Self::inexact(Self::join(|t| format!("{name}({}, -8, 8))", t[0]), &[a])),
                };
                if exact && !e.exact { self.leaf(f, max, exact) } else { e }
            }
            8 => {
                let parts =
                    [self.expr(f, max, exact, d), self.expr(f, max, exact, d), self.expr(f, max, exact, d)];
                match self.c.pick(3) {
                    0 => Self::join(|t| format!("mix({}, {}, {})", t[0], t[1], t[2]), &parts),
                    1 => Self::join(|t| format!("clamp({}, -1, {})", t[0], t[1]), &parts[..2]),
                    _ => {
                        let name = ["min", "max"][self.c.pick(2)];
                        Self::join(|t| format!("{name}({}, {})", t[0], t[1]), &parts[..2])
                    }
                }
            }
            9 => {
                let a = self.expr(f, max, exact, d);
                Self::join(|t| format!("smoothstep(-1, 1.5, {})", t[0]), &[a])
            }
            10 => {
                // Discontinuous: exact operands only.
                let (a, b) = (self.expr(f, max, true, d), self.expr(f, max, true, d));
                match self.c.pick(4) {
                    0 => Self::join(|t| format!("floor({})", t[0]), &[a]),
                    1 => Self::join(|t| format!("mod({}, 1)", t[0]), &[a]),
                    2 => Self::join(|t| format!("mod({}, abs({}) + 0.5)", t[0], t[1]), &[a, b]),
                    _ => Self::join(|t| format!("step({}, {})", t[0], t[1]), &[a, b]),
                }
            }
            11 => {
                let (cond, a, b) = self.conditional(|g| {
                    (g.expr(Ty::Bool, max, true, d), g.expr(f, max, exact, d), g.expr(f, max, exact, d))
                });
                Self::join(|t| format!("({} ? {} : {})", t[0], t[1], t[2]), &[cond, a, b])
            }
            12 => {
                let i = self.expr(Ty::Int, max, true, d);
                Self::join(|t| format!("float({})", t[0]), &[i])
            }
            13 => self.call(f, max, exact, d),
            14 if !exact => self.library(max, d),
            15 => self.integrate(f, max, exact, d),
            16 => self.element(max, exact, d),
            _ => self.leaf(f, max, exact),
        }
    }

    fn int_expr(&mut self, max: Rate, d: u32) -> E {
        let i = Ty::Int;
        match self.c.pick(6) {
            1 => {
                let op = ["+", "-", "*", "/", "%"][self.c.pick(5)];
                let (a, b) = (self.expr(i, max, true, d), self.expr(i, max, true, d));
                Self::join(|t| format!("({} {op} {})", t[0], t[1]), &[a, b])
            }
            2 => {
                let a = self.expr(Ty::Float, max, true, d);
                Self::join(|t| format!("int(clamp({}, -64, 64))", t[0]), &[a])
            }
            3 => {
                let (cond, a, b) = self.conditional(|g| {
                    (g.expr(Ty::Bool, max, true, d), g.expr(i, max, true, d), g.expr(i, max, true, d))
                });
                Self::join(|t| format!("({} ? {} : {})", t[0], t[1], t[2]), &[cond, a, b])
            }
            4 => {
                let (a, b) = (self.expr(i, max, true, d), self.expr(i, max, true, d));
                Self::join(|t| format!("max({}, {})", t[0], t[1]), &[a, b])
            }
            _ => self.leaf(i, max, true),
        }
    }

    fn bool_expr(&mut self, max: Rate, d: u32) -> E {
        match self.c.pick(6) {
            1 | 2 => {
                let ty = if self.c.pick(3) == 0 { Ty::Int } else { Ty::Float };
                let op = ["<", ">", "<=", ">=", "==", "!="][self.c.pick(6)];
                let (a, b) = (self.expr(ty, max, true, d), self.expr(ty, max, true, d));
                Self::join(|t| format!("{} {op} {}", t[0], t[1]), &[a, b])
            }
            3 => {
                let op = ["&&", "||"][self.c.pick(2)];
                let (a, b) =
                    self.conditional(|g| (g.expr(Ty::Bool, max, true, d), g.expr(Ty::Bool, max, true, d)));
                Self::join(|t| format!("({} {op} {})", t[0], t[1]), &[a, b])
            }
            4 => {
                let a = self.expr(Ty::Bool, max, true, d);
                Self::join(|t| format!("!({})", t[0]), &[a])
            }
            _ => self.leaf(Ty::Bool, max, true),
        }
    }

    /// A triple type of this style.
    fn triple_ty(&mut self) -> Ty {
        match self.style {
            Style::Stanford => Ty::Float3,
            Style::RenderMan => [Ty::Color, Ty::Point, Ty::Vector, Ty::Normal][self.c.pick(4)],
        }
    }

    /// A type with a dot product, length and cross product.
    fn geometric_ty(&mut self) -> Ty {
        match self.style {
            Style::Stanford => Ty::Float3,
            Style::RenderMan => [Ty::Vector, Ty::Normal][self.c.pick(2)],
        }
    }

    fn triple_expr(&mut self, ty: Ty, max: Rate, exact: bool, d: u32) -> E {
        let f = Ty::Float;
        match self.c.pick(15) {
            1 => {
                // `point - point` is a vector: points only add and scale.
                let ops: &[&str] = if ty == Ty::Point { &["+", "*"] } else { &["+", "-", "*"] };
                let op = ops[self.c.pick(ops.len())];
                let (a, b) = (self.expr(ty, max, exact, d), self.expr(ty, max, exact, d));
                Self::join(|t| format!("({} {op} {})", t[0], t[1]), &[a, b])
            }
            2 => {
                let (a, k) = (self.expr(ty, max, exact, d), self.expr(f, max, exact, d));
                match self.c.pick(3) {
                    0 => Self::join(|t| format!("({} * {})", t[0], t[1]), &[a, k]),
                    1 => Self::join(|t| format!("({} * {})", t[1], t[0]), &[a, k]),
                    _ => Self::join(|t| format!("({} / (abs({}) + 0.5))", t[0], t[1]), &[a, k]),
                }
            }
            3 => {
                let parts =
                    [self.expr(f, max, exact, d), self.expr(f, max, exact, d), self.expr(f, max, exact, d)];
                let texts: Vec<String> = parts.iter().map(|e| e.s.clone()).collect();
                let s = self.construct(ty, &texts);
                Self::join(|_| s, &parts)
            }
            4 if self.style == Style::RenderMan => {
                // A cast from another triple (colour and geometry convert only with a cast).
                let from = self.triple_ty();
                let a = self.expr(from, max, exact, d);
                Self::join(|t| format!("{}({})", ty.name(), t[0]), &[a])
            }
            5 => {
                let (a, b, k) =
                    (self.expr(ty, max, exact, d), self.expr(ty, max, exact, d), self.expr(f, max, exact, d));
                match self.c.pick(4) {
                    0 => Self::join(|t| format!("mix({}, {}, {})", t[0], t[1], t[2]), &[a, b, k]),
                    1 => Self::join(|t| format!("clamp({}, 0, 1)", t[0]), &[a]),
                    2 => Self::join(|t| format!("abs({})", t[0]), &[a]),
                    _ => Self::join(|t| format!("max({}, {})", t[0], t[1]), &[a, b]),
                }
            }
            6 if matches!(ty, Ty::Vector | Ty::Float3) => {
                let (a, b) = (self.expr(ty, max, exact, d), self.expr(ty, max, exact, d));
                match (self.style, self.c.pick(2)) {
                    (Style::RenderMan, 0) => Self::join(|t| format!("({} ^ {})", t[0], t[1]), &[a, b]),
                    (Style::Stanford, 0) => Self::join(|t| format!("cross({}, {})", t[0], t[1]), &[a, b]),
                    // A guarded normalize: the offset keeps the argument away from zero for
                    // almost every input (the comparison skips the rest, see generated.rs).
                    (Style::RenderMan, _) => {
                        Self::join(|t| format!("normalize({} + vector(0, 0.01, 0.02))", t[0]), &[a])
                    }
                    (Style::Stanford, _) => {
                        Self::join(|t| format!("normalize({} + {{0, 0.01, 0.02}})", t[0]), &[a])
                    }
                }
            }
            7 => {
                let a = self.expr(ty, max, true, d);
                Self::join(|t| format!("floor({})", t[0]), &[a])
            }
            8 => {
                let (cond, a, b) = self.conditional(|g| {
                    (g.expr(Ty::Bool, max, true, d), g.expr(ty, max, exact, d), g.expr(ty, max, exact, d))
                });
                Self::join(|t| format!("({} ? {} : {})", t[0], t[1], t[2]), &[cond, a, b])
            }
            9 if !exact && matches!(ty, Ty::Color | Ty::Float3) => {
                let a = self.expr(ty, max, false, d);
                Self::inexact(Self::join(|t| format!("sin(clamp({}, -8, 8))", t[0]), &[a]))
            }
            10 => self.call(ty, max, exact, d),
            11 if !exact
                && matches!(ty, Ty::Color | Ty::Vector | Ty::Point)
                && self.style == Style::RenderMan =>
            {
                let p = self.expr(Ty::Point, max, false, d);
                Self::inexact(Self::join(|t| format!("{} noise({})", ty.name(), t[0]), &[p]))
            }
            11 if !exact && ty == Ty::Vector => {
                self.includes[0] = true;
                let p = self.expr(Ty::Point, max, false, d);
                Self::inexact(Self::join(|t| format!("vsnoise3({})", t[0]), &[p]))
            }
            12 => self.integrate(ty, max, exact, d),
            _ => self.leaf(ty, max, exact),
        }
    }

    /// `f` with calls of functions with `output` parameters left out: every operand of `?:`,
    /// `&&` and `||` is evaluated, so such a call there would write its output unconditionally
    /// (E0520).
    fn conditional<T>(&mut self, f: impl FnOnce(&mut Self) -> T) -> T {
        self.conditional += 1;
        let r = f(self);
        self.conditional -= 1;
        r
    }

    /// A call of a user function returning `ty`, if one fits.
    fn call(&mut self, ty: Ty, max: Rate, exact: bool, d: u32) -> E {
        // Function results are varying (a RenderMan function's variables are).
        let fits: Vec<Func> = self
            .funcs
            .iter()
            .filter(|f| {
                f.ret == ty
                    && (f.exact || !exact)
                    && max >= Rate::Varying
                    && !(f.output && self.conditional > 0)
            })
            .cloned()
            .collect();
        if fits.is_empty() {
            return self.leaf(ty, max, exact);
        }
        let f = fits[self.c.pick(fits.len())].clone();
        let mut args: Vec<E> =
            f.params.iter().map(|(t, x)| self.expr(*t, max.min(Rate::Varying), *x, d)).collect();
        if f.output {
            // The output argument: a writable varying float that may take the value.
            let control = self.control;
            let outs: Vec<Var> = self
                .vars()
                .filter(|v| {
                    v.writable
                        && v.ty == Ty::Float
                        && v.len.is_none()
                        && v.rate >= Rate::Varying.max(control)
                        && (f.exact || !v.exact)
                })
                .cloned()
                .collect();
            if outs.is_empty() {
                return self.leaf(ty, max, exact);
            }
            let v = &outs[self.c.pick(outs.len())];
            args.push(E { s: v.name.clone(), rate: Rate::Constant, exact: true });
        }
        let mut e = Self::join(|t| format!("{}({})", f.name, t.join(", ")), &args);
        e.rate = Rate::Varying;
        e.exact = f.exact && e.exact;
        e
    }

    /// A standard-library call (a float; never exact).
    fn library(&mut self, max: Rate, d: u32) -> E {
        let f = Ty::Float;
        let point = |g: &mut Self| {
            g.expr(if g.style == Style::Stanford { Ty::Float3 } else { Ty::Point }, max, false, d)
        };
        let e = match self.c.pick(10) {
            0 => {
                let p = point(self);
                Self::join(|t| format!("noise({})", t[0]), &[p])
            }
            1 => {
                self.includes[0] = true;
                let p = point(self);
                Self::join(|t| format!("snoise3({})", t[0]), &[p])
            }
            2 => {
                self.includes[0] = true;
                let (x, y) = (self.expr(f, max, false, d), self.expr(f, max, false, d));
                Self::join(|t| format!("snoise2({}, {})", t[0], t[1]), &[x, y])
            }
            3 => {
                self.includes[1] = true;
                let p = point(self);
                let (h, oct) = (["0.5", "0.75", "1"][self.c.pick(3)], 1 + self.c.pick(4));
                Self::join(|t| format!("fbm({}, {h}, 2, {oct})", t[0]), &[p])
            }
            4 => {
                self.includes[1] = true;
                let p = point(self);
                let oct = 1 + self.c.pick(3);
                Self::join(|t| format!("turbulence({}, {oct})", t[0]), &[p])
            }
            5 => {
                // Discontinuous: an exact argument.
                let p = self.expr(
                    if self.style == Style::Stanford { Ty::Float3 } else { Ty::Point },
                    max,
                    true,
                    d,
                );
                Self::join(|t| format!("cellnoise({})", t[0]), &[p])
            }
            6 => {
                self.includes[2] = true;
                let x = self.expr(f, max, true, d);
                Self::join(|t| format!("pulse(0.25, 0.75, {})", t[0]), &[x])
            }
            7 => {
                self.includes[2] = true;
                let x = self.expr(f, max, false, d);
                let name = ["bias", "gain"][self.c.pick(2)];
                Self::join(|t| format!("{name}(0.7, clamp({}, 0, 1))", t[0]), &[x])
            }
            8 => {
                self.includes[2] = true;
                let x = self.expr(f, max, false, d);
                Self::join(|t| format!("boxstep(-0.5, 1, {})", t[0]), &[x])
            }
            _ => {
                self.includes[2] = true;
                let x = self.expr(f, max, false, d);
                Self::join(|t| format!("gammacorrect(2.2, abs({}))", t[0]), &[x])
            }
        };
        Self::inexact(e)
    }

    /// `integrate` of a Stanford per-light value (a leaf of `ty` where there is none).
    fn integrate(&mut self, ty: Ty, max: Rate, exact: bool, d: u32) -> E {
        if self.style != Style::Stanford || exact || max < Rate::Varying || self.in_func.is_some() {
            return self.leaf(ty, max, exact);
        }
        let inner = self.expr(ty, Rate::Perlight, false, d);
        if inner.rate < Rate::Perlight {
            // `integrate` of a value that is not per light is warning E0606.
            return inner;
        }
        let mut e = Self::inexact(Self::join(|t| format!("integrate({})", t[0]), &[inner]));
        e.rate = e.rate.min(Rate::Varying);
        e
    }

    /// An element of a float array.
    fn element(&mut self, max: Rate, exact: bool, d: u32) -> E {
        let arrays: Vec<Var> = self
            .vars()
            .filter(|v| v.len.is_some() && v.rate <= max && (v.exact || !exact))
            .cloned()
            .collect();
        if arrays.is_empty() {
            return self.leaf(Ty::Float, max, exact);
        }
        let a = arrays[self.c.pick(arrays.len())].clone();
        let i = self.index(a.len.expect("an array"), max, d);
        let mut e = Self::join(|t| format!("{}[{}]", a.name, t[0]), &[i]);
        e.rate = e.rate.max(a.rate);
        e.exact = a.exact;
        e
    }

    /// An index into an array of `n`: a constant one is in range (out of range is an error,
    /// E0516); others may be anything (both backends clamp them).
    fn index(&mut self, n: usize, max: Rate, d: u32) -> E {
        let i = self.expr(Ty::Int, max, true, d);
        if i.rate == Rate::Constant { E::lit(self.c.pick(n).to_string()) } else { i }
    }

    // ---------------------------------------------------------------------------------------------
    // Statements.

    /// A block of statements (none once the bytes run out).
    fn block(&mut self, depth: u32) {
        self.scopes.push(Vec::new());
        self.statements_here(depth);
        self.scopes.pop();
    }

    /// Statements in the current scope.
    fn statements_here(&mut self, depth: u32) {
        while self.statements < 40 && self.c.chance(3, 4) {
            self.statement(depth);
        }
    }

    fn statement(&mut self, depth: u32) {
        self.statements += 1;
        let control = self.control;
        match self.c.pick(10) {
            0 | 1 => self.declaration(),
            2 | 3 => self.assignment(),
            4 if depth > 0 => {
                let cond = self.expr(Ty::Bool, Rate::Varying, true, 2);
                self.line(&format!("if ({}) {{", cond.s));
                self.nested(cond.rate, depth);
                if self.c.chance(1, 2) {
                    self.line("} else {");
                    self.nested(cond.rate, depth);
                }
                self.line("}");
            }
            5 if depth > 0 => {
                let rate = if self.c.pick(2) == 0 { Rate::Uniform.max(control) } else { Rate::Varying };
                let i = self.fresh("i");
                let qualifier =
                    if self.style == Style::RenderMan && rate == Rate::Uniform { "uniform " } else { "" };
                let n = 1 + self.c.pick(4);
                self.line(&format!("for ({qualifier}int {i} = 0; {i} < {n}; {i} += 1) {{"));
                self.scopes.push(vec![Var {
                    name: i,
                    ty: Ty::Int,
                    rate: if self.style == Style::RenderMan { rate } else { Rate::Constant },
                    exact: true,
                    writable: false,
                    len: None,
                }]);
                self.looped(rate, depth);
                self.scopes.pop();
                self.line("}");
            }
            6 if depth > 0 => {
                let w = self.fresh("w");
                let n = 1 + self.c.pick(4);
                self.line(&format!("int {w} = 0;"));
                self.line(&format!("while ({w} < {n}) {{"));
                self.line(&format!("    {w} += 1;"));
                let rate = if self.style == Style::RenderMan { Rate::Varying } else { Rate::Constant };
                self.declare(Var { name: w, ty: Ty::Int, rate, exact: true, writable: false, len: None });
                self.looped(Rate::Varying, depth);
                self.line("}");
            }
            7 if self.loops.last().is_some_and(|r| control <= *r) => {
                let cond = self.expr(Ty::Bool, self.control, true, 1);
                let what = ["break", "continue"][self.c.pick(2)];
                self.line(&format!("if ({}) {what};", cond.s));
            }
            7 if self.in_func.is_some() => {
                let (ty, exact) = self.in_func.expect("in a function");
                let cond = self.expr(Ty::Bool, Rate::Varying, true, 1);
                let e = self.expr(ty, Rate::Varying, exact, 2);
                self.line(&format!("if ({}) return {};", cond.s, e.s));
            }
            8 if self.style == Style::RenderMan && !self.in_light && self.in_func.is_none() && depth > 0 => {
                let header =
                    ["illuminance(P)", "illuminance(P, N, 1.2)", "illuminance(P, N, PI / 2)"][self.c.pick(3)];
                self.line(&format!("{header} {{"));
                self.in_light = true;
                let loops = std::mem::take(&mut self.loops);
                self.nested(Rate::Varying, depth);
                self.loops = loops;
                self.in_light = false;
                self.line("}");
            }
            8 if self.style == Style::Stanford && self.in_func.is_none() && control == Rate::Constant => {
                let ty = if self.c.pick(2) == 0 { Ty::Float3 } else { Ty::Float };
                let e = self.expr(ty, Rate::Perlight, false, 3);
                let name = self.fresh("pl");
                self.line(&format!("perlight {} {name} = {};", ty.name(), e.s));
                self.declare(Var {
                    name,
                    ty,
                    rate: Rate::Perlight,
                    exact: false,
                    writable: false,
                    len: None,
                });
            }
            _ => self.assignment(),
        }
    }

    /// A block under a condition or loop of rate `rate`.
    fn nested(&mut self, rate: Rate, depth: u32) {
        let saved = self.control;
        self.control = self.control.max(rate);
        self.indent += 1;
        self.block(depth - 1);
        self.indent -= 1;
        self.control = saved;
    }

    fn looped(&mut self, rate: Rate, depth: u32) {
        let rate = rate.max(self.control);
        self.loops.push(rate);
        self.nested(rate, depth);
        self.loops.pop();
    }

    /// The rate of a new local: RenderMan's are varying unless declared uniform (then they may
    /// only take uniform values under uniform control); Stanford's are inferred, and taken as
    /// varying here (the highest they can get).
    fn declaration(&mut self) {
        let kind = self.c.pick(6);
        let uniform = self.style == Style::RenderMan && self.control <= Rate::Uniform && self.c.pick(3) == 0;
        let rate = if uniform { Rate::Uniform } else { Rate::Varying };
        let exact = self.c.pick(2) == 0;
        let qualifier = if uniform { "uniform " } else { "" };
        if kind == 5 {
            let n = 2 + self.c.pick(3);
            let items: Vec<String> = (0..n).map(|_| self.expr(Ty::Float, rate, exact, 2).s).collect();
            let name = self.fresh("a");
            self.line(&format!("{qualifier}float {name}[{n}] = {{{}}};", items.join(", ")));
            self.declare(Var { name, ty: Ty::Float, rate, exact, writable: true, len: Some(n) });
            return;
        }
        if self.style == Style::Stanford && kind == 4 {
            let name = self.fresh("k");
            let value = self.float_lit();
            self.line(&format!("constant float {name} = {value};"));
            self.declare(Var {
                name,
                ty: Ty::Float,
                rate: Rate::Constant,
                exact: true,
                writable: false,
                len: None,
            });
            return;
        }
        let ty = match kind {
            0 | 1 => Ty::Float,
            2 => Ty::Int,
            3 => Ty::Bool,
            _ => self.triple_ty(),
        };
        let exact = exact || matches!(ty, Ty::Int | Ty::Bool);
        let max = if self.in_light && !uniform { Rate::Perlight } else { rate };
        let e = self.expr(ty, max, exact, 3);
        let name = self.fresh(&ty.name()[..1]);
        self.line(&format!("{qualifier}{} {name} = {};", ty.name(), e.s));
        self.declare(Var { name, ty, rate, exact, writable: true, len: None });
    }

    fn assignment(&mut self) {
        let control = self.control;
        let targets: Vec<Var> = self.vars().filter(|v| v.writable && v.rate >= control).cloned().collect();
        if targets.is_empty() {
            return self.declaration();
        }
        let v = targets[self.c.pick(targets.len())].clone();
        let max = self.store_rate(&v);
        let e = self.expr(v.ty, max, v.exact, 3);
        let target = match v.len {
            Some(n) => {
                let i = self.index(n, v.rate, 1);
                format!("{}[{}]", v.name, i.s)
            }
            None => v.name.clone(),
        };
        let op = match v.ty {
            Ty::Bool => "=",
            Ty::Int => ["=", "+=", "*="][self.c.pick(3)],
            _ => ["=", "+=", "*=", "-="][self.c.pick(4)],
        };
        self.line(&format!("{target} {op} {};", e.s));
    }

    // ---------------------------------------------------------------------------------------------
    // Functions and the surface.

    fn function(&mut self) -> String {
        let ret = match self.c.pick(3) {
            0 => Ty::Float,
            _ => self.triple_ty(),
        };
        let exact = self.c.pick(2) == 0;
        let name = self.fresh("f");
        let count = 1 + self.c.pick(3);
        let output = self.c.pick(2) == 1;
        let mut params = Vec::new();
        let mut scope = Vec::new();
        let mut text = Vec::new();
        for k in 0..count {
            let ty = if self.c.pick(2) == 0 { Ty::Float } else { self.triple_ty() };
            let x = exact || self.c.pick(2) == 0;
            let pname = format!("{name}p{k}");
            text.push(format!("{} {pname}", ty.name()));
            scope.push(Var { name: pname, ty, rate: Rate::Varying, exact: x, writable: false, len: None });
            params.push((ty, x));
        }
        let out_name = format!("{name}out");
        if output {
            text.push(format!("output float {out_name}"));
        }
        let saved_out = std::mem::take(&mut self.out);
        let saved_scopes = std::mem::replace(&mut self.scopes, vec![scope]);
        self.in_func = Some((ret, exact));
        // Calls may sit under varying conditions, so a function's body is under varying control
        // (no uniform locals or loops there).
        let saved_control = std::mem::replace(&mut self.control, Rate::Varying);
        if output {
            let e = self.expr(Ty::Float, Rate::Varying, exact, 2);
            self.line(&format!("{out_name} = {};", e.s));
            self.declare(Var {
                name: out_name,
                ty: Ty::Float,
                rate: Rate::Varying,
                exact,
                writable: true,
                len: None,
            });
        }
        self.block(2);
        let e = self.expr(ret, Rate::Varying, exact, 3);
        self.line(&format!("return {};", e.s));
        self.in_func = None;
        self.control = saved_control;
        self.scopes = saved_scopes;
        let body = std::mem::replace(&mut self.out, saved_out);
        self.funcs.push(Func { name: name.clone(), params, output, ret, exact });
        format!("{} {name}({})\n{{\n{body}}}\n", ret.name(), text.join("; "))
    }

    /// The surface shader's text, its parameters and its outputs.
    #[allow(clippy::type_complexity)]
    fn surface(&mut self) -> (String, Vec<Param>, Vec<(String, Vec<bool>)>) {
        let mut params = Vec::new();
        let mut decls = Vec::new();
        for k in 0..1 + self.c.pick(4) {
            let ty = if self.c.pick(2) == 0 { Ty::Float } else { self.triple_ty() };
            let uniform = self.c.pick(2) == 0;
            let default: Vec<f64> =
                (0..ty.width()).map(|_| self.float_lit().parse().expect("a literal")).collect();
            let text: Vec<String> = default.iter().map(|x| x.to_string()).collect();
            let default_text = if ty.triple() { self.construct(ty, &text) } else { text[0].clone() };
            let name = format!("{}{k}", if uniform { "up" } else { "vp" });
            let rate = match (self.style, uniform) {
                (Style::RenderMan, true) => "uniform",
                (Style::RenderMan, false) => "varying",
                (Style::Stanford, true) => "primitive group",
                (Style::Stanford, false) => "vertex",
            };
            decls.push(format!("{rate} {} {name} = {default_text}", ty.name()));
            let defaulted = self.c.pick(4) == 1;
            self.declare(Var {
                name: name.clone(),
                ty,
                rate: if uniform { Rate::Uniform } else { Rate::Varying },
                exact: true,
                writable: false,
                len: None,
            });
            params.push(Param { name, default, defaulted });
        }
        let mut outputs = Vec::new();
        if self.style == Style::RenderMan {
            for k in 0..self.c.pick(3) {
                let ty = if self.c.pick(2) == 0 { Ty::Float } else { self.triple_ty() };
                let name = format!("o{k}");
                outputs.push((name, ty));
            }
            for (name, ty) in &outputs {
                decls.push(format!("output varying {} {name} = 0", ty.name()));
            }
        }
        self.statements_here(3);
        // The outputs read the surface's variables, so that what the body computed is compared:
        // one sum of the exact ones (compared tightly) and one of all.
        let (exact_sum, all_sum) = (self.sum(true), self.sum(false));
        let mut compared = Vec::new();
        match self.style {
            Style::RenderMan => {
                for (name, ty) in outputs {
                    let e = self.expr(ty, Rate::Varying, false, 4);
                    self.line(&format!("{name} = {};", e.s));
                    compared.push((name, vec![e.exact; ty.width()]));
                }
                self.line(&format!("output_exact = {};", exact_sum.s));
                compared.push(("output_exact".into(), vec![true]));
                let e = self.expr(Ty::Color, Rate::Varying, false, 4);
                self.line(&format!("Ci = {} + {};", e.s, all_sum.s));
                compared.push(("Ci".into(), vec![e.exact && all_sum.exact; 3]));
                decls.push("output varying float output_exact = 0".into());
            }
            Style::Stanford => {
                let e = self.expr(Ty::Float3, Rate::Varying, false, 4);
                self.line(&format!("return {{{} + {}, {}}};", e.s, all_sum.s, exact_sum.s));
                compared.push((
                    "result".into(),
                    vec![e.exact && all_sum.exact, e.exact && all_sum.exact, e.exact && all_sum.exact, true],
                ));
            }
        }
        let head = match self.style {
            Style::RenderMan => format!("surface generated(\n    {})\n", decls.join(";\n    ")),
            Style::Stanford => format!("surface shader float4 generated(\n    {})\n", decls.join(",\n    ")),
        };
        let body = std::mem::take(&mut self.out);
        (format!("{head}{{\n{body}}}\n"), params, compared)
    }

    /// The sum of the surface body's variables (the exact ones only if `exact`), as a float
    /// (exact) or a triple (all: a colour in RenderMan style, a float3 in Stanford style).
    fn sum(&self, exact: bool) -> E {
        let mut terms = vec!["0".to_string()];
        let mut all_exact = true;
        for v in self.vars().filter(|v| v.rate <= Rate::Varying && (v.exact || !exact)) {
            let value = match v.len {
                Some(n) => format!("{}[{}]", v.name, n - 1),
                None => v.name.clone(),
            };
            let term = match (v.ty, exact) {
                (Ty::Bool, _) => format!("({value} ? 1 : 0)"),
                (Ty::Int, _) => format!("float({value})"),
                (Ty::Float, _) => value,
                (_, true) => format!("{value}[{}]", v.name.len() % 3),
                (Ty::Color | Ty::Float3, false) => value,
                (_, false) => format!("color({value})"),
            };
            all_exact &= v.exact;
            terms.push(term);
        }
        E { s: terms.join(" + "), rate: Rate::Varying, exact: all_exact }
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
