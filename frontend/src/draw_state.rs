//! A draw's fixed-function pipeline state: the depth test, depth writes,
//! blending, the alpha test, face culling, the scissor, the depth range,
//! polygon offset and colour writes, as an engine sets them per draw call.
//!
//! A [`crate::Material`] without a state uses [`DrawState::for_blend`] of
//! its [`Blend`], which is exactly what the front end did before per-draw
//! states existed: the loaders' traces do not change. A material with a
//! state (the GL importer's) is drawn in submission order, blended or not,
//! and every field decides what its name says.

use crate::Blend;

/// A comparison of the depth and alpha tests (OpenGL's eight).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Compare {
    /// Never passes.
    Never,
    /// Passes if the incoming value is less than the reference.
    Less,
    /// Passes if equal.
    Equal,
    /// Passes if less or equal.
    LEqual,
    /// Passes if greater.
    Greater,
    /// Passes if not equal.
    NotEqual,
    /// Passes if greater or equal.
    GEqual,
    /// Always passes.
    Always,
}

impl Compare {
    /// Whether `value` passes against `reference`.
    #[inline]
    pub fn passes(self, value: f32, reference: f32) -> bool {
        match self {
            Compare::Never => false,
            Compare::Less => value < reference,
            Compare::Equal => value == reference,
            Compare::LEqual => value <= reference,
            Compare::Greater => value > reference,
            Compare::NotEqual => value != reference,
            Compare::GEqual => value >= reference,
            Compare::Always => true,
        }
    }

    /// Whether a fragment farther than every stored depth fails this depth
    /// test (so the hierarchical depth test may reject it coarsely).
    pub fn fails_when_farther(self) -> bool {
        matches!(
            self,
            Compare::Never | Compare::Less | Compare::Equal | Compare::LEqual
        )
    }
}

/// Which faces are culled.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Cull {
    /// No culling.
    None,
    /// Back faces.
    Back,
    /// Front faces.
    Front,
    /// Both (the draw rasterizes nothing).
    Both,
}

/// A blend factor of the picture's colour blending (the trace does not
/// depend on it: a blended fragment is one warp whatever its factors).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BlendFactor {
    /// 0.
    Zero,
    /// 1.
    One,
    /// The source colour.
    SrcColour,
    /// 1 - the source colour.
    OneMinusSrcColour,
    /// The destination colour.
    DstColour,
    /// 1 - the destination colour.
    OneMinusDstColour,
    /// The source alpha.
    SrcAlpha,
    /// 1 - the source alpha.
    OneMinusSrcAlpha,
    /// The destination alpha (the picture keeps alpha 1).
    DstAlpha,
    /// 1 - the destination alpha.
    OneMinusDstAlpha,
}

impl BlendFactor {
    /// The factor of one channel `k` (0..3), for source `s` and
    /// destination `d`.
    #[inline]
    pub fn of(self, s: &[f32; 4], d: &[f32; 4], k: usize) -> f32 {
        match self {
            BlendFactor::Zero => 0.0,
            BlendFactor::One => 1.0,
            BlendFactor::SrcColour => s[k],
            BlendFactor::OneMinusSrcColour => 1.0 - s[k],
            BlendFactor::DstColour => d[k],
            BlendFactor::OneMinusDstColour => 1.0 - d[k],
            BlendFactor::SrcAlpha => s[3],
            BlendFactor::OneMinusSrcAlpha => 1.0 - s[3],
            BlendFactor::DstAlpha => d[3],
            BlendFactor::OneMinusDstAlpha => 1.0 - d[3],
        }
    }
}

/// The pipeline state of a draw.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DrawState {
    /// The depth test: `None` when disabled (every fragment passes and no
    /// depth is written, as OpenGL does), else the comparison of the
    /// fragment's depth with the stored one. A quad none of whose covered
    /// pixels passes is rejected by Early-Z.
    pub depth_test: Option<Compare>,
    /// Depth writes of the pixels that pass every test.
    pub depth_write: bool,
    /// Colour blending `src * sfactor + dst * dfactor` (`None`: the
    /// fragment replaces the colour). The picture only.
    pub blend: Option<(BlendFactor, BlendFactor)>,
    /// The alpha test on the first texture instruction's alpha (1 without
    /// texture): a pixel that fails writes neither depth nor colour.
    pub alpha_test: Option<(Compare, f32)>,
    /// Face culling.
    pub cull: Cull,
    /// Front faces are counter-clockwise on screen (OpenGL's default).
    pub front_ccw: bool,
    /// Only pixels inside this rectangle are covered: x0, y0, x1, y1
    /// (exclusive) in frame pixels, y down. `None`: the whole frame.
    pub scissor: Option<[u32; 4]>,
    /// Window depth range (near, far): the depth of a pixel is
    /// `near + (far - near) * (z_ndc / 2 + 1/2)`. `None`: (0, 1).
    pub depth_range: Option<[f64; 2]>,
    /// Polygon offset (factor, units): added to the depth, `factor` times
    /// the triangle's largest depth slope in x or y plus `units` times
    /// 2^-24 (a 24-bit depth buffer's resolution, (wasp)).
    pub polygon_offset: Option<(f32, f32)>,
    /// Whether any colour channel is written (the picture only).
    pub colour_write: bool,
    /// Depth clears before the draw, counted from the frame's start: a
    /// tile's depth buffer is cleared when a triangle of a later clear
    /// comes (every loader's draws are all of clear 0).
    pub depth_epoch: u32,
}

impl DrawState {
    /// The state a [`Blend`] mode has always meant: depth test `<=`, so a
    /// later triangle at the same depth wins; opaque writes depth,
    /// alpha-tested writes it where alpha >= 0.5, alpha-blended writes
    /// none and blends `src * a + dst * (1 - a)`; no culling, scissor,
    /// offset. (Back-face culling of the loaders is
    /// [`crate::raster::RasterOptions::cull_back_faces`]; the back-to-front
    /// order of alpha-blended triangles belongs to materials without a
    /// state.)
    pub fn for_blend(blend: Blend) -> DrawState {
        DrawState {
            depth_test: Some(Compare::LEqual),
            depth_write: blend != Blend::AlphaBlend,
            blend: (blend == Blend::AlphaBlend)
                .then_some((BlendFactor::SrcAlpha, BlendFactor::OneMinusSrcAlpha)),
            alpha_test: (blend == Blend::AlphaTest).then_some((Compare::GEqual, 0.5)),
            cull: Cull::None,
            front_ccw: true,
            scissor: None,
            depth_range: None,
            polygon_offset: None,
            colour_write: true,
            depth_epoch: 0,
        }
    }

    /// Whether the draw is plain opaque: depth written, no alpha test, no
    /// blending (what the depth pre-pass takes).
    pub fn is_opaque(&self) -> bool {
        self.depth_write && self.alpha_test.is_none() && self.blend.is_none()
    }

    /// Whether a triangle with this screen winding is culled (`ccw`:
    /// counter-clockwise with y up, as OpenGL's window coordinates).
    pub fn culls(&self, ccw: bool) -> bool {
        let front = ccw == self.front_ccw;
        match self.cull {
            Cull::None => false,
            Cull::Back => !front,
            Cull::Front => front,
            Cull::Both => true,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn comparisons_and_blend_modes_mean_what_they_always_meant() {
        assert!(Compare::LEqual.passes(0.5, 0.5) && !Compare::Less.passes(0.5, 0.5));
        assert!(Compare::Equal.passes(0.25, 0.25) && !Compare::Equal.passes(0.25, 0.5));
        assert!(Compare::Greater.passes(0.6, 0.5) && !Compare::Never.passes(0.0, 1.0));
        assert!(Compare::NotEqual.passes(0.1, 0.2) && Compare::Always.passes(2.0, 1.0));
        assert!(Compare::LEqual.fails_when_farther() && !Compare::GEqual.fails_when_farther());
        let o = DrawState::for_blend(Blend::Opaque);
        assert!(o.is_opaque() && o.depth_test == Some(Compare::LEqual));
        let t = DrawState::for_blend(Blend::AlphaTest);
        assert_eq!(t.alpha_test, Some((Compare::GEqual, 0.5)));
        assert!(t.depth_write && !t.is_opaque());
        let b = DrawState::for_blend(Blend::AlphaBlend);
        assert!(!b.depth_write && b.blend.is_some() && !b.culls(false));
        let s = [0.2, 0.4, 0.6, 0.25];
        let d = [1.0, 1.0, 1.0, 1.0];
        assert_eq!(BlendFactor::OneMinusSrcAlpha.of(&s, &d, 0), 0.75);
        assert_eq!(BlendFactor::SrcColour.of(&s, &d, 1), 0.4);
        let back = DrawState {
            cull: Cull::Back,
            ..o
        };
        assert!(back.culls(false) && !back.culls(true));
        let cw_front = DrawState {
            front_ccw: false,
            cull: Cull::Front,
            ..o
        };
        assert!(cw_front.culls(false) && !cw_front.culls(true));
    }
}
