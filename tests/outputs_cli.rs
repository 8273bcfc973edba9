//! Whole-program tests of the outputs' safety: no output may overwrite an
//! input of the command or another output (an error before any work, the
//! input left byte-identical), and a file output replaces the old file
//! only once it is whole.

mod common;
use common::run::{dir, run_tiny, tiny_config, tiny_trace};
use common::{ok, stderr, wasp};

#[test]
fn an_output_naming_the_trace_is_refused_and_the_trace_kept() {
    let d = dir("out-in");
    let trace = d.join("in.trace");
    std::fs::copy(tiny_trace(), &trace).unwrap();
    let before = std::fs::read(&trace).unwrap();
    let cfg = tiny_config(&d);
    let t = trace.to_str().unwrap();
    for flag in ["--json", "--csv", "--vcd"] {
        let o = wasp(&["run", "-q", "--config", &cfg, "--trace", t, flag, t]);
        assert_eq!(o.status.code(), Some(2), "{flag}: {}", stderr(&o));
        let e = stderr(&o);
        assert!(
            e.contains(flag) && e.contains("--trace") && e.contains("in.trace"),
            "{e}"
        );
        assert_eq!(std::fs::read(&trace).unwrap(), before, "{flag}");
    }
    // Another spelling of the configuration file.
    let other = d.join(".").join("tiny.toml");
    let o = wasp(&[
        "compare",
        "-q",
        "--config",
        &cfg,
        "--trace",
        t,
        "--csv",
        other.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--config"), "{}", stderr(&o));
    let o = wasp(&["cost", "--no-yosys", "--config", &cfg, "--json", &cfg]);
    assert_eq!(o.status.code(), Some(2));
    // A scene named by its definition file is an input of render.
    let scene = d.join("mine.toml");
    std::fs::write(&scene, "name = \"mine\"\n").unwrap();
    let sc = scene.to_str().unwrap();
    let o = wasp(&["render", sc, "-q", "--trace-out", sc]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("the scene file"), "{}", stderr(&o));
    assert_eq!(
        std::fs::read_to_string(&scene).unwrap(),
        "name = \"mine\"\n"
    );
    // The save file of --vcd is an output too.
    let vcd = d.join("w.vcd");
    let o = wasp(&[
        "run",
        "-q",
        "--config",
        &cfg,
        "--trace",
        t,
        "--vcd",
        vcd.to_str().unwrap(),
        "--json",
        d.join("w.vcd.gtkw").to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("both name"), "{}", stderr(&o));
}

#[test]
fn a_finished_run_replaces_its_output_and_leaves_no_temporary_file() {
    let d = dir("out-atomic");
    let cfg = tiny_config(&d);
    let json = d.join("r.json");
    std::fs::write(&json, "old").unwrap();
    ok(&run_tiny(&cfg, &["--json", json.to_str().unwrap()]));
    let text = std::fs::read_to_string(&json).unwrap();
    assert!(text.starts_with('{'), "{text}");
    let left: Vec<String> = std::fs::read_dir(&d)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains("wasp-tmp"))
        .collect();
    assert!(left.is_empty(), "{left:?}");
}

#[test]
fn a_folder_option_naming_a_file_says_it_needs_a_folder() {
    let d = dir("out-folder");
    let f = d.join("report.md");
    std::fs::write(&f, "mine").unwrap();
    let o = wasp(&["reproduce", "-q", "--quick", "--out", f.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("--out names a folder"),
        "{}",
        stderr(&o)
    );
    assert_eq!(std::fs::read_to_string(&f).unwrap(), "mine");
}
