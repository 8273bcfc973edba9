//! The fixed-function state a frame needs besides matrices, arrays and
//! textures: viewport, depth range, scissor, the depth test, function and
//! mask, blending, the alpha test, face culling, polygon offset, the
//! colour mask, depth clears and a bound shader program; and the
//! [`DrawState`] a draw gets from it.

use super::enums as gl;
use crate::{BlendFactor, Compare, Cull, DrawState};

/// The fixed-function state.
#[derive(Clone, Debug, PartialEq)]
pub struct FixedState {
    /// glViewport (x, y, width, height), window coordinates (y up).
    pub viewport: [i64; 4],
    /// glDepthRange (near, far), clamped to 0..1.
    pub depth_range: [f64; 2],
    /// GL_SCISSOR_TEST and glScissor (x, y, width, height).
    pub scissor_test: bool,
    pub scissor: [i64; 4],
    /// GL_DEPTH_TEST, glDepthFunc, glDepthMask.
    pub depth_test: bool,
    pub depth_func: i64,
    pub depth_mask: bool,
    /// GL_BLEND and glBlendFunc (source, destination).
    pub blend: bool,
    pub blend_func: [i64; 2],
    /// GL_ALPHA_TEST and glAlphaFunc (function, reference).
    pub alpha_test: bool,
    pub alpha_func: i64,
    pub alpha_ref: f64,
    /// GL_CULL_FACE, glCullFace, glFrontFace.
    pub cull: bool,
    pub cull_face: i64,
    pub front_face: i64,
    /// GL_POLYGON_OFFSET_FILL and glPolygonOffset (factor, units).
    pub offset_fill: bool,
    pub offset: [f64; 2],
    /// glColorMask.
    pub colour_mask: [bool; 4],
    /// Depth clears since the frame's first draw.
    pub depth_epoch: u32,
    /// The program glUseProgram bound (0: fixed function).
    pub program: u64,
}

impl Default for FixedState {
    /// OpenGL's initial state (the viewport and scissor are the window's
    /// until set; apitrace records them at the context's first use).
    fn default() -> Self {
        Self {
            viewport: [0; 4],
            depth_range: [0.0, 1.0],
            scissor_test: false,
            scissor: [0; 4],
            depth_test: false,
            depth_func: gl::NEVER + 1,
            depth_mask: true,
            blend: false,
            blend_func: [gl::ONE, gl::ZERO],
            alpha_test: false,
            alpha_func: gl::ALWAYS,
            alpha_ref: 0.0,
            cull: false,
            cull_face: gl::BACK,
            front_face: gl::CCW,
            offset_fill: false,
            offset: [0.0; 2],
            colour_mask: [true; 4],
            depth_epoch: 0,
            program: 0,
        }
    }
}

/// A comparison function's enum as a [`Compare`].
pub fn compare(f: i64) -> Result<Compare, String> {
    Ok(match f - gl::NEVER {
        0 => Compare::Never,
        1 => Compare::Less,
        2 => Compare::Equal,
        3 => Compare::LEqual,
        4 => Compare::Greater,
        5 => Compare::NotEqual,
        6 => Compare::GEqual,
        7 => Compare::Always,
        _ => {
            return Err(format!(
                "comparison {}: expected GL_NEVER to GL_ALWAYS",
                gl::name(f)
            ))
        }
    })
}

/// A blend factor's enum.
pub fn blend_factor(f: i64) -> Result<BlendFactor, String> {
    Ok(match f {
        gl::ZERO => BlendFactor::Zero,
        gl::ONE => BlendFactor::One,
        gl::SRC_COLOR => BlendFactor::SrcColour,
        gl::ONE_MINUS_SRC_COLOR => BlendFactor::OneMinusSrcColour,
        gl::DST_COLOR => BlendFactor::DstColour,
        gl::ONE_MINUS_DST_COLOR => BlendFactor::OneMinusDstColour,
        gl::SRC_ALPHA => BlendFactor::SrcAlpha,
        gl::ONE_MINUS_SRC_ALPHA => BlendFactor::OneMinusSrcAlpha,
        gl::DST_ALPHA => BlendFactor::DstAlpha,
        gl::ONE_MINUS_DST_ALPHA => BlendFactor::OneMinusDstAlpha,
        _ => return Err(format!("blend factor {}: not modelled", gl::name(f))),
    })
}

/// A window-coordinate box (x, y, width, height; y up) as frame pixels
/// (x0, y0, x1, y1; y down) clipped to a `w` x `h` frame.
pub fn frame_rect(b: [i64; 4], w: u32, h: u32) -> [u32; 4] {
    let (w, h) = (i64::from(w), i64::from(h));
    let c = |v: i64, hi: i64| v.clamp(0, hi) as u32;
    [
        c(b[0], w),
        c(h - (b[1] + b[3]), h),
        c(b[0] + b[2], w),
        c(h - b[1], h),
    ]
}

impl FixedState {
    /// Turn a capability on or off; `false` if the capability is not one
    /// of this state's.
    pub fn enable(&mut self, cap: i64, on: bool) -> bool {
        match cap {
            gl::DEPTH_TEST => self.depth_test = on,
            gl::BLEND => self.blend = on,
            gl::ALPHA_TEST => self.alpha_test = on,
            gl::CULL_FACE => self.cull = on,
            gl::SCISSOR_TEST => self.scissor_test = on,
            gl::POLYGON_OFFSET_FILL => self.offset_fill = on,
            _ => return false,
        }
        true
    }

    /// The pipeline state of a draw in a `w` x `h` frame: its scissor is
    /// the viewport (clipping maps the view volume onto it) intersected
    /// with the scissor box when the scissor test is on.
    pub fn draw_state(&self, w: u32, h: u32) -> Result<DrawState, String> {
        let mut sc = frame_rect(self.viewport, w, h);
        if self.scissor_test {
            let s = frame_rect(self.scissor, w, h);
            sc = [
                sc[0].max(s[0]),
                sc[1].max(s[1]),
                sc[2].min(s[2]),
                sc[3].min(s[3]),
            ];
        }
        let blend = if self.blend {
            Some((
                blend_factor(self.blend_func[0])?,
                blend_factor(self.blend_func[1])?,
            ))
        } else {
            None
        };
        let cull = match (self.cull, self.cull_face) {
            (false, _) => Cull::None,
            (true, gl::FRONT) => Cull::Front,
            (true, gl::FRONT_AND_BACK) => Cull::Both,
            (true, _) => Cull::Back,
        };
        Ok(DrawState {
            depth_test: if self.depth_test {
                Some(compare(self.depth_func)?)
            } else {
                None
            },
            // GL writes no depth while the depth test is off.
            depth_write: self.depth_test && self.depth_mask,
            blend,
            alpha_test: if self.alpha_test {
                Some((compare(self.alpha_func)?, self.alpha_ref as f32))
            } else {
                None
            },
            cull,
            front_ccw: self.front_face != gl::CW,
            scissor: Some(sc),
            depth_range: (self.depth_range != [0.0, 1.0]).then_some(self.depth_range),
            polygon_offset: self
                .offset_fill
                .then_some((self.offset[0] as f32, self.offset[1] as f32)),
            colour_write: self.colour_mask.iter().any(|&m| m),
            depth_epoch: self.depth_epoch,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn state_after_a_sequence_of_settings_is_the_draw_state() {
        let mut s = FixedState {
            viewport: [0, 0, 128, 96],
            ..Default::default()
        };
        let d = s.draw_state(128, 96).unwrap();
        assert_eq!(d.depth_test, None);
        assert!(!d.depth_write, "no depth writes with the test off");
        assert_eq!(d.scissor, Some([0, 0, 128, 96]));
        assert!(s.enable(gl::DEPTH_TEST, true) && s.enable(gl::BLEND, true));
        assert!(s.enable(gl::ALPHA_TEST, true) && s.enable(gl::CULL_FACE, true));
        assert!(s.enable(gl::SCISSOR_TEST, true) && !s.enable(0x0B50, true));
        s.depth_func = gl::NEVER + 3;
        s.depth_mask = false;
        s.blend_func = [gl::SRC_ALPHA, gl::ONE_MINUS_SRC_ALPHA];
        s.alpha_func = gl::NEVER + 4;
        s.alpha_ref = 0.5;
        s.cull_face = gl::FRONT;
        s.front_face = gl::CW;
        // Scissor box 10,20 30x40 in window coordinates (y up): frame rows
        // 96 - 60 = 36 to 76.
        s.scissor = [10, 20, 30, 40];
        let d = s.draw_state(128, 96).unwrap();
        assert_eq!(d.depth_test, Some(Compare::LEqual));
        assert!(!d.depth_write);
        assert_eq!(
            d.blend,
            Some((BlendFactor::SrcAlpha, BlendFactor::OneMinusSrcAlpha))
        );
        assert_eq!(d.alpha_test, Some((Compare::Greater, 0.5)));
        assert_eq!((d.cull, d.front_ccw), (Cull::Front, false));
        assert_eq!(d.scissor, Some([10, 36, 40, 76]));
        assert_eq!(frame_rect([-5, -5, 500, 500], 128, 96), [0, 0, 128, 96]);
        s.blend_func[0] = 0x8001;
        assert!(s.draw_state(128, 96).unwrap_err().contains("blend factor"));
        assert!(compare(0x1234).is_err());
    }
}
