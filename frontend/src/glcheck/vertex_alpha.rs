//! Which alpha-tested draws read a vertex alpha below 1: the replays of
//! the check give every vertex the same colour (alpha 1), so the alpha
//! test there reads the texture's alpha alone, as wasp's model does.
//! Where the engine's vertex alpha is below 1 the engine's frame can
//! differ from both; such draws are counted, so the check says so.

use crate::gl::enums as gl;
use wasp_gltrace::Call;

const ALPHA_TEST: i64 = gl::ALPHA_TEST;

/// The state that decides a draw's vertex alpha.
#[derive(Clone, Debug, Default)]
pub(super) struct VertexAlpha {
    alpha_test: bool,
    colour_array: bool,
    /// Whether the colour array's alpha is below 1 somewhere (`None`:
    /// unknown, for example in a buffer object).
    array_below_one: Option<bool>,
    /// Whether the current colour's alpha is below 1.
    current_below_one: bool,
    /// Inside glBegin .. glEnd: whether a vertex so far had it.
    block_below_one: Option<bool>,
    /// Whether a vertex of the last block ended had it.
    last_block_below_one: bool,
}

impl VertexAlpha {
    /// Follows `call` (before it is rewritten).
    pub(super) fn follow(&mut self, call: &Call) {
        let int = |i: usize| call.arg(i).as_i64();
        match &*call.name {
            "glEnable" | "glDisable" if int(0) == Some(ALPHA_TEST) => {
                self.alpha_test = &*call.name == "glEnable";
            }
            "glEnableClientState" | "glDisableClientState" if int(0) == Some(gl::COLOR_ARRAY) => {
                self.colour_array = &*call.name == "glEnableClientState";
            }
            "glColorPointer" => self.array_below_one = array_alpha(call),
            n if n.starts_with("glColor4") => {
                if let Some(a) = colour_alpha(call) {
                    self.current_below_one = a < 1.0;
                }
            }
            "glColor3f" | "glColor3ub" | "glColor3fv" | "glColor3ubv" => {
                self.current_below_one = false;
            }
            "glBegin" => self.block_below_one = Some(false),
            "glEnd" => self.last_block_below_one = self.block_below_one.take() == Some(true),
            n if is_vertex(n) => {
                if let Some(b) = &mut self.block_below_one {
                    *b |= self.current_below_one;
                }
            }
            _ => {}
        }
    }

    /// Whether the immediate-mode block a glEnd just ended is alpha-tested
    /// with a vertex alpha below 1.
    pub(super) fn block_reads_vertex_alpha(&self) -> bool {
        self.alpha_test && self.last_block_below_one
    }

    /// Whether a draw now is alpha-tested with a vertex alpha that may be
    /// below 1.
    pub(super) fn draw_reads_vertex_alpha(&self) -> bool {
        self.alpha_test
            && if self.colour_array {
                self.array_below_one != Some(false)
            } else {
                self.current_below_one
            }
    }
}

/// glVertex2f, glVertex3fv...: a vertex of an immediate-mode block (not
/// glVertexPointer, glVertexAttrib*).
fn is_vertex(name: &str) -> bool {
    name.strip_prefix("glVertex")
        .is_some_and(|r| r.starts_with(|c: char| c.is_ascii_digit()))
}

/// Whether a colour array's recorded data has an alpha below 1:
/// glColorPointer(size, type, stride, pointer) of 4 unsigned bytes or
/// floats in client memory; `Some(false)` for 3 components.
fn array_alpha(call: &Call) -> Option<bool> {
    let (size, ty, stride) = (
        call.arg(0).as_i64()?,
        call.arg(1).as_i64()?,
        call.arg(2).as_i64()?,
    );
    if size == 3 {
        return Some(false);
    }
    let data = call.arg(3).as_bytes()?;
    let (elem, at) = match ty {
        gl::UNSIGNED_BYTE => (4usize, 3usize),
        gl::FLOAT => (16, 12),
        _ => return None,
    };
    let step = if stride > 0 { stride as usize } else { elem };
    let below = (0..)
        .map(|i| i * step + at)
        .take_while(|&o| o + elem - at <= data.len())
        .any(|o| match ty {
            gl::UNSIGNED_BYTE => data[o] < 255,
            _ => f32::from_le_bytes([data[o], data[o + 1], data[o + 2], data[o + 3]]) < 1.0,
        });
    Some(below)
}

/// The alpha of a glColor4* call, in 0..=1 (`None` for a type not read).
fn colour_alpha(call: &Call) -> Option<f64> {
    let name = &call.name["glColor4".len()..];
    let a = match name.strip_suffix('v') {
        Some(_) => call.arg(0).as_array()?.get(3)?.as_f64()?,
        None => call.arg(3).as_f64()?,
    };
    match name.trim_end_matches('v') {
        "f" | "d" => Some(a),
        "ub" => Some(a / 255.0),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use wasp_gltrace::Value;

    fn call(name: &str, args: Vec<Value>) -> Call {
        Call {
            no: 0,
            thread: 0,
            name: name.into(),
            arg_names: vec![String::new(); args.len()].into(),
            args,
            ret: None,
        }
    }

    #[test]
    fn alpha_tested_draws_with_translucent_vertices_are_seen() {
        let mut v = VertexAlpha::default();
        v.follow(&call("glEnable", vec![Value::Enum(ALPHA_TEST)]));
        assert!(!v.draw_reads_vertex_alpha());
        v.follow(&call(
            "glColor4ub",
            vec![Value::UInt(255); 3]
                .into_iter()
                .chain([Value::UInt(128)])
                .collect(),
        ));
        assert!(v.draw_reads_vertex_alpha());
        v.follow(&call("glColor4f", vec![Value::Float(1.0); 4]));
        assert!(!v.draw_reads_vertex_alpha());
        let ptr = |alpha: u8| {
            call(
                "glColorPointer",
                vec![
                    Value::UInt(4),
                    Value::Enum(gl::UNSIGNED_BYTE),
                    Value::UInt(0),
                    Value::Blob(vec![9, 9, 9, 255, 9, 9, 9, alpha]),
                ],
            )
        };
        v.follow(&call(
            "glEnableClientState",
            vec![Value::Enum(gl::COLOR_ARRAY)],
        ));
        v.follow(&ptr(255));
        assert!(!v.draw_reads_vertex_alpha());
        v.follow(&ptr(254));
        assert!(v.draw_reads_vertex_alpha());
        // Immediate mode: a block one of whose vertices had alpha 0.5.
        v.follow(&call(
            "glDisableClientState",
            vec![Value::Enum(gl::COLOR_ARRAY)],
        ));
        let half = call("glColor4f", vec![Value::Float(0.5); 4]);
        let one = call("glColor4f", vec![Value::Float(1.0); 4]);
        let vertex = call("glVertex2f", vec![Value::Float(0.0); 2]);
        for (colours, below) in [([&one, &one], false), ([&half, &one], true)] {
            v.follow(&call("glBegin", vec![Value::Enum(gl::TRIANGLES)]));
            for c in colours {
                v.follow(c);
                v.follow(&vertex);
            }
            v.follow(&call("glVertexPointer", vec![]));
            v.follow(&call("glEnd", vec![]));
            assert_eq!(v.block_reads_vertex_alpha(), below);
        }
        v.follow(&call("glDisable", vec![Value::Enum(ALPHA_TEST)]));
        assert!(!v.draw_reads_vertex_alpha() && !v.block_reads_vertex_alpha());
    }
}
