//! Quake 3 / OpenArena `.bsp` maps (IBSP 46): the lumps of shaders,
//! faces, vertices, indices and lightmaps, read with
//! [`crate::bytes::Bytes`].

use super::*;

/// A shader (texture) reference of the BSP.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BspShader {
    /// Shader name (e.g. `textures/base_wall/concrete`).
    pub name: String,
    /// Surface flags.
    pub flags: i32,
    /// Content flags.
    pub contents: i32,
}

/// A drawing vertex.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BspVertex {
    /// Position.
    pub pos: Vec3,
    /// Surface texture coordinates.
    pub uv: Vec2,
    /// Lightmap coordinates.
    pub lm: Vec2,
    /// Normal.
    pub normal: Vec3,
}

/// A face (surface).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BspFace {
    /// Index into [`Bsp::shaders`].
    pub shader: usize,
    /// 1 polygon, 2 patch, 3 mesh, 4 flare.
    pub kind: i32,
    /// First vertex.
    pub first_vertex: usize,
    /// Vertex count.
    pub n_vertices: usize,
    /// First mesh vertex.
    pub first_meshvert: usize,
    /// Mesh vertex count.
    pub n_meshverts: usize,
    /// Lightmap index (negative: none).
    pub lightmap: i32,
    /// Face normal (polygons).
    pub normal: Vec3,
    /// Patch control grid size.
    pub size: [usize; 2],
    /// Byte offset of the face record (for errors).
    pub offset: usize,
}

/// The parts of an IBSP v46 file the loader uses.
#[derive(Clone, Debug, PartialEq)]
pub struct Bsp {
    /// Entity lump text.
    pub entities: String,
    /// Byte offset of the entity lump.
    pub entities_offset: usize,
    /// Shaders.
    pub shaders: Vec<BspShader>,
    /// Vertices.
    pub vertices: Vec<BspVertex>,
    /// Mesh vertices (offsets from a face's first vertex).
    pub meshverts: Vec<i32>,
    /// Faces (validated: ranges inside the vertex and mesh-vertex lumps).
    pub faces: Vec<BspFace>,
    /// Lightmaps, 128x128 RGB each.
    pub lightmaps: Vec<Vec<u8>>,
    /// The object of each face ([`crate::Draw::object`]): the first BSP
    /// leaf (lump 4, in order) whose leaf faces (lump 5) list it, else
    /// leaves + the brush model (lump 7) holding it (doors, platforms),
    /// else leaves + models + the face's own index.
    pub face_objects: Vec<u32>,
    /// The visibility structures (lumps 2, 3, 4, 5, 16).
    pub vis: Vis,
}

/// Lump `i` of the directory, of `rec`-byte records: (offset, record
/// count), inside the `file_len`-byte file and whole records.
fn read_lump(
    r: &Bytes,
    file_len: usize,
    i: usize,
    rec: usize,
    what: &str,
) -> Result<(usize, usize), SceneError> {
    let at = 8 + 8 * i;
    let off = r.i32_at(at, "lump directory")?;
    let len = r.i32_at(at + 4, "lump directory")?;
    if off < 0 || len < 0 || off as usize + len as usize > file_len {
        return Err(r.err(
            at,
            format!("{what} lump ({off}, {len} bytes) outside the file ({file_len} bytes)"),
        ));
    }
    if !(len as usize).is_multiple_of(rec) {
        return Err(r.err(
            at + 4,
            format!("{what} lump length {len} is not a multiple of {rec}"),
        ));
    }
    Ok((off as usize, len as usize / rec))
}

/// The shaders lump: 72-byte records, a NUL-padded 64-byte name, surface
/// and content flags.
fn read_shaders(r: &Bytes, (soff, sn): (usize, usize)) -> Result<Vec<BspShader>, SceneError> {
    let mut shaders = Vec::with_capacity(sn);
    for i in 0..sn {
        let at = soff + 72 * i;
        let raw = r.slice(at, 64, "shader name")?;
        let end = raw.iter().position(|&c| c == 0).unwrap_or(64);
        shaders.push(BspShader {
            name: String::from_utf8_lossy(&raw[..end]).into_owned(),
            flags: r.i32_at(at + 64, "shader flags")?,
            contents: r.i32_at(at + 68, "shader contents")?,
        });
    }
    Ok(shaders)
}

/// The vertices lump: 44-byte records, position, texture and lightmap
/// coordinates, normal (and a colour, unused).
fn read_vertices(r: &Bytes, (voff, vn): (usize, usize)) -> Result<Vec<BspVertex>, SceneError> {
    let mut vertices = Vec::with_capacity(vn);
    for i in 0..vn {
        let at = voff + 44 * i;
        let f = |k: usize| r.f32_at(at + 4 * k, "vertex position");
        // Attributes other than the position: non-finite values (q3map2
        // leaves NaN lightmap coordinates on a few vertices of six shipped
        // maps) become 0.
        let g = |k: usize| -> Result<f32, SceneError> {
            let b = r.slice(at + 4 * k, 4, "vertex")?;
            let v = f32::from_le_bytes([b[0], b[1], b[2], b[3]]);
            Ok(if v.is_finite() { v } else { 0.0 })
        };
        vertices.push(BspVertex {
            pos: [f(0)?, f(1)?, f(2)?],
            uv: [g(3)?, g(4)?],
            lm: [g(5)?, g(6)?],
            normal: [g(7)?, g(8)?, g(9)?],
        });
    }
    Ok(vertices)
}

/// Parse an IBSP version 46 file (`file` names it in errors).
pub fn parse_bsp(bytes: &[u8], file: &Path) -> Result<Bsp, SceneError> {
    let r = Bytes::new(bytes, file);
    if r.slice(0, 4, "magic")? != b"IBSP" {
        return Err(r.err(0, "not a Quake 3 BSP: magic is not \"IBSP\""));
    }
    let version = r.i32_at(4, "version")?;
    if version != 46 {
        return Err(r.err(4, format!("BSP version {version} (expected 46)")));
    }
    let lump = |i: usize, rec: usize, what: &str| read_lump(&r, bytes.len(), i, rec, what);
    let (eoff, elen) = lump(0, 1, "entities")?;
    let entities = String::from_utf8_lossy(&bytes[eoff..eoff + elen])
        .trim_end_matches('\0')
        .to_string();
    let shaders = read_shaders(&r, lump(1, 72, "shaders")?)?;
    let vertices = read_vertices(&r, lump(10, 44, "vertices")?)?;
    let (moff, mn) = lump(11, 4, "mesh vertices")?;
    let meshverts = (0..mn)
        .map(|i| r.i32_at(moff + 4 * i, "mesh vertex"))
        .collect::<Result<Vec<_>, _>>()?;
    let (foff, fcount) = lump(13, 104, "faces")?;
    let lumps = FaceLumps {
        n_shaders: shaders.len(),
        n_vertices: vertices.len(),
        meshverts: &meshverts,
        meshverts_at: moff,
    };
    let faces = (0..fcount)
        .map(|i| read_face(&r, &lumps, i, foff + 104 * i))
        .collect::<Result<Vec<_>, _>>()?;
    let face_objects = face_objects(
        &r,
        lump(4, 48, "leaves")?,
        lump(5, 4, "leaf faces")?,
        lump(7, 40, "models")?,
        faces.len(),
    )?;
    let vis = Vis::read(
        &r,
        [
            lump(2, 16, "planes")?,
            lump(3, 36, "nodes")?,
            lump(4, 48, "leaves")?,
            lump(5, 4, "leaf faces")?,
            lump(16, 1, "visibility")?,
        ],
        faces.len(),
    )?;
    let lm_bytes = LIGHTMAP_SIDE * LIGHTMAP_SIDE * 3;
    let (loff, ln) = lump(14, lm_bytes, "lightmaps")?;
    let lightmaps = (0..ln)
        .map(|i| bytes[loff + i * lm_bytes..loff + (i + 1) * lm_bytes].to_vec())
        .collect();
    Ok(Bsp {
        entities,
        entities_offset: eoff,
        shaders,
        vertices,
        meshverts,
        faces,
        lightmaps,
        face_objects,
        vis,
    })
}

/// What a face's references are checked against.
struct FaceLumps<'a> {
    n_shaders: usize,
    n_vertices: usize,
    meshverts: &'a [i32],
    /// File offset of the mesh vertices lump.
    meshverts_at: usize,
}

/// Face `i`, the 104-byte record at `at`: its shader, vertex range and
/// (polygons and meshes) mesh vertex range or (patches) control grid, all
/// checked.
fn read_face(r: &Bytes, lumps: &FaceLumps, i: usize, at: usize) -> Result<BspFace, SceneError> {
    let g = |k: usize| r.i32_at(at + 4 * k, "face");
    let idx = |v: i32, what: &str| -> Result<usize, SceneError> {
        usize::try_from(v).map_err(|_| r.err(at, format!("face {i}: negative {what} {v}")))
    };
    let face = BspFace {
        shader: idx(g(0)?, "shader")?,
        kind: g(2)?,
        first_vertex: idx(g(3)?, "first vertex")?,
        n_vertices: idx(g(4)?, "vertex count")?,
        first_meshvert: idx(g(5)?, "first mesh vertex")?,
        n_meshverts: idx(g(6)?, "mesh vertex count")?,
        lightmap: g(7)?,
        normal: [
            r.f32_at(at + 84, "face normal")?,
            r.f32_at(at + 88, "face normal")?,
            r.f32_at(at + 92, "face normal")?,
        ],
        size: [idx(g(24)?, "patch width")?, idx(g(25)?, "patch height")?],
        offset: at,
    };
    let (shader, first_vertex, n_vertices) = (face.shader, face.first_vertex, face.n_vertices);
    if shader >= lumps.n_shaders {
        return Err(r.err(
            at,
            format!(
                "face {i}: shader {shader} out of range ({})",
                lumps.n_shaders
            ),
        ));
    }
    if first_vertex
        .checked_add(n_vertices)
        .is_none_or(|e| e > lumps.n_vertices)
    {
        return Err(r.err(
            at + 12,
            format!(
                "face {i}: vertices {first_vertex}+{n_vertices} out of range ({})",
                lumps.n_vertices
            ),
        ));
    }
    if matches!(face.kind, 1 | 3) {
        check_mesh_vertices(r, lumps, i, &face)?;
    }
    if face.kind == 2 {
        let [w, h] = face.size;
        if w < 3 || h < 3 || w % 2 == 0 || h % 2 == 0 || w.checked_mul(h) != Some(n_vertices) {
            return Err(r.err(
                at + 96,
                format!(
                    "face {i}: patch grid {w}x{h} (odd, >= 3, = {n_vertices} vertices expected)"
                ),
            ));
        }
    }
    Ok(face)
}

/// A polygon or mesh face's mesh vertices: inside the lump, whole
/// triangles, each an offset inside the face's own vertices.
fn check_mesh_vertices(
    r: &Bytes,
    lumps: &FaceLumps,
    i: usize,
    face: &BspFace,
) -> Result<(), SceneError> {
    let (at, first_meshvert, n_meshverts, n_vertices) = (
        face.offset,
        face.first_meshvert,
        face.n_meshverts,
        face.n_vertices,
    );
    let meshverts = lumps.meshverts;
    if first_meshvert
        .checked_add(n_meshverts)
        .is_none_or(|e| e > meshverts.len())
    {
        return Err(r.err(
            at + 20,
            format!(
                "face {i}: mesh vertices {first_meshvert}+{n_meshverts} out of range ({})",
                meshverts.len()
            ),
        ));
    }
    if n_meshverts % 3 != 0 {
        return Err(r.err(
            at + 24,
            format!("face {i}: {n_meshverts} mesh vertices, not whole triangles"),
        ));
    }
    let span = &meshverts[first_meshvert..first_meshvert + n_meshverts];
    for (j, &m) in span.iter().enumerate() {
        let k = first_meshvert + j;
        if m < 0 || m as usize >= n_vertices {
            return Err(r.err(
                lumps.meshverts_at + 4 * k,
                format!("face {i}: mesh vertex {m} outside its {n_vertices} vertices"),
            ));
        }
    }
    Ok(())
}

/// [`Bsp::face_objects`] from the leaves, leaf faces and models lumps
/// (each as offset and record count), for `n_faces` faces.
fn face_objects(
    r: &Bytes,
    (loff, ln): (usize, usize),
    (lfoff, lfn): (usize, usize),
    (moff, mn): (usize, usize),
    n_faces: usize,
) -> Result<Vec<u32>, SceneError> {
    let mut obj: Vec<Option<u32>> = vec![None; n_faces];
    // A range of `count` records from `first` inside a lump of `len`.
    let range = |at: usize, first: i32, count: i32, len: usize, what: &str| match (
        usize::try_from(first),
        usize::try_from(count),
    ) {
        (Ok(f), Ok(c)) if f.checked_add(c).is_some_and(|e| e <= len) => Ok(f..f + c),
        _ => Err(r.err(at, format!("{what} {first}+{count} out of range ({len})"))),
    };
    for leaf in 0..ln {
        let at = loff + 48 * leaf;
        let first = r.i32_at(at + 32, "leaf")?;
        let count = r.i32_at(at + 36, "leaf")?;
        let what = format!("leaf {leaf}: leaf faces");
        for k in range(at + 32, first, count, lfn, &what)? {
            let f = r.i32_at(lfoff + 4 * k, "leaf face")?;
            let f = usize::try_from(f)
                .ok()
                .filter(|&f| f < n_faces)
                .ok_or_else(|| {
                    r.err(
                        lfoff + 4 * k,
                        format!("leaf face {f} out of range ({n_faces})"),
                    )
                })?;
            obj[f].get_or_insert(leaf as u32);
        }
    }
    for model in 0..mn {
        let at = moff + 40 * model;
        let first = r.i32_at(at + 24, "model")?;
        let count = r.i32_at(at + 28, "model")?;
        let what = format!("model {model}: faces");
        for f in range(at + 24, first, count, n_faces, &what)? {
            obj[f].get_or_insert((ln + model) as u32);
        }
    }
    Ok(obj
        .into_iter()
        .enumerate()
        .map(|(f, o)| o.unwrap_or((ln + mn + f) as u32))
        .collect())
}

#[cfg(test)]
pub(super) fn vertex(b: &mut Vec<u8>, p: Vec3, uv: Vec2, lm: Vec2) {
    for v in [p[0], p[1], p[2], uv[0], uv[1], lm[0], lm[1], 0.0, 0.0, 1.0] {
        b.extend_from_slice(&v.to_le_bytes());
    }
    b.extend_from_slice(&[255; 4]);
}

#[cfg(test)]
#[allow(clippy::too_many_arguments)]
pub(super) fn face(
    b: &mut Vec<u8>,
    shader: i32,
    kind: i32,
    fv: i32,
    nv: i32,
    fm: i32,
    nm: i32,
    lm: i32,
    size: [i32; 2],
) {
    for v in [shader, -1, kind, fv, nv, fm, nm, lm, 0, 0, 0, 0] {
        b.extend_from_slice(&v.to_le_bytes());
    }
    for v in [0.0f32; 3 + 6] {
        b.extend_from_slice(&v.to_le_bytes());
    }
    for v in [0.0f32, 0.0, 1.0] {
        b.extend_from_slice(&v.to_le_bytes());
    }
    for v in size {
        b.extend_from_slice(&v.to_le_bytes());
    }
}

#[cfg(test)]
/// A hand-made IBSP 46: two shaders, a floor quad (polygon, lightmap
/// 0), a flat 3x3 patch, a flare, one lightmap; the lightmap lump last
/// so that any truncation cuts a lump.
pub(super) fn tiny_bsp() -> Vec<u8> {
    let ents = b"{\n\"classname\" \"worldspawn\"\n}\n{\n\"classname\" \"info_player_deathmatch\"\n\"origin\" \"16 32 24\"\n\"angle\" \"90\"\n}\n\0".to_vec();
    let mut shaders = Vec::new();
    for (name, flags) in [("textures/t/floor", 0), ("textures/t/nodraw", SURF_NODRAW)] {
        let mut n = [0u8; 64];
        n[..name.len()].copy_from_slice(name.as_bytes());
        shaders.extend_from_slice(&n);
        shaders.extend_from_slice(&flags.to_le_bytes());
        shaders.extend_from_slice(&1i32.to_le_bytes());
    }
    let mut verts = Vec::new();
    for (x, y) in [(0.0, 0.0), (64.0, 0.0), (64.0, 64.0), (0.0, 64.0)] {
        vertex(
            &mut verts,
            [x, y, 0.0],
            [x / 64.0, y / 64.0],
            [x / 128.0, y / 128.0],
        );
    }
    for j in 0..3 {
        for i in 0..3 {
            let (x, y) = (i as f32 * 32.0, j as f32 * 32.0);
            vertex(&mut verts, [x, y, 8.0], [x / 64.0, y / 64.0], [0.5, 0.5]);
        }
    }
    let mut mv = Vec::new();
    // Stored clockwise seen from +z (the BSP's convention).
    for i in [0i32, 2, 1, 0, 3, 2] {
        mv.extend_from_slice(&i.to_le_bytes());
    }
    let mut faces = Vec::new();
    face(&mut faces, 0, 1, 0, 4, 0, 6, 0, [0, 0]);
    face(&mut faces, 0, 2, 4, 9, 0, 0, -1, [3, 3]);
    face(&mut faces, 1, 1, 0, 4, 0, 6, -1, [0, 0]);
    face(&mut faces, 0, 4, 0, 0, 0, 0, -1, [0, 0]);
    let lm: Vec<u8> = (0..LIGHTMAP_SIDE * LIGHTMAP_SIDE * 3)
        .map(|i| (i % 251) as u8)
        .collect();
    let mut lumps: Vec<Vec<u8>> = vec![Vec::new(); 17];
    lumps[0] = ents;
    lumps[1] = shaders;
    lumps[10] = verts;
    lumps[11] = mv;
    lumps[13] = faces;
    let mut out = b"IBSP".to_vec();
    out.extend_from_slice(&46i32.to_le_bytes());
    let mut off = 8 + 17 * 8;
    let order: Vec<usize> = (0..17).filter(|&i| i != 14).chain([14]).collect();
    let mut dir = vec![(0usize, 0usize); 17];
    let mut body = Vec::new();
    for &i in &order {
        let data = if i == 14 { &lm } else { &lumps[i] };
        dir[i] = (off, data.len());
        body.extend_from_slice(data);
        off += data.len();
    }
    for (o, l) in dir {
        out.extend_from_slice(&(o as i32).to_le_bytes());
        out.extend_from_slice(&(l as i32).to_le_bytes());
    }
    out.extend_from_slice(&body);
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    #[test]
    fn parses_a_tiny_bsp() {
        let b = parse_bsp(&tiny_bsp(), Path::new("t.bsp")).unwrap();
        assert_eq!(b.shaders.len(), 2);
        assert_eq!(b.shaders[1].name, "textures/t/nodraw");
        assert_eq!(b.shaders[1].flags, SURF_NODRAW);
        assert_eq!(b.vertices.len(), 13);
        assert_eq!(b.vertices[2].pos, [64.0, 64.0, 0.0]);
        assert_eq!(b.vertices[2].lm, [0.5, 0.5]);
        assert_eq!(b.meshverts, vec![0, 2, 1, 0, 3, 2]);
        assert_eq!(b.faces.len(), 4);
        assert_eq!((b.faces[1].kind, b.faces[1].size), (2, [3, 3]));
        assert_eq!(b.lightmaps.len(), 1);
        assert_eq!(b.lightmaps[0][250..252], [250, 0]);
        let ents = parse_entities(&b.entities, Path::new("t.bsp"), b.entities_offset).unwrap();
        assert_eq!(spawn_points(&ents), vec![([16.0, 32.0, 24.0], 90.0)]);
        // The polygon comes out counter-clockwise seen from +z.
        let (v, i) = face_triangles(&b, &b.faces[0]).unwrap();
        assert_eq!(i, vec![0, 1, 2, 0, 2, 3]);
        let n = cross(sub(v[1].pos, v[0].pos), sub(v[2].pos, v[0].pos));
        assert!(n[2] > 0.0);
        // The patch: (L+1)^2 vertices, 2 L^2 triangles, facing +z, flat.
        let (v, i) = face_triangles(&b, &b.faces[1]).unwrap();
        assert_eq!(v.len(), (PATCH_LEVEL + 1) * (PATCH_LEVEL + 1));
        assert_eq!(i.len(), 6 * PATCH_LEVEL * PATCH_LEVEL);
        assert!(v.iter().all(|p| (p.pos[2] - 8.0).abs() < 1e-5));
        assert_eq!(v[v.len() - 1].pos, [64.0, 64.0, 8.0]);
        for t in i.chunks_exact(3) {
            let n = cross(
                sub(v[t[1] as usize].pos, v[t[0] as usize].pos),
                sub(v[t[2] as usize].pos, v[t[0] as usize].pos),
            );
            assert!(n[2] > 0.0);
        }
        assert!(face_triangles(&b, &b.faces[3]).is_none());
    }

    #[test]
    fn faces_belong_to_their_first_leaf_else_their_model_else_themselves() {
        // Leaves (48 bytes: leaf faces at 32, count at 36), then leaf
        // faces, then models (40 bytes: faces at 24, count at 28).
        let mut b = Vec::new();
        for (first, n) in [(0, 1), (1, 2)] {
            let mut leaf = [0u8; 48];
            leaf[32..36].copy_from_slice(&i32::to_le_bytes(first));
            leaf[36..40].copy_from_slice(&i32::to_le_bytes(n));
            b.extend_from_slice(&leaf);
        }
        for f in [2i32, 0, 2] {
            b.extend_from_slice(&f.to_le_bytes());
        }
        for (first, n) in [(0, 3), (3, 1)] {
            let mut model = [0u8; 40];
            model[24..28].copy_from_slice(&i32::to_le_bytes(first));
            model[28..32].copy_from_slice(&i32::to_le_bytes(n));
            b.extend_from_slice(&model);
        }
        let file = Path::new("m.bsp");
        let objects = |b: &[u8], n_faces| {
            face_objects(&Bytes::new(b, file), (0, 2), (96, 3), (108, 2), n_faces)
        };
        // Face 2 is in leaves 0 and 1 (the first wins), face 0 in leaf 1,
        // face 1 only in the world model (2 leaves + model 0), face 3 in
        // model 1, face 4 in nothing (2 + 2 + its own index).
        assert_eq!(objects(&b, 5).unwrap(), [1, 2, 0, 3, 8]);
        // A leaf face naming no face, and a model past the faces.
        let e = objects(&b, 2).unwrap_err();
        assert!(e.message.contains("leaf face 2 out of range (2)"), "{e}");
        let mut bad = b.clone();
        bad[96 + 4..96 + 8].copy_from_slice(&1i32.to_le_bytes());
        let e = objects(&bad, 3).unwrap_err();
        assert!(
            e.message.contains("model 1: faces 3+1 out of range (3)"),
            "{e}"
        );
        // A leaf whose leaf faces run past their lump.
        bad[36..40].copy_from_slice(&9i32.to_le_bytes());
        let e = objects(&bad, 5).unwrap_err();
        assert!(
            e.message
                .contains("leaf 0: leaf faces 0+9 out of range (3)"),
            "{e}"
        );
    }

    #[test]
    fn bsp_errors_name_file_and_offset() {
        let f = Path::new("bad.bsp");
        let e = parse_bsp(b"IBSQ", f).unwrap_err();
        assert_eq!((e.file.as_path(), e.offset), (f, Some(0)));
        let mut v = tiny_bsp();
        v[4] = 47;
        assert_eq!(parse_bsp(&v, f).unwrap_err().offset, Some(4));
        // A mesh vertex past its face's vertices.
        let mut v = tiny_bsp();
        let moff = i32::from_le_bytes(v[8 + 8 * 11..8 + 8 * 11 + 4].try_into().unwrap()) as usize;
        v[moff + 4..moff + 8].copy_from_slice(&9i32.to_le_bytes());
        let e = parse_bsp(&v, f).unwrap_err();
        assert_eq!(e.offset, Some(moff as u64 + 4), "{e}");
        // A face whose vertices run past the lump.
        let mut v = tiny_bsp();
        let foff = i32::from_le_bytes(v[8 + 8 * 13..8 + 8 * 13 + 4].try_into().unwrap()) as usize;
        v[foff + 16..foff + 20].copy_from_slice(&1000i32.to_le_bytes());
        let e = parse_bsp(&v, f).unwrap_err();
        assert_eq!(e.offset, Some(foff as u64 + 12), "{e}");
        // A bad patch size.
        let mut v = tiny_bsp();
        v[foff + 104 + 96..foff + 104 + 100].copy_from_slice(&2i32.to_le_bytes());
        assert!(parse_bsp(&v, f).unwrap_err().message.contains("patch"));
        let v = tiny_bsp();
        let e = parse_bsp(&v[..v.len() - 1], f).unwrap_err();
        assert!(e.message.contains("outside the file"), "{e}");
    }

    proptest! {
        #[test]
        fn bsp_random_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..600)) {
            if let Err(e) = parse_bsp(&bytes, Path::new("r.bsp")) {
                prop_assert_eq!(e.file, PathBuf::from("r.bsp"));
                prop_assert!(e.offset.is_some());
            }
        }

        #[test]
        fn bsp_truncations_are_errors(cut in 0usize..60_000) {
            let v = tiny_bsp();
            let cut = cut % v.len();
            let e = parse_bsp(&v[..cut], Path::new("t.bsp")).unwrap_err();
            prop_assert!(e.offset.unwrap() <= v.len() as u64);
        }

        #[test]
        fn bsp_corruptions_never_panic(at in 0usize..2000, byte in any::<u8>()) {
            let mut v = tiny_bsp();
            v[at % 2000] = byte;
            if let Ok(b) = parse_bsp(&v, Path::new("c.bsp")) {
                for f in &b.faces {
                    let _ = face_triangles(&b, f);
                }
                let _ = parse_entities(&b.entities, Path::new("c.bsp"), 0);
            }
        }

        #[test]
        fn tga_random_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..300)) {
            if let Ok((w, h, rgba)) = decode_tga(&bytes, Path::new("r.tga")) {
                prop_assert_eq!(rgba.len(), (w * h * 4) as usize);
            }
        }

        #[test]
        fn tga_truncations_are_errors(cut in 0usize..200, rle in any::<bool>()) {
            let v = tiny_tga(rle, false);
            let cut = cut % v.len();
            prop_assert!(decode_tga(&v[..cut], Path::new("t.tga")).is_err());
        }

        #[test]
        fn text_parsers_never_panic(text in "[{}\"a-z/* \n]{0,80}") {
            let _ = parse_entities(&text, Path::new("e"), 0);
            let _ = parse_shaders(&text, Path::new("s.shader"));
        }
    }
}
