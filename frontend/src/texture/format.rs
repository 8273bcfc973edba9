//! Texture formats as a mobile GPU stores them: RGBA8 and the compressed
//! block formats ETC2 and ASTC, how their blocks pack into 64-byte lines,
//! and the rule that picks a texture's format for a whole scene.
//!
//! # Formats and lines
//!
//! A memory block (cache line, the trace's block number = byte address /
//! 64) holds a rectangle of texels, its *line region*:
//!
//! | format | block | bytes/block | blocks per line | line region |
//! | --- | --- | --- | --- | --- |
//! | `rgba8` | 1 texel | 4 | 16 (4x4 texels, row-major) | 4x4 texels |
//! | `etc2-rgb` | 4x4 texels | 8 | 8 (4x2 blocks, Morton order) | 16x8 texels |
//! | `etc2-rgba` | 4x4 texels | 16 | 4 (2x2 blocks, Morton order) | 8x8 texels |
//! | `astc-4x4` | 4x4 texels | 16 | 4 (2x2 blocks, Morton order) | 8x8 texels |
//! | `astc-6x6` | 6x6 texels | 16 | 4 (2x2 blocks, Morton order) | 12x12 texels |
//! | `astc-8x8` | 8x8 texels | 16 | 4 (2x2 blocks, Morton order) | 16x16 texels |
//!
//! Inside a line the blocks are in Morton order (x in the even bits, y in
//! the odd bits): a texel (x, y) of a level lies in block (x / bw, y / bh)
//! (`bw` x `bh` the format's block), that block at index
//! `morton(bx % lbx, by % lby)` of line `(bx / lbx, by / lby)` (`lbx` x
//! `lby` blocks per line), so at byte `line * 64 + index * bytes_per_block`
//! ([`TextureFormat::byte_in_line`]). The lines of a level are laid out as
//! RGBA8's 4x4-texel blocks always were (see the module documentation of
//! [`crate::texture`]): a power-of-two grid of lines in Morton squares.
//!
//! A level whose size is not a multiple of the block is padded to whole
//! blocks (as the APIs require: an ETC2 level of w x h texels is
//! `ceil(w/4) * ceil(h/4)` blocks), and its block grid to whole lines; each
//! level starts on a line (64-byte) boundary, so a small level (4x4 texels
//! down to 1x1) takes a whole line, as every other level does (wasp: no
//! packing of the mip tail into one line, which a driver may do; its levels
//! are read rarely). The picture is made of the uncompressed texels: wasp
//! models where a compressed texture's texels lie, not its compression
//! error.
//!
//! # The rule for a whole scene
//!
//! A scene gets a [`FormatChoice`]: one format for every texture, or the
//! `etc2` rule a mobile port applies per texture (`docs/textures.md`,
//! with its sources): ETC2 RGB for a texture whose alpha the scene does not
//! need, ETC2 RGBA (ETC2 + EAC alpha) for one whose alpha it does. A
//! texture *needs its alpha* when it is the alpha source of an
//! alpha-tested or alpha-blended material (its first texture instruction)
//! and some texel of it has an alpha below 255. Forcing `etc2-rgb` on such
//! a texture is an error naming the texture and the formats it can take.

use super::super::{Blend, Scene, SceneError, ShaderOp};
use crate::draw_state::BlendFactor;
use std::fmt;
use std::str::FromStr;

/// How one texture is stored.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum TextureFormat {
    /// Uncompressed, 4 bytes a texel (the layout of every trace before
    /// compressed formats existed).
    #[default]
    Rgba8,
    /// ETC2 RGB8: 8 bytes per 4x4 block, no alpha.
    Etc2Rgb,
    /// ETC2 RGBA8 (ETC2 colour + EAC alpha): 16 bytes per 4x4 block.
    Etc2Rgba,
    /// ASTC 4x4: 16 bytes per 4x4 block (8 bits a texel).
    Astc4x4,
    /// ASTC 6x6: 16 bytes per 6x6 block (3.56 bits a texel).
    Astc6x6,
    /// ASTC 8x8: 16 bytes per 8x8 block (2 bits a texel).
    Astc8x8,
}

impl TextureFormat {
    /// Every format.
    pub const ALL: [TextureFormat; 6] = [
        TextureFormat::Rgba8,
        TextureFormat::Etc2Rgb,
        TextureFormat::Etc2Rgba,
        TextureFormat::Astc4x4,
        TextureFormat::Astc6x6,
        TextureFormat::Astc8x8,
    ];

    /// The name on the command line and in scene files.
    pub fn name(self) -> &'static str {
        match self {
            TextureFormat::Rgba8 => "rgba8",
            TextureFormat::Etc2Rgb => "etc2-rgb",
            TextureFormat::Etc2Rgba => "etc2-rgba",
            TextureFormat::Astc4x4 => "astc-4x4",
            TextureFormat::Astc6x6 => "astc-6x6",
            TextureFormat::Astc8x8 => "astc-8x8",
        }
    }

    /// Texels along the x and y edges of one block (RGBA8: one texel).
    pub fn block_texels(self) -> (u32, u32) {
        match self {
            TextureFormat::Rgba8 => (1, 1),
            TextureFormat::Etc2Rgb | TextureFormat::Etc2Rgba | TextureFormat::Astc4x4 => (4, 4),
            TextureFormat::Astc6x6 => (6, 6),
            TextureFormat::Astc8x8 => (8, 8),
        }
    }

    /// Bytes of one block.
    pub fn block_bytes(self) -> u32 {
        match self {
            TextureFormat::Rgba8 => 4,
            TextureFormat::Etc2Rgb => 8,
            _ => 16,
        }
    }

    /// Blocks along x and y of one 64-byte line.
    pub fn blocks_per_line(self) -> (u32, u32) {
        match self {
            TextureFormat::Rgba8 => (4, 4),
            TextureFormat::Etc2Rgb => (4, 2),
            _ => (2, 2),
        }
    }

    /// Texels along x and y of the rectangle one 64-byte line holds.
    pub fn line_texels(self) -> (u32, u32) {
        let (bw, bh) = self.block_texels();
        let (lx, ly) = self.blocks_per_line();
        (bw * lx, bh * ly)
    }

    /// Whether it stores alpha.
    pub fn has_alpha(self) -> bool {
        self != TextureFormat::Etc2Rgb
    }

    /// The byte offset, inside its 64-byte line, of the block holding
    /// texel (`x`, `y`) of a level (RGBA8: of the texel itself).
    pub fn byte_in_line(self, x: u32, y: u32) -> u32 {
        let (bw, bh) = self.block_texels();
        let (lx, ly) = self.blocks_per_line();
        let (bx, by) = ((x / bw) % lx, (y / bh) % ly);
        let index = match self {
            // RGBA8 texels are row-major inside their 4x4 block.
            TextureFormat::Rgba8 => by * lx + bx,
            _ => morton2(bx, by) as u32,
        };
        index * self.block_bytes()
    }
}

/// Interleaves the low 16 bits of x (even bit positions) and y (odd).
#[inline]
pub(super) fn morton2(x: u32, y: u32) -> u64 {
    fn spread(v: u32) -> u64 {
        let mut v = u64::from(v & 0xffff);
        v = (v | (v << 8)) & 0x00ff_00ff;
        v = (v | (v << 4)) & 0x0f0f_0f0f;
        v = (v | (v << 2)) & 0x3333_3333;
        v = (v | (v << 1)) & 0x5555_5555;
        v
    }
    spread(x) | (spread(y) << 1)
}

impl fmt::Display for TextureFormat {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The format of every texture of a scene: one format for all, or the
/// `etc2` rule (ETC2 RGB, or ETC2 RGBA where the texture's alpha is
/// needed). The default is the `etc2` rule: a scene whose definition names
/// no format stores its textures as a mobile port ships them
/// (docs/textures.md). The rasterizer's own default
/// ([`RasterOptions`](crate::raster::RasterOptions)) stays RGBA8.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum FormatChoice {
    /// Every texture in this format.
    Rgba8,
    /// The `etc2` rule, per texture (the default).
    #[default]
    Etc2,
    /// Every texture in one format (not RGBA8, which is [`FormatChoice::Rgba8`]).
    All(TextureFormat),
}

impl FormatChoice {
    /// Every choice, in the order the help lists them.
    pub fn all() -> Vec<FormatChoice> {
        let mut v = vec![FormatChoice::Rgba8, FormatChoice::Etc2];
        v.extend(
            TextureFormat::ALL[1..]
                .iter()
                .map(|&f| FormatChoice::All(f)),
        );
        v
    }

    /// The name on the command line, in scene files and in traces.
    pub fn name(self) -> &'static str {
        match self {
            FormatChoice::Rgba8 => "rgba8",
            FormatChoice::Etc2 => "etc2",
            FormatChoice::All(f) => f.name(),
        }
    }

    /// The allowed names, for errors.
    pub fn names() -> String {
        let n: Vec<&str> = FormatChoice::all().iter().map(|c| c.name()).collect();
        n.join(", ")
    }

    /// The format a texture gets, given whether the scene needs its alpha;
    /// `None` when the choice is a format without alpha and the alpha is
    /// needed.
    pub fn format_for(self, needs_alpha: bool) -> Option<TextureFormat> {
        match self {
            FormatChoice::Rgba8 => Some(TextureFormat::Rgba8),
            FormatChoice::Etc2 if needs_alpha => Some(TextureFormat::Etc2Rgba),
            FormatChoice::Etc2 => Some(TextureFormat::Etc2Rgb),
            FormatChoice::All(f) if needs_alpha && !f.has_alpha() => None,
            FormatChoice::All(f) => Some(f),
        }
    }

    /// The format of every texture of `scene` (in scene order), or an
    /// error naming the scene, the first texture that cannot take this
    /// choice and the choices it can take.
    pub fn formats(self, scene: &Scene) -> Result<Vec<TextureFormat>, SceneError> {
        let needs = alpha_needed(scene);
        let mut out = Vec::with_capacity(needs.len());
        for (t, &need) in scene.textures.iter().zip(&needs) {
            match self.format_for(need) {
                Some(f) => out.push(f),
                None => {
                    let ok: Vec<&str> = FormatChoice::all()
                        .into_iter()
                        .filter(|c| c.format_for(need).is_some())
                        .map(|c| c.name())
                        .collect();
                    return Err(SceneError::in_file(
                        &scene.name,
                        format!(
                            "texture `{}` cannot be stored as {}: its alpha is used (an \
                             alpha-tested or alpha-blended material reads it and some texel \
                             is not opaque), and {} has no alpha (allowed texture formats \
                             for it: {})",
                            t.name,
                            self.name(),
                            self.name(),
                            ok.join(", ")
                        ),
                    ));
                }
            }
        }
        Ok(out)
    }
}

/// Per texture of `scene`: whether the scene needs its alpha (it is the
/// first texture of an alpha-tested or alpha-blended material, which reads
/// its alpha, and some texel's alpha is below 255). Every material counts,
/// seen or not: a port ships one format per texture, whatever the camera.
pub fn alpha_needed(scene: &Scene) -> Vec<bool> {
    let mut read = vec![false; scene.textures.len()];
    for m in &scene.materials {
        if !reads_alpha(m) {
            continue;
        }
        let first = m.shader.iter().find_map(|op| match op {
            ShaderOp::Tex(s) => Some(s.texture),
            ShaderOp::Alu(_) => None,
        });
        if let Some(slot) = first.and_then(|t| read.get_mut(t)) {
            *slot = true;
        }
    }
    scene
        .textures
        .iter()
        .zip(read)
        .map(|(t, r)| r && t.rgba.chunks_exact(4).any(|p| p[3] < 255))
        .collect()
}

/// Whether material `m` reads its first texture's alpha: a loader's
/// alpha-tested or alpha-blended material; a material with a draw state (the
/// GL importer's) when the alpha test is on or a blend factor is the source
/// alpha (additive `GL_ONE, GL_ONE` blending never reads it).
fn reads_alpha(m: &crate::Material) -> bool {
    let Some(s) = &m.state else {
        return m.blend != Blend::Opaque;
    };
    let src_alpha =
        |f: &BlendFactor| matches!(f, BlendFactor::SrcAlpha | BlendFactor::OneMinusSrcAlpha);
    s.alpha_test.is_some() || s.blend.is_some_and(|(a, b)| src_alpha(&a) || src_alpha(&b))
}

impl fmt::Display for FormatChoice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for FormatChoice {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        FormatChoice::all()
            .into_iter()
            .find(|c| c.name() == s.trim())
            .ok_or_else(|| {
                format!(
                    "unknown texture format `{s}` (expected one of {})",
                    FormatChoice::names()
                )
            })
    }
}

impl serde::Serialize for FormatChoice {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.name())
    }
}

impl<'de> serde::Deserialize<'de> for FormatChoice {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let s = String::deserialize(d)?;
        s.parse().map_err(serde::de::Error::custom)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_hold_the_stated_regions_and_blocks_fill_them() {
        let want = [
            (TextureFormat::Rgba8, (4, 4)),
            (TextureFormat::Etc2Rgb, (16, 8)),
            (TextureFormat::Etc2Rgba, (8, 8)),
            (TextureFormat::Astc4x4, (8, 8)),
            (TextureFormat::Astc6x6, (12, 12)),
            (TextureFormat::Astc8x8, (16, 16)),
        ];
        for (f, region) in want {
            assert_eq!(f.line_texels(), region, "{f}");
            let (lx, ly) = f.blocks_per_line();
            assert_eq!(lx * ly * f.block_bytes(), 64, "{f}: a line is full");
            // Every block of a line has its own offset, inside the line.
            let (bw, bh) = f.block_texels();
            let mut offs: Vec<u32> = (0..ly)
                .flat_map(|by| (0..lx).map(move |bx| f.byte_in_line(bx * bw, by * bh)))
                .collect();
            offs.sort_unstable();
            let expect: Vec<u32> = (0..lx * ly).map(|i| i * f.block_bytes()).collect();
            assert_eq!(offs, expect, "{f}");
        }
        // ETC2 RGB: Morton order of 4x2 blocks, x in the even bits.
        let e = TextureFormat::Etc2Rgb;
        assert_eq!(e.byte_in_line(4, 0), 8);
        assert_eq!(e.byte_in_line(0, 4), 16);
        assert_eq!(e.byte_in_line(8, 0), 32);
        assert_eq!(e.byte_in_line(15, 7), 56);
        // RGBA8: row-major texels.
        assert_eq!(TextureFormat::Rgba8.byte_in_line(1, 2), 36);
    }

    #[test]
    fn choices_parse_and_the_rule_keeps_needed_alpha() {
        for c in FormatChoice::all() {
            assert_eq!(c.name().parse::<FormatChoice>().unwrap(), c);
        }
        let e = "etc3".parse::<FormatChoice>().unwrap_err();
        assert!(
            e.contains("`etc3`") && e.contains("rgba8, etc2, etc2-rgb"),
            "{e}"
        );
        assert_eq!(
            FormatChoice::Etc2.format_for(false),
            Some(TextureFormat::Etc2Rgb)
        );
        assert_eq!(
            FormatChoice::Etc2.format_for(true),
            Some(TextureFormat::Etc2Rgba)
        );
        let rgb = FormatChoice::All(TextureFormat::Etc2Rgb);
        assert_eq!(rgb.format_for(true), None);
        assert_eq!(rgb.format_for(false), Some(TextureFormat::Etc2Rgb));
        let astc = FormatChoice::All(TextureFormat::Astc8x8);
        assert_eq!(astc.format_for(true), Some(TextureFormat::Astc8x8));
    }

    #[test]
    fn a_draw_state_reads_alpha_through_the_alpha_test_or_a_source_alpha_factor() {
        use crate::draw_state::{Compare, DrawState};
        use crate::{Camera, Material, TexSample, Texture};
        let tex = |name: &str| Texture {
            name: name.into(),
            width: 4,
            height: 4,
            rgba: [[9, 9, 9, 100]; 16].concat(),
            repeat: true,
        };
        let mat = |t: usize, state: DrawState| Material {
            name: format!("m{t}"),
            blend: Blend::AlphaBlend,
            shader: vec![ShaderOp::Tex(TexSample {
                texture: t,
                uv_set: 0,
                filter: crate::Filter::Bilinear,
                mipmapped: true,
                second: None,
            })],
            state: Some(state),
        };
        let opaque = DrawState::for_blend(Blend::Opaque);
        let additive = DrawState {
            blend: Some((BlendFactor::One, BlendFactor::One)),
            ..opaque
        };
        let over = DrawState {
            blend: Some((BlendFactor::SrcAlpha, BlendFactor::OneMinusSrcAlpha)),
            ..opaque
        };
        let tested = DrawState {
            alpha_test: Some((Compare::Greater, 0.0)),
            ..opaque
        };
        let scene = Scene {
            name: "s".into(),
            source: String::new(),
            meshes: vec![],
            materials: vec![
                mat(0, additive),
                mat(1, over),
                mat(2, tested),
                mat(3, opaque),
            ],
            textures: vec![tex("a"), tex("b"), tex("c"), tex("d")],
            camera: Camera::Clip,
        };
        assert_eq!(alpha_needed(&scene), [false, true, true, false]);
        let f = FormatChoice::Etc2.formats(&scene).unwrap();
        assert_eq!(f[0], TextureFormat::Etc2Rgb);
        assert_eq!(f[1], TextureFormat::Etc2Rgba);
    }
}
