//! Reading a call's arguments as the importer needs them, with an error
//! naming the call, the argument and what was expected.

use wasp_gltrace::{Call, Value};

/// An error of the importer at a call: its number and name, and what was
/// wrong.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CallError {
    /// The call's number in the capture.
    pub call: u64,
    /// The function's name.
    pub name: String,
    /// What was wrong.
    pub message: String,
}

impl CallError {
    /// An error at `call`.
    pub fn at(call: &Call, message: impl Into<String>) -> Self {
        Self {
            call: call.no,
            name: call.name.to_string(),
            message: message.into(),
        }
    }
}

impl std::fmt::Display for CallError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "call {} ({}): {}", self.call, self.name, self.message)
    }
}

/// The name of argument `i` for messages.
fn arg_name(call: &Call, i: usize) -> String {
    call.arg_names
        .get(i)
        .map_or_else(|| format!("argument {i}"), |n| format!("argument `{n}`"))
}

/// Argument `i` as an integer (integers, enums, bitmasks, booleans).
pub fn int(call: &Call, i: usize) -> Result<i64, CallError> {
    let v = call.arg(i);
    v.as_i64()
        .or_else(|| single(v).and_then(Value::as_i64))
        .ok_or_else(|| {
            CallError::at(
                call,
                format!("{} is {v:?}: expected an integer", arg_name(call, i)),
            )
        })
}

/// Argument `i` as a non-negative size or count.
pub fn count(call: &Call, i: usize) -> Result<usize, CallError> {
    let v = int(call, i)?;
    usize::try_from(v)
        .ok()
        .filter(|&n| n <= 1 << 30)
        .ok_or_else(|| {
            CallError::at(
                call,
                format!("{} is {v}: expected 0 to 2^30", arg_name(call, i)),
            )
        })
}

/// Argument `i` as a number (floats, doubles, integers).
pub fn num(call: &Call, i: usize) -> Result<f64, CallError> {
    let v = call.arg(i);
    v.as_f64().ok_or_else(|| {
        CallError::at(
            call,
            format!("{} is {v:?}: expected a number", arg_name(call, i)),
        )
    })
}

/// The one element of a one-element array (apitrace records a pointer to
/// one value, such as `&1`, as an array of one).
fn single(v: &Value) -> Option<&Value> {
    match v.as_array() {
        Some([x]) => Some(x),
        _ => None,
    }
}

/// Argument `i` as `n` numbers (an array, such as glLoadMatrixf's).
pub fn nums(call: &Call, i: usize, n: usize) -> Result<Vec<f64>, CallError> {
    let v = call.arg(i);
    let bad = || {
        CallError::at(
            call,
            format!("{} is {v:?}: expected {n} numbers", arg_name(call, i)),
        )
    };
    let a = v.as_array().ok_or_else(bad)?;
    if a.len() < n {
        return Err(bad());
    }
    a[..n].iter().map(|x| x.as_f64().ok_or_else(bad)).collect()
}

/// What a pointer argument holds: the bytes recorded with it (client
/// memory), or an address / offset into a bound buffer.
#[derive(Clone, Debug, PartialEq)]
pub enum Pointer {
    /// Bytes recorded in the capture.
    Data(std::sync::Arc<[u8]>),
    /// An address or a buffer offset.
    Offset(u64),
}

/// Argument `i` as a pointer.
pub fn pointer(call: &Call, i: usize) -> Result<Pointer, CallError> {
    let v = call.arg(i);
    match v {
        Value::Blob(b) => Ok(Pointer::Data(b.as_slice().into())),
        Value::Null => Ok(Pointer::Offset(0)),
        Value::Opaque(a) | Value::UInt(a) => Ok(Pointer::Offset(*a)),
        Value::SInt(a) if *a >= 0 => Ok(Pointer::Offset(*a as u64)),
        _ => Err(CallError::at(
            call,
            format!(
                "{} is {v:?}: expected recorded data or an offset",
                arg_name(call, i)
            ),
        )),
    }
}

#[cfg(test)]
pub(crate) mod test_calls {
    //! Hand-built calls for the importer's unit tests.
    use super::*;

    /// A call `name(args)` numbered `no`.
    pub fn call(no: u64, name: &str, args: Vec<Value>) -> Call {
        Call {
            no,
            thread: 0,
            name: name.into(),
            arg_names: (0..args.len())
                .map(|i| format!("a{i}"))
                .collect::<Vec<_>>()
                .into(),
            args,
            ret: None,
        }
    }

    /// Integers as enum values.
    pub fn e(v: i64) -> Value {
        Value::Enum(v)
    }

    /// A float.
    pub fn f(v: f32) -> Value {
        Value::Float(v)
    }

    /// Floats as a blob of little-endian f32s.
    pub fn floats(v: &[f32]) -> Value {
        Value::Blob(v.iter().flat_map(|x| x.to_le_bytes()).collect())
    }
}

#[cfg(test)]
mod tests {
    use super::test_calls::*;
    use super::*;

    #[test]
    fn arguments_read_as_what_they_are_or_say_what_was_expected() {
        let c = call(
            4,
            "glTest",
            vec![
                e(5),
                Value::Array(vec![Value::UInt(3)]),
                f(0.5),
                Value::Opaque(16),
                floats(&[1.0]),
            ],
        );
        assert_eq!(int(&c, 0), Ok(5));
        assert_eq!(int(&c, 1), Ok(3));
        assert_eq!(num(&c, 2), Ok(0.5));
        assert_eq!(pointer(&c, 3), Ok(Pointer::Offset(16)));
        assert_eq!(
            pointer(&c, 4),
            Ok(Pointer::Data(vec![0, 0, 128, 63].into()))
        );
        let err = int(&c, 2).unwrap_err();
        assert_eq!((err.call, err.name.as_str()), (4, "glTest"));
        assert!(err.to_string().contains("argument `a2`"), "{err}");
        assert!(nums(&c, 1, 16).is_err());
        assert!(count(&call(1, "x", vec![Value::SInt(-1)]), 0).is_err());
    }
}
