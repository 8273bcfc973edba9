//! The Verilog side of the co-simulation: finding `iverilog`/`vvp`, and
//! compiling and running the testbench on a stimulus file.

use super::stimulus::Config;
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;

pub(crate) fn env_u64(name: &str) -> Option<u64> {
    std::env::var(name).ok().and_then(|s| s.trim().parse().ok())
}

pub(crate) fn verilog_dir() -> PathBuf {
    match std::env::var_os("WASP_COSIM_VERILOG_DIR") {
        Some(d) => PathBuf::from(d),
        None => Path::new(env!("CARGO_MANIFEST_DIR")).join("verilog"),
    }
}

/// Whether iverilog and vvp can run; if not, skip (or fail under
/// `WASP_REQUIRE_TOOLS=1`).
pub(crate) fn tools_present() -> bool {
    let ok = |prog: &str, arg: &str| {
        Command::new(prog)
            .arg(arg)
            .output()
            .map(|o| o.status.success() || !o.stdout.is_empty() || !o.stderr.is_empty())
            .unwrap_or(false)
    };
    if ok("iverilog", "-V") && ok("vvp", "-V") {
        return true;
    }
    if std::env::var("WASP_REQUIRE_TOOLS").as_deref() == Ok("1") {
        panic!("iverilog/vvp not installed and WASP_REQUIRE_TOOLS=1 (apt-get install iverilog)");
    }
    // Straight to the process's stderr, once: the test harness captures
    // `eprintln!` of passing tests.
    static SKIP_NOTE: std::sync::Once = std::sync::Once::new();
    SKIP_NOTE.call_once(|| {
        let _ = writeln!(
            std::io::stderr(),
            "skipped: iverilog not installed (the Verilog co-simulation did not run; set WASP_REQUIRE_TOOLS=1 to make this a failure)"
        );
    });
    false
}

/// Compile the testbench for `cfg`, run the stimulus, return the lines.
pub(crate) fn run_verilog(cfg: &Config, stimulus: &str) -> Vec<String> {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("wasp-cosim")
        .join(format!("{}-{}", cfg.name, std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let stim = dir.join("stimulus.txt");
    let out = dir.join("outputs.txt");
    let vvp = dir.join("tb.vvp");
    std::fs::write(&stim, stimulus).unwrap();
    let tb = Path::new(env!("CARGO_MANIFEST_DIR")).join("verilog/tb_cosim.v");
    let src = verilog_dir().join("wasp_sched.v");
    let o = Command::new("iverilog")
        .args(["-g2005", "-Wall", "-s", "tb_cosim", "-o"])
        .arg(&vvp)
        .args(cfg.iverilog_params())
        .arg(&tb)
        .arg(&src)
        .output()
        .expect("run iverilog");
    assert!(
        o.status.success() && o.stderr.is_empty(),
        "{}: iverilog failed or warned:\n{}",
        cfg.name,
        String::from_utf8_lossy(&o.stderr)
    );
    let mut plus_stim = std::ffi::OsString::from("+stim=");
    plus_stim.push(&stim);
    let mut plus_out = std::ffi::OsString::from("+out=");
    plus_out.push(&out);
    let o = Command::new("vvp")
        .arg("-n")
        .arg(&vvp)
        .arg(plus_stim)
        .arg(plus_out)
        .output()
        .expect("run vvp");
    let log = String::from_utf8_lossy(&o.stdout).to_string() + &String::from_utf8_lossy(&o.stderr);
    assert!(
        o.status.success() && !log.contains("ERROR"),
        "{}: vvp failed:\n{log}",
        cfg.name
    );
    let text = std::fs::read_to_string(&out).expect("testbench output");
    let _ = std::fs::remove_dir_all(&dir);
    text.lines().map(str::to_owned).collect()
}
