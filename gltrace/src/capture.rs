//! An open capture: its header (format version, semantic version,
//! properties), the API its calls belong to, and the stream of its calls,
//! decoded one chunk at a time as they are iterated.

use crate::api::Api;
use crate::container::{self, Compression, Container};
use crate::decoder::Decoder;
use crate::error::Fault;
use crate::events::{EventFault, Events};
use crate::stream::Stream;
use crate::{Call, CaptureError};
use std::collections::VecDeque;
use std::path::{Path, PathBuf};

/// The newest format version this reader knows (apitrace's `TRACE_VERSION`
/// since version 6 added properties and wide strings).
pub const MAX_VERSION: u32 = 6;

/// How many calls [`Capture::open`] reads ahead to find the API when the
/// first calls name none.
const API_LOOKAHEAD: usize = 1024;

/// An apitrace capture, open for reading. Iterating it yields its calls in
/// the order `apitrace dump` prints them, each numbered as apitrace numbers
/// it; after the first error it yields nothing more.
pub struct Capture {
    /// The capture file.
    pub path: PathBuf,
    /// The container's compression.
    pub compression: Compression,
    /// The format version (0 to [`MAX_VERSION`]).
    pub version: u32,
    /// The semantic version (how calls are to be replayed; the format
    /// version before version 6).
    pub semantic_version: u32,
    /// The properties of the header (version 6 on), in file order: for
    /// example `process.name`.
    pub properties: Vec<(String, String)>,
    /// The API the calls belong to (decided by the first call that names
    /// one, within the first calls).
    pub api: Api,
    events: Events,
    ahead: VecDeque<Result<Call, CaptureError>>,
    done: bool,
}

impl Capture {
    /// Opens a capture and reads its header and enough of its first calls
    /// to know its API.
    pub fn open(path: impl AsRef<Path>) -> Result<Capture, CaptureError> {
        let path = path.as_ref().to_path_buf();
        let container = container::open(&path);
        Capture::start(path, container)
    }

    /// A capture held in memory (`bytes`, the whole file as apitrace wrote
    /// it); `name` stands for the file in errors.
    pub fn from_bytes(name: impl Into<PathBuf>, bytes: Vec<u8>) -> Result<Capture, CaptureError> {
        Capture::start(name.into(), container::from_bytes(bytes))
    }

    fn start(
        path: PathBuf,
        container: Result<(Container, Compression), String>,
    ) -> Result<Capture, CaptureError> {
        let (container, compression) = container.map_err(|message| CaptureError {
            file: path.clone(),
            offset: None,
            call: None,
            message,
        })?;
        let mut stream = Stream::new(container);
        let header =
            read_header(&mut stream).map_err(|f| f.into_error(&path, None, "the header"))?;
        let events = Events::new(Decoder::new(stream, u64::from(header.version)));
        let mut capture = Capture {
            path,
            compression,
            version: header.version,
            semantic_version: header.semantic_version,
            properties: header.properties,
            api: Api::Unknown,
            events,
            ahead: VecDeque::new(),
            done: false,
        };
        while capture.events.api == Api::Unknown
            && capture.ahead.len() < API_LOOKAHEAD
            && !capture.done
        {
            match capture.read() {
                Some(r) => capture.ahead.push_back(r),
                None => break,
            }
        }
        capture.api = capture.events.api;
        Ok(capture)
    }

    /// A property of the header, by name.
    pub fn property(&self, name: &str) -> Option<&str> {
        self.properties
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, v)| v.as_str())
    }

    /// An error unless the capture's calls are OpenGL's (through GLX, WGL,
    /// CGL or EGL).
    pub fn require_gl(&self) -> Result<(), CaptureError> {
        match self.api {
            Api::Gl | Api::Egl => Ok(()),
            other => Err(CaptureError {
                file: self.path.clone(),
                offset: None,
                call: None,
                message: format!("the capture's calls are {}, not OpenGL", other.describe()),
            }),
        }
    }

    /// The numbers of the calls handed out so far that have no leave event:
    /// calls still open when the capture ended (a program killed inside a
    /// call, typically its last glXSwapBuffers). Their return value and
    /// output arguments are missing. `apitrace dump` marks them
    /// `// incomplete`.
    pub fn incomplete_calls(&self) -> &[u64] {
        &self.events.incomplete
    }

    /// How far into the decompressed stream the reader is.
    pub fn offset(&self) -> u64 {
        self.events.decoder.stream.offset()
    }

    /// The next call from the stream (not the read-ahead).
    fn read(&mut self) -> Option<Result<Call, CaptureError>> {
        if self.done {
            return None;
        }
        match self.events.next_call() {
            Ok(Some(call)) => Some(Ok(call)),
            Ok(None) => {
                self.done = true;
                None
            }
            Err(EventFault {
                fault,
                call,
                context,
            }) => {
                self.done = true;
                Some(Err(fault.into_error(&self.path, call, &context)))
            }
        }
    }
}

// A capture can be read on another thread than the one that opened it.
const _: fn() = || {
    fn send<T: Send>() {}
    send::<Capture>();
};

impl Iterator for Capture {
    type Item = Result<Call, CaptureError>;

    fn next(&mut self) -> Option<Self::Item> {
        match self.ahead.pop_front() {
            Some(r) => Some(r),
            None => self.read(),
        }
    }
}

struct Header {
    version: u32,
    semantic_version: u32,
    properties: Vec<(String, String)>,
}

/// The header: the version, and from version 6 the semantic version and
/// the properties (name/value strings up to an empty name).
fn read_header(stream: &mut Stream) -> Result<Header, Fault> {
    let version = stream.uint()?;
    if version > u64::from(MAX_VERSION) {
        return Err(Fault::corrupt(
            0,
            format!(
                "the capture's format version is {version}; this reader knows versions 0 to \
                 {MAX_VERSION}"
            ),
        ));
    }
    let version = version as u32;
    let mut header = Header {
        version,
        semantic_version: version,
        properties: Vec::new(),
    };
    if version >= 6 {
        let at = stream.offset();
        let semantic = stream.uint()?;
        if semantic > u64::from(version) {
            return Err(Fault::corrupt(
                at,
                format!("the semantic version {semantic} is past the format version {version}"),
            ));
        }
        header.semantic_version = semantic as u32;
        loop {
            let name = stream.string()?;
            if name.is_empty() {
                break;
            }
            let value = stream.string()?;
            header.properties.push((name, value));
        }
    }
    Ok(header)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Value;

    /// A capture of `body` in one Snappy chunk, named `name`.
    fn capture_of(name: &str, body: &[u8]) -> Result<Capture, CaptureError> {
        Capture::from_bytes(name, crate::container::tests::snappy_file(&[body]))
    }

    /// Version 6, semantic 6, one property, then: call 0 glXSwapBuffers
    /// (sig 1, args dpy, drawable) entered; call 1 glClear (sig 2, arg mask)
    /// entered and left; call 0 left with a return value.
    fn two_calls() -> Vec<u8> {
        let mut b = vec![6, 6, 1, b'k', 1, b'v', 0];
        b.extend_from_slice(&[0x00, 0x00, 0x01, 14]);
        b.extend_from_slice(b"glXSwapBuffers");
        b.extend_from_slice(&[2, 3, b'd', b'p', b'y', 8]);
        b.extend_from_slice(b"drawable");
        b.extend_from_slice(&[0x01, 0x00, 0x0d, 0x10, 0x01, 0x01, 0x04, 0x05, 0x00]);
        b.extend_from_slice(&[0x00, 0x00, 0x02, 7]);
        b.extend_from_slice(b"glClear");
        b.extend_from_slice(&[1, 4, b'm', b'a', b's', b'k', 0x00]);
        b.extend_from_slice(&[0x01, 0x01, 0x05, 0x01, 0x00]); // flags: fake
        b.extend_from_slice(&[0x01, 0x00, 0x02, 0x02, 0x00]);
        b
    }

    #[test]
    fn header_api_and_calls_in_leave_order_with_their_numbers() {
        let mut c = capture_of("two", &two_calls()).unwrap();
        assert_eq!((c.version, c.semantic_version, c.api), (6, 6, Api::Gl));
        assert_eq!(c.property("k"), Some("v"));
        c.require_gl().unwrap();
        let calls: Vec<Call> = c.by_ref().map(Result::unwrap).collect();
        assert_eq!(calls.len(), 2);
        assert_eq!((calls[0].no, &*calls[0].name), (1, "glClear"));
        assert_eq!(calls[0].args, vec![Value::Null]);
        assert_eq!((calls[1].no, &*calls[1].name), (0, "glXSwapBuffers"));
        assert_eq!(calls[1].args, vec![Value::Opaque(0x10), Value::UInt(5)]);
        assert_eq!(calls[1].ret, Some(Value::Bool(true)));
        assert_eq!(&calls[1].arg_names[..], ["dpy", "drawable"]);
        assert!(c.next().is_none());
        assert!(c.incomplete_calls().is_empty());
        // Cut before call 0's leave: call 0 comes last, incomplete.
        let cut = &two_calls()[..71];
        let mut c = capture_of("open", cut).unwrap();
        let nos: Vec<u64> = c.by_ref().map(|r| r.unwrap().no).collect();
        assert_eq!((nos, c.incomplete_calls()), (vec![1, 0], &[0u64][..]));
    }

    #[test]
    fn newer_versions_other_apis_and_bad_events_are_refused_by_name() {
        let e = capture_of("v7", &[7, 7, 0]).err().unwrap();
        assert!(
            e.message.contains("version is 7") && e.to_string().contains("v7"),
            "{e}"
        );
        // A Direct3D capture (version 5: no properties, no semantic version).
        let mut b = vec![5, 0x00, 0x00, 0x00, 17];
        b.extend_from_slice(b"Direct3DCreate9Ex");
        b.extend_from_slice(&[0, 0x00]);
        let c = capture_of("d3d", &b).unwrap();
        assert_eq!(c.api, Api::Dx);
        let e = c.require_gl().unwrap_err();
        assert!(
            e.message.contains("Direct3D") && e.message.contains("not OpenGL"),
            "{e}"
        );
        // Event 0x07 after the header.
        let mut c = capture_of("event", &[6, 6, 0, 0x07]).unwrap();
        let e = c.next().unwrap().unwrap_err();
        assert_eq!((e.call, e.offset), (Some(0), Some(3)));
        assert!(e.message.contains("unknown event 0x07"), "{e}");
        assert!(c.next().is_none());
        // A leave for a call never entered.
        let mut c = capture_of("leave", &[6, 6, 0, 0x01, 0x09, 0x00]).unwrap();
        let e = c.next().unwrap().unwrap_err();
        assert!(e.message.contains("call 9, which is not open"), "{e}");
    }

    #[test]
    fn every_truncation_is_an_error_naming_the_call_and_offset_or_a_clean_end() {
        let whole = two_calls();
        for cut in 0..whole.len() {
            let got: Vec<Result<Call, CaptureError>> = match capture_of("cut", &whole[..cut]) {
                Ok(c) => c.collect(),
                Err(e) => vec![Err(e)],
            };
            let err = got.iter().find_map(|r| r.as_ref().err());
            // A cut at an event boundary is a clean (shorter) capture; any
            // other cut is a truncation error naming its offset.
            let boundaries = [7, 48, 66, 71];
            if boundaries.contains(&cut) {
                assert!(err.is_none(), "cut {cut}: {err:?}");
            } else {
                let e = err.unwrap_or_else(|| panic!("cut {cut} read without error"));
                assert!(e.message.contains("truncated capture"), "cut {cut}: {e}");
                assert_eq!(e.offset, Some(cut as u64), "cut {cut}");
            }
        }
    }
}
