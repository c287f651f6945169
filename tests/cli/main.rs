//! The `patina` command as a user meets it, one test binary: exit codes and one-line errors, the
//! diagnostics' formats, the limits, `bench`, `stability`, `view` (under Xvfb) and `watch`, the
//! packaging of the crates and of the VS Code extension.

mod bench;
mod cli;
mod editor_package;
mod limits_cli;
mod packaging;
mod stability;
mod support;
mod view;
mod watch;
