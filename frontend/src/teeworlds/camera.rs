//! The camera: the game's view size at zoom 1, and the selectors that
//! centre it (`spawn:N`, `center`).

/// The game's view size (world units) at zoom 1 for a frame aspect ratio
/// (width / height): 1 150 000 square units, at most 1500 wide, at most
/// 1050 high.
pub fn view_size(aspect: f32) -> (f32, f32) {
    let f = (1_150_000.0f32).sqrt() / aspect.sqrt();
    let (mut w, mut h) = (f * aspect, f);
    if w > 1500.0 {
        w = 1500.0;
        h = w / aspect;
    }
    if h > 1050.0 {
        h = 1050.0;
        w = h * aspect;
    }
    (w, h)
}

/// Camera selector of a scene definition.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CameraSel {
    /// Centred on the Nth spawn point.
    Spawn(usize),
    /// Centred on the game layer.
    Center,
}

impl CameraSel {
    /// Parse `spawn:N` or `center`.
    pub fn parse(s: &str) -> Option<Self> {
        if s == "center" || s == "centre" {
            return Some(Self::Center);
        }
        s.strip_prefix("spawn:")
            .and_then(|n| n.parse().ok())
            .map(Self::Spawn)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn view_matches_the_game() {
        let (w, h) = view_size(1960.0 / 768.0);
        assert!(
            (w - 1500.0).abs() < 1e-3 && (h - 587.755).abs() < 0.01,
            "{w}x{h}"
        );
        let (w, h) = view_size(4.0 / 3.0);
        assert!((w * h - 1_150_000.0).abs() < 10.0 && (w / h - 4.0 / 3.0).abs() < 1e-4);
    }
}
