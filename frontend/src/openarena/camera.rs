//! The camera: `spawn:N` selectors and the spawn points of the map's
//! entities in the order they count them.

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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn camera_selectors() {
        assert_eq!(parse_camera("spawn:2"), Some(2));
        assert_eq!(parse_camera("start:0"), None);
        assert_eq!(parse_camera("spawn:x"), None);
    }
}
