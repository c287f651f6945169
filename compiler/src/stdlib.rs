//! The standard library's sources, embedded at build time so that `#include <name.sl>` works without
//! any installed files.

use crate::ir::builtin::BuiltinId;

/// The directory name standard-library files are shown under in diagnostics.
pub const PREFIX: &str = "<stdlib>";

/// Every module: its file name and its source.
pub const MODULES: &[(&str, &str)] = &[
    ("pattern.sl", include_str!("../stdlib/pattern.sl")),
    ("noise.sl", include_str!("../stdlib/noise.sl")),
    ("fractal.sl", include_str!("../stdlib/fractal.sl")),
    ("lattice.sl", include_str!("../stdlib/lattice.sl")),
    ("cellular.sl", include_str!("../stdlib/cellular.sl")),
    ("color.sl", include_str!("../stdlib/color.sl")),
    ("volume.sl", include_str!("../stdlib/volume.sl")),
    ("lighting.sl", include_str!("../stdlib/lighting.sl")),
    ("solid.sl", include_str!("../stdlib/solid.sl")),
    ("shaders.sl", include_str!("../stdlib/shaders.sl")),
];

/// The source of the standard-library module `name` (e.g. `"pattern.sl"`).
pub fn source(name: &str) -> Option<&'static str> {
    MODULES.iter().find(|(n, _)| *n == name).map(|(_, s)| *s)
}

/// The built-in functions whose implementations are written in the language, in
/// `compiler/stdlib/builtins.sl` (as `__NAME_RESULT` overloaded by parameter types).
pub const LIBRARY_BUILTINS: &[BuiltinId] = &[
    BuiltinId::Noise,
    BuiltinId::Snoise,
    BuiltinId::Pnoise,
    BuiltinId::Cellnoise,
    BuiltinId::Diffuse,
    BuiltinId::Specular,
    BuiltinId::Phong,
    BuiltinId::SpecularBrdf,
    BuiltinId::CTransform,
    BuiltinId::Ptlined,
    BuiltinId::Rotate,
    BuiltinId::Translate,
    BuiltinId::Scale,
    BuiltinId::Determinant,
    BuiltinId::Fresnel,
    BuiltinId::Reflect,
    BuiltinId::Refract,
    BuiltinId::Distance,
    BuiltinId::FaceForward,
    BuiltinId::Radians,
    BuiltinId::Degrees,
];

/// The colour spaces (docs/builtins.md), converted by `compiler/stdlib/builtins.sl` for
/// `ctransform` and the casts `color "space" (a, b, c)`.
pub const COLOUR_SPACES: &[&str] = &["rgb", "hsv", "hsl", "xyz", "XYZ", "xyY", "YIQ"];

/// Checks a colour space name that only a backend knows (a string parameter's bound value or
/// default, read by `ctransform`): names given as literals are checked by the semantic stage.
pub fn check_colour_space(name: &str, span: crate::source::Span) -> Result<(), crate::diag::Diagnostic> {
    if COLOUR_SPACES.contains(&name) {
        return Ok(());
    }
    Err(crate::diag::Diagnostic::error(
        crate::diag::Code::UnknownSpace,
        format!("unknown colour space \"{name}\""),
        span,
        "in this conversion",
    )
    .with_note(format!("the colour spaces are {}", COLOUR_SPACES.join(", "))))
}

/// The file that implements the library built-ins (shown as `<stdlib>/builtins.sl`); it is not
/// for `#include`.
pub const LIBRARY: &str = include_str!("../stdlib/builtins.sl");

/// Where the standard-library file shown as `name` (`<stdlib>/fractal.sl`, as the source map names
/// it) lies in the compiler's source tree, for tools that open it (an editor's go-to-definition).
/// `None` for a name outside the library. The path is the one this crate was built from, so it
/// may be gone from a machine the binary was copied to; the text itself is always embedded.
pub fn path(name: &str) -> Option<std::path::PathBuf> {
    let file = name.strip_prefix(PREFIX)?.strip_prefix('/')?;
    let known = file == "builtins.sl" || source(file).is_some();
    known.then(|| std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("stdlib").join(file))
}

/// Whether `name` is a built-in written in the language.
pub fn is_library_builtin(name: &str) -> bool {
    BuiltinId::from_name(name).is_some_and(|id| LIBRARY_BUILTINS.contains(&id))
}

/// Whether any file in `sources` contains the name of a library built-in, or of a colour space
/// other than RGB (a cast `color "hsv" (h, s, v)` is converted by the library), as a word
/// (comments included: a false positive costs only a parse).
pub fn mentions_library_builtins(sources: &crate::source::SourceMap) -> bool {
    let is_word = |c: u8| c.is_ascii_alphanumeric() || c == b'_';
    // The library's own modules call their functions directly, and mention `noise` in comments.
    sources.files().filter(|(_, file)| !file.name.starts_with(PREFIX)).any(|(_, file)| {
        let text = file.text.as_bytes();
        LIBRARY_BUILTINS.iter().map(|id| id.name()).chain(COLOUR_SPACES[1..].iter().copied()).any(|name| {
            file.text.match_indices(name).any(|(at, _)| {
                let end = at + name.len();
                (at == 0 || !is_word(text[at - 1])) && (end == text.len() || !is_word(text[end]))
            })
        })
    })
}

/// Parses `compiler/stdlib/builtins.sl` into `sources` (as `<stdlib>/builtins.sl`), for the semantic stage.
pub fn parse_library_builtins(
    sources: &mut crate::source::SourceMap,
    loader: &dyn crate::syntax::preprocess::SourceLoader,
    diags: &mut crate::diag::Diagnostics,
) -> crate::syntax::ast::Module {
    let file = sources.add_file(format!("{PREFIX}/builtins.sl"), LIBRARY, None);
    crate::syntax::parse_file(sources, file, loader, diags)
}

/// The files of `sources` that belong to the standard library.
pub fn files(sources: &crate::source::SourceMap) -> rustc_hash::FxHashSet<crate::source::FileId> {
    sources.files().filter(|(_, f)| f.name.starts_with(PREFIX)).map(|(id, _)| id).collect()
}

#[cfg(test)]
mod tests {
    use crate::syntax::preprocess::MemoryLoader;

    #[test]
    fn every_module_checks_clean_on_its_own() {
        // Read as a user's own file, every function is checked, called or not: this is what lets
        // an including file skip the module's uncalled functions.
        for (name, source) in super::MODULES {
            let checked = crate::check_source(name, source, &MemoryLoader::default());
            let messages: Vec<String> =
                checked.diagnostics.iter().map(|d| format!("{}: {}", d.code, d.message)).collect();
            assert!(messages.is_empty(), "{name}: {messages:#?}");
        }
    }

    #[test]
    fn every_module_lies_in_the_source_tree_as_embedded() {
        // Editors open these paths for go-to-definition: they must hold the text that is compiled.
        for (name, source) in super::MODULES.iter().chain([&("builtins.sl", super::LIBRARY)]) {
            let path = super::path(&format!("{}/{name}", super::PREFIX)).expect("a library file");
            assert_eq!(std::fs::read_to_string(&path).ok().as_deref(), Some(*source), "{}", path.display());
        }
        assert_eq!(super::path("<stdlib>/nothing.sl"), None);
        assert_eq!(super::path("fractal.sl"), None);
    }

    #[test]
    fn the_pair_table_holds_each_permutation_entry_beside_the_next() {
        // noise.sl's PATINA_PERLIN_PAIRS is written out as literals: entry i must be
        // p[i] + 256 p[(i + 1) mod 256] for Perlin's permutation p above it.
        let noise = super::MODULES.iter().find(|(n, _)| *n == "noise.sl").expect("noise.sl").1;
        let table = |name: &str| -> Vec<u32> {
            let start = noise.find(&format!("#define {name} {{")).expect("the table's macro");
            let body = &noise[start..];
            let body = &body[body.find('{').unwrap() + 1..body.find('}').unwrap()];
            body.split(|c: char| !c.is_ascii_digit())
                .filter(|t| !t.is_empty())
                .map(|t| t.parse().unwrap())
                .collect()
        };
        let (p, pairs) = (table("PATINA_PERLIN_PERMUTATION"), table("PATINA_PERLIN_PAIRS"));
        assert_eq!(p.len(), 256);
        let mut sorted = p.clone();
        sorted.sort_unstable();
        assert_eq!(sorted, (0..256).collect::<Vec<u32>>(), "a permutation of 0..255");
        let want: Vec<u32> = (0..256).map(|i| p[i] + 256 * p[(i + 1) % 256]).collect();
        assert_eq!(pairs, want);
    }

    #[test]
    fn a_stanford_file_can_include_a_renderman_style_module() {
        // lighting.sl's uncalled functions use `illuminance`, which a Stanford-style file would
        // reject if it checked them in its own style.
        let source = "#include <lighting.sl>\n\
                      surface shader float4 f(primitive group float s) { return {s, 0, 0, 1}; }\n";
        let checked = crate::check_source("stanford.sl", source, &MemoryLoader::default());
        let messages: Vec<String> =
            checked.diagnostics.iter().map(|d| format!("{}: {}", d.code, d.message)).collect();
        assert!(messages.is_empty(), "{messages:#?}");
        assert_eq!(checked.program.shaders.len(), 1);
    }
}
