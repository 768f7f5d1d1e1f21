//! The README's "run" command: `rocking thesis` reproduces every reference value and exits 0.

mod common;

use common::run;

#[test]
fn thesis_command_reproduces_the_reference_values() {
    let out = run(["thesis"]);
    let text = &out.stdout;
    assert!(out.ok, "{text}");
    assert!(text.contains("all reference values reproduced"), "{text}");
    assert!(!text.contains("MISMATCH"), "{text}");
}

#[test]
fn unknown_command_is_an_error() {
    let out = run(["frobnicate"]);
    assert_eq!(out.code, Some(2));
    // clap reports unknown subcommands.
    assert!(out.stderr.contains("unrecognized subcommand"));
}
