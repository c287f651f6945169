//! The typed IR's invariants, checked: what every stage assumes of the shader it is given, so that
//! a pass that breaks one is caught where it does (issue 23), not as a wrong picture or a panic in
//! a backend three passes later.
//!
//! [`verify`] checks a shader as it stands after a [`Pass`]; what holds depends on the pass (the
//! arena is in operand order only until `bind` rewrites it, rates are meaningful only once
//! `sema::rates` has run, derivative built-ins are gone only after `opt::derivs`), and each check
//! is one that the passes guarantee on every program, so a failure is a compiler bug. ARCHITECTURE.md
//! ("Invariants between stages") lists them. [`assert_valid`] and [`assert_valid_stages`] are what
//! the passes call: in debug builds (tests, fuzzing) they panic naming the pass and the violations;
//! in release builds they do nothing.
//!
//! The checks apply the semantic stage's rules (the conversions a cast allows, the table of
//! predefined variables, the built-ins' options) and read the split's stages, so this module sits
//! beside `ir`, `sema` and `split` rather than inside `ir`, which depends on none of them.

use std::fmt;

use smol_str::SmolStr;

use crate::ir::builtin::{Builtin, BuiltinId, Context};
use crate::ir::global::{Access, Global, Scope};
use crate::ir::types::{Base, Frequency, Rate, Type};
use crate::ir::{
    BinaryOp, Block, ExprId, ExprKind, Input, Literal, LocalId, LocalKind, Place, Shader, Stmt, UnaryOp,
};
use crate::sema::builtins;
use crate::sema::convert;
use crate::sema::globals;
use crate::split::{StageKind, Stages};
use crate::syntax::ast::ShaderKind;

#[cfg(test)]
mod tests;

/// The pass a shader has just been through: it decides which invariants are checked.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Pass {
    /// `sema::lower`: types are final and operands precede their users; every rate is still
    /// `constant`.
    Lower,
    /// `sema::rates`, when it reported no error: every expression's rate is exactly the one its
    /// operands give it, and every stored value fits its variable's rate.
    Rates,
    /// A step of `bind::specialize` (named): literals for parameters and decided branches make
    /// rates only lower than their operands allow, and the arena leaves operand order.
    Bind(&'static str),
    /// `opt::textures::footprints`.
    Footprints,
    /// `opt::derivs::differentiate`: no derivative built-in remains.
    Derivatives,
    /// `opt::textures::expand`: no texture lookup it can filter remains.
    Textures,
    /// `opt::shadow::expand`: no shadow-map lookup remains.
    Shadows,
    /// `opt::splines::expand`.
    Splines,
    /// `opt::lights::unroll`: no light construct, light sum built-in or per-light statement
    /// outside a light loop remains.
    Lights,
    /// The whole of `opt::Prepared::new`: what the passes above each guarantee.
    Prepare,
    /// `split`: one stage, which reads only values of its own stage or lower.
    Split(StageKind),
}

impl Pass {
    /// Whether operands precede their users in the arena (the semantic stage's order; `bind`
    /// appends the parts of folded vectors after the reads they replace).
    fn ordered(self) -> bool {
        matches!(self, Pass::Lower | Pass::Rates)
    }

    /// Whether rates have been inferred.
    fn rated(self) -> bool {
        self != Pass::Lower
    }

    /// Whether `Eval` statements still hold only built-in calls (before `opt` rewrites calls in
    /// place: a derivative or a lookup evaluated for nothing becomes arithmetic).
    fn calls_evaluated(self) -> bool {
        matches!(self, Pass::Lower | Pass::Rates | Pass::Bind(_))
    }

    fn no_derivatives(self) -> bool {
        matches!(self, Pass::Derivatives | Pass::Prepare)
    }

    fn no_textures(self) -> bool {
        matches!(self, Pass::Textures | Pass::Prepare)
    }

    fn no_shadows(self) -> bool {
        matches!(self, Pass::Shadows | Pass::Prepare)
    }
}

impl fmt::Display for Pass {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Pass::Lower => f.write_str("sema::lower"),
            Pass::Rates => f.write_str("sema::rates"),
            Pass::Bind(step) => write!(f, "bind::specialize ({step})"),
            Pass::Footprints => f.write_str("opt::textures::footprints"),
            Pass::Derivatives => f.write_str("opt::derivs::differentiate"),
            Pass::Textures => f.write_str("opt::textures::expand"),
            Pass::Shadows => f.write_str("opt::shadow::expand"),
            Pass::Splines => f.write_str("opt::splines::expand"),
            Pass::Lights => f.write_str("opt::lights::unroll"),
            Pass::Prepare => f.write_str("opt::Prepared::new"),
            Pass::Split(stage) => write!(f, "split ({} stage)", stage.name()),
        }
    }
}

/// The invariants a shader breaks after a pass.
#[derive(Clone, Debug, PartialEq)]
pub struct VerifyError {
    /// The shader's name.
    pub shader: SmolStr,
    /// The pass after which it was checked.
    pub pass: Pass,
    /// One line per violation, naming the expression (`e12`), local (`l3`) or statement.
    pub violations: Vec<String>,
}

/// How many violations a message lists (one broken pass usually breaks many values alike).
const SHOWN: usize = 20;

impl fmt::Display for VerifyError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "the IR of shader `{}` is invalid after {}: {} violation{}",
            self.shader,
            self.pass,
            self.violations.len(),
            if self.violations.len() == 1 { "" } else { "s" }
        )?;
        for v in self.violations.iter().take(SHOWN) {
            write!(f, "\n  - {v}")?;
        }
        if self.violations.len() > SHOWN {
            write!(f, "\n  ... and {} more", self.violations.len() - SHOWN)?;
        }
        Ok(())
    }
}

impl std::error::Error for VerifyError {}

/// Checks `shader` against the invariants that hold after `pass`.
pub fn verify(shader: &Shader, pass: Pass) -> Result<(), VerifyError> {
    let mut v = Verifier { shader, pass, out: Vec::new() };
    v.run();
    if v.out.is_empty() {
        Ok(())
    } else {
        Err(VerifyError { shader: shader.name.clone(), pass, violations: v.out })
    }
}

/// Checks each stage of a split shader (`Pass::Split`) and the transfers between them: the three
/// share the input's numbering of locals and expressions, and a value that crosses is an output
/// parameter of its producer and an input parameter of each stage that reads it.
pub fn verify_stages(stages: &Stages) -> Result<(), VerifyError> {
    let kinds = [StageKind::Host, StageKind::Vertex, StageKind::Fragment];
    for kind in kinds {
        verify(stages.stage(kind), Pass::Split(kind))?;
    }
    let mut out = Vec::new();
    let (host, fragment) = (&stages.host, &stages.fragment);
    for kind in [StageKind::Vertex, StageKind::Fragment] {
        let s = stages.stage(kind);
        if s.exprs.len() != host.exprs.len() || s.locals.len() != host.locals.len() {
            out.push(format!(
                "the {} stage has {} expressions and {} locals, the host {} and {}",
                kind.name(),
                s.exprs.len(),
                s.locals.len(),
                host.exprs.len(),
                host.locals.len()
            ));
        }
    }
    for t in &stages.transfers {
        let readers = [(StageKind::Vertex, t.to_vertex), (StageKind::Fragment, t.to_fragment)];
        if t.from == StageKind::Fragment || (t.from == StageKind::Vertex && t.to_vertex) {
            out.push(format!(
                "transfer `{}` goes from the {} stage to itself or down",
                t.name,
                t.from.name()
            ));
        }
        if !t.to_vertex && !t.to_fragment {
            out.push(format!("transfer `{}` has no reader", t.name));
        }
        for kind in kinds {
            let s = stages.stage(kind);
            let Some(local) = s.locals.get(t.local.0 as usize) else {
                out.push(format!(
                    "transfer `{}`: l{} is not a local of the {} stage",
                    t.name,
                    t.local.0,
                    kind.name()
                ));
                continue;
            };
            if local.ty != t.ty {
                out.push(format!(
                    "transfer `{}` is `{}` but its local in the {} stage is `{}`",
                    t.name,
                    t.ty,
                    kind.name(),
                    local.ty
                ));
            }
            let reads = readers.iter().any(|(k, r)| *k == kind && *r);
            let want = if kind == t.from {
                Some(true)
            } else if reads {
                Some(false)
            } else {
                None
            };
            let is = match local.kind {
                LocalKind::Param { output, .. } if s.params.contains(&t.local) => Some(output),
                _ => None,
            };
            if want != is {
                let what = |p: Option<bool>| match p {
                    Some(true) => "an output parameter",
                    Some(false) => "an input parameter",
                    None => "not a parameter",
                };
                out.push(format!(
                    "transfer `{}` should be {} of the {} stage, and is {}",
                    t.name,
                    what(want),
                    kind.name(),
                    what(is)
                ));
            }
        }
    }
    if out.is_empty() {
        Ok(())
    } else {
        Err(VerifyError {
            shader: fragment.name.clone(),
            pass: Pass::Split(StageKind::Fragment),
            violations: out,
        })
    }
}

/// [`verify`], as the passes call it: in debug builds a violation panics (it is a compiler bug,
/// never the user's); release builds check nothing.
#[track_caller]
pub fn assert_valid(shader: &Shader, pass: Pass) {
    if cfg!(debug_assertions)
        && let Err(e) = verify(shader, pass)
    {
        panic!("internal compiler error: {e}");
    }
}

/// [`verify_stages`], as `split` calls it (see [`assert_valid`]).
#[track_caller]
pub fn assert_valid_stages(stages: &Stages) {
    if cfg!(debug_assertions)
        && let Err(e) = verify_stages(stages)
    {
        panic!("internal compiler error: {e}");
    }
}

/// The stage that computes values of `rate` (the split's rule).
fn stage_of(rate: Rate) -> StageKind {
    match (rate.perlight, rate.frequency) {
        (true, _) | (false, Frequency::Fragment) => StageKind::Fragment,
        (false, Frequency::Vertex) => StageKind::Vertex,
        (false, Frequency::Constant | Frequency::PrimitiveGroup) => StageKind::Host,
    }
}

/// What indexing a value of type `ty` gives (the semantic stage's rule), or `None` when it cannot
/// be indexed.
fn element(ty: Type) -> Option<Type> {
    match (ty.array, ty.base) {
        (Some(_), b) => Some(Type::of(b)),
        (None, b) if b.is_triple() || b == Base::Float4 => Some(Type::FLOAT),
        (None, Base::Matrix4) => Some(Type::of(Base::Float4)),
        (None, Base::Matrix3) => Some(Type::of(Base::Float3)),
        (None, Base::String) => Some(Type::STRING),
        _ => None,
    }
}

/// Whether a call is one `opt::derivs` replaces (its `is_consumer`).
fn is_derivative(b: &Builtin) -> bool {
    match b.id {
        BuiltinId::Du
        | BuiltinId::Dv
        | BuiltinId::Deriv
        | BuiltinId::FilterWidth
        | BuiltinId::Area
        | BuiltinId::CalculateNormal => true,
        BuiltinId::FilterStep => b.params.len() == 2,
        _ => false,
    }
}

/// Whether `opt::textures` or `opt::shadow` rewrites this call into texel fetches: every lookup
/// but the forms they leave for the backends to refuse (`texture(name)` where the shader has no
/// `s` and `t`).
fn expanded_lookup(shader: &Shader, b: &Builtin, args: &[ExprId]) -> bool {
    let positional = b.params.len().min(args.len());
    let has = |name| globals::lookup(name, shader.kind, shader.stanford).is_some();
    match b.id {
        BuiltinId::Texture | BuiltinId::Texture3d => match positional {
            1 => has("s") && has("t"),
            2 | 3 | 9 => true,
            _ => false,
        },
        BuiltinId::Environment => matches!(positional, 2 | 5),
        BuiltinId::Shadow => positional >= 2,
        _ => false,
    }
}

struct Verifier<'s> {
    shader: &'s Shader,
    pass: Pass,
    out: Vec<String>,
}

/// Where a statement stands: what encloses it.
#[derive(Copy, Clone, Default)]
struct Within {
    /// Loops since the innermost inlined call (`break n` counts only those).
    loops: u32,
}

impl Verifier<'_> {
    fn fail(&mut self, message: String) {
        self.out.push(message);
    }

    fn run(&mut self) {
        // Everything else indexes the arenas: check the references first, and stop if one is out
        // of range.
        self.references();
        if !self.out.is_empty() {
            return;
        }
        self.shape();
        self.acyclic();
        for i in 0..self.shader.exprs.len() {
            self.expr(ExprId(i as u32));
        }
        let body = &self.shader.body;
        self.block(body, Within::default());
        if !self.shader.stanford && self.shader.kind == ShaderKind::Surface {
            self.light_values();
        }
        if self.pass.no_derivatives() || self.pass.no_textures() || self.pass.no_shadows() {
            self.prepared();
        }
        if let Pass::Split(stage) = self.pass {
            self.stage_reads(stage);
        }
        if self.pass == Pass::Lights {
            self.lights_unrolled();
        }
    }

    // --- references -----------------------------------------------------------------------

    fn references(&mut self) {
        let (n_exprs, n_locals) = (self.shader.exprs.len(), self.shader.locals.len());
        let mut bad = Vec::new();
        let expr_ok = |e: ExprId| (e.0 as usize) < n_exprs;
        let local_ok = |l: LocalId| (l.0 as usize) < n_locals;
        for (i, e) in self.shader.exprs.iter().enumerate() {
            e.kind.for_each_operand(|o| {
                if !expr_ok(o) {
                    bad.push(format!("e{i} has operand e{}, past the {n_exprs} expressions", o.0));
                }
            });
            match &e.kind {
                ExprKind::Local(l) | ExprKind::Seed(Input::Param(l), _) if !local_ok(*l) => {
                    bad.push(format!("e{i} reads l{}, past the {n_locals} locals", l.0));
                }
                _ => {}
            }
        }
        for (i, l) in self.shader.locals.iter().enumerate() {
            if let LocalKind::Param { default: Some(d), .. } = l.kind
                && !expr_ok(d)
            {
                bad.push(format!(
                    "the default of l{i} `{}` is e{}, past the {n_exprs} expressions",
                    l.name, d.0
                ));
            }
        }
        for p in self.shader.params.iter().chain(&self.shader.result_local) {
            if !local_ok(*p) {
                bad.push(format!("parameter or result l{} is past the {n_locals} locals", p.0));
            }
        }
        fn place(
            p: &Place,
            ok: &dyn Fn(ExprId) -> bool,
            lok: &dyn Fn(LocalId) -> bool,
            bad: &mut Vec<String>,
        ) {
            match p {
                Place::Local(l) if !lok(*l) => bad.push(format!("a store into l{}, past the locals", l.0)),
                Place::Index(inner, i) => {
                    if !ok(*i) {
                        bad.push(format!("a store indexed by e{}, past the expressions", i.0));
                    }
                    place(inner, ok, lok, bad);
                }
                _ => {}
            }
        }
        fn walk(
            block: &Block,
            ok: &dyn Fn(ExprId) -> bool,
            lok: &dyn Fn(LocalId) -> bool,
            bad: &mut Vec<String>,
        ) {
            for stmt in block {
                let mut roots = Vec::new();
                stmt.for_each_root(|e| roots.push(e));
                for e in roots {
                    if !ok(e) {
                        bad.push(format!("a statement reads e{}, past the expressions", e.0));
                    }
                }
                if let Stmt::Store { place: p, .. } = stmt {
                    place(p, ok, lok, bad);
                }
                stmt.for_each_block(|b| walk(b, ok, lok, bad));
            }
        }
        walk(&self.shader.body, &expr_ok, &local_ok, &mut bad);
        self.out.extend(bad);
    }

    // --- the shader's own fields ----------------------------------------------------------

    fn shape(&mut self) {
        let s = self.shader;
        let mut seen = vec![false; s.locals.len()];
        for &p in &s.params {
            if std::mem::replace(&mut seen[p.0 as usize], true) {
                self.fail(format!("parameter l{} is listed twice", p.0));
            }
            if !matches!(s.local(p).kind, LocalKind::Param { .. }) {
                self.fail(format!("parameter l{} `{}` is not a parameter local", p.0, s.local(p).name));
            }
        }
        for (i, l) in s.locals.iter().enumerate() {
            if let LocalKind::Param { default, .. } = l.kind {
                if !seen[i] {
                    self.fail(format!("l{i} `{}` is a parameter local missing from the parameters", l.name));
                }
                if let Some(d) = default
                    && s.expr(d).ty != l.ty
                {
                    let ty = s.expr(d).ty;
                    self.fail(format!(
                        "the default of `{}` (e{}) is `{ty}`, the parameter `{}`",
                        l.name, d.0, l.ty
                    ));
                }
                // Defaults are evaluated on the host, before the body.
                if let Some(d) = default
                    && self.pass.rated()
                    && s.expr(d).rate.frequency > Frequency::PrimitiveGroup
                {
                    self.fail(format!("the default of `{}` (e{}) is {}", l.name, d.0, s.expr(d).rate));
                }
            }
        }
        match (s.stanford, s.result_local) {
            (true, Some(r)) if s.local(r).ty != s.result => {
                self.fail(format!(
                    "the result local is `{}`, the shader returns `{}`",
                    s.local(r).ty,
                    s.result
                ));
            }
            (true, None) => self.fail("a Stanford-style shader without a result local".into()),
            (false, Some(_)) => self.fail("a RenderMan-style shader with a result local".into()),
            (false, None) if s.result != Type::VOID => {
                self.fail(format!("a RenderMan-style shader returns `{}`", s.result));
            }
            _ => {}
        }
    }

    // --- the expression graph -------------------------------------------------------------

    /// The expressions form a DAG (Kahn's algorithm over operand edges), and, where the pass keeps
    /// it, in operand order.
    fn acyclic(&mut self) {
        let exprs = &self.shader.exprs;
        let n = exprs.len();
        let mut pending = vec![0u32; n];
        let mut users_count = vec![0u32; n + 1];
        for (i, e) in exprs.iter().enumerate() {
            let mut late = None;
            e.kind.for_each_operand(|o| {
                pending[i] += 1;
                users_count[o.0 as usize + 1] += 1;
                if o.0 as usize >= i {
                    late = Some(o);
                }
            });
            if let (true, Some(o)) = (self.pass.ordered(), late) {
                self.out.push(format!("e{i} uses e{}, which does not come before it", o.0));
            }
        }
        // Users of each expression, as one array sliced by `start`.
        let mut start = users_count;
        for i in 0..n {
            start[i + 1] += start[i];
        }
        let mut fill = start.clone();
        let mut users = vec![0u32; start[n] as usize];
        for (i, e) in exprs.iter().enumerate() {
            e.kind.for_each_operand(|o| {
                users[fill[o.0 as usize] as usize] = i as u32;
                fill[o.0 as usize] += 1;
            });
        }
        let mut ready: Vec<u32> = (0..n as u32).filter(|&i| pending[i as usize] == 0).collect();
        let mut done = 0;
        while let Some(i) = ready.pop() {
            done += 1;
            for &u in &users[start[i as usize] as usize..start[i as usize + 1] as usize] {
                pending[u as usize] -= 1;
                if pending[u as usize] == 0 {
                    ready.push(u);
                }
            }
        }
        if done < n {
            let first = pending.iter().position(|&p| p > 0).unwrap_or(0);
            self.out.push(format!(
                "the expressions have a cycle (through e{first}, among {} others)",
                n - done - 1
            ));
        }
    }

    fn ty(&self, e: ExprId) -> Type {
        self.shader.expr(e).ty
    }

    fn rate(&self, e: ExprId) -> Rate {
        self.shader.expr(e).rate
    }

    fn expr(&mut self, id: ExprId) {
        let e = self.shader.expr(id);
        if let Err(why) = self.expr_type(&e.kind, e.ty) {
            self.fail(format!("e{} {}: {why}", id.0, describe(&e.kind)));
        }
        if self.pass.rated() {
            let expected = self.shader.rate_of(&e.kind);
            let ok = if self.pass == Pass::Rates { e.rate == expected } else { expected.fits_in(e.rate) };
            if !ok {
                let relation = if self.pass == Pass::Rates { "exactly" } else { "at least" };
                self.fail(format!(
                    "e{} {} is {}, but its operands make it {relation} {expected}",
                    id.0,
                    describe(&e.kind),
                    e.rate
                ));
            }
        }
    }

    /// Why an expression of this kind cannot have type `ty`, if it cannot.
    fn expr_type(&self, kind: &ExprKind, ty: Type) -> Result<(), String> {
        let s = self.shader;
        let same = |a: ExprId, b: ExprId| -> Result<(), String> {
            let (ta, tb) = (self.ty(a), self.ty(b));
            if ta == tb { Ok(()) } else { Err(format!("operands `{ta}` and `{tb}` differ")) }
        };
        let want = |got: Type, want: Type, what: &str| -> Result<(), String> {
            if got == want { Ok(()) } else { Err(format!("{what} is `{got}`, not `{want}`")) }
        };
        match kind {
            ExprKind::Literal(lit) => {
                let ok = match lit {
                    Literal::Float(_) => ty.array.is_none() && ty.base.is_float_scalar(),
                    Literal::Int(_) => ty == Type::INT,
                    Literal::Uint(_) => ty == Type::of(Base::Uint),
                    Literal::Bool(_) => ty == Type::BOOL,
                    Literal::String(_) => ty == Type::STRING,
                };
                if !ok {
                    return Err(format!("a literal of type `{ty}`"));
                }
            }
            ExprKind::Local(l) => want(ty, s.local(*l).ty, "the read")?,
            ExprKind::Global(g) => {
                if !globals::lookup(g.name, s.kind, s.stanford).is_some_and(|found| std::ptr::eq(found, *g)) {
                    return Err(format!("`{}` is not a predefined variable of this shader", g.name));
                }
                want(ty, Type::of(g.ty), "the read")?;
            }
            ExprKind::Unary(op, a) => {
                let ta = self.ty(*a);
                let ok = match op {
                    UnaryOp::Neg => ta == ty && ty.array.is_none() && ty.base.is_numeric(),
                    UnaryOp::Not => ta == Type::BOOL && ty == Type::BOOL,
                    UnaryOp::BitNot => ta == ty && ty.array.is_none() && ty.base.is_integer(),
                };
                if !ok {
                    return Err(format!("{op:?} of `{ta}` gives `{ty}`"));
                }
            }
            ExprKind::Binary(op, a, b) => self.binary_type(*op, *a, *b, ty)?,
            ExprKind::Convert(a) => {
                let from = self.ty(*a);
                if !convert::explicit_ok(from, ty) {
                    return Err(format!("no conversion from `{from}` to `{ty}`"));
                }
            }
            ExprKind::Construct(parts) => {
                if let Some(n) = ty.array {
                    if n as usize != parts.len() {
                        return Err(format!("{} elements for `{ty}`", parts.len()));
                    }
                    for &p in parts {
                        want(self.ty(p), Type::of(ty.base), "an element")?;
                    }
                } else if parts.is_empty() && ty == Type::VOID {
                    // What a call of a function returning nothing gives its caller to ignore.
                } else {
                    if !ty.base.is_numeric() {
                        return Err(format!("`{ty}` is not built from components"));
                    }
                    let mut count = 0;
                    for &p in parts {
                        let tp = self.ty(p);
                        let float = tp.base.is_float_scalar() || tp.base.components() > 1;
                        if tp.is_array() || !tp.base.is_numeric() || !float {
                            return Err(format!("a component of type `{tp}`"));
                        }
                        count += tp.base.components();
                    }
                    // A matrix from one float is that float times the identity.
                    let diagonal = matches!(ty.base, Base::Matrix3 | Base::Matrix4)
                        && parts.len() == 1
                        && self.ty(parts[0]).base.is_float_scalar();
                    if count != ty.base.components() && !diagonal {
                        return Err(format!("{count} components for `{ty}`"));
                    }
                }
            }
            ExprKind::FromSpace { space, value } => {
                want(self.ty(*value), ty, "the value")?;
                if ty.is_array()
                    || !(ty.base.is_triple() || ty.base == Base::Matrix4)
                    || ty.base == Base::Float3
                {
                    return Err(format!("`{ty}` values have no space"));
                }
                if space.is_empty() {
                    return Err("no space name".into());
                }
            }
            ExprKind::Index(base, index) => {
                let ti = self.ty(*index);
                if ti.is_array() || !ti.base.is_integer() {
                    return Err(format!("an index of type `{ti}`"));
                }
                let tb = self.ty(*base);
                match element(tb) {
                    Some(el) => want(ty, el, "an element")?,
                    None => return Err(format!("`{tb}` cannot be indexed")),
                }
            }
            ExprKind::Select(c, a, b) => {
                want(self.ty(*c), Type::BOOL, "the condition")?;
                same(*a, *b)?;
                want(ty, self.ty(*a), "the result")?;
            }
            ExprKind::Builtin(b, args) => self.call_type(b, args, ty)?,
            ExprKind::LightSum { value, .. } => {
                want(self.ty(*value), ty, "the summed value")?;
                if ty.is_array() || matches!(ty.base, Base::Void | Base::Bool | Base::String | Base::Texref) {
                    return Err(format!("`{ty}` values cannot be summed"));
                }
            }
            ExprKind::Seed(input, _) => {
                let of = match input {
                    Input::Global(g) => Type::of(g.ty),
                    Input::Param(l) => {
                        if !matches!(s.local(*l).kind, LocalKind::Param { .. }) {
                            return Err(format!("l{} is not a parameter", l.0));
                        }
                        s.local(*l).ty
                    }
                };
                match of.derivative() {
                    Some(d) => want(ty, d, "the derivative")?,
                    None => return Err(format!("`{of}` has no derivative")),
                }
            }
        }
        Ok(())
    }

    fn binary_type(&self, op: BinaryOp, a: ExprId, b: ExprId, ty: Type) -> Result<(), String> {
        use BinaryOp as B;
        let (ta, tb) = (self.ty(a), self.ty(b));
        let bad = || Err(format!("`{ta}` {op:?} `{tb}` gives `{ty}`"));
        if ta.is_array() || tb.is_array() {
            return bad();
        }
        let ok = match op {
            B::And | B::Or => ta == Type::BOOL && tb == Type::BOOL && ty == Type::BOOL,
            B::Eq | B::Ne => ta == tb && ty == Type::BOOL,
            B::Lt | B::Le | B::Gt | B::Ge => {
                ta == tb && (ta.base.is_float_scalar() || ta.base.is_integer()) && ty == Type::BOOL
            }
            B::Rem | B::BitXor | B::BitAnd | B::BitOr | B::Shl | B::Shr => {
                ta == tb && ta.base.is_integer() && ty == ta
            }
            B::Cross => ta == tb && ty == ta && matches!(ta.base, Base::Vector | Base::Float3),
            B::Dot => ta == tb && (ta.base.is_triple() || ta.base == Base::Float4) && ty == Type::FLOAT,
            B::Add | B::Sub | B::Mul | B::Div => {
                // Matrix products keep their operands' types.
                let product = match (ta.base, tb.base) {
                    (Base::Matrix4, Base::Float4) => Some(tb),
                    (Base::Matrix3, x) if x.is_triple() => Some(tb),
                    _ => None,
                };
                match product {
                    Some(p) if op == B::Mul => ty == p,
                    _ => {
                        // point - point is a vector.
                        let difference =
                            op == B::Sub && ta.base == Base::Point && ty == Type::of(Base::Vector);
                        ta == tb && ta.base.is_numeric() && (ty == ta || difference)
                    }
                }
            }
        };
        if ok { Ok(()) } else { bad() }
    }

    /// A call's arguments against the overload it resolved to.
    fn call_type(&self, b: &Builtin, args: &[ExprId], ty: Type) -> Result<(), String> {
        if ty != b.ret {
            return Err(format!("the call is `{ty}`, `{}` returns `{}`", b.signature, b.ret));
        }
        let (n, p) = (args.len(), b.params.len());
        if n < p {
            return Err(format!("{n} arguments for `{}`", b.signature));
        }
        for (k, (param, &arg)) in b.params.iter().zip(args).enumerate() {
            let got = self.ty(arg);
            let fits = if param.ty.array == Some(0) {
                got.array.is_some() && got.base == param.ty.base
            } else {
                got == param.ty
            };
            if !fits {
                return Err(format!("argument {k} is `{got}` for `{}`", b.signature));
            }
            if param.output && !self.is_place(arg) {
                return Err(format!("output argument {k} (e{}) is not a variable", arg.0));
            }
        }
        let rest = &args[p..];
        if rest.is_empty() {
            return Ok(());
        }
        if let Some(rest_ty) = b.rest {
            // `printf` and `format` take values of any type, checked against the format.
            if !matches!(b.id, BuiltinId::Printf | BuiltinId::Format)
                && let Some(&bad) = rest.iter().find(|&&a| self.ty(a) != rest_ty)
            {
                return Err(format!(
                    "further argument e{} is `{}` for `{}`",
                    bad.0,
                    self.ty(bad),
                    b.signature
                ));
            }
            return Ok(());
        }
        if builtins::options(b.id).is_none() {
            return Err(format!("{n} arguments for `{}`", b.signature));
        }
        // Optional `"name", value` pairs.
        if !rest.len().is_multiple_of(2) {
            return Err(format!("an option of `{}` without its value", b.id));
        }
        for pair in rest.chunks_exact(2) {
            if !matches!(self.shader.expr(pair[0]).kind, ExprKind::Literal(Literal::String(_))) {
                return Err(format!("option name e{} is not a string literal", pair[0].0));
            }
            let tv = self.ty(pair[1]);
            if tv.is_array()
                || !(tv.base.is_float_scalar() || tv.base.is_integer() || tv.base == Base::String)
            {
                return Err(format!("option value e{} is `{tv}`", pair[1].0));
            }
        }
        Ok(())
    }

    /// Whether an expression denotes a variable (a built-in's `output` argument).
    fn is_place(&self, e: ExprId) -> bool {
        match &self.shader.expr(e).kind {
            ExprKind::Local(_) => true,
            ExprKind::Global(g) => g.access == Access::ReadWrite,
            ExprKind::Index(base, _) => self.is_place(*base),
            _ => false,
        }
    }

    // --- statements -----------------------------------------------------------------------

    fn block(&mut self, block: &Block, within: Within) {
        for stmt in block {
            self.statement(stmt, within);
        }
    }

    fn statement(&mut self, stmt: &Stmt, within: Within) {
        let s = self.shader;
        match stmt {
            Stmt::Eval(id) => {
                let call = match &s.expr(*id).kind {
                    ExprKind::Builtin(b, args) => Some((*b, args)),
                    _ => None,
                };
                if call.is_none() && self.pass.calls_evaluated() {
                    self.fail(format!("`Eval` of e{}, which is not a built-in call", id.0));
                }
                // The call's outputs are stored at its rate.
                if let (Some((b, args)), true) = (call, self.pass.rated()) {
                    for (param, arg) in b.params.iter().zip(args) {
                        if let (true, ExprKind::Local(l)) = (param.output, &s.expr(*arg).kind) {
                            self.store_rate(*l, *id);
                        }
                    }
                }
            }
            Stmt::Store { place, value, .. } => {
                match self.place_type(place) {
                    Ok(ty) if ty != self.ty(*value) => self.fail(format!(
                        "a store of e{} (`{}`) into a place of type `{ty}`",
                        value.0,
                        self.ty(*value)
                    )),
                    Ok(_) => {}
                    Err(why) => self.fail(format!("a store of e{}: {why}", value.0)),
                }
                if let (Some(l), true) = (place.root_local(), self.pass.rated()) {
                    self.store_rate(l, *value);
                }
            }
            Stmt::If { cond, then, otherwise } => {
                self.condition(*cond, "`if`");
                self.block(then, within);
                self.block(otherwise, within);
            }
            Stmt::Loop { cond, body, step, .. } => {
                if let Some(c) = cond {
                    self.condition(*c, "loop");
                }
                let inner = Within { loops: within.loops + 1 };
                self.block(body, inner);
                self.block(step, inner);
            }
            Stmt::Break(n) | Stmt::Continue(n) => {
                if *n == 0 || *n > within.loops {
                    let word = if matches!(stmt, Stmt::Break(_)) { "break" } else { "continue" };
                    self.fail(format!("`{word} {n}` inside {} loops of its function", within.loops));
                }
            }
            Stmt::Return => {}
            Stmt::Inline { function, body, .. } => {
                if function.is_empty() {
                    self.fail("an inlined call without a function name".into());
                }
                self.block(body, Within { loops: 0 });
            }
            Stmt::Illuminance { args, body } => {
                if s.stanford || s.kind != ShaderKind::Surface {
                    self.fail("`illuminance` outside a RenderMan-style surface shader".into());
                }
                let types: Vec<Type> = args.iter().map(|a| self.ty(*a)).collect();
                let rest = match types.first() {
                    Some(t) if *t == Type::STRING => &types[1..],
                    _ => &types[..],
                };
                let (point, vector) = (Type::of(Base::Point), Type::of(Base::Vector));
                if rest != [point] && rest != [point, vector, Type::FLOAT] {
                    self.fail(format!("`illuminance` arguments {types:?}"));
                }
                self.block(body, within);
            }
            Stmt::Emit { solar, args, body } => {
                if s.kind != ShaderKind::Light {
                    self.fail("`illuminate` or `solar` outside a light shader".into());
                }
                let types: Vec<Type> = args.iter().map(|a| self.ty(*a)).collect();
                let (point, vector) = (Type::of(Base::Point), Type::of(Base::Vector));
                let ok = if *solar {
                    types.is_empty() || types == [vector, Type::FLOAT]
                } else {
                    types == [point] || types == [point, vector, Type::FLOAT]
                };
                if !ok {
                    self.fail(format!(
                        "`{}` arguments {types:?}",
                        if *solar { "solar" } else { "illuminate" }
                    ));
                }
                self.block(body, within);
            }
            Stmt::Lights { body, .. } => {
                if s.kind == ShaderKind::Light {
                    self.fail("a light loop in a light shader".into());
                }
                self.block(body, within);
            }
        }
    }

    fn condition(&mut self, cond: ExprId, what: &str) {
        let ty = self.ty(cond);
        if ty != Type::BOOL {
            self.fail(format!("the {what} condition e{} is `{ty}`", cond.0));
        }
    }

    /// The type a place holds.
    fn place_type(&self, place: &Place) -> Result<Type, String> {
        match place {
            Place::Local(l) => Ok(self.shader.local(*l).ty),
            Place::Global(g) => {
                if g.access != Access::ReadWrite {
                    return Err(format!("`{}` is read-only", g.name));
                }
                if !globals::lookup(g.name, self.shader.kind, self.shader.stanford)
                    .is_some_and(|found| std::ptr::eq(found, *g))
                {
                    return Err(format!("`{}` is not a predefined variable of this shader", g.name));
                }
                Ok(Type::of(g.ty))
            }
            Place::Index(inner, index) => {
                let ti = self.ty(*index);
                if ti.is_array() || !ti.base.is_integer() {
                    return Err(format!("an index of type `{ti}`"));
                }
                let outer = self.place_type(inner)?;
                element(outer).ok_or_else(|| format!("`{outer}` cannot be indexed"))
            }
        }
    }

    /// A value stored into local `l` fits its rate (RenderMan drops `perlight` from stores: inside
    /// `illuminance` a store accumulates over the lights).
    fn store_rate(&mut self, l: LocalId, value: ExprId) {
        let mut rate = self.rate(value);
        if !self.shader.stanford {
            rate.perlight = false;
        }
        let local = self.shader.local(l);
        if !rate.fits_in(local.rate) {
            self.fail(format!(
                "a {rate} value (e{}) stored into l{} `{}`, which is {}",
                value.0, l.0, local.name, local.rate
            ));
        }
    }

    // --- light loops ----------------------------------------------------------------------

    /// In a RenderMan-style surface, the per-light values (`L`, `Cl`, `lightsource`) are read only
    /// inside `illuminance`, where one light is visited.
    fn light_values(&mut self) {
        let s = self.shader;
        let mut outside = vec![false; s.exprs.len()];
        let mut stack = Vec::new();
        fn roots(block: &Block, stack: &mut Vec<ExprId>) {
            for stmt in block {
                stmt.for_each_root(|e| stack.push(e));
                if !matches!(stmt, Stmt::Illuminance { .. } | Stmt::Lights { .. }) {
                    stmt.for_each_block(|b| roots(b, stack));
                }
            }
        }
        roots(&s.body, &mut stack);
        for l in &s.locals {
            if let LocalKind::Param { default: Some(d), .. } = l.kind {
                stack.push(d);
            }
        }
        while let Some(e) = stack.pop() {
            if std::mem::replace(&mut outside[e.0 as usize], true) {
                continue;
            }
            // A light sum's value is read for each of its lights.
            if !matches!(s.expr(e).kind, ExprKind::LightSum { .. }) {
                s.expr(e).kind.for_each_operand(|o| stack.push(o));
            }
        }
        for (i, e) in s.exprs.iter().enumerate() {
            if !outside[i] {
                continue;
            }
            let per_light = match &e.kind {
                ExprKind::Global(g) => g.scope == Scope::PerLight,
                ExprKind::Builtin(b, _) => b.context == Context::Illuminance,
                _ => false,
            };
            if per_light {
                self.fail(format!("e{i} {} is read outside `illuminance`", describe(&e.kind)));
            }
        }
    }

    // --- pass-specific --------------------------------------------------------------------

    /// What `opt::Prepared::new`'s passes leave: no derivative built-ins, no texture or shadow lookups.
    fn prepared(&mut self) {
        let s = self.shader;
        for (i, e) in s.exprs.iter().enumerate() {
            let ExprKind::Builtin(b, args) = &e.kind else { continue };
            let left = if is_derivative(b) {
                self.pass.no_derivatives()
            } else if b.id == BuiltinId::Shadow {
                self.pass.no_shadows() && expanded_lookup(s, b, args)
            } else {
                self.pass.no_textures() && expanded_lookup(s, b, args)
            };
            if left {
                self.fail(format!("e{i} still calls `{}`", b.signature));
            }
        }
    }

    /// What `opt::lights::unroll` leaves: no light construct or light sum built-in, and no
    /// statement computing a per-light value outside a light loop.
    fn lights_unrolled(&mut self) {
        let s = self.shader;
        for (i, e) in s.exprs.iter().enumerate() {
            if let ExprKind::Builtin(b, _) = &e.kind
                && matches!(b.id, BuiltinId::Ambient | BuiltinId::Integrate)
            {
                self.fail(format!("e{i} still calls `{}`", b.signature));
            }
        }
        fn walk(s: &Shader, block: &Block, out: &mut Vec<String>) {
            for stmt in block {
                match stmt {
                    Stmt::Illuminance { .. } | Stmt::Emit { .. } => {
                        out.push("a light construct is left".into())
                    }
                    Stmt::Lights { .. } => continue,
                    _ => {}
                }
                if s.computes_perlight(stmt) {
                    out.push("a per-light statement outside a light loop".into());
                }
                stmt.for_each_block(|b| walk(s, b, out));
            }
        }
        let mut found = Vec::new();
        walk(s, &s.body, &mut found);
        found.dedup();
        self.out.extend(found);
    }

    /// A stage reads only values its own stage or a lower one computes, and stores only into
    /// variables of such rates; light constructs belong to the fragment stage.
    fn stage_reads(&mut self, stage: StageKind) {
        let s = self.shader;
        let mut seen = vec![false; s.exprs.len()];
        let mut stack = Vec::new();
        let mut stores = Vec::new();
        let mut lights = false;
        fn walk(block: &Block, stack: &mut Vec<ExprId>, stores: &mut Vec<Place>, lights: &mut bool) {
            for stmt in block {
                stmt.for_each_root(|e| stack.push(e));
                match stmt {
                    Stmt::Store { place, .. } => stores.push(place.clone()),
                    Stmt::Illuminance { .. } | Stmt::Emit { .. } => *lights = true,
                    _ => {}
                }
                stmt.for_each_block(|b| walk(b, stack, stores, lights));
            }
        }
        walk(&s.body, &mut stack, &mut stores, &mut lights);
        if lights && stage != StageKind::Fragment {
            self.fail(format!("a light construct in the {} stage", stage.name()));
        }
        while let Some(e) = stack.pop() {
            if std::mem::replace(&mut seen[e.0 as usize], true) {
                continue;
            }
            let expr = s.expr(e);
            if stage_of(expr.rate) > stage {
                self.fail(format!(
                    "the {} stage reads e{} {}, which is {}",
                    stage.name(),
                    e.0,
                    describe(&expr.kind),
                    expr.rate
                ));
            }
            expr.kind.for_each_operand(|o| stack.push(o));
        }
        for place in stores {
            let (name, rate) = match root_of(&place) {
                Place::Local(l) => (s.local(*l).name.clone(), s.local(*l).rate),
                Place::Global(g) => (SmolStr::new(g.name), global_rate(g)),
                Place::Index(..) => unreachable!("a root is not an index"),
            };
            if stage_of(rate) > stage {
                self.fail(format!("the {} stage stores into `{name}`, which is {rate}", stage.name()));
            }
        }
    }
}

/// The rate of a predefined variable.
fn global_rate(g: &Global) -> Rate {
    Rate { frequency: g.frequency, perlight: g.perlight }
}

/// The local or predefined variable a place is part of.
fn root_of(place: &Place) -> &Place {
    match place {
        Place::Index(inner, _) => root_of(inner),
        other => other,
    }
}

/// A short description of an expression for messages: its kind with operand ids.
fn describe(kind: &ExprKind) -> String {
    let ids = |ids: &[ExprId]| ids.iter().map(|e| format!("e{}", e.0)).collect::<Vec<_>>().join(", ");
    match kind {
        ExprKind::Literal(l) => format!("({l:?})"),
        ExprKind::Local(l) => format!("(read of l{})", l.0),
        ExprKind::Global(g) => format!("(`{}`)", g.name),
        ExprKind::Unary(op, a) => format!("({op:?} e{})", a.0),
        ExprKind::Binary(op, a, b) => format!("(e{} {op:?} e{})", a.0, b.0),
        ExprKind::Convert(a) => format!("(conversion of e{})", a.0),
        ExprKind::Construct(parts) => format!("(construct {})", ids(parts)),
        ExprKind::FromSpace { space, value } => format!("(e{} from \"{space}\")", value.0),
        ExprKind::Index(a, i) => format!("(e{}[e{}])", a.0, i.0),
        ExprKind::Select(c, a, b) => format!("(e{} ? e{} : e{})", c.0, a.0, b.0),
        ExprKind::Builtin(b, args) => format!("(`{}`({}))", b.id, ids(args)),
        ExprKind::LightSum { lights, value } => format!("(e{} summed over lights {lights:?})", value.0),
        ExprKind::Seed(Input::Global(g), axis) => format!("(seed of `{}` along {axis:?})", g.name),
        ExprKind::Seed(Input::Param(l), axis) => format!("(seed of l{} along {axis:?})", l.0),
    }
}
