//! What parameter defaults depend on. The semantic stage lowers the calls in a default (user
//! functions, the built-ins the library implements) into statements at the top of the body, ahead
//! of the shader's own, and leaves the default an expression that reads their results from
//! temporaries. Whoever evaluates a default (the interpreter, before the body) runs those
//! statements first, and the split keeps them in the host stage, which computes the defaults.
//! A default written with literals alone has a value known before anything runs
//! ([`Shader::literal_default`]), which a renderer can bind like a value the scene sets.

use rustc_hash::FxHashSet;

use super::types::Base;
use super::{ExprId, ExprKind, Literal, LocalId, LocalKind, Shader, Stmt, UnaryOp};

impl Shader {
    /// The locals the parameters' default expressions read.
    pub fn default_reads(&self) -> FxHashSet<LocalId> {
        let mut out = FxHashSet::default();
        for &p in &self.params {
            if let LocalKind::Param { default: Some(d), .. } = self.local(p).kind {
                self.add_reads(d, &mut out);
            }
        }
        out
    }

    /// The statements the default `value` needs run before it: the body's top-level statements
    /// that store a local it reads (not a parameter), transitively, in body order. They also stay
    /// in the body, where running them again computes the same temporaries.
    pub fn default_prelude(&self, value: ExprId) -> Vec<Stmt> {
        let mut needed = FxHashSet::default();
        self.add_reads(value, &mut needed);
        let mut taken = vec![false; self.body.len()];
        // A statement feeds an earlier one only through locals it stores: walk backwards.
        for (i, stmt) in self.body.iter().enumerate().rev() {
            let mut stored = FxHashSet::default();
            self.stmt_locals(stmt, &mut stored, &mut FxHashSet::default());
            if stored.iter().any(|l| needed.contains(l) && !self.params.contains(l)) {
                taken[i] = true;
                self.stmt_locals(stmt, &mut FxHashSet::default(), &mut needed);
            }
        }
        self.body.iter().zip(taken).filter(|(_, t)| *t).map(|(s, _)| s.clone()).collect()
    }

    /// The value of parameter `param`'s default, in the language's component order, when it is
    /// written with literals alone: a literal, a negated one, a conversion of one (`color 1`,
    /// `float 2` of an int) or a construction of them (`color (1, 0.5, 0)`). These are the
    /// values the host computes for it on every draw, exactly (no arithmetic rounds). `None` for
    /// any other default (a call, a space, another parameter, a matrix or array) and for a
    /// parameter without one.
    pub fn literal_default(&self, param: LocalId) -> Option<Vec<f64>> {
        match self.local(param).kind {
            LocalKind::Param { default: Some(d), .. } => self.literal_value(d),
            _ => None,
        }
    }

    /// The components of `e` when it is built from literals as [`Shader::literal_default`] says.
    fn literal_value(&self, e: ExprId) -> Option<Vec<f64>> {
        let expr = self.expr(e);
        if expr.ty.array.is_some() {
            return None;
        }
        match &expr.kind {
            ExprKind::Literal(Literal::Float(x)) => Some(vec![*x]),
            ExprKind::Literal(Literal::Int(i)) => Some(vec![f64::from(*i)]),
            ExprKind::Literal(Literal::Uint(u)) => Some(vec![f64::from(*u)]),
            ExprKind::Literal(Literal::Bool(b)) => Some(vec![f64::from(u8::from(*b))]),
            // Negation is exact, except that it wraps for the most negative int (and a uint).
            ExprKind::Unary(UnaryOp::Neg, a) => {
                let value = self.literal_value(*a)?;
                let exact = match expr.ty.base {
                    Base::Int => value.iter().all(|&x| x != f64::from(i32::MIN)),
                    Base::Float => true,
                    base => base.is_triple(),
                };
                exact.then(|| value.into_iter().map(|x| -x).collect())
            }
            ExprKind::Convert(a) => {
                let from = self.literal_value(*a)?;
                let source = self.expr(*a).ty.base;
                let scalar = matches!(source, Base::Float | Base::Int | Base::Uint);
                match (expr.ty.base, from.len()) {
                    (Base::Float, 1) if scalar => Some(from),
                    // A clampf clamps, a float4 and the matrices are not duplications.
                    (to, 1) if to.is_triple() && scalar => Some(vec![from[0]; 3]),
                    (to, 3) if to.is_triple() && source.is_triple() => Some(from),
                    _ => None,
                }
            }
            ExprKind::Construct(parts) if expr.ty.base.is_triple() => {
                let values: Vec<f64> = parts
                    .iter()
                    .map(|&p| self.literal_value(p).filter(|v| v.len() == 1).map(|v| v[0]))
                    .collect::<Option<_>>()?;
                (values.len() == 3).then_some(values)
            }
            _ => None,
        }
    }

    /// Adds the locals `stmt` (with the blocks in it) stores to `stored` and those it reads to
    /// `read`.
    fn stmt_locals(&self, stmt: &Stmt, stored: &mut FxHashSet<LocalId>, read: &mut FxHashSet<LocalId>) {
        if let Stmt::Store { place, .. } = stmt {
            stored.extend(place.root_local());
        }
        stmt.for_each_root(|e| self.add_reads(e, read));
        stmt.for_each_block(|block| block.iter().for_each(|s| self.stmt_locals(s, stored, read)));
    }
}

#[cfg(test)]
mod tests {
    use crate::syntax::preprocess::MemoryLoader;

    /// `literal_default` of each parameter of the first shader of `src`, by name.
    fn literal_defaults(src: &str) -> Vec<(String, Option<Vec<f64>>)> {
        let checked = crate::check_source("t.sl", src, &MemoryLoader::default());
        assert!(!checked.has_errors(), "{:?}", checked.diagnostics);
        let shader = &checked.program.shaders[0];
        shader.params.iter().map(|&p| (shader.local(p).name.to_string(), shader.literal_default(p))).collect()
    }

    #[test]
    fn defaults_written_with_literals_have_their_values() {
        let got = literal_defaults(
            "surface t(float a = 0.1; float b = -2; color c = 1; color d = color(1, -0.5, 0);
                       int n = -3; float m = 4; color e = color(n, 1, 1))
             { Ci = a * b * c * d * n * m * e; }",
        );
        let want: [(&str, Option<Vec<f64>>); 7] = [
            ("a", Some(vec![0.1])),
            ("b", Some(vec![-2.0])),
            ("c", Some(vec![1.0; 3])),
            ("d", Some(vec![1.0, -0.5, 0.0])),
            ("n", Some(vec![-3.0])),
            ("m", Some(vec![4.0])),
            // A component read from another parameter is the host's to compute.
            ("e", None),
        ];
        for (name, value) in want {
            let found = got.iter().find(|(n, _)| n == name).map(|(_, v)| v.clone());
            assert_eq!(found, Some(value), "{name}: {got:?}");
        }
    }

    #[test]
    fn defaults_that_compute_are_not_literal() {
        let got = literal_defaults(
            "surface t(float a = 1; float b = 2 * a; float c = sqrt(2); float d = 1 + 1;
                       color e = color \"hsv\" (0.5, 1, 1); point p = point \"shader\" (0, 0, 0);
                       matrix m = 1; float f[2] = {1, 2}; string s = \"x\")
             { Ci = a * b * c * d * e * f[0] * f[1] + color(p) + comp(m, 0, 0) * (s == \"x\" ? 1 : 0); }",
        );
        for (name, value) in &got {
            if name == "a" {
                assert_eq!(value, &Some(vec![1.0]));
            } else {
                assert_eq!(value, &None, "{name}");
            }
        }
    }
}
