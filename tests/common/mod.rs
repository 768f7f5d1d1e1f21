//! Shared by the integration tests: compiling C against `include/rocking.h` and the cdylib
//! (here), the harness's scenes (`scenes`), comparisons with printed numbers (`compare`).
#![allow(dead_code)]

pub mod column_scene;
pub mod compare;
pub mod scenes;

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
pub const SANITIZE: &[&str] = &[
    "-fsanitize=address,undefined",
    "-fno-sanitize-recover=all",
    "-fno-omit-frame-pointer",
    "-g",
];

/// The C programs of `c_examples/` (every `*.c`), sorted.
pub fn c_examples() -> Vec<String> {
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
pub fn success_marker(source: &str) -> &'static str {
    match source {
        "c_examples/minimal.c" => "all thesis values reproduced",
        "c_examples/arch.c" => "arch: all checks passed",
        "c_examples/element_skeleton.c" => "done: 3 events",
        "c_examples/opensees_style_harness.c" => "harness: all self-checks passed",
        "c_examples/stiff_blocks.c" => "stiff blocks: all self-checks passed",
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
            "{}{}-{}.bin",
            if extra.is_empty() { "" } else { "san." },
            // tests (and test binaries) may build the same source at once: one executable each
            std::process::id(),
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
