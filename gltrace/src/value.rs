//! One recorded value: an argument or a return value of a call, as
//! apitrace's format types it.

/// A recorded value, by the type the capture gives it.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    /// `NULL` (also an argument the capture did not record).
    Null,
    /// A boolean (`FALSE` / `TRUE`).
    Bool(bool),
    /// A signed integer.
    SInt(i64),
    /// An unsigned integer.
    UInt(u64),
    /// A single-precision float.
    Float(f32),
    /// A double-precision float.
    Double(f64),
    /// A string.
    String(String),
    /// A blob of bytes (array data, pixel data, indices in client memory).
    Blob(Vec<u8>),
    /// An enum value (its signature's names are not kept: GL enums are
    /// matched by value).
    Enum(i64),
    /// A bitmask value.
    Bitmask(u64),
    /// An array of values.
    Array(Vec<Value>),
    /// A struct's members, in signature order, with their names.
    Struct(Vec<(String, Value)>),
    /// An opaque pointer (its address as recorded).
    Opaque(u64),
    /// A value with two representations: the human one (for example a
    /// name) and the machine one.
    Repr(Box<Value>, Box<Value>),
}

impl Value {
    /// The value as a signed integer: integers, enums, bitmasks, booleans
    /// and (for `Repr`) the machine representation. Floats are not
    /// converted.
    pub fn as_i64(&self) -> Option<i64> {
        match self {
            Value::Bool(b) => Some(*b as i64),
            Value::SInt(v) | Value::Enum(v) => Some(*v),
            Value::UInt(v) | Value::Bitmask(v) => i64::try_from(*v).ok(),
            Value::Repr(_, m) => m.as_i64(),
            _ => None,
        }
    }

    /// The value as a float: floats, doubles and integers.
    pub fn as_f64(&self) -> Option<f64> {
        match self {
            Value::Float(v) => Some(*v as f64),
            Value::Double(v) => Some(*v),
            Value::Repr(_, m) => m.as_f64(),
            _ => self.as_i64().map(|v| v as f64),
        }
    }

    /// The bytes of a blob or a string.
    pub fn as_bytes(&self) -> Option<&[u8]> {
        match self {
            Value::Blob(b) => Some(b),
            Value::String(s) => Some(s.as_bytes()),
            _ => None,
        }
    }

    /// The elements of an array.
    pub fn as_array(&self) -> Option<&[Value]> {
        match self {
            Value::Array(a) => Some(a),
            _ => None,
        }
    }

    /// Whether the value is a null pointer or `NULL`.
    pub fn is_null(&self) -> bool {
        matches!(self, Value::Null | Value::Opaque(0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn conversions_read_through_repr_and_refuse_what_does_not_fit() {
        let r = Value::Repr(
            Box::new(Value::String("GL_TEXTURE0".into())),
            Box::new(Value::Enum(0x84C0)),
        );
        assert_eq!(r.as_i64(), Some(0x84C0));
        assert_eq!(Value::UInt(u64::MAX).as_i64(), None);
        assert_eq!(Value::Float(0.5).as_i64(), None);
        assert_eq!(Value::Float(0.5).as_f64(), Some(0.5));
        assert_eq!(Value::SInt(-3).as_f64(), Some(-3.0));
        assert!(Value::Opaque(0).is_null() && !Value::Opaque(8).is_null());
        assert_eq!(Value::Blob(vec![1, 2]).as_bytes(), Some(&[1u8, 2][..]));
    }
}
