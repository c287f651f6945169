//! The front and semantic stages, one test binary: parsing and preprocessing, types and rates,
//! every diagnostic (insta snapshots in `snapshots/`), the resource limits, generated programs,
//! fuzz regressions, Aqsis's RenderMan shaders (`../shared/corpus`), and the tidy checks that the
//! documents agree with the code.

mod diagnostics;
mod fuzz_regressions;
mod limits;
mod properties;
mod rates;
mod renderman_corpus;
mod semantics;
mod syntax;
mod tidy;
