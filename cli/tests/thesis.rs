//! The README's "run" command: `rocking thesis` reproduces every reference value and exits 0.

use std::process::Command;

#[test]
fn thesis_command_reproduces_the_reference_values() {
    let out = Command::new(env!("CARGO_BIN_EXE_rocking"))
        .arg("thesis")
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{text}");
    assert!(text.contains("all reference values reproduced"), "{text}");
    assert!(!text.contains("MISMATCH"), "{text}");
}

#[test]
fn unknown_command_is_an_error() {
    let out = Command::new(env!("CARGO_BIN_EXE_rocking"))
        .arg("frobnicate")
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    // clap reports unknown subcommands.
    assert!(String::from_utf8_lossy(&out.stderr).contains("unrecognized subcommand"));
}
