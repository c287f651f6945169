//! The light constructs over the bound lights, once for both backends: after this pass a shader
//! has no `illuminance`, `illuminate` or `solar`, no `ambient()` or `integrate`, and no
//! per-light statement outside a light loop; the backends only run a [`Stmt::Lights`] body once
//! per listed light and sum an [`ExprKind::LightSum`] over its lights, with the per-light variables
//! the visited light's.
//!
//! - `illuminance([category,] P [, axis, angle]) body` becomes a loop over the bound lights the
//!   category selects (`LightBinding::visited_by`: never the ambient ones) of `body`, under
//!   `dot(L, axis) >= cos(angle) sqrt(dot(L, L) dot(axis, axis))` when it has a cone.
//! - `illuminate(from [, axis, angle]) body` (in a light shader) becomes `L = Ps - from;` and
//!   `body`, under the cone test when there is one; `solar([axis, angle]) body` becomes
//!   `L = axis;` and `body` under the test (without arguments, `body` alone).
//! - `ambient()` is the sum of the ambient lights' `Cl`, `integrate(x)` the sum of `x` over every
//!   bound light (also inside a per-light value: the inner sum is over every light).
//! - A Stanford statement that computes a per-light value outside a light loop (a store into or
//!   of a per-light value, a per-light condition) becomes a loop over every bound light of that
//!   statement.
//! - A call that light loops repeat with the same per-light arguments (`normalize(L)` in both
//!   `diffuse` and `specular`) is computed once per light ([`shared`]).
//!
//! The result is a copy of the shader for one binding: a backend compiles it in place of the
//! prepared shader it was given. Expression ids keep their meaning (expressions are only added,
//! and `ambient`/`integrate` calls turned into sums in place).

mod shared;

use crate::backend::binding::LightBinding;
use crate::ir::builtin::BuiltinId;
use crate::ir::global::Global;
use crate::ir::types::{Base, Type};
use crate::ir::{BinaryOp, Block, ExprId, ExprKind, Place, Shader, Stmt};
use crate::opt::build::Builder;
use crate::source::Span;

/// `shader` with its light constructs over `lights` (module documentation); `strings` are the
/// values of its `string` parameters, by name (an `illuminance` category may be one).
pub fn unroll(shader: &Shader, lights: &[LightBinding], strings: &[(String, String)]) -> Shader {
    let mut out = shader.clone();
    sums(&mut out, lights);
    let body = std::mem::take(&mut out.body);
    let mut unroll = Unroll { shader: &mut out, lights, strings };
    let body = unroll.block(body, false);
    out.body = body;
    shared::share_calls(&mut out);
    crate::verify::assert_valid(&out, crate::verify::Pass::Lights);
    out
}

/// Turns `ambient()` and `integrate(x)` into sums over their lights, in place.
fn sums(shader: &mut Shader, lights: &[LightBinding]) {
    let every: Vec<u32> = (0..lights.len() as u32).collect();
    let ambient: Vec<u32> = every.iter().copied().filter(|&k| lights[k as usize].ambient).collect();
    for i in 0..shader.exprs.len() {
        let kind = match &shader.exprs[i].kind {
            ExprKind::Builtin(b, args) if b.id == BuiltinId::Integrate => {
                ExprKind::LightSum { lights: every.clone(), value: args[0] }
            }
            ExprKind::Builtin(b, _) if b.id == BuiltinId::Ambient => {
                let Some(cl) = global(shader, "Cl") else { continue };
                let span = shader.exprs[i].span;
                let value = Builder::new(shader, span).push(ExprKind::Global(cl), Type::of(cl.ty));
                ExprKind::LightSum { lights: ambient.clone(), value }
            }
            _ => continue,
        };
        shader.exprs[i].kind = kind;
    }
}

/// The predefined variable `name` of `shader`'s kind and style.
fn global(shader: &Shader, name: &str) -> Option<&'static Global> {
    crate::sema::globals::lookup(name, shader.kind, shader.stanford)
}

/// The rewriting of statements.
struct Unroll<'a> {
    shader: &'a mut Shader,
    lights: &'a [LightBinding],
    strings: &'a [(String, String)],
}

impl Unroll<'_> {
    /// `block` rewritten; `in_light` when it runs inside a light loop.
    fn block(&mut self, block: Block, in_light: bool) -> Block {
        let mut out = Vec::with_capacity(block.len());
        for stmt in block {
            self.statement(stmt, in_light, &mut out);
        }
        out
    }

    fn statement(&mut self, stmt: Stmt, in_light: bool, out: &mut Block) {
        if !in_light && self.shader.computes_perlight(&stmt) {
            // Stanford per-light computation: once per bound light.
            let body = self.block(vec![stmt], true);
            let lights = (0..self.lights.len() as u32).collect();
            push_loop(out, lights, body);
            return;
        }
        match stmt {
            Stmt::If { cond, then, otherwise } => {
                let (then, otherwise) = (self.block(then, in_light), self.block(otherwise, in_light));
                out.push(Stmt::If { cond, then, otherwise });
            }
            Stmt::Loop { cond, body, step, span } => {
                let (body, step) = (self.block(body, in_light), self.block(step, in_light));
                out.push(Stmt::Loop { cond, body, step, span });
            }
            Stmt::Inline { function, body, span } => {
                let body = self.block(body, in_light);
                out.push(Stmt::Inline { function, body, span });
            }
            Stmt::Lights { lights, body } => {
                let body = self.block(body, true);
                out.push(Stmt::Lights { lights, body });
            }
            Stmt::Illuminance { args, body } => self.illuminance(&args, body, out),
            Stmt::Emit { solar, args, body } => self.emission(solar, &args, body, in_light, out),
            Stmt::Store { .. } | Stmt::Eval(_) | Stmt::Break(_) | Stmt::Continue(_) | Stmt::Return => {
                out.push(stmt)
            }
        }
    }

    /// `illuminance([category,] P [, axis, angle]) body`.
    fn illuminance(&mut self, args: &[ExprId], body: Block, out: &mut Block) {
        let (category, rest) = match args.first() {
            Some(&a) if self.shader.expr(a).ty.base == Base::String => {
                (self.shader.string_value(a, self.strings), &args[1..])
            }
            _ => (None, args),
        };
        let visited: Vec<u32> = (0..self.lights.len() as u32)
            .filter(|&k| self.lights[k as usize].visited_by(category.as_deref()))
            .collect();
        let body = self.block(body, true);
        let body = match rest {
            [_, axis, angle] => match self.l() {
                Some(l) => vec![self.within_cone(l, *axis, *angle, body)],
                None => body,
            },
            _ => body,
        };
        push_loop(out, visited, body);
    }

    /// `illuminate(from [, axis, angle]) body` or `solar([axis, angle]) body`.
    fn emission(&mut self, solar: bool, args: &[ExprId], body: Block, in_light: bool, out: &mut Block) {
        let body = self.block(body, in_light);
        let Some(l) = self.l() else {
            out.extend(body);
            return;
        };
        let span = args.first().map_or(self.shader.span, |a| self.shader.expr(*a).span);
        let direction = if solar {
            args.first().copied()
        } else {
            let ps = global(self.shader, "Ps").expect("a light shader has `Ps`");
            let mut b = Builder::new(self.shader, span);
            let ps = b.push(ExprKind::Global(ps), Type::of(ps.ty));
            let from_light = b.binary(BinaryOp::Sub, ps, args[0]);
            Some(b.convert(from_light, Type::of(l.ty)))
        };
        if let Some(direction) = direction {
            out.push(Stmt::Store { place: Place::Global(l), value: direction, span: Span::default() });
        }
        let (axis, angle) = if solar { (args.first(), args.get(1)) } else { (args.get(1), args.get(2)) };
        match (axis, angle) {
            (Some(&axis), Some(&angle)) => out.push(self.within_cone(l, axis, angle, body)),
            _ => out.extend(body),
        }
    }

    /// The shader's `L`.
    fn l(&self) -> Option<&'static Global> {
        global(self.shader, "L")
    }

    /// `if (dot(L, axis) >= cos(angle) * sqrt(dot(L, L) * dot(axis, axis))) body`: the cone test
    /// of the light constructs (RenderMan's, without dividing by the lengths).
    fn within_cone(&mut self, l: &'static Global, axis: ExprId, angle: ExprId, body: Block) -> Stmt {
        let span = self.shader.expr(axis).span;
        let mut b = Builder::new(self.shader, span);
        let l = b.push(ExprKind::Global(l), Type::of(l.ty));
        let along = b.binary(BinaryOp::Dot, l, axis);
        let ll = b.binary(BinaryOp::Dot, l, l);
        let aa = b.binary(BinaryOp::Dot, axis, axis);
        let lengths = b.binary(BinaryOp::Mul, ll, aa);
        let lengths = b.call(BuiltinId::Sqrt, vec![lengths]);
        let cos = b.call(BuiltinId::Cos, vec![angle]);
        let bound = b.binary(BinaryOp::Mul, cos, lengths);
        let cond = b.binary(BinaryOp::Ge, along, bound);
        Stmt::If { cond, then: body, otherwise: Vec::new() }
    }
}

/// A loop over `lights` of `body`, when there is a light to visit and something to do.
fn push_loop(out: &mut Block, lights: Vec<u32>, body: Block) {
    if !lights.is_empty() && !body.is_empty() {
        out.push(Stmt::Lights { lights, body });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::syntax::preprocess::MemoryLoader;

    /// The first shader of `src`, prepared, with its light constructs over `lights`.
    fn unrolled(src: &str, lights: &[LightBinding]) -> Shader {
        let checked = crate::check_source("test.sl", src, &MemoryLoader::default());
        assert!(!checked.has_errors(), "{:?}", checked.diagnostics);
        let prepared = crate::opt::Prepared::new(checked.program.shaders[0].clone());
        unroll(&prepared, lights, &[])
    }

    /// The light lists of the light loops in `block`, outermost first, in order.
    fn loops(block: &Block, out: &mut Vec<Vec<u32>>) {
        for stmt in block {
            if let Stmt::Lights { lights, .. } = stmt {
                out.push(lights.clone());
            }
            stmt.for_each_block(|b| loops(b, out));
        }
    }

    fn light(ambient: bool, categories: &[&str]) -> LightBinding {
        LightBinding {
            ambient,
            categories: categories.iter().map(|c| c.to_string()).collect(),
            params: vec![],
        }
    }

    #[test]
    fn illuminance_visits_the_lights_its_category_selects_and_never_the_ambient_ones() {
        let lights = [light(false, &["key"]), light(true, &[]), light(false, &["fill"]), light(false, &[])];
        let src = "surface s() {
            illuminance(P) { Ci += Cl; }
            illuminance(\"fill\", P) { Ci += Cl; }
            illuminance(\"-fill\", P, N, 1) { Ci += Cl; }
        }";
        let shader = unrolled(src, &lights);
        let mut found = Vec::new();
        loops(&shader.body, &mut found);
        assert_eq!(found, vec![vec![0, 2, 3], vec![2], vec![0, 3]]);
        // The cone's loop runs its body under the test.
        let coned = shader.body.iter().filter(|s| matches!(s, Stmt::Lights { .. })).nth(2).unwrap();
        let Stmt::Lights { body, .. } = coned else { unreachable!() };
        assert!(matches!(body.as_slice(), [Stmt::If { .. }]), "{body:?}");
    }

    #[test]
    fn light_sums_become_sums_over_their_lights() {
        let lights = [light(true, &[]), light(false, &[]), light(true, &[])];
        let src = "surface s() { Ci = ambient(); }";
        let shader = unrolled(src, &lights);
        let sums: Vec<&Vec<u32>> = shader
            .exprs
            .iter()
            .filter_map(|e| match &e.kind {
                ExprKind::LightSum { lights, .. } => Some(lights),
                _ => None,
            })
            .collect();
        assert_eq!(sums, vec![&vec![0, 2]]);
        // Stanford: `integrate` over every light, and a per-light statement in a loop over every light.
        let src = "surface shader float4 s() {
            perlight float3 c = rgb(Cl) * max(dot(L, {0, 0, 1}), 0);
            return {integrate(c), 1};
        }";
        let shader = unrolled(src, &lights);
        let mut found = Vec::new();
        loops(&shader.body, &mut found);
        assert_eq!(found, vec![vec![0, 1, 2]]);
        assert!(
            shader
                .exprs
                .iter()
                .any(|e| matches!(&e.kind, ExprKind::LightSum { lights, .. } if lights == &[0, 1, 2]))
        );
    }

    #[test]
    fn emission_stores_l_and_runs_its_body_inside_the_cone() {
        let src =
            "light l(point from = point(0, 1, 0)) { illuminate(from, vector(0, -1, 0), 0.5) { Cl = 1; } }";
        let shader = unrolled(src, &[]);
        assert!(
            matches!(
                shader.body.as_slice(),
                [.., Stmt::Store { place: Place::Global(g), .. }, Stmt::If { .. }] if g.name == "L"
            ),
            "{:?}",
            shader.body
        );
        let src = "light l() { solar() { Cl = 1; } }";
        let shader = unrolled(src, &[]);
        assert!(!shader.body.iter().any(|s| matches!(s, Stmt::Emit { .. } | Stmt::If { .. })));
    }

    /// The inlined calls of `function` in `block`, at any depth.
    fn calls(block: &[Stmt], function: &str) -> usize {
        block
            .iter()
            .map(|s| {
                let mut n = usize::from(matches!(s, Stmt::Inline { function: f, .. } if f == function));
                s.for_each_block(|b| n += calls(b, function));
                n
            })
            .sum()
    }

    /// The per-light variables `opt::lights` added to hold shared calls.
    fn shared(shader: &Shader) -> Vec<&str> {
        shader.locals.iter().filter(|l| l.name.ends_with(" per light")).map(|l| l.name.as_str()).collect()
    }

    #[test]
    fn a_call_that_two_light_sums_repeat_is_computed_once_per_light() {
        // diffuse normalizes L for each light, specular too (and then L + V): the first two are
        // one call, computed before the sums, over every light either sum visits.
        let lights = [light(false, &["key"]), light(true, &[]), light(false, &[])];
        let src = "surface s() {
            normal Nf = normalize(N);
            Ci = diffuse(Nf) + specular(Nf, -normalize(I), 0.1);
        }";
        let prepared = {
            let checked = crate::check_source("test.sl", src, &MemoryLoader::default());
            crate::opt::Prepared::new(checked.program.shaders[0].clone())
        };
        assert_eq!(calls(&prepared.body, "lighting_normalize"), 3);
        let shader = unrolled(src, &lights);
        assert_eq!(shared(&shader), ["lighting_normalize per light"]);
        assert!(shader.locals.last().unwrap().rate.perlight);
        assert_eq!(calls(&shader.body, "lighting_normalize"), 2, "one shared, H's left in specular");
        let mut found = Vec::new();
        loops(&shader.body, &mut found);
        assert_eq!(found, vec![vec![0, 2], vec![0, 2], vec![0, 2]], "the shared call's loop comes first");
        let first = shader.body.iter().position(|s| matches!(s, Stmt::Lights { .. })).unwrap();
        let sums = shader.body.iter().position(|s| calls(std::slice::from_ref(s), "rm_diffuse") > 0).unwrap();
        assert!(first < sums, "the shared loop runs before the sums");
        // Only two lights' worth of sums in one: nothing repeats, nothing is shared.
        let src = "surface s() { Ci = diffuse(normalize(N)); }";
        assert!(shared(&unrolled(src, &lights)).is_empty());
    }

    #[test]
    fn calls_that_depend_on_more_than_the_light_are_not_shared() {
        let lights = [light(false, &[]), light(false, &[])];
        // An argument read from a variable that changes between the loops.
        let src = "surface s() {
            vector d = vector(1, 0, 0);
            color c = 0;
            illuminance(P) { c += Cl * (normalize(L + d) . N); }
            d = vector(0, 1, 0);
            illuminance(P) { c += Cl * (normalize(L + d) . N); }
            Ci = c;
        }";
        assert!(shared(&unrolled(src, &lights)).is_empty());
        // A predefined variable the shader stores.
        let src = "float lit(vector l) { return l . vector(Ci); }
        surface s() {
            Ci = 1;
            float a = 0;
            illuminance(P) { a += lit(L); }
            Ci = 0.5;
            illuminance(P) { a += lit(L); }
            Oi = a;
        }";
        assert!(shared(&unrolled(src, &lights)).is_empty());
        // A call with an output parameter beside its result.
        let src = "float halve(vector l; output float n) { n = l . l; return n / 2; }
        surface s() {
            float a = 0, n = 0;
            illuminance(P) { a += halve(L, n); }
            illuminance(P) { a += halve(L, n); }
            Oi = a + n;
        }";
        assert!(shared(&unrolled(src, &lights)).is_empty());
        // The same function of the same light in both loops is shared.
        let src = "float len(vector l) { return sqrt(l . l); }
        surface s() {
            float a = 0;
            illuminance(P) { a += len(L); }
            Ci = a;
            illuminance(P) { a += 2 * len(L); }
            Oi = a;
        }";
        assert_eq!(shared(&unrolled(src, &lights)), ["len per light"]);
    }
}
