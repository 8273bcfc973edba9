//! Client vertex arrays and buffer objects: the vertex, texture
//! coordinate (one per texture unit, chosen by glClientActiveTexture),
//! colour and normal arrays, whether each is enabled, and the buffers
//! glBufferData / glBufferSubData filled.
//!
//! apitrace records an array in client memory at the draw that reads it:
//! before the draw it writes the array's `gl*Pointer` call again (a "fake"
//! call) with the array's bytes from its start to the last vertex the draw
//! reads as a blob, so element `i` of the blob's array is at `i * stride`.
//! A pointer call with an address and no buffer bound leaves the array's
//! data unknown until such a call comes.

use super::args::{self, CallError, Pointer};
use super::enums as gl;
use std::collections::HashMap;
use std::sync::Arc;
use wasp_gltrace::Call;

/// Where an array's bytes are.
#[derive(Clone, Debug, PartialEq)]
pub enum Source {
    /// Recorded client memory.
    Client(Arc<[u8]>),
    /// Buffer object `id` from byte `offset`.
    Buffer { id: u32, offset: u64 },
    /// Client memory at this address, its bytes not recorded.
    Unknown(u64),
}

/// One array: components per element, their type, the stride in bytes
/// and the bytes.
#[derive(Clone, Debug, PartialEq)]
pub struct Array {
    /// Components per element (1 to 4).
    pub size: usize,
    /// The component type (a GL enum).
    pub ty: i64,
    /// Bytes from one element to the next.
    pub stride: usize,
    /// The bytes.
    pub source: Source,
    /// Whether the array is enabled (glEnableClientState).
    pub enabled: bool,
}

/// Bytes of one component of type `ty`, or `None` for a type the importer
/// does not read.
fn type_bytes(ty: i64) -> Option<usize> {
    match ty {
        gl::BYTE | gl::UNSIGNED_BYTE => Some(1),
        gl::SHORT | gl::UNSIGNED_SHORT => Some(2),
        gl::INT | gl::UNSIGNED_INT | gl::FLOAT => Some(4),
        gl::DOUBLE => Some(8),
        _ => None,
    }
}

/// Component `k` of type `ty` at `at` in `bytes` (little-endian, as
/// apitrace records the machine's memory on x86 and ARM).
fn component(bytes: &[u8], at: usize, ty: i64) -> Option<f64> {
    let n = type_bytes(ty)?;
    let b = bytes.get(at..at + n)?;
    Some(match ty {
        gl::BYTE => f64::from(b[0] as i8),
        gl::UNSIGNED_BYTE => f64::from(b[0]),
        gl::SHORT => f64::from(i16::from_le_bytes([b[0], b[1]])),
        gl::UNSIGNED_SHORT => f64::from(u16::from_le_bytes([b[0], b[1]])),
        gl::INT => f64::from(i32::from_le_bytes([b[0], b[1], b[2], b[3]])),
        gl::UNSIGNED_INT => f64::from(u32::from_le_bytes([b[0], b[1], b[2], b[3]])),
        gl::FLOAT => f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]])),
        _ => f64::from_le_bytes(b.try_into().ok()?),
    })
}

/// The client arrays and buffer objects.
#[derive(Clone, Debug, Default)]
pub struct Arrays {
    /// The vertex array.
    pub vertex: Option<Array>,
    /// Texture coordinate arrays, per texture unit.
    pub texcoord: Vec<Option<Array>>,
    /// The colour array (read by no part of the model: recorded only).
    pub colour: Option<Array>,
    /// The normal array (likewise).
    pub normal: Option<Array>,
    /// glClientActiveTexture's unit.
    pub client_unit: usize,
    /// Buffer objects by name.
    pub buffers: HashMap<u32, Arc<Vec<u8>>>,
    /// GL_ARRAY_BUFFER's binding (0: none).
    pub array_buffer: u32,
    /// GL_ELEMENT_ARRAY_BUFFER's binding (0: none).
    pub element_buffer: u32,
}

/// Which array a pointer or client-state call names.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Which {
    Vertex,
    TexCoord,
    Colour,
    Normal,
}

impl Arrays {
    /// No arrays, `units` texture units.
    pub fn new(units: usize) -> Self {
        Self {
            texcoord: vec![None; units],
            ..Default::default()
        }
    }

    fn slot(&mut self, w: Which) -> &mut Option<Array> {
        match w {
            Which::Vertex => &mut self.vertex,
            Which::TexCoord => &mut self.texcoord[self.client_unit],
            Which::Colour => &mut self.colour,
            Which::Normal => &mut self.normal,
        }
    }

    /// glVertexPointer, glTexCoordPointer, glColorPointer (size, type,
    /// stride, pointer) and glNormalPointer (type, stride, pointer).
    pub fn pointer(&mut self, call: &Call) -> Result<(), CallError> {
        let (which, first) = match &*call.name {
            "glVertexPointer" | "glVertexPointerEXT" => (Which::Vertex, 0),
            "glTexCoordPointer" | "glTexCoordPointerEXT" => (Which::TexCoord, 0),
            "glColorPointer" | "glColorPointerEXT" => (Which::Colour, 0),
            _ => (Which::Normal, 1),
        };
        let size = if first == 0 { args::count(call, 0)? } else { 3 };
        let ty = args::int(call, 1 - first)?;
        let stride = args::count(call, 2 - first)?;
        let Some(tb) = type_bytes(ty) else {
            return Err(CallError::at(
                call,
                format!("component type {}: not modelled", gl::name(ty)),
            ));
        };
        if !(1..=4).contains(&size) {
            return Err(CallError::at(call, format!("size {size}: expected 1 to 4")));
        }
        let source = match args::pointer(call, 3 - first)? {
            Pointer::Data(d) => Source::Client(d),
            Pointer::Offset(o) if self.array_buffer != 0 => Source::Buffer {
                id: self.array_buffer,
                offset: o,
            },
            Pointer::Offset(o) => Source::Unknown(o),
        };
        let slot = self.slot(which);
        let enabled = slot.as_ref().is_some_and(|a| a.enabled);
        *slot = Some(Array {
            size,
            ty,
            stride: if stride == 0 { size * tb } else { stride },
            source,
            enabled,
        });
        Ok(())
    }

    /// glEnableClientState / glDisableClientState; `Err` for an array
    /// the model does not know (its name, to count).
    pub fn client_state(&mut self, array: i64, on: bool) -> Result<(), String> {
        let which = match array {
            gl::VERTEX_ARRAY => Which::Vertex,
            gl::TEXTURE_COORD_ARRAY => Which::TexCoord,
            gl::COLOR_ARRAY => Which::Colour,
            gl::NORMAL_ARRAY => Which::Normal,
            _ => return Err(gl::name(array)),
        };
        let slot = self.slot(which);
        match slot {
            Some(a) => a.enabled = on,
            None => {
                *slot = Some(Array {
                    size: 4,
                    ty: gl::FLOAT,
                    stride: 16,
                    source: Source::Unknown(0),
                    enabled: on,
                })
            }
        }
        Ok(())
    }

    /// glBindBuffer(target, buffer); `Err` for a target the model does not
    /// know.
    pub fn bind_buffer(&mut self, target: i64, id: u32) -> Result<(), String> {
        match target {
            gl::ARRAY_BUFFER => self.array_buffer = id,
            gl::ELEMENT_ARRAY_BUFFER => self.element_buffer = id,
            _ => return Err(gl::name(target)),
        }
        Ok(())
    }

    fn bound(&self, target: i64) -> u32 {
        if target == gl::ELEMENT_ARRAY_BUFFER {
            self.element_buffer
        } else {
            self.array_buffer
        }
    }

    /// glBufferData(target, size, data, usage): the bound buffer's bytes
    /// (zeros where no data was given).
    pub fn buffer_data(&mut self, call: &Call) -> Result<(), CallError> {
        let id = self.bound(args::int(call, 0)?);
        let size = args::count(call, 1)?;
        let mut bytes = vec![0u8; size];
        if let Some(d) = call.arg(2).as_bytes() {
            let n = d.len().min(size);
            bytes[..n].copy_from_slice(&d[..n]);
        }
        if id == 0 {
            return Err(CallError::at(call, "no buffer bound to the target"));
        }
        self.buffers.insert(id, Arc::new(bytes));
        Ok(())
    }

    /// glBufferSubData(target, offset, size, data).
    pub fn buffer_sub_data(&mut self, call: &Call) -> Result<(), CallError> {
        let id = self.bound(args::int(call, 0)?);
        let offset = args::count(call, 1)?;
        let size = args::count(call, 2)?;
        let data = call.arg(3).as_bytes().unwrap_or(&[]);
        let Some(buf) = self.buffers.get_mut(&id) else {
            return Err(CallError::at(call, format!("buffer {id} has no storage")));
        };
        let buf = Arc::make_mut(buf);
        let n = size.min(data.len());
        if offset + n > buf.len() {
            return Err(CallError::at(
                call,
                format!(
                    "bytes {offset}..{} past the buffer's {} bytes",
                    offset + n,
                    buf.len()
                ),
            ));
        }
        buf[offset..offset + n].copy_from_slice(&data[..n]);
        Ok(())
    }

    /// The bytes of `source` from its start.
    pub fn bytes<'a>(&'a self, source: &'a Source) -> Result<&'a [u8], String> {
        match source {
            Source::Client(d) => Ok(d),
            Source::Buffer { id, offset } => {
                let b = self
                    .buffers
                    .get(id)
                    .ok_or_else(|| format!("buffer {id} has no storage"))?;
                b.get(*offset as usize..)
                    .ok_or_else(|| format!("offset {offset} past buffer {id}'s end"))
            }
            Source::Unknown(a) => Err(format!(
                "array in client memory at {a:#x}: the capture recorded no data for it"
            )),
        }
    }
}

impl Array {
    /// Element `i` as (x, y, z, w) with GL's defaults (0, 0, 0, 1) for
    /// missing components, read from `bytes` (the array's bytes).
    pub fn element(&self, bytes: &[u8], i: usize) -> Result<[f64; 4], String> {
        let mut v = [0.0, 0.0, 0.0, 1.0];
        let tb = type_bytes(self.ty).unwrap_or(4);
        let at = i * self.stride;
        for (k, c) in v.iter_mut().enumerate().take(self.size) {
            *c = component(bytes, at + k * tb, self.ty).ok_or_else(|| {
                format!(
                    "element {i} past the array's {} recorded bytes (stride {})",
                    bytes.len(),
                    self.stride
                )
            })?;
        }
        Ok(v)
    }
}

/// Indices of glDrawElements (`count` of type `ty`) from `bytes`.
pub fn indices(bytes: &[u8], count: usize, ty: i64) -> Result<Vec<u32>, String> {
    let n = match ty {
        gl::UNSIGNED_BYTE => 1,
        gl::UNSIGNED_SHORT => 2,
        gl::UNSIGNED_INT => 4,
        _ => {
            return Err(format!(
                "index type {}: expected GL_UNSIGNED_BYTE, _SHORT or _INT",
                gl::name(ty)
            ))
        }
    };
    if bytes.len() < count * n {
        return Err(format!(
            "{count} indices of {n} bytes, but {} bytes recorded",
            bytes.len()
        ));
    }
    Ok(bytes[..count * n]
        .chunks_exact(n)
        .map(|c| match n {
            1 => u32::from(c[0]),
            2 => u32::from(u16::from_le_bytes([c[0], c[1]])),
            _ => u32::from_le_bytes([c[0], c[1], c[2], c[3]]),
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::super::args::test_calls::*;
    use super::*;
    use wasp_gltrace::Value;

    /// `name(size, ty, stride, ptr)` numbered `no`.
    fn ptr(no: u64, name: &str, size: i64, ty: i64, stride: i64, p: Value) -> Call {
        let i = Value::SInt;
        call(no, name, vec![i(size), e(ty), i(stride), p])
    }

    #[test]
    fn recorded_arrays_and_buffers_give_their_elements() {
        let mut a = Arrays::new(2);
        a.client_state(gl::VERTEX_ARRAY, true).unwrap();
        // Interleaved x, y, z, pad: stride 16.
        let data = floats(&[1.0, 2.0, 3.0, 9.0, 4.0, 5.0, 6.0, 9.0]);
        a.pointer(&ptr(1, "glVertexPointer", 3, gl::FLOAT, 16, data))
            .unwrap();
        let v = a.vertex.clone().unwrap();
        assert!(
            v.enabled,
            "enabling before the pointer call keeps it enabled"
        );
        let bytes = a.bytes(&v.source).unwrap();
        assert_eq!(v.element(bytes, 1).unwrap(), [4.0, 5.0, 6.0, 1.0]);
        assert!(v.element(bytes, 2).unwrap_err().contains("past"));
        // Unit 1's texcoords from a buffer at offset 4, shorts.
        a.bind_buffer(gl::ARRAY_BUFFER, 7).unwrap();
        let bytes: Vec<u8> = [0u16, 0, 10, 20, 30, 40]
            .iter()
            .flat_map(|x| x.to_le_bytes())
            .collect();
        a.buffer_data(&call(
            2,
            "glBufferData",
            vec![
                e(gl::ARRAY_BUFFER),
                Value::SInt(12),
                Value::Blob(bytes),
                e(0),
            ],
        ))
        .unwrap();
        a.client_unit = 1;
        a.pointer(&ptr(
            3,
            "glTexCoordPointer",
            2,
            gl::SHORT,
            0,
            Value::Opaque(4),
        ))
        .unwrap();
        a.buffer_sub_data(&call(
            4,
            "glBufferSubData",
            vec![
                e(gl::ARRAY_BUFFER),
                Value::SInt(8),
                Value::SInt(2),
                Value::Blob(vec![31, 0]),
            ],
        ))
        .unwrap();
        let t = a.texcoord[1].clone().unwrap();
        assert_eq!(t.source, Source::Buffer { id: 7, offset: 4 });
        let bytes = a.bytes(&t.source).unwrap();
        assert_eq!(t.element(bytes, 1).unwrap(), [31.0, 40.0, 0.0, 1.0]);
        assert!(a.texcoord[0].is_none());
        // An address with no buffer bound: data unknown, said at use.
        a.bind_buffer(gl::ARRAY_BUFFER, 0).unwrap();
        a.pointer(&ptr(
            5,
            "glColorPointer",
            4,
            gl::UNSIGNED_BYTE,
            0,
            Value::Opaque(0x1000),
        ))
        .unwrap();
        let c = a.colour.clone().unwrap();
        assert!(a.bytes(&c.source).unwrap_err().contains("0x1000"));
        assert_eq!(a.client_state(0x1234, true), Err("0x1234".into()));
    }

    #[test]
    fn indices_read_each_type_and_refuse_short_data() {
        assert_eq!(
            indices(&[1, 0, 2, 0], 2, gl::UNSIGNED_SHORT).unwrap(),
            [1, 2]
        );
        assert_eq!(indices(&[5, 6], 2, gl::UNSIGNED_BYTE).unwrap(), [5, 6]);
        assert_eq!(
            indices(&[1, 0, 0, 1], 1, gl::UNSIGNED_INT).unwrap(),
            [0x0100_0001]
        );
        assert!(indices(&[1, 0], 2, gl::UNSIGNED_SHORT).is_err());
        assert!(indices(&[1], 1, gl::FLOAT)
            .unwrap_err()
            .contains("index type"));
    }
}
