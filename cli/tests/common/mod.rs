//! Shared by the CLI's integration tests: the `rocking` binary of this build, run from the
//! workspace root (so that `examples/…` and `../shared/…` resolve as in the README).
#![allow(dead_code)]

use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::process::Command;

/// The workspace root.
pub fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The `rocking` binary of this build.
pub fn bin() -> &'static str {
    env!("CARGO_BIN_EXE_rocking")
}

/// A command running the `rocking` binary from the workspace root.
pub fn rocking() -> Command {
    let mut command = Command::new(bin());
    command.current_dir(root());
    command
}

/// What a finished run printed.
pub struct Run {
    /// Exit status 0.
    pub ok: bool,
    /// The exit code (`None` when killed by a signal).
    pub code: Option<i32>,
    /// Standard output.
    pub stdout: String,
    /// Standard error.
    pub stderr: String,
}

/// Runs `rocking args…` from the workspace root and waits for it.
pub fn run<I, S>(args: I) -> Run
where
    I: IntoIterator<Item = S>,
    S: AsRef<OsStr>,
{
    let out = rocking()
        .args(args)
        .output()
        .expect("run the rocking binary");
    Run {
        ok: out.status.success(),
        code: out.status.code(),
        stdout: String::from_utf8_lossy(&out.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&out.stderr).into_owned(),
    }
}
