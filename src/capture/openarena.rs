//! OpenArena's engine (Debian `openarena`: ioquake3 with OpenArena's
//! game code, renderer `opengl1`) at a scene's spawn point.
//!
//! The engine starts on the map with cheats (`devmap`), sound and network
//! off, the scene's resolution in a window (`r_mode -1`,
//! `r_customwidth/height`), HUD, weapon and console notify lines off, and a
//! fresh home folder (so no earlier configuration is read). A console
//! script then runs, counting frames with `wait`:
//!
//! 1. `team spectator`: a spectator flies (no gravity, no weapon, no
//!    body), so its origin is exactly the one given;
//! 2. `fixedtime 20`: every frame advances the game by 20 ms, so the
//!    motion below is the same on any machine;
//! 3. `setviewpos`: the teleport gives a speed of 400 units/s along the
//!    yaw it sets, which the spectator friction (5/s, applied per 20 ms
//!    step) takes away after [`GLIDE`] units. The spectator is teleported
//!    that far *in front of* the spawn point facing backwards (spawn
//!    points face open space; behind them there is often a wall), glides
//!    back to rest on the spawn point, and turns 180 degrees on the spot
//!    (`+left` for 10 frames at `cl_yawspeed 900`, then `cl_yawspeed 0`
//!    before `-left`, so the key's release adds no turn);
//!    from `team spectator` until the turn is done nothing is drawn
//!    (`r_norefresh 1`: those frames still end in a swap, with no draw
//!    call);
//! 4. `viewpos` prints the view, then the frames at the camera are drawn
//!    and `viewpos` prints it again before `quit`.
//!
//! `wait N` waits N/2 frames: the engine runs its command buffer twice a
//! frame. All counts below are frames.
//!
//! The script's `viewpos` lines are checked against the spawn point: the
//! eye must be [`EYE_HEIGHT`] above the spawn origin, at the spawn's yaw.

use super::tools::{self, Group, Need, WorkDir};
use super::{EngineRun, Progress};
use serde_json::json;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};
use wasp_frontend::def::{Game, SceneDef};
use wasp_frontend::openarena::{self, scene_spawn, EYE_HEIGHT};

/// The engine binary of Debian's `openarena` package.
pub const ENGINE: &str = "/usr/lib/ioquake3/ioquake3";
/// What the capture runs besides Xvfb and apitrace.
pub const NEEDS: [Need; 1] = [Need {
    program: ENGINE,
    package: "openarena",
}];
/// The game folder the `openarena` package's wrapper passes as
/// `fs_basepath`.
const BASEPATH: &str = "/usr/lib/openarena";
/// The game data the engine reads (`openarena-data`, a dependency of
/// `openarena`), where the spawn points are read from.
const INSTALLED_DATA: &str = "/usr/share/games/openarena";
/// Frames drawn at the camera by default.
pub const DEFAULT_FRAMES: u32 = 5;
/// Game milliseconds per frame (`fixedtime`).
const FRAME_MS: u32 = 20;
/// How far a spectator glides after `setviewpos` at [`FRAME_MS`]: speed
/// 400 units/s times (1 - 5 x 0.02) per step, summed over the steps:
/// 0.02 x 400 x 0.9 / 0.1 = 72 units (to 0.1 unit: the engine stops a
/// spectator slower than 1 unit/s).
pub const GLIDE: f32 = 72.0;
/// Frames for the glide to end: 60 steps take the speed under 1 unit/s
/// (0.9^60 x 400 < 1), and the teleport reaches the view some frames
/// after the command.
const GLIDE_FRAMES: u32 = 80;
/// Frames of the 180-degree turn.
const TURN_FRAMES: u32 = 10;
/// Seconds the engine may run.
const DEADLINE_S: u64 = 60;

/// The spawn point of the scene's `spawn:N` camera, from the installed
/// game data, else the scene cache's.
fn spawn(def: &SceneDef) -> Result<([f32; 3], f32), String> {
    let installed = Path::new(INSTALLED_DATA);
    let root = if installed.join("baseoa").is_dir() {
        installed.to_path_buf()
    } else {
        wasp_frontend::fetch::data_root(Game::Openarena)
    };
    scene_spawn(&root, def).map_err(|e| e.to_string())
}

/// The engine's console script for a camera at spawn `origin`, `yaw`.
pub fn script(origin: [f32; 3], yaw: f32, frames: u32) -> String {
    let (s, c) = yaw.to_radians().sin_cos();
    // In front of the spawn point, facing back; TeleportPlayer raises the
    // origin by 1 unit.
    let start = [
        origin[0] + GLIDE * c,
        origin[1] + GLIDE * s,
        origin[2] - 1.0,
    ];
    let back = yaw + 180.0;
    let turn_speed = 180.0 / (TURN_FRAMES as f32 * FRAME_MS as f32 / 1000.0);
    // `wait N` waits N/2 frames (two command-buffer runs a frame).
    let w = |frames: u32| 2 * frames;
    format!(
        "wait {}\nteam spectator\nset r_norefresh 1\nwait {}\nset fixedtime {FRAME_MS}\n\
         wait {}\nsetviewpos {:.3} {:.3} {:.3} {back}\nwait {}\n\
         set cl_yawspeed {turn_speed}\n+left\nwait {}\nset cl_yawspeed 0\n-left\n\
         set r_norefresh 0\nviewpos\nwait {}\nviewpos\nquit\n",
        w(15),
        w(10),
        w(5),
        start[0],
        start[1],
        start[2],
        w(GLIDE_FRAMES),
        w(TURN_FRAMES),
        w(frames.max(1)),
    )
}

/// The engine's arguments (after the program) for scene `def`.
pub fn engine_args(def: &SceneDef, home: &Path) -> Vec<String> {
    let mut a: Vec<String> = Vec::new();
    let mut set = |k: &str, v: &str| {
        a.extend(["+set".to_string(), k.to_string(), v.to_string()]);
    };
    set("com_basegame", "baseoa");
    set("fs_basepath", BASEPATH);
    set("fs_homepath", &home.to_string_lossy());
    set("com_legacyprotocol", "71");
    set("com_protocol", "71");
    set("ttycon", "0");
    set("net_enabled", "0");
    set("cl_motd", "0");
    set("cl_renderer", "opengl1");
    set("r_mode", "-1");
    set("r_customwidth", &def.width.to_string());
    set("r_customheight", &def.height.to_string());
    set("r_fullscreen", "0");
    set("s_initsound", "0");
    set("in_nograb", "1");
    set("sv_pure", "0");
    set("bot_enable", "0");
    set("com_introplayed", "1");
    set("cg_draw2D", "0");
    set("cg_drawGun", "0");
    set("con_notifytime", "0");
    a.extend([
        "+devmap".into(),
        def.map.clone(),
        "+exec".into(),
        "wasp-capture.cfg".into(),
    ]);
    a
}

/// The `(x y z) : yaw` lines `viewpos` printed.
pub fn viewpos_lines(log: &str) -> Vec<[i64; 4]> {
    log.lines()
        .filter_map(|l| {
            let l = l.trim();
            let (pos, yaw) = l.strip_prefix('(')?.split_once(") : ")?;
            let v: Vec<i64> = pos
                .split_whitespace()
                .map(|w| w.parse().ok())
                .collect::<Option<_>>()?;
            (v.len() == 3).then_some([v[0], v[1], v[2], yaw.trim().parse().ok()?])
        })
        .collect()
}

/// Check the view the engine printed against the spawn point's eye:
/// each coordinate within 1 unit (`viewpos` prints whole units), the yaw
/// within 1 degree.
pub fn check_view(views: &[[i64; 4]], eye: [f32; 3], yaw: f32) -> Result<[i64; 4], String> {
    let [.., at_rest, last] = views else {
        return Err(format!(
            "the engine printed {} of the 2 `viewpos` lines of the script (did the map \
             load?)",
            views.len()
        ));
    };
    let off = |v: &[i64; 4]| {
        let d = (0..3)
            .map(|i| (v[i] as f32 - eye[i]).abs())
            .fold(0.0, f32::max);
        let dy = ((v[3] as f32 - yaw).rem_euclid(360.0) + 180.0).rem_euclid(360.0) - 180.0;
        d <= 1.0 && dy.abs() <= 1.0
    };
    for v in [at_rest, last] {
        if !off(v) {
            return Err(format!(
                "the engine's view is ({} {} {}) yaw {}, not the spawn point's eye ({:.1} \
                 {:.1} {:.1}) yaw {yaw}: the spectator's path to it is blocked",
                v[0], v[1], v[2], v[3], eye[0], eye[1], eye[2]
            ));
        }
    }
    Ok(*last)
}

/// Capture scene `def` into `out`.
pub fn capture(
    def: &SceneDef,
    frames: u32,
    out: &Path,
    work: &WorkDir,
    progress: &Progress,
) -> Result<EngineRun, String> {
    let (origin, yaw) = spawn(def)?;
    let eye = [origin[0], origin[1], origin[2] + EYE_HEIGHT];
    let home: PathBuf = work.0.join("home");
    let cfg_dir = home.join("baseoa");
    std::fs::create_dir_all(&cfg_dir).map_err(|e| format!("{}: {e}", cfg_dir.display()))?;
    let cfg = script(origin, yaw, frames);
    std::fs::write(cfg_dir.join("wasp-capture.cfg"), &cfg).map_err(|e| e.to_string())?;
    let mut cmd = Command::new("xvfb-run");
    cmd.args(["-a", "-s"])
        .arg(format!("-screen 0 {}x{}x24", def.width, def.height))
        .args(["apitrace", "trace", "--api", "gl", "-o"])
        .arg(out)
        .arg(ENGINE)
        .args(engine_args(def, &home));
    let command = tools::command_line(&cmd);
    progress.say(&format!(
        "OpenArena {} at spawn ({} {} {}) yaw {yaw}, {}x{}",
        def.map, origin[0], origin[1], origin[2], def.width, def.height
    ));
    let log = work.0.join("engine.log");
    let mut g = Group::spawn(&mut cmd, &log)?;
    let mut said = 0;
    let marks = [
        ("CL_InitCGame", "map loaded"),
        (
            "entered the game",
            "in the game; moving the spectator to the spawn point",
        ),
        (") : ", "at the camera; drawing the frames"),
        ("Server Shutdown", "quitting"),
    ];
    let deadline = Instant::now() + Duration::from_secs(DEADLINE_S);
    let status = g.wait_until(deadline, "the OpenArena engine", &mut || {
        let text = tools::read_log(&log);
        while said < marks.len() && text.contains(marks[said].0) {
            progress.say(marks[said].1);
            said += 1;
        }
    })?;
    let seconds = g.started.elapsed().as_secs_f64();
    drop(g);
    let text = tools::read_log(&log);
    if !status.success() {
        return Err(format!(
            "the engine ended with {status}: {}",
            tools::tail(&text, 6)
        ));
    }
    let view = check_view(&viewpos_lines(&text), eye, yaw)?;
    Ok(EngineRun {
        engine: "ioquake3 (Debian openarena), renderer opengl1".into(),
        command,
        script: Some(cfg),
        frames_at_camera: Some(frames),
        seconds,
        camera: json!({
            "placement": "spectator teleported with setviewpos 72 units in front of the spawn point facing back, glides to rest on it, turns 180 degrees",
            "spawn_origin": origin,
            "spawn_yaw_deg": yaw,
            "eye": eye,
            "engine_viewpos": view,
            "fov_x_deg": openarena::CG_FOV_X_DEG,
            "fov_y_deg": openarena::fov_y_deg(def.width, def.height),
            "frame_ms": FRAME_MS,
        }),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_spectator_glides_back_to_the_spawn_point_and_turns() {
        let s = script([280.0, 1416.0, -120.0], 180.0, 5);
        assert!(
            s.contains("setviewpos 208.000 1416.000 -121.000 360\n"),
            "{s}"
        );
        assert!(
            s.contains("set fixedtime 20\n") && s.ends_with("viewpos\nquit\n"),
            "{s}"
        );
        // 10 frames (wait 20) at 900 degrees/s, 20 ms each: 180 degrees.
        assert!(
            s.contains("set cl_yawspeed 900\n+left\nwait 20\nset cl_yawspeed 0\n-left\n"),
            "{s}"
        );
        assert!(s.contains("wait 10\nviewpos\nquit"), "{s}");
        let s = script([0.0, 0.0, 0.0], 90.0, 1);
        assert!(s.contains("setviewpos -0.000 72.000 -1.000 270\n"), "{s}");
    }

    #[test]
    fn the_glide_is_the_sum_of_the_friction_steps() {
        // v' = v (1 - 5 dt) each 20 ms step, x += v' dt, until v < 1.
        let (mut v, mut x) = (400.0f64, 0.0);
        while v >= 1.0 {
            v *= 1.0 - 5.0 * f64::from(FRAME_MS) / 1000.0;
            x += v * f64::from(FRAME_MS) / 1000.0;
        }
        assert!((x - f64::from(GLIDE)).abs() < 0.2, "{x}");
        assert!(400.0 * 0.9f64.powi(GLIDE_FRAMES as i32 - 20) < 1.0);
    }

    #[test]
    fn the_view_is_read_and_checked() {
        let log = "x\n(280 1416 -94) : -180\nUnnamedPlayer^7 entered\n(280 1416 -94) : -180\n";
        let v = viewpos_lines(log);
        assert_eq!(v, [[280, 1416, -94, -180]; 2]);
        assert_eq!(
            check_view(&v, [280.0, 1416.0, -94.0], 180.0).unwrap(),
            [280, 1416, -94, -180]
        );
        let e = check_view(&v, [208.0, 1416.0, -94.0], 180.0).unwrap_err();
        assert!(e.contains("blocked"), "{e}");
        let e = check_view(&v[..1], [280.0, 1416.0, -94.0], 180.0).unwrap_err();
        assert!(e.contains("1 of the 2"), "{e}");
    }

    #[test]
    fn the_command_line_stays_under_the_engines_32_commands() {
        let def = wasp_frontend::def::lookup("oa-dm1-spawn0-engine").unwrap();
        let a = engine_args(&def, Path::new("/tmp/h"));
        let plus = a.iter().filter(|w| w.starts_with('+')).count();
        assert!(
            plus < 32,
            "{plus}: ioquake3 drops command-line commands past 32"
        );
        assert!(a.windows(2).any(|w| w == ["+devmap", "oa_dm1"]));
        assert!(a.windows(3).any(|w| w == ["+set", "r_customwidth", "1960"]));
    }
}
