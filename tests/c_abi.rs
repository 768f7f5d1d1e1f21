//! The C programs in `c_examples/` compiled (with the `cc` crate's compiler detection) against
//! `include/rocking.h` alone and the cdylib, then run: each must exit 0.

use std::path::{Path, PathBuf};
use std::process::Command;

/// `target/<profile>`, where cargo put `librocking.so` for this test run.
fn profile_dir() -> PathBuf {
    let exe = std::env::current_exe().expect("test executable path");
    exe.parent()
        .and_then(Path::parent)
        .expect("target/<profile>/deps/<test>")
        .to_path_buf()
}

fn compiler(cpp: bool) -> cc::Tool {
    let target =
        std::env::var("TARGET").unwrap_or_else(|_| env!("ROCKING_TEST_TARGET").to_string());
    cc::Build::new()
        .cpp(cpp)
        .target(&target)
        .host(&target)
        .opt_level(1)
        .cargo_metadata(false)
        .cargo_warnings(false)
        .get_compiler()
}

/// Compiles `source` into an executable with `extra` flags, links the cdylib, runs it from
/// `c_examples/` and returns its stdout.
pub fn build_and_run(source: &str, extra: &[&str], cpp: bool) -> String {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let lib_dir = profile_dir();
    assert!(
        lib_dir.join("librocking.so").exists(),
        "librocking.so not found in {}",
        lib_dir.display()
    );
    let out_dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
    let exe = out_dir
        .join(Path::new(source).file_stem().unwrap())
        .with_extension(if extra.is_empty() { "bin" } else { "san.bin" });
    let tool = compiler(cpp);
    let mut cmd = tool.to_command();
    cmd.arg(if cpp { "-std=c++11" } else { "-std=c99" })
        .args(["-Wall", "-Wextra", "-Werror", "-pedantic"])
        .args(extra)
        .arg(format!("-I{}", root.join("include").display()))
        .arg(root.join(source))
        .arg("-o")
        .arg(&exe)
        .arg(format!("-L{}", lib_dir.display()))
        .arg(format!("-Wl,-rpath,{}", lib_dir.display()))
        .args(["-lrocking", "-lm"]);
    let out = cmd.output().expect("run the C compiler");
    assert!(
        out.status.success(),
        "compiling {source} failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let run = Command::new(&exe)
        .current_dir(root.join("c_examples"))
        .output()
        .expect("run the example");
    let stdout = String::from_utf8_lossy(&run.stdout).into_owned();
    assert!(
        run.status.success(),
        "{source} exited with {:?}\nstdout:\n{stdout}\nstderr:\n{}",
        run.status,
        String::from_utf8_lossy(&run.stderr)
    );
    stdout
}

#[test]
fn minimal_c_example_reproduces_the_thesis() {
    let out = build_and_run("c_examples/minimal.c", &[], false);
    assert!(out.contains("all thesis values reproduced"), "{out}");
}

#[test]
fn header_is_cxx_clean() {
    let out = build_and_run("c_examples/cxx_header_check.cpp", &[], true);
    assert!(out.contains("ok"), "{out}");
}
