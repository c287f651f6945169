//! Scenes: TOML files naming a camera, lights, objects, output settings and quality knobs.
//!
//! A complete scene, with every field (those marked "default" may be left out):
//!
//! ```toml
//! include = ["../include"]     # directories searched by every shader's #include after its own
//!                              # (relative to this file's directory; default none)
//!
//! [output]                     # the whole table is optional
//! width = 256                  # pixels, 1..=16384 (default 256)
//! height = 256                 # (default 256)
//! background = [0, 0, 0, 1]    # RGB or RGBA (default opaque black)
//! supersample = 1              # samples per pixel along each axis, 1..=16 (default 1)
//!
//! [camera]
//! from = [0, 1, -5]            # eye position (world space)
//! to = [0, 0, 0]               # the point at the image centre
//! up = [0, 1, 0]               # (default +y)
//! fov = 40                     # vertical field of view in degrees, in (0, 180) (default 40)
//! near = 0.1                   # clipping distances, 0 < near < far (default 0.1 and 100)
//! far = 100
//!
//! [[light]]                    # any number of lights
//! shader = "../shaders/lights.sl"        # relative to this file's directory, or a standard-
//!                                        # library module in brackets: "<shaders.sl>"
//! name = "spotlight"                     # which shader of the file (optional if it has one light)
//! params = { intensity = 20.0, from = [2, 3, -4], to = [0, 0, 0], lightcolor = [1.0, 0.9, 0.8] }
//!
//! [[light]]                    # a Stanford-style light shader: its shader computes the colour,
//! shader = "../shaders/aniso.sl"         # the scene places it
//! name = "falloff_light"
//! params = { lightcolor = [1, 1, 1, 1], constant_term = 1, linear_term = 0.1 }
//! position = [2, 3, -4]        # world space; required for a Stanford-style light, refused for a
//!                              # RenderMan-style one (its parameters place it, e.g. `from`)
//!
//! [[object]]                   # any number of objects
//! mesh = "sphere"              # sphere | torus | plane | cube | teapot, or { obj = "model.obj" }
//! detail = 64                  # tessellation, 1..=1024 (default 64; see MeshSource::build)
//! shader = "../shaders/plastic.sl"       # the surface shader
//! name = "plastic"                       # (optional)
//! params = { Kd = 0.8, roughness = 0.2, texturename = "grid.png", twosided = true }
//! animate = ["roughness"]      # parameters kept dynamic (the others set here are compiled in)
//! displacement = { shader = "../shaders/bumpy.sl", params = { Km = 0.05 } }   # (optional)
//! atmosphere = { shader = "../shaders/fog.sl", name = "fog", params = { falloff = 4 } }
//!                              # a volume shader run after the surface on its Ci and Oi
//!                              # (optional; default: the scene's [atmosphere], if any)
//! color = [1.0, 0.5, 0.2]      # Cs (default white)
//! opacity = [1, 1, 1]          # Os (default opaque)
//! transform = [              # (default: none)
//!     { translate = [0, 0, 1] },
//!     { rotate = { angle = 30, axis = [0, 1, 0] } },
//!     { scale = [2, 2, 2] },
//! ]
//!
//! [atmosphere]                 # (optional) every object's atmosphere, unless it has its own
//! shader = "../shaders/fog.sl"
//! name = "fog"
//! params = { falloff = 4, background = [0.5, 0.6, 0.7] }
//!
//! [imager]                     # (optional) an imager shader over the finished image, per pixel:
//! shader = "../shaders/imagers.sl"   # P is the raster position (pixel centres), s and t are
//! name = "background"                # in [0, 1] across the image, alpha is the coverage
//! params = { bgcolor = [0.2, 0.3, 0.4] }
//!
//! [[knob]]                     # any number: what `patina bench` sweeps (error against time)
//! kind = "steps"               # steps | step_size | octaves | samples | antialias | table_size |
//!                              # step_phase | early_termination | shadow | noise
//! param = "steps"              # a surface shader parameter; the knob is named after it unless
//!                              # `name` is given
//! object = 0                   # which object's (default: every object whose `params` set it)
//! values = [8, 16, 32, 64, 128]
//! reference = 512              # the setting the others are measured against
//!
//! [[knob]]                     # a knob whose settings assign several values
//! name = "finish"
//! kind = "antialias"
//! settings = [
//!     { label = "rough", set = { roughness = 0.4 } },
//!     { label = "smooth", set = { roughness = 0.1, Kd = 0.5 } },
//!     { label = "rough 4x4", set = { roughness = 0.4, "output.supersample" = 4 } },
//! ]
//! reference = { scene = "exact.toml", label = "exact" }   # or a setting { label, set }
//!
//! [[shadow]]                   # any number: a shadow map, a depth pass from a light
//! name = "spot.shad"           # what shaders look up: shadow("spot.shad", Ps) (a light's shadowname)
//! light = 0                    # which light's `from` and `to` (world space) place its camera
//! resolution = 512             # texels along each side, 8..=4096 (default 512)
//! bias = 0.04                  # depth bias of lookups that give no "bias" (default 0)
//! fov = 60                     # degrees (default: twice the light's `coneangle` plus 10)
//! near = 0.05                  # clipping distances (default 0.05 and 1000)
//! far = 1000
//! projection = "perspective"   # or "orthographic": parallel rays along from -> to, for distant
//!                              # lights, over a window fitted to the meshes (default perspective)
//! to = [1, 4, 0]               # optional: the world point the map looks at, instead of the
//!                              # light's `to` (six maps with fov = 90 along the axes from a point
//!                              # light's `from`: its cube, as `shadowpoint` reads it)
//!
//! [compare]                    # optional: how closely the GPU must match the CPU reference
//! hard_fail = 0.5              # (fail, hard_fail, max_failing_fraction: default OSL's, see
//! reason = "silhouettes"       #  image::Thresholds); the reason is required and shown
//! ```
//!
//! Besides surface parameters and `output.supersample`, a knob's setting may assign
//! `"shadow.resolution"` (every shadow map's resolution) and `"light.NAME"` (parameter NAME of
//! every light whose `params` set it, e.g. `"light.samples"`). A shadow map is drawn from the
//! undisplaced meshes by the CPU rasterizer, once per render, and the same texture goes to both
//! backends (`render::shadow`); a point light's six-map cube is not made.
//!
//! Parameter values are numbers, arrays of numbers, strings or booleans ([`ParamValue`]); the
//! shader's declaration gives them their type. The transformation list concatenates like
//! RenderMan's `Translate`/`Rotate`/`Scale` calls: the matrix is `T₀ · T₁ · … · Tₙ` (column
//! vectors), so the *last* step applies to the object's points first; the example scales, then
//! rotates, then moves the object. World space is left-handed like RenderMan's (see
//! [`crate::camera`]). The built-in meshes have unit size: a sphere of radius 1, a torus of radii
//! 1 and 0.25, a plane and a cube of side 2, the teapot in its own coordinates (z up, 3.15 tall).
//!
//! Every problem is reported as one line naming the file, the line and column, and the field:
//! `scenes/bad.toml:12:7: camera.fov: expected a number, found a string`. Unknown fields are
//! rejected with the list of allowed ones.

mod check;
mod error;
mod knob;
mod schema;
mod shadow;
mod value;

pub(crate) use error::io_message;
pub use error::{SceneError, SceneErrorKind};
pub use knob::{
    Assignment, Knob, KnobKind, LIGHT_PREFIX, Reference, SHADOW_RESOLUTION_KEY, SUPERSAMPLE_KEY, Setting,
};
pub use shadow::ShadowMap;
pub use value::{ParamValue, TransformStep};

use crate::camera::Camera;
use crate::image::Thresholds;
use crate::mesh::{Mesh, MeshError};
use error::Locator;
use glam::{Mat4, Vec3};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The tessellation level of an object that does not set `detail`.
pub const DEFAULT_DETAIL: u32 = 64;

/// A parsed and checked scene. Paths in it are resolved against the scene file's directory.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// The scene file as named when loading (for messages).
    pub file: PathBuf,
    /// Image settings.
    pub output: Output,
    /// The camera (also available as [`Scene::camera`]).
    pub camera: Camera,
    /// The lights, in file order.
    pub lights: Vec<Light>,
    /// The objects, in file order.
    pub objects: Vec<Object>,
    /// The quality knobs that `patina bench` sweeps, in file order.
    pub knobs: Vec<Knob>,
    /// The imager shader run over the finished image, pixel by pixel (`[imager]`), if any.
    pub imager: Option<ShaderRef>,
    /// The shadow maps the renderer makes by depth passes from lights (`[[shadow]]`).
    pub shadow_maps: Vec<ShadowMap>,
    /// How closely the GPU must match the CPU reference, when the scene says (OSL's thresholds
    /// otherwise: [`Scene::thresholds`]).
    pub compare: Option<Compare>,
}

/// A scene's own image thresholds, with the reason they differ from OSL's.
#[derive(Clone, Debug, PartialEq)]
pub struct Compare {
    /// The thresholds.
    pub thresholds: Thresholds,
    /// Why the two renderers may differ this much (shown beside the comparison).
    pub reason: String,
}

/// Image settings.
#[derive(Clone, Debug, PartialEq)]
pub struct Output {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// The colour of pixels no object covers, RGBA (straight alpha).
    pub background: [f32; 4],
    /// Samples per pixel along each axis (so `supersample²` per pixel), for references.
    pub supersample: u32,
}

/// A shader instance: a file, which shader of it, and the parameter values the scene sets.
#[derive(Clone, Debug, PartialEq)]
pub struct ShaderRef {
    /// The source file, resolved against the scene's directory.
    pub path: PathBuf,
    /// The shader's name; `None` when the file has exactly one shader of the needed kind.
    pub name: Option<String>,
    /// Parameter values by name; parameters not listed keep their defaults.
    pub params: BTreeMap<String, ParamValue>,
    /// The parameters the scene animates: they stay in the uniform block, where the others the
    /// scene sets are folded into the shader (DESIGN.md §4).
    pub animate: Vec<String>,
    /// Further directories searched by `#include` after the shader's own (the scene's `include`
    /// list, resolved against the scene's directory).
    pub include_dirs: Vec<PathBuf>,
}

/// A light source.
#[derive(Clone, Debug, PartialEq)]
pub struct Light {
    /// The light shader.
    pub shader: ShaderRef,
    /// Where a Stanford-style light is, in world space (its shader computes only the colour; the
    /// host places it, as OpenGL's light position does). A RenderMan-style light has none: its
    /// parameters place it (`from`). Rendering checks that the shader's style agrees.
    pub position: Option<Vec3>,
    /// The line of its `[[light]]` header, for later messages about it.
    pub line: usize,
}

/// Where an object's geometry comes from.
#[derive(Clone, Debug, PartialEq)]
pub enum MeshSource {
    /// [`Mesh::sphere`] of radius 1.
    Sphere,
    /// [`Mesh::torus`] of radii 1 and 0.25.
    Torus,
    /// [`Mesh::plane`] of side 2.
    Plane,
    /// [`Mesh::cube`] of side 2.
    Cube,
    /// [`Mesh::teapot`].
    Teapot,
    /// An OBJ file (resolved path), read by [`Mesh::load_obj`].
    Obj(PathBuf),
}

impl MeshSource {
    /// The mesh in object space. `detail` is the number of cells around the longest parameter:
    /// sphere and torus `detail × detail/2`, plane `detail × detail`, each teapot patch
    /// `detail/4 × detail/4`; the cube and OBJ files ignore it.
    pub fn build(&self, detail: u32) -> Result<Mesh, MeshError> {
        let half = (detail / 2).max(2);
        Ok(match self {
            MeshSource::Sphere => Mesh::sphere(1.0, detail, half),
            MeshSource::Torus => Mesh::torus(1.0, 0.25, detail, half.max(3)),
            MeshSource::Plane => Mesh::plane(2.0, detail),
            MeshSource::Cube => Mesh::cube(2.0),
            MeshSource::Teapot => Mesh::teapot((detail / 4).max(1)),
            MeshSource::Obj(path) => Mesh::load_obj(path)?,
        })
    }
}

/// An object: geometry, shaders, colours and placement.
#[derive(Clone, Debug, PartialEq)]
pub struct Object {
    /// The geometry.
    pub mesh: MeshSource,
    /// The tessellation level ([`DEFAULT_DETAIL`] unless the scene sets it).
    pub detail: u32,
    /// The surface shader.
    pub surface: ShaderRef,
    /// The displacement shader, if any.
    pub displacement: Option<ShaderRef>,
    /// The atmosphere (volume) shader run after the surface on its colour and opacity: the
    /// object's own `atmosphere`, or the scene's `[atmosphere]`, if any.
    pub atmosphere: Option<ShaderRef>,
    /// `Cs`.
    pub color: [f32; 3],
    /// `Os`.
    pub opacity: [f32; 3],
    /// The transformation steps as written; [`Object::transform_matrix`] concatenates them.
    pub transform: Vec<TransformStep>,
    /// The line of its `[[object]]` header, for later messages about it.
    pub line: usize,
}

impl Object {
    /// Object to world space: the steps concatenated RenderMan's way, `T₀ · T₁ · … · Tₙ`.
    pub fn transform_matrix(&self) -> Mat4 {
        self.transform.iter().fold(Mat4::IDENTITY, |m, step| m * step.matrix())
    }

    /// The mesh in object space.
    pub fn build_mesh(&self) -> Result<Mesh, MeshError> {
        self.mesh.build(self.detail)
    }
}

impl Scene {
    /// Adds `dirs` to every shader's `#include` search path, after the shader's own folder and
    /// the scene's `include` list (the command line's `-I`).
    pub fn add_include_dirs(&mut self, dirs: &[PathBuf]) {
        for shader in self.shaders_mut() {
            shader.include_dirs.extend(dirs.iter().cloned());
        }
    }

    /// Every shader the scene refers to: the lights', then each object's surface, displacement
    /// and atmosphere, then the imager.
    pub fn shaders_mut(&mut self) -> impl Iterator<Item = &mut ShaderRef> {
        let lights = self.lights.iter_mut().map(|l| &mut l.shader);
        let objects = self.objects.iter_mut().flat_map(|o| {
            std::iter::once(&mut o.surface).chain(o.displacement.as_mut()).chain(o.atmosphere.as_mut())
        });
        lights.chain(objects).chain(self.imager.as_mut())
    }

    /// Reads and checks a scene file; relative paths in it are resolved against its directory.
    pub fn load(path: impl AsRef<Path>) -> Result<Scene, SceneError> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path).map_err(|e| SceneError {
            file: path.display().to_string(),
            kind: SceneErrorKind::Read,
            position: None,
            field: None,
            message: io_message(&e),
        })?;
        let base = path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
        Scene::parse(&text, path, base)
    }

    /// Parses and checks scene text. `file` names it in messages; relative paths in it are
    /// resolved against `base_dir`.
    pub fn parse(
        text: &str,
        file: impl AsRef<Path>,
        base_dir: impl AsRef<Path>,
    ) -> Result<Scene, SceneError> {
        let file = file.as_ref();
        let mut locator = Locator { file: file.display().to_string(), text, root: None };
        let root = match toml::de::DeTable::parse(text) {
            Ok(root) => root,
            Err(e) => {
                // What did parse still names the field the error is in.
                let (partial, _) = toml::de::DeTable::parse_recoverable(text);
                locator.root = Some(&partial);
                return Err(locator.toml_error(SceneErrorKind::Syntax, &e));
            }
        };
        locator.root = Some(&root);
        let raw: schema::RawScene =
            serde::Deserialize::deserialize(toml::de::Deserializer::from(root.clone()))
                .map_err(|e| locator.toml_error(SceneErrorKind::Schema, &e))?;
        check::build(raw, &locator, file, base_dir.as_ref())
    }

    /// The camera.
    pub fn camera(&self) -> Camera {
        self.camera
    }

    /// Object `i`'s object-to-world matrix; the identity when there is no object `i`.
    pub fn object_transform(&self, i: usize) -> Mat4 {
        self.objects.get(i).map_or(Mat4::IDENTITY, Object::transform_matrix)
    }

    /// The thresholds the GPU's image must meet against the CPU reference's.
    pub fn thresholds(&self) -> Thresholds {
        self.compare.as_ref().map_or_else(Thresholds::default, |c| c.thresholds)
    }

    /// The image's width / height.
    pub fn aspect(&self) -> f32 {
        self.output.width as f32 / self.output.height.max(1) as f32
    }
}

/// `s` as a TOML basic string, for scene text written by a program.
pub fn toml_string(s: &str) -> String {
    let mut out = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if c.is_control() => out.push_str(&format!("\\u{:04X}", c as u32)),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}
