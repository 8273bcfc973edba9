//! Texture objects and texture units: glGenTextures / glBindTexture per
//! unit (glActiveTexture) and target (`GL_TEXTURE_2D`, `GL_TEXTURE_3D`),
//! the 2D uploads (glTexImage2D, glTexSubImage2D, glCompressedTexImage2D;
//! the 3D ones are [`super::volume`]'s) with their sizes, formats and mip
//! levels, the
//! unpack alignment (glPixelStorei), filters and wrap modes
//! (glTexParameter) and each unit's texture environment (glTexEnv).
//!
//! Level 0 is kept as RGBA8 for the front end's [`Texture`]; the texture
//! path builds its own mip chain and block-linear layout from it, as for
//! the loaders, and the levels the engine uploaded are recorded for the
//! summary. Texels the importer cannot read (a compressed upload, a pixel
//! type other than GL_UNSIGNED_BYTE) are the placeholder colour
//! [`PLACEHOLDER`], counted.

use super::args::{self, CallError};
use super::enums as gl;
use crate::{Filter, Texture};
use std::collections::{BTreeMap, HashMap};
use std::sync::Arc;
use wasp_gltrace::Call;

/// The colour of texels the capture does not let the importer read
/// (wasp): opaque magenta.
pub const PLACEHOLDER: [u8; 4] = [255, 0, 255, 255];

/// One uploaded mip level: its size, formats and whether its texels are
/// known.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Level {
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// Depth in texels (slices): 1 for a 2D texture.
    pub depth: u32,
    /// Internal format (a GL enum).
    pub internal: i64,
    /// Pixel format and type of the upload (compressed: the internal
    /// format and 0).
    pub format: i64,
    pub ty: i64,
    /// Compressed upload.
    pub compressed: bool,
}

/// A texture object.
#[derive(Clone, Debug, PartialEq)]
pub struct TexObject {
    /// The GL name.
    pub id: u32,
    /// The uploaded levels by level number.
    pub levels: BTreeMap<u32, Level>,
    /// Level 0 as RGBA8, row by row as uploaded (GL's t = 0 first), slice
    /// after slice for a 3D texture.
    pub rgba: Vec<u8>,
    /// Level 0's texels are the placeholder (why, for the summary).
    pub placeholder: Option<String>,
    /// GL_TEXTURE_MIN_FILTER, GL_TEXTURE_MAG_FILTER.
    pub min_filter: i64,
    pub mag_filter: i64,
    /// GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R.
    pub wrap: [i64; 3],
    /// Bound to GL_TEXTURE_3D (its level 0 is slices, [`super::volume`]).
    pub is_3d: bool,
}

impl TexObject {
    fn new(id: u32, is_3d: bool) -> Self {
        Self {
            id,
            is_3d,
            levels: BTreeMap::new(),
            rgba: Vec::new(),
            placeholder: None,
            min_filter: gl::NEAREST_MIPMAP_LINEAR,
            mag_filter: gl::LINEAR,
            wrap: [gl::REPEAT; 3],
        }
    }

    /// Whether GL_TEXTURE_MIN_FILTER reads the mip chain (a
    /// `*_MIPMAP_*` filter); `GL_NEAREST` and `GL_LINEAR` read level 0
    /// alone (OpenGL 1.2 specification, 3.8.7: "level zero" when the
    /// minification filter is NEAREST or LINEAR).
    pub fn mipmapped(&self) -> bool {
        !matches!(self.min_filter, gl::NEAREST | gl::LINEAR)
    }

    /// The texture instruction's filter from GL_TEXTURE_MIN_FILTER
    /// (wasp): a `*_MIPMAP_LINEAR` filter is trilinear, `GL_NEAREST` and
    /// `GL_NEAREST_MIPMAP_NEAREST` nearest, the others bilinear.
    pub fn filter(&self) -> Filter {
        match self.min_filter {
            gl::NEAREST_MIPMAP_LINEAR | gl::LINEAR_MIPMAP_LINEAR => Filter::Trilinear,
            gl::NEAREST | gl::NEAREST_MIPMAP_NEAREST => Filter::Nearest,
            _ => Filter::Bilinear,
        }
    }

    /// Whether level 0 has been uploaded.
    pub fn complete(&self) -> bool {
        self.levels.contains_key(&0) && !self.rgba.is_empty()
    }

    /// Level 0's depth (1 for a 2D texture).
    pub fn depth(&self) -> u32 {
        self.levels.get(&0).map_or(1, |l| l.depth)
    }

    /// Level 0 as the front end's texture: repeat if either wrap mode is
    /// GL_REPEAT (wasp: the texture path has one wrap mode for both axes).
    pub fn texture(&self) -> Texture {
        let l0 = &self.levels[&0];
        Texture {
            name: format!("gl texture {}", self.id),
            width: l0.width,
            height: l0.height,
            rgba: self.rgba.clone(),
            repeat: self.wrap[..2].contains(&gl::REPEAT),
        }
    }
}

/// A texture unit: its 2D and 3D bindings, which targets are enabled,
/// and its environment mode.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Unit {
    /// The texture bound to GL_TEXTURE_2D (0: the default texture).
    pub bound: u32,
    /// The texture bound to GL_TEXTURE_3D (0: the default texture).
    pub bound_3d: u32,
    /// glEnable(GL_TEXTURE_2D).
    pub enabled_2d: bool,
    /// glEnable(GL_TEXTURE_3D) (it takes precedence over 2D, as in GL).
    pub enabled_3d: bool,
    /// A texture target the model does not draw with is enabled
    /// (GL_TEXTURE_1D, cube map), or texture coordinate generation: its
    /// name.
    pub enabled_other: Vec<i64>,
    /// GL_TEXTURE_ENV_MODE.
    pub env_mode: i64,
}

/// The texture objects, the units and the pixel unpack state.
#[derive(Clone, Debug)]
pub struct Textures {
    /// Objects by name (copied on write: a frame keeps the objects its
    /// draws used as they were).
    pub objects: HashMap<u32, Arc<TexObject>>,
    /// The objects bound to GL_TEXTURE_3D, by name (a name is bound to
    /// one target; each target has its own default texture 0).
    pub objects_3d: HashMap<u32, Arc<TexObject>>,
    /// Texture units.
    pub units: Vec<Unit>,
    /// glActiveTexture's unit.
    pub active: usize,
    /// GL_UNPACK_ALIGNMENT.
    pub unpack_alignment: usize,
    /// GL_UNPACK_ROW_LENGTH (0: the upload's width).
    pub unpack_row_length: usize,
}

impl Textures {
    /// `units` texture units, nothing bound.
    pub fn new(units: usize) -> Self {
        Self {
            objects: HashMap::new(),
            objects_3d: HashMap::new(),
            units: vec![
                Unit {
                    bound: 0,
                    bound_3d: 0,
                    enabled_2d: false,
                    enabled_3d: false,
                    enabled_other: Vec::new(),
                    env_mode: gl::MODULATE,
                };
                units
            ],
            active: 0,
            unpack_alignment: 4,
            unpack_row_length: 0,
        }
    }

    /// The object bound to `target` (GL_TEXTURE_2D or GL_TEXTURE_3D) on
    /// the active unit (created on first use, as GL creates a texture
    /// object at its first bind).
    pub(super) fn bound_mut(&mut self, target: i64) -> &mut TexObject {
        let unit = &self.units[self.active];
        let is_3d = target == gl::TEXTURE_3D;
        let (id, objects) = if is_3d {
            (unit.bound_3d, &mut self.objects_3d)
        } else {
            (unit.bound, &mut self.objects)
        };
        Arc::make_mut(
            objects
                .entry(id)
                .or_insert_with(|| Arc::new(TexObject::new(id, is_3d))),
        )
    }

    /// glBindTexture(target, id) on the active unit, `target`
    /// GL_TEXTURE_2D or GL_TEXTURE_3D.
    pub fn bind(&mut self, target: i64, id: u32) {
        let unit = &mut self.units[self.active];
        let objects = if target == gl::TEXTURE_3D {
            unit.bound_3d = id;
            &mut self.objects_3d
        } else {
            unit.bound = id;
            &mut self.objects
        };
        objects
            .entry(id)
            .or_insert_with(|| Arc::new(TexObject::new(id, target == gl::TEXTURE_3D)));
    }

    /// glTexParameteri/f(target, pname, param); `Err` names a parameter
    /// the model does not use.
    pub fn parameter(&mut self, target: i64, pname: i64, param: i64) -> Result<(), String> {
        let t = self.bound_mut(target);
        match pname {
            gl::TEXTURE_MIN_FILTER => t.min_filter = param,
            gl::TEXTURE_MAG_FILTER => t.mag_filter = param,
            gl::TEXTURE_WRAP_S => t.wrap[0] = param,
            gl::TEXTURE_WRAP_T => t.wrap[1] = param,
            gl::TEXTURE_WRAP_R => t.wrap[2] = param,
            _ => return Err(gl::name(pname)),
        }
        Ok(())
    }

    /// glPixelStorei(pname, param); `Err` names a parameter not modelled.
    pub fn pixel_store(&mut self, pname: i64, param: i64) -> Result<(), String> {
        match (pname, param) {
            (gl::UNPACK_ALIGNMENT, 1 | 2 | 4 | 8) => self.unpack_alignment = param as usize,
            (gl::UNPACK_ROW_LENGTH, 0..) => self.unpack_row_length = param as usize,
            (gl::UNPACK_SKIP_ROWS | gl::UNPACK_SKIP_PIXELS, 0) => {}
            _ => return Err(format!("{}={param}", gl::name(pname))),
        }
        Ok(())
    }

    /// glTexImage2D(target, level, internalformat, width, height, border,
    /// format, type, pixels).
    pub fn image(&mut self, call: &Call) -> Result<(), CallError> {
        let (level, l) = read_level(call, false)?;
        let (width, height, format, ty) = (l.width, l.height, l.format, l.ty);
        let pixels = call.arg(8).as_bytes().map(<[u8]>::to_vec);
        let (align, row_len) = (self.unpack_alignment, self.unpack_row_length);
        let t = self.bound_mut(gl::TEXTURE_2D);
        t.levels.insert(level, l);
        if level == 0 {
            let n = width as usize * height as usize;
            match pixels {
                None => {
                    t.rgba = vec![0; n * 4];
                    t.placeholder = None;
                }
                Some(p) => match to_rgba(&p, width, height, format, ty, align, row_len) {
                    Ok(rgba) => {
                        t.rgba = rgba;
                        t.placeholder = None;
                    }
                    Err(why) => {
                        t.rgba = PLACEHOLDER.repeat(n);
                        t.placeholder = Some(why);
                    }
                },
            }
        }
        Ok(())
    }

    /// glTexSubImage2D(target, level, xoffset, yoffset, width, height,
    /// format, type, pixels): level 0's texels updated.
    pub fn sub_image(&mut self, call: &Call) -> Result<(), CallError> {
        let level = level_of(call, 1)?;
        let (x, y) = (args::count(call, 2)?, args::count(call, 3)?);
        let (w, h) = size_of(call, 4)?;
        let (format, ty) = (args::int(call, 6)?, args::int(call, 7)?);
        let (align, row_len) = (self.unpack_alignment, self.unpack_row_length);
        let pixels = call
            .arg(8)
            .as_bytes()
            .map(<[u8]>::to_vec)
            .unwrap_or_default();
        let t = self.bound_mut(gl::TEXTURE_2D);
        let Some(l) = t.levels.get(&level) else {
            return Err(CallError::at(
                call,
                format!("level {level} was never uploaded"),
            ));
        };
        if x + w as usize > l.width as usize || y + h as usize > l.height as usize {
            return Err(CallError::at(
                call,
                format!(
                    "rectangle {x},{y} {w}x{h} outside level {level}'s {}x{}",
                    l.width, l.height
                ),
            ));
        }
        if level != 0 || t.placeholder.is_some() {
            return Ok(());
        }
        let lw = l.width as usize;
        let rgba = to_rgba(&pixels, w, h, format, ty, align, row_len)
            .unwrap_or_else(|_| PLACEHOLDER.repeat(w as usize * h as usize));
        for row in 0..h as usize {
            let src = &rgba[row * w as usize * 4..(row + 1) * w as usize * 4];
            let at = ((y + row) * lw + x) * 4;
            t.rgba[at..at + src.len()].copy_from_slice(src);
        }
        Ok(())
    }

    /// glCompressedTexImage2D(target, level, internalformat, width,
    /// height, border, imageSize, data): the size and format kept, level 0's
    /// texels the placeholder.
    pub fn compressed_image(&mut self, call: &Call) -> Result<(), CallError> {
        let (level, l) = read_level(call, true)?;
        let (width, height, internal) = (l.width, l.height, l.internal);
        let t = self.bound_mut(gl::TEXTURE_2D);
        t.levels.insert(level, l);
        if level == 0 {
            t.rgba = PLACEHOLDER.repeat(width as usize * height as usize);
            t.placeholder = Some(format!("compressed format {}", gl::name(internal)));
        }
        Ok(())
    }
}

/// The level number and level of an upload (glTexImage2D's or
/// glCompressedTexImage2D's arguments: target, level, internal format,
/// width, height, ..., and for an uncompressed one the format and type).
fn read_level(call: &Call, compressed: bool) -> Result<(u32, Level), CallError> {
    let level = level_of(call, 1)?;
    let internal = args::int(call, 2)?;
    let (width, height) = size_of(call, 3)?;
    let (format, ty) = if compressed {
        (internal, 0)
    } else {
        (args::int(call, 6)?, args::int(call, 7)?)
    };
    let l = Level {
        width,
        height,
        depth: 1,
        internal,
        format,
        ty,
        compressed,
    };
    Ok((level, l))
}

pub(super) fn level_of(call: &Call, i: usize) -> Result<u32, CallError> {
    let l = args::count(call, i)?;
    u32::try_from(l)
        .ok()
        .filter(|&l| l < 16)
        .ok_or_else(|| CallError::at(call, format!("level {l}: expected 0 to 15")))
}

pub(super) fn size_of(call: &Call, i: usize) -> Result<(u32, u32), CallError> {
    let (w, h) = (args::count(call, i)?, args::count(call, i + 1)?);
    if w == 0 || h == 0 || w > 16384 || h > 16384 {
        return Err(CallError::at(
            call,
            format!("size {w}x{h}: expected 1 to 16384 texels each"),
        ));
    }
    Ok((w as u32, h as u32))
}

/// An upload's pixels as RGBA8: formats GL_RGBA, GL_RGB, GL_BGRA, GL_BGR,
/// GL_LUMINANCE (l, l, l, 1), GL_LUMINANCE_ALPHA (l, l, l, a) and
/// GL_ALPHA (1, 1, 1, a: the texture environment leaves the fragment's
/// colour) of GL_UNSIGNED_BYTE, rows `align`-aligned (GL_UNPACK_ALIGNMENT)
/// of `row_len` pixels (0: the width). `Err` says why not.
pub fn to_rgba(
    p: &[u8],
    width: u32,
    height: u32,
    format: i64,
    ty: i64,
    align: usize,
    row_len: usize,
) -> Result<Vec<u8>, String> {
    if ty != gl::UNSIGNED_BYTE {
        return Err(format!("pixel type {}", gl::name(ty)));
    }
    let n = match format {
        gl::RGBA | gl::BGRA => 4,
        gl::RGB | gl::BGR => 3,
        gl::LUMINANCE_ALPHA => 2,
        gl::LUMINANCE | gl::ALPHA => 1,
        _ => return Err(format!("pixel format {}", gl::name(format))),
    };
    let (w, h) = (width as usize, height as usize);
    let row = (if row_len == 0 { w } else { row_len } * n).div_ceil(align) * align;
    let need = row * (h - 1) + w * n;
    if p.len() < need {
        return Err(format!("{} bytes of pixels, {need} expected", p.len()));
    }
    let mut out = Vec::with_capacity(w * h * 4);
    for y in 0..h {
        for px in p[y * row..y * row + w * n].chunks_exact(n) {
            out.extend_from_slice(&match format {
                gl::RGBA => [px[0], px[1], px[2], px[3]],
                gl::BGRA => [px[2], px[1], px[0], px[3]],
                gl::RGB => [px[0], px[1], px[2], 255],
                gl::BGR => [px[2], px[1], px[0], 255],
                gl::LUMINANCE_ALPHA => [px[0], px[0], px[0], px[1]],
                gl::LUMINANCE => [px[0], px[0], px[0], 255],
                _ => [255, 255, 255, px[0]],
            });
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::super::args::test_calls::*;
    use super::*;
    use wasp_gltrace::Value;

    fn tex_image(no: u64, level: i64, w: i64, h: i64, format: i64, ty: i64, px: Vec<u8>) -> Call {
        let i = Value::SInt;
        call(
            no,
            "glTexImage2D",
            vec![
                e(gl::TEXTURE_2D),
                i(level),
                e(format),
                i(w),
                i(h),
                i(0),
                e(format),
                e(ty),
                Value::Blob(px),
            ],
        )
    }

    /// glTexSubImage2D of level 0 at (x, y), w x h, GL_ALPHA bytes `px`.
    fn sub_alpha(no: u64, [x, y, w, h]: [i64; 4], px: Vec<u8>) -> Call {
        let i = Value::SInt;
        let a = vec![e(gl::TEXTURE_2D), i(0), i(x), i(y), i(w), i(h)];
        let b = vec![e(gl::ALPHA), e(gl::UNSIGNED_BYTE), Value::Blob(px)];
        call(no, "glTexSubImage2D", [a, b].concat())
    }

    #[test]
    fn uploads_keep_levels_formats_and_level_zero_as_rgba() {
        let mut t = Textures::new(2);
        t.active = 1;
        t.bind(gl::TEXTURE_2D, 5);
        // RGB 3x2, alignment 4: rows of 9 bytes padded to 12.
        let mut px = Vec::new();
        for y in 0..2u8 {
            for x in 0..3u8 {
                px.extend_from_slice(&[x, y, 7]);
            }
            px.extend_from_slice(&[0, 0, 0]);
        }
        t.image(&tex_image(1, 0, 3, 2, gl::RGB, gl::UNSIGNED_BYTE, px))
            .unwrap();
        t.image(&tex_image(
            2,
            1,
            1,
            1,
            gl::LUMINANCE,
            gl::UNSIGNED_BYTE,
            vec![9],
        ))
        .unwrap();
        let o = &t.objects[&5];
        assert_eq!(o.levels.keys().copied().collect::<Vec<_>>(), [0, 1]);
        assert_eq!(&o.rgba[4 * 4..4 * 5], &[1, 1, 7, 255], "texel (1, 1)");
        assert_eq!(o.texture().width, 3);
        assert_eq!(t.units[0].bound, 0, "unit 0 untouched");
        // A sub-image on level 0, then the filter and wrap parameters.
        t.pixel_store(gl::UNPACK_ALIGNMENT, 1).unwrap();
        t.sub_image(&sub_alpha(3, [2, 1, 1, 1], vec![33])).unwrap();
        assert_eq!(&t.objects[&5].rgba[5 * 4..6 * 4], &[255, 255, 255, 33]);
        t.parameter(
            gl::TEXTURE_2D,
            gl::TEXTURE_MIN_FILTER,
            gl::LINEAR_MIPMAP_LINEAR,
        )
        .unwrap();
        assert_eq!(t.objects[&5].filter(), Filter::Trilinear);
        t.parameter(gl::TEXTURE_2D, gl::TEXTURE_MIN_FILTER, gl::NEAREST)
            .unwrap();
        assert_eq!(t.objects[&5].filter(), Filter::Nearest);
        t.parameter(gl::TEXTURE_2D, gl::TEXTURE_WRAP_S, 0x812F)
            .unwrap();
        t.parameter(gl::TEXTURE_2D, gl::TEXTURE_WRAP_T, 0x812F)
            .unwrap();
        assert!(!t.objects[&5].texture().repeat);
        assert!(
            t.parameter(gl::TEXTURE_2D, 0x8191, 1).is_err(),
            "GL_GENERATE_MIPMAP is counted"
        );
        let bad = t.sub_image(&sub_alpha(4, [2, 1, 5, 1], vec![0; 5]));
        assert!(bad.unwrap_err().message.contains("outside"));
    }

    #[test]
    fn unreadable_texels_are_the_placeholder_and_say_why() {
        let mut t = Textures::new(1);
        t.bind(gl::TEXTURE_2D, 2);
        t.image(&tex_image(1, 0, 2, 1, gl::RGBA, 0x8033, vec![0; 4]))
            .unwrap();
        assert_eq!(&t.objects[&2].rgba[..4], &PLACEHOLDER);
        assert!(t.objects[&2]
            .placeholder
            .as_deref()
            .unwrap()
            .contains("pixel type"));
        let i = Value::SInt;
        t.compressed_image(&call(
            2,
            "glCompressedTexImage2D",
            vec![
                e(gl::TEXTURE_2D),
                i(0),
                e(0x83F1),
                i(8),
                i(4),
                i(0),
                i(16),
                Value::Blob(vec![0; 16]),
            ],
        ))
        .unwrap();
        let o = &t.objects[&2];
        assert!(o.levels[&0].compressed && o.rgba.len() == 8 * 4 * 4);
        assert!(o.placeholder.as_deref().unwrap().contains("compressed"));
        assert!(to_rgba(&[1, 2], 1, 1, gl::RGBA, gl::UNSIGNED_BYTE, 4, 0)
            .unwrap_err()
            .contains("bytes"));
    }
}
