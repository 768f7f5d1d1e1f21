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

mod common;

use common::{build_and_run, c_examples, success_marker, SANITIZE};

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
