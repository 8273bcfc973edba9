//! The Teeworlds 0.7 client (Debian `teeworlds`) connected to a local
//! `teeworlds-server` on the scene's map.
//!
//! Both run inside a network namespace of their own (`unshare --user
//! --map-root-user --net`, loopback brought up with `ip link set lo up`):
//! the only address there is 127.0.0.1, so neither the server (its master
//! server registration is off too, `sv_register 0`) nor the client (its
//! version check and server browser) can reach any other. The server binds
//! 127.0.0.1:[`PORT`]; the client, under Xvfb and apitrace at the scene's
//! resolution, connects to it, with HUD and name plates off
//! (`cl_showhud 0`, `cl_nameplates 0`) and the static camera
//! (`cl_dynamic_camera 0`, `cl_mouse_followfactor 0`: the view centred on
//! the player, not pulled towards the mouse).
//!
//! The camera: a lone player joins the game and the server spawns it at
//! the map's first spawn point (with no other player every spawn point
//! scores the same and the first wins); the client centres its view on the
//! player. So `spawn:0` is the one camera an engine scene can ask for.
//! When the server logs that the player entered the game, the client draws
//! for [`HOLD_S`] more seconds (the player lands on the ground in well
//! under one), then the whole process group is stopped (apitrace writes the
//! capture out on the signal).

use super::tools::{self, Group, Need, WorkDir};
use super::{EngineRun, Progress};
use serde_json::json;
use std::path::Path;
use std::process::Command;
use std::time::{Duration, Instant};
use wasp_frontend::def::SceneDef;

/// The client binary of Debian's `teeworlds` package.
pub const CLIENT: &str = "/usr/games/teeworlds";
/// The server binary of Debian's `teeworlds-server` package.
pub const SERVER: &str = "/usr/games/teeworlds-server";
/// What the capture runs besides Xvfb and apitrace: the client, the
/// server, and what makes their network namespace.
pub const NEEDS: [Need; 4] = [
    Need {
        program: CLIENT,
        package: "teeworlds",
    },
    Need {
        program: SERVER,
        package: "teeworlds-server",
    },
    Need {
        program: "unshare",
        package: "util-linux",
    },
    Need {
        program: "ip",
        package: "iproute2",
    },
];
/// The server's port on 127.0.0.1.
pub const PORT: u16 = 8303;
/// Seconds the client draws after the player entered the game.
const HOLD_S: u64 = 2;
/// Seconds to wait for the player to enter the game.
const JOIN_DEADLINE_S: u64 = 45;

/// The script run inside the network namespace: bring up the loopback,
/// start the server and the client, wait for both. Arguments: work
/// folder, capture path, WxH, server commands, client commands.
const SCRIPT: &str = r#"set -u
ip link set lo up || { echo "wasp: cannot bring up the loopback interface" >&2; exit 97; }
cd "$1" || exit 96
"$SERVER" "$4" > "$1/server.log" 2>&1 &
xvfb-run -a -s "-screen 0 ${3}x24" apitrace trace --api gl -o "$2" "$CLIENT" "$5" > "$1/client.log" 2>&1 &
wait
"#;

/// The server's console commands for map `map`.
pub fn server_commands(map: &str) -> String {
    format!(
        "sv_map {map}; sv_port {PORT}; bindaddr 127.0.0.1; sv_register 0; \
         sv_name wasp-capture"
    )
}

/// The client's console commands for scene `def`.
pub fn client_commands(def: &SceneDef) -> String {
    format!(
        "gfx_screen_width {}; gfx_screen_height {}; gfx_fullscreen 0; gfx_borderless 0; \
         gfx_vsync 0; snd_enable 0; cl_showhud 0; cl_nameplates 0; cl_dynamic_camera 0; \
         cl_mouse_followfactor 0; cl_show_welcome 0; cl_skip_start_menu 1; \
         connect 127.0.0.1:{PORT}",
        def.width, def.height
    )
}

/// The camera of an engine scene: `spawn:0` only (see the module
/// documentation).
pub fn check_camera(def: &SceneDef) -> Result<(), String> {
    if def.camera.trim() == "spawn:0" {
        return Ok(());
    }
    Err(format!(
        "camera `{}`: a Teeworlds engine scene can only use `spawn:0` (the server spawns \
         a lone player at the map's first spawn point and the client follows it; the \
         client has no command to place its view elsewhere)",
        def.camera
    ))
}

/// Capture scene `def` into `out`.
pub fn capture(
    def: &SceneDef,
    out: &Path,
    work: &WorkDir,
    progress: &Progress,
) -> Result<EngineRun, String> {
    check_camera(def)?;
    let home = work.0.join("home");
    std::fs::create_dir_all(&home).map_err(|e| format!("{}: {e}", home.display()))?;
    let mut cmd = unshare_command(def, out, work, &home);
    let command = tools::command_line(&cmd);
    progress.say(&format!(
        "Teeworlds {}: server on 127.0.0.1:{PORT} and client {}x{} in a network namespace \
         of their own",
        def.map, def.width, def.height
    ));
    let log = work.0.join("unshare.log");
    let client_log = work.0.join("client.log");
    let mut g = Group::spawn(&mut cmd, &log)?;
    wait_for_join(&mut g, work)?;
    progress.say(&format!(
        "the player entered the game; drawing {HOLD_S} s more"
    ));
    std::thread::sleep(Duration::from_secs(HOLD_S));
    g.stop();
    let seconds = g.started.elapsed().as_secs_f64();
    drop(g);
    if !out.is_file() {
        return Err(format!(
            "apitrace wrote no capture: {}",
            tools::tail(&tools::read_log(&client_log), 4)
        ));
    }
    Ok(engine_run(def, command, seconds))
}

/// The server and the client of scene `def`, run by [`SCRIPT`] in a
/// network namespace of their own, writing the capture to `out`.
fn unshare_command(def: &SceneDef, out: &Path, work: &WorkDir, home: &Path) -> Command {
    let mut cmd = Command::new("unshare");
    cmd.args([
        "--user",
        "--map-root-user",
        "--net",
        "sh",
        "-c",
        SCRIPT,
        "sh",
    ])
    .arg(&work.0)
    .arg(out)
    .arg(format!("{}x{}", def.width, def.height))
    .arg(server_commands(&def.map))
    .arg(client_commands(def))
    .env("HOME", home)
    .env("SERVER", SERVER)
    .env("CLIENT", CLIENT);
    cmd
}

/// Wait until the server's log says the player entered the game; an
/// error if the group ends first or [`JOIN_DEADLINE_S`] passes (then the
/// group is stopped).
fn wait_for_join(g: &mut Group, work: &WorkDir) -> Result<(), String> {
    let log = work.0.join("unshare.log");
    let server_log = work.0.join("server.log");
    let client_log = work.0.join("client.log");
    let deadline = Instant::now() + Duration::from_secs(JOIN_DEADLINE_S);
    loop {
        if tools::read_log(&server_log).contains("player has entered the game") {
            return Ok(());
        }
        if let Some(s) = g.try_wait()? {
            return Err(format!(
                "the server and client ended ({s}) before the player entered the game: {} | \
                 server: {} | client: {}",
                tools::tail(&tools::read_log(&log), 3),
                tools::tail(&tools::read_log(&server_log), 3),
                tools::tail(&tools::read_log(&client_log), 3)
            ));
        }
        if Instant::now() >= deadline {
            g.stop();
            return Err(format!(
                "the player did not enter the game within {JOIN_DEADLINE_S} s: stopped \
                 (server: {} | client: {})",
                tools::tail(&tools::read_log(&server_log), 3),
                tools::tail(&tools::read_log(&client_log), 3)
            ));
        }
        std::thread::sleep(Duration::from_millis(200));
    }
}

/// What the capture of scene `def` records of its run.
fn engine_run(def: &SceneDef, command: Vec<String>, seconds: f64) -> EngineRun {
    EngineRun {
        engine: "Teeworlds 0.7 client (Debian teeworlds) with teeworlds-server on 127.0.0.1".into(),
        command,
        script: Some(SCRIPT.to_string()),
        frames_at_camera: None,
        seconds,
        camera: json!({
            "placement": "the player spawned by the server at the map's first spawn point; \
                          the client's static camera centred on it",
            "camera": def.camera,
            "server": server_commands(&def.map),
            "client": client_commands(def),
            "seconds_after_join": HOLD_S,
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_loopback_is_named() {
        let def = wasp_frontend::def::lookup("tw-dm1-spawn0-engine").unwrap();
        let s = server_commands(&def.map);
        assert!(
            s.contains("sv_map dm1") && s.contains("bindaddr 127.0.0.1"),
            "{s}"
        );
        assert!(s.contains("sv_register 0"), "{s}");
        let c = client_commands(&def);
        assert!(c.ends_with("connect 127.0.0.1:8303"), "{c}");
        assert!(
            c.contains("gfx_screen_width 1960; gfx_screen_height 768"),
            "{c}"
        );
        assert!(SCRIPT.contains("ip link set lo up"));
    }

    #[test]
    fn only_the_first_spawn_point_is_a_camera() {
        let mut def = wasp_frontend::def::lookup("tw-dm1-spawn0-engine").unwrap();
        assert!(check_camera(&def).is_ok());
        def.camera = "center".into();
        let e = check_camera(&def).unwrap_err();
        assert!(e.contains("`center`") && e.contains("spawn:0"), "{e}");
    }
}
