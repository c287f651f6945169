//! The generator's expressions: of each type, within a rate, exact or not (see `generator.rs`).

use super::{E, Func, Gen, Rate, Style, Ty, Var, operand};

impl Gen<'_> {
    /// An expression of `ty` whose rate is at most `max` (exact if `exact`), `depth` levels deep
    /// at most.
    pub(super) fn expr(&mut self, ty: Ty, max: Rate, exact: bool, depth: u32) -> E {
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

    pub(super) fn join(op: impl FnOnce(&[String]) -> String, parts: &[E]) -> E {
        let texts: Vec<String> = parts.iter().map(|e| e.s.clone()).collect();
        E {
            s: op(&texts),
            rate: parts.iter().map(|e| e.rate).max().unwrap_or(Rate::Constant),
            exact: parts.iter().all(|e| e.exact),
        }
    }

    /// `e` marked inexact (a transcendental, a light sum, a library function).
    pub(super) fn inexact(mut e: E) -> E {
        e.exact = false;
        e
    }

    pub(super) fn float_expr(&mut self, max: Rate, exact: bool, d: u32) -> E {
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

    pub(super) fn int_expr(&mut self, max: Rate, d: u32) -> E {
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

    pub(super) fn bool_expr(&mut self, max: Rate, d: u32) -> E {
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
    pub(super) fn triple_ty(&mut self) -> Ty {
        match self.style {
            Style::Stanford => Ty::Float3,
            Style::RenderMan => [Ty::Color, Ty::Point, Ty::Vector, Ty::Normal][self.c.pick(4)],
        }
    }

    /// A type with a dot product, length and cross product.
    pub(super) fn geometric_ty(&mut self) -> Ty {
        match self.style {
            Style::Stanford => Ty::Float3,
            Style::RenderMan => [Ty::Vector, Ty::Normal][self.c.pick(2)],
        }
    }

    pub(super) fn triple_expr(&mut self, ty: Ty, max: Rate, exact: bool, d: u32) -> E {
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
    pub(super) fn conditional<T>(&mut self, f: impl FnOnce(&mut Self) -> T) -> T {
        self.conditional += 1;
        let r = f(self);
        self.conditional -= 1;
        r
    }

    /// A call of a user function returning `ty`, if one fits.
    pub(super) fn call(&mut self, ty: Ty, max: Rate, exact: bool, d: u32) -> E {
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
    pub(super) fn library(&mut self, max: Rate, d: u32) -> E {
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
    pub(super) fn integrate(&mut self, ty: Ty, max: Rate, exact: bool, d: u32) -> E {
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
    pub(super) fn element(&mut self, max: Rate, exact: bool, d: u32) -> E {
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
    pub(super) fn index(&mut self, n: usize, max: Rate, d: u32) -> E {
        let i = self.expr(Ty::Int, max, true, d);
        if i.rate == Rate::Constant { E::lit(self.c.pick(n).to_string()) } else { i }
    }
}
