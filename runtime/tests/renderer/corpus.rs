//! Aqsis's standard shaders (`../shared/corpus/aqsis/`, read from there, never copied into the
//! project), as a new user would try them: each file checks, or fails with a diagnostic naming a
//! feature Patina leaves out on purpose; each shader that checks renders on both backends in the
//! scene made for its kind (`patina_runtime::corpus`), with finite pixels, and the pictures agree
//! within the gallery's thresholds. `patina corpus` writes the same results as docs/corpus.md.

use std::path::PathBuf;

use patina_runtime::corpus::{self, Entry, Options, Outcome};

/// Files that do not check, each with words its first error must contain: the feature it needs.
const EXCLUDED: &[(&str, &str)] = &[];

/// Files that check but do not yet render on both backends or agree, with the reason: the test
/// asserts that each still fails, so that this list stays true as the gaps close.
const NOT_YET: &[(&str, &str)] = &[(
    "surface/expensive.sl",
    "reads the map its baking pass writes (`objname.bakename.tex`, \".bake.tex\" by default), which no \
     pass of the corpus scene makes: a missing map is an error here, where RenderMan answers black",
)];

/// Files whose test picture is black by design, with why.
const DARK: &[(&str, &str)] = &[("surface/showuser.sl", "shows a user attribute the scene does not set")];

fn corpus_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../shared/corpus/aqsis")
}

fn renders_and_agrees(e: &Entry) -> bool {
    e.cpu.worked() && e.gpu.worked() && e.agrees == Some(true)
}

#[test]
fn aqsis_shaders_check_render_and_agree() {
    let Some(gpu) = patina_runtime::gpu::for_tests() else { return };
    let dir = corpus_dir();
    assert!(
        dir.is_dir(),
        "{}: the corpus is missing (it lives in ../shared beside the checkout)",
        dir.display()
    );
    let options = Options { include_dirs: vec![dir.join("include")], ..Options::default() };
    let entries = corpus::run(&dir, &options, Some(gpu), |_| {}).expect("the corpus directory reads");
    assert_eq!(entries.len(), 47, "Aqsis's set has 47 shader files");
    let mut failures = Vec::new();
    for e in &entries {
        let file = e.file.to_string_lossy().replace('\\', "/");
        let excluded = EXCLUDED.iter().find(|(f, _)| *f == file);
        let not_yet = NOT_YET.iter().find(|(f, _)| *f == file);
        match (&e.check, excluded) {
            (Outcome::Failed(error), Some((_, feature))) => {
                if !error.contains(feature) {
                    failures.push(format!("{file}: its error does not name `{feature}`: {error}"));
                }
                continue;
            }
            (Outcome::Failed(error), None) => {
                failures.push(format!("{file}: does not check: {error}"));
                continue;
            }
            (_, Some(_)) => failures.push(format!("{file}: checks now; take it off EXCLUDED")),
            _ => {}
        }
        if e.shader.is_none() {
            continue; // functions only (include/patterns.sl)
        }
        match (renders_and_agrees(e), not_yet) {
            (true, Some(_)) => failures.push(format!("{file}: renders and agrees now; take it off NOT_YET")),
            (false, None) => failures.push(format!(
                "{file}: CPU {:?}, GPU {:?}, agreement {:?} ({:?})",
                e.cpu, e.gpu, e.agrees, e.comparison
            )),
            _ => {}
        }
        for (backend, image) in [("CPU", &e.cpu_image), ("GPU", &e.gpu_image)] {
            if let Some(image) = image {
                let lit = image.pixels.iter().filter(|p| p[..3].iter().any(|c| *c > 0.1)).count();
                if lit == 0 && not_yet.is_none() && !DARK.iter().any(|(f, _)| *f == file) {
                    failures.push(format!("{file}: the {backend} picture is black"));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
