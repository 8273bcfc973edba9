//! The rewriter of a capture into one `glretrace` replays to measure a
//! frame (docs/scenes.md, "Checked against Mesa"). Both modes replace
//! the colour of every fragment and keep everything that decides which
//! fragments are written (geometry, matrices, viewport, scissor, depth,
//! culling, polygon offset, the alpha test and the texture alpha it
//! reads):
//!
//! - [`Mode::Id`]: every 2D and 3D texture upload's RGB is the texture's id
//!   colour ([`id_colour`]; its alpha kept, so the alpha test discards the
//!   same fragments), texture unit 0 replaces the fragment's colour
//!   (`GL_REPLACE`), the other units are off, vertex colours are one
//!   constant (the untextured colour), blending, lighting, fog and
//!   dithering are off: a pixel's colour names the texture of the last
//!   fragment written to it.
//! - [`Mode::Count`]: the same with every texel's and vertex's RGB 1/255,
//!   blending `GL_ONE, GL_ONE` always on and colour writes always on: a
//!   pixel's red value counts the fragments that passed the scissor,
//!   alpha and depth tests there.
//!
//! The frame's colour buffer is cleared to black where it starts, and the
//! capture ends at the frame's swap. Before the first frame's swap, a swap
//! follows every make-current call: glretrace shows its window at the
//! first swap, and reads undefined pixels before that. Draws of earlier frames are left out
//! (they change no state); everything else is replayed, so the textures
//! and state of earlier frames are there.

use super::texels::{id_texels, Unpack, RGBA8};
use super::vertex_alpha::VertexAlpha;
use crate::gl::enums as gl;
use std::collections::{BTreeMap, HashMap};
use std::path::Path;
use std::sync::Arc;
use wasp_gltrace::{Call, Capture, CaptureWriter, Value};

const LIGHTING: i64 = 0x0B50;
const FOG: i64 = 0x0B60;
const DITHER: i64 = 0x0BD0;
const COLOR_LOGIC_OP: i64 = 0x0BF2;
const CLAMP: i64 = 0x2900;
const CLAMP_TO_EDGE: i64 = 0x812F;
const WRAP_S: i64 = 0x2802;
const WRAP_T: i64 = 0x2803;
const FUNC_ADD: i64 = 0x8006;
const TEXTURE_ENV: i64 = 0x2300;
const TEXTURE_ENV_MODE: i64 = 0x2200;
const SCISSOR_BIT: u64 = 0x0008_0000;
const COLOR_BUFFER_BIT: u64 = 0x4000;
const UNPACK_SKIP_ROWS: i64 = 0x0CF3;
const UNPACK_SKIP_PIXELS: i64 = 0x0CF4;

/// The id colour of pixels no fragment was written to (the clear).
pub const CLEAR_ID: u32 = 0;
/// The id colour of fragments of untextured draws.
pub const UNTEXTURED_ID: u32 = 0x00FF_FFFF;

/// The colour that names texture `name` in an id replay: `name + 1` in
/// 24 bits, red lowest (0 is the clear, `0xFFFFFF` untextured).
pub fn id_colour(name: u32) -> [u8; 3] {
    let v = name.wrapping_add(1) & 0x00FF_FFFF;
    [v as u8, (v >> 8) as u8, (v >> 16) as u8]
}

/// The texture name an id replay's pixel colour names: `None` for the
/// clear, `Some(None)` for an untextured draw.
pub fn name_of_colour(rgb: [u8; 3]) -> Option<Option<u32>> {
    let v = u32::from(rgb[0]) | u32::from(rgb[1]) << 8 | u32::from(rgb[2]) << 16;
    match v {
        CLEAR_ID => None,
        UNTEXTURED_ID => Some(None),
        v => Some(Some(v - 1)),
    }
}

/// What a replay of the rewritten capture measures.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// Per pixel, the texture of the last fragment written.
    Id,
    /// Per pixel, the number of fragments written.
    Count,
}

/// What the rewriting did.
#[derive(Clone, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct Rewritten {
    /// Calls read from the original capture (up to the frame's swap).
    pub calls_read: u64,
    /// Calls written.
    pub calls_written: u64,
    /// The frame's swap call's number in the rewritten capture (for
    /// `glretrace -S`).
    pub swap_call: u64,
    /// 2D texture uploads rewritten.
    pub uploads: u64,
    /// Draws of earlier frames left out.
    pub earlier_draws_left_out: u64,
    /// What could not be rewritten exactly, by what (uploads whose alpha
    /// could not be decoded, other texture targets...), with counts.
    pub notes: BTreeMap<String, u64>,
}

/// An error rewriting: reading the capture or writing the new one.
#[derive(Debug)]
pub struct RewriteError(pub String);

impl std::fmt::Display for RewriteError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for RewriteError {}

/// The GL state the rewriting follows.
struct Rewriter {
    mode: Mode,
    /// The frame's size.
    size: (u32, u32),
    unit: u32,
    /// The 2D texture bound per unit.
    bound: HashMap<u32, u32>,
    /// The 3D texture bound per unit.
    bound_3d: HashMap<u32, u32>,
    /// Level 0's internal format per texture name (for sub-images).
    internal: HashMap<u32, i64>,
    unpack: Unpack,
    unpack_skip: bool,
    context: bool,
    /// Whether a frame ended (a swap was written) yet.
    swapped: bool,
    clear_pending: bool,
    vertex_alpha: VertexAlpha,
    out: Rewritten,
}

/// Rewrites `capture` for `mode` into `out`, up to and including the
/// frame whose calls are `frame` (first, swap: the importer's range) and
/// whose size is `size`.
pub fn rewrite(
    capture: Capture,
    mode: Mode,
    frame: (u64, u64),
    size: (u32, u32),
    out: &Path,
) -> Result<Rewritten, RewriteError> {
    let io = |e: std::io::Error| RewriteError(format!("{}: {e}", out.display()));
    let mut w =
        CaptureWriter::create(out, capture.semantic_version, &capture.properties).map_err(io)?;
    let mut r = Rewriter::new(mode, size);
    let mut swap = None;
    for call in capture {
        let call = call.map_err(|e| RewriteError(e.to_string()))?;
        // Calls numbered after the swap come before it only when the swap
        // never returned (the program was killed in it): they are later.
        if call.no > frame.1 {
            continue;
        }
        r.out.calls_read += 1;
        if call.no == frame.0 {
            r.clear_pending = true;
        }
        if call.no < frame.0 && is_draw(&call.name) {
            r.out.earlier_draws_left_out += 1;
            continue;
        }
        let mut calls = Vec::new();
        if r.clear_pending && r.context {
            r.clear_frame(&call, &mut calls);
        }
        r.swapped |= wasp_gltrace::is_frame_end(&call.name);
        r.vertex_alpha.follow(&call);
        let reads_vertex_alpha = match &*call.name {
            "glEnd" => r.vertex_alpha.block_reads_vertex_alpha(),
            n => is_draw(n) && r.vertex_alpha.draw_reads_vertex_alpha(),
        };
        if call.no >= frame.0 && reads_vertex_alpha {
            r.note(
                "alpha-tested draw of the frame whose vertex alpha is below 1 (replayed with 1)"
                    .into(),
            );
        }
        r.call(call, &mut calls);
        for c in &calls {
            let no = w.write_call(c).map_err(io)?;
            if c.no == frame.1 && wasp_gltrace::is_frame_end(&c.name) {
                swap = Some(no);
            }
        }
        if swap.is_some() {
            break;
        }
    }
    r.out.calls_written = w.calls_written();
    w.finish().map_err(io)?;
    r.out.swap_call = swap.ok_or_else(|| {
        RewriteError(format!(
            "the capture ends before call {} (the frame's swap)",
            frame.1
        ))
    })?;
    Ok(r.out)
}

fn is_draw(name: &str) -> bool {
    matches!(
        name,
        "glDrawElements"
            | "glDrawArrays"
            | "glDrawRangeElements"
            | "glDrawRangeElementsEXT"
            | "glMultiDrawArrays"
            | "glMultiDrawElements"
            | "glDrawArraysEXT"
    )
}

/// A new call on `like`'s thread, numbered as `like` (so the frame's swap
/// is still found by number only for the swap itself).
fn make(like: &Call, name: &str, arg_names: &[&str], args: Vec<Value>) -> Call {
    Call {
        no: u64::MAX,
        thread: like.thread,
        name: Arc::from(name),
        arg_names: arg_names.iter().map(|s| s.to_string()).collect(),
        args,
        ret: None,
    }
}

fn cap(like: &Call, enable: bool, what: i64) -> Call {
    let name = if enable { "glEnable" } else { "glDisable" };
    make(like, name, &["cap"], vec![Value::Enum(what)])
}

impl Rewriter {
    fn new(mode: Mode, size: (u32, u32)) -> Rewriter {
        Rewriter {
            mode,
            size,
            unit: 0,
            bound: HashMap::new(),
            bound_3d: HashMap::new(),
            internal: HashMap::new(),
            unpack: Unpack {
                align: 4,
                row_length: 0,
            },
            unpack_skip: false,
            context: false,
            swapped: false,
            clear_pending: false,
            vertex_alpha: VertexAlpha::default(),
            out: Rewritten::default(),
        }
    }

    /// The colour of vertices and untextured fragments, and the RGB of
    /// every texel of texture `name`.
    fn rgb(&self, name: Option<u32>) -> [u8; 3] {
        match (self.mode, name) {
            (Mode::Count, _) => [1, 1, 1],
            (Mode::Id, Some(n)) => id_colour(n),
            (Mode::Id, None) => id_colour(UNTEXTURED_ID - 1),
        }
    }

    fn note(&mut self, what: String) {
        *self.out.notes.entry(what).or_default() += 1;
    }

    /// The state every replay starts from, after a context is made current.
    fn initial_state(&self, like: &Call, calls: &mut Vec<Call>) {
        let env = [
            Value::Enum(TEXTURE_ENV),
            Value::Enum(TEXTURE_ENV_MODE),
            Value::Enum(gl::REPLACE),
        ];
        calls.push(make(
            like,
            "glTexEnvi",
            &["target", "pname", "param"],
            env.into(),
        ));
        calls.push(self.colour_call(like));
        calls.push(cap(like, false, DITHER));
        if self.mode == Mode::Count {
            calls.push(cap(like, true, gl::BLEND));
            calls.push(blend_one_one(like));
        }
    }

    fn colour_call(&self, like: &Call) -> Call {
        let c = self.rgb(None).map(|v| Value::Float(f32::from(v) / 255.0));
        let [r, g, b] = c;
        let args = vec![r, g, b, Value::Float(1.0)];
        make(like, "glColor4f", &["red", "green", "blue", "alpha"], args)
    }

    /// Clears the colour buffer to black where the frame starts, whatever
    /// the scissor and colour mask (restored after).
    fn clear_frame(&mut self, like: &Call, calls: &mut Vec<Call>) {
        self.clear_pending = false;
        let bits = Value::Bitmask(COLOR_BUFFER_BIT | SCISSOR_BIT);
        calls.push(make(like, "glPushAttrib", &["mask"], vec![bits]));
        calls.push(cap(like, false, gl::SCISSOR_TEST));
        let t = vec![Value::Bool(true); 4];
        calls.push(make(
            like,
            "glColorMask",
            &["red", "green", "blue", "alpha"],
            t,
        ));
        let zero = vec![Value::Float(0.0); 4];
        calls.push(make(
            like,
            "glClearColor",
            &["red", "green", "blue", "alpha"],
            zero,
        ));
        let clear = vec![Value::Bitmask(COLOR_BUFFER_BIT)];
        calls.push(make(like, "glClear", &["mask"], clear));
        calls.push(make(like, "glPopAttrib", &[], vec![]));
    }

    /// `call` rewritten into `calls`.
    fn call(&mut self, mut call: Call, calls: &mut Vec<Call>) {
        let int = |i: usize| call.arg(i).as_i64();
        let name = call.name.to_string();
        match name.as_str() {
            "glXMakeCurrent" | "glXMakeContextCurrent" | "eglMakeCurrent" | "wglMakeCurrent" => {
                calls.push(call.clone());
                self.context = true;
                if !self.swapped {
                    // glretrace sizes its window by the viewport and shows
                    // it at the first swap; before that its pixels are
                    // undefined, so both happen first.
                    let (w, h) = self.size;
                    let vp = [0, 0, w, h].map(|v| Value::UInt(u64::from(v))).into();
                    let names = ["x", "y", "width", "height"];
                    calls.push(make(&call, "glViewport", &names, vp));
                    calls.extend(show_window(&call));
                }
                self.initial_state(&call, calls);
                if self.clear_pending {
                    self.clear_frame(&call, calls);
                }
                return;
            }
            "glActiveTexture" | "glActiveTextureARB" => {
                self.unit = int(0).map_or(0, |v| (v - gl::TEXTURE0).clamp(0, 255) as u32);
            }
            "glBindTexture" | "glBindTextureEXT" if int(0) == Some(gl::TEXTURE_2D) => {
                self.bound.insert(self.unit, int(1).unwrap_or(0) as u32);
            }
            "glBindTexture" | "glBindTextureEXT" if int(0) == Some(gl::TEXTURE_3D) => {
                self.bound_3d.insert(self.unit, int(1).unwrap_or(0) as u32);
            }
            "glEnable" | "glDisable" => {
                if let Some(c) = int(0).and_then(|v| self.capability(v, name == "glEnable")) {
                    call = cap(&call, c.0, c.1);
                }
            }
            "glEnableClientState" if int(0) == Some(gl::COLOR_ARRAY) => {
                call = make(&call, "glDisableClientState", &["array"], call.args.clone());
            }
            n if is_colour(n) => call = self.colour_call(&call),
            "glClearColor" => call.args = vec![Value::Float(0.0); 4],
            "glTexEnvi" | "glTexEnvf" | "glTexEnviv" | "glTexEnvfv"
                if int(0) == Some(TEXTURE_ENV) && int(1) == Some(TEXTURE_ENV_MODE) =>
            {
                let args = vec![
                    Value::Enum(TEXTURE_ENV),
                    Value::Enum(TEXTURE_ENV_MODE),
                    Value::Enum(gl::REPLACE),
                ];
                call = make(&call, "glTexEnvi", &["target", "pname", "param"], args);
            }
            "glTexParameteri" | "glTexParameterf" if matches!(int(1), Some(WRAP_S | WRAP_T)) => {
                if call.arg(2).as_f64() == Some(CLAMP as f64) {
                    call.args[2] = Value::Enum(CLAMP_TO_EDGE);
                    call.name = Arc::from("glTexParameteri");
                    // (The border colour would mix into the id colour.)
                    self.note("GL_CLAMP wrap (replayed as GL_CLAMP_TO_EDGE)".into());
                }
            }
            "glPixelStorei" | "glPixelStoref" => self.pixel_store(&mut call),
            "glTexImage2D" | "glCompressedTexImage2D" | "glCompressedTexImage2DARB" => {
                self.image(&mut call)
            }
            "glTexSubImage2D" | "glTexSubImage2DEXT" => self.sub_image(&mut call),
            "glTexImage3D" | "glTexImage3DEXT" => self.image_3d(&mut call),
            "glTexSubImage3D" | "glTexSubImage3DEXT" => self.sub_image_3d(&mut call),
            "glCopyTexImage2D" | "glCopyTexSubImage2D" | "glInterleavedArrays" => {
                self.note(format!("{name} (left as it is)"))
            }
            _ => self.mode_call(&mut call),
        }
        calls.push(call);
    }

    /// The calls only one mode changes: blending and colour masks.
    fn mode_call(&mut self, call: &mut Call) {
        if self.mode != Mode::Count {
            return;
        }
        let n = call.args.len();
        match &*call.name {
            "glBlendFunc" | "glBlendFuncSeparate" | "glBlendFuncSeparateEXT" => {
                call.args = vec![Value::Enum(gl::ONE); n]
            }
            "glBlendEquation" | "glBlendEquationEXT" | "glBlendEquationSeparate" => {
                call.args = vec![Value::Enum(FUNC_ADD); n]
            }
            "glColorMask" => call.args = vec![Value::Bool(true); n],
            _ => {}
        }
    }

    /// What glEnable/glDisable of `v` becomes: (enable, capability), or
    /// `None` to keep it.
    fn capability(&mut self, v: i64, enable: bool) -> Option<(bool, i64)> {
        match v {
            gl::TEXTURE_2D | gl::TEXTURE_3D if self.unit > 0 => Some((false, v)),
            gl::TEXTURE_1D | gl::TEXTURE_CUBE_MAP => {
                if enable {
                    self.note(format!("texture target {} (disabled)", gl::name(v)));
                }
                Some((false, v))
            }
            LIGHTING | FOG | DITHER | COLOR_LOGIC_OP => Some((false, v)),
            gl::BLEND => Some((self.mode == Mode::Count, v)),
            _ => None,
        }
    }

    /// Unpack state: tracked for decoding, and written as the rewritten
    /// uploads need it (tight rows of RGBA8).
    fn pixel_store(&mut self, call: &mut Call) {
        let (p, v) = (call.arg(0).as_i64(), call.arg(1).as_f64().unwrap_or(0.0));
        let v = v.max(0.0) as usize;
        match p {
            Some(gl::UNPACK_ALIGNMENT) => {
                self.unpack.align = v;
                call.args[1] = Value::UInt(4);
            }
            Some(gl::UNPACK_ROW_LENGTH) => {
                self.unpack.row_length = v;
                call.args[1] = Value::UInt(0);
            }
            Some(UNPACK_SKIP_ROWS | UNPACK_SKIP_PIXELS) => {
                self.unpack_skip = v != 0;
                call.args[1] = Value::UInt(0);
            }
            _ => {}
        }
    }

    /// glTexImage2D (and glCompressedTexImage2D, rewritten as one) of a
    /// 2D texture.
    fn image(&mut self, call: &mut Call) {
        if call.arg(0).as_i64() != Some(gl::TEXTURE_2D) {
            self.note(format!("{} of another target (left as it is)", call.name));
            return;
        }
        let compressed = call.name.starts_with("glCompressed");
        let internal = call.arg(2).as_i64().unwrap_or(0);
        let size = (arg_u32(call, 3), arg_u32(call, 4));
        let name = self.bound.get(&self.unit).copied().unwrap_or(0);
        if call.arg(1).as_i64() == Some(0) {
            self.internal.insert(name, internal);
        }
        let rgb = self.rgb(Some(name));
        let blob = if compressed {
            self.note("compressed upload (alpha 1)".into());
            Some(id_texels(None, size, (0x1907, 0, 0), self.unpack, rgb).0)
        } else {
            self.texels(call, size, internal, rgb)
        };
        let border = call.arg(5).clone();
        let level = call.arg(1).clone();
        *call = make(
            call,
            "glTexImage2D",
            &[
                "target",
                "level",
                "internalformat",
                "width",
                "height",
                "border",
                "format",
                "type",
                "pixels",
            ],
            vec![
                Value::Enum(gl::TEXTURE_2D),
                level,
                Value::Enum(RGBA8),
                Value::UInt(u64::from(size.0)),
                Value::UInt(u64::from(size.1)),
                border,
                Value::Enum(gl::RGBA),
                Value::Enum(gl::UNSIGNED_BYTE),
                blob.map_or(Value::Null, Value::Blob),
            ],
        );
        self.out.uploads += 1;
    }

    /// glTexSubImage2D of a 2D texture.
    fn sub_image(&mut self, call: &mut Call) {
        if call.arg(0).as_i64() != Some(gl::TEXTURE_2D) {
            self.note(format!("{} of another target (left as it is)", call.name));
            return;
        }
        let size = (arg_u32(call, 4), arg_u32(call, 5));
        let name = self.bound.get(&self.unit).copied().unwrap_or(0);
        let internal = self.internal.get(&name).copied().unwrap_or(gl::RGBA);
        let rgb = self.rgb(Some(name));
        if let Some(blob) = self.texels(call, size, internal, rgb) {
            call.args[6] = Value::Enum(gl::RGBA);
            call.args[7] = Value::Enum(gl::UNSIGNED_BYTE);
            call.args[8] = Value::Blob(blob);
            self.out.uploads += 1;
        }
    }

    /// glTexImage3D of a 3D texture: its slices' texels rewritten as one
    /// image of their rows.
    fn image_3d(&mut self, call: &mut Call) {
        if call.arg(0).as_i64() != Some(gl::TEXTURE_3D) {
            self.note(format!("{} of another target (left as it is)", call.name));
            return;
        }
        let internal = call.arg(2).as_i64().unwrap_or(0);
        let (w, h, d) = (arg_u32(call, 3), arg_u32(call, 4), arg_u32(call, 5));
        let name = self.bound_3d.get(&self.unit).copied().unwrap_or(0);
        if call.arg(1).as_i64() == Some(0) {
            self.internal.insert(name, internal);
        }
        let rgb = self.rgb(Some(name));
        if let Some(blob) = self.texels_at(call, 7, (w, h.saturating_mul(d)), internal, rgb) {
            call.args[2] = Value::Enum(RGBA8);
            call.args[7] = Value::Enum(gl::RGBA);
            call.args[8] = Value::Enum(gl::UNSIGNED_BYTE);
            call.args[9] = Value::Blob(blob);
            self.out.uploads += 1;
        }
    }

    /// glTexSubImage3D of a 3D texture.
    fn sub_image_3d(&mut self, call: &mut Call) {
        if call.arg(0).as_i64() != Some(gl::TEXTURE_3D) {
            self.note(format!("{} of another target (left as it is)", call.name));
            return;
        }
        let (w, h, d) = (arg_u32(call, 5), arg_u32(call, 6), arg_u32(call, 7));
        let name = self.bound_3d.get(&self.unit).copied().unwrap_or(0);
        let internal = self.internal.get(&name).copied().unwrap_or(gl::RGBA);
        let rgb = self.rgb(Some(name));
        if let Some(blob) = self.texels_at(call, 8, (w, h.saturating_mul(d)), internal, rgb) {
            call.args[8] = Value::Enum(gl::RGBA);
            call.args[9] = Value::Enum(gl::UNSIGNED_BYTE);
            call.args[10] = Value::Blob(blob);
            self.out.uploads += 1;
        }
    }

    /// The rewritten texels of an upload whose format and type are
    /// arguments 6 and 7 and pixels argument 8 (`None`: no client pixels).
    fn texels(
        &mut self,
        call: &Call,
        size: (u32, u32),
        internal: i64,
        rgb: [u8; 3],
    ) -> Option<Vec<u8>> {
        self.texels_at(call, 6, size, internal, rgb)
    }

    /// [`Rewriter::texels`] of an upload whose format, type and pixels are
    /// arguments `at`, `at + 1` and `at + 2`.
    fn texels_at(
        &mut self,
        call: &Call,
        at: usize,
        size: (u32, u32),
        internal: i64,
        rgb: [u8; 3],
    ) -> Option<Vec<u8>> {
        let (format, ty) = (
            call.arg(at).as_i64().unwrap_or(0),
            call.arg(at + 1).as_i64().unwrap_or(0),
        );
        let pixels = call.arg(at + 2).as_bytes();
        if pixels.is_none() && !call.arg(at + 2).is_null() {
            self.note(format!(
                "{} from a buffer object (left as it is)",
                call.name
            ));
            return None;
        }
        if self.unpack_skip {
            self.note("upload with GL_UNPACK_SKIP_* (alpha 1)".into());
        }
        let src = if self.unpack_skip { None } else { pixels };
        let (texels, why) = id_texels(src, size, (internal, format, ty), self.unpack, rgb);
        if let Some(why) = why {
            self.note(format!(
                "upload whose alpha is not decoded: {why} (alpha 1)"
            ));
        }
        Some(texels)
    }
}

/// glColor3f, glColor4ub, glColor4fv...: the current colour (not
/// glColorPointer, glColorMask, glColorMaterial).
fn is_colour(name: &str) -> bool {
    name.strip_prefix("glColor")
        .is_some_and(|r| r.starts_with(['3', '4']))
}

/// A swap of the drawable a make-current call binds (GLX and EGL).
fn show_window(make_current: &Call) -> Option<Call> {
    let a = |i: usize| make_current.arg(i).clone();
    match &*make_current.name {
        "glXMakeCurrent" | "glXMakeContextCurrent" => Some(make(
            make_current,
            "glXSwapBuffers",
            &["dpy", "drawable"],
            vec![a(0), a(1)],
        )),
        "eglMakeCurrent" => Some(make(
            make_current,
            "eglSwapBuffers",
            &["dpy", "surface"],
            vec![a(0), a(1)],
        )),
        _ => None,
    }
}

fn blend_one_one(like: &Call) -> Call {
    let args = vec![Value::Enum(gl::ONE), Value::Enum(gl::ONE)];
    make(like, "glBlendFunc", &["sfactor", "dfactor"], args)
}

fn arg_u32(call: &Call, i: usize) -> u32 {
    call.arg(i)
        .as_i64()
        .map_or(0, |v| v.clamp(0, 1 << 16) as u32)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// tests/gl/quads.trace rewritten for frame 1 (calls 90 to 159), read
    /// back.
    fn rewritten(mode: Mode) -> (Rewritten, Vec<Call>) {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
        let capture = Capture::open(root.join("tests/gl/quads.trace")).unwrap();
        let dir = std::env::temp_dir().join(format!("wasp-glcheck-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let out = dir.join(format!("{mode:?}.trace"));
        let r = rewrite(capture, mode, (90, 159), (256, 128), &out).unwrap();
        let calls = Capture::open(&out).unwrap().map(Result::unwrap).collect();
        (r, calls)
    }

    fn named<'a>(calls: &'a [Call], name: &'a str) -> impl Iterator<Item = &'a Call> + 'a {
        calls.iter().filter(move |c| &*c.name == name)
    }

    #[test]
    fn a_3d_texture_is_named_by_its_id_colour_and_stays_enabled_on_unit_0() {
        use crate::gl::args::test_calls::{call, e};
        let mut r = Rewriter::new(Mode::Id, (8, 8));
        let mut out = Vec::new();
        let i = Value::SInt;
        r.call(
            call(1, "glBindTexture", vec![e(gl::TEXTURE_3D), i(5)]),
            &mut out,
        );
        // 1x1x2 GL_RGBA: alphas 10 and 20.
        let px = Value::Blob(vec![1, 2, 3, 10, 4, 5, 6, 20]);
        let a = vec![e(gl::TEXTURE_3D), i(0), e(gl::RGBA), i(1), i(1), i(2), i(0)];
        let up = [a, vec![e(gl::RGBA), e(gl::UNSIGNED_BYTE), px]].concat();
        r.call(call(2, "glTexImage3D", up), &mut out);
        r.call(call(3, "glEnable", vec![e(gl::TEXTURE_3D)]), &mut out);
        let texels = out[1].arg(9).as_bytes().unwrap();
        let [x, y, z] = id_colour(5);
        assert_eq!(texels, [x, y, z, 10, x, y, z, 20]);
        assert_eq!(r.out.uploads, 1);
        let enable = &out[2];
        assert_eq!(
            (&*enable.name, enable.arg(0).as_i64()),
            ("glEnable", Some(gl::TEXTURE_3D))
        );
    }

    #[test]
    fn the_id_replay_names_textures_and_keeps_their_alpha() {
        let (r, calls) = rewritten(Mode::Id);
        // Frame 0's 7 draws are left out; the capture ends at frame 1's swap.
        assert_eq!(r.earlier_draws_left_out, 7);
        assert_eq!((r.uploads, r.notes.len()), (3, 0));
        assert_eq!(calls.len() as u64, r.calls_written);
        let last = calls.last().unwrap();
        assert_eq!((&*last.name, last.no), ("glXSwapBuffers", r.swap_call));
        let uploads: Vec<&Call> = named(&calls, "glTexImage2D").collect();
        for (up, name) in uploads.iter().zip([1u32, 1, 2]) {
            assert_eq!(up.arg(2).as_i64(), Some(RGBA8));
            let texels = up.arg(8).as_bytes().unwrap();
            assert!(texels.chunks(4).all(|t| t[..3] == id_colour(name)));
        }
        // Texture 2's checkerboard alpha is kept: 8 texels of 0, 8 of 255.
        let alpha: Vec<u8> = uploads[2].arg(8).as_bytes().unwrap()[3..]
            .iter()
            .step_by(4)
            .copied()
            .collect();
        assert_eq!(alpha.iter().filter(|&&a| a == 0).count(), 8);
        assert_eq!(alpha.iter().filter(|&&a| a == 255).count(), 8);
        let enables_blend = named(&calls, "glEnable").any(|c| c.arg(0).as_i64() == Some(gl::BLEND));
        assert!(!enables_blend);
        assert_eq!(
            named(&calls, "glEnableClientState")
                .filter(|c| c.arg(0).as_i64() == Some(gl::COLOR_ARRAY))
                .count(),
            0
        );
        assert!(named(&calls, "glDisableClientState").count() >= 2);
    }

    #[test]
    fn the_count_replay_adds_one_per_fragment() {
        let (_, calls) = rewritten(Mode::Count);
        for up in named(&calls, "glTexImage2D") {
            let texels = up.arg(8).as_bytes().unwrap();
            assert!(texels.chunks(4).all(|t| t[..3] == [1, 1, 1]));
        }
        let funcs: Vec<&Call> = named(&calls, "glBlendFunc").collect();
        assert!(funcs.len() >= 2);
        for f in funcs {
            assert_eq!(f.args, [Value::Enum(gl::ONE), Value::Enum(gl::ONE)]);
        }
        let blend: Vec<bool> = calls
            .iter()
            .filter(|c| c.arg(0).as_i64() == Some(gl::BLEND))
            .map(|c| &*c.name == "glEnable")
            .collect();
        assert!(!blend.is_empty() && blend.iter().all(|&on| on));
    }

    #[test]
    fn id_colours_name_textures_and_keep_the_clear_and_untextured_apart() {
        for name in [0, 1, 2, 255, 256, 70_000] {
            assert_eq!(name_of_colour(id_colour(name)), Some(Some(name)));
        }
        assert_eq!(name_of_colour([0, 0, 0]), None);
        assert_eq!(name_of_colour([255, 255, 255]), Some(None));
        assert_eq!(id_colour(UNTEXTURED_ID - 1), [255, 255, 255]);
        assert!(is_colour("glColor4ub") && is_colour("glColor3fv"));
        assert!(!is_colour("glColorPointer") && !is_colour("glColorMask"));
    }
}
