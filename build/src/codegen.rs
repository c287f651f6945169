//! The Rust source generated for one compiled shader: a `#[repr(C)]` struct laid out as the
//! uniform block, and constants for its bindings, locations and entry points.

use std::collections::HashSet;
use std::fmt::Write as _;
use std::path::Path;

use patina::Interface;
use patina::interface::{AttributeSource, GeometryMatrix, ScalarKind, UniformField, UniformSource};

/// The type of one member of the generated struct: a 32-bit scalar or an array of them (every
/// member is 4-byte aligned, so `#[repr(C)]` places each right after the one before).
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum RustType {
    Scalar(ScalarKind),
    Array(Box<RustType>, u32),
}

impl RustType {
    pub(crate) fn size(&self) -> u32 {
        match self {
            RustType::Scalar(_) => 4,
            RustType::Array(t, n) => t.size() * n,
        }
    }

    pub(crate) fn render(&self) -> String {
        match self {
            RustType::Scalar(ScalarKind::I32) => "i32".into(),
            RustType::Scalar(ScalarKind::U32) => "u32".into(),
            RustType::Scalar(_) => "f32".into(),
            RustType::Array(t, n) => format!("[{}; {n}]", t.render()),
        }
    }
}

/// A member of the generated struct: a uniform field (its index in the interface) or padding.
#[derive(Clone, Debug)]
pub(crate) struct Member {
    pub ident: String,
    pub ty: RustType,
    pub offset: u32,
    pub field: Option<usize>,
}

fn scalar(kind: ScalarKind) -> Result<RustType, String> {
    match kind {
        ScalarKind::F32 | ScalarKind::I32 | ScalarKind::U32 => Ok(RustType::Scalar(kind)),
        other => Err(format!("scalar kind {other:?} has no Rust type here")),
    }
}

/// The Rust type that covers `field` exactly as the WGSL block lays it out: `f32` for a float,
/// `[f32; 3]` for a colour (whose 16-byte alignment is the offsets' business, not the type's),
/// `[[f32; 4]; 4]` for a matrix, `[[f32; 4]; 3]` for a 3x3 matrix (three padded columns), and
/// for an array `[E; N]` with each element `E` widened to the array's stride (`[[f32; 4]; N]`
/// for a `float[N]`, whose elements are 16 bytes apart in a uniform block).
pub(crate) fn type_of(field: &UniformField) -> Result<RustType, String> {
    let l = &field.layout;
    let s = scalar(l.scalar)?;
    let words = |t: RustType, n: u32| RustType::Array(Box::new(t), n);
    let element = if l.column_stride > 0 {
        if !l.column_stride.is_multiple_of(4) || l.column_stride < 12 || !l.components.is_multiple_of(3) {
            return Err(format!("`{}`: unexpected column stride {}", field.name, l.column_stride));
        }
        words(words(s.clone(), l.column_stride / 4), l.components / 3)
    } else {
        match l.components {
            0 => return Err(format!("`{}` has no components", field.name)),
            1 => s.clone(),
            16 => words(words(s.clone(), 4), 4),
            n => words(s.clone(), n),
        }
    };
    let is_array = field.ty.ends_with(']') || l.elements > 1;
    if !is_array {
        return Ok(element);
    }
    let stride = l.element_stride;
    let element = if element.size() == stride {
        element
    } else if element.size() < stride && stride.is_multiple_of(4) && l.column_stride == 0 && l.components <= 4
    {
        // A scalar or vector element padded to the array stride.
        words(s, stride / 4)
    } else {
        return Err(format!(
            "`{}`: an element of {} bytes does not fit the array stride {stride}",
            field.name,
            element.size()
        ));
    };
    Ok(words(element, l.elements.max(1)))
}

/// Rust's keywords that a raw identifier (`r#type`) can stand for.
const KEYWORDS: &[&str] = &[
    "as", "async", "await", "break", "const", "continue", "dyn", "else", "enum", "extern", "false", "fn",
    "for", "gen", "if", "impl", "in", "let", "loop", "match", "mod", "move", "mut", "pub", "ref", "return",
    "static", "struct", "trait", "true", "type", "unsafe", "use", "where", "while", "abstract", "become",
    "box", "do", "final", "macro", "override", "priv", "try", "typeof", "unsized", "virtual", "yield",
];

/// `name` as a Rust identifier: characters other than letters, digits and `_` become `_`, a
/// leading digit gets a `_` before it, a keyword is written raw (`r#type`) and the few that
/// cannot be (`self`, `crate`, ...) get a `_` after.
pub(crate) fn ident(name: &str) -> String {
    let mut s: String = name.chars().map(|c| if c.is_alphanumeric() || c == '_' { c } else { '_' }).collect();
    if s.is_empty() || s.starts_with(|c: char| c.is_ascii_digit()) {
        s.insert(0, '_');
    }
    if matches!(s.as_str(), "self" | "Self" | "super" | "crate" | "_") {
        s.push('_');
    } else if KEYWORDS.contains(&s.as_str()) {
        s.insert_str(0, "r#");
    }
    s
}

/// `base`, or `base` with `_` appended until it is not in `used`; then marks it used.
fn unique(base: String, used: &mut HashSet<String>) -> String {
    let mut s = base;
    while used.contains(&s) {
        s.push('_');
    }
    used.insert(s.clone());
    s
}

/// An upper-case constant name part for `name` (`checker:8` → `CHECKER_8`).
fn upper(name: &str) -> String {
    name.chars().map(|c| if c.is_alphanumeric() { c } else { '_' }).collect::<String>().to_uppercase()
}

/// The members of the struct for `interface`'s uniform block: its fields in order, with `_padN`
/// words wherever the block skips bytes, and at the end up to `uniform_size`.
pub(crate) fn plan(interface: &Interface) -> Result<Vec<Member>, String> {
    let mut used: HashSet<String> = HashSet::new();
    let idents: Vec<String> = interface.uniforms.iter().map(|f| unique(ident(&f.name), &mut used)).collect();
    let mut members = Vec::new();
    let mut pads = 0;
    let mut pad = |members: &mut Vec<Member>, from: u32, to: u32, used: &mut HashSet<String>| {
        let ident = unique(format!("_pad{pads}"), used);
        pads += 1;
        let ty = RustType::Array(Box::new(RustType::Scalar(ScalarKind::U32)), (to - from) / 4);
        members.push(Member { ident, ty, offset: from, field: None });
    };
    let mut cursor = 0u32;
    for (i, f) in interface.uniforms.iter().enumerate() {
        if !f.offset.is_multiple_of(4) {
            return Err(format!("uniform `{}` is at offset {}, not a multiple of 4", f.name, f.offset));
        }
        if f.offset < cursor {
            return Err(format!("uniform `{}` at offset {} overlaps the member before it", f.name, f.offset));
        }
        if f.offset > cursor {
            pad(&mut members, cursor, f.offset, &mut used);
        }
        let ty = type_of(f)?;
        if ty.size() < f.layout.size() {
            return Err(format!(
                "uniform `{}`: {} does not cover its {} bytes",
                f.name,
                ty.render(),
                f.layout.size()
            ));
        }
        members.push(Member { ident: idents[i].clone(), ty: ty.clone(), offset: f.offset, field: Some(i) });
        cursor = f.offset + ty.size();
    }
    if cursor > interface.uniform_size {
        return Err(format!(
            "the uniform members end at {cursor}, past the block's {}",
            interface.uniform_size
        ));
    }
    if !interface.uniform_size.is_multiple_of(4) {
        return Err(format!("the block's size {} is not a multiple of 4", interface.uniform_size));
    }
    if cursor < interface.uniform_size {
        pad(&mut members, cursor, interface.uniform_size, &mut used);
    }
    Ok(members)
}

/// Where a uniform's value comes from, in words.
fn describe(source: &UniformSource) -> String {
    match source {
        UniformSource::Param { name } => format!("the surface parameter `{name}`"),
        UniformSource::Host { name } => format!(
            "computed by the shader's host part (its output `{name}`): fill it at run time with \
             `patina::Uniforms`, or compile with `fold_host(true)` so that no field needs the host"
        ),
        UniformSource::Global { name } => format!("the predefined variable `{name}`"),
        UniformSource::Space { name, inverse, light } => {
            let whose = light.map_or(String::new(), |l| format!(" (of light {l})"));
            if *inverse {
                format!("the matrix from `{name}` space{whose} back to camera space")
            } else {
                format!("the matrix from camera space to `{name}` space{whose}")
            }
        }
        UniformSource::LightParam { light, name } => format!("parameter `{name}` of light {light}"),
        UniformSource::LightPosition { light } => {
            format!("the position of light {light} (a Stanford-style light), in camera space")
        }
        UniformSource::DisplacementParam { name } => format!("parameter `{name}` of the displacement shader"),
        UniformSource::AtmosphereParam { name } => format!("parameter `{name}` of the atmosphere shader"),
        UniformSource::Geometry { matrix } => match matrix {
            GeometryMatrix::ObjectToCamera => {
                "the object-to-camera matrix (column vectors, `v' = M v`)".into()
            }
            GeometryMatrix::NormalToCamera => {
                "the normal matrix, object to camera space (column vectors)".into()
            }
            GeometryMatrix::CameraToClip => {
                "the camera-to-clip matrix (column vectors, wgpu's clip space)".into()
            }
            other => format!("the geometry matrix {other:?}"),
        },
        UniformSource::Table { values } => format!(
            "a constant table of the shader ({} values: a noise's permutation or gradients); always \
             the constant of the same name in [`tables`]",
            values.len()
        ),
        other => format!("{other:?}"),
    }
}

/// Options of the generated code.
#[derive(Clone, Debug)]
pub(crate) struct Options {
    /// Derive `bytemuck::Pod` and `Zeroable` (the user's crate depends on `bytemuck`).
    pub bytemuck: bool,
}

/// A doc attribute with `text` (a Rust string literal, so any text is safe).
fn doc(out: &mut String, indent: &str, text: &str) {
    for line in text.lines() {
        let _ = writeln!(out, "{indent}#[doc = {:?}]", format!(" {line}"));
    }
}

/// The shared item types that every shader module's tables use (written once, at the top).
pub(crate) const PRELUDE: &str = r#"// Generated by patina-build: do not edit. Include it with
// `mod shaders { include!(concat!(env!("OUT_DIR"), "/patina_shaders.rs")); }`.

/// A member of a shader's uniform block (see each module's `FIELDS`).
#[allow(dead_code)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct UniformFieldInfo {
    /// The member's name in the WGSL text (and in the generated struct).
    pub name: &'static str,
    /// Its type in the shading language (`float`, `color`, `matrix`, `float[4]`, ...).
    pub ty: &'static str,
    /// Where its value comes from, as the interface's JSON writes it
    /// (`{"kind":"param","name":"Kd"}`; docs/interface.md lists the kinds).
    pub source: &'static str,
    /// Its byte offset in the block.
    pub offset: usize,
    /// The bytes its member of the generated struct spans.
    pub size: usize,
}

/// A vertex input of a shader (see each module's `ATTRIBUTES`).
#[allow(dead_code)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AttributeInfo {
    /// The entry point argument's name in the WGSL text.
    pub name: &'static str,
    /// Its `@location`.
    pub location: u32,
    /// `f32` components per vertex.
    pub components: u32,
}

/// A texture a shader reads: group 1, `binding`, read with `textureLoad` (no sampler).
#[allow(dead_code)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TextureInfo {
    /// The texture's name (a string parameter's value or a `texref` binding).
    pub name: &'static str,
    /// 2 or 3.
    pub dimensions: u32,
    /// Its `@binding` in group 1.
    pub binding: u32,
}
"#;

/// The module `module` for a compiled shader whose WGSL and interface JSON are at `wgsl` and
/// `json` (absolute paths, read with `include_str!`).
pub(crate) fn module(
    module: &str,
    source: &Path,
    interface: &Interface,
    wgsl: &Path,
    json: &Path,
    options: &Options,
) -> Result<String, String> {
    let members = plan(interface)?;
    let mut out = String::new();
    let i = "    ";
    let mut about = format!(
        "The shader `{}` compiled from `{}` by patina-build.\n\n\
         Bind the uniform block ([`Uniforms`], [`UNIFORM_SIZE`] bytes) at group [`UNIFORM_GROUP`], \
         binding [`UNIFORM_BINDING`]; textures at group [`TEXTURE_GROUP`] (see [`TEXTURES`]); vertex \
         inputs at the locations of [`ATTRIBUTES`]. The fragment entry point writes premultiplied RGBA \
         at `@location(0)`; points, vectors and normals are in camera space (docs/interface.md).",
        interface.shader,
        source.display()
    );
    if interface.needs_host {
        let host: Vec<String> = interface
            .uniforms
            .iter()
            .filter(|f| matches!(f.source, UniformSource::Host { .. }))
            .map(|f| format!("`{}`", f.name))
            .collect();
        let _ = write!(
            about,
            "\n\n**Needs the host part** ([`NEEDS_HOST`]): {} of the fields ({}) are computed by the \
             shader's host stage, which runs on the CPU. Fill the block at run time with \
             `patina::Uniforms` (`compiled.uniforms().bytes()`, which has this layout), or build the \
             shader with `fold_host(true)`: then every field is a parameter, a predefined variable, \
             a space or a geometry matrix, and a program without Patina can fill this struct.",
            host.len(),
            host.join(", ")
        );
    } else {
        about.push_str(
            "\n\nNo field needs the host part ([`NEEDS_HOST`] is false): a program without Patina can \
             fill this struct from the parameters, predefined variables, spaces and geometry matrices.",
        );
    }
    let _ = writeln!(out, "pub mod {} {{", ident(module));
    for line in about.lines() {
        let _ = writeln!(out, "{i}#![doc = {:?}]", format!(" {line}"));
    }
    let _ = writeln!(out, "{i}#![allow(non_snake_case, non_upper_case_globals, dead_code, clippy::all)]");
    let konst = |out: &mut String, text: &str, decl: String| {
        doc(out, i, text);
        let _ = writeln!(out, "{i}pub const {decl};");
    };
    konst(&mut out, "The surface shader's name.", format!("SHADER: &str = {:?}", interface.shader));
    konst(
        &mut out,
        "The WGSL module (entry points [`VERTEX_ENTRY`] and [`FRAGMENT_ENTRY`]).",
        format!("WGSL: &str = include_str!({:?})", wgsl.display().to_string()),
    );
    konst(
        &mut out,
        "The interface as JSON (docs/interface.md; `patina::Interface` deserializes it).",
        format!("INTERFACE_JSON: &str = include_str!({:?})", json.display().to_string()),
    );
    konst(&mut out, "The vertex entry point.", format!("VERTEX_ENTRY: &str = {:?}", interface.vertex_entry));
    konst(
        &mut out,
        "The fragment entry point.",
        format!("FRAGMENT_ENTRY: &str = {:?}", interface.fragment_entry),
    );
    konst(
        &mut out,
        "Whether some uniform is computed by the host part (see the module's documentation).",
        format!("NEEDS_HOST: bool = {}", interface.needs_host),
    );
    konst(&mut out, "The bind group of the uniform block.", "UNIFORM_GROUP: u32 = 0".into());
    konst(&mut out, "The binding of the uniform block in its group.", "UNIFORM_BINDING: u32 = 0".into());
    konst(
        &mut out,
        &format!(
            "The uniform block's size in bytes (`size_of::<Uniforms>()`; WGSL struct `{}`).",
            interface.uniform_struct
        ),
        format!("UNIFORM_SIZE: usize = {}", interface.uniform_size),
    );
    konst(
        &mut out,
        "The bind group of the textures (binding `k` is texture `k`).",
        "TEXTURE_GROUP: u32 = 1".into(),
    );

    let mut used = HashSet::new();
    for t in &interface.textures {
        let name = unique(format!("TEXTURE_{}_BINDING", upper(&t.name)), &mut used);
        konst(
            &mut out,
            &format!("The binding of texture `{}` ({}D) in group [`TEXTURE_GROUP`].", t.name, t.dimensions),
            format!("{name}: u32 = {}", t.binding),
        );
    }
    doc(&mut out, i, "The textures, in binding order.");
    let _ = writeln!(out, "{i}pub const TEXTURES: &[super::TextureInfo] = &[");
    for t in &interface.textures {
        let _ = writeln!(
            out,
            "{i}    super::TextureInfo {{ name: {:?}, dimensions: {}, binding: {} }},",
            t.name, t.dimensions, t.binding
        );
    }
    let _ = writeln!(out, "{i}];");

    for a in &interface.attributes {
        let (part, what) = match &a.source {
            AttributeSource::Mesh { what } => {
                (upper(what.name()), format!("the mesh's {what:?} (object space)").to_lowercase())
            }
            AttributeSource::Param { name } => {
                (format!("PARAM_{}", upper(name)), format!("the vertex-rate parameter `{name}`"))
            }
            other => (upper(&a.name), format!("{other:?}")),
        };
        let name = unique(format!("LOCATION_{part}"), &mut used);
        konst(
            &mut out,
            &format!("The `@location` of `{}`: {what}, {} `f32` per vertex.", a.name, a.components),
            format!("{name}: u32 = {}", a.location),
        );
    }
    doc(&mut out, i, "The vertex inputs the shader reads, by location.");
    let _ = writeln!(out, "{i}pub const ATTRIBUTES: &[super::AttributeInfo] = &[");
    for a in &interface.attributes {
        let _ = writeln!(
            out,
            "{i}    super::AttributeInfo {{ name: {:?}, location: {}, components: {} }},",
            a.name, a.location, a.components
        );
    }
    let _ = writeln!(out, "{i}];");

    // The struct.
    doc(
        &mut out,
        i,
        &format!(
            "The uniform block (WGSL struct `{}` at group 0, binding 0), member for member at the \
             WGSL offsets, with `_pad` words where the block skips bytes. Matrices are columns in the \
             layout of `glam::Mat4::to_cols_array`; a 3x3 matrix is three 16-byte columns; array \
             elements are padded to the block's 16-byte array stride.",
            interface.uniform_struct
        ),
    );
    let derives = if options.bytemuck {
        "Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable"
    } else {
        "Clone, Copy, Debug, PartialEq"
    };
    let _ = writeln!(out, "{i}#[repr(C)]\n{i}#[derive({derives})]\n{i}pub struct Uniforms {{");
    for m in &members {
        match m.field {
            Some(k) => {
                let f = &interface.uniforms[k];
                doc(
                    &mut out,
                    "        ",
                    &format!("`{}` `{}` at byte {}: {}.", f.ty, f.name, f.offset, describe(&f.source)),
                );
            }
            None => {
                doc(&mut out, "        ", &format!("Padding: {} bytes at byte {}.", m.ty.size(), m.offset))
            }
        }
        let _ = writeln!(out, "        pub {}: {},", m.ident, m.ty.render());
    }
    let _ = writeln!(out, "{i}}}");
    if options.bytemuck {
        let _ = writeln!(
            out,
            "{i}impl Uniforms {{\n{i}    /// The block's bytes, for `Queue::write_buffer`.\n\
             {i}    pub fn as_bytes(&self) -> &[u8] {{\n{i}        bytemuck::bytes_of(self)\n{i}    }}\n{i}}}"
        );
    }

    doc(&mut out, i, "The byte offset of each field of [`Uniforms`], by its name.");
    let _ = writeln!(out, "{i}pub mod offset {{");
    for m in members.iter().filter(|m| m.field.is_some()) {
        let _ = writeln!(out, "{i}    /// The offset of `Uniforms::{}`.", m.ident.trim_start_matches("r#"));
        let _ = writeln!(out, "{i}    pub const {}: usize = {};", m.ident, m.offset);
    }
    let _ = writeln!(out, "{i}}}");

    tables(&mut out, interface, &members);

    doc(&mut out, i, "The uniform block's members, in order (padding left out).");
    let _ = writeln!(out, "{i}pub const FIELDS: &[super::UniformFieldInfo] = &[");
    for m in &members {
        let Some(k) = m.field else { continue };
        let f = &interface.uniforms[k];
        let source = serde_json::to_string(&f.source).map_err(|e| e.to_string())?;
        let _ = writeln!(
            out,
            "{i}    super::UniformFieldInfo {{ name: {:?}, ty: {:?}, source: {:?}, offset: {}, size: {} }},",
            f.name,
            f.ty,
            source,
            f.offset,
            m.ty.size()
        );
    }
    let _ = writeln!(out, "{i}];");

    // The layout, checked when the user's crate compiles.
    let _ = writeln!(out, "{i}const _: () = {{");
    let _ = writeln!(out, "{i}    assert!(core::mem::size_of::<Uniforms>() == UNIFORM_SIZE);");
    for m in &members {
        let _ =
            writeln!(out, "{i}    assert!(core::mem::offset_of!(Uniforms, {}) == {});", m.ident, m.offset);
    }
    let _ = writeln!(out, "{i}}};");
    let _ = writeln!(out, "}}");
    Ok(out)
}

/// The module `tables`: for each constant table in the block, a constant of the member's type
/// and name holding its values as the block lays them out (each element padded to 16 bytes).
fn tables(out: &mut String, interface: &Interface, members: &[Member]) {
    let i = "    ";
    doc(out, i, "The values of the uniform block's constant tables, one constant per member of that name.");
    let _ = writeln!(out, "{i}pub mod tables {{");
    for m in members {
        let Some(k) = m.field else { continue };
        let f = &interface.uniforms[k];
        let UniformSource::Table { values } = &f.source else { continue };
        let per = (f.layout.element_stride / 4).max(1) as usize;
        let word = |x: Option<&f64>| match (f.layout.scalar, x) {
            (ScalarKind::F32, Some(x)) => format!("{:?}", *x as f32),
            (ScalarKind::F32, None) => "0.0".into(),
            (_, Some(x)) => format!("{}", *x as i64),
            (_, None) => "0".into(),
        };
        let elements: Vec<String> = values
            .iter()
            .map(|x| {
                let words: Vec<String> = (0..per).map(|w| word((w == 0).then_some(x))).collect();
                if per == 1 { words.join("") } else { format!("[{}]", words.join(", ")) }
            })
            .collect();
        doc(out, "        ", &format!("The values of `Uniforms::{}`.", m.ident.trim_start_matches("r#")));
        let _ = writeln!(out, "{i}    pub const {}: {} = [{}];", m.ident, m.ty.render(), elements.join(", "));
    }
    let _ = writeln!(out, "{i}}}");
}

#[cfg(test)]
mod tests {
    use super::*;
    use patina::interface::FieldLayout;

    fn field(name: &str, ty: &str, offset: u32, components: u32, elements: u32, stride: u32) -> UniformField {
        UniformField {
            name: name.into(),
            source: UniformSource::Param { name: name.into() },
            ty: ty.into(),
            offset,
            layout: FieldLayout {
                components,
                elements,
                element_stride: stride,
                column_stride: if components == 9 { 16 } else { 0 },
                scalar: ScalarKind::F32,
            },
        }
    }

    #[test]
    fn types_cover_each_layout() {
        let t = |f: UniformField| type_of(&f).unwrap().render();
        assert_eq!(t(field("a", "float", 0, 1, 1, 4)), "f32");
        assert_eq!(t(field("a", "color", 0, 3, 1, 16)), "[f32; 3]");
        assert_eq!(t(field("a", "float4", 0, 4, 1, 16)), "[f32; 4]");
        assert_eq!(t(field("a", "matrix", 0, 16, 1, 64)), "[[f32; 4]; 4]");
        assert_eq!(t(field("a", "matrix3", 0, 9, 1, 48)), "[[f32; 4]; 3]");
        assert_eq!(t(field("a", "float[5]", 0, 1, 5, 16)), "[[f32; 4]; 5]");
        assert_eq!(t(field("a", "color[2]", 0, 3, 2, 16)), "[[f32; 4]; 2]");
        assert_eq!(t(field("a", "matrix[2]", 0, 16, 2, 64)), "[[[f32; 4]; 4]; 2]");
        assert_eq!(t(field("a", "matrix3[2]", 0, 9, 2, 48)), "[[[f32; 4]; 3]; 2]");
        assert_eq!(t(field("a", "float[1]", 0, 1, 1, 16)), "[[f32; 4]; 1]");
        let mut int = field("a", "int", 0, 1, 1, 4);
        int.layout.scalar = ScalarKind::I32;
        assert_eq!(t(int), "i32");
    }

    #[test]
    fn padding_fills_every_gap_up_to_the_block_size() {
        let interface = Interface {
            uniforms: vec![
                field("m", "matrix", 0, 16, 1, 64),
                field("Kd", "float", 64, 1, 1, 4),
                field("tint", "color", 80, 3, 1, 16),
                field("Ks", "float", 92, 1, 1, 4),
                field("weights", "float[3]", 96, 1, 3, 16),
                field("n", "matrix3", 144, 9, 1, 48),
            ],
            uniform_size: 208,
            ..Interface::default()
        };
        let members = plan(&interface).unwrap();
        let mut at = 0;
        for m in &members {
            assert_eq!(m.offset, at, "{m:?}");
            at += m.ty.size();
        }
        assert_eq!(at, 208);
        let pads: Vec<(u32, u32)> =
            members.iter().filter(|m| m.field.is_none()).map(|m| (m.offset, m.ty.size())).collect();
        assert_eq!(pads, vec![(68, 12), (192, 16)]);
        for m in members.iter().filter(|m| m.field.is_some()) {
            assert_eq!(m.offset, interface.uniforms[m.field.unwrap()].offset);
        }
    }

    #[test]
    fn overlapping_or_oversized_fields_are_errors() {
        let overlap = Interface {
            uniforms: vec![field("a", "color", 0, 3, 1, 16), field("b", "float", 8, 1, 1, 4)],
            uniform_size: 16,
            ..Interface::default()
        };
        assert!(plan(&overlap).unwrap_err().contains("overlaps"));
        let past = Interface {
            uniforms: vec![field("a", "matrix", 0, 16, 1, 64)],
            uniform_size: 48,
            ..Interface::default()
        };
        assert!(plan(&past).unwrap_err().contains("past"));
    }

    #[test]
    fn identifiers_are_rust_identifiers_and_unique() {
        assert_eq!(ident("Ci_h1_"), "Ci_h1_");
        assert_eq!(ident("type"), "r#type");
        assert_eq!(ident("self"), "self_");
        assert_eq!(ident("checker:8"), "checker_8");
        assert_eq!(ident("3d"), "_3d");
        let interface = Interface {
            uniforms: vec![field("_pad0", "float", 0, 1, 1, 4), field("match", "float", 8, 1, 1, 4)],
            uniform_size: 16,
            ..Interface::default()
        };
        let idents: Vec<String> = plan(&interface).unwrap().into_iter().map(|m| m.ident).collect();
        assert_eq!(idents, ["_pad0", "_pad0_", "r#match", "_pad1"]);
    }
}
