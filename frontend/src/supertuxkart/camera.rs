//! The camera selectors (`start:N`, `driveline:F`) and where they put
//! the kart: explicit start positions, the start grid along the
//! driveline, or a cutscene camera.

use super::*;

/// A camera selector.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CameraSel {
    /// Behind kart start position N.
    Start(usize),
    /// At this fraction (0..1) of the driveline.
    Driveline(f32),
}

/// Parse `start:N` or `driveline:F`.
pub fn parse_camera(sel: &str) -> Option<CameraSel> {
    let (kind, arg) = sel.split_once(':')?;
    match kind.trim() {
        "start" => arg.trim().parse().ok().map(CameraSel::Start),
        "driveline" => arg
            .trim()
            .parse::<f32>()
            .ok()
            .filter(|f| (0.0..=1.0).contains(f))
            .map(CameraSel::Driveline),
        _ => None,
    }
}

/// The kart (or camera base) position and direction of travel in the
/// game's coordinates, from the selector.
pub(super) fn camera_base(
    sel: CameraSel,
    track_dir: &Path,
    scene: &Digest,
    scene_file: &Path,
) -> Result<(Vec3, Vec3, bool), SceneError> {
    let quads_file = track_dir.join("quads.xml");
    let graph_file = track_dir.join("graph.xml");
    let line = if quads_file.is_file() {
        let quads = parse_quads(&read_text(&quads_file)?, &quads_file)?;
        let succ = if graph_file.is_file() {
            parse_graph(&read_text(&graph_file)?, &graph_file, quads.len())?
        } else {
            (0..quads.len())
                .map(|i| vec![(i + 1) % quads.len()])
                .collect()
        };
        main_line(&quads, &succ)
    } else {
        Vec::new()
    };
    match sel {
        CameraSel::Driveline(f) => {
            if line.is_empty() {
                return Err(SceneError::in_file(
                    &quads_file,
                    "camera driveline:F needs a driveline (quads.xml): this track has none",
                ));
            }
            let (p, dir) = along(&line, f * line_length(&line));
            Ok((p, dir, false))
        }
        CameraSel::Start(n) => {
            if !scene.starts.is_empty() {
                let (p, h) = *scene.starts.get(n).ok_or_else(|| {
                    SceneError::in_file(
                        scene_file,
                        format!(
                            "camera start:{n}: the track has {} start positions",
                            scene.starts.len()
                        ),
                    )
                })?;
                let (s, c) = h.to_radians().sin_cos();
                return Ok((p, [s, 0.0, c], false));
            }
            if !line.is_empty() {
                if n >= 64 {
                    return Err(SceneError::in_file(
                        scene_file,
                        format!("camera start:{n}: at most 64 karts"),
                    ));
                }
                let (kpr, fwd, side, upw) = scene.default_start.unwrap_or((2, 1.5, 3.0, 0.1));
                let behind = 0.1 + fwd * (n as f32 + 1.0);
                let (p, dir) = along(&line, -behind);
                // Lateral axis: horizontal, perpendicular to travel.
                let lateral = normalize(cross([0.0, 1.0, 0.0], dir));
                let col = (n % kpr) as f32 - (kpr as f32 - 1.0) * 0.5;
                let p = add(add(p, scale(lateral, col * side)), [0.0, upw, 0.0]);
                return Ok((p, dir, false));
            }
            if let Some(&c) = scene.cutscene_cameras.get(n) {
                return Ok((c, [0.0, 0.0, 1.0], true));
            }
            Err(SceneError::in_file(
                scene_file,
                format!(
                    "camera start:{n}: no <start> elements, no driveline (quads.xml) and {} cutscene cameras",
                    scene.cutscene_cameras.len()
                ),
            ))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn camera_selectors() {
        assert_eq!(parse_camera("start:3"), Some(CameraSel::Start(3)));
        assert_eq!(
            parse_camera("driveline:0.25"),
            Some(CameraSel::Driveline(0.25))
        );
        assert_eq!(parse_camera("driveline:2"), None);
        assert_eq!(parse_camera("spawn:0"), None);
        assert_eq!(parse_camera("start"), None);
    }
}
