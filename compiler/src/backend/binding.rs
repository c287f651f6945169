//! What a shader is compiled for, beyond its own code: the lights bound to it and the values of
//! its string parameters. Both backends bind lights late and the same way (ARCHITECTURE.md,
//! "Departures from DESIGN.md"): light loops and light sums are unrolled over exactly these
//! lights, `illuminance` selects them by category, and `lightsource` reads their parameters, so
//! the description of a binding is theirs in common: both make it from a [`BoundLight`] with
//! [`BoundLight::binding`] (or from a light shader with [`LightBinding::of`]).
//!
//! It lives beside the backends rather than in `bind/`: `bind` rewrites the IR before the stages
//! are split, while a binding is applied by each backend as it lowers the stages.

use smol_str::SmolStr;

use crate::ir::types::Type;
use crate::ir::{ExprKind, LocalKind, Shader};
use crate::opt::Prepared;

/// A shader bound beside a surface (a light, a displacement or an atmosphere), with the values
/// of its string parameters.
#[derive(Clone, Debug)]
pub struct BoundLight<'a> {
    /// The shader.
    pub shader: &'a Prepared,
    /// Its string parameters' values.
    pub strings: Vec<(String, String)>,
    /// Categories besides those its `__category` parameter names (for `illuminance("category",
    /// ...)`).
    pub categories: Vec<String>,
}

impl BoundLight<'_> {
    /// The light's binding as both backends apply it: [`LightBinding::of`] its shader and
    /// strings, in its extra categories too.
    pub fn binding(&self) -> LightBinding {
        let mut binding = LightBinding::of(self.shader, &self.strings);
        binding.categories.extend(self.categories.iter().cloned());
        binding
    }
}

/// What the program is compiled for: the decisions that change its code.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Binding {
    /// The lights, in order: `illuminance` and the light sums run over them.
    pub lights: Vec<LightBinding>,
    /// Values of `string` parameters (texture and space names), by parameter name.
    pub strings: Vec<(String, String)>,
}

/// One bound light.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LightBinding {
    /// An ambient light: summed by `ambient()`, skipped by `illuminance` and the other sums.
    pub ambient: bool,
    /// The categories it belongs to (`illuminance("category", ...)` selects on them).
    pub categories: Vec<String>,
    /// Its parameters, by name and type: what `lightsource("name", v)` can read from it.
    pub params: Vec<(SmolStr, Type)>,
}

/// The light parameter that names a light's categories (RenderMan's convention).
pub const CATEGORY_PARAM: &str = "__category";

impl LightBinding {
    /// The binding of light shader `light` whose string parameters have the values `strings`
    /// (the others their literal defaults): ambient when it emits no light, in the categories
    /// its `__category` parameter lists (comma-separated), with its parameters for `lightsource`.
    pub fn of(light: &Shader, strings: &[(String, String)]) -> LightBinding {
        let params: Vec<(SmolStr, Type)> =
            light.params.iter().map(|p| (light.local(*p).name.clone(), light.local(*p).ty)).collect();
        let category =
            light.params.iter().map(|p| light.local(*p)).find(|l| l.name == CATEGORY_PARAM).and_then(|l| {
                match strings.iter().find(|(n, _)| n == CATEGORY_PARAM) {
                    Some((_, v)) => Some(v.clone()),
                    None => match l.kind {
                        LocalKind::Param { default: Some(d), .. } => match &light.expr(d).kind {
                            ExprKind::Literal(crate::ir::Literal::String(s)) => Some(s.to_string()),
                            _ => None,
                        },
                        _ => None,
                    },
                }
            });
        let categories = category
            .iter()
            .flat_map(|c| c.split(','))
            .map(str::trim)
            .filter(|c| !c.is_empty())
            .map(String::from)
            .collect();
        LightBinding { ambient: crate::ir::is_ambient(light), categories, params }
    }
}

impl LightBinding {
    /// Whether `illuminance` with the category selector `category` (none: every light) visits
    /// this light, on both backends: never an ambient light, else one the selector matches.
    pub fn visited_by(&self, category: Option<&str>) -> bool {
        !self.ambient && category.is_none_or(|c| category_matches(c, &self.categories))
    }
}

/// RenderMan's category selection, which `illuminance("selector", ...)` applies to each bound
/// light on both backends: a light matches `"a,b"` when it is in any of those categories, and
/// `"-a"` when it is not in `a`.
pub(crate) fn category_matches(selector: &str, categories: &[String]) -> bool {
    match selector.strip_prefix('-') {
        Some(name) => !categories.iter().any(|c| c == name),
        None => selector.split(',').any(|s| categories.iter().any(|c| c == s.trim())),
    }
}
