//! The writer of `wasp-trace 4` text (every one-frame trace, whatever
//! version it was read from: version 4 accepts every version-1, -2 and -3
//! trace) and of `wasp-trace 5` text (a trace of two or more frames).

use super::{Instr, Trace, FORMAT_VERSION, FORMAT_VERSION_FRAMES, FRAME_MARKER, MAGIC};
use std::fmt::Write as _;
use std::io::{self, Write};

impl Trace {
    /// Writes the trace as `wasp-trace 4` text: line 1, the header notes as
    /// `#` lines, the header, then each tile record. A trace of two or more
    /// frames is written as `wasp-trace 5`, with a `next-frame` line before
    /// each frame after the first. Hex is lowercase without leading zeros.
    /// `Trace::parse` of the output gives back `self`.
    pub fn write(&self, mut out: impl Write) -> io::Result<()> {
        let h = &self.header;
        let mut buf = String::new();
        let version = if self.frame_count() > 1 {
            FORMAT_VERSION_FRAMES
        } else {
            FORMAT_VERSION
        };
        // Writing into a String cannot fail.
        let _ = writeln!(buf, "{MAGIC} {version}");
        for note in &h.notes {
            let _ = writeln!(buf, "#{note}");
        }
        let _ = writeln!(buf, "workload {}", h.workload);
        if let Some(f) = &h.texture_format {
            let _ = writeln!(buf, "texture-format {f}");
        }
        if let Some(map) = &h.texture_map {
            buf.push_str("texture-lines decoded\n");
            for level in map.levels() {
                let _ = writeln!(buf, "texture-level {}", level.to_fields());
            }
        }
        let _ = writeln!(buf, "frame {} {} tile {}", h.frame_w, h.frame_h, h.tile);
        out.write_all(buf.as_bytes())?;
        // The frames after the first, by their first tile.
        let mut starts = self.frame_starts[1..].iter().peekable();
        for (i, tile) in self.tiles.iter().enumerate() {
            buf.clear();
            while starts.next_if(|&&s| s == i).is_some() {
                let _ = writeln!(buf, "{FRAME_MARKER}");
            }
            let _ = writeln!(buf, "tile {} {}", tile.tx(), tile.ty());
            for q in tile.quads() {
                let z = tile.rejected_before(q.index());
                if z > 0 {
                    let _ = writeln!(buf, "z {z}");
                }
                let _ = write!(buf, "q {} {}", q.x(), q.y());
                for instr in q.instrs() {
                    match instr {
                        Instr::Alu(n) => {
                            let _ = write!(buf, " a{n}");
                        }
                        Instr::Tex(blocks) | Instr::TriTex(blocks) => {
                            buf.push_str(if instr.is_trilinear() { " T" } else { " t" });
                            for (i, b) in blocks.iter().enumerate() {
                                if i > 0 {
                                    buf.push(',');
                                }
                                let _ = write!(buf, "{b:x}");
                            }
                        }
                    }
                }
                buf.push('\n');
            }
            if tile.rejected_after_last() > 0 {
                let _ = writeln!(buf, "z {}", tile.rejected_after_last());
            }
            buf.push_str("end\n");
            out.write_all(buf.as_bytes())?;
        }
        // Empty frames at the end.
        for _ in starts {
            out.write_all(format!("{FRAME_MARKER}\n").as_bytes())?;
        }
        out.flush()
    }

    /// The trace as `wasp-trace 4` text (`wasp-trace 5` for two or more
    /// frames).
    pub fn to_text(&self) -> String {
        let mut out = Vec::new();
        self.write(&mut out).expect("writing to a Vec cannot fail");
        String::from_utf8(out).expect("the writer emits UTF-8")
    }
}
