//! The camera: `spawn:N` selectors, the spawn points of the map's
//! entities in the order they count them, and the field of view the
//! engine gives a frame of a given size.

use super::*;

/// A camera selector: `spawn:N`.
pub fn parse_camera(sel: &str) -> Option<usize> {
    let (k, n) = sel.split_once(':')?;
    if k.trim() != "spawn" {
        return None;
    }
    n.trim().parse().ok()
}

/// Spawn points (origin, yaw in degrees) in the order `spawn:N` counts them.
pub fn spawn_points(entities: &[HashMap<String, String>]) -> Vec<(Vec3, f32)> {
    let mut out = Vec::new();
    for class in [
        "info_player_deathmatch",
        "info_player_start",
        "team_ctf_redspawn",
        "team_ctf_bluespawn",
        "team_ctf_redplayer",
        "team_ctf_blueplayer",
    ] {
        for e in entities {
            if e.get("classname")
                .is_some_and(|c| c.eq_ignore_ascii_case(class))
            {
                let Some(o) = e.get("origin") else { continue };
                let v: Vec<f32> = o
                    .split_whitespace()
                    .filter_map(|w| w.parse().ok())
                    .collect();
                if v.len() != 3 || v.iter().any(|x: &f32| !x.is_finite()) {
                    continue;
                }
                let yaw = e
                    .get("angle")
                    .and_then(|a| a.trim().parse::<f32>().ok())
                    .filter(|a| a.is_finite())
                    .unwrap_or(0.0);
                out.push(([v[0], v[1], v[2]], yaw));
            }
        }
        if !out.is_empty() && class == "info_player_start" {
            break;
        }
    }
    out
}

/// The engine's default `cg_fov` (degrees): OpenArena 0.8.8 applies it
/// across the frame's width whatever the aspect (it has no aspect
/// correction).
pub const CG_FOV_X_DEG: f64 = 90.0;

/// The engine's vertical field of view (degrees) at `w` x `h` pixels for
/// its default [`CG_FOV_X_DEG`] across: the game's view code sets the
/// projection so that `fov_x` spans the width and derives the vertical
/// angle from the aspect, 2 atan(h / w x tan(fov_x / 2)) (42.79 degrees
/// at 1960x768; [`FOV_Y_4_3_DEG`] at 4:3).
pub fn fov_y_deg(w: u32, h: u32) -> f64 {
    let half_x = (CG_FOV_X_DEG / 2.0).to_radians();
    2.0 * (f64::from(h) / f64::from(w) * half_x.tan())
        .atan()
        .to_degrees()
}

/// The camera's vertical field of view for scene `def`: the engine's at
/// the scene's size, or (`fov = "4:3"`) [`FOV_Y_4_3_DEG`].
pub fn scene_fov_y_deg(def: &SceneDef) -> f32 {
    match def.oa_fov() {
        OaFov::Engine => fov_y_deg(def.width, def.height) as f32,
        OaFov::FourThree => FOV_Y_4_3_DEG,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_field_of_view_is_the_engines_at_any_aspect() {
        // cg_fov 90 across 1960 pixels: 42.79 degrees up the 768 rows.
        assert!((fov_y_deg(1960, 768) - 42.79).abs() < 0.01);
        // At 4:3 the engine's view is the loader's old one.
        assert!((fov_y_deg(640, 480) - f64::from(FOV_Y_4_3_DEG)).abs() < 1e-4);
        // Square: 90 up as across; twice as tall: 2 atan(2) up.
        assert!((fov_y_deg(512, 512) - 90.0).abs() < 1e-9);
        assert!((fov_y_deg(100, 200) - 2.0 * 2f64.atan().to_degrees()).abs() < 1e-9);
        let mut def = crate::def::test_def(crate::def::Game::Openarena, "m", "spawn:0", 1960, 768);
        assert!((scene_fov_y_deg(&def) - 42.79).abs() < 0.01);
        def.fov = Some(OaFov::FourThree);
        assert_eq!(scene_fov_y_deg(&def), FOV_Y_4_3_DEG);
        def.fov = Some(OaFov::Engine);
        assert!((scene_fov_y_deg(&def) - 42.79).abs() < 0.01);
    }

    #[test]
    fn camera_selectors() {
        assert_eq!(parse_camera("spawn:2"), Some(2));
        assert_eq!(parse_camera("start:0"), None);
        assert_eq!(parse_camera("spawn:x"), None);
    }
}
