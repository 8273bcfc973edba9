//! Draw calls: glDrawArrays, glDrawElements and glDrawRangeElements with
//! GL_TRIANGLES, strips, fans, GL_QUADS, quad strips and GL_POLYGON turned
//! into triangles; each vertex fetched from the arrays and transformed to
//! clip space by the draw's matrices, each texture unit's coordinates by
//! its texture matrix. The result ([`DrawRec`]) waits for the frame's size,
//! which places it on screen ([`mod@super::import`]).

use super::args::{self, CallError, Pointer};
use super::arrays::{self, Arrays};
use super::enums as gl;
use super::state::FixedState;
use super::textures::TexObject;
use super::tracker::Context;
use super::volume::{self, Slices};
use std::sync::Arc;
use wasp_gltrace::Call;

/// Texture units the front end has UV sets for.
pub const UV_SETS: usize = 2;

/// A texture unit a draw samples: its number, its texture as it was at the
/// draw, its environment mode, and for a 3D texture each vertex's r.
#[derive(Clone, Debug)]
pub struct Sampled {
    pub unit: usize,
    pub texture: Arc<TexObject>,
    pub env_mode: i64,
    /// The slices of a 3D texture each triangle reads (the draw's
    /// triangles in order); empty for a 2D texture.
    pub slices: Vec<Slices>,
}

/// One draw, transformed to clip space.
#[derive(Clone, Debug)]
pub struct DrawRec {
    /// The call's number.
    pub call: u64,
    /// Clip-space positions (before the viewport).
    pub clip: Vec<[f64; 4]>,
    /// Texture coordinates of units 0 and 1 (zeros for a unit not
    /// sampled).
    pub uv: [Vec<[f32; 2]>; UV_SETS],
    /// Triangles (three indices into `clip` each).
    pub indices: Vec<u32>,
    /// Triangles submitted (after assembly, before clipping).
    pub triangles: u64,
    /// The fixed-function state of the draw.
    pub fixed: FixedState,
    /// The units it samples, in unit order.
    pub sampled: Vec<Sampled>,
}

/// Triangles of a primitive of `mode` over the vertices `v`, wound as
/// OpenGL winds them; `Err` names a primitive outside the subset.
pub fn triangles(mode: i64, v: &[u32]) -> Result<Vec<[u32; 3]>, String> {
    let n = v.len();
    let mut out = Vec::with_capacity(n);
    match mode {
        gl::TRIANGLES => out.extend(v.chunks_exact(3).map(|t| [t[0], t[1], t[2]])),
        gl::TRIANGLE_STRIP => {
            for i in 0..n.saturating_sub(2) {
                out.push(if i % 2 == 0 {
                    [v[i], v[i + 1], v[i + 2]]
                } else {
                    [v[i + 1], v[i], v[i + 2]]
                });
            }
        }
        gl::TRIANGLE_FAN | gl::POLYGON => {
            for i in 1..n.saturating_sub(1) {
                out.push([v[0], v[i], v[i + 1]]);
            }
        }
        gl::QUADS => {
            for q in v.chunks_exact(4) {
                out.push([q[0], q[1], q[2]]);
                out.push([q[0], q[2], q[3]]);
            }
        }
        gl::QUAD_STRIP => {
            for k in 0..(n / 2).saturating_sub(1) {
                let (a, b, c, d) = (v[2 * k], v[2 * k + 1], v[2 * k + 3], v[2 * k + 2]);
                out.push([a, b, c]);
                out.push([a, c, d]);
            }
        }
        _ => return Err(format!("primitive type {}", primitive_name(mode))),
    }
    Ok(out)
}

fn primitive_name(mode: i64) -> String {
    match mode {
        gl::POINTS => "GL_POINTS".into(),
        gl::LINES => "GL_LINES".into(),
        gl::LINE_LOOP => "GL_LINE_LOOP".into(),
        gl::LINE_STRIP => "GL_LINE_STRIP".into(),
        _ => gl::name(mode),
    }
}

/// What a draw needs that the model lacks (a bound program, texture
/// coordinate generation, a texture target other than 2D, a unit past
/// the front end's UV sets), if anything.
fn unsupported(ctx: &Context) -> Option<String> {
    if ctx.state.program != 0 {
        return Some(format!("a shader program (program {})", ctx.state.program));
    }
    for (u, unit) in ctx.textures.units.iter().enumerate() {
        if let Some(&cap) = unit.enabled_other.first() {
            return Some(format!("{} enabled on texture unit {u}", gl::name(cap)));
        }
        if (unit.enabled_2d || unit.enabled_3d) && u >= UV_SETS {
            return Some(format!(
                "texturing on unit {u} (the front end has {UV_SETS} UV sets)"
            ));
        }
    }
    None
}

/// The vertex indices a draw call reads, in order, and its mode.
fn vertex_list(ctx: &Context, call: &Call) -> Result<(i64, Vec<u32>), CallError> {
    let mode = args::int(call, 0)?;
    if call.name.starts_with("glDrawArrays") {
        let first = args::count(call, 1)?;
        let count = args::count(call, 2)?;
        return Ok((mode, (first as u32..(first + count) as u32).collect()));
    }
    // glDrawElements(mode, count, type, indices) or
    // glDrawRangeElements(mode, start, end, count, type, indices).
    let k = if call.name.starts_with("glDrawRangeElements") {
        3
    } else {
        1
    };
    let count = args::count(call, k)?;
    let ty = args::int(call, k + 1)?;
    let fail = |m: String| CallError::at(call, m);
    let list = match args::pointer(call, k + 2)? {
        Pointer::Data(d) => arrays::indices(&d, count, ty),
        Pointer::Offset(o) if ctx.arrays.element_buffer != 0 => {
            let src = arrays::Source::Buffer {
                id: ctx.arrays.element_buffer,
                offset: o,
            };
            ctx.arrays
                .bytes(&src)
                .and_then(|b| arrays::indices(b, count, ty))
        }
        Pointer::Offset(o) => Err(format!(
            "indices in client memory at {o:#x}: the capture recorded none"
        )),
    }
    .map_err(fail)?;
    Ok((mode, list))
}

/// Records draw `call` in the current state: `Ok(Err(feature))` when it
/// needs what the model lacks, `Err` for a GL error the engine would have
/// hit (no vertex array, indices or vertices outside the recorded data).
pub fn record(ctx: &Context, call: &Call) -> Result<Result<DrawRec, String>, CallError> {
    if let Some(f) = unsupported(ctx) {
        return Ok(Err(f));
    }
    if let ("glEnd", Some(b)) = (&*call.name, &ctx.immediate.ended) {
        // Immediate mode: the block as glDrawArrays(mode, 0, n) over
        // arrays of its vertices, numbered by its glBegin.
        if let Some(f) = &b.unsupported {
            return Ok(Err(format!("{f} between glBegin and glEnd")));
        }
        let list: Vec<u32> = (0..b.vertices.len() as u32).collect();
        let rec = record_list(ctx, &b.arrays(), call, b.mode, &list)?;
        return Ok(rec.map(|r| DrawRec { call: b.begin, ..r }));
    }
    let (mode, list) = vertex_list(ctx, call)?;
    record_list(ctx, &ctx.arrays, call, mode, &list)
}

/// Records draw `call` of the vertices `list` of `arrays` as primitive
/// `mode` in the current state.
pub fn record_list(
    ctx: &Context,
    arrays: &Arrays,
    call: &Call,
    mode: i64,
    list: &[u32],
) -> Result<Result<DrawRec, String>, CallError> {
    let tris = match triangles(mode, list) {
        Ok(t) => t,
        Err(f) => return Ok(Err(f)),
    };
    let fail = |m: String| CallError::at(call, m);
    let vertex = match &arrays.vertex {
        Some(a) if a.enabled => a,
        _ => {
            return Err(fail(
                "no vertex array enabled (glEnableClientState(GL_VERTEX_ARRAY) and \
                 glVertexPointer)"
                    .into(),
            ))
        }
    };
    let (used, indices) = renumber(&tris);
    let mvp = ctx.matrices.mvp();
    let bytes = arrays
        .bytes(&vertex.source)
        .map_err(|m| fail(format!("vertex array: {m}")))?;
    let clip = used
        .iter()
        .map(|&i| vertex.element(bytes, i as usize).map(|p| mvp.apply(p)))
        .collect::<Result<Vec<_>, _>>()
        .map_err(|m| fail(format!("vertex array: {m}")))?;
    let mut sampled = Vec::new();
    let mut uv: [Vec<[f32; 2]>; UV_SETS] = [vec![[0.0; 2]; used.len()], vec![[0.0; 2]; used.len()]];
    for (u, out) in uv.iter_mut().enumerate() {
        match sample_unit(ctx, arrays, call, u, &used, &indices, out)? {
            Ok(Some(x)) => sampled.push(x),
            Ok(None) => {}
            Err(feature) => return Ok(Err(feature)),
        }
    }
    Ok(Ok(DrawRec {
        call: call.no,
        clip,
        uv,
        indices,
        triangles: tris.len() as u64,
        fixed: ctx.state.clone(),
        sampled,
    }))
}

/// Texture unit `u` of a draw whose vertices `used` make triangles
/// `indices`: their texture coordinates into `out`, and what the unit
/// samples (`None`: it is off). `Err` inside: a feature not modelled.
fn sample_unit(
    ctx: &Context,
    arrays: &Arrays,
    call: &Call,
    u: usize,
    used: &[u32],
    indices: &[u32],
    out: &mut [[f32; 2]],
) -> Result<Result<Option<Sampled>, String>, CallError> {
    let unit = &ctx.textures.units[u];
    // GL_TEXTURE_3D takes precedence over GL_TEXTURE_2D; an incomplete
    // texture of the enabled target turns the unit off.
    let tex = if unit.enabled_3d {
        ctx.textures.objects_3d.get(&unit.bound_3d)
    } else if unit.enabled_2d {
        ctx.textures.objects.get(&unit.bound)
    } else {
        None
    };
    let Some(tex) = tex.filter(|t| t.complete()) else {
        return Ok(Ok(None));
    };
    if unit.enabled_3d && tex.mipmapped() {
        return Ok(Err(format!(
            "a mipmapped 3D texture (texture {}, GL_TEXTURE_MIN_FILTER {})",
            tex.id,
            gl::name(tex.min_filter)
        )));
    }
    let mut r = Vec::new();
    let want_r = unit.enabled_3d.then_some(&mut r);
    texcoords(ctx, arrays, u, used, out, want_r)
        .map_err(|m| CallError::at(call, format!("texture coordinates of unit {u}: {m}")))?;
    let slices = if unit.enabled_3d {
        match volume::triangle_slices(tex, &r, indices) {
            Ok(s) => s,
            Err(feature) => return Ok(Err(feature)),
        }
    } else {
        Vec::new()
    };
    Ok(Ok(Some(Sampled {
        unit: u,
        texture: tex.clone(),
        env_mode: unit.env_mode,
        slices,
    })))
}

/// The vertices triangles `tris` use, in order of first use, and the
/// triangles' indices into them.
fn renumber(tris: &[[u32; 3]]) -> (Vec<u32>, Vec<u32>) {
    // A map, not a table over the index range: an index far past the
    // others (a corrupt one, found out at the vertex fetch) costs nothing.
    let mut remap: std::collections::HashMap<u32, u32> = Default::default();
    let mut used: Vec<u32> = Vec::new();
    let mut indices = Vec::with_capacity(tris.len() * 3);
    for &i in tris.iter().flatten() {
        let r = *remap.entry(i).or_insert_with(|| {
            used.push(i);
            used.len() as u32 - 1
        });
        indices.push(r);
    }
    (used, indices)
}

/// Unit `u`'s coordinates of the vertices `used` through its texture
/// matrix, divided by q (r too, into `r` when asked for); without an
/// enabled array, the unit's current texture coordinates (glTexCoord,
/// glMultiTexCoord).
fn texcoords(
    ctx: &Context,
    arrays: &Arrays,
    u: usize,
    used: &[u32],
    out: &mut [[f32; 2]],
    mut r: Option<&mut Vec<f64>>,
) -> Result<(), String> {
    let m = ctx.matrices.texture[u].top();
    let bytes = match &arrays.texcoord[u] {
        Some(a) if a.enabled => Some((a, arrays.bytes(&a.source)?)),
        _ => None,
    };
    for (o, &i) in out.iter_mut().zip(used) {
        let tc = match bytes {
            Some((a, b)) => a.element(b, i as usize)?,
            None => ctx.immediate.texcoord[u],
        };
        let t = m.apply(tc);
        let q = if t[3] != 0.0 { t[3] } else { 1.0 };
        *o = [(t[0] / q) as f32, (t[1] / q) as f32];
        if let Some(r) = r.as_deref_mut() {
            r.push(t[2] / q);
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strips_fans_quads_and_quad_strips_become_triangles_wound_as_gl_winds_them() {
        let v = [10, 11, 12, 13, 14, 15];
        assert_eq!(triangles(gl::TRIANGLES, &v[..5]).unwrap(), [[10, 11, 12]]);
        assert_eq!(
            triangles(gl::TRIANGLE_STRIP, &v[..5]).unwrap(),
            [[10, 11, 12], [12, 11, 13], [12, 13, 14]]
        );
        assert_eq!(
            triangles(gl::TRIANGLE_FAN, &v[..4]).unwrap(),
            [[10, 11, 12], [10, 12, 13]]
        );
        assert_eq!(
            triangles(gl::QUADS, &v[..4]).unwrap(),
            [[10, 11, 12], [10, 12, 13]]
        );
        // Quad strip 10 11 / 12 13 / 14 15: quads (10, 11, 13, 12) and
        // (12, 13, 15, 14).
        assert_eq!(
            triangles(gl::QUAD_STRIP, &v).unwrap(),
            [[10, 11, 13], [10, 13, 12], [12, 13, 15], [12, 15, 14]]
        );
        assert_eq!(triangles(gl::POLYGON, &v[..3]).unwrap(), [[10, 11, 12]]);
        assert!(triangles(gl::TRIANGLE_STRIP, &v[..2]).unwrap().is_empty());
        assert_eq!(
            triangles(gl::LINES, &v).unwrap_err(),
            "primitive type GL_LINES"
        );
    }
}
