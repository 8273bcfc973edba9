//! The GL context the importer tracks from the capture's first call: the
//! matrices, arrays, textures and fixed-function state, and what each call
//! does to them ([`Context::apply`]).

use super::args::{self, CallError};
use super::arrays::Arrays;
use super::enums as gl;
use super::immediate::{Immediate, Step};
use super::matrices::{Mat4, Matrices};
use super::state::{self, FixedState};
use super::textures::Textures;
use wasp_gltrace::{is_frame_end, Call};

/// Texture units tracked (GL 1.x implementations have 2 to 8; the front
/// end samples the first [`super::draw::UV_SETS`]).
pub const UNITS: usize = 8;

/// What a call was to the importer.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Effect {
    /// It changed the modelled state (or is a no-op of it, such as
    /// glLockArraysEXT).
    Modelled,
    /// The model does not use it: counted under this name.
    Unmodelled(String),
    /// A draw call of the subset (glDrawArrays, glDrawElements,
    /// glDrawRangeElements, glEnd of an immediate-mode block).
    Draw,
    /// A draw outside the subset: what it needs.
    UnsupportedDraw(String),
    /// A buffer swap: the frame ends.
    FrameEnd,
}

/// The tracked context.
#[derive(Clone, Debug)]
pub struct Context {
    pub matrices: Matrices,
    pub arrays: Arrays,
    pub textures: Textures,
    pub state: FixedState,
    /// Immediate mode: current attributes, glBegin .. glEnd blocks.
    pub immediate: Immediate,
    /// Inside glNewList .. glEndList: calls are compiled into a display
    /// list, not executed.
    pub in_list: bool,
    /// The current frame has drawn (a depth clear after that starts a new
    /// depth epoch).
    pub drawn: bool,
}

impl Default for Context {
    fn default() -> Self {
        Self {
            matrices: Matrices::new(UNITS),
            arrays: Arrays::new(UNITS),
            textures: Textures::new(UNITS),
            state: FixedState::default(),
            immediate: Immediate::new(UNITS),
            in_list: false,
            drawn: false,
        }
    }
}

/// The call's name with a GL_* argument, for counting what is not
/// modelled (for example `glEnable(GL_FOG)`).
fn with(call: &Call, what: impl std::fmt::Display) -> Effect {
    Effect::Unmodelled(format!("{}({what})", call.name))
}

impl Context {
    /// Apply `call`; `Err` for a call the engine could not have made
    /// without a GL error (a bad enum, a stack underflow) or whose
    /// arguments are not what its signature says.
    pub fn apply(&mut self, call: &Call) -> Result<Effect, CallError> {
        let name: &str = &call.name;
        if is_frame_end(name) {
            self.drawn = false;
            self.state.depth_epoch = 0;
            return Ok(Effect::FrameEnd);
        }
        if self.in_list {
            if name == "glEndList" {
                self.in_list = false;
            }
            return Ok(Effect::Unmodelled(format!("{name} (in a display list)")));
        }
        match self.immediate.apply(call)? {
            Step::Other => {}
            Step::Modelled => return Ok(Effect::Modelled),
            Step::Unmodelled(n) => return Ok(Effect::Unmodelled(n)),
            Step::End => {
                self.drawn = true;
                return Ok(Effect::Draw);
            }
        }
        let err = |m: String| CallError::at(call, m);
        if let Some(e) = self.apply_matrix(call, name)? {
            return Ok(e);
        }
        if let Some(e) = self.apply_texture(call, name)? {
            return Ok(e);
        }
        if let Some(e) = self.apply_arrays(call, name)? {
            return Ok(e);
        }
        if let Some(e) = self.apply_state(call, name)? {
            return Ok(e);
        }
        Ok(match name {
            "glDrawArrays"
            | "glDrawArraysEXT"
            | "glDrawElements"
            | "glDrawRangeElements"
            | "glDrawRangeElementsEXT" => {
                self.drawn = true;
                Effect::Draw
            }
            "glCallList" | "glCallLists" => Effect::UnsupportedDraw("a display list".into()),
            "glNewList" => {
                self.in_list = true;
                Effect::Unmodelled(name.into())
            }
            n if n.starts_with("glMultiDraw") || n.starts_with("glDrawPixels") => {
                Effect::UnsupportedDraw(n.to_string())
            }
            "glUseProgram" | "glUseProgramObjectARB" => {
                self.state.program = args::int(call, 0).map_err(|e| err(e.message))?.max(0) as u64;
                Effect::Modelled
            }
            _ => Effect::Unmodelled(name.into()),
        })
    }

    fn apply_matrix(&mut self, call: &Call, name: &str) -> Result<Option<Effect>, CallError> {
        let err = |m: String| CallError::at(call, m);
        let unit = self.textures.active;
        let n = |i| args::num(call, i);
        let m = &mut self.matrices;
        match name {
            "glMatrixMode" => m.set_mode(args::int(call, 0)?).map_err(err)?,
            "glLoadIdentity" => m.load(unit, Mat4::IDENTITY),
            "glLoadMatrixf" | "glLoadMatrixd" => {
                m.load(unit, Mat4(args::nums(call, 0, 16)?.try_into().expect("16")))
            }
            "glMultMatrixf" | "glMultMatrixd" => m.mult(
                unit,
                &Mat4(args::nums(call, 0, 16)?.try_into().expect("16")),
            ),
            "glPushMatrix" => m.push(unit).map_err(err)?,
            "glPopMatrix" => m.pop(unit).map_err(err)?,
            "glOrtho" | "glFrustum" => {
                let v = [n(0)?, n(1)?, n(2)?, n(3)?, n(4)?, n(5)?];
                let f = if name == "glOrtho" {
                    Mat4::ortho
                } else {
                    Mat4::frustum
                };
                m.mult(unit, &f(v[0], v[1], v[2], v[3], v[4], v[5]));
            }
            "glTranslatef" | "glTranslated" => m.mult(unit, &Mat4::translate(n(0)?, n(1)?, n(2)?)),
            "glScalef" | "glScaled" => m.mult(unit, &Mat4::scale(n(0)?, n(1)?, n(2)?)),
            "glRotatef" | "glRotated" => m.mult(unit, &Mat4::rotate(n(0)?, n(1)?, n(2)?, n(3)?)),
            _ => return Ok(None),
        }
        Ok(Some(Effect::Modelled))
    }

    fn apply_texture(&mut self, call: &Call, name: &str) -> Result<Option<Effect>, CallError> {
        let err = |m: String| CallError::at(call, m);
        let t = &mut self.textures;
        match name {
            "glActiveTexture" | "glActiveTextureARB" => {
                t.active = unit_of(call, args::int(call, 0)?)?;
            }
            "glGenTextures" | "glDeleteTextures" => {}
            "glBindTexture" | "glBindTextureEXT" => {
                let target = args::int(call, 0)?;
                if target != gl::TEXTURE_2D && target != gl::TEXTURE_3D {
                    return Ok(Some(with(call, gl::name(target))));
                }
                let id = u32::try_from(args::int(call, 1)?).map_err(|e| err(e.to_string()))?;
                t.bind(target, id);
            }
            "glTexImage3D" | "glTexImage3DEXT" | "glTexSubImage3D" | "glTexSubImage3DEXT" => {
                let target = args::int(call, 0)?;
                if target != gl::TEXTURE_3D {
                    return Ok(Some(with(call, gl::name(target))));
                }
                if name.starts_with("glTexImage") {
                    t.image_3d(call)?;
                } else {
                    t.sub_image_3d(call)?;
                }
            }
            "glTexParameteri" | "glTexParameterf" if args::int(call, 0)? == gl::TEXTURE_3D => {
                let pname = args::int(call, 1)?;
                let v = args::num(call, 2)? as i64;
                if let Err(p) = t.parameter(gl::TEXTURE_3D, pname, v) {
                    return Ok(Some(with(call, p)));
                }
            }
            "glTexImage2D"
            | "glTexSubImage2D"
            | "glCompressedTexImage2D"
            | "glCompressedTexImage2DARB"
            | "glTexParameteri"
            | "glTexParameterf" => {
                let target = args::int(call, 0)?;
                if target != gl::TEXTURE_2D {
                    return Ok(Some(with(call, gl::name(target))));
                }
                match name {
                    "glTexImage2D" => t.image(call)?,
                    "glTexSubImage2D" => t.sub_image(call)?,
                    "glTexParameteri" | "glTexParameterf" => {
                        let pname = args::int(call, 1)?;
                        let v = args::num(call, 2)? as i64;
                        if let Err(p) = t.parameter(gl::TEXTURE_2D, pname, v) {
                            return Ok(Some(with(call, p)));
                        }
                    }
                    _ => t.compressed_image(call)?,
                }
            }
            "glPixelStorei" => {
                if let Err(p) = t.pixel_store(args::int(call, 0)?, args::int(call, 1)?) {
                    return Ok(Some(with(call, p)));
                }
            }
            "glTexEnvi" | "glTexEnvf" => {
                let (target, pname) = (args::int(call, 0)?, args::int(call, 1)?);
                if target != gl::TEXTURE_ENV || pname != gl::TEXTURE_ENV_MODE {
                    return Ok(Some(with(call, gl::name(pname))));
                }
                t.units[t.active].env_mode = args::num(call, 2)? as i64;
            }
            _ => return Ok(None),
        }
        Ok(Some(Effect::Modelled))
    }

    fn apply_arrays(&mut self, call: &Call, name: &str) -> Result<Option<Effect>, CallError> {
        let a = &mut self.arrays;
        match name {
            "glVertexPointer"
            | "glTexCoordPointer"
            | "glColorPointer"
            | "glNormalPointer"
            | "glVertexPointerEXT"
            | "glTexCoordPointerEXT"
            | "glColorPointerEXT" => a.pointer(call)?,
            "glClientActiveTexture" | "glClientActiveTextureARB" => {
                a.client_unit = unit_of(call, args::int(call, 0)?)?;
            }
            "glEnableClientState" | "glDisableClientState" => {
                let on = name == "glEnableClientState";
                if let Err(n) = a.client_state(args::int(call, 0)?, on) {
                    return Ok(Some(with(call, n)));
                }
            }
            "glBindBuffer" | "glBindBufferARB" => {
                let id = args::int(call, 1)?.max(0) as u32;
                if let Err(n) = a.bind_buffer(args::int(call, 0)?, id) {
                    return Ok(Some(with(call, n)));
                }
            }
            "glBufferData" | "glBufferDataARB" => a.buffer_data(call)?,
            "glBufferSubData" | "glBufferSubDataARB" => a.buffer_sub_data(call)?,
            "glGenBuffers" | "glGenBuffersARB" | "glDeleteBuffers" | "glDeleteBuffersARB"
            | "glLockArraysEXT" | "glUnlockArraysEXT" => {}
            _ => return Ok(None),
        }
        Ok(Some(Effect::Modelled))
    }

    fn apply_state(&mut self, call: &Call, name: &str) -> Result<Option<Effect>, CallError> {
        let err = |m: String| CallError::at(call, m);
        let s = &mut self.state;
        let four = || -> Result<[i64; 4], CallError> {
            Ok([
                args::int(call, 0)?,
                args::int(call, 1)?,
                args::int(call, 2)?,
                args::int(call, 3)?,
            ])
        };
        match name {
            "glEnable" | "glDisable" => {
                let (cap, on) = (args::int(call, 0)?, name == "glEnable");
                if !s.enable(cap, on) {
                    let u = &mut self.textures.units[self.textures.active];
                    match cap {
                        gl::TEXTURE_2D => u.enabled_2d = on,
                        gl::TEXTURE_3D => u.enabled_3d = on,
                        gl::TEXTURE_1D
                        | gl::TEXTURE_CUBE_MAP
                        | gl::TEXTURE_GEN_S..=gl::TEXTURE_GEN_Q => {
                            u.enabled_other.retain(|&c| c != cap);
                            if on {
                                u.enabled_other.push(cap);
                            }
                        }
                        _ => return Ok(Some(with(call, gl::name(cap)))),
                    }
                }
            }
            "glViewport" => s.viewport = four()?,
            "glScissor" => s.scissor = four()?,
            "glDepthRange" | "glDepthRangef" => {
                s.depth_range = [
                    args::num(call, 0)?.clamp(0.0, 1.0),
                    args::num(call, 1)?.clamp(0.0, 1.0),
                ]
            }
            "glDepthFunc" => {
                let f = args::int(call, 0)?;
                state::compare(f).map_err(err)?;
                s.depth_func = f;
            }
            "glDepthMask" => s.depth_mask = args::int(call, 0)? != 0,
            "glBlendFunc" => s.blend_func = [args::int(call, 0)?, args::int(call, 1)?],
            "glAlphaFunc" => {
                let f = args::int(call, 0)?;
                state::compare(f).map_err(err)?;
                s.alpha_func = f;
                s.alpha_ref = args::num(call, 1)?.clamp(0.0, 1.0);
            }
            "glCullFace" => s.cull_face = args::int(call, 0)?,
            "glFrontFace" => s.front_face = args::int(call, 0)?,
            "glPolygonOffset" => s.offset = [args::num(call, 0)?, args::num(call, 1)?],
            "glColorMask" => {
                let m = four()?;
                s.colour_mask = m.map(|v| v != 0);
            }
            "glClear" => {
                if args::int(call, 0)? & gl::DEPTH_BUFFER_BIT != 0 && self.drawn {
                    s.depth_epoch += 1;
                }
            }
            _ => return Ok(None),
        }
        Ok(Some(Effect::Modelled))
    }
}

/// A GL_TEXTUREi enum as a unit number.
fn unit_of(call: &Call, e: i64) -> Result<usize, CallError> {
    usize::try_from(e - gl::TEXTURE0)
        .ok()
        .filter(|&u| u < UNITS)
        .ok_or_else(|| {
            CallError::at(
                call,
                format!(
                    "texture unit {}: expected GL_TEXTURE0 to GL_TEXTURE{}",
                    gl::name(e),
                    UNITS - 1
                ),
            )
        })
}

#[cfg(test)]
mod tests {
    use super::super::args::test_calls::*;
    use super::*;
    use wasp_gltrace::Value;

    #[test]
    fn calls_change_the_state_they_name_and_the_rest_are_counted() {
        let mut c = Context::default();
        let i = Value::SInt;
        let run = |c: &mut Context, name: &str, a: Vec<Value>| c.apply(&call(1, name, a)).unwrap();
        assert_eq!(
            run(&mut c, "glActiveTexture", vec![e(gl::TEXTURE0 + 1)]),
            Effect::Modelled
        );
        run(&mut c, "glEnable", vec![e(gl::TEXTURE_2D)]);
        run(&mut c, "glBindTexture", vec![e(gl::TEXTURE_2D), i(3)]);
        run(&mut c, "glBindTexture", vec![e(gl::TEXTURE_3D), i(4)]);
        run(&mut c, "glEnable", vec![e(gl::TEXTURE_3D)]);
        let wrap_r = vec![e(gl::TEXTURE_3D), e(gl::TEXTURE_WRAP_R), e(0x812F)];
        run(&mut c, "glTexParameteri", wrap_r);
        assert_eq!(c.textures.objects_3d[&4].wrap[2], 0x812F);
        assert!(c.textures.units[1].enabled_3d && c.textures.units[1].bound_3d == 4);
        assert!(c.textures.units[1].enabled_other.is_empty());
        assert!(c.textures.units[1].enabled_2d && c.textures.units[1].bound == 3);
        assert!(!c.textures.units[0].enabled_2d);
        run(&mut c, "glMatrixMode", vec![e(gl::TEXTURE)]);
        run(&mut c, "glScalef", vec![f(2.0), f(2.0), f(1.0)]);
        assert_eq!(c.matrices.texture[1].top().at(0, 0), 2.0);
        assert_eq!(c.matrices.texture[0].top(), &Mat4::IDENTITY);
        run(&mut c, "glDepthFunc", vec![e(gl::NEVER + 2)]);
        run(&mut c, "glViewport", vec![i(0), i(0), i(64), i(32)]);
        assert_eq!(
            (c.state.depth_func, c.state.viewport),
            (gl::NEVER + 2, [0, 0, 64, 32])
        );
        assert_eq!(
            run(&mut c, "glEnable", vec![e(0x0B60)]),
            Effect::Unmodelled("glEnable(GL_FOG)".into())
        );
        assert_eq!(
            run(&mut c, "glHint", vec![]),
            Effect::Unmodelled("glHint".into())
        );
        run(&mut c, "glEnable", vec![e(gl::TEXTURE_GEN_S)]);
        assert_eq!(c.textures.units[1].enabled_other, [gl::TEXTURE_GEN_S]);
        // A depth clear after a draw starts a new depth epoch; a swap ends
        // the frame and resets it.
        run(&mut c, "glClear", vec![Value::Bitmask(0x100)]);
        assert_eq!(c.state.depth_epoch, 0);
        assert_eq!(
            run(&mut c, "glDrawArrays", vec![e(4), i(0), i(3)]),
            Effect::Draw
        );
        run(&mut c, "glClear", vec![Value::Bitmask(0x4100)]);
        assert_eq!(c.state.depth_epoch, 1);
        assert_eq!(run(&mut c, "glXSwapBuffers", vec![]), Effect::FrameEnd);
        assert_eq!(c.state.depth_epoch, 0);
        // An immediate-mode block draws at its glEnd.
        assert_eq!(run(&mut c, "glBegin", vec![e(4)]), Effect::Modelled);
        assert_eq!(run(&mut c, "glEnd", vec![]), Effect::Draw);
        // Display lists compile, not execute.
        run(&mut c, "glNewList", vec![i(1), e(0x1300)]);
        run(&mut c, "glViewport", vec![i(0), i(0), i(8), i(8)]);
        assert_eq!(c.state.viewport, [0, 0, 64, 32]);
        run(&mut c, "glEndList", vec![]);
        let bad = c.apply(&call(9, "glPopMatrix", vec![])).unwrap_err();
        assert_eq!(bad.call, 9);
        assert!(c
            .apply(&call(10, "glActiveTexture", vec![e(0x1234)]))
            .is_err());
        assert!(c.apply(&call(11, "glDepthFunc", vec![e(0x1234)])).is_err());
    }
}
