//! Immediate mode: glBegin(mode), the vertices glVertex* gives, each with
//! the current texture coordinates of every unit (glTexCoord*,
//! glMultiTexCoord*), then glEnd. The block is drawn as
//! glDrawArrays(mode, 0, n) over client arrays holding those vertices
//! would be ([`Block::arrays`]), so it gets the same assembly, transform,
//! clipping, per-draw state and texture units as an array draw.
//!
//! The current colour (glColor*) and normal (glNormal*) are tracked, as
//! the colour and normal arrays are, and read by no part of the model.
//! A call GL forbids between glBegin and glEnd is the error GL raises
//! (GL_INVALID_OPERATION); glArrayElement, glEvalCoord*, glEvalPoint* and
//! glVertexAttrib* there make the block a draw that needs what is not
//! modelled.

use super::args::{self, CallError};
use super::arrays::{Array, Arrays, Source};
use super::enums as gl;
use wasp_gltrace::Call;

/// One glBegin .. glEnd block.
#[derive(Clone, Debug, PartialEq)]
pub struct Block {
    /// glBegin's call number.
    pub begin: u64,
    /// The primitive (glBegin's mode).
    pub mode: i64,
    /// The vertices (x, y, z, w) in issue order.
    pub vertices: Vec<[f64; 4]>,
    /// Each vertex's texture coordinates (s, t, r, q), per texture unit.
    pub texcoords: Vec<Vec<[f64; 4]>>,
    /// A call in the block that is not modelled, if any.
    pub unsupported: Option<String>,
}

/// Immediate-mode state: the current attributes and the blocks.
#[derive(Clone, Debug, PartialEq)]
pub struct Immediate {
    /// The current texture coordinates per texture unit (GL's initial
    /// (0, 0, 0, 1)).
    pub texcoord: Vec<[f64; 4]>,
    /// The current colour (initial (1, 1, 1, 1)), in 0..1 for integer
    /// types as GL converts them.
    pub colour: [f64; 4],
    /// The current normal (initial (0, 0, 1)).
    pub normal: [f64; 3],
    /// The block being specified (after glBegin, before glEnd).
    pub open: Option<Block>,
    /// The block the last glEnd closed: the draw it makes.
    pub ended: Option<Block>,
}

impl Immediate {
    /// The initial state with `units` texture units.
    pub fn new(units: usize) -> Self {
        Self {
            texcoord: vec![[0.0, 0.0, 0.0, 1.0]; units],
            colour: [1.0; 4],
            normal: [0.0, 0.0, 1.0],
            open: None,
            ended: None,
        }
    }
}

/// What an immediate-mode call was.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Step {
    /// Not an immediate-mode call: the tracker applies it.
    Other,
    /// It changed the immediate-mode state.
    Modelled,
    /// Counted under this name (glVertex outside a block, whose result GL
    /// leaves undefined).
    Unmodelled(String),
    /// glEnd: [`Immediate::ended`] is the draw.
    End,
}

/// The attribute a glVertex / glTexCoord / glMultiTexCoord / glColor /
/// glNormal call sets.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Attr {
    Vertex,
    TexCoord,
    MultiTexCoord,
    Colour,
    Normal,
}

/// An attribute call's name parsed: the attribute, its component count,
/// its component type suffix and whether it passes a vector.
fn parse(name: &str) -> Option<(Attr, usize, &str, bool)> {
    let name = name
        .strip_suffix("ARB")
        .or_else(|| name.strip_suffix("EXT"))
        .unwrap_or(name);
    let (attr, rest, sizes) = [
        ("glVertex", Attr::Vertex, 2..=4),
        ("glTexCoord", Attr::TexCoord, 1..=4),
        ("glMultiTexCoord", Attr::MultiTexCoord, 1..=4),
        ("glColor", Attr::Colour, 3..=4),
        ("glNormal", Attr::Normal, 3..=3),
    ]
    .into_iter()
    .find_map(|(p, a, s)| name.strip_prefix(p).map(|r| (a, r, s)))?;
    let n = rest.chars().next()?.to_digit(10)? as usize;
    let ty = &rest[1..];
    let (ty, vector) = ty.strip_suffix('v').map_or((ty, false), |t| (t, true));
    let types = ["b", "s", "i", "f", "d", "ub", "us", "ui"];
    (sizes.contains(&n) && types.contains(&ty)).then_some((attr, n, ty, vector))
}

/// Calls GL allows between glBegin and glEnd besides the attributes
/// [`parse`] reads: those that make the block unmodelled, and those
/// counted as not modelled (material, edge flag, index, fog coordinate
/// and secondary colour, display lists).
fn allowed_in_block(name: &str) -> (bool, bool) {
    let unmodelled_draw = [
        "glArrayElement",
        "glEvalCoord",
        "glEvalPoint",
        "glVertexAttrib",
    ];
    let counted = [
        "glMaterial",
        "glEdgeFlag",
        "glIndex",
        "glFogCoord",
        "glSecondaryColor",
        "glCallList",
    ];
    let starts = |l: &[&str]| l.iter().any(|p| name.starts_with(p));
    (starts(&unmodelled_draw), starts(&counted))
}

/// A colour component of type `ty` in 0..1 as GL converts it (floats as
/// given).
fn colour_component(v: f64, ty: &str) -> f64 {
    let bits = |b: i32| 2f64.powi(b) - 1.0;
    match ty {
        "ub" => v / bits(8),
        "us" => v / bits(16),
        "ui" => v / bits(32),
        "b" => (2.0 * v + 1.0) / bits(8),
        "s" => (2.0 * v + 1.0) / bits(16),
        "i" => (2.0 * v + 1.0) / bits(32),
        _ => v,
    }
}

impl Immediate {
    /// Apply `call` if it is an immediate-mode one; `Err` for what GL
    /// raises an error on.
    pub fn apply(&mut self, call: &Call) -> Result<Step, CallError> {
        let name: &str = &call.name;
        match name {
            "glBegin" => {
                let mode = args::int(call, 0)?;
                if self.open.is_some() {
                    return Err(invalid(call, "glBegin inside a glBegin/glEnd block"));
                }
                if !(gl::POINTS..=gl::POLYGON).contains(&mode) {
                    return Err(CallError::at(
                        call,
                        format!("mode {}: not a primitive (GL_INVALID_ENUM)", gl::name(mode)),
                    ));
                }
                self.open = Some(Block {
                    begin: call.no,
                    mode,
                    vertices: Vec::new(),
                    texcoords: Vec::new(),
                    unsupported: None,
                });
                return Ok(Step::Modelled);
            }
            "glEnd" => {
                let Some(b) = self.open.take() else {
                    return Err(invalid(call, "glEnd without a glBegin"));
                };
                self.ended = Some(b);
                return Ok(Step::End);
            }
            _ => {}
        }
        if let Some((attr, n, ty, vector)) = parse(name) {
            return self.attribute(call, attr, n, ty, vector);
        }
        let Some(block) = &mut self.open else {
            return Ok(Step::Other);
        };
        match allowed_in_block(name) {
            (true, _) => {
                block.unsupported.get_or_insert_with(|| name.to_string());
                Ok(Step::Modelled)
            }
            (_, true) => Ok(Step::Other),
            // Window-system calls (glX*) are not GL commands.
            _ if name.starts_with("glX") || !name.starts_with("gl") => Ok(Step::Other),
            _ => Err(invalid(call, "not allowed between glBegin and glEnd")),
        }
    }

    /// An attribute call: the current attribute set, and for glVertex a
    /// vertex of the open block.
    fn attribute(
        &mut self,
        call: &Call,
        attr: Attr,
        n: usize,
        ty: &str,
        vector: bool,
    ) -> Result<Step, CallError> {
        let first = usize::from(attr == Attr::MultiTexCoord);
        let v = if vector {
            args::nums(call, first, n)?
        } else {
            (first..first + n)
                .map(|i| args::num(call, i))
                .collect::<Result<Vec<_>, _>>()?
        };
        let mut c = [0.0, 0.0, 0.0, 1.0];
        c[..n].copy_from_slice(&v);
        match attr {
            Attr::Vertex => {
                let Some(block) = &mut self.open else {
                    return Ok(Step::Unmodelled(format!(
                        "{} outside glBegin/glEnd",
                        call.name
                    )));
                };
                block.vertices.push(c);
                block.texcoords.push(self.texcoord.clone());
            }
            Attr::TexCoord => self.texcoord[0] = c,
            Attr::MultiTexCoord => {
                let target = args::int(call, 0)?;
                let unit = usize::try_from(target - gl::TEXTURE0)
                    .ok()
                    .filter(|&u| u < self.texcoord.len())
                    .ok_or_else(|| {
                        CallError::at(
                            call,
                            format!(
                                "target {}: expected GL_TEXTURE0 to GL_TEXTURE{} \
                                 (GL_INVALID_ENUM)",
                                gl::name(target),
                                self.texcoord.len() - 1
                            ),
                        )
                    })?;
                self.texcoord[unit] = c;
            }
            Attr::Colour => {
                let mut rgba = c.map(|x| colour_component(x, ty));
                if n == 3 {
                    rgba[3] = 1.0;
                }
                self.colour = rgba;
            }
            Attr::Normal => self.normal = [c[0], c[1], c[2]],
        }
        Ok(Step::Modelled)
    }
}

/// GL_INVALID_OPERATION at `call`.
fn invalid(call: &Call, what: &str) -> CallError {
    CallError::at(call, format!("{what} (GL_INVALID_OPERATION)"))
}

/// Doubles as little-endian bytes.
fn doubles(v: impl Iterator<Item = [f64; 4]>) -> Source {
    Source::Client(
        v.flat_map(|c| c.into_iter().flat_map(f64::to_le_bytes))
            .collect(),
    )
}

impl Block {
    /// Client arrays holding the block's vertices and texture coordinates
    /// as four doubles each (so every value reads back exactly), all
    /// enabled: glDrawArrays(mode, 0, n) over them draws the block.
    pub fn arrays(&self) -> Arrays {
        let array = |source| Array {
            size: 4,
            ty: gl::DOUBLE,
            stride: 32,
            source,
            enabled: true,
        };
        let units = self.texcoords.first().map_or(0, Vec::len);
        let mut a = Arrays::new(units);
        a.vertex = Some(array(doubles(self.vertices.iter().copied())));
        for (u, slot) in a.texcoord.iter_mut().enumerate() {
            *slot = Some(array(doubles(self.texcoords.iter().map(|t| t[u]))));
        }
        a
    }
}

#[cfg(test)]
mod tests {
    use super::super::args::test_calls::*;
    use super::super::import::{import, ImportOptions, Imported};
    use super::*;
    use crate::raster::{rasterize, Frame, RasterOptions};
    use std::path::Path;
    use wasp_gltrace::Value;

    /// A vertex: position (x, y, z) and unit 0's texture coordinates.
    type Vert = ([f32; 3], [f32; 2]);

    /// The square (x0, y0)-(x1, y1) at depth `z` as GL_QUADS vertices,
    /// texture coordinates 0..1 across it.
    fn square(x0: f32, y0: f32, x1: f32, y1: f32, z: f32) -> Vec<Vert> {
        vec![
            ([x0, y0, z], [0.0, 0.0]),
            ([x1, y0, z], [1.0, 0.0]),
            ([x1, y1, z], [1.0, 1.0]),
            ([x0, y1, z], [0.0, 1.0]),
        ]
    }

    /// A 64x64 window: glOrtho(0, 64, 0, 64, -1, 1), GL_LESS depth test,
    /// a 2x2 texture on unit 0 with a texture matrix scaling by 2, then
    /// each primitive (mode, vertices) drawn in immediate mode or with
    /// client arrays and glDrawArrays; one swap.
    fn frame(immediate: bool, prims: &[(i64, Vec<Vert>)]) -> Vec<Call> {
        let i = Value::SInt;
        let px = Value::Blob((0..16).collect());
        let mut c = vec![
            call(0, "glViewport", vec![i(0), i(0), i(64), i(64)]),
            call(0, "glMatrixMode", vec![e(gl::PROJECTION)]),
            call(
                0,
                "glOrtho",
                [0.0, 64.0, 0.0, 64.0, -1.0, 1.0].map(f).into(),
            ),
            call(0, "glMatrixMode", vec![e(gl::TEXTURE)]),
            call(0, "glScalef", vec![f(2.0), f(2.0), f(1.0)]),
            call(0, "glEnable", vec![e(gl::DEPTH_TEST)]),
            call(0, "glDepthFunc", vec![e(gl::NEVER + 1)]),
            call(0, "glEnable", vec![e(gl::TEXTURE_2D)]),
            call(0, "glBindTexture", vec![e(gl::TEXTURE_2D), i(5)]),
            call(
                0,
                "glTexImage2D",
                vec![
                    e(gl::TEXTURE_2D),
                    i(0),
                    e(gl::RGBA),
                    i(2),
                    i(2),
                    i(0),
                    e(gl::RGBA),
                    e(gl::UNSIGNED_BYTE),
                    px,
                ],
            ),
        ];
        if !immediate {
            c.push(call(0, "glEnableClientState", vec![e(gl::VERTEX_ARRAY)]));
            let tc = e(gl::TEXTURE_COORD_ARRAY);
            c.push(call(0, "glEnableClientState", vec![tc]));
        }
        for (mode, verts) in prims {
            if immediate {
                c.push(call(0, "glBegin", vec![e(*mode)]));
                for (p, t) in verts {
                    c.push(call(
                        0,
                        "glTexCoord2fv",
                        vec![Value::Array(t.map(f).into())],
                    ));
                    c.push(call(0, "glVertex3f", p.map(f).into()));
                }
                c.push(call(0, "glEnd", vec![]));
                continue;
            }
            let pos: Vec<f32> = verts.iter().flat_map(|v| v.0).collect();
            let tex: Vec<f32> = verts.iter().flat_map(|v| v.1).collect();
            let ptr = |n, d| vec![i(n), e(gl::FLOAT), i(0), floats(d)];
            c.push(call(0, "glTexCoordPointer", ptr(2, &tex)));
            c.push(call(0, "glVertexPointer", ptr(3, &pos)));
            let n = verts.len() as i64;
            c.push(call(0, "glDrawArrays", vec![e(*mode), i(0), i(n)]));
        }
        c.push(call(0, "glXSwapBuffers", vec![]));
        for (n, k) in c.iter_mut().enumerate() {
            k.no = n as u64;
        }
        c
    }

    fn run(calls: Vec<Call>) -> Result<(Imported, Frame), String> {
        let imp = import(
            calls.into_iter().map(Ok),
            Path::new("t.trace"),
            ImportOptions::default(),
        )
        .map_err(|e| e.to_string())?;
        let opts = RasterOptions {
            threads: 1,
            ..Default::default()
        };
        let f = rasterize(&imp.scene, imp.width, imp.height, &opts).unwrap();
        Ok((imp, f))
    }

    /// The frame both ways: the immediate-mode import, after checking
    /// that its meshes, materials (but their names), quads and rejects
    /// are the array draws' exactly.
    fn both_ways(prims: &[(i64, Vec<Vert>)]) -> (Imported, Frame) {
        let (ai, af) = run(frame(false, prims)).unwrap();
        let (ii, inf) = run(frame(true, prims)).unwrap();
        assert_eq!(ii.scene.meshes, ai.scene.meshes);
        let unnamed = |i: &Imported| {
            let mut m = i.scene.materials.clone();
            m.iter_mut().for_each(|m| m.name.clear());
            m
        };
        assert_eq!(unnamed(&ii), unnamed(&ai));
        assert_eq!((ii.draw_calls, ii.triangles), (ai.draw_calls, ai.triangles));
        let s = |f: &Frame| {
            let m: Vec<_> = f
                .stats
                .materials
                .iter()
                .map(|m| (m.warps, m.pixels))
                .collect();
            (
                f.stats.warps,
                f.stats.quads_rejected_early_z,
                f.stats.positions,
                m,
            )
        };
        assert_eq!(s(&inf), s(&af));
        (ii, inf)
    }

    #[test]
    fn an_immediate_quad_draws_exactly_as_the_same_quad_from_arrays() {
        // As in the import tests: the near square covers 32x32 pixels and
        // rejects its area of the far one (plus the 16 quads of its
        // diagonal); the texture matrix doubles the coordinates.
        let near = square(0.0, 0.0, 32.0, 32.0, 0.5);
        let far = square(0.0, 0.0, 64.0, 64.0, -0.5);
        let (imp, f) = both_ways(&[(gl::QUADS, near), (gl::QUADS, far)]);
        assert_eq!((imp.draw_calls, imp.triangles), (2, 4));
        // Numbered by their glBegin calls.
        assert_eq!(imp.draw_call_numbers, [10, 20]);
        assert_eq!(f.stats.materials[0].warps, 16 * 16 + 16);
        assert_eq!(f.stats.quads_rejected_early_z, 16 * 16 + 16);
        assert_eq!(f.stats.materials[1].warps, 32 * 32 - 16 * 16 + 16);
        assert_eq!(imp.scene.meshes[0].uv[2], [2.0, 2.0]);
        assert_eq!(imp.scene.materials[0].name, "call 10");
    }

    #[test]
    fn strips_fans_triangles_and_polygons_match_their_array_draws() {
        let sq = square(8.0, 8.0, 40.0, 24.0, 0.0);
        let strip = vec![sq[0], sq[1], sq[3], sq[2]];
        let tri: Vec<Vert> = [0, 1, 2, 0, 2, 3].iter().map(|&k| sq[k]).collect();
        let prims = [
            (gl::TRIANGLE_STRIP, strip.clone()),
            (gl::TRIANGLE_FAN, sq.clone()),
            (gl::POLYGON, sq.clone()),
            (gl::TRIANGLES, tri),
            (gl::QUAD_STRIP, strip),
        ];
        let (imp, f) = both_ways(&prims);
        assert_eq!((imp.draw_calls, imp.triangles), (5, 10));
        // Each covers the same 32x16 pixels; the first is shaded, the
        // rest fail GL_LESS against it.
        assert_eq!(f.stats.materials[0].pixels, 32 * 16);
        assert!(f.stats.materials[1..].iter().all(|m| m.warps == 0));
    }

    #[test]
    fn an_array_draw_without_coordinates_uses_the_current_ones() {
        let mut calls = frame(false, &[(gl::QUADS, square(0.0, 0.0, 8.0, 8.0, 0.0))]);
        calls.retain(|c| c.args.first() != Some(&e(gl::TEXTURE_COORD_ARRAY)));
        let tc = call(
            0,
            "glMultiTexCoord2f",
            vec![e(gl::TEXTURE0), f(0.5), f(0.25)],
        );
        calls.insert(1, tc);
        let (imp, _) = run(calls).unwrap();
        // Through the texture matrix (x2).
        assert!(imp.scene.meshes[0].uv.iter().all(|&t| t == [1.0, 0.5]));
    }

    #[test]
    fn lines_and_points_are_refused_as_array_draws_are() {
        let l = square(0.0, 0.0, 8.0, 8.0, 0.0);
        for mode in [gl::LINES, gl::LINE_STRIP, gl::LINE_LOOP, gl::POINTS] {
            let a = run(frame(false, &[(mode, l.clone())])).unwrap_err();
            let i = run(frame(true, &[(mode, l.clone())])).unwrap_err();
            assert!(i.contains("call 19 (glEnd)") && i.contains("primitive type GL_"));
            assert_eq!(
                i.replace("call 19 (glEnd)", "x"),
                a.replace("call 14 (glDrawArrays)", "x")
            );
        }
    }

    /// Applies the call `name` with arguments `a` to `m`.
    fn go(m: &mut Immediate, name: &str, a: Vec<Value>) -> Result<Step, CallError> {
        m.apply(&call(3, name, a))
    }

    /// A glBegin(GL_TRIANGLES) block of three vertices in every vertex
    /// form, between attributes in every form, texture unit 1 included,
    /// in an `Immediate` of 2 texture units; `errors` adds, before its
    /// glEnd, calls that GL refuses inside a block, and after it calls
    /// refused outside one (each checked for its error).
    fn block_of_every_form(errors: bool) -> Immediate {
        let mut m = Immediate::new(2);
        let i = Value::SInt;
        assert_eq!(
            go(&mut m, "glVertex2f", vec![f(1.0), f(2.0)]),
            Ok(Step::Unmodelled("glVertex2f outside glBegin/glEnd".into()))
        );
        assert_eq!(
            go(&mut m, "glBegin", vec![e(gl::TRIANGLES)]),
            Ok(Step::Modelled)
        );
        go(
            &mut m,
            "glMultiTexCoord2fARB",
            vec![e(gl::TEXTURE0 + 1), f(0.5), f(0.25)],
        )
        .unwrap();
        go(&mut m, "glColor4ub", vec![i(255), i(0), i(51), i(255)]).unwrap();
        go(&mut m, "glNormal3f", vec![f(0.0), f(1.0), f(0.0)]).unwrap();
        go(&mut m, "glVertex2i", vec![i(3), i(4)]).unwrap();
        go(&mut m, "glTexCoord1d", vec![Value::Double(0.75)]).unwrap();
        let v = Value::Array([1.0, 2.0, 3.0].map(Value::Double).into());
        go(&mut m, "glVertex3dv", vec![v]).unwrap();
        go(&mut m, "glVertex4s", vec![i(1), i(2), i(3), i(2)]).unwrap();
        if errors {
            assert!(go(&mut m, "glViewport", vec![])
                .unwrap_err()
                .message
                .contains("INVALID_OPERATION"));
            assert!(go(&mut m, "glBegin", vec![e(gl::TRIANGLES)]).is_err());
        }
        assert_eq!(go(&mut m, "glEnd", vec![]), Ok(Step::End));
        if errors {
            assert!(go(&mut m, "glEnd", vec![])
                .unwrap_err()
                .message
                .contains("without a glBegin"));
            assert!(go(&mut m, "glBegin", vec![e(10)])
                .unwrap_err()
                .message
                .contains("INVALID_ENUM"));
            assert!(go(
                &mut m,
                "glMultiTexCoord2f",
                vec![e(gl::TEXTURE0 + 2), f(0.), f(0.)]
            )
            .is_err());
            assert!(go(&mut m, "glVertex3f", vec![f(1.0)]).is_err());
        }
        m
    }

    #[test]
    fn every_vertex_form_and_unit_reads() {
        let m = block_of_every_form(false);
        let b = m.ended.clone().unwrap();
        assert_eq!(
            b.vertices,
            [
                [3.0, 4.0, 0.0, 1.0],
                [1.0, 2.0, 3.0, 1.0],
                [1.0, 2.0, 3.0, 2.0]
            ]
        );
        let t0: Vec<_> = b.texcoords.iter().map(|t| t[0]).collect();
        assert_eq!(
            t0,
            [
                [0.0, 0.0, 0.0, 1.0],
                [0.75, 0.0, 0.0, 1.0],
                [0.75, 0.0, 0.0, 1.0]
            ]
        );
        assert!(b.texcoords.iter().all(|t| t[1] == [0.5, 0.25, 0.0, 1.0]));
        assert_eq!(
            (m.colour, m.normal),
            ([1.0, 0.0, 0.2, 1.0], [0.0, 1.0, 0.0])
        );
    }

    #[test]
    fn gl_errors_are_errors_and_leave_the_block_as_it_was() {
        let m = block_of_every_form(true);
        let clean = block_of_every_form(false);
        assert_eq!(
            (m.ended, m.colour, m.normal),
            (clean.ended, clean.colour, clean.normal)
        );
    }

    #[test]
    fn a_block_with_array_elements_is_unsupported() {
        // A block with glArrayElement needs what is not modelled.
        let mut m = block_of_every_form(false);
        go(&mut m, "glBegin", vec![e(gl::TRIANGLES)]).unwrap();
        go(&mut m, "glArrayElement", vec![Value::SInt(0)]).unwrap();
        go(&mut m, "glEnd", vec![]).unwrap();
        assert_eq!(
            m.ended.unwrap().unsupported.as_deref(),
            Some("glArrayElement")
        );
    }

    #[test]
    fn calls_of_no_vertex_form_are_not_read() {
        let parsed = [
            "glVertexPointer",
            "glColorMaterial",
            "glTexCoord5f",
            "glNormal2f",
        ];
        assert!(parsed.iter().all(|n| parse(n).is_none()));
    }
}
