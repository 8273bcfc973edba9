//! Whole-program tests of the draw order: `wasp render --draw-order`,
//! `draw_order` in a scene file, `wasp characterize --draw-order` and a
//! sweep's `draw_orders`, with their error messages (procedural scenes at
//! small sizes: no game data needed).

use std::path::{Path, PathBuf};

mod common;
use common::{ok, stderr, wasp};

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// A small copy of the procedural plane (ground, blocks, sky) named
/// `small-plane` in a folder of scene definitions, with `extra` lines.
fn scenes_dir(name: &str, extra: &str) -> PathBuf {
    let d = common::scratch("draworder", name);
    std::fs::write(
        d.join("small-plane.toml"),
        format!(
            "name = \"small-plane\"\ngame = \"procedural\"\nmap = \"plane\"\ncamera = \
             \"ground\"\nwidth = 392\nheight = 154\n{extra}"
        ),
    )
    .unwrap();
    d
}

/// `wasp render SCENE` at 392x154 with `args`, the trace written to
/// `out`; its standard error.
fn render(dir: &Path, scene: &str, out: &Path, args: &[&str]) -> String {
    let mut a = vec![
        "render",
        "--scenes-dir",
        s(dir),
        scene,
        "--size",
        "392x154",
        "--trace-out",
        s(out),
    ];
    a.extend_from_slice(args);
    let o = wasp(&a);
    ok(&o);
    stderr(&o)
}

#[test]
fn render_takes_a_draw_order_and_as_loaded_is_the_default_trace() {
    let d = scenes_dir("render", "");
    let t = |n: &str| d.join(format!("{n}.trace"));
    let err = render(&d, "small-plane", &t("default"), &[]);
    assert!(err.contains("392x154 (as-loaded)"), "{err}");
    render(
        &d,
        "small-plane",
        &t("loaded"),
        &["--draw-order", "as-loaded"],
    );
    let err = render(
        &d,
        "small-plane",
        &t("object"),
        &["--draw-order", "front-to-back-object"],
    );
    assert!(err.contains("(front-to-back-object)"), "{err}");
    render(
        &d,
        "small-plane",
        &t("draw"),
        &["--draw-order", "front-to-back-draw"],
    );
    let read = |n: &str| std::fs::read_to_string(t(n)).unwrap();
    assert_eq!(read("default"), read("loaded"));
    assert!(!read("default").contains("draw order"));
    let object = read("object");
    assert_ne!(object, read("default"));
    assert!(
        object.contains("# draw order front-to-back-object: "),
        "{}",
        &object[..600]
    );
    // The ground is drawn after the blocks: fewer warps.
    let warps = |text: &str| {
        wasp_sim::trace::Trace::parse(text, "t")
            .unwrap()
            .stats()
            .warps
    };
    assert!(warps(&object) < warps(&read("default")));
    assert!(read("draw").contains("# draw order front-to-back-draw: "));
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_scene_file_names_its_draw_order_and_the_option_overrides_it() {
    let d = scenes_dir("file", "draw_order = \"front-to-back-object\"\n");
    let t = |n: &str| d.join(format!("{n}.trace"));
    render(&d, "small-plane", &t("file"), &[]);
    render(
        &d,
        "small-plane",
        &t("asked"),
        &["--draw-order", "front-to-back-object"],
    );
    render(
        &d,
        "small-plane",
        &t("loaded"),
        &["--draw-order", "as-loaded"],
    );
    let read = |n: &str| std::fs::read_to_string(t(n)).unwrap();
    assert_eq!(read("file"), read("asked"));
    assert_ne!(read("file"), read("loaded"));
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_2d_scene_is_drawn_as_loaded_with_a_note() {
    let d = common::scratch("draworder", "2d");
    let (a, b) = (d.join("a.trace"), d.join("b.trace"));
    render(&d, "procedural-sprites", &a, &["-q"]);
    let err = render(
        &d,
        "procedural-sprites",
        &b,
        &["-q", "--draw-order", "front-to-back-draw"],
    );
    assert!(
        err.contains(
            "wasp: note: procedural-sprites is a 2D scene drawn in painter's order without a \
             depth test (its order is its picture): draw order front-to-back-draw changes \
             nothing, it is drawn as-loaded"
        ),
        "{err}"
    );
    assert_eq!(
        std::fs::read_to_string(&a).unwrap(),
        std::fs::read_to_string(&b).unwrap()
    );
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn bad_draw_orders_are_usage_errors_that_say_what_is_allowed() {
    let o = wasp(&[
        "render",
        "procedural-plane",
        "--draw-order",
        "sideways",
        "--png",
        "x.png",
    ]);
    assert_eq!(o.status.code(), Some(2));
    let err = stderr(&o);
    assert!(
        err.contains(
            "unknown draw order `sideways` (expected as-loaded, front-to-back-object or \
             front-to-back-draw)"
        ),
        "{err}"
    );
    let o = wasp(&["characterize", "--draw-order", "nearest-first"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("unknown draw order `nearest-first`"));
    // In a scene file: the file, the line and the field.
    let d = scenes_dir("bad", "draw_order = \"back-to-front\"\n");
    let file = d.join("small-plane.toml");
    let o = wasp(&["render", s(&file), "--trace-out", s(&d.join("x.trace"))]);
    assert_eq!(o.status.code(), Some(2));
    let err = stderr(&o);
    assert!(err.contains(s(&file)), "{err}");
    assert!(
        err.contains("line 7") && err.contains("draw_order = \"back-to-front\""),
        "{err}"
    );
    assert!(
        err.contains("`as-loaded`, `front-to-back-object`, `front-to-back-draw`"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn characterize_reports_every_order_asked_for() {
    let d = scenes_dir("characterize", "");
    let json = d.join("c.json");
    let o = wasp(&[
        "characterize",
        "--scenes-dir",
        s(&d),
        "small-plane",
        "--draw-order",
        "as-loaded",
        "--draw-order",
        "front-to-back-object",
        "--json",
        s(&json),
    ]);
    let table = ok(&o);
    assert!(table.contains("shaded warps per quad position"), "{table}");
    assert!(table.contains("early-Z rejected share"), "{table}");
    assert!(table.contains("front-to-back-object"), "{table}");
    let rows: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let rows = rows.as_array().unwrap();
    assert_eq!(rows.len(), 2);
    assert_eq!(rows[0]["draw_order"], "as-loaded");
    assert_eq!(rows[1]["draw_order"], "front-to-back-object");
    let f = |r: &serde_json::Value, k: &str| r[k].as_f64().unwrap();
    assert!(f(&rows[1], "warps_per_position") < f(&rows[0], "warps_per_position"));
    assert!(f(&rows[1], "rejected_early_z_share") > f(&rows[0], "rejected_early_z_share"));
    for r in rows {
        assert!(f(r, "warps_per_position_p50") <= f(r, "warps_per_position_p99"));
    }
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_sweep_runs_each_draw_order_on_its_own_trace() {
    let d = scenes_dir("sweep", "");
    // Beside the folder of scene definitions, not in it.
    let file = d.with_extension("sweep.toml");
    std::fs::write(
        &file,
        "scenes = [\"small-plane\"]\ndraw_orders = [\"as-loaded\", \"front-to-back-object\"]\n\
         policies = [\"baseline\"]\n[[configs]]\nname = \"shipped\"\nbase = \"paper\"\n",
    )
    .unwrap();
    let out = d.join("out");
    let o = wasp(&[
        "sweep",
        "--scenes-dir",
        s(&d),
        s(&file),
        "--out",
        s(&out),
        "--jobs",
        "2",
    ]);
    let table = ok(&o);
    assert!(table.contains("front-to-back-object"), "{table}");
    let csv = std::fs::read_to_string(out.join("results.csv")).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines.len(), 3, "{csv}");
    assert!(lines[0].starts_with("point,config,dispatch,policy,scene,draw_order,"));
    assert!(lines[1].starts_with("1,shipped,shared-tile,baseline,small-plane,as-loaded,"));
    assert!(
        lines[2].starts_with("2,shipped,shared-tile,baseline,small-plane,front-to-back-object,")
    );
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("results.json")).unwrap()).unwrap();
    let warps = |i: usize| json[i]["stats"]["warps"].as_u64().unwrap();
    assert!(warps(1) < warps(0), "{} vs {}", warps(1), warps(0));
    assert_ne!(json[0]["key"], json[1]["key"]);
    // Two records, two keys; the rerun takes both from the folder.
    let o = wasp(&["sweep", "--scenes-dir", s(&d), s(&file), "--out", s(&out)]);
    ok(&o);
    assert!(
        stderr(&o).contains("2 tasks (0 run, 2 already done)"),
        "{}",
        stderr(&o)
    );
    let list = ok(&wasp(&["sweep", "--scenes-dir", s(&d), s(&file), "--list"]));
    assert_eq!(
        list,
        "1\tsmall-plane, config shipped, shared-tile, baseline, draw order as-loaded\n\
         2\tsmall-plane, config shipped, shared-tile, baseline, draw order \
         front-to-back-object\n"
    );
    let _ = std::fs::remove_file(&file);
    let _ = std::fs::remove_dir_all(&d);
}
