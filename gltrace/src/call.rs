//! One recorded call: its number, thread, function name, arguments and
//! return value.

use crate::Value;
use std::sync::Arc;

/// A call as the capture recorded it.
#[derive(Clone, Debug, PartialEq)]
pub struct Call {
    /// The call's number in the capture (apitrace's numbering, from 0, as
    /// `apitrace dump` prints it).
    pub no: u64,
    /// The thread that made the call.
    pub thread: u32,
    /// The function's name, from its signature (for example
    /// `glDrawElements`).
    pub name: Arc<str>,
    /// The argument names, from the signature.
    pub arg_names: Arc<[String]>,
    /// The arguments by position; one the capture did not record is
    /// [`Value::Null`].
    pub args: Vec<Value>,
    /// The return value, if recorded.
    pub ret: Option<Value>,
}

impl Call {
    /// Argument `i` ([`Value::Null`] past the recorded ones).
    pub fn arg(&self, i: usize) -> &Value {
        const NULL: Value = Value::Null;
        self.args.get(i).unwrap_or(&NULL)
    }
}

/// Whether a call ends a frame: a swap of buffers of any window-system API
/// (apitrace ends its frames at the same calls).
pub fn is_frame_end(name: &str) -> bool {
    matches!(
        name,
        "glXSwapBuffers"
            | "eglSwapBuffers"
            | "eglSwapBuffersWithDamageEXT"
            | "eglSwapBuffersWithDamageKHR"
            | "wglSwapBuffers"
            | "wglSwapLayerBuffers"
            | "CGLFlushDrawable"
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn missing_arguments_read_as_null_and_swaps_end_frames() {
        let c = Call {
            no: 7,
            thread: 0,
            name: "glClear".into(),
            arg_names: vec!["mask".to_string()].into(),
            args: vec![Value::Bitmask(0x4100)],
            ret: None,
        };
        assert_eq!(c.arg(0), &Value::Bitmask(0x4100));
        assert_eq!(c.arg(3), &Value::Null);
        assert!(is_frame_end("glXSwapBuffers") && !is_frame_end("glFlush"));
    }
}
