//! Helpers shared by the whole-program tests: run the `wasp` binary as a
//! user does, read what it printed, and make scratch folders; [`run`] has
//! those of the `wasp run` tests.
// Each test file uses its own part of this module.
#![allow(dead_code)]

pub mod run;

use std::path::PathBuf;
use std::process::{Command, Output};

/// Run `wasp` with `args` and wait for it.
pub fn wasp(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_wasp"))
        .args(args)
        .output()
        .expect("run wasp")
}

/// Its standard output, after checking that it succeeded.
pub fn ok(o: &Output) -> String {
    assert!(
        o.status.success(),
        "wasp failed: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    stdout(o)
}

/// Its standard output.
pub fn stdout(o: &Output) -> String {
    String::from_utf8(o.stdout.clone()).unwrap()
}

/// Its standard error.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// A fresh scratch folder `wasp-{kind}-{pid}-{name}` in the temp dir.
pub fn scratch(kind: &str, name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("wasp-{kind}-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}
