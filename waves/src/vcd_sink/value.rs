//! One signal's value: its state from cycle to cycle and its VCD
//! value-change line, a vector written most significant bit first.

use std::io::{self, Write};

use vcd::IdCode;

/// The widest signal a [`VcdSink`](super::VcdSink) accepts, in bits.
pub const MAX_WIDTH: u32 = 64;

/// Longest VCD identifier code a `u64` index can produce (94 printable
/// characters per digit: 94^10 > 2^64).
const MAX_ID_LEN: usize = 10;

/// Per-signal state, indexed like [`VcdSink::signals`].
#[derive(Debug)]
pub(super) struct Slot {
    /// VCD identifier code, ASCII.
    pub(super) id: [u8; MAX_ID_LEN],
    pub(super) id_len: u8,
    pub(super) width: u32,
    pub(super) mask: u64,
    /// Value seen this cycle.
    pub(super) value: u64,
    /// Value last written to the file.
    pub(super) written: u64,
}

impl Slot {
    #[inline]
    pub(super) fn new(index: usize, width: u32, value: u64) -> Slot {
        let code = IdCode::from(index as u64).to_string();
        debug_assert!(code.len() <= MAX_ID_LEN);
        let mut id = [0u8; MAX_ID_LEN];
        id[..code.len()].copy_from_slice(code.as_bytes());
        let mask = width_mask(width);
        Slot {
            id,
            id_len: code.len() as u8,
            width,
            mask,
            value: value & mask,
            written: value & mask,
        }
    }

    #[inline]
    fn id(&self) -> &[u8] {
        &self.id[..self.id_len as usize]
    }

    /// Writes the current value as one VCD value-change line.
    #[inline]
    pub(super) fn write_value<W: Write>(&self, out: &mut W) -> io::Result<()> {
        // 'b' + 64 bits + ' ' + id + '\n'
        let mut buf = [0u8; 1 + MAX_WIDTH as usize + 1 + MAX_ID_LEN + 1];
        let mut n;
        if self.width == 1 {
            buf[0] = b'0' + (self.value & 1) as u8;
            n = 1;
        } else {
            buf[0] = b'b';
            n = 1;
            for bit in (0..self.width).rev() {
                buf[n] = b'0' + ((self.value >> bit) & 1) as u8;
                n += 1;
            }
            buf[n] = b' ';
            n += 1;
        }
        let id = self.id();
        buf[n..n + id.len()].copy_from_slice(id);
        n += id.len();
        buf[n] = b'\n';
        n += 1;
        out.write_all(&buf[..n])
    }
}

#[inline]
fn width_mask(width: u32) -> u64 {
    if width >= 64 {
        u64::MAX
    } else {
        (1u64 << width) - 1
    }
}

#[cfg(test)]
mod tests {
    use crate::vcd_sink::testkit::*;
    use crate::vcd_sink::VcdSink;

    #[test]
    fn values_wider_than_width_are_masked() {
        let mut sink = VcdSink::new(Vec::new(), "top");
        let design = Toy {
            free_mshrs: 0xFF, // 8 bits into a 5-bit signal
            warp: 0b1010,     // 4 bits into 3
            ..START
        };
        sink.trace_cycle(0, &design).unwrap();
        // Same low bits, different high bits: no change.
        let same = Toy {
            free_mshrs: 0x3F,
            warp: 0b0010,
            ..START
        };
        sink.trace_cycle(1, &same).unwrap();
        let text = String::from_utf8(sink.finish(2).unwrap()).unwrap();
        assert!(text.contains("b11111 !\n"), "{text}");
        assert!(text.contains("b010 #\n"), "{text}");
        assert!(!text.contains("#1\n"), "{text}");
    }
}
