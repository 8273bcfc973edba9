//! SuperTuxKart's `.spm` meshes: materials, buffers of vertices (half-
//! float UVs) and indices, read with [`crate::bytes::Bytes`].

use super::*;

/// One SPM material: its textures (file names).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SpmMaterial {
    /// First texture (base colour); vertices carry UVs only if present.
    pub texture: Option<String>,
    /// Second texture (second UV set).
    pub texture2: Option<String>,
}

/// One mesh buffer of an SPM file (object space).
#[derive(Clone, Debug, PartialEq)]
pub struct SpmBuffer {
    /// Index into [`Spm::materials`].
    pub material: usize,
    /// Positions.
    pub positions: Vec<Vec3>,
    /// First UV set (if the material has a texture).
    pub uv: Option<Vec<Vec2>>,
    /// Second UV set (if the material has a second texture).
    pub uv2: Option<Vec<Vec2>>,
    /// Triangle list.
    pub indices: Vec<u32>,
}

/// A parsed SPM file.
#[derive(Clone, Debug, PartialEq)]
pub struct Spm {
    /// Skinned ("SPMA"): the bind pose is what the buffers hold.
    pub skinned: bool,
    /// Bounding box: min xyz, max xyz.
    pub bbox: [f32; 6],
    /// Materials.
    pub materials: Vec<SpmMaterial>,
    /// Mesh buffers.
    pub buffers: Vec<SpmBuffer>,
}

/// The next IEEE 754 binary16, which must be finite, as f32.
pub(super) fn half(r: &mut Bytes, what: &str) -> Result<f32, SceneError> {
    let at = r.pos();
    let v = half_to_f32(r.u16(what)?);
    r.finite(at, v, what)
}

/// A name: a length byte, then that many bytes (none: no name).
pub(super) fn name(r: &mut Bytes, what: &str) -> Result<Option<String>, SceneError> {
    let n = r.u8(what)? as usize;
    if n == 0 {
        return Ok(None);
    }
    let b = r.take(n, what)?;
    Ok(Some(String::from_utf8_lossy(b).into_owned()))
}

/// IEEE 754 binary16 to f32.
pub fn half_to_f32(h: u16) -> f32 {
    let sign = if h & 0x8000 != 0 { -1.0f32 } else { 1.0 };
    let exp = ((h >> 10) & 0x1f) as i32;
    let frac = (h & 0x3ff) as f32;
    match exp {
        0 => sign * frac * (2.0f32).powi(-24),
        31 => {
            if frac == 0.0 {
                sign * f32::INFINITY
            } else {
                f32::NAN
            }
        }
        _ => sign * (1.0 + frac / 1024.0) * (2.0f32).powi(exp - 15),
    }
}

/// What every vertex of a file carries besides its position (the
/// header's kind and flags); UVs depend on the buffer's material.
#[derive(Clone, Copy, Debug)]
struct VertexFormat {
    skinned: bool,
    normal: bool,
    color: bool,
    tangent: bool,
}

/// One vertex layout: the file's format and whether the buffer's material
/// has a texture (`uv`) and a second one (`uv2`).
#[derive(Clone, Copy, Debug)]
struct BufferFormat {
    file: VertexFormat,
    uv: bool,
    uv2: bool,
}

impl BufferFormat {
    /// The fewest bytes a vertex takes (a colour may add 3).
    fn min_vertex(&self) -> usize {
        let f = self.file;
        12 + 4 * f.normal as usize
            + f.color as usize
            + 4 * self.uv as usize
            + 4 * self.uv2 as usize
            + 4 * (self.uv && f.tangent) as usize
            + 16 * f.skinned as usize
    }
}

/// Read the magic, the version byte (version 1; kind skinned or static)
/// and the flags.
fn read_header(r: &mut Bytes) -> Result<VertexFormat, SceneError> {
    if r.take(2, "magic")? != b"SP" {
        return Err(r.err(0, "not an SPM file: magic is not \"SP\""));
    }
    let b = r.u8("version byte")?;
    if b >> 3 != 1 {
        return Err(r.err(2, format!("SPM version {} (expected 1)", b >> 3)));
    }
    let kind = b & !0x08;
    if kind == 0 {
        return Err(r.err(2, "space-partitioned SPM (SPMS) is not supported"));
    }
    let flags = r.u8("flags")?;
    Ok(VertexFormat {
        skinned: kind == 1,
        normal: flags & 1 != 0,
        color: flags & 2 != 0,
        tangent: flags & 4 != 0,
    })
}

/// Parse an SPM file (`file` names it in errors).
pub fn parse_spm(bytes: &[u8], file: &Path) -> Result<Spm, SceneError> {
    let mut r = Bytes::new(bytes, file);
    let format = read_header(&mut r)?;
    let mut bbox = [0f32; 6];
    for v in &mut bbox {
        *v = r.f32("bounding box")?;
    }
    let nmat = r.u16("material count")? as usize;
    let mut materials = Vec::with_capacity(nmat);
    for _ in 0..nmat {
        let texture = name(&mut r, "texture name")?;
        let texture2 = name(&mut r, "second texture name")?;
        materials.push(SpmMaterial { texture, texture2 });
    }
    let nsec = r.u16("sector count")?;
    let mut buffers = Vec::new();
    for _ in 0..nsec {
        let nbuf = r.u16("buffer count")?;
        for _ in 0..nbuf {
            buffers.push(read_buffer(&mut r, format, &materials)?);
        }
    }
    Ok(Spm {
        skinned: format.skinned,
        bbox,
        materials,
        buffers,
    })
}

/// One mesh buffer: its counts and material, vertices and indices.
fn read_buffer(
    r: &mut Bytes,
    format: VertexFormat,
    materials: &[SpmMaterial],
) -> Result<SpmBuffer, SceneError> {
    let at = r.pos();
    let nv = r.u32("vertex count")? as usize;
    if nv > 65535 {
        return Err(r.err(at, format!("{nv} vertices in a buffer (at most 65535)")));
    }
    let ni = r.u32("index count")? as usize;
    if !ni.is_multiple_of(3) {
        return Err(r.err(at + 4, format!("index count {ni} is not a multiple of 3")));
    }
    let mat_at = r.pos();
    let material = r.u16("material id")? as usize;
    if material >= materials.len() {
        return Err(r.err(
            mat_at,
            format!(
                "material {material} out of range ({} materials)",
                materials.len()
            ),
        ));
    }
    let has_uv = materials[material].texture.is_some();
    let layout = BufferFormat {
        file: format,
        uv: has_uv,
        uv2: has_uv && materials[material].texture2.is_some(),
    };
    let min_vertex = layout.min_vertex();
    if nv * min_vertex > r.remaining() {
        return Err(r.err(
            r.pos(),
            format!(
                "truncated: {nv} vertices need at least {} bytes, {} left",
                nv * min_vertex,
                r.remaining()
            ),
        ));
    }
    let (positions, uv, uv2) = read_vertices(r, layout, nv)?;
    let indices = read_indices(r, nv, ni)?;
    Ok(SpmBuffer {
        material,
        positions,
        uv,
        uv2,
        indices,
    })
}

/// A buffer's positions and its UV sets (if its material has them).
type Vertices = (Vec<Vec3>, Option<Vec<Vec2>>, Option<Vec<Vec2>>);

/// `nv` vertices of `layout`: the positions and UV sets kept, normals,
/// colours, tangents and skinning skipped.
fn read_vertices(r: &mut Bytes, layout: BufferFormat, nv: usize) -> Result<Vertices, SceneError> {
    let f = layout.file;
    let mut positions = Vec::with_capacity(nv);
    let mut uv = layout.uv.then(|| Vec::with_capacity(nv));
    let mut uv2 = layout.uv2.then(|| Vec::with_capacity(nv));
    for _ in 0..nv {
        let p = [
            r.finite_f32("position")?,
            r.finite_f32("position")?,
            r.finite_f32("position")?,
        ];
        positions.push(p);
        if f.normal {
            r.take(4, "normal")?;
        }
        if f.color && r.u8("colour tag")? != 128 {
            r.take(3, "colour")?;
        }
        if let Some(uv) = uv.as_mut() {
            uv.push([half(r, "uv")?, half(r, "uv")?]);
            if let Some(uv2) = uv2.as_mut() {
                uv2.push([half(r, "second uv")?, half(r, "second uv")?]);
            }
            if f.tangent {
                r.take(4, "tangent")?;
            }
        }
        if f.skinned {
            r.take(16, "joints and weights")?;
        }
    }
    Ok((positions, uv, uv2))
}

/// `ni` indices below `nv`: bytes for up to 255 vertices, else `u16`s.
fn read_indices(r: &mut Bytes, nv: usize, ni: usize) -> Result<Vec<u32>, SceneError> {
    let wide = nv > 255;
    let isize = if wide { 2 } else { 1 };
    let raw = r.take(ni * isize, "indices")?;
    let base = r.pos() - raw.len();
    let mut indices = Vec::with_capacity(ni);
    for k in 0..ni {
        let i = if wide {
            u16::from_le_bytes([raw[2 * k], raw[2 * k + 1]]) as usize
        } else {
            raw[k] as usize
        };
        if i >= nv {
            return Err(r.err(
                base + k * isize,
                format!("index {i} out of range ({nv} vertices)"),
            ));
        }
        indices.push(i as u32);
    }
    Ok(indices)
}

#[cfg(test)]
/// A hand-made SPM: one static mesh, normals and vertex colours, two
/// materials (one with a second texture), `nv` vertices in the first
/// buffer (u16 indices past 255) and a 3-vertex second buffer.
pub(super) fn tiny_spm(nv: usize) -> Vec<u8> {
    let mut b = Vec::new();
    b.extend_from_slice(b"SP");
    b.push(0x08 | 2); // version 1, static
    b.push(0x03); // normals + colours
    for v in [-1.0f32, 0.0, -2.0, 1.0, 2.0, 3.0] {
        b.extend_from_slice(&v.to_le_bytes());
    }
    b.extend_from_slice(&2u16.to_le_bytes());
    for (t1, t2) in [("a.png", ""), ("b.jpg", "lm.png")] {
        b.push(t1.len() as u8);
        b.extend_from_slice(t1.as_bytes());
        b.push(t2.len() as u8);
        b.extend_from_slice(t2.as_bytes());
    }
    b.extend_from_slice(&1u16.to_le_bytes()); // sectors
    b.extend_from_slice(&2u16.to_le_bytes()); // buffers
                                              // Buffer 0: material 0, nv vertices.
    b.extend_from_slice(&(nv as u32).to_le_bytes());
    b.extend_from_slice(&((nv - 2) as u32 * 3).to_le_bytes());
    b.extend_from_slice(&0u16.to_le_bytes());
    for i in 0..nv {
        for v in [i as f32, 0.5, -(i as f32)] {
            b.extend_from_slice(&v.to_le_bytes());
        }
        b.extend_from_slice(&[0, 0, 0, 0]); // normal
        if i % 2 == 0 {
            b.push(128); // white
        } else {
            b.extend_from_slice(&[255, 10, 20, 30]);
        }
        b.extend_from_slice(&0x3C00u16.to_le_bytes()); // u = 1
        b.extend_from_slice(&0x3800u16.to_le_bytes()); // v = 0.5
    }
    let wide = nv > 255;
    for t in 0..nv - 2 {
        for i in [0, t + 1, t + 2] {
            if wide {
                b.extend_from_slice(&(i as u16).to_le_bytes());
            } else {
                b.push(i as u8);
            }
        }
    }
    // Buffer 1: material 1 (two UV sets), 3 vertices.
    b.extend_from_slice(&3u32.to_le_bytes());
    b.extend_from_slice(&3u32.to_le_bytes());
    b.extend_from_slice(&1u16.to_le_bytes());
    for i in 0..3 {
        for v in [0.0f32, i as f32, 0.0] {
            b.extend_from_slice(&v.to_le_bytes());
        }
        b.extend_from_slice(&[0, 0, 0, 0]);
        b.push(128);
        b.extend_from_slice(&0xC000u16.to_le_bytes()); // u = -2
        b.extend_from_slice(&0x0000u16.to_le_bytes()); // v = 0
        b.extend_from_slice(&0x3400u16.to_le_bytes()); // u2 = 0.25
        b.extend_from_slice(&0x3C00u16.to_le_bytes()); // v2 = 1
    }
    b.extend_from_slice(&[2, 1, 0]);
    b
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    #[test]
    fn half_floats() {
        assert_eq!(half_to_f32(0x3C00), 1.0);
        assert_eq!(half_to_f32(0xC000), -2.0);
        assert_eq!(half_to_f32(0x3555), 0.333_251_95);
        assert_eq!(half_to_f32(0x0001), 2f32.powi(-24));
        assert_eq!(half_to_f32(0x7BFF), 65504.0);
        assert!(half_to_f32(0x7C00).is_infinite());
        assert!(half_to_f32(0x7E00).is_nan());
    }

    #[test]
    fn parses_a_tiny_spm() {
        for nv in [4, 300] {
            let s = parse_spm(&tiny_spm(nv), Path::new("t.spm")).unwrap();
            assert!(!s.skinned);
            assert_eq!(s.bbox, [-1.0, 0.0, -2.0, 1.0, 2.0, 3.0]);
            assert_eq!(s.materials[0].texture.as_deref(), Some("a.png"));
            assert_eq!(s.materials[0].texture2, None);
            assert_eq!(s.materials[1].texture2.as_deref(), Some("lm.png"));
            assert_eq!(s.buffers.len(), 2);
            let b0 = &s.buffers[0];
            assert_eq!(b0.positions.len(), nv);
            assert_eq!(b0.positions[3], [3.0, 0.5, -3.0]);
            assert_eq!(b0.uv.as_ref().unwrap()[nv - 1], [1.0, 0.5]);
            assert!(b0.uv2.is_none());
            assert_eq!(b0.indices.len(), (nv - 2) * 3);
            assert_eq!(
                &b0.indices[b0.indices.len() - 3..],
                &[0, nv as u32 - 2, nv as u32 - 1]
            );
            let b1 = &s.buffers[1];
            assert_eq!(b1.material, 1);
            assert_eq!(b1.uv.as_ref().unwrap()[0], [-2.0, 0.0]);
            assert_eq!(b1.uv2.as_ref().unwrap()[2], [0.25, 1.0]);
            assert_eq!(b1.indices, vec![2, 1, 0]);
        }
    }

    #[test]
    fn spm_errors_name_file_and_offset() {
        let f = Path::new("bad.spm");
        let e = parse_spm(b"XX\x0a\x03", f).unwrap_err();
        assert_eq!((e.file.as_path(), e.offset), (f, Some(0)));
        let mut v = tiny_spm(4);
        v[2] = 0x10; // version 2
        assert_eq!(parse_spm(&v, f).unwrap_err().offset, Some(2));
        let mut v = tiny_spm(4);
        v[2] = 0x08; // space-partitioned
        assert!(parse_spm(&v, f)
            .unwrap_err()
            .message
            .contains("space-partitioned"));
        // An index past the vertices: the first index of buffer 0.
        let mut v = tiny_spm(4);
        let first_index = v.len() - 3 - (3 * (12 + 4 + 1 + 8) + 10) - 6;
        v[first_index] = 9;
        let e = parse_spm(&v, f).unwrap_err();
        assert_eq!(e.offset, Some(first_index as u64), "{e}");
        assert!(e.message.contains("out of range"), "{e}");
        // Truncated.
        let v = tiny_spm(4);
        let e = parse_spm(&v[..v.len() - 1], f).unwrap_err();
        assert!(e.message.contains("truncated"), "{e}");
    }

    proptest! {
        #[test]
        fn spm_random_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..512)) {
            if let Err(e) = parse_spm(&bytes, Path::new("r.spm")) {
                prop_assert_eq!(e.file, PathBuf::from("r.spm"));
                prop_assert!(e.offset.unwrap() <= bytes.len() as u64);
            }
        }

        #[test]
        fn spm_with_a_valid_header_and_random_body_never_panics(body in proptest::collection::vec(any::<u8>(), 0..400)) {
            let mut v = tiny_spm(4)[..28].to_vec();
            v.extend_from_slice(&body);
            let _ = parse_spm(&v, Path::new("r.spm"));
        }

        #[test]
        fn spm_truncations_are_errors(cut in 0usize..1000, nv in 3usize..300) {
            let v = tiny_spm(nv);
            let cut = cut % v.len();
            let e = parse_spm(&v[..cut], Path::new("t.spm")).unwrap_err();
            prop_assert!(e.offset.unwrap() <= cut as u64);
        }

        #[test]
        fn spm_corruptions_never_panic(at in 0usize..2000, byte in any::<u8>()) {
            let mut v = tiny_spm(5);
            let at = at % v.len();
            v[at] = byte;
            let _ = parse_spm(&v, Path::new("c.spm"));
        }
    }
}
