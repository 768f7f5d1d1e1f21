//! Regenerates `include/rocking.h` from `src/ffi/` with cbindgen. CI checks that the checked-in
//! header equals what this writes (`git diff --exit-code include/rocking.h`).

use std::path::PathBuf;

fn main() {
    println!("cargo:rerun-if-changed=src/ffi");
    println!("cargo:rerun-if-changed=cbindgen.toml");
    // The C tests compile examples for the same target with the `cc` crate.
    if let Ok(target) = std::env::var("TARGET") {
        println!("cargo:rustc-env=ROCKING_TEST_TARGET={target}");
    }
    let crate_dir =
        PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR"));
    let config = cbindgen::Config::from_file(crate_dir.join("cbindgen.toml"))
        .expect("cbindgen.toml is valid");
    match cbindgen::Builder::new()
        .with_crate(&crate_dir)
        .with_config(config)
        .generate()
    {
        Ok(bindings) => {
            bindings.write_to_file(crate_dir.join("include/rocking.h"));
        }
        Err(e) => {
            // A half-edited source must not break the build of the library itself; the drift
            // check in CI catches a stale header.
            println!("cargo:warning=cbindgen could not regenerate include/rocking.h: {e}");
        }
    }
}
