//! Generates the C header from `src/ffi/` (and the status table of `src/error.rs`) with cbindgen
//! into `$OUT_DIR/rocking.h` — the build directory, never the source tree. The checked-in
//! `include/rocking.h` must equal it: `tests/c_abi.rs` (`checked_in_header_is_the_generated_one`)
//! compares them, and regenerates the checked-in one when asked:
//!
//! ```sh
//! ROCKING_BLESS=1 cargo test --release --test c_abi generated   # or: make header
//! ```

use std::fmt::Write as _;
use std::path::PathBuf;

/// The status table, compiled here as well as in the library: the header's status block and the
/// library's `ErrorKind` and `ROCKING_ERR_*` constants come from the same rows.
#[allow(dead_code)]
#[path = "src/error.rs"]
mod error;

fn main() {
    println!("cargo:rerun-if-changed=src/ffi");
    println!("cargo:rerun-if-changed=src/error.rs");
    println!("cargo:rerun-if-changed=cbindgen.toml");
    // The C tests compile examples for the same target with the `cc` crate.
    if let Ok(target) = std::env::var("TARGET") {
        println!("cargo:rustc-env=ROCKING_TEST_TARGET={target}");
    }
    let crate_dir =
        PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR"));
    let out =
        PathBuf::from(std::env::var("OUT_DIR").expect("cargo sets OUT_DIR")).join("rocking.h");
    let config = cbindgen::Config::from_file(crate_dir.join("cbindgen.toml"))
        .expect("cbindgen.toml is valid");
    // Only `src/ffi/` (and the modules it declares) is parsed: the header holds exactly what the
    // C ABI declares, never a `pub const` of the rest of the crate.
    match cbindgen::Builder::new()
        .with_config(config)
        .with_src(crate_dir.join("src/ffi/mod.rs"))
        .with_after_include(status_block())
        .generate()
    {
        Ok(bindings) => {
            let mut text = Vec::new();
            bindings.write(&mut text);
            let text = String::from_utf8(text).expect("cbindgen writes UTF-8");
            std::fs::write(&out, c89_comments(&text)).expect("write the header into OUT_DIR");
        }
        Err(e) => {
            // A half-edited source must not break the build of the library itself; the header
            // test fails on a missing or stale header.
            std::fs::remove_file(&out).ok();
            println!(
                "cargo:warning=cbindgen could not generate {}: {e}",
                out.display()
            );
        }
    }
}

/// cbindgen closes its `extern "C"` guards with `//` comments, which C89 does not have; every
/// other comment of the header is `/* */`.
fn c89_comments(header: &str) -> String {
    header
        .lines()
        .map(
            |line| match line.split_once("  // ").or_else(|| line.split_once(" // ")) {
                Some((code, comment)) if code.starts_with('#') || code.starts_with('}') => {
                    format!("{code}  /* {comment} */\n")
                }
                _ => format!("{line}\n"),
            },
        )
        .collect()
}

/// The `#define`s of the status codes with the table's documentation and messages.
fn status_block() -> String {
    let mut s = String::from(
        "\n/*\n * Status codes (the table of src/error.rs). Every call that can fail returns one: 0 \
         success,\n * negative: the call is wrong (fix the caller), positive: a valid call that \
         cannot be solved\n * as asked (the numbers). On any non-zero code no output was written. \
         The quoted text is\n * what rocking_error_message(code) returns.\n */\n",
    );
    let (name, doc, message) = error::SUCCESS;
    define(&mut s, name, 0, doc, message);
    for kind in error::ErrorKind::ALL {
        define(
            &mut s,
            kind.c_name(),
            kind.code(),
            kind.doc(),
            kind.message(),
        );
    }
    s.pop(); // cbindgen ends the block with a newline of its own
    s
}

fn define(s: &mut String, name: &str, code: i32, doc: &str, message: &str) {
    s.push_str("\n/**\n");
    for line in doc.lines() {
        let line = line.strip_prefix(' ').unwrap_or(line);
        writeln!(s, " * {line}").unwrap();
    }
    writeln!(s, " * \"{message}\"").unwrap();
    s.push_str(" */\n");
    if code < 0 {
        writeln!(s, "#define {name} ({code})").unwrap();
    } else {
        writeln!(s, "#define {name} {code}").unwrap();
    }
}
