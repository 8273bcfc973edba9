//! The trace header ([`TraceHeader`]): provenance, frame and tile size and
//! the header notes, with the rules a header and its free text obey.

use crate::limits::{MAX_FRAME_DIM, MAX_TILE_SIZE};
use crate::problem::{Problem, TextField};
use crate::TextureMap;

/// The header: provenance, frame and tile size, and the header notes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TraceHeader {
    /// Where the trace comes from; `synthetic:...` for generated ones.
    pub workload: String,
    /// Frame width in pixels.
    pub frame_w: u32,
    /// Frame height in pixels.
    pub frame_h: u32,
    /// Tile edge in pixels (even).
    pub tile: u32,
    /// How the textures whose blocks the trace lists were stored (the
    /// `texture-format NAME` line): a lowercase name such as `etc2` or
    /// `astc-8x8`; `None` when the trace does not say, which for a trace
    /// of the front end means RGBA8 (every trace before the line existed).
    pub texture_format: Option<String>,
    /// The map of a trace whose texture instructions list decoded lines
    /// (the `texture-lines decoded` line and its `texture-level` lines):
    /// the RGBA8 lines of the texels, each mapped to the compressed line
    /// of the stored texture holding them ([`TextureMap`]). `None` for a
    /// trace that lists the stored lines, as every trace without the line.
    pub texture_map: Option<TextureMap>,
    /// Header comment lines, the text after `#` verbatim.
    pub notes: Vec<String>,
}

impl TraceHeader {
    /// A header without notes (validated when a [`TraceBuilder`](crate::TraceBuilder) takes it).
    pub fn new(workload: impl Into<String>, frame_w: u32, frame_h: u32, tile: u32) -> TraceHeader {
        TraceHeader {
            workload: workload.into(),
            frame_w,
            frame_h,
            tile,
            texture_format: None,
            texture_map: None,
            notes: Vec::new(),
        }
    }

    /// Checks the header against the format's rules.
    pub fn validate(&self) -> Result<(), Problem> {
        check_text(&self.workload, TextField::Workload)?;
        if self.workload.is_empty() {
            return Err(Problem::EmptyWorkload);
        }
        if self.workload.trim_matches(BLANKS) != self.workload {
            return Err(Problem::BadText {
                field: TextField::Workload,
                why: "starts or ends with a blank",
            });
        }
        for note in &self.notes {
            check_text(note, TextField::Note)?;
        }
        if let Some(f) = &self.texture_format {
            check_format_name(f)?;
        }
        for (dim, v) in [("width", self.frame_w), ("height", self.frame_h)] {
            if v == 0 || v > MAX_FRAME_DIM {
                return Err(Problem::BadFrame { dim, value: v });
            }
        }
        if self.tile < 2 || self.tile > MAX_TILE_SIZE || !self.tile.is_multiple_of(2) {
            return Err(Problem::BadTileSize(self.tile));
        }
        Ok(())
    }

    /// Tile columns in the frame, ceil(frame_w / tile).
    pub fn tiles_x(&self) -> u32 {
        self.frame_w.div_ceil(self.tile.max(1))
    }

    /// Tile rows in the frame, ceil(frame_h / tile).
    pub fn tiles_y(&self) -> u32 {
        self.frame_h.div_ceil(self.tile.max(1))
    }

    /// Quads per tile edge, tile / 2.
    pub fn quads_per_side(&self) -> u32 {
        self.tile / 2
    }

    /// Quads whose top-left pixel lies in the frame: the most a frame can
    /// shade, ceil(w/2) x ceil(h/2).
    pub fn frame_quads(&self) -> u64 {
        u64::from(self.frame_w.div_ceil(2)) * u64::from(self.frame_h.div_ceil(2))
    }

    /// Whether quad (x, y) of tile (tx, ty) has its top-left pixel in the frame.
    pub fn quad_in_frame(&self, tx: u32, ty: u32, x: u32, y: u32) -> bool {
        let px = u64::from(tx) * u64::from(self.tile) + 2 * u64::from(x);
        let py = u64::from(ty) * u64::from(self.tile) + 2 * u64::from(y);
        px < u64::from(self.frame_w) && py < u64::from(self.frame_h)
    }
}

const BLANKS: &[char] = &[' ', '\t'];

/// Checks a texture format name: 1 to 32 lowercase ASCII letters, digits
/// and `-`.
pub(crate) fn check_format_name(s: &str) -> Result<(), Problem> {
    let ok = !s.is_empty()
        && s.len() <= 32
        && s.bytes()
            .all(|b| b.is_ascii_lowercase() || b.is_ascii_digit() || b == b'-');
    if ok {
        Ok(())
    } else {
        Err(Problem::BadTextureFormat(s.to_string()))
    }
}

/// Checks that a workload name or note holds no character a line cannot.
pub(crate) fn check_text(s: &str, field: TextField) -> Result<(), Problem> {
    if s.chars().any(|c| c.is_control() && c != '\t') {
        return Err(Problem::BadText {
            field,
            why: "contains a control character",
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Trace;

    #[test]
    fn builder_rejects_bad_headers() {
        let bad = |h: TraceHeader| Trace::builder(h).unwrap_err();
        assert_eq!(bad(TraceHeader::new("", 1, 1, 2)), Problem::EmptyWorkload);
        assert!(matches!(
            bad(TraceHeader::new(" w", 1, 1, 2)),
            Problem::BadText { .. }
        ));
        assert!(matches!(
            bad(TraceHeader::new("a\nb", 1, 1, 2)),
            Problem::BadText { .. }
        ));
        assert!(matches!(
            bad(TraceHeader::new("w", 1, 0, 2)),
            Problem::BadFrame { .. }
        ));
        assert_eq!(
            bad(TraceHeader::new("w", 1, 1, 514)),
            Problem::BadTileSize(514)
        );
        let mut f = TraceHeader::new("w", 1, 1, 2);
        f.texture_format = Some("ETC 2".into());
        assert_eq!(bad(f), Problem::BadTextureFormat("ETC 2".into()));
        let mut h = TraceHeader::new("w", 1, 1, 2);
        h.notes.push("x\ry".into());
        assert!(matches!(
            bad(h),
            Problem::BadText {
                field: TextField::Note,
                ..
            }
        ));
    }
}
