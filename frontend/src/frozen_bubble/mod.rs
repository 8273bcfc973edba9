//! Frozen Bubble (2D puzzle, the paper's "Candy Crush" case): the one-player
//! screen at the start of a level of `frozen-bubble-data`.
//!
//! # Data layout
//!
//! The data root passed to [`load`] is the game's data directory inside the
//! unpacked Debian package: `<unpacked frozen-bubble-data>/usr/share/games/frozen-bubble`
//! ([`DATA_SUBDIR`] under the directory `dpkg-deb -x` unpacked the package
//! into; with `wasp scenes fetch`, `$WASP_SCENES/frozen-bubble/` + [`DATA_SUBDIR`]).
//! Files read:
//!
//! - `data/<levelset>`: the level set; `def.map` names it (`levels`, the
//!   game's 100 levels).
//! - `gfx/back_one_player.png` (640x480 background), `gfx/balls/bubble-N.gif`
//!   (N = 1..8, 32x32, GIF89a with a transparent colour; decoded here, see
//!   [`decode_gif`]), `gfx/compressor_main.png`,
//!   `gfx/shooter.png`, `gfx/on_top_next.png`, `gfx/dot_red.png`,
//!   `gfx/dot_green.png`, `gfx/pinguins/anime-shooter_p1_0020.png`.
//!
//! Data licence: GPL-2 (`debian/copyright` of `frozen-bubble-data`).
//!
//! # Level set format
//!
//! Plain text. A level is a block of non-blank lines, one line per bubble
//! row from the top; blank lines separate levels (runs of blank lines
//! count once). A line is whitespace-separated cells, one per column: `-`
//! (any token containing `-`) is empty, a digit `0`..`7` a bubble of that
//! colour (drawn with `bubble-<digit+1>.gif`). Even rows (0, 2, ...) have 8
//! columns, odd rows 7, shifted right by half a bubble (the file indents
//! them by two spaces); the playfield has 12 rows, the shipped levels fill
//! the top 10.
//!
//! # Scene
//!
//! The game draws with SDL blits on a 640x480 screen; the scene is that
//! screen at the start of a one-player level, in the game's blit order
//! (painter's order), positions in screen pixels (y down), one sprite = one
//! textured quad (2 triangles), z = draw order:
//!
//! 1. the background (`Blend::Opaque`);
//! 2. the compressor at the top of the playfield (x centred on 318, bottom
//!    at the playfield top 44, so it starts 7 pixels above the screen);
//! 3. the level's bubbles: column `c`, row `r` at
//!    x = 190 + 32 c + 16 (r odd), y = 44 + 28 r (32-pixel bubbles, rows
//!    7/8 of a bubble apart);
//! 4. the new-row progress dots (9 dots, 7x7, from (447, 28), one red);
//! 5. the next bubble at (302, 440) with its frame `on_top_next` at
//!    (299, 437), the bubble to launch at (302, 390);
//! 6. the launcher (`shooter.png` pointing up, cropped to its opaque
//!    bounding box as the game crops its rotated copies, box at (268, 356));
//! 7. the penguin (first frame of its idle animation) at (404, 420).
//!
//! Everything but the background is `Blend::AlphaBlend`. The layout
//! constants are those of the game's `Games::FrozenBubble::Stuff` (%POS_1P,
//! $BUBBLE_SIZE, $ROW_SIZE); the colours of the bubble to launch and of the
//! next bubble are random in the game: here the level's most and second
//! most frequent colours. Not drawn: text (level number and time, rendered
//! with a system font), the "hurry" warning, animations.
//!
//! Camera selector: `level:N` (1-based, in level-set order). The ortho view
//! keeps the 4:3 aspect of the 640x480 screen: it is the screen, widened
//! (pillarbox) or heightened (letterbox) around its centre to the frame's
//! aspect, so the frame shows the whole screen undistorted. Materials use
//! the `sprite` template with [`Filter::Bilinear`] (a GPU port scales the
//! 640x480 screen to the frame).

use super::bytes::Bytes;
use super::def::SceneDef;
use super::teeworlds::program;
use super::{Blend, Camera, Filter, Material, Mesh, Scene, SceneError, Texture};
use std::path::{Path, PathBuf};

/// The Debian package holding the data.
pub const PACKAGE: &str = "frozen-bubble-data";
/// The data root inside the unpacked package.
pub const DATA_SUBDIR: &str = "usr/share/games/frozen-bubble";
/// The game's screen (pixels).
pub const SCREEN: (f32, f32) = (640.0, 480.0);
/// Bubble size (pixels).
pub const BUBBLE_SIZE: f32 = 32.0;
/// Distance between bubble rows: 7/8 of a bubble.
pub const ROW_SIZE: f32 = BUBBLE_SIZE * 7.0 / 8.0;
/// Left edge of the one-player playfield.
pub const LEFT_LIMIT: f32 = 190.0;
/// Right edge of the one-player playfield.
pub const RIGHT_LIMIT: f32 = 446.0;
/// Top edge of the one-player playfield.
pub const TOP_LIMIT: f32 = 44.0;
/// y of the bubble to launch.
pub const INITIAL_BUBBLE_Y: f32 = 390.0;
/// Top-left of the launcher's 100x100 box.
pub const CANON: (f32, f32) = (268.0, 356.0);
/// Top-left of the penguin.
pub const PENGUIN: (f32, f32) = (LEFT_LIMIT + 214.0, 420.0);
/// Top-left of the next bubble.
pub const NEXT_BUBBLE: (f32, f32) = (LEFT_LIMIT + 112.0, 440.0);
/// Offset of the next bubble's frame from the next bubble.
pub const ON_TOP_NEXT_REL: (f32, f32) = (-3.0, -3.0);
/// Horizontal centre of the compressor.
pub const COMPRESSOR_X: f32 = 318.0;
/// Top-left of the first progress dot.
pub const PROGRESS: (f32, f32) = (447.0, 28.0);
/// Shots between new rows in one-player games; the game shows this + 1 dots.
pub const TIME_APPEARS_NEW_ROOT: usize = 8;
/// Rows of the playfield.
pub const ROWS: usize = 12;
/// Bubble colours.
pub const COLOURS: u8 = 8;

// ---------------------------------------------------------------------------
// Level sets
// ---------------------------------------------------------------------------

/// What a cell holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Bubble {
    /// Column (0..8 on even rows, 0..7 on odd rows).
    pub col: u8,
    /// Row from the top.
    pub row: u8,
    /// Colour 0..8.
    pub colour: u8,
}

/// One level: its bubbles in file order.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Level {
    /// Bubbles.
    pub bubbles: Vec<Bubble>,
    /// Byte offset of the level's first line in the file.
    pub offset: usize,
}

/// Parse a level set (see the module documentation); `path` names it in
/// errors, which carry the byte offset of the offending cell.
pub fn parse_levels(path: &Path, text: &[u8]) -> Result<Vec<Level>, SceneError> {
    let mut levels = Vec::new();
    let mut current: Option<Level> = None;
    let mut row = 0usize;
    let mut pos = 0usize;
    for line in text.split_inclusive(|&b| b == b'\n') {
        let start = pos;
        pos += line.len();
        let body = line.strip_suffix(b"\n").unwrap_or(line);
        let body = body.strip_suffix(b"\r").unwrap_or(body);
        if body.iter().all(|b| b.is_ascii_whitespace()) {
            if let Some(l) = current.take() {
                levels.push(l);
                row = 0;
            }
            continue;
        }
        let level = current.get_or_insert_with(|| Level {
            bubbles: Vec::new(),
            offset: start,
        });
        if row >= ROWS {
            return Err(SceneError::at(
                path,
                start as u64,
                format!(
                    "level {}: row {} (the playfield has {ROWS} rows)",
                    levels.len() + 1,
                    row + 1
                ),
            ));
        }
        let mut col = 0usize;
        let mut i = 0usize;
        while i < body.len() {
            if body[i].is_ascii_whitespace() {
                i += 1;
                continue;
            }
            let tok_start = i;
            while i < body.len() && !body[i].is_ascii_whitespace() {
                i += 1;
            }
            let tok = &body[tok_start..i];
            let at = (start + tok_start) as u64;
            let cols = 8 - row % 2;
            if !tok.contains(&b'-') {
                let colour = match tok {
                    [d @ b'0'..=b'7'] => d - b'0',
                    _ => {
                        return Err(SceneError::at(
                            path,
                            at,
                            format!(
                                "level {}: cell {:?}: expected `-` or a colour 0..7",
                                levels.len() + 1,
                                String::from_utf8_lossy(tok)
                            ),
                        ))
                    }
                };
                if col >= cols {
                    return Err(SceneError::at(
                        path,
                        at,
                        format!(
                            "level {}: bubble in column {} of row {} (that row has {cols} columns)",
                            levels.len() + 1,
                            col + 1,
                            row + 1
                        ),
                    ));
                }
                level.bubbles.push(Bubble {
                    col: col as u8,
                    row: row as u8,
                    colour,
                });
            }
            col += 1;
        }
        row += 1;
    }
    if let Some(l) = current.take() {
        levels.push(l);
    }
    Ok(levels)
}

/// Top-left of the bubble at column `col`, row `row` (row parity as at the
/// start of a level).
pub fn bubble_position(col: u8, row: u8) -> (f32, f32) {
    (
        LEFT_LIMIT + col as f32 * BUBBLE_SIZE + (row % 2) as f32 * BUBBLE_SIZE / 2.0,
        TOP_LIMIT + row as f32 * ROW_SIZE,
    )
}

// ---------------------------------------------------------------------------
// GIF
// ---------------------------------------------------------------------------

/// Largest GIF canvas accepted (pixels).
const MAX_GIF_PIXELS: usize = 4096 * 4096;

/// GIF data sub-blocks up to the terminator, concatenated.
fn sub_blocks(r: &mut Bytes, what: &str) -> Result<Vec<u8>, SceneError> {
    let mut out = Vec::new();
    loop {
        let n = r.u8(what)? as usize;
        if n == 0 {
            return Ok(out);
        }
        out.extend_from_slice(r.take(n, what)?);
    }
}

/// LZW-decode GIF image data to at most `limit` colour indices.
fn lzw_decode(data: &[u8], min_size: u8, limit: usize) -> Result<Vec<u8>, String> {
    let clear = 1u16 << min_size;
    let end = clear + 1;
    let mut prefix = vec![0u16; 4096];
    let mut suffix = vec![0u8; 4096];
    let mut first = vec![0u8; 4096];
    for c in 0..clear {
        suffix[c as usize] = c as u8;
        first[c as usize] = c as u8;
    }
    let mut size = min_size as u32 + 1;
    let mut next = clear + 2;
    let mut prev: Option<u16> = None;
    let mut out = Vec::with_capacity(limit.min(1 << 20));
    let mut stack = Vec::with_capacity(4096);
    let (mut acc, mut bits, mut byte) = (0u32, 0u32, 0usize);
    loop {
        while bits < size {
            let Some(&b) = data.get(byte) else {
                return Err(format!(
                    "image data ends (no end code) after {} of {limit} pixels",
                    out.len()
                ));
            };
            acc |= (b as u32) << bits;
            bits += 8;
            byte += 1;
        }
        let code = (acc & ((1 << size) - 1)) as u16;
        acc >>= size;
        bits -= size;
        if code == clear {
            size = min_size as u32 + 1;
            next = clear + 2;
            prev = None;
            continue;
        }
        if code == end {
            return Ok(out);
        }
        let Some(p) = prev else {
            if code >= clear {
                return Err(format!(
                    "LZW code {code} after a clear code (literals < {clear})"
                ));
            }
            out.push(code as u8);
            prev = Some(code);
            if out.len() >= limit {
                return Ok(out);
            }
            continue;
        };
        // The string for `code` (or, for the code being defined, prev's
        // string plus its first byte).
        let (walk, extra) = if code < next {
            (code, None)
        } else if code == next && next < 4096 {
            (p, Some(first[p as usize]))
        } else {
            return Err(format!("LZW code {code} is not defined yet (next {next})"));
        };
        stack.clear();
        let mut c = walk;
        while c >= clear {
            stack.push(suffix[c as usize]);
            c = prefix[c as usize];
        }
        stack.push(c as u8);
        let head = c as u8;
        out.extend(stack.iter().rev());
        if let Some(x) = extra {
            out.push(x);
        }
        if next < 4096 {
            prefix[next as usize] = p;
            suffix[next as usize] = head;
            first[next as usize] = first[p as usize];
            next += 1;
            if next == (1 << size) && size < 12 {
                size += 1;
            }
        }
        prev = Some(code);
        if out.len() >= limit {
            out.truncate(limit);
            return Ok(out);
        }
    }
}

/// Decode the first image of a GIF (87a/89a) into an RGBA texture of the
/// logical screen size; the transparent colour (graphic control extension)
/// and pixels outside the frame are transparent black. Errors name the
/// file and the byte offset.
pub fn decode_gif(path: &Path, bytes: &[u8]) -> Result<(u32, u32, Vec<u8>), SceneError> {
    let mut r = Bytes::new(bytes, path);
    let sig = r.take(6, "GIF signature")?.to_vec();
    if sig != b"GIF87a" && sig != b"GIF89a" {
        return Err(r.err(0, format!("not a GIF: signature {sig:?}")));
    }
    let sw = r.u16("screen width")? as usize;
    let sh = r.u16("screen height")? as usize;
    if sw == 0 || sh == 0 || sw * sh > MAX_GIF_PIXELS {
        return Err(r.err(
            6,
            format!("GIF screen {sw}x{sh}: expected 1..{MAX_GIF_PIXELS} pixels"),
        ));
    }
    let flags = r.u8("screen flags")?;
    r.take(2, "background and aspect")?;
    let global = if flags & 0x80 != 0 {
        let n = 2usize << (flags & 7);
        Some(r.take(3 * n, "global colour table")?.to_vec())
    } else {
        None
    };
    let mut transparent: Option<u8> = None;
    loop {
        let at = r.pos();
        match r.u8("block introducer")? {
            0x21 => {
                let label = r.u8("extension label")?;
                let body = sub_blocks(&mut r, "extension")?;
                if label == 0xf9 {
                    if body.len() < 4 {
                        return Err(r.err(at, "graphic control extension shorter than 4 bytes"));
                    }
                    transparent = (body[0] & 1 != 0).then_some(body[3]);
                }
            }
            0x2c => {
                let left = r.u16("image left")? as usize;
                let top = r.u16("image top")? as usize;
                let w = r.u16("image width")? as usize;
                let h = r.u16("image height")? as usize;
                let iflags = r.u8("image flags")?;
                let local = if iflags & 0x80 != 0 {
                    let n = 2usize << (iflags & 7);
                    Some(r.take(3 * n, "local colour table")?.to_vec())
                } else {
                    None
                };
                let table = local
                    .or(global)
                    .ok_or_else(|| r.err(at, "image without a local or a global colour table"))?;
                let min_at = r.pos();
                let min_size = r.u8("LZW minimum code size")?;
                if !(1..=11).contains(&min_size) {
                    return Err(r.err(min_at, format!("LZW minimum code size {min_size}")));
                }
                let data_at = r.pos();
                let data = sub_blocks(&mut r, "image data")?;
                if w * h > MAX_GIF_PIXELS {
                    return Err(r.err(at, format!("GIF image {w}x{h} too large")));
                }
                let idx = lzw_decode(&data, min_size, w * h).map_err(|m| r.err(data_at, m))?;
                if idx.len() < w * h {
                    return Err(r.err(
                        data_at,
                        format!("image data holds {} of {}x{} pixels", idx.len(), w, h),
                    ));
                }
                // Interlaced rows come in 4 passes.
                let rows: Vec<usize> = if iflags & 0x40 != 0 {
                    (0..h)
                        .step_by(8)
                        .chain((4..h).step_by(8))
                        .chain((2..h).step_by(4))
                        .chain((1..h).step_by(2))
                        .collect()
                } else {
                    (0..h).collect()
                };
                let colours = table.len() / 3;
                let mut rgba = vec![0u8; sw * sh * 4];
                for (k, &y) in rows.iter().enumerate() {
                    for x in 0..w {
                        let i = idx[k * w + x];
                        let (sx, sy) = (left + x, top + y);
                        if Some(i) == transparent || sx >= sw || sy >= sh {
                            continue;
                        }
                        if i as usize >= colours {
                            return Err(r.err(
                                data_at,
                                format!("colour index {i} outside the {colours}-colour table"),
                            ));
                        }
                        let c = &table[3 * i as usize..3 * i as usize + 3];
                        let o = 4 * (sy * sw + sx);
                        rgba[o..o + 4].copy_from_slice(&[c[0], c[1], c[2], 255]);
                    }
                }
                return Ok((sw as u32, sh as u32, rgba));
            }
            0x3b => return Err(r.err(at, "GIF ends (trailer) before any image")),
            b => {
                return Err(r.err(
                    at,
                    format!("unknown GIF block 0x{b:02x} (expected 0x21, 0x2c or 0x3b)"),
                ))
            }
        }
    }
}

// ---------------------------------------------------------------------------
// Scene
// ---------------------------------------------------------------------------

fn load_image(gfx: &Path, rel: &str) -> Result<Texture, SceneError> {
    let path = gfx.join(rel);
    let bytes = std::fs::read(&path)
        .map_err(|e| SceneError::in_file(&path, format!("cannot read: {e}")))?;
    let (width, height, rgba) = if rel.ends_with(".gif") {
        decode_gif(&path, &bytes)?
    } else {
        let img = image::load_from_memory_with_format(&bytes, image::ImageFormat::Png)
            .map_err(|e| SceneError::in_file(&path, format!("PNG: {e}")))?
            .to_rgba8();
        let (w, h) = img.dimensions();
        (w, h, img.into_raw())
    };
    if width == 0 || height == 0 {
        return Err(SceneError::in_file(&path, "image has no pixels"));
    }
    Ok(Texture {
        name: format!("gfx/{rel}"),
        width,
        height,
        rgba,
        repeat: false,
    })
}

/// Crop a texture to the bounding box of its non-transparent texels;
/// returns the crop's offset. Fully transparent textures stay as they are.
fn crop_to_alpha(t: &mut Texture) -> (u32, u32) {
    let (w, h) = (t.width as usize, t.height as usize);
    let opaque = |x: usize, y: usize| t.rgba[4 * (y * w + x) + 3] != 0;
    let (mut x0, mut y0, mut x1, mut y1) = (w, h, 0, 0);
    for y in 0..h {
        for x in 0..w {
            if opaque(x, y) {
                x0 = x0.min(x);
                y0 = y0.min(y);
                x1 = x1.max(x + 1);
                y1 = y1.max(y + 1);
            }
        }
    }
    if x0 >= x1 || y0 >= y1 {
        return (0, 0);
    }
    let mut rgba = Vec::with_capacity((x1 - x0) * (y1 - y0) * 4);
    for y in y0..y1 {
        rgba.extend_from_slice(&t.rgba[4 * (y * w + x0)..4 * (y * w + x1)]);
    }
    t.rgba = rgba;
    t.width = (x1 - x0) as u32;
    t.height = (y1 - y0) as u32;
    (x0 as u32, y0 as u32)
}

/// Parse `level:N` (1-based).
pub fn parse_camera(s: &str) -> Option<usize> {
    s.strip_prefix("level:")
        .and_then(|n| n.parse::<usize>().ok())
        .filter(|&n| n >= 1)
}

/// The ortho view of the 640x480 screen at a frame aspect (width/height),
/// keeping the screen's aspect: (left, top, width, height).
pub fn screen_view(aspect: f32) -> (f32, f32, f32, f32) {
    let (sw, sh) = SCREEN;
    if aspect >= sw / sh {
        let w = sh * aspect;
        ((sw - w) / 2.0, 0.0, w, sh)
    } else {
        let h = sw / aspect;
        (0.0, (sh - h) / 2.0, sw, h)
    }
}

/// Path of a level set under the data root.
pub fn levels_path(data_root: &Path, name: &str) -> Result<PathBuf, SceneError> {
    if name.is_empty()
        || !name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-' || c == '.')
        || name.starts_with('.')
    {
        return Err(SceneError::in_file(
            data_root.join("data"),
            format!("level set {name:?}: expected a file name under data/, such as `levels`"),
        ));
    }
    Ok(data_root.join("data").join(name))
}

/// Colours in decreasing frequency (ties: lower colour first).
fn colours_by_frequency(level: &Level) -> Vec<u8> {
    let mut count = [0usize; COLOURS as usize];
    for b in &level.bubbles {
        count[b.colour as usize] += 1;
    }
    let mut c: Vec<u8> = (0..COLOURS).filter(|&c| count[c as usize] > 0).collect();
    c.sort_by_key(|&c| std::cmp::Reverse(count[c as usize]));
    c
}

/// Load a Frozen Bubble scene: `def.map` names the level set under `data/`
/// (`levels`), `def.camera` is `level:N`. See the module documentation.
pub fn load(data_root: &Path, def: &SceneDef) -> Result<Scene, SceneError> {
    let lpath = levels_path(data_root, &def.map)?;
    let text = std::fs::read(&lpath)
        .map_err(|e| SceneError::in_file(&lpath, format!("cannot read: {e}")))?;
    let levels = parse_levels(&lpath, &text)?;
    let n = parse_camera(&def.camera).ok_or_else(|| {
        SceneError::in_file(
            &lpath,
            format!(
                "scene `{}`: camera {:?}: expected `level:N` (N from 1)",
                def.name, def.camera
            ),
        )
    })?;
    let level = levels.get(n - 1).ok_or_else(|| {
        SceneError::in_file(
            &lpath,
            format!(
                "scene `{}`: level {n}: the level set has {} levels",
                def.name,
                levels.len()
            ),
        )
    })?;
    build(data_root, &lpath, level, n, def)
}

/// Sprites of a scene under construction: one texture and one material per
/// image file, one quad mesh per sprite, z = draw order.
struct Sprites<'a> {
    gfx: PathBuf,
    lpath: &'a Path,
    template: Option<&'a str>,
    textures: Vec<Texture>,
    materials: Vec<Material>,
    meshes: Vec<Mesh>,
    /// (file, material, texture, crop offset)
    loaded: Vec<(String, usize, usize, (u32, u32))>,
}

impl Sprites<'_> {
    /// The material, texture and crop offset of an image file.
    fn image(
        &mut self,
        rel: &str,
        blend: Blend,
        crop: bool,
    ) -> Result<(usize, usize, (u32, u32)), SceneError> {
        if let Some(e) = self.loaded.iter().find(|e| e.0 == rel) {
            return Ok((e.1, e.2, e.3));
        }
        let mut t = load_image(&self.gfx, rel)?;
        let off = if crop { crop_to_alpha(&mut t) } else { (0, 0) };
        self.textures.push(t);
        let ti = self.textures.len() - 1;
        let shader = program(self.template, Some(ti), Filter::Bilinear)
            .map_err(|m| SceneError::in_file(self.lpath, m))?;
        self.materials.push(Material {
            name: format!("frozen-bubble:{rel}"),
            blend,
            shader,
        });
        let mi = self.materials.len() - 1;
        self.loaded.push((rel.to_string(), mi, ti, off));
        Ok((mi, ti, off))
    }

    /// Size (pixels) of an image file, once cropped.
    fn size(&mut self, rel: &str, blend: Blend) -> Result<(f32, f32), SceneError> {
        let (_, ti, _) = self.image(rel, blend, false)?;
        Ok((
            self.textures[ti].width as f32,
            self.textures[ti].height as f32,
        ))
    }

    /// Draw an image file with its top-left corner (before cropping) at x, y.
    fn draw(
        &mut self,
        rel: &str,
        x: f32,
        y: f32,
        blend: Blend,
        crop: bool,
    ) -> Result<(), SceneError> {
        let (mi, ti, off) = self.image(rel, blend, crop)?;
        let (w, h) = (
            self.textures[ti].width as f32,
            self.textures[ti].height as f32,
        );
        let (x, y) = (x + off.0 as f32, y + off.1 as f32);
        let z = self.meshes.len() as f32;
        self.meshes.push(Mesh {
            positions: vec![[x, y, z], [x + w, y, z], [x + w, y + h, z], [x, y + h, z]],
            uv: vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
            uv2: None,
            indices: vec![0, 1, 2, 0, 2, 3],
            material: mi,
        });
        Ok(())
    }
}

fn build(
    data_root: &Path,
    lpath: &Path,
    level: &Level,
    n: usize,
    def: &SceneDef,
) -> Result<Scene, SceneError> {
    let mut s = Sprites {
        gfx: data_root.join("gfx"),
        lpath,
        template: def.shader.as_deref(),
        textures: Vec::new(),
        materials: Vec::new(),
        meshes: Vec::new(),
        loaded: Vec::new(),
    };
    let ab = Blend::AlphaBlend;
    s.draw("back_one_player.png", 0.0, 0.0, Blend::Opaque, false)?;
    // The compressor: centred on COMPRESSOR_X, its bottom at the playfield top.
    let (cw, ch) = s.size("compressor_main.png", ab)?;
    s.draw(
        "compressor_main.png",
        COMPRESSOR_X - (cw / 2.0).floor(),
        TOP_LIMIT - ch,
        ab,
        false,
    )?;
    for b in &level.bubbles {
        let (x, y) = bubble_position(b.col, b.row);
        s.draw(
            &format!("balls/bubble-{}.gif", b.colour + 1),
            x,
            y,
            ab,
            false,
        )?;
    }
    for i in 0..=TIME_APPEARS_NEW_ROOT {
        let dot = if i == 0 {
            "dot_red.png"
        } else {
            "dot_green.png"
        };
        // Dots one pixel apart.
        let (_, dh) = s.size(dot, ab)?;
        s.draw(
            dot,
            PROGRESS.0,
            PROGRESS.1 + (dh + 1.0) * i as f32,
            ab,
            false,
        )?;
    }
    let colours = colours_by_frequency(level);
    let launch = colours.first().copied().unwrap_or(0);
    let next = colours.get(1).copied().unwrap_or(launch);
    s.draw(
        &format!("balls/bubble-{}.gif", next + 1),
        NEXT_BUBBLE.0,
        NEXT_BUBBLE.1,
        ab,
        false,
    )?;
    s.draw(
        "on_top_next.png",
        NEXT_BUBBLE.0 + ON_TOP_NEXT_REL.0,
        NEXT_BUBBLE.1 + ON_TOP_NEXT_REL.1,
        ab,
        false,
    )?;
    s.draw(
        &format!("balls/bubble-{}.gif", launch + 1),
        (LEFT_LIMIT + RIGHT_LIMIT) / 2.0 - BUBBLE_SIZE / 2.0,
        INITIAL_BUBBLE_Y,
        ab,
        false,
    )?;
    s.draw("shooter.png", CANON.0, CANON.1, ab, true)?;
    s.draw(
        "pinguins/anime-shooter_p1_0020.png",
        PENGUIN.0,
        PENGUIN.1,
        ab,
        false,
    )?;
    let (left, top, width, height) = screen_view(def.width as f32 / def.height as f32);
    Ok(Scene {
        name: format!("frozen-bubble:{}:level:{n}", def.map),
        source: format!(
            "{PACKAGE} 2.212 (Debian), data/{} level {n} and gfx/ (GPL-2)",
            def.map
        ),
        meshes: s.meshes,
        materials: s.materials,
        textures: s.textures,
        camera: Camera::Ortho {
            left,
            top,
            width,
            height,
        },
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    const TINY: &str = "\
6   6   4   -   -   -   -   -
  -   7   -   -   -   -   -

-   -   -   -   -   -   -   0


1   2   3   4   5   6   7   0
  1   2   3   4   5   6   7
";

    #[test]
    fn parses_levels() {
        let l = parse_levels(Path::new("levels"), TINY.as_bytes()).unwrap();
        assert_eq!(l.len(), 3);
        assert_eq!(
            l[0].bubbles,
            vec![
                Bubble {
                    col: 0,
                    row: 0,
                    colour: 6
                },
                Bubble {
                    col: 1,
                    row: 0,
                    colour: 6
                },
                Bubble {
                    col: 2,
                    row: 0,
                    colour: 4
                },
                Bubble {
                    col: 1,
                    row: 1,
                    colour: 7
                },
            ]
        );
        assert_eq!(
            l[1].bubbles,
            vec![Bubble {
                col: 7,
                row: 0,
                colour: 0
            }]
        );
        assert_eq!(l[2].bubbles.len(), 15);
        assert_eq!(l[2].offset, TINY.find("1   2").unwrap());
        assert_eq!(bubble_position(1, 1), (190.0 + 32.0 + 16.0, 44.0 + 28.0));
    }

    #[test]
    fn level_errors_name_the_cell() {
        let text = b"-  -  9\n";
        let e = parse_levels(Path::new("levels"), text).unwrap_err();
        assert_eq!(e.offset, Some(6));
        assert!(e.message.contains("\"9\""), "{e}");
        // Odd rows have 7 columns.
        let text = b"0 0 0 0 0 0 0 0\n0 0 0 0 0 0 0 0\n";
        let e = parse_levels(Path::new("levels"), text).unwrap_err();
        assert_eq!(e.offset, Some(16 + 14));
        let thirteen = "-\n".repeat(13);
        let e = parse_levels(Path::new("levels"), thirteen.as_bytes()).unwrap_err();
        assert_eq!(e.offset, Some(24));
    }

    /// A GIF encoder for tests: clear codes every two pixels keep the code
    /// size at min_size + 1.
    fn encode_gif(
        w: u16,
        h: u16,
        palette: &[[u8; 3]; 4],
        px: &[u8],
        transparent: Option<u8>,
        interlace: bool,
    ) -> Vec<u8> {
        let mut out = b"GIF89a".to_vec();
        out.extend(w.to_le_bytes());
        out.extend(h.to_le_bytes());
        out.extend([0x80 | 0x01, 0, 0]); // global table of 4 colours
        for c in palette {
            out.extend(c);
        }
        if let Some(t) = transparent {
            out.extend([0x21, 0xf9, 4, 1, 0, 0, t, 0]);
        }
        out.push(0x2c);
        out.extend([0u8, 0, 0, 0]);
        out.extend(w.to_le_bytes());
        out.extend(h.to_le_bytes());
        out.push(if interlace { 0x40 } else { 0 });
        out.push(2); // min code size: clear 4, end 5, codes of 3 bits
        let mut codes = Vec::new();
        for pair in px.chunks(2) {
            codes.push(4u8);
            codes.extend(pair);
        }
        codes.push(5);
        let (mut acc, mut bits, mut data) = (0u32, 0u32, Vec::new());
        for c in codes {
            acc |= (c as u32) << bits;
            bits += 3;
            while bits >= 8 {
                data.push(acc as u8);
                acc >>= 8;
                bits -= 8;
            }
        }
        if bits > 0 {
            data.push(acc as u8);
        }
        for chunk in data.chunks(255) {
            out.push(chunk.len() as u8);
            out.extend(chunk);
        }
        out.extend([0, 0x3b]);
        out
    }

    const PAL: [[u8; 3]; 4] = [[0, 0, 0], [255, 0, 0], [0, 255, 0], [0, 0, 255]];

    #[test]
    fn decodes_a_hand_made_gif() {
        let px = [0u8, 1, 2, 3, 3, 2, 1, 0, 1, 1, 2, 2];
        let gif = encode_gif(4, 3, &PAL, &px, Some(0), false);
        let (w, h, rgba) = decode_gif(Path::new("t.gif"), &gif).unwrap();
        assert_eq!((w, h), (4, 3));
        for (i, &p) in px.iter().enumerate() {
            let want = if p == 0 {
                [0, 0, 0, 0]
            } else {
                let c = PAL[p as usize];
                [c[0], c[1], c[2], 255]
            };
            assert_eq!(rgba[4 * i..4 * i + 4], want, "pixel {i}");
        }
        // Interlaced: rows stored in the order 0, 2, 1 for 3 rows.
        let stored = [0u8, 1, 2, 3, 1, 1, 2, 2, 3, 2, 1, 0];
        let gif = encode_gif(4, 3, &PAL, &stored, None, true);
        let (_, _, rgba) = decode_gif(Path::new("t.gif"), &gif).unwrap();
        assert_eq!(rgba[4 * 4..4 * 4 + 3], [0, 0, 255]); // row 1 = stored row 2
    }

    #[test]
    fn lzw_handles_growing_codes() {
        // Hand-coded stream (min size 2: clear 4, end 5, first free code 6):
        // clear, 1 -> "1"; 6 is the code being defined (prev "1" + its first
        // byte) -> "11"; 7 likewise -> "111", and defining 7 fills the 3-bit
        // codes, so the end code that follows is 4 bits wide.
        let codes: [(u32, u32); 5] = [(4, 3), (1, 3), (6, 3), (7, 3), (5, 4)];
        let pack = |codes: &[(u32, u32)]| {
            let (mut acc, mut bits) = (0u64, 0u32);
            for &(c, n) in codes {
                acc |= (c as u64) << bits;
                bits += n;
            }
            acc.to_le_bytes()[..bits.div_ceil(8) as usize].to_vec()
        };
        assert_eq!(lzw_decode(&pack(&codes), 2, 100).unwrap(), vec![1; 6]);
        // Existing codes: clear, 1, 2 (defines 6 = "12"), 6 -> "12"
        // (defines 7 = "21"), 7 -> "21" (4 bits from here), end.
        let codes = [(4, 3), (1, 3), (2, 3), (6, 3), (7, 4), (5, 4)];
        assert_eq!(
            lzw_decode(&pack(&codes), 2, 100).unwrap(),
            vec![1, 2, 1, 2, 2, 1]
        );
        // A code beyond the next free one is an error, not a panic.
        assert!(lzw_decode(&pack(&[(4, 3), (1, 3), (7, 3)]), 2, 100).is_err());
    }

    #[test]
    fn every_gif_truncation_is_an_error_with_an_offset() {
        let px = [0u8, 1, 2, 3, 3, 2, 1, 0, 1, 1, 2, 2];
        let gif = encode_gif(4, 3, &PAL, &px, Some(0), false);
        // The trailer is not needed once the image is decoded.
        for len in 0..gif.len() - 1 {
            let e = decode_gif(Path::new("cut.gif"), &gif[..len]).expect_err("truncated");
            assert_eq!(e.file, Path::new("cut.gif"));
            assert!(e.offset.is_some(), "{e}");
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(512))]

        #[test]
        fn random_gifs_never_panic(mut bytes in proptest::collection::vec(any::<u8>(), 0..400)) {
            if bytes.len() > 13 && bytes[0] % 2 == 0 {
                bytes[..6].copy_from_slice(b"GIF89a");
                bytes[6..10].copy_from_slice(&[8, 0, 8, 0]);
            }
            if let Err(e) = decode_gif(Path::new("r.gif"), &bytes) {
                prop_assert!(e.offset.is_some());
            }
        }

        #[test]
        fn corrupted_gifs_never_panic(pos in 0usize..200, val in any::<u8>()) {
            let px = [0u8, 1, 2, 3, 3, 2, 1, 0, 1, 1, 2, 2];
            let mut gif = encode_gif(4, 3, &PAL, &px, Some(0), false);
            let n = gif.len();
            gif[pos % n] = val;
            if let Ok((w, h, rgba)) = decode_gif(Path::new("c.gif"), &gif) {
                prop_assert_eq!(rgba.len(), (w * h * 4) as usize);
            }
        }

        #[test]
        fn random_level_text_never_panics(text in "[-0-9 \\n\\r\\tx]{0,300}") {
            match parse_levels(Path::new("levels"), text.as_bytes()) {
                Ok(levels) => {
                    for l in levels {
                        for b in l.bubbles {
                            prop_assert!(b.colour < COLOURS && (b.row as usize) < ROWS);
                            prop_assert!(b.col < 8 - b.row % 2);
                        }
                    }
                }
                Err(e) => prop_assert!(e.offset.unwrap() as usize <= text.len()),
            }
        }

        #[test]
        fn random_level_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..300)) {
            let _ = parse_levels(Path::new("levels"), &bytes);
        }
    }

    #[test]
    fn views_keep_the_aspect() {
        let (l, t, w, h) = screen_view(1960.0 / 768.0);
        assert!((h - 480.0).abs() < 1e-3 && (w / h - 1960.0 / 768.0).abs() < 1e-4);
        assert!((l + w / 2.0 - 320.0).abs() < 1e-3 && t == 0.0);
        assert_eq!(screen_view(4.0 / 3.0), (0.0, 0.0, 640.0, 480.0));
        let (_, t, w, h) = screen_view(0.5);
        assert!((w - 640.0).abs() < 1e-3 && (t + h / 2.0 - 240.0).abs() < 1e-3);
    }

    fn def(camera: &str) -> SceneDef {
        SceneDef {
            name: "t".into(),
            game: crate::def::Game::FrozenBubble,
            map: "levels".into(),
            camera: camera.into(),
            width: 1024,
            height: 768,
            description: String::new(),
            shader: None,
        }
    }

    /// A data root with hand-made images and levels (GIF and PNG writers
    /// of this module's tests and the image crate).
    fn fake_root() -> PathBuf {
        let root = std::env::temp_dir().join(format!("wasp-fb-test-{}", std::process::id()));
        let gfx = root.join("gfx");
        std::fs::create_dir_all(gfx.join("balls")).unwrap();
        std::fs::create_dir_all(gfx.join("pinguins")).unwrap();
        std::fs::create_dir_all(root.join("data")).unwrap();
        std::fs::write(root.join("data/levels"), TINY).unwrap();
        let png = |rel: &str, w: u32, h: u32| {
            let img = image::RgbaImage::from_fn(w, h, |x, y| {
                image::Rgba([x as u8, y as u8, 0, if x == 0 { 0 } else { 255 }])
            });
            img.save(gfx.join(rel)).unwrap();
        };
        png("back_one_player.png", 640, 480);
        png("compressor_main.png", 252, 51);
        png("dot_red.png", 7, 7);
        png("dot_green.png", 7, 7);
        png("on_top_next.png", 39, 39);
        png("shooter.png", 100, 100);
        png("pinguins/anime-shooter_p1_0020.png", 80, 60);
        let px = vec![1u8; 32 * 32];
        for c in 1..=8 {
            std::fs::write(
                gfx.join(format!("balls/bubble-{c}.gif")),
                encode_gif(32, 32, &PAL, &px, Some(0), false),
            )
            .unwrap();
        }
        root
    }

    #[test]
    fn loads_a_hand_made_level_end_to_end() {
        let root = fake_root();
        let scene = load(&root, &def("level:3")).unwrap();
        // background, compressor, 15 bubbles, 9 dots, next + frame,
        // launch, shooter, penguin.
        assert_eq!(scene.meshes.len(), 2 + 15 + 9 + 2 + 1 + 2);
        assert_eq!(scene.materials[0].blend, Blend::Opaque);
        assert!(scene.materials[1..]
            .iter()
            .all(|m| m.blend == Blend::AlphaBlend));
        // Bubble textures once per colour; the shooter cropped by a column.
        let shooter = scene
            .textures
            .iter()
            .find(|t| t.name.ends_with("shooter.png"))
            .unwrap();
        assert_eq!((shooter.width, shooter.height), (99, 100));
        let m = &scene.meshes[scene.meshes.len() - 2];
        assert_eq!(m.positions[0], [CANON.0 + 1.0, CANON.1, m.positions[0][2]]);
        assert_eq!(
            scene.camera,
            Camera::Ortho {
                left: 0.0,
                top: 0.0,
                width: 640.0,
                height: 480.0
            }
        );
        let e = load(&root, &def("level:4")).unwrap_err();
        assert!(e.message.contains("3 levels"), "{e}");
        let e = load(&root, &def("level:0")).unwrap_err();
        assert!(e.message.contains("level:N"), "{e}");
        std::fs::remove_dir_all(&root).ok();
    }

    fn shipped_defs() -> Vec<SceneDef> {
        crate::def::all()
            .unwrap()
            .into_iter()
            .filter(|d| d.game == crate::def::Game::FrozenBubble)
            .collect()
    }

    #[test]
    fn shipped_scene_definitions_are_valid() {
        let defs = shipped_defs();
        assert!(defs.len() >= 2);
        for d in defs {
            assert!(d.name.starts_with("fb-"), "{}", d.name);
            assert!(parse_camera(&d.camera).is_some(), "{}", d.camera);
            levels_path(Path::new("/data"), &d.map).unwrap();
        }
    }

    #[test]
    #[ignore = "needs fetched game data: wasp scenes fetch frozen-bubble"]
    fn real_shipped_scenes_load() {
        let root = real_data_root().expect("frozen-bubble-data not found");
        for d in shipped_defs() {
            let t0 = std::time::Instant::now();
            let s = load(&root, &d).unwrap();
            let dt = t0.elapsed();
            let tris: usize = s.meshes.iter().map(|m| m.indices.len() / 3).sum();
            let texels: u64 = s
                .textures
                .iter()
                .map(|t| t.width as u64 * t.height as u64)
                .sum();
            println!(
                "{:18} meshes {:3} triangles {:4} materials {:3} textures {:2} ({:.2} Mtexels) load {dt:?}",
                d.name,
                s.meshes.len(),
                tris,
                s.materials.len(),
                s.textures.len(),
                texels as f64 / 1e6,
            );
            assert!(tris > 40);
        }
    }

    /// The real data root in the scene cache, if it holds `data/levels`.
    fn real_data_root() -> Option<PathBuf> {
        crate::fetch::cached_data_root(crate::def::Game::FrozenBubble, "data/levels")
    }

    #[test]
    #[ignore = "needs fetched game data: wasp scenes fetch frozen-bubble"]
    fn real_level1() {
        let root = real_data_root().expect("frozen-bubble-data not found");
        let text = std::fs::read(root.join("data/levels")).unwrap();
        let levels = parse_levels(Path::new("levels"), &text).unwrap();
        assert_eq!(levels.len(), 100);
        assert_eq!(levels[0].bubbles.len(), 30);
        let scene = load(&root, &def("level:1")).unwrap();
        assert_eq!(scene.meshes.len(), 2 + 30 + 9 + 2 + 1 + 2);
        let bubble = scene
            .textures
            .iter()
            .find(|t| t.name.ends_with("bubble-7.gif"))
            .unwrap();
        assert_eq!((bubble.width, bubble.height), (32, 32));
        // A round bubble: transparent corners, opaque centre.
        assert_eq!(bubble.rgba[3], 0);
        assert_eq!(bubble.rgba[4 * (16 * 32 + 16) + 3], 255);
        let back = &scene.textures[0];
        assert_eq!((back.width, back.height), (640, 480));
        for t in &scene.textures {
            assert_eq!(
                t.rgba.len(),
                (t.width * t.height * 4) as usize,
                "{}",
                t.name
            );
        }
    }

    #[test]
    #[ignore = "needs fetched game data: wasp scenes fetch frozen-bubble"]
    fn real_levels_load() {
        let root = real_data_root().expect("frozen-bubble-data not found");
        let mut failures = Vec::new();
        for n in [1, 2, 10, 25, 50, 75, 99, 100] {
            let t0 = std::time::Instant::now();
            match load(&root, &def(&format!("level:{n}"))) {
                Ok(s) => {
                    let tris: usize = s.meshes.iter().map(|m| m.indices.len() / 3).sum();
                    println!(
                        "level {n:3}: meshes {:3} tris {:3} textures {:2} {:?}",
                        s.meshes.len(),
                        tris,
                        s.textures.len(),
                        t0.elapsed()
                    );
                }
                Err(e) => failures.push(format!("level {n}: {e}")),
            }
        }
        // Every bubble GIF of the package (normal and colour-blind) decodes.
        for entry in std::fs::read_dir(root.join("gfx/balls")).unwrap() {
            let p = entry.unwrap().path();
            if p.extension().is_some_and(|x| x == "gif") {
                if let Err(e) = decode_gif(&p, &std::fs::read(&p).unwrap()) {
                    failures.push(e.to_string());
                }
            }
        }
        assert!(failures.is_empty(), "{failures:#?}");
    }

    #[test]
    #[ignore = "needs fetched game data; writes previews to $WASP_PREVIEW_DIR"]
    fn real_previews() {
        let root = real_data_root().expect("frozen-bubble-data not found");
        let Some(dir) = std::env::var_os("WASP_PREVIEW_DIR") else {
            return;
        };
        for (n, w, h) in [(1, 1024, 768), (50, 1024, 768), (100, 1960, 768)] {
            let mut d = def(&format!("level:{n}"));
            d.width = w;
            d.height = h;
            let scene = load(&root, &d).unwrap();
            let img = super::super::teeworlds::render_preview(&scene, w / 2, h / 2);
            img.save(Path::new(&dir).join(format!("fb-level{n}.png")))
                .unwrap();
        }
    }
}
