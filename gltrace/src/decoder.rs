//! The decoder of values and signatures: the typed values of apitrace's
//! format (null, booleans, integers, floats, strings, blobs, enums,
//! bitmasks, arrays, structs, opaque pointers, dual representations, wide
//! strings) and the signatures that are defined on their first use by id
//! (functions, enums, bitmasks, structs, backtrace frames).

use crate::error::Fault;
use crate::stream::Stream;
use crate::Value;
use std::sync::Arc;

/// Signature ids are small: apitrace gives each function, enum, bitmask
/// and struct type a fixed id in its tables (a few thousand for GL). A
/// larger id is refused as corrupt, so that it cannot make a huge table.
pub(crate) const MAX_SIG_ID: u64 = 1 << 20;
/// Values nest (arrays of structs of arrays...) a few levels in real
/// captures; deeper nesting is refused as corrupt rather than overflowing
/// the stack.
const MAX_DEPTH: u32 = 64;

/// A function's signature: its name and argument names.
#[derive(Debug)]
pub(crate) struct FunctionSig {
    pub name: Arc<str>,
    pub arg_names: Arc<[String]>,
}

/// A table of signatures by id.
pub(crate) struct IdTable<T> {
    slots: Vec<Option<T>>,
}

impl<T> IdTable<T> {
    pub(crate) fn new() -> IdTable<T> {
        IdTable { slots: Vec::new() }
    }

    /// The signature `id` if it was defined; an error for an id past
    /// [`MAX_SIG_ID`].
    #[inline]
    pub(crate) fn get(&self, id: u64, what: &str, at: u64) -> Result<Option<&T>, Fault> {
        if id >= MAX_SIG_ID {
            return Err(Fault::corrupt(
                at,
                format!("{what} signature id {id} is out of range (ids are below {MAX_SIG_ID})"),
            ));
        }
        Ok(self.slots.get(id as usize).and_then(Option::as_ref))
    }

    /// Defines signature `id` (already checked by [`IdTable::get`]).
    pub(crate) fn define(&mut self, id: u64, sig: T) {
        let i = id as usize;
        if i >= self.slots.len() {
            self.slots.resize_with(i + 1, || None);
        }
        self.slots[i] = Some(sig);
    }
}

/// The value and signature decoder over the stream.
pub(crate) struct Decoder {
    pub stream: Stream,
    /// The format version (from the header): versions before 3 encode
    /// enums differently.
    pub version: u64,
    pub functions: IdTable<Arc<FunctionSig>>,
    structs: IdTable<(Arc<str>, Arc<[String]>)>,
    /// Defined enum signatures; the value is the enum's own only for
    /// version-2 captures (one name and value per signature).
    enums: IdTable<i64>,
    bitmasks: IdTable<()>,
    frames: IdTable<()>,
}

impl Decoder {
    pub(crate) fn new(stream: Stream, version: u64) -> Decoder {
        Decoder {
            stream,
            version,
            functions: IdTable::new(),
            structs: IdTable::new(),
            enums: IdTable::new(),
            bitmasks: IdTable::new(),
            frames: IdTable::new(),
        }
    }

    /// A function signature: `id`, then on its first occurrence the name,
    /// the argument count and the argument names.
    pub(crate) fn function_sig(&mut self) -> Result<Arc<FunctionSig>, Fault> {
        let at = self.stream.offset();
        let id = self.stream.uint()?;
        if let Some(sig) = self.functions.get(id, "function", at)? {
            return Ok(Arc::clone(sig));
        }
        let name: Arc<str> = self.stream.string()?.into();
        let count = self.stream.uint()?;
        let mut arg_names = Vec::with_capacity(count.min(64) as usize);
        for _ in 0..count {
            arg_names.push(self.stream.string()?);
        }
        let sig = Arc::new(FunctionSig {
            name,
            arg_names: arg_names.into(),
        });
        self.functions.define(id, Arc::clone(&sig));
        Ok(sig)
    }

    /// One value, by its type byte.
    pub(crate) fn value(&mut self) -> Result<Value, Fault> {
        self.value_at(0)
    }

    fn value_at(&mut self, depth: u32) -> Result<Value, Fault> {
        let at = self.stream.offset();
        let tag = self.stream.byte()?;
        Ok(match tag {
            0x00 => Value::Null,
            0x01 => Value::Bool(false),
            0x02 => Value::Bool(true),
            0x03 => Value::SInt(self.negative(at)?),
            0x04 => Value::UInt(self.stream.uint()?),
            0x05 => Value::Float(self.stream.f32()?),
            0x06 => Value::Double(self.stream.f64()?),
            0x07 => Value::String(self.stream.string()?),
            0x08 => Value::Blob(self.stream.blob()?),
            0x09 => Value::Enum(self.enumeration()?),
            0x0a => {
                self.bitmask_sig()?;
                Value::Bitmask(self.stream.uint()?)
            }
            0x0b | 0x0c | 0x0e if depth >= MAX_DEPTH => {
                return Err(Fault::corrupt(
                    at,
                    format!(
                        "values nest deeper than {MAX_DEPTH} levels at decompressed offset {at}"
                    ),
                ))
            }
            0x0b => {
                let n = self.stream.uint()?;
                let mut items = Vec::with_capacity(n.min(1024) as usize);
                for _ in 0..n {
                    items.push(self.value_at(depth + 1)?);
                }
                Value::Array(items)
            }
            0x0c => self.structure(depth)?,
            0x0d => Value::Opaque(self.stream.uint()?),
            0x0e => {
                let human = self.value_at(depth + 1)?;
                let machine = self.value_at(depth + 1)?;
                Value::Repr(Box::new(human), Box::new(machine))
            }
            0x0f => Value::String(self.wide_string()?),
            _ => return Err(Fault::unknown(at, "value type", tag, "0x00 to 0x0f")),
        })
    }

    /// The magnitude of a negative integer, negated.
    fn negative(&mut self, at: u64) -> Result<i64, Fault> {
        let m = self.stream.uint()?;
        0i64.checked_sub_unsigned(m).ok_or_else(|| {
            Fault::corrupt(
                at,
                format!("the negative integer -{m} does not fit 64 bits"),
            )
        })
    }

    /// A signed integer as enum signatures store it: a value of type SINT
    /// or UINT.
    fn sint(&mut self) -> Result<i64, Fault> {
        let at = self.stream.offset();
        match self.stream.byte()? {
            0x03 => self.negative(at),
            0x04 => {
                let v = self.stream.uint()?;
                i64::try_from(v).map_err(|_| {
                    Fault::corrupt(
                        at,
                        format!("the enum value {v} does not fit a signed 64-bit integer"),
                    )
                })
            }
            t => Err(Fault::corrupt(
                at,
                format!(
                    "an enum value at decompressed offset {at} has type 0x{t:02x}, not an integer"
                ),
            )),
        }
    }

    /// An enum: its signature (defined on first use), then its value. In
    /// versions before 3 the signature holds one name and the value itself.
    fn enumeration(&mut self) -> Result<i64, Fault> {
        let at = self.stream.offset();
        let id = self.stream.uint()?;
        let known = self.enums.get(id, "enum", at)?.copied();
        if self.version < 3 {
            // The old signature is `id name value`: one name, and the
            // value is the enum's own.
            if let Some(v) = known {
                return Ok(v);
            }
            self.stream.skip_string()?;
            let v = self.sint()?;
            self.enums.define(id, v);
            return Ok(v);
        }
        if known.is_none() {
            let n = self.stream.uint()?;
            for _ in 0..n {
                self.stream.skip_string()?;
                self.sint()?;
            }
            self.enums.define(id, 0);
        }
        self.sint()
    }

    /// A bitmask signature: `id`, then on first use the flags' names and
    /// values.
    fn bitmask_sig(&mut self) -> Result<(), Fault> {
        let at = self.stream.offset();
        let id = self.stream.uint()?;
        if self.bitmasks.get(id, "bitmask", at)?.is_none() {
            let n = self.stream.uint()?;
            for _ in 0..n {
                self.stream.skip_string()?;
                self.stream.uint()?;
            }
            self.bitmasks.define(id, ());
        }
        Ok(())
    }

    /// A struct: its signature (name and member names on first use), then
    /// one value per member.
    fn structure(&mut self, depth: u32) -> Result<Value, Fault> {
        let at = self.stream.offset();
        let id = self.stream.uint()?;
        let members = match self.structs.get(id, "struct", at)? {
            Some((_, members)) => Arc::clone(members),
            None => {
                let name: Arc<str> = self.stream.string()?.into();
                let n = self.stream.uint()?;
                let mut names = Vec::with_capacity(n.min(64) as usize);
                for _ in 0..n {
                    names.push(self.stream.string()?);
                }
                let members: Arc<[String]> = names.into();
                self.structs.define(id, (name, Arc::clone(&members)));
                members
            }
        };
        let mut fields = Vec::with_capacity(members.len());
        for m in members.iter() {
            fields.push((m.clone(), self.value_at(depth + 1)?));
        }
        Ok(Value::Struct(fields))
    }

    /// A wide string: a count, then one code point per integer. Code points
    /// that are not Unicode scalar values read as U+FFFD.
    fn wide_string(&mut self) -> Result<String, Fault> {
        let n = self.stream.uint()?;
        let mut s = String::with_capacity(n.min(1024) as usize);
        for _ in 0..n {
            let c = self.stream.uint()?;
            s.push(
                u32::try_from(c)
                    .ok()
                    .and_then(char::from_u32)
                    .unwrap_or('\u{fffd}'),
            );
        }
        Ok(s)
    }

    /// A backtrace (`count frame*`), skipped: each frame is an id and, on
    /// first use, tagged details up to a terminator.
    pub(crate) fn skip_backtrace(&mut self) -> Result<(), Fault> {
        let n = self.stream.uint()?;
        for _ in 0..n {
            let at = self.stream.offset();
            let id = self.stream.uint()?;
            if self.frames.get(id, "backtrace frame", at)?.is_some() {
                continue;
            }
            loop {
                let at = self.stream.offset();
                match self.stream.byte()? {
                    0x00 => break,
                    0x01..=0x03 => self.stream.skip_string()?,
                    0x04 | 0x05 => {
                        self.stream.uint()?;
                    }
                    t => return Err(Fault::unknown(at, "backtrace detail", t, "0x00 to 0x05")),
                }
            }
            self.frames.define(id, ());
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::FaultKind;
    use crate::stream::tests::stream_of;

    fn decode(version: u64, bytes: &[u8]) -> Decoder {
        Decoder::new(stream_of(&[bytes]), version)
    }

    #[test]
    fn every_value_type_decodes_and_signatures_are_defined_once() {
        let mut b = vec![0x00, 0x01, 0x02, 0x03, 0x05, 0x04, 0x90, 0x01];
        b.push(0x05);
        b.extend_from_slice(&0.25f32.to_le_bytes());
        b.push(0x06);
        b.extend_from_slice(&(-2.5f64).to_le_bytes());
        b.extend_from_slice(&[0x07, 0x02, b'o', b'k', 0x08, 0x02, 9, 8]);
        // Enum sig 3 with one pair (GL_ONE = 1), value 0x0de1; then reused.
        b.extend_from_slice(&[
            0x09, 0x03, 0x01, 0x06, b'G', b'L', b'_', b'O', b'N', b'E', 0x04, 0x01,
        ]);
        b.extend_from_slice(&[0x04, 0xe1, 0x1b, 0x09, 0x03, 0x04, 0x01]);
        // Bitmask sig 0 with one flag, value 0x4100; array of two; opaque.
        b.extend_from_slice(&[0x0a, 0x00, 0x01, 0x01, b'A', 0x40, 0x80, 0x82, 0x01]);
        b.extend_from_slice(&[0x0b, 0x02, 0x04, 0x07, 0x02, 0x0d, 0xff, 0x01]);
        // Struct sig 1 "P" with members x, y; then reused; repr; wstring.
        b.extend_from_slice(&[
            0x0c, 0x01, 0x01, b'P', 0x02, 0x01, b'x', 0x01, b'y', 0x04, 1, 0x04, 2,
        ]);
        b.extend_from_slice(&[0x0c, 0x01, 0x01, 0x00]);
        b.extend_from_slice(&[0x0e, 0x07, 0x01, b'T', 0x09, 0x03, 0x04, 0x05]);
        b.extend_from_slice(&[0x0f, 0x02, 0xe9, 0x01, 0x41]);
        let mut d = decode(6, &b);
        let want = [
            Value::Null,
            Value::Bool(false),
            Value::Bool(true),
            Value::SInt(-5),
            Value::UInt(0x90),
            Value::Float(0.25),
            Value::Double(-2.5),
            Value::String("ok".into()),
            Value::Blob(vec![9, 8]),
            Value::Enum(0x0de1),
            Value::Enum(1),
            Value::Bitmask(0x4100),
            Value::Array(vec![Value::UInt(7), Value::Bool(true)]),
            Value::Opaque(0xff),
            Value::Struct(vec![
                ("x".into(), Value::UInt(1)),
                ("y".into(), Value::UInt(2)),
            ]),
            Value::Struct(vec![
                ("x".into(), Value::Bool(false)),
                ("y".into(), Value::Null),
            ]),
            Value::Repr(
                Box::new(Value::String("T".into())),
                Box::new(Value::Enum(5)),
            ),
            Value::String("éA".into()),
        ];
        for (i, w) in want.iter().enumerate() {
            assert_eq!(&d.value().unwrap(), w, "value {i}");
        }
        assert!(d.stream.at_end().unwrap());
    }

    #[test]
    fn old_enums_unknown_types_deep_nesting_and_big_ids_are_handled() {
        // Version 2: `id name value` on every use.
        let mut d = decode(2, &[0x09, 0x00, 0x01, b'A', 0x04, 0x07, 0x09, 0x00]);
        assert_eq!(d.value().unwrap(), Value::Enum(7));
        assert_eq!(d.value().unwrap(), Value::Enum(7));
        let mut d = decode(6, &[0x10]);
        let e = d.value().unwrap_err();
        assert!(
            matches!(e.kind, FaultKind::Corrupt(ref m) if m.contains("unknown value type 0x10"))
        );
        let deep: Vec<u8> = std::iter::repeat_n([0x0b, 0x01], 100).flatten().collect();
        let mut d = decode(6, &deep);
        let e = d.value().unwrap_err();
        assert!(matches!(e.kind, FaultKind::Corrupt(ref m) if m.contains("nest deeper")));
        let mut d = decode(6, &[0x0a, 0x80, 0x80, 0x80, 0x01, 0x00, 0x00]);
        let e = d.value().unwrap_err();
        assert!(
            matches!(e.kind, FaultKind::Corrupt(ref m) if m.contains("id 2097152 is out of range"))
        );
    }

    #[test]
    fn backtraces_are_skipped_with_their_frames_defined_once() {
        // Two frames: id 0 with a module and a line, then id 0 again.
        let b = [0x02, 0x00, 0x01, 0x01, b'm', 0x04, 0x0a, 0x00, 0x00, 0x07];
        let mut d = decode(6, &b);
        d.skip_backtrace().unwrap();
        assert_eq!(d.stream.byte().unwrap(), 0x07);
        let mut d = decode(6, &[0x01, 0x00, 0x09]);
        assert!(d.skip_backtrace().is_err());
    }
}
