//! The writer of apitrace captures, the inverse of the reader: the header
//! (format version 6, the semantic version and properties), each [`Call`]
//! as an enter event and a leave event with its signature defined on first
//! use, and the Snappy container (the bytes `a` `t`, then chunks of at
//! most 1 MB of the stream, each a 32-bit little-endian length and a raw
//! Snappy block). `glretrace` replays what it writes.
//!
//! What the reader does not keep cannot be written back: enum and bitmask
//! signatures are written without names (one signature each, apitrace's
//! dump prints their values as numbers), struct signatures with an empty
//! type name, wide strings as strings, and no backtraces or call flags
//! (apitrace derives a call's replay flags from its name). A call is
//! written whole: its arguments in its enter event, its return value in
//! its leave event, so calls are numbered in the order they are written.

use crate::{Call, Value};
use std::collections::HashMap;
use std::io::Write;
use std::path::Path;
use std::sync::Arc;

/// The format version written (apitrace's current `TRACE_VERSION`).
pub const WRITE_VERSION: u32 = 6;
/// Decompressed bytes per Snappy chunk (apitrace's own chunk size).
const CHUNK: usize = 1 << 20;
/// The one enum signature and the one bitmask signature written.
const ENUM_SIG: u64 = 0;
const BITMASK_SIG: u64 = 0;

/// Writes a capture call by call.
pub struct CaptureWriter<W: Write> {
    out: W,
    /// The stream not yet compressed.
    buf: Vec<u8>,
    encoder: snap::raw::Encoder,
    functions: HashMap<(Arc<str>, Arc<[String]>), u64>,
    structs: HashMap<Vec<String>, u64>,
    enum_defined: bool,
    bitmask_defined: bool,
    next_no: u64,
}

impl CaptureWriter<std::io::BufWriter<std::fs::File>> {
    /// Creates the capture file `path` and writes its header.
    pub fn create(
        path: impl AsRef<Path>,
        semantic_version: u32,
        properties: &[(String, String)],
    ) -> std::io::Result<Self> {
        let file = std::fs::File::create(path)?;
        CaptureWriter::new(std::io::BufWriter::new(file), semantic_version, properties)
    }
}

impl<W: Write> CaptureWriter<W> {
    /// A writer to `out`, with the header written: format version
    /// [`WRITE_VERSION`], `semantic_version` (at most that) and the
    /// properties in order.
    pub fn new(
        mut out: W,
        semantic_version: u32,
        properties: &[(String, String)],
    ) -> std::io::Result<Self> {
        out.write_all(b"at")?;
        let mut w = CaptureWriter {
            out,
            buf: Vec::with_capacity(CHUNK + 4096),
            encoder: snap::raw::Encoder::new(),
            functions: HashMap::new(),
            structs: HashMap::new(),
            enum_defined: false,
            bitmask_defined: false,
            next_no: 0,
        };
        w.uint(u64::from(WRITE_VERSION));
        w.uint(u64::from(semantic_version.min(WRITE_VERSION)));
        for (name, value) in properties.iter().filter(|(n, _)| !n.is_empty()) {
            w.string(name);
            w.string(value);
        }
        w.string("");
        Ok(w)
    }

    /// Writes `call` (its `no` is not written: calls are numbered in the
    /// order they are written) and returns its number in the new capture.
    pub fn write_call(&mut self, call: &Call) -> std::io::Result<u64> {
        let no = self.next_no;
        self.next_no += 1;
        self.buf.push(0x00);
        self.uint(u64::from(call.thread));
        self.function_sig(call);
        for (i, v) in call.args.iter().enumerate() {
            self.buf.push(0x01);
            self.uint(i as u64);
            self.value(v);
        }
        self.buf.push(0x00);
        self.buf.push(0x01);
        self.uint(no);
        if let Some(ret) = &call.ret {
            self.buf.push(0x02);
            self.value(ret);
        }
        self.buf.push(0x00);
        if self.buf.len() >= CHUNK {
            self.flush_chunks(false)?;
        }
        Ok(no)
    }

    /// Calls written so far.
    pub fn calls_written(&self) -> u64 {
        self.next_no
    }

    /// Writes what is left and hands back the output, flushed.
    pub fn finish(mut self) -> std::io::Result<W> {
        self.flush_chunks(true)?;
        self.out.flush()?;
        Ok(self.out)
    }

    /// Compresses whole chunks of the buffer (and with `all` the rest).
    fn flush_chunks(&mut self, all: bool) -> std::io::Result<()> {
        let mut start = 0;
        while self.buf.len() - start >= CHUNK || (all && start < self.buf.len()) {
            let end = (start + CHUNK).min(self.buf.len());
            let block = self
                .encoder
                .compress_vec(&self.buf[start..end])
                .map_err(std::io::Error::other)?;
            self.out.write_all(&(block.len() as u32).to_le_bytes())?;
            self.out.write_all(&block)?;
            start = end;
        }
        self.buf.drain(..start);
        Ok(())
    }

    /// A variable-length unsigned integer, 7 bits per byte.
    fn uint(&mut self, mut v: u64) {
        while v >= 0x80 {
            self.buf.push((v as u8 & 0x7f) | 0x80);
            v >>= 7;
        }
        self.buf.push(v as u8);
    }

    fn string(&mut self, s: &str) {
        self.bytes(s.as_bytes());
    }

    fn bytes(&mut self, b: &[u8]) {
        self.uint(b.len() as u64);
        self.buf.extend_from_slice(b);
    }

    /// The function signature: its id, and on first use its name and
    /// argument names.
    fn function_sig(&mut self, call: &Call) {
        let key = (Arc::clone(&call.name), Arc::clone(&call.arg_names));
        let next = self.functions.len() as u64;
        match self.functions.get(&key) {
            Some(&id) => self.uint(id),
            None => {
                self.functions.insert(key, next);
                self.uint(next);
                self.string(&call.name);
                self.uint(call.arg_names.len() as u64);
                for a in call.arg_names.iter() {
                    self.string(a);
                }
            }
        }
    }

    /// An integer as enum values are stored: SINT (negated) or UINT.
    fn sint(&mut self, v: i64) {
        if v < 0 {
            self.buf.push(0x03);
            self.uint(v.unsigned_abs());
        } else {
            self.buf.push(0x04);
            self.uint(v as u64);
        }
    }

    fn value(&mut self, v: &Value) {
        match v {
            Value::Null => self.buf.push(0x00),
            Value::Bool(b) => self.buf.push(if *b { 0x02 } else { 0x01 }),
            // SINT holds a magnitude that is negated: zero and negative
            // values keep their type; apitrace writes positive ones as UINT.
            Value::SInt(i) if *i <= 0 => {
                self.buf.push(0x03);
                self.uint(i.unsigned_abs());
            }
            Value::SInt(i) => {
                self.buf.push(0x04);
                self.uint(*i as u64);
            }
            Value::UInt(u) => {
                self.buf.push(0x04);
                self.uint(*u);
            }
            Value::Float(f) => {
                self.buf.push(0x05);
                self.buf.extend_from_slice(&f.to_le_bytes());
            }
            Value::Double(d) => {
                self.buf.push(0x06);
                self.buf.extend_from_slice(&d.to_le_bytes());
            }
            Value::String(s) => {
                self.buf.push(0x07);
                self.string(s);
            }
            Value::Blob(b) => {
                self.buf.push(0x08);
                self.bytes(b);
            }
            Value::Enum(e) => {
                self.buf.push(0x09);
                self.uint(ENUM_SIG);
                if !std::mem::replace(&mut self.enum_defined, true) {
                    self.uint(0);
                }
                self.sint(*e);
            }
            Value::Bitmask(m) => {
                self.buf.push(0x0a);
                self.uint(BITMASK_SIG);
                if !std::mem::replace(&mut self.bitmask_defined, true) {
                    self.uint(0);
                }
                self.uint(*m);
            }
            Value::Array(items) => {
                self.buf.push(0x0b);
                self.uint(items.len() as u64);
                items.iter().for_each(|i| self.value(i));
            }
            Value::Struct(fields) => self.structure(fields),
            Value::Opaque(p) => {
                self.buf.push(0x0d);
                self.uint(*p);
            }
            Value::Repr(human, machine) => {
                self.buf.push(0x0e);
                self.value(human);
                self.value(machine);
            }
        }
    }

    /// A struct: its signature (by member names; an empty type name) on
    /// first use, then its members' values.
    fn structure(&mut self, fields: &[(String, Value)]) {
        self.buf.push(0x0c);
        let names: Vec<String> = fields.iter().map(|(n, _)| n.clone()).collect();
        let next = self.structs.len() as u64;
        match self.structs.get(&names) {
            Some(&id) => self.uint(id),
            None => {
                self.uint(next);
                self.string("");
                self.uint(names.len() as u64);
                names.iter().for_each(|n| self.string(n));
                self.structs.insert(names, next);
            }
        }
        fields.iter().for_each(|(_, v)| self.value(v));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Capture;

    fn call(name: &str, args: Vec<Value>, ret: Option<Value>) -> Call {
        let names: Vec<String> = (0..args.len()).map(|i| format!("a{i}")).collect();
        Call {
            no: 0,
            thread: 0,
            name: name.into(),
            arg_names: names.into(),
            args,
            ret,
        }
    }

    #[test]
    fn every_value_type_reads_back_and_big_streams_span_chunks() {
        let s = |f: &[(&str, Value)]| {
            Value::Struct(f.iter().map(|(n, v)| (n.to_string(), v.clone())).collect())
        };
        let values = vec![
            Value::Null,
            Value::Bool(false),
            Value::Bool(true),
            Value::SInt(-5),
            Value::SInt(0),
            Value::SInt(i64::MIN),
            Value::UInt(u64::MAX),
            Value::Float(0.25),
            Value::Double(-2.5),
            Value::String("é ok".into()),
            Value::Blob((0..3_000_000u32).map(|i| (i * 7 % 251) as u8).collect()),
            Value::Enum(0x0de1),
            Value::Enum(-1),
            Value::Bitmask(0x4100),
            Value::Array(vec![Value::UInt(7), Value::Array(vec![])]),
            s(&[("x", Value::UInt(1)), ("y", Value::Null)]),
            s(&[("x", Value::Opaque(0xff)), ("y", Value::Bool(true))]),
            Value::Repr(
                Box::new(Value::String("T".into())),
                Box::new(Value::Enum(5)),
            ),
        ];
        let calls = vec![
            call("glXMakeCurrent", values.clone(), Some(Value::Bool(true))),
            call("glClear", vec![Value::Bitmask(1)], None),
            call("glXMakeCurrent", values[..3].to_vec(), None),
        ];
        let props = [("process.name".to_string(), "/bin/x".to_string())];
        let mut w = CaptureWriter::new(Vec::new(), 6, &props).unwrap();
        for c in &calls {
            w.write_call(c).unwrap();
        }
        let bytes = w.finish().unwrap();
        let capture = Capture::from_bytes("w.trace", bytes).unwrap();
        assert_eq!(capture.property("process.name"), Some("/bin/x"));
        let back: Vec<Call> = capture.map(Result::unwrap).collect();
        assert_eq!(back.len(), 3);
        for (i, (b, c)) in back.iter().zip(&calls).enumerate() {
            let want = Call {
                no: i as u64,
                ..c.clone()
            };
            assert_eq!(b, &want, "call {i}");
        }
        // A positive SInt is written as apitrace writes it: UINT.
        let mut w = CaptureWriter::new(Vec::new(), 6, &[]).unwrap();
        w.write_call(&call("glF", vec![Value::SInt(3)], None))
            .unwrap();
        let c = Capture::from_bytes("p.trace", w.finish().unwrap())
            .unwrap()
            .next()
            .unwrap()
            .unwrap();
        assert_eq!(c.args, [Value::UInt(3)]);
    }
}
