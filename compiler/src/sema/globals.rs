//! Predefined variables: what each kind of shader can read and write without declaring it, with a
//! fixed type and rate (RenderMan's tables of section 12 of the RI spec, and Stanford's predefined
//! variables). The record of one, [`Global`], is the IR's (`ir/global.rs`); this module owns the
//! table and its lookup.

use crate::ir::global::{Access, Global, Scope, Styles};
use crate::ir::types::{Base, Frequency};
use crate::syntax::ast::ShaderKind;

const SURFACE: &[ShaderKind] = &[ShaderKind::Surface];
const LIGHT: &[ShaderKind] = &[ShaderKind::Light];
const VOLUME: &[ShaderKind] = &[ShaderKind::Volume];
const IMAGER: &[ShaderKind] = &[ShaderKind::Imager];
const SURFACE_DISPLACEMENT: &[ShaderKind] = &[ShaderKind::Surface, ShaderKind::Displacement];
/// The shaders with a surface under them: its parameters, derivatives and texture coordinates.
const SURFACE_LIGHT_DISPLACEMENT: &[ShaderKind] =
    &[ShaderKind::Surface, ShaderKind::Light, ShaderKind::Displacement];
const SURFACE_DISPLACEMENT_VOLUME: &[ShaderKind] =
    &[ShaderKind::Surface, ShaderKind::Displacement, ShaderKind::Volume];
const SURFACE_LIGHT_DISPLACEMENT_VOLUME: &[ShaderKind] =
    &[ShaderKind::Surface, ShaderKind::Light, ShaderKind::Displacement, ShaderKind::Volume];
/// Stanford has surface and light shaders (its deformation shaders have no kind here).
const SURFACE_LIGHT: &[ShaderKind] = &[ShaderKind::Surface, ShaderKind::Light];
const ALL: &[ShaderKind] = &[
    ShaderKind::Surface,
    ShaderKind::Light,
    ShaderKind::Displacement,
    ShaderKind::Volume,
    ShaderKind::Imager,
];

#[allow(clippy::too_many_arguments)]
const fn g(
    name: &'static str,
    ty: Base,
    frequency: Frequency,
    perlight: bool,
    access: Access,
    shaders: &'static [ShaderKind],
    styles: Styles,
    scope: Scope,
    doc: &'static str,
) -> Global {
    Global { name, ty, frequency, perlight, access, shaders, styles, scope, doc }
}

use Access::{Read, ReadWrite};
use Frequency::{Constant, Fragment, PrimitiveGroup, Vertex};
use Scope::{Anywhere, PerLight};
use Styles::{Both, RenderMan, Stanford};

/// Every predefined variable.
///
/// Rates: per-point geometric inputs are vertex-rate (interpolated); `du`, `dv` are fragment-rate
/// (screen derivatives); the eye position, times and matrices are primitive-group; outputs are
/// fragment-rate. The per-light values a surface sees (`L`, `Cl`, `Ol`, `H`) carry the rate of a
/// light computed per vertex; binding a light that computes per fragment raises them.
#[rustfmt::skip]
pub const GLOBALS: &[Global] = &[
    g("PI", Base::Float, Constant, false, Read, ALL, Both, Anywhere, "π"),
    // ---------------------------------------------------------------------------------------------
    // RenderMan (RI spec 3.2, Tables 12.1-12.5).
    // ---------------------------------------------------------------------------------------------
    // Surface-only inputs.
    g("Cs", Base::Color, Vertex, false, Read, SURFACE, RenderMan, Anywhere, "surface colour"),
    g("Os", Base::Color, Vertex, false, Read, SURFACE, RenderMan, Anywhere, "surface opacity"),
    g("dPdtime", Base::Vector, Vertex, false, Read, SURFACE, RenderMan, Anywhere, "change of P with time"),
    // Position and normal: written by displacement shaders (and, as RenderMan renderers allow, by
    // surface shaders); read by lights, where they belong to the light's own surface.
    g("P", Base::Point, Vertex, false, ReadWrite, SURFACE_DISPLACEMENT, RenderMan, Anywhere, "surface position"),
    g("P", Base::Point, Vertex, false, Read, LIGHT, RenderMan, Anywhere, "position on the light's surface"),
    g("P", Base::Point, Vertex, false, Read, VOLUME, RenderMan, Anywhere, "origin of the light ray"),
    g("P", Base::Point, Vertex, false, Read, IMAGER, RenderMan, Anywhere, "pixel position in raster space"),
    g("N", Base::Normal, Vertex, false, ReadWrite, SURFACE_DISPLACEMENT, RenderMan, Anywhere, "shading normal"),
    g("N", Base::Normal, Vertex, false, Read, LIGHT, RenderMan, Anywhere, "shading normal of the light's surface"),
    // The parametric surface: surface, light and displacement shaders.
    g("dPdu", Base::Vector, Vertex, false, Read, SURFACE_LIGHT_DISPLACEMENT, RenderMan, Anywhere, "change of P with u"),
    g("dPdv", Base::Vector, Vertex, false, Read, SURFACE_LIGHT_DISPLACEMENT, RenderMan, Anywhere, "change of P with v"),
    g("Ng", Base::Normal, Vertex, false, Read, SURFACE_LIGHT_DISPLACEMENT, RenderMan, Anywhere, "geometric normal"),
    g("u", Base::Float, Vertex, false, Read, SURFACE_LIGHT_DISPLACEMENT, RenderMan, Anywhere, "surface parameter u"),
    g("v", Base::Float, Vertex, false, Read, SURFACE_LIGHT_DISPLACEMENT, RenderMan, Anywhere, "surface parameter v"),
    g("du", Base::Float, Fragment, false, Read, SURFACE_LIGHT_DISPLACEMENT, RenderMan, Anywhere, "change of u between adjacent samples"),
    g("dv", Base::Float, Fragment, false, Read, SURFACE_LIGHT_DISPLACEMENT, RenderMan, Anywhere, "change of v between adjacent samples"),
    g("s", Base::Float, Vertex, false, Read, SURFACE_LIGHT_DISPLACEMENT, RenderMan, Anywhere, "texture coordinate s"),
    g("t", Base::Float, Vertex, false, Read, SURFACE_LIGHT_DISPLACEMENT, RenderMan, Anywhere, "texture coordinate t"),
    // Aqsis gives imagers s and t too: the pixel's position across the image, in [0, 1].
    g("s", Base::Float, Vertex, false, Read, IMAGER, RenderMan, Anywhere, "horizontal position in the image, 0 to 1"),
    g("t", Base::Float, Vertex, false, Read, IMAGER, RenderMan, Anywhere, "vertical position in the image, 0 to 1 (downwards)"),
    // The viewer.
    g("I", Base::Vector, Vertex, false, Read, SURFACE_DISPLACEMENT_VOLUME, RenderMan, Anywhere, "incident ray direction, eye to point"),
    g("E", Base::Point, PrimitiveGroup, false, Read, SURFACE_LIGHT_DISPLACEMENT_VOLUME, RenderMan, Anywhere, "position of the eye"),
    // Light arriving at a surface: one value per light, inside `illuminance`.
    g("L", Base::Vector, Vertex, true, Read, SURFACE, RenderMan, PerLight, "direction from the point to the light"),
    g("Cl", Base::Color, Vertex, true, Read, SURFACE, RenderMan, PerLight, "colour of the light arriving"),
    g("Ol", Base::Color, Vertex, true, Read, SURFACE, RenderMan, PerLight, "opacity of the light arriving"),
    // Light shaders: `L` inside `illuminate`/`solar`; the outputs anywhere.
    g("L", Base::Vector, Vertex, false, ReadWrite, LIGHT, RenderMan, Anywhere, "direction from the light to the point lit (ambient lights set it to 0)"),
    g("Ps", Base::Point, Vertex, false, Read, LIGHT, RenderMan, Anywhere, "the surface point being lit"),
    g("Cl", Base::Color, Fragment, false, ReadWrite, LIGHT, RenderMan, Anywhere, "colour of the light emitted"),
    g("Ol", Base::Color, Fragment, false, ReadWrite, LIGHT, RenderMan, Anywhere, "opacity of the light emitted"),
    // Outputs.
    g("Ci", Base::Color, Fragment, false, ReadWrite, SURFACE, RenderMan, Anywhere, "output colour"),
    g("Oi", Base::Color, Fragment, false, ReadWrite, SURFACE, RenderMan, Anywhere, "output opacity"),
    g("Ci", Base::Color, Fragment, false, ReadWrite, VOLUME, RenderMan, Anywhere, "colour of the ray, in and out"),
    g("Oi", Base::Color, Fragment, false, ReadWrite, VOLUME, RenderMan, Anywhere, "opacity of the ray, in and out"),
    g("Ci", Base::Color, Fragment, false, ReadWrite, IMAGER, RenderMan, Anywhere, "pixel colour"),
    g("Oi", Base::Color, Fragment, false, ReadWrite, IMAGER, RenderMan, Anywhere, "pixel opacity"),
    g("alpha", Base::Float, Fragment, false, ReadWrite, IMAGER, RenderMan, Anywhere, "fractional pixel coverage"),
    // Every shader.
    g("ncomps", Base::Float, Constant, false, Read, ALL, RenderMan, Anywhere, "number of colour components (3)"),
    g("time", Base::Float, PrimitiveGroup, false, Read, ALL, RenderMan, Anywhere, "shutter time of the frame"),
    g("dtime", Base::Float, PrimitiveGroup, false, Read, ALL, RenderMan, Anywhere, "time covered by the frame"),
    // ---------------------------------------------------------------------------------------------
    // Stanford (Mark's chapter of Texturing & Modeling, book lines 3275-3402 and 3520-3660). The
    // implicit variables, in eye space and normalized, with w = 0 for directions and 1 for points.
    // Light shaders run at the surface point they light, so they see its geometry too.
    // ---------------------------------------------------------------------------------------------
    g("P", Base::Float4, Vertex, false, Read, SURFACE_LIGHT, Stanford, Anywhere, "eye-space position, w = 1"),
    g("Pobj", Base::Float4, Vertex, false, Read, SURFACE_LIGHT, Stanford, Anywhere, "object-space position, w = 1"),
    g("N", Base::Float3, Vertex, false, Read, SURFACE_LIGHT, Stanford, Anywhere, "eye-space normal, normalized"),
    g("B", Base::Float3, Vertex, false, Read, SURFACE_LIGHT, Stanford, Anywhere, "eye-space binormal, normalized"),
    g("T", Base::Float3, Vertex, false, Read, SURFACE_LIGHT, Stanford, Anywhere, "eye-space tangent, normalized"),
    g("E", Base::Float3, Vertex, false, Read, SURFACE_LIGHT, Stanford, Anywhere, "eye-space direction to the eye, normalized"),
    // Per light, in surface shaders.
    g("L", Base::Float3, Vertex, true, Read, SURFACE, Stanford, PerLight, "eye-space direction to the light, normalized"),
    g("H", Base::Float3, Vertex, true, Read, SURFACE, Stanford, PerLight, "half-angle vector between L and E, normalized"),
    g("Cl", Base::Float4, Vertex, true, Read, SURFACE, Stanford, PerLight, "colour of the light (what the light shader returned)"),
    g("Ca", Base::Float4, PrimitiveGroup, false, Read, SURFACE, Stanford, Anywhere, "colour of the global ambient light"),
    // In light shaders: the one light being computed.
    g("L", Base::Float3, Vertex, false, Read, LIGHT, Stanford, Anywhere, "eye-space direction from the point to this light, normalized"),
    g("Sdist", Base::Float, Vertex, false, Read, LIGHT, Stanford, Anywhere, "distance from the light to the surface point"),
    // The raw inputs from the geometry API, and the matrices.
    g("__position", Base::Float4, Vertex, false, Read, SURFACE_LIGHT, Stanford, Anywhere, "object-space vertex position, as given"),
    g("__normal", Base::Float3, Vertex, false, Read, SURFACE_LIGHT, Stanford, Anywhere, "object-space vertex normal, as given"),
    g("__binormal", Base::Float3, Vertex, false, Read, SURFACE_LIGHT, Stanford, Anywhere, "object-space vertex binormal, as given"),
    g("__objnormal", Base::Float3, Vertex, false, Read, SURFACE_LIGHT, Stanford, Anywhere, "object-space normal (as __normal)"),
    g("__objbinormal", Base::Float3, Vertex, false, Read, SURFACE_LIGHT, Stanford, Anywhere, "object-space binormal (as __binormal)"),
    g("__modelview", Base::Matrix4, PrimitiveGroup, false, Read, SURFACE_LIGHT, Stanford, Anywhere, "modelview matrix"),
    g("__modelview3", Base::Matrix3, PrimitiveGroup, false, Read, SURFACE_LIGHT, Stanford, Anywhere, "upper-left 3x3 of the modelview matrix"),
    g("__invmodelview", Base::Matrix4, PrimitiveGroup, false, Read, SURFACE_LIGHT, Stanford, Anywhere, "inverse of the modelview matrix"),
    g("__invmodelview3", Base::Matrix3, PrimitiveGroup, false, Read, SURFACE_LIGHT, Stanford, Anywhere, "inverse transpose of the 3x3 modelview (for normals)"),
    g("__projection", Base::Matrix4, PrimitiveGroup, false, Read, SURFACE_LIGHT, Stanford, Anywhere, "projection matrix"),
    g("__ambient", Base::Float4, PrimitiveGroup, false, Read, SURFACE_LIGHT, Stanford, Anywhere, "global ambient colour"),
];

/// Whether `name` is a predefined variable of any shader kind or style (backends keep their own
/// names clear of these).
pub fn is_predefined(name: &str) -> bool {
    GLOBALS.iter().any(|g| g.name == name)
}

/// The predefined variable `name` as seen from a shader of `kind` written in `stanford` style.
pub fn lookup(name: &str, kind: ShaderKind, stanford: bool) -> Option<&'static Global> {
    GLOBALS.iter().find(|g| g.name == name && g.seen_by(kind, stanford))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn globals_are_unique_per_kind_and_style() {
        for (i, a) in GLOBALS.iter().enumerate() {
            for b in &GLOBALS[i + 1..] {
                let same_style = a.styles == b.styles || a.styles == Both || b.styles == Both;
                let same_kind = a.shaders.iter().any(|k| b.shaders.contains(k));
                assert!(!(a.name == b.name && same_style && same_kind), "`{}` is defined twice", a.name);
            }
        }
    }

    #[test]
    fn lookup_respects_kind_and_style() {
        use ShaderKind::{Displacement, Imager, Light, Surface, Volume};
        assert_eq!(lookup("Cl", Surface, false).map(|g| g.perlight), Some(true));
        assert_eq!(lookup("Cl", Light, false).map(|g| (g.scope, g.access)), Some((Anywhere, ReadWrite)));
        assert_eq!(lookup("L", Light, false).map(|g| g.scope), Some(Anywhere));
        assert_eq!(lookup("L", Surface, false).map(|g| (g.scope, g.perlight)), Some((PerLight, true)));
        assert_eq!(lookup("Cl", Surface, true).map(|g| g.ty), Some(Base::Float4));
        assert!(lookup("Ci", Light, false).is_none());
        assert!(lookup("Ci", Displacement, false).is_none());
        assert_eq!(lookup("Ci", Volume, false).map(|g| g.access), Some(ReadWrite));
        assert_eq!(lookup("alpha", Imager, false).map(|g| g.frequency), Some(Fragment));
        assert!(lookup("alpha", Surface, false).is_none());
        assert_eq!(lookup("P", Displacement, false).map(|g| g.access), Some(ReadWrite));
        assert_eq!(lookup("P", Light, false).map(|g| g.access), Some(Read));
        assert_eq!(lookup("P", Surface, true).map(|g| g.ty), Some(Base::Float4));
        assert_eq!(lookup("N", Surface, true).map(|g| g.ty), Some(Base::Float3));
        assert_eq!(lookup("du", Surface, false).map(|g| g.frequency), Some(Fragment));
        assert_eq!(
            lookup("E", Surface, false).map(|g| (g.ty, g.frequency)),
            Some((Base::Point, PrimitiveGroup))
        );
        assert_eq!(lookup("ncomps", Imager, false).map(|g| g.frequency), Some(Constant));
        assert!(lookup("time", Imager, false).is_some() && lookup("time", Surface, true).is_none());
        assert!(lookup("I", Imager, false).is_none() && lookup("E", Imager, false).is_none());
        assert!(lookup("Ps", Light, false).is_some() && lookup("Ps", Surface, false).is_none());
        assert!(lookup("dPdtime", Surface, false).is_some() && lookup("dPdtime", Light, false).is_none());
        assert_eq!(lookup("H", Surface, true).map(|g| g.perlight), Some(true));
        assert!(lookup("H", Surface, false).is_none());
        assert_eq!(lookup("Ca", Surface, true).map(|g| g.frequency), Some(PrimitiveGroup));
        assert_eq!(lookup("Sdist", Light, true).map(|g| g.ty), Some(Base::Float));
        assert!(lookup("Sdist", Surface, true).is_none());
        assert_eq!(lookup("__invmodelview3", Surface, true).map(|g| g.ty), Some(Base::Matrix3));
        assert!(lookup("__modelview", Surface, false).is_none());
        assert_eq!(lookup("PI", Volume, true).map(|g| g.frequency), Some(Constant));
    }

    #[test]
    fn every_shader_kind_has_its_table() {
        use ShaderKind::{Displacement, Imager, Light, Surface, Volume};
        let names = |kind, stanford| {
            let mut v: Vec<&str> = GLOBALS
                .iter()
                .filter(|g| lookup(g.name, kind, stanford).is_some_and(|found| found == *g))
                .map(|g| g.name)
                .collect();
            v.sort_unstable();
            v.join(" ")
        };
        let sorted = |s: &str| {
            let mut v: Vec<&str> = s.split(' ').collect();
            v.sort_unstable();
            v.join(" ")
        };
        let rsl = |s: &str| sorted(&format!("PI {s}"));
        assert_eq!(
            names(Surface, false),
            rsl("Cs Os P dPdu dPdv N Ng u v du dv s t L Cl Ol E I ncomps time dtime dPdtime Ci Oi")
        );
        assert_eq!(names(Light, false), rsl("P dPdu dPdv N Ng u v du dv s t L Ps E Cl Ol ncomps time dtime"));
        assert_eq!(names(Displacement, false), rsl("P dPdu dPdv N Ng I E u v du dv s t ncomps time dtime"));
        assert_eq!(names(Volume, false), rsl("P I E Ci Oi ncomps time dtime"));
        assert_eq!(names(Imager, false), rsl("P s t Ci Oi alpha ncomps time dtime"));
        let raw = "__position __normal __binormal __objnormal __objbinormal __modelview __modelview3 \
                   __invmodelview __invmodelview3 __projection __ambient";
        let raw: Vec<&str> = raw.split_whitespace().collect();
        assert_eq!(names(Surface, true), rsl(&format!("P Pobj N B T E L H Cl Ca {}", raw.join(" "))));
        assert_eq!(names(Light, true), rsl(&format!("P Pobj N B T E L Sdist {}", raw.join(" "))));
    }
}
