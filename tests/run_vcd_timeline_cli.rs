//! Whole-program tests of what `wasp run` records over a window of cycles:
//! the VCD waveforms with their GTKWave save file and time axis, and the
//! timeline picture.

use wasp_waves::readback;

mod common;
use common::run::{dir, run_json, synth_trace, tiny_config, tiny_trace};
use common::{ok, stderr, wasp};

#[test]
fn vcd_window_and_signals() {
    let d = dir("vcd");
    let cfg = tiny_config(&d);
    let vcd = d.join("run.vcd");
    let v = run_json(&[
        "--config",
        &cfg,
        "--trace",
        &tiny_trace(),
        "--vcd",
        vcd.to_str().unwrap(),
        "--vcd-from",
        "10",
        "--vcd-to",
        "40",
    ]);
    assert!(v["cycles"].as_u64().unwrap() > 40);
    let bytes = std::fs::read(&vcd).unwrap();
    let rb = readback::values_by_cycle(&bytes).unwrap();
    let names: Vec<&str> = rb.names().collect();
    for s in [
        "wasp.core0.scheduler.free_mshrs",
        "wasp.core0.scheduler.nonblocked_priority",
        "wasp.core0.scheduler.real_free_mshrs",
        "wasp.core0.scheduler.priority_over_regular",
        "wasp.core0.scheduler.launch",
        "wasp.core0.scheduler.prio_queue_occupancy",
        "wasp.core0.warps_active",
        "wasp.raster.tile",
        "wasp.raster.quad",
        "wasp.raster.sent",
        "wasp.raster.rejected",
        "wasp.raster.backpressure",
        "wasp.raster.flush_left",
    ] {
        assert!(names.contains(&s), "{s} missing: {names:?}");
    }
    // The rasterizer works on tile 1 (index 0) from the window's start.
    let tile = rb.signal("wasp.raster.tile").unwrap().changes()[0];
    assert_eq!(tile, (10, 1));
    let first = rb.signal("wasp.core0.warps_active").unwrap().changes()[0].0;
    assert_eq!(first, 10);
    assert_eq!(rb.end_time(), Some(41));
    let gtkw = std::fs::read_to_string(d.join("run.vcd.gtkw")).unwrap();
    assert!(gtkw.contains("wasp.core0.scheduler.free_mshrs[4:0]"));
    assert!(gtkw.contains("wasp.raster.quad[31:0]"), "{gtkw}");
}

#[test]
fn the_timeline_is_drawn_as_png_or_svg() {
    let d = dir("timeline");
    let trace = synth_trace(&d, 6);
    let png = d.join("t.png");
    let svg = d.join("t.svg");
    for p in [&png, &svg] {
        ok(&wasp(&[
            "run",
            "-q",
            "--trace",
            &trace,
            "--timeline",
            p.to_str().unwrap(),
            "--timeline-to",
            "3000",
        ]));
    }
    let bytes = std::fs::read(&png).unwrap();
    assert!(bytes.starts_with(b"\x89PNG\r\n\x1a\n"));
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(
        text.contains("Resident warps per core"),
        "svg has the panels"
    );
    // A window after the run's end, and a wrong extension, are refused.
    let late = d.join("late.png");
    let e = stderr(&wasp(&[
        "run",
        "-q",
        "--trace",
        &trace,
        "--timeline",
        late.to_str().unwrap(),
        "--timeline-from",
        "900000000",
    ]));
    assert!(e.contains("before the window"), "{e}");
    assert!(!late.exists());
    let e = stderr(&wasp(&["run", "--trace", &trace, "--timeline", "t.gif"]));
    assert!(e.contains(".png or .svg"), "{e}");
}

/// Cycles `--vcd` writes a change at, read from the VCD's timestamps.
fn vcd_times(bytes: &[u8]) -> Vec<u64> {
    String::from_utf8_lossy(bytes)
        .lines()
        .filter_map(|l| l.strip_prefix('#'))
        .map(|t| t.parse().unwrap())
        .collect()
}

#[test]
fn vcd_time_axis_is_cycles_or_picoseconds_and_says_so() {
    let d = dir("vcd-time");
    let cfg = tiny_config(&d);
    let trace = tiny_trace();
    let write = |name: &str, extra: &[&str]| -> (String, String) {
        let vcd = d.join(name);
        let mut a = vec![
            "--config",
            &cfg,
            "--trace",
            &trace,
            "--vcd",
            vcd.to_str().unwrap(),
            "--vcd-from",
            "10",
            "--vcd-to",
            "40",
        ];
        a.extend_from_slice(extra);
        run_json(&a);
        let gtkw = std::fs::read_to_string(d.join(format!("{name}.gtkw"))).unwrap();
        (std::fs::read_to_string(&vcd).unwrap(), gtkw)
    };
    let (cycles, cycles_gtkw) = write("cycles.vcd", &[]);
    let (explicit, _) = write("explicit.vcd", &["--vcd-time", "cycles"]);
    assert_eq!(cycles, explicit.replace("explicit.vcd", "cycles.vcd"));
    let note = "one time unit = one GPU cycle at 600 MHz (1.667 ns)";
    assert!(
        cycles.contains(&format!("$comment\n    {note}\n$end")),
        "{cycles}"
    );
    assert!(cycles.contains("$timescale 1 ns $end"));
    assert!(
        cycles_gtkw.contains(&format!("[*] {note}\n")),
        "{cycles_gtkw}"
    );
    assert!(cycles_gtkw.contains("[timestart] 10\n"), "{cycles_gtkw}");

    let (real, real_gtkw) = write("real.vcd", &["--vcd-time", "real"]);
    assert!(real.contains("$timescale 1 ps $end"), "{real}");
    let note = "time unit = 1 ps; one GPU cycle at 600 MHz = 1667 ps: cycle N is at time N x 1667";
    assert!(real.contains(note), "{real}");
    assert!(real_gtkw.contains(&format!("[*] {note}\n")), "{real_gtkw}");
    assert!(real_gtkw.contains("[timestart] 16670\n"), "{real_gtkw}");
    let c = vcd_times(cycles.as_bytes());
    assert_eq!(c.first(), Some(&10));
    assert_eq!(c.last(), Some(&41));
    let scaled: Vec<u64> = c.iter().map(|t| t * 1667).collect();
    assert_eq!(vcd_times(real.as_bytes()), scaled);

    // The axis follows gpu.frequency_mhz.
    let (fast, _) = write("fast.vcd", &["--set", "gpu.frequency_mhz=1000"]);
    assert!(
        fast.contains("one GPU cycle at 1000 MHz (1.000 ns)"),
        "{fast}"
    );
    let (fast_real, _) = write(
        "fast-real.vcd",
        &["--set", "gpu.frequency_mhz=1000", "--vcd-time", "real"],
    );
    let scaled: Vec<u64> = c.iter().map(|t| t * 1000).collect();
    assert_eq!(vcd_times(fast_real.as_bytes()), scaled);

    // Checked before any work: an unknown axis, and an axis without --vcd.
    let o = wasp(&[
        "run",
        "--trace",
        &trace,
        "--vcd",
        "x.vcd",
        "--vcd-time",
        "ns",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("cycles") && stderr(&o).contains("real"));
    let o = wasp(&["run", "--trace", &trace, "--vcd-time", "real"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--vcd <FILE>"), "{}", stderr(&o));
}
