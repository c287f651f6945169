//! What the interpreter's tests share: a shader's source checked and compiled for the interpreter.

use patina_compiler::backend::binding::Binding;
use patina_compiler::backend::cpu::CpuProgram;
use patina_compiler::diag::Diagnostic;
use patina_compiler::opt::Prepared;
use patina_compiler::syntax::preprocess::MemoryLoader;

/// Checks `source` (which must have no errors: the test fails with them and the source) and
/// compiles its first shader for the interpreter with `binding`; the interpreter's own refusal
/// is the `Err`.
pub fn try_compile(source: &str, binding: &Binding) -> Result<CpuProgram, Diagnostic> {
    let checked = patina_compiler::check_source("test.sl", source, &MemoryLoader::default());
    assert!(!checked.has_errors(), "{}in\n{source}", checked.diagnostics_text());
    CpuProgram::compile(
        &Prepared::with_strings(checked.program.shaders[0].clone(), &binding.strings),
        binding,
    )
}

/// As [`try_compile`], failing the test when the interpreter refuses the shader.
pub fn compile(source: &str, binding: &Binding) -> CpuProgram {
    try_compile(source, binding).unwrap_or_else(|d| panic!("{}: {}\nin\n{source}", d.code, d.message))
}
