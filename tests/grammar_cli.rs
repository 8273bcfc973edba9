//! Whole-program tests of the command line's one grammar: every output
//! option takes a FILE (`-` for standard output), at most one output goes
//! to standard output, outputs are checked before any work, `-q` is
//! accepted everywhere, `--scenes-dir` only where scenes are read, and an
//! interrupted study says how to resume.

mod common;
use common::{ok, scratch, stderr, stdout, wasp};

/// Every subcommand, as typed.
const COMMANDS: [&[&str]; 16] = [
    &["example"],
    &["run"],
    &["compare"],
    &["synth"],
    &["trace-cat"],
    &["cost"],
    &["bench"],
    &["scenes", "list"],
    &["scenes", "fetch"],
    &["scenes", "capture"],
    &["render"],
    &["import-gl"],
    &["characterize"],
    &["reproduce"],
    &["sweep"],
    &["merge"],
];

fn help(cmd: &[&str]) -> String {
    let mut a = cmd.to_vec();
    a.push("--help");
    ok(&wasp(&a))
}

#[test]
fn every_command_takes_quiet_and_only_scene_readers_take_a_scenes_folder() {
    let readers = [
        "scenes list",
        "scenes capture",
        "render",
        "characterize",
        "reproduce",
        "sweep",
        "merge",
    ];
    for cmd in COMMANDS {
        let h = help(cmd);
        let name = cmd.join(" ");
        assert!(h.contains("-q, --quiet"), "{name}: {h}");
        assert_eq!(
            h.contains("--scenes-dir <DIR>"),
            readers.contains(&name.as_str()),
            "{name}: {h}"
        );
    }
    let o = wasp(&["cost", "--scenes-dir", "/tmp", "--no-yosys"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("unexpected argument '--scenes-dir'"),
        "{}",
        stderr(&o)
    );
    // -q where it used to be refused.
    ok(&wasp(&["cost", "-q", "--no-yosys"]));
    let d = scratch("grammar", "quiet-merge");
    let e = wasp(&["merge", "-q", d.to_str().unwrap()]);
    assert_eq!(e.status.code(), Some(1), "{}", stderr(&e));
    ok(&wasp(&["scenes", "-q", "list"]));
    // Options only where they apply: nothing runs under --jobs-file.
    let e = wasp(&["sweep", "x.toml", "--jobs", "2", "--jobs-file", "-"]);
    assert_eq!(e.status.code(), Some(2));
    assert!(stderr(&e).contains("cannot be used with"), "{}", stderr(&e));
}

/// `-q` before the subcommand quiets it as `-q` after it does.
#[test]
fn quiet_before_the_subcommand_is_quiet_after_it() {
    let d = scratch("grammar", "quiet-before");
    let trace = d.join("p.trace");
    let t = trace.to_str().unwrap();
    let render = [
        "render",
        "procedural-plane",
        "--size",
        "128x64",
        "--trace-out",
        t,
    ];
    let loud = wasp(&render);
    ok(&loud);
    assert!(stderr(&loud).contains("wasp: wrote"), "{}", stderr(&loud));
    assert!(stderr(&loud).contains("procedural:plane 128x64"));
    for quiet in [
        [&["-q"][..], &render[..]].concat(),
        [&render[..], &["-q"][..]].concat(),
    ] {
        let o = wasp(&quiet);
        ok(&o);
        // `render -q` prints nothing: the frame's counts and the note of
        // what was written go.
        assert_eq!(stderr(&o), "", "{quiet:?}");
    }
}

#[test]
fn every_output_option_takes_a_file_or_standard_output() {
    for (cmd, flags) in [
        (&["example"][..], &["--json", "--vcd"][..]),
        (&["run"], &["--json", "--csv", "--vcd", "--timeline"]),
        (&["compare"], &["--json", "--csv"]),
        (&["synth"], &["--out"]),
        (&["trace-cat"], &["--out"]),
        (&["cost"], &["--json"]),
        (&["bench"], &["--json"]),
        (&["render"], &["--png", "--trace-out"]),
        (&["characterize"], &["--json", "--csv"]),
        (&["sweep"], &["--jobs-file"]),
        (&["merge"], &["--csv", "--json"]),
    ] {
        let h = help(cmd);
        for f in flags {
            assert!(
                h.contains(&format!("{f} <FILE>")),
                "{} {f} takes no FILE: {h}",
                cmd.join(" ")
            );
        }
    }
    // The example's outputs, as the README's table reads them.
    let d = scratch("grammar", "example");
    let (json, vcd) = (d.join("ex.json"), d.join("ex.vcd"));
    let o = ok(&wasp(&[
        "example",
        "--json",
        json.to_str().unwrap(),
        "--vcd",
        vcd.to_str().unwrap(),
    ]));
    assert!(o.contains("Waveform: "), "{o}");
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(v["wasp"]["cycles"], 16);
    assert!(std::fs::read_to_string(&vcd)
        .unwrap()
        .contains("$enddefinitions"));
    // A VCD on standard output is the whole of it.
    let o = ok(&wasp(&["example", "--vcd", "-"]));
    assert!(o.starts_with("$") && !o.contains("Waveform:"), "{o}");
    // A bare --vcd names the value it needs.
    let e = wasp(&["example", "--vcd"]);
    assert_eq!(e.status.code(), Some(2));
    assert!(stderr(&e).contains("'--vcd <FILE>'"), "{}", stderr(&e));
}

#[test]
fn at_most_one_output_goes_to_standard_output() {
    for args in [
        &["run", "--json", "-", "--csv", "-"][..],
        &["compare", "--json", "-", "--csv", "-"],
        &["example", "--json", "-", "--vcd", "-"],
        &[
            "characterize",
            "procedural-plane",
            "--json",
            "-",
            "--csv",
            "-",
        ],
        &["merge", "/tmp", "--json", "-", "--csv", "-"],
    ] {
        let o = wasp(args);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        assert!(
            stderr(&o).contains("only one output can go to standard output"),
            "{args:?}: {}",
            stderr(&o)
        );
        assert!(stdout(&o).is_empty(), "{args:?} wrote {}", stdout(&o));
    }
    // One of them alone parses.
    let v: serde_json::Value = serde_json::from_str(&ok(&wasp(&[
        "run",
        "-q",
        "--trace",
        concat!(env!("CARGO_MANIFEST_DIR"), "/tests/traces/tiny.trace"),
        "--set",
        "gpu.tile_size=8",
        "--json",
        "-",
        "--csv",
        &scratch("grammar", "one")
            .join("r.csv")
            .display()
            .to_string(),
    ])))
    .unwrap();
    assert!(v["cycles"].as_u64().unwrap() > 0);
}

#[test]
fn outputs_are_checked_before_any_simulation() {
    for (args, flag) in [
        (
            &["run", "--timeline", "/nonexistent/dir/x.png"][..],
            "--timeline",
        ),
        (&["run", "--json", "/nonexistent/dir/x.json"], "--json"),
        (&["compare", "--csv", "/nonexistent/dir/x.csv"], "--csv"),
        (&["synth", "-o", "/nonexistent/dir/x.trace"], "--out"),
        (&["bench", "--json", "/nonexistent/dir/x.json"], "--json"),
        (
            &[
                "render",
                "procedural-plane",
                "--png",
                "/nonexistent/dir/x.png",
            ],
            "--png",
        ),
    ] {
        let o = wasp(args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        let e = stderr(&o);
        assert!(
            e.contains(&format!("{flag} /nonexistent/dir/x."))
                && e.contains("the folder /nonexistent/dir does not exist"),
            "{args:?}: {e}"
        );
        // Refused at once: no note of a generated workload or a run.
        assert!(!e.contains("generating") && !e.contains("front end"), "{e}");
    }
    let e = stderr(&wasp(&["run", "--timeline", "-"]));
    assert!(e.contains("--timeline -: this output is a picture"), "{e}");
}

#[test]
fn merging_nothing_is_an_error_and_run_lists_every_policy() {
    let d = scratch("grammar", "empty");
    let o = wasp(&["merge", d.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stdout(&o).is_empty(), "{}", stdout(&o));
    assert!(
        stderr(&o).contains("no point records in") && stderr(&o).contains("nothing to merge"),
        "{}",
        stderr(&o)
    );
    let h = help(&["run"]);
    assert!(h.contains("wasp-m[:THRESHOLD]"), "{h}");
}

/// `render` fetches a game's missing data as `reproduce` does: with an
/// empty scene cache and no apt-get on the PATH, it tries and says why it
/// cannot, instead of asking for `wasp scenes fetch` first.
#[test]
fn render_fetches_missing_game_data() {
    let d = scratch("grammar", "fetch");
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_wasp"))
        .args(["render", "tw-dm1-spawn0", "--trace-out"])
        .arg(d.join("t.trace"))
        .env("WASP_SCENES", d.join("cache"))
        .env("PATH", d.join("no-tools"))
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1));
    let e = stderr(&o);
    assert!(
        e.contains("fetching the teeworlds data") && e.contains("`apt-get` not found"),
        "{e}"
    );
}

/// Start wasp with `args`, wait for its first finished point in
/// `points`, send `signal` and return its exit code and standard error.
#[cfg(unix)]
fn interrupt_after_the_first_point(
    args: &[&str],
    points: &std::path::Path,
    signal: libc::c_int,
) -> (i32, String) {
    let child = std::process::Command::new(env!("CARGO_BIN_EXE_wasp"))
        .args(args)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let start = std::time::Instant::now();
    while std::fs::read_dir(points).map_or(0, |d| d.count()) == 0 {
        assert!(start.elapsed().as_secs() < 600, "no point finished");
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
    // SAFETY: sends `signal` to the child this test spawned.
    unsafe {
        libc::kill(child.id() as libc::pid_t, signal);
    }
    let o = child.wait_with_output().unwrap();
    let code = o.status.code().unwrap_or(-1);
    (code, String::from_utf8_lossy(&o.stderr).into_owned())
}

/// Ctrl-C during a sweep keeps the finished points and says that the same
/// command resumes.
#[cfg(unix)]
#[test]
fn an_interrupted_sweep_says_a_rerun_resumes() {
    let d = scratch("grammar", "interrupt");
    let out = d.join("out");
    let _ = std::fs::remove_dir_all(&out);
    let mut file =
        String::from("scenes = [\"procedural-plane\"]\npolicies = [\"baseline\", \"wasp:0:3\"]\n");
    for m in 4..=31 {
        file.push_str(&format!(
            "[[configs]]\nname = \"m{m}\"\nbase = \"paper\"\nset = [\"l0.mshrs={m}\"]\n"
        ));
    }
    let sweep = d.join("many.toml");
    std::fs::write(&sweep, file).unwrap();
    let (o, s) = (out.to_str().unwrap(), sweep.to_str().unwrap());
    let points = out.join("points");
    let (code, e) = interrupt_after_the_first_point(
        &["sweep", "--jobs", "1", "--out", o, s],
        &points,
        libc::SIGINT,
    );
    assert_eq!(code, 130, "{e}");
    assert!(
        e.contains("wasp: interrupted: the finished points are kept in")
            && e.contains("many.toml")
            && e.contains("again to resume"),
        "{e}"
    );
    assert!(std::fs::read_dir(&points).unwrap().count() >= 1);
    let _ = std::fs::remove_dir_all(&d);
}

/// SIGTERM (a batch system's stop) during `reproduce` is taken as Ctrl-C
/// is: the same message, a rerun of the same command resumes.
#[cfg(unix)]
#[test]
fn an_interrupted_reproduction_says_a_rerun_resumes() {
    let d = scratch("grammar", "interrupt-reproduce");
    let out = d.join("out");
    let o = out.to_str().unwrap();
    let args = [
        "reproduce",
        "--quick",
        "--scenes",
        "procedural-plane",
        "--jobs",
        "1",
        "--out",
        o,
    ];
    let (code, e) = interrupt_after_the_first_point(&args, &out.join("points"), libc::SIGTERM);
    assert_eq!(code, 130, "{e}");
    assert!(
        e.contains(&format!(
            "wasp: interrupted: the finished points are kept in {o}; run `wasp reproduce \
             --quick --scenes procedural-plane --jobs 1 --out {o}` again to resume"
        )),
        "{e}"
    );
    assert!(!out.join("REPORT.md").exists());
    let _ = std::fs::remove_dir_all(&d);
}
