//! Instruction entries: [`Instr`], the entry of a quad's program as a
//! reader sees it, [`OpKind`], the same without its block list for the
//! shader core's hot path, and `Op`, the 12-byte form a tile stores.

/// One instruction entry of a quad's program.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Instr<'a> {
    /// A run of this many ALU instructions (at least 1).
    Alu(u32),
    /// One texture instruction whose sample is bilinear (or nearest), and
    /// the distinct 64-byte block numbers it touches (at least 1), in
    /// request order: `t` in the text.
    Tex(&'a [u64]),
    /// One texture instruction whose sample is trilinear (it filters two
    /// mip levels), and its blocks as for [`Instr::Tex`]: `T` in the text
    /// (format 4).
    TriTex(&'a [u64]),
}

impl<'a> Instr<'a> {
    /// The blocks of a texture instruction (`None` for an ALU run).
    pub fn blocks(&self) -> Option<&'a [u64]> {
        match *self {
            Instr::Alu(_) => None,
            Instr::Tex(b) | Instr::TriTex(b) => Some(b),
        }
    }

    /// Whether this is a trilinear texture instruction.
    pub fn is_trilinear(&self) -> bool {
        matches!(self, Instr::TriTex(_))
    }
}

/// One entry of a tile's instruction pool: 12 bytes whichever the kind
/// (the trilinear flag lies in the padding beside the tag).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Op {
    Alu(u32),
    /// Blocks `start..start + len` of the tile's block pool; `tri`: the
    /// sample is trilinear.
    Tex {
        start: u32,
        len: u32,
        tri: bool,
    },
}

/// An instruction entry as the shader core's hot path reads it: the
/// entry's kind and length, without borrowing its block list (the core
/// walks a quad's blocks in order, so it knows where they start).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OpKind {
    /// A run of this many ALU instructions.
    Alu(u32),
    /// A texture instruction touching `len` blocks; `tri`: its sample is
    /// trilinear.
    Tex {
        /// Blocks it touches.
        len: u32,
        /// Whether it is trilinear.
        tri: bool,
    },
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_instruction_entry_stays_twelve_bytes() {
        assert_eq!(std::mem::size_of::<Op>(), 12);
    }
}
