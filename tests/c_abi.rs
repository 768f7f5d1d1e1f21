//! The C programs in `c_examples/` compiled (with the `cc` crate's compiler detection) against
//! `include/rocking.h` alone and the cdylib, then run: each must exit 0. Every `*.c` there is
//! found by listing the directory, built twice (`-std=c99 -Wall -Wextra -Werror -pedantic`, then
//! the same under AddressSanitizer and UndefinedBehaviorSanitizer), and the header is compiled
//! once more from a C++ translation unit.
//!
//! Sanitizers with a Rust cdylib: only the C executable is instrumented. `-fsanitize=address`
//! makes the compiler link the ASan runtime into the executable (gcc: `libasan.so` as its first
//! `DT_NEEDED`, so it is first in the initial library list and `verify_asan_link_order` is
//! satisfied; clang: the static runtime), hence no `LD_PRELOAD` — that is needed only when the
//! executable is not instrumented, e.g. Python loading the library through ctypes. The Rust code
//! allocates through `malloc`/`free`, which ASan intercepts process-wide, so LeakSanitizer sees
//! the library's allocations too and stays on (`detect_leaks=1`, the Linux default; it reports
//! nothing: no call leaks). LeakSanitizer needs ptrace-free execution: under strace/gdb set
//! `ASAN_OPTIONS=detect_leaks=0`. UBSan only prints and carries on by default, so
//! `-fno-sanitize-recover=all` turns every finding into a non-zero exit. Valgrind runs the same
//! examples from `.ci/run` (it cannot run an ASan binary, hence the separate plain build).

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::atomic::{AtomicUsize, Ordering};

static BUILDS: AtomicUsize = AtomicUsize::new(0);

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

/// Compiler flags of the sanitizer build.
const SANITIZE: &[&str] = &[
    "-fsanitize=address,undefined",
    "-fno-sanitize-recover=all",
    "-fno-omit-frame-pointer",
    "-g",
];

/// The C programs of `c_examples/` (every `*.c`), sorted.
fn c_examples() -> Vec<String> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("c_examples");
    let mut out: Vec<String> = std::fs::read_dir(&dir)
        .expect("c_examples/")
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".c"))
        .map(|n| format!("c_examples/{n}"))
        .collect();
    out.sort();
    assert!(
        out.len() >= 2,
        "expected minimal.c and opensees_style_harness.c, found {out:?}"
    );
    out
}

/// What each example prints when all its checks pass.
fn success_marker(source: &str) -> &'static str {
    match source {
        "c_examples/minimal.c" => "all thesis values reproduced",
        "c_examples/opensees_style_harness.c" => "harness: all self-checks passed",
        _ => "",
    }
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
        .with_extension(format!(
            "{}{}.bin",
            if extra.is_empty() { "" } else { "san." },
            // tests run in parallel and may build the same source: one executable each
            BUILDS.fetch_add(1, Ordering::Relaxed)
        ));
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
        .env("UBSAN_OPTIONS", "print_stacktrace=1")
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
fn every_c_example_builds_warning_free_and_passes() {
    for source in c_examples() {
        let out = build_and_run(&source, &[], false);
        assert!(out.contains(success_marker(&source)), "{source}:\n{out}");
    }
}

#[test]
fn every_c_example_is_clean_under_asan_and_ubsan() {
    for source in c_examples() {
        let out = build_and_run(&source, SANITIZE, false);
        assert!(out.contains(success_marker(&source)), "{source}:\n{out}");
    }
}

/// The harness prints one RESULT line per scene; the self-checks inside it assert the exact
/// single-block answers (Housner's ratio, the energy-integral times, the opening time).
#[test]
fn harness_prints_machine_readable_results() {
    let out = build_and_run("c_examples/opensees_style_harness.c", &[], false);
    for scene in ["a", "b", "c", "d"] {
        assert!(
            out.lines()
                .any(|l| l.starts_with(&format!("RESULT scene={scene} "))),
            "no RESULT line for scene {scene}:\n{out}"
        );
    }
    assert!(!out.contains(" FAIL"), "{out}");
}

#[test]
fn header_is_cxx_clean() {
    let out = build_and_run("c_examples/cxx_header_check.cpp", &[], true);
    assert!(out.contains("ok"), "{out}");
    let out = build_and_run("c_examples/cxx_header_check.cpp", SANITIZE, true);
    assert!(out.contains("ok"), "{out}");
}
