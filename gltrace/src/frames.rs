//! Frames of a capture: the calls up to and including each call that ends
//! a frame ([`is_frame_end`]), counted from 0, as apitrace counts them.

use crate::{is_frame_end, Call, CaptureError};

/// One frame's calls.
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    /// The frame's number, from 0.
    pub index: u64,
    /// Its calls in capture order; a complete frame's last call ends it.
    pub calls: Vec<Call>,
    /// Whether a call ended the frame (false only for the calls after the
    /// last frame's end, which apitrace does not count as a frame).
    pub complete: bool,
}

/// Splits calls into frames (see [`frames`]).
pub struct Frames<I> {
    calls: I,
    index: u64,
    done: bool,
}

/// The frames of a stream of calls, one at a time (only one frame's calls
/// are held). The calls after the last frame's end, if any, come last as a
/// frame that is not [`Frame::complete`]. An error ends the frames.
pub fn frames<I>(calls: I) -> Frames<I::IntoIter>
where
    I: IntoIterator<Item = Result<Call, CaptureError>>,
{
    Frames {
        calls: calls.into_iter(),
        index: 0,
        done: false,
    }
}

impl<I: Iterator<Item = Result<Call, CaptureError>>> Iterator for Frames<I> {
    type Item = Result<Frame, CaptureError>;

    fn next(&mut self) -> Option<Self::Item> {
        if self.done {
            return None;
        }
        let mut calls = Vec::new();
        for r in self.calls.by_ref() {
            let call = match r {
                Ok(c) => c,
                Err(e) => {
                    self.done = true;
                    return Some(Err(e));
                }
            };
            let end = is_frame_end(&call.name);
            calls.push(call);
            if end {
                let index = self.index;
                self.index += 1;
                return Some(Ok(Frame {
                    index,
                    calls,
                    complete: true,
                }));
            }
        }
        self.done = true;
        (!calls.is_empty()).then_some(Ok(Frame {
            index: self.index,
            calls,
            complete: false,
        }))
    }
}

/// How many complete frames the calls make (the calls that end a frame;
/// `apitrace info` reports the same `FramesCount`). Holds no call.
pub fn count_frames<I>(calls: I) -> Result<u64, CaptureError>
where
    I: IntoIterator<Item = Result<Call, CaptureError>>,
{
    let mut n = 0;
    for r in calls {
        n += u64::from(is_frame_end(&r?.name));
    }
    Ok(n)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;

    fn call(no: u64, name: &str) -> Result<Call, CaptureError> {
        Ok(Call {
            no,
            thread: 0,
            name: name.into(),
            arg_names: Vec::new().into(),
            args: Vec::new(),
            ret: None,
        })
    }

    #[test]
    fn frames_end_at_swaps_and_the_tail_is_an_incomplete_frame() {
        let calls = vec![
            call(0, "glClear"),
            call(1, "glXSwapBuffers"),
            call(2, "glXSwapBuffers"),
            call(3, "glFlush"),
        ];
        assert_eq!(count_frames(calls.clone()).unwrap(), 2);
        let f: Vec<Frame> = frames(calls).map(Result::unwrap).collect();
        let shape: Vec<(u64, usize, bool)> = f
            .iter()
            .map(|f| (f.index, f.calls.len(), f.complete))
            .collect();
        assert_eq!(shape, [(0, 2, true), (1, 1, true), (2, 1, false)]);
        assert_eq!(f[2].calls[0].no, 3);
    }

    #[test]
    fn an_error_ends_the_frames_and_the_count() {
        let bad = CaptureError {
            file: PathBuf::from("x.trace"),
            offset: Some(9),
            call: Some(1),
            message: "truncated capture".into(),
        };
        let calls = vec![
            call(0, "glXSwapBuffers"),
            Err(bad.clone()),
            call(2, "glXSwapBuffers"),
        ];
        assert_eq!(count_frames(calls.clone()), Err(bad.clone()));
        let f: Vec<Result<Frame, CaptureError>> = frames(calls).collect();
        assert_eq!(f.len(), 2);
        assert!(f[0].is_ok());
        assert_eq!(f[1], Err(bad));
    }
}
