//! `[[shadow]]` tables: shadow maps the renderer makes by a depth pass from a light
//! (runtime/src/render/shadow.rs), read by the shaders' `shadow(name, P)` under `name`.

use super::Light;
use super::error::{Locator, SceneError, field};
use super::schema::RawShadowMap;
use super::value::ParamValue;

/// The resolution of a map that does not set one.
pub const DEFAULT_RESOLUTION: u32 = 512;

/// The largest resolution a map may have (texels along each side).
pub const MAX_RESOLUTION: u32 = 4096;

/// The smallest: the map's last row holds its 4×4 matrix and its bias in five texels.
pub const MIN_RESOLUTION: u32 = 8;

/// A shadow map, checked: the light it is seen from and its camera settings.
#[derive(Clone, Debug, PartialEq)]
pub struct ShadowMap {
    /// The name the shaders look it up by (a light's `shadowname`).
    pub name: String,
    /// Which light (an index into [`super::Scene::lights`]): its `from` and `to` parameters place
    /// the map's camera, and its `coneangle` gives the field of view unless `fov` does.
    pub light: usize,
    /// Texels along each side.
    pub resolution: u32,
    /// The field of view in degrees; `None` for twice the light's `coneangle` plus a margin.
    pub fov: Option<f32>,
    /// The near clipping distance (default 0.05).
    pub near: f32,
    /// The far clipping distance (default 1000).
    pub far: f32,
    /// The depth bias of lookups that give no `"bias"` (default 0), in the light camera's units.
    pub bias: f32,
    /// Parallel projection (`projection = "orthographic"`, for distant lights) instead of
    /// perspective from the light's `from`.
    pub orthographic: bool,
    /// The world point the map looks at instead of the light's `to`: six maps with `fov = 90`
    /// looking along the axes from a point light's `from` make its cube of maps (as Aqsis's
    /// `shadowpoint` reads them, one per direction of L).
    pub to: Option<[f32; 3]>,
}

/// The `[[shadow]]` tables, checked against the lights.
pub(super) fn shadow_maps(
    raw: &[RawShadowMap],
    lights: &[Light],
    loc: &Locator,
) -> Result<Vec<ShadowMap>, SceneError> {
    let mut maps: Vec<ShadowMap> = Vec::new();
    for (i, r) in raw.iter().enumerate() {
        let at = field(&["shadow"]).index(i);
        let name = r.name.trim();
        if name.is_empty() {
            return Err(loc.invalid(&at.key("name"), "the shadow map's name is empty"));
        }
        if maps.iter().any(|m| m.name == name) {
            return Err(loc.invalid(&at.key("name"), format!("a second shadow map named `{name}`")));
        }
        let light = match usize::try_from(r.light) {
            Ok(l) if l < lights.len() => l,
            _ => {
                let n = lights.len();
                let message = format!("there is no light {} (the scene has {n}, numbered from 0)", r.light);
                return Err(loc.invalid(&at.key("light"), message));
            }
        };
        if let Some(to) = r.to
            && !to.iter().all(|x| x.is_finite())
        {
            return Err(loc.invalid(&at.key("to"), "`to` must be three finite numbers (world space)"));
        }
        let needed: &[&str] = if r.to.is_some() { &["from"] } else { &["from", "to"] };
        for &p in needed {
            match lights[light].shader.params.get(p) {
                Some(ParamValue::Numbers(v)) if v.len() == 3 && v.iter().all(|x| x.is_finite()) => {}
                _ => {
                    let message = format!(
                        "light {light} must set `{p}` (three numbers, world space) to cast a shadow map{}",
                        if p == "to" { ", or the map its own `to`" } else { "" }
                    );
                    return Err(loc.invalid(&at.key("light"), message));
                }
            }
        }
        let resolution = match r.resolution {
            None => DEFAULT_RESOLUTION,
            Some(v) => match u32::try_from(v) {
                Ok(v) if (MIN_RESOLUTION..=MAX_RESOLUTION).contains(&v) => v,
                _ => {
                    let message = format!("must be between {MIN_RESOLUTION} and {MAX_RESOLUTION}, found {v}");
                    return Err(loc.invalid(&at.key("resolution"), message));
                }
            },
        };
        if let Some(fov) = r.fov
            && !(fov.is_finite() && fov > 0.0 && fov < 180.0)
        {
            return Err(loc.invalid(&at.key("fov"), "the field of view must be in (0, 180) degrees"));
        }
        let near = r.near.unwrap_or(0.05);
        let far = r.far.unwrap_or(1000.0);
        if !(near.is_finite() && far.is_finite() && near > 0.0 && far > near) {
            return Err(loc.invalid(&at, "near and far must be finite with 0 < near < far"));
        }
        let bias = r.bias.unwrap_or(0.0);
        if !bias.is_finite() {
            return Err(loc.invalid(&at.key("bias"), "the bias must be a finite number"));
        }
        let orthographic = match r.projection.as_deref().map(str::trim) {
            None | Some("perspective") => false,
            Some("orthographic") => true,
            Some(other) => {
                let message = format!("the projection is `perspective` or `orthographic`, found `{other}`");
                return Err(loc.invalid(&at.key("projection"), message));
            }
        };
        maps.push(ShadowMap {
            name: name.to_string(),
            light,
            resolution,
            fov: r.fov,
            near,
            far,
            bias,
            orthographic,
            to: r.to,
        });
    }
    Ok(maps)
}

#[cfg(test)]
mod tests {
    use super::super::Scene;

    const HEAD: &str = "[camera]\nfrom = [0, 1, -5]\nto = [0, 0, 0]\n\n[[light]]\nshader = \"l.sl\"\nparams = { from = [1, 4, -1], to = [0, 0, 0] }\n\n[[light]]\nshader = \"l.sl\"\n\n";

    fn parse(shadow: &str) -> Result<Scene, String> {
        Scene::parse(&format!("{HEAD}[[shadow]]\n{shadow}\n"), "s.toml", ".").map_err(|e| e.to_string())
    }

    #[test]
    fn shadow_tables_are_checked_with_one_line_errors() {
        let scene = parse("name = \"a.shad\"\nlight = 0\nbias = 0.1").unwrap();
        let map = &scene.shadow_maps[0];
        assert_eq!((map.name.as_str(), map.light, map.resolution, map.bias), ("a.shad", 0, 512, 0.1));
        assert_eq!((map.fov, map.near, map.far, map.orthographic), (None, 0.05, 1000.0, false));
        let ortho = parse("name = \"a\"\nlight = 0\nprojection = \"orthographic\"").unwrap();
        assert!(ortho.shadow_maps[0].orthographic);
        for (table, says) in [
            ("name = \"a\"\nlight = 2", "there is no light 2"),
            ("name = \"a\"\nlight = -1", "there is no light -1"),
            ("name = \"a\"\nlight = 1", "must set `from`"),
            ("name = \" \"\nlight = 0", "name is empty"),
            ("name = \"a\"\nlight = 0\nresolution = 4", "between 8 and 4096"),
            ("name = \"a\"\nlight = 0\nfov = 180", "(0, 180)"),
            ("name = \"a\"\nlight = 0\nnear = 2\nfar = 1", "0 < near < far"),
            ("name = \"a\"\nlight = 0\nsize = 3", "size"),
            (
                "name = \"a\"\nlight = 0\nprojection = \"fisheye\"",
                "`perspective` or `orthographic`, found `fisheye`",
            ),
        ] {
            let e = parse(table).expect_err(table);
            assert!(e.contains(says) && !e.contains('\n'), "{table}: {e}");
        }
        let twice =
            format!("{HEAD}[[shadow]]\nname = \"a\"\nlight = 0\n\n[[shadow]]\nname = \"a\"\nlight = 0\n");
        let e = Scene::parse(&twice, "s.toml", ".").unwrap_err().to_string();
        assert!(e.contains("a second shadow map named `a`"), "{e}");
    }

    #[test]
    fn a_map_may_look_where_it_says_for_a_light_without_a_target() {
        let point = "[camera]\nfrom = [0, 1, -5]\nto = [0, 0, 0]\n\n[[light]]\nshader = \"l.sl\"\nparams = { from = [0, 4, 0] }\n\n";
        let with = |shadow: &str| {
            Scene::parse(&format!("{point}[[shadow]]\nname = \"f\"\nlight = 0\n{shadow}\n"), "s.toml", ".")
                .map_err(|e| e.to_string())
        };
        let scene = with("to = [1, 4, 0]\nfov = 90").unwrap();
        assert_eq!(scene.shadow_maps[0].to, Some([1.0, 4.0, 0.0]));
        let e = with("fov = 90").unwrap_err();
        assert!(e.contains("must set `to`") && e.contains("or the map its own `to`"), "{e}");
        let e = with("to = [1, 2]").unwrap_err();
        assert!(e.contains("shadow[0].to") && !e.contains('\n'), "{e}");
        let e = with("to = [1, nan, 0]").unwrap_err();
        assert!(e.contains("three finite numbers"), "{e}");
    }

    #[test]
    fn knobs_assign_shadow_resolution_and_light_parameters() {
        let text = format!(
            "{HEAD}[[shadow]]\nname = \"a\"\nlight = 0\n\n[[object]]\nmesh = \"plane\"\nshader = \"p.sl\"\n\n[[knob]]\nname = \"res\"\nkind = \"shadow\"\nsettings = [{{ label = \"64\", set = {{ \"shadow.resolution\" = 64, \"light.from\" = 2 }} }}]\nreference = {{ label = \"1024\", set = {{ \"shadow.resolution\" = 1024 }} }}\n"
        );
        let scene = Scene::parse(&text, "s.toml", ".").unwrap();
        let low = scene.with_setting(&scene.knob("res").unwrap().settings[0]);
        assert_eq!(low.shadow_maps[0].resolution, 64);
        assert_eq!(low.lights[0].shader.params["from"], super::ParamValue::Number(2.0));
        assert!(!low.lights[1].shader.params.contains_key("from"));
        let bad = text.replace("\"light.from\"", "\"light.nothing\"");
        let e = Scene::parse(&bad, "s.toml", ".").unwrap_err().to_string();
        assert!(e.contains("no light's `params` set `nothing`"), "{e}");
        let bad = text.replace("= 64,", "= 5000,");
        let e = Scene::parse(&bad, "s.toml", ".").unwrap_err().to_string();
        assert!(e.contains("8..=4096"), "{e}");
    }
}
