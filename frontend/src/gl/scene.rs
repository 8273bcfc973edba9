//! A frame's draws placed in the frame as a clip-space [`Scene`]: one
//! material per draw carrying the engine's pipeline state and a shader of
//! its texture units (wasp), meshes in issue order, and the textures the
//! draws sample (a 3D texture as the stack of its slices,
//! [`super::volume`]).
//!
//! A draw is one mesh, unless it samples a 3D texture whose triangles read
//! different slices: then each run of consecutive triangles that read the
//! same slices is a mesh of its own (so the triangles keep their order),
//! and each distinct choice of slices after the draw's first has a
//! material of its own, appended after the draws' materials, with the
//! draw's state.

use super::args::CallError;
use super::draw::DrawRec;
use super::enums as gl;
use super::textures::TexObject;
use super::volume::Slices;
use crate::{Blend, Camera, Material, Mesh, Scene, SecondSlice, ShaderOp, TexSample, Texture};
use std::collections::HashMap;
use std::path::Path;
use std::sync::Arc;

/// A texture the frame samples, for the summary.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct TextureInfo {
    /// The GL name.
    pub id: u32,
    pub width: u32,
    pub height: u32,
    /// Level 0's internal format, pixel format and type.
    pub format: String,
    /// A 3D texture's depth (slices).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub depth: Option<u32>,
    /// The levels the engine uploaded.
    pub levels: Vec<u32>,
    /// Why its texels are the placeholder, if they are.
    pub placeholder: Option<String>,
}

/// A frame's scene and what the summary and the Mesa check need of it.
pub struct Built {
    pub scene: Scene,
    /// The textures the frame samples, one per GL texture object.
    pub infos: Vec<TextureInfo>,
    /// The GL name of each of the scene's textures.
    pub texture_ids: Vec<u32>,
    /// The draw (its index) each of the scene's materials belongs to.
    pub material_draws: Vec<usize>,
}

/// The slices a triangle reads on each of the draw's sampled units (`None`
/// for a 2D texture): triangles with equal keys share a material.
type Key = [Option<Slices>; super::draw::UV_SETS];

/// A version of a texture object placed in the scene, and its index.
type Placed = (Arc<TexObject>, usize);

/// The textures of the scene being built: each GL object's first scene
/// texture (a 3D texture's slices follow one another). The versions of
/// one object that differ only in state the layout does not hold (a
/// filter, a wrap mode set again to its value: a draw keeps the version it
/// sampled) are one texture; versions with other texels or another repeat
/// mode are textures of their own (wasp).
#[derive(Default)]
struct Textures {
    textures: Vec<Texture>,
    infos: Vec<TextureInfo>,
    ids: Vec<u32>,
    seen: HashMap<*const TexObject, usize>,
    /// By (GL name, 3D, repeat): the versions placed and their index.
    versions: HashMap<(u32, bool, bool), Vec<Placed>>,
}

impl Textures {
    /// The scene index of `t` (of its slice 0 for a 3D texture), added
    /// on first use.
    fn index(&mut self, t: &Arc<TexObject>) -> usize {
        if let Some(&at) = self.seen.get(&Arc::as_ptr(t)) {
            return at;
        }
        let repeat = t.wrap[..2].contains(&gl::REPEAT);
        let versions = self.versions.entry((t.id, t.is_3d, repeat)).or_default();
        let same = |v: &Arc<TexObject>| v.levels.get(&0) == t.levels.get(&0) && v.rgba == t.rgba;
        let at = match versions.iter().find(|(v, _)| same(v)) {
            Some(&(_, at)) => at,
            None => {
                let at = self.textures.len();
                versions.push((t.clone(), at));
                self.infos.push(info(t));
                if t.is_3d {
                    self.textures
                        .extend((0..t.depth()).map(|k| t.slice_texture(k)));
                } else {
                    self.textures.push(t.texture());
                }
                self.ids.resize(self.textures.len(), t.id);
                at
            }
        };
        self.seen.insert(Arc::as_ptr(t), at);
        at
    }
}

/// ALU instructions of a texture environment mode (wasp).
fn env_alu(mode: i64) -> u32 {
    match mode {
        gl::REPLACE => 0,
        gl::DECAL | gl::BLEND_ENV | gl::COMBINE => 2,
        _ => 1,
    }
}

/// The shader of draw `d` when its 3D units read the slices of `key`
/// (wasp): a2, then per sampled unit T(unit) and its environment's ALU,
/// an ALU for the alpha test, a1 to write.
fn shader_of(d: &DrawRec, key: &Key, alpha_test: bool, tex: &mut Textures) -> Vec<ShaderOp> {
    let mut shader = vec![ShaderOp::Alu(2)];
    for (k, s) in d.sampled.iter().enumerate() {
        let base = tex.index(&s.texture);
        let (texture, second) = match key[k] {
            Some(sl) => (
                base + sl.first as usize,
                sl.second.map(|(b, weight)| SecondSlice {
                    texture: base + b as usize,
                    weight,
                }),
            ),
            None => (base, None),
        };
        shader.push(ShaderOp::Tex(TexSample {
            texture,
            uv_set: s.unit as u8,
            filter: s.texture.filter(),
            mipmapped: s.texture.mipmapped(),
            second,
        }));
        shader.push(ShaderOp::Alu(env_alu(s.env_mode)));
    }
    shader.push(ShaderOp::Alu(1 + u32::from(alpha_test)));
    shader.retain(|op| *op != ShaderOp::Alu(0));
    shader
}

/// Each triangle's key, and the runs of consecutive triangles with equal
/// keys (first triangle, end).
fn runs(d: &DrawRec) -> Vec<(Key, usize, usize)> {
    let n = d.indices.len() / 3;
    let key = |t: usize| -> Key {
        let mut k: Key = [None; super::draw::UV_SETS];
        for (j, s) in d.sampled.iter().enumerate() {
            k[j] = s.slices.get(t).copied();
        }
        k
    };
    let mut out: Vec<(Key, usize, usize)> = Vec::new();
    for t in 0..n {
        let k = key(t);
        match out.last_mut() {
            Some(last) if last.0 == k => last.2 = t + 1,
            _ => out.push((k, t, t + 1)),
        }
    }
    if out.is_empty() {
        out.push((key(0), 0, 0));
    }
    out
}

/// The scene of a frame's draws in a `w` x `h` frame.
pub fn scene_of(
    draws: &[DrawRec],
    w: u32,
    h: u32,
    file: &Path,
    frame: u64,
) -> Result<Built, CallError> {
    let mut tex = Textures::default();
    let (mut meshes, mut materials) = (Vec::new(), Vec::new());
    let mut extra: Vec<Material> = Vec::new();
    let mut material_draws: Vec<usize> = (0..draws.len()).collect();
    for (i, d) in draws.iter().enumerate() {
        let state = d.fixed.draw_state(w, h).map_err(|m| CallError {
            call: d.call,
            name: "draw".into(),
            message: m,
        })?;
        let blend = if state.blend.is_some() {
            Blend::AlphaBlend
        } else if state.alpha_test.is_some() {
            Blend::AlphaTest
        } else {
            Blend::Opaque
        };
        let alpha = state.alpha_test.is_some();
        let material = |shader| Material {
            name: format!("call {}", d.call),
            blend,
            shader,
            state: Some(state),
        };
        let runs = runs(d);
        let mut keys: HashMap<Key, usize> = HashMap::new();
        keys.insert(runs[0].0, i);
        materials.push(material(shader_of(d, &runs[0].0, alpha, &mut tex)));
        if runs.len() == 1 {
            meshes.push(mesh_of(d, None, w, h, i));
            continue;
        }
        for (key, a, b) in runs {
            let m = *keys.entry(key).or_insert_with(|| {
                extra.push(material(shader_of(d, &key, alpha, &mut tex)));
                material_draws.push(i);
                draws.len() + extra.len() - 1
            });
            meshes.push(mesh_of(d, Some((a, b)), w, h, m));
        }
    }
    materials.extend(extra);
    let scene = Scene {
        name: format!("gl:{}:frame{frame}", file.display()),
        source: format!("apitrace capture {}, frame {frame}", file.display()),
        meshes,
        materials,
        textures: tex.textures,
        camera: Camera::Clip,
    };
    Ok(Built {
        scene,
        infos: tex.infos,
        texture_ids: tex.ids,
        material_draws,
    })
}

/// A draw's mesh (of its triangles `tris`, first and end, when given):
/// clip-space positions with the viewport folded in (linear in clip
/// space: the viewport's rectangle of a `w` x `h` frame becomes its place
/// in the frame's normalized device coordinates).
fn mesh_of(d: &DrawRec, tris: Option<(usize, usize)>, w: u32, h: u32, material: usize) -> Mesh {
    let vp = &d.fixed.viewport;
    let (wf, hf) = (f64::from(w), f64::from(h));
    let (vx, vy, vw, vh) = (vp[0] as f64, vp[1] as f64, vp[2] as f64, vp[3] as f64);
    let (sx, ox) = (vw / wf, (2.0 * vx + vw) / wf - 1.0);
    let (sy, oy) = (vh / hf, (2.0 * vy + vh) / hf - 1.0);
    // The vertices the triangles use, in order of first use.
    let (used, indices): (Vec<usize>, Vec<u32>) = match tris {
        None => ((0..d.clip.len()).collect(), d.indices.clone()),
        Some((a, b)) => {
            let mut map: HashMap<u32, u32> = HashMap::new();
            let mut used = Vec::new();
            let indices = d.indices[3 * a..3 * b]
                .iter()
                .map(|&v| {
                    *map.entry(v).or_insert_with(|| {
                        used.push(v as usize);
                        used.len() as u32 - 1
                    })
                })
                .collect();
            (used, indices)
        }
    };
    let positions = used
        .iter()
        .map(|&v| {
            let p = d.clip[v];
            [
                (p[0] * sx + p[3] * ox) as f32,
                (p[1] * sy + p[3] * oy) as f32,
                p[2] as f32,
            ]
        })
        .collect();
    let pick = |uv: &Vec<[f32; 2]>| used.iter().map(|&v| uv[v]).collect::<Vec<_>>();
    Mesh {
        positions,
        uv: pick(&d.uv[0]),
        uv2: d
            .sampled
            .iter()
            .any(|s| s.unit == 1)
            .then(|| pick(&d.uv[1])),
        indices,
        material,
        clip_w: Some(used.iter().map(|&v| d.clip[v][3] as f32).collect()),
        ..Default::default()
    }
}

/// The summary's entry of a texture.
fn info(t: &TexObject) -> TextureInfo {
    let l0 = &t.levels[&0];
    TextureInfo {
        id: t.id,
        width: l0.width,
        height: l0.height,
        depth: t.is_3d.then_some(l0.depth),
        format: if l0.compressed {
            format!("{} (compressed)", gl::name(l0.internal))
        } else {
            format!(
                "{} from {}/{}",
                gl::name(l0.internal),
                gl::name(l0.format),
                gl::name(l0.ty)
            )
        },
        levels: t.levels.keys().copied().collect(),
        placeholder: t.placeholder.clone(),
    }
}

#[cfg(test)]
mod tests {
    use super::super::args::test_calls::*;
    use super::super::import::tests::run;
    use super::super::import::{import, ImportOptions};
    use super::*;
    use wasp_gltrace::{Call, Value};

    /// A 64x64 window (glOrtho 0..64), one texture on unit 0 uploaded by
    /// `upload` with GL_TEXTURE_MIN_FILTER `min`, enabled as `target`,
    /// then one GL_QUADS draw of the squares (x0, x1, r): x0..x1 by 0..h
    /// pixels, s and t 0..1 and the third coordinate r; one swap.
    fn frame(target: i64, upload: Call, min: i64, h: f32, squares: &[[f32; 3]]) -> Vec<Call> {
        let i = Value::SInt;
        let (mut v, mut tc) = (Vec::new(), Vec::new());
        for &[x0, x1, r] in squares {
            v.extend([x0, 0.0, x1, 0.0, x1, h, x0, h]);
            tc.extend([0.0, 0.0, r, 1.0, 0.0, r, 1.0, 1.0, r, 0.0, 1.0, r]);
        }
        let n = 4 * squares.len() as i64;
        let mut c = vec![
            call(0, "glViewport", vec![i(0), i(0), i(64), i(64)]),
            call(0, "glMatrixMode", vec![e(gl::PROJECTION)]),
            call(
                0,
                "glOrtho",
                vec![f(0.0), f(64.0), f(0.0), f(64.0), f(-1.0), f(1.0)],
            ),
            call(0, "glBindTexture", vec![e(target), i(7)]),
            upload,
            call(
                0,
                "glTexParameteri",
                vec![e(target), e(gl::TEXTURE_MIN_FILTER), e(min)],
            ),
            call(0, "glEnable", vec![e(target)]),
            call(0, "glEnableClientState", vec![e(gl::VERTEX_ARRAY)]),
            call(0, "glEnableClientState", vec![e(gl::TEXTURE_COORD_ARRAY)]),
            call(
                0,
                "glVertexPointer",
                vec![i(2), e(gl::FLOAT), i(0), floats(&v)],
            ),
            call(
                0,
                "glTexCoordPointer",
                vec![i(3), e(gl::FLOAT), i(0), floats(&tc)],
            ),
            call(0, "glDrawArrays", vec![e(gl::QUADS), i(0), i(n)]),
            call(0, "glXSwapBuffers", vec![]),
        ];
        for (n, k) in c.iter_mut().enumerate() {
            k.no = n as u64;
        }
        c
    }

    /// glTexImage3D of a `w` x `w` x `d` GL_RGBA texture.
    fn image_3d(w: i64, d: i64) -> Call {
        let i = Value::SInt;
        let px = Value::Blob(vec![200; (w * w * d * 4) as usize]);
        let a = vec![e(gl::TEXTURE_3D), i(0), e(gl::RGBA), i(w), i(w), i(d), i(0)];
        let b = vec![e(gl::RGBA), e(gl::UNSIGNED_BYTE), px];
        call(0, "glTexImage3D", [a, b].concat())
    }

    fn sample(m: &Material) -> TexSample {
        m.shader
            .iter()
            .find_map(|op| match op {
                ShaderOp::Tex(t) => Some(*t),
                _ => None,
            })
            .unwrap()
    }

    #[test]
    fn a_3d_texture_is_its_slices_and_r_picks_them_per_triangle() {
        // 4x4x4, nearest: the left square reads slice 1, the right one
        // slice 2: one draw, two materials, the second appended.
        let squares = [[0.0, 32.0, 1.5 / 4.0], [32.0, 64.0, 2.5 / 4.0]];
        let calls = frame(gl::TEXTURE_3D, image_3d(4, 4), gl::NEAREST, 64.0, &squares);
        let (imp, f) = run(calls);
        assert_eq!(imp.scene.textures.len(), 4, "the stack of slices");
        assert_eq!(imp.texture_ids, [7; 4]);
        assert_eq!(imp.textures.len(), 1);
        assert_eq!(imp.textures[0].depth, Some(4));
        assert_eq!(imp.material_draws, [0, 0]);
        assert_eq!(imp.scene.meshes.len(), 2);
        let (a, b) = (
            sample(&imp.scene.materials[0]),
            sample(&imp.scene.materials[1]),
        );
        assert_eq!((a.texture, a.second, a.mipmapped), (1, None, false));
        assert_eq!((b.texture, b.second), (2, None));
        // Each slice is one 4x4-texel block: two blocks in the frame.
        assert_eq!(f.trace.stats().frame_unique_blocks, 2);
        assert_eq!(f.stats.positions, 32 * 32);
        // Linear in r at slice 1's centre: slice 2's weight is 0, so slice 1
        // alone is read (an array of 2D layers), one pass.
        let one = [[0.0, 64.0, 1.5 / 4.0]];
        let calls = frame(gl::TEXTURE_3D, image_3d(4, 4), gl::LINEAR, 64.0, &one);
        let (imp, f) = run(calls);
        let s = sample(&imp.scene.materials[0]);
        assert_eq!((s.texture, s.second), (1, None));
        assert_eq!(f.trace.stats().frame_unique_blocks, 1);
        assert_eq!(f.trace.trilinear_count(), 0);
        // A quarter of the way to slice 2's centre: slices 1 and 2, one
        // texture instruction of two passes.
        let between = [[0.0, 64.0, 1.75 / 4.0]];
        let calls = frame(gl::TEXTURE_3D, image_3d(4, 4), gl::LINEAR, 64.0, &between);
        let (imp, f) = run(calls);
        let s = sample(&imp.scene.materials[0]);
        let second = Some(crate::SecondSlice {
            texture: 2,
            weight: 16384,
        });
        assert_eq!((s.texture, s.second), (1, second));
        assert_eq!(f.trace.stats().frame_unique_blocks, 2);
        // Every texture instruction filters twice.
        assert_eq!(f.trace.trilinear_count(), f.trace.tex_count());
        assert!(f.trace.tex_count() > 0);
        // r varying across a triangle is not modelled: counted, or an error.
        let mut calls = frame(gl::TEXTURE_3D, image_3d(4, 4), gl::LINEAR, 64.0, &one);
        let tc = floats(&[0.0, 0.0, 0.1, 1.0, 0.0, 0.9, 1.0, 1.0, 0.9, 0.0, 1.0, 0.1]);
        calls[10].args[3] = tc;
        let err = import(
            calls.into_iter().map(Ok),
            Path::new("t"),
            ImportOptions::default(),
        );
        let msg = err.unwrap_err().to_string();
        assert!(msg.contains("different slices across a triangle"), "{msg}");
    }

    #[test]
    fn a_texture_without_a_mipmap_filter_reads_level_zero_when_minified() {
        // A 64x64 texture on an 8x8-pixel square: lambda 3. GL_LINEAR
        // reads level 0 (each pixel's 2x2 texels straddle two 4x4-texel
        // cells each way: all 16x16 blocks); a mipmap filter reads level 3
        // (8x8 texels: 2x2 blocks).
        let i = Value::SInt;
        let up = |_| {
            let a = vec![e(gl::TEXTURE_2D), i(0), e(gl::RGBA), i(64), i(64), i(0)];
            let px = Value::Blob(vec![9; 64 * 64 * 4]);
            call(
                0,
                "glTexImage2D",
                [a, vec![e(gl::RGBA), e(gl::UNSIGNED_BYTE), px]].concat(),
            )
        };
        let sq = [[0.0, 8.0, 0.0]];
        let blocks = |min| {
            let (imp, f) = run(frame(gl::TEXTURE_2D, up(()), min, 8.0, &sq));
            (
                sample(&imp.scene.materials[0]).mipmapped,
                f.trace.stats().frame_unique_blocks,
            )
        };
        assert_eq!(blocks(gl::LINEAR), (false, 256));
        assert!(!blocks(gl::NEAREST).0);
        assert_eq!(blocks(gl::LINEAR_MIPMAP_NEAREST), (true, 4));
    }
}
