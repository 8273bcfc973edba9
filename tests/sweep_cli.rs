//! Whole-program tests of `wasp sweep` and `wasp merge`: a sweep run at
//! once and the same sweep run as cluster jobs give the same table.

use std::path::Path;
use std::process::Command;

mod common;
use common::{ok, stderr, stdout, wasp};

/// One scene, one machine, two policies: two points.
const SWEEP: &str = r#"
scenes = ["procedural-plane"]
policies = ["baseline", "wasp:0:3"]
[[configs]]
name = "shipped"
base = "paper"
"#;

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// The rows of a results table without its header, which names the
/// columns.
fn rows(csv: &str) -> Vec<String> {
    csv.lines().map(String::from).collect()
}

#[test]
fn a_sweep_run_at_once_and_as_jobs_gives_the_same_table() {
    let d = common::scratch("sweep", "jobs");
    let _ = std::fs::remove_dir_all(d.join("a"));
    let _ = std::fs::remove_dir_all(d.join("b"));
    let file = d.join("tiny sweep.toml");
    std::fs::write(&file, SWEEP).unwrap();
    let (a, b) = (d.join("a"), d.join("b"));

    let csv_a = run_at_once(&file, &a);
    the_list_numbers_the_points_as_the_jobs_do(&file);
    let jobs = write_jobs(&file, &b, &d.join("jobs.txt"));
    run_jobs(&jobs);
    the_merged_jobs_give_the_same_table(&file, &b, &d.join("m.csv"), &csv_a);
    a_rerun_finds_every_point_done(&file, &a, &csv_a);
    a_merge_names_the_point_without_a_result(&file, &b, &csv_a);
    a_point_out_of_range_is_a_usage_error(&file, &b);
    let _ = std::fs::remove_dir_all(&d);
}

/// (a) All at once: the table, the CSV and the JSON; the CSV's text.
fn run_at_once(file: &Path, a: &Path) -> String {
    let o = wasp(&["sweep", s(file), "--out", s(a), "--jobs", "2"]);
    let table = ok(&o);
    assert!(table.starts_with("point  scene"), "{table}");
    assert!(table.contains("shared-tile  wasp:0:3"), "{table}");
    assert!(
        stderr(&o).contains("2 tasks (2 run, 0 already done)"),
        "{}",
        stderr(&o)
    );
    let csv_a = std::fs::read_to_string(a.join("results.csv")).unwrap();
    let lines = rows(&csv_a);
    assert_eq!(lines.len(), 3, "{csv_a}");
    assert!(
        lines[0].starts_with("point,config,dispatch,policy,scene,"),
        "{}",
        lines[0]
    );
    assert!(lines[0].contains(",cycles,"), "{}", lines[0]);
    assert!(lines[1].starts_with("1,shipped,shared-tile,baseline,procedural-plane,"));
    assert!(lines[2].starts_with("2,shipped,shared-tile,wasp:0:3,procedural-plane,"));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(a.join("results.json")).unwrap()).unwrap();
    assert_eq!(json.as_array().unwrap().len(), 2);
    assert_eq!(json[1]["stats"]["policy"], "wasp:0:3");
    assert!(json[0]["stats"]["cycles"].as_u64().unwrap() > 0);
    csv_a
}

/// --list numbers the points as the jobs do.
fn the_list_numbers_the_points_as_the_jobs_do(file: &Path) {
    let list = ok(&wasp(&["sweep", s(file), "--list"]));
    assert_eq!(
        list,
        "1\tprocedural-plane, config shipped, shared-tile, baseline\n\
         2\tprocedural-plane, config shipped, shared-tile, wasp:0:3\n"
    );
}

/// (b) As jobs: the jobs file `jobs` and how to run it; its lines.
fn write_jobs(file: &Path, b: &Path, jobs: &Path) -> Vec<String> {
    let how = ok(&wasp(&[
        "sweep",
        s(file),
        "--out",
        s(b),
        "--jobs-file",
        s(jobs),
    ]));
    assert!(how.contains("sbatch --array=1-2"), "{how}");
    assert!(how.contains("parallel -j 8 <"), "{how}");
    let lines = rows(&std::fs::read_to_string(jobs).unwrap());
    assert_eq!(lines.len(), 2);
    assert!(
        lines[1].ends_with(&format!("--out {} --point 2 -q", s(b))),
        "{}",
        lines[1]
    );
    assert!(
        lines[0].contains("'"),
        "the file name has a space: {}",
        lines[0]
    );
    lines
}

/// One process per point, each a line of the jobs file.
fn run_jobs(lines: &[String]) {
    for (i, line) in lines.iter().enumerate() {
        // Run from elsewhere: the commands are self-contained.
        let o = Command::new("sh")
            .arg("-c")
            .arg(line)
            .current_dir(std::env::temp_dir())
            .output()
            .unwrap();
        assert!(o.status.success(), "{line}: {}", stderr(&o));
        assert!(
            stdout(&o).starts_with(&format!("point {}/2 (", i + 1)),
            "{}",
            stdout(&o)
        );
        assert!(stderr(&o).is_empty(), "-q: {}", stderr(&o));
    }
}

/// The jobs' points, merged into `merged`, are the table run at once.
fn the_merged_jobs_give_the_same_table(file: &Path, b: &Path, merged: &Path, csv_a: &str) {
    assert!(
        !b.join("results.csv").exists(),
        "a job writes its point only"
    );
    ok(&wasp(&[
        "merge",
        s(b),
        "--sweep",
        s(file),
        "--csv",
        s(merged),
    ]));
    assert_eq!(rows(&std::fs::read_to_string(merged).unwrap()), rows(csv_a));
}

/// (c) A rerun finds every point done.
fn a_rerun_finds_every_point_done(file: &Path, a: &Path, csv_a: &str) {
    let o = wasp(&["sweep", s(file), "--out", s(a)]);
    ok(&o);
    assert!(
        stderr(&o).contains("2 tasks (0 run, 2 already done)"),
        "{}",
        stderr(&o)
    );
    assert_eq!(
        std::fs::read_to_string(a.join("results.csv")).unwrap(),
        csv_a
    );
}

/// A merge without one point's file writes the rest and names it.
fn a_merge_names_the_point_without_a_result(file: &Path, b: &Path, csv_a: &str) {
    let points: Vec<_> = std::fs::read_dir(b.join("points"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    assert_eq!(points.len(), 2);
    let wasp_m = points
        .iter()
        .find(|p| std::fs::read_to_string(p).unwrap().contains("wasp:0:3"))
        .unwrap();
    std::fs::remove_file(wasp_m).unwrap();
    let o = wasp(&["merge", s(b), "--sweep", s(file)]);
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(rows(&stdout(&o)), rows(csv_a)[..2]);
    let e = stderr(&o);
    assert!(
        e.contains("1 of 2 points have no result: 2; run them with `wasp sweep"),
        "{e}"
    );
    assert!(e.contains("--point N`"), "{e}");
}

/// (d) A point out of range is a usage error naming the range.
fn a_point_out_of_range_is_a_usage_error(file: &Path, b: &Path) {
    let o = wasp(&["sweep", s(file), "--out", s(b), "--point", "99"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--point 99: "), "{}", stderr(&o));
    assert!(stderr(&o).contains("has points 1 to 2"), "{}", stderr(&o));
}

#[test]
fn a_bad_sweep_file_is_refused_before_any_run() {
    let d = common::scratch("sweep", "bad");
    let file = d.join("bad.toml");
    std::fs::write(
        &file,
        "scenes = [\"procedural-plane\"]\npolicies = [\"baseline\"]\n[[configs]]\nname = \"x\"\n\
         base = \"paper\"\nset = [\"l0.mshrs=0\"]\n",
    )
    .unwrap();
    let out = d.join("out");
    let o = wasp(&["sweep", s(&file), "--out", s(&out)]);
    assert_eq!(o.status.code(), Some(2));
    let e = stderr(&o);
    assert!(
        e.contains("bad.toml:4: configs `x` with its own dispatch"),
        "{e}"
    );
    assert!(e.contains("l0.mshrs"), "{e}");
    assert!(!out.exists(), "nothing ran");
    // The shipped example parses and expands.
    let example = concat!(env!("CARGO_MANIFEST_DIR"), "/configs/sweep-example.toml");
    let list = ok(&wasp(&["sweep", example, "--list"]));
    assert_eq!(list.lines().count(), 24, "{list}");
    let _ = std::fs::remove_dir_all(&d);
}

/// The scene cache `wasp` uses in this environment (as
/// `wasp_frontend::fetch::cache_dir` finds it).
fn scene_cache() -> std::path::PathBuf {
    let env = |k: &str| std::env::var_os(k).filter(|v| !v.is_empty());
    if let Some(d) = env("WASP_SCENES") {
        return d.into();
    }
    if let Some(d) = env("XDG_CACHE_HOME").map(std::path::PathBuf::from) {
        if d.is_absolute() {
            return d.join("wasp").join("scenes");
        }
    }
    match env("HOME") {
        Some(h) => std::path::PathBuf::from(h).join(".cache/wasp/scenes"),
        None => std::env::temp_dir().join("wasp-scenes"),
    }
}

/// A stand-in for Debian's archive: a `teeworlds-data` package of version
/// `version` (a data folder, no data: a study whose points are all stored
/// renders nothing) built by the real dpkg-deb, and an `apt-get` on a
/// PATH folder that hands it over. Returns that folder.
fn stand_in_archive(d: &Path, version: &str) -> std::path::PathBuf {
    let pkg = d.join("pkg");
    let _ = std::fs::remove_dir_all(&pkg);
    for dir in [
        "DEBIAN",
        "usr/share/games/teeworlds/data",
        "usr/share/doc/teeworlds-data",
    ] {
        std::fs::create_dir_all(pkg.join(dir)).unwrap();
    }
    std::fs::write(
        pkg.join("DEBIAN/control"),
        format!(
            "Package: teeworlds-data\nVersion: {version}\nArchitecture: all\nMaintainer: wasp \
             tests <tests@example.org>\nDescription: a stand-in for a test\n"
        ),
    )
    .unwrap();
    std::fs::write(pkg.join("usr/share/doc/teeworlds-data/copyright"), "test\n").unwrap();
    let deb = d.join(format!("teeworlds-data_{version}_all.deb"));
    let built = Command::new("dpkg-deb")
        .arg("--build")
        .arg(&pkg)
        .arg(&deb)
        .output()
        .expect("dpkg-deb");
    assert!(built.status.success(), "{}", stderr(&built));
    let bin = d.join("bin");
    std::fs::create_dir_all(&bin).unwrap();
    let apt = bin.join("apt-get");
    std::fs::write(
        &apt,
        format!(
            "#!/bin/sh\ncase \"$1 $2\" in\n\"download --print-uris\") ;;\n\"download \"*) cp '{}' . \
             ;;\nesac\nexit 0\n",
            deb.display()
        ),
    )
    .unwrap();
    use std::os::unix::fs::PermissionsExt;
    std::fs::set_permissions(&apt, std::fs::Permissions::from_mode(0o755)).unwrap();
    bin
}

/// A study run again with another scene cache (`WASP_SCENES`) keeps its
/// game points: a game's scene counts by the versions of its packages, not
/// by the folder they lie in. The other cache starts empty, so the game is
/// fetched first (from a stand-in archive of the same version), then its
/// points are found.
#[cfg(unix)]
#[test]
#[ignore = "needs fetched game data: wasp scenes fetch teeworlds"]
fn a_study_keeps_its_game_points_in_another_scene_cache() {
    let marker = std::fs::read_to_string(scene_cache().join("teeworlds/.wasp-fetched")).unwrap();
    let version = marker
        .lines()
        .find_map(|l| l.strip_prefix("teeworlds-data "))
        .expect("the package's version")
        .trim()
        .to_string();
    let d = common::scratch("sweep", "other-cache");
    let (file, out) = (d.join("tw.toml"), d.join("out"));
    let _ = std::fs::remove_dir_all(&out);
    std::fs::write(
        &file,
        "scenes = [\"tw-dm1-spawn0\"]\npolicies = [\"baseline\"]\n[[configs]]\nname = \
         \"shipped\"\nbase = \"paper\"\n",
    )
    .unwrap();
    let args = ["sweep", s(&file), "--out", s(&out), "--jobs", "1"];
    let first = wasp(&args);
    let table = ok(&first);
    assert!(
        stderr(&first).contains("(1 run, 0 already done"),
        "{}",
        stderr(&first)
    );

    let bin = stand_in_archive(&d, &version);
    let path = format!("{}:{}", bin.display(), std::env::var("PATH").unwrap());
    let other = d.join("other cache");
    let _ = std::fs::remove_dir_all(&other);
    let again = Command::new(env!("CARGO_BIN_EXE_wasp"))
        .args(args)
        .env("WASP_SCENES", &other)
        .env("PATH", path)
        .output()
        .unwrap();
    let e = stderr(&again);
    assert_eq!(ok(&again), table);
    assert!(e.contains("fetching the teeworlds data"), "{e}");
    assert!(e.contains("(0 run, 1 already done"), "{e}");
    assert!(other.join("teeworlds/.wasp-fetched").is_file());
    let _ = std::fs::remove_dir_all(&d);
}
