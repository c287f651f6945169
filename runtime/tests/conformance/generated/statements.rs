//! The generator's statements, user functions and the surface shader (see `generator.rs`).

use super::{E, Func, Gen, Param, Rate, Style, Ty, Var};

impl Gen<'_> {
    /// A block of statements (none once the bytes run out).
    pub(super) fn block(&mut self, depth: u32) {
        self.scopes.push(Vec::new());
        self.statements_here(depth);
        self.scopes.pop();
    }

    /// Statements in the current scope.
    pub(super) fn statements_here(&mut self, depth: u32) {
        while self.statements < 40 && self.c.chance(3, 4) {
            self.statement(depth);
        }
    }

    pub(super) fn statement(&mut self, depth: u32) {
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
    pub(super) fn nested(&mut self, rate: Rate, depth: u32) {
        let saved = self.control;
        self.control = self.control.max(rate);
        self.indent += 1;
        self.block(depth - 1);
        self.indent -= 1;
        self.control = saved;
    }

    pub(super) fn looped(&mut self, rate: Rate, depth: u32) {
        let rate = rate.max(self.control);
        self.loops.push(rate);
        self.nested(rate, depth);
        self.loops.pop();
    }

    /// The rate of a new local: RenderMan's are varying unless declared uniform (then they may
    /// only take uniform values under uniform control); Stanford's are inferred, and taken as
    /// varying here (the highest they can get).
    pub(super) fn declaration(&mut self) {
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

    pub(super) fn assignment(&mut self) {
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

    pub(super) fn function(&mut self) -> String {
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
    pub(super) fn surface(&mut self) -> (String, Vec<Param>, Vec<(String, Vec<bool>)>) {
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
    pub(super) fn sum(&self, exact: bool) -> E {
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
