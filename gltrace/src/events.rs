//! The events of the call stream: an enter event opens a call (numbered in
//! order from 0), a leave event completes it, and both carry call details
//! (arguments by index, the return value, the thread, a backtrace, flags).
//! Calls are handed out as they complete, in the order of their leave
//! events, as apitrace's own parser does; calls still open when the
//! stream ends follow, in the order they were entered, and are noted as
//! incomplete (apitrace's dump marks them `// incomplete`).

use crate::api::Api;
use crate::decoder::{Decoder, FunctionSig};
use crate::error::Fault;
use crate::{Call, Value};
use std::collections::VecDeque;
use std::sync::Arc;

/// An argument index past this is refused as corrupt (GL functions have at
/// most a few tens of arguments).
const MAX_ARG_INDEX: u64 = 1 << 12;

/// A call entered and not yet left.
struct Open {
    no: u64,
    thread: u32,
    sig: Arc<FunctionSig>,
    args: Vec<Value>,
    ret: Option<Value>,
}

impl Open {
    /// The call, with an argument the capture did not record read as
    /// [`Value::Null`] (as apitrace sizes a call's arguments by its
    /// signature).
    fn into_call(mut self) -> Call {
        if self.args.len() < self.sig.arg_names.len() {
            self.args.resize(self.sig.arg_names.len(), Value::Null);
        }
        Call {
            no: self.no,
            thread: self.thread,
            name: Arc::clone(&self.sig.name),
            arg_names: Arc::clone(&self.sig.arg_names),
            args: self.args,
            ret: self.ret,
        }
    }
}

/// What went wrong, with the call it happened in (where known) and what
/// was being read.
pub(crate) struct EventFault {
    pub fault: Fault,
    pub call: Option<u64>,
    pub context: String,
}

/// The event reader: the decoder, the calls open and the API seen so far.
pub(crate) struct Events {
    pub decoder: Decoder,
    open: VecDeque<Open>,
    next_no: u64,
    /// The API, from the first function signature that names one.
    pub api: Api,
    /// The calls handed out with no leave event (open when the stream
    /// ended), by number.
    pub incomplete: Vec<u64>,
}

impl Events {
    pub(crate) fn new(decoder: Decoder) -> Events {
        Events {
            decoder,
            open: VecDeque::new(),
            next_no: 0,
            api: Api::Unknown,
            incomplete: Vec::new(),
        }
    }

    /// The next completed call, or `None` at the end of the stream.
    pub(crate) fn next_call(&mut self) -> Result<Option<Call>, EventFault> {
        loop {
            let start = self.decoder.stream.offset();
            let ended = self.decoder.stream.at_end().map_err(|fault| EventFault {
                fault,
                call: None,
                context: "a chunk".into(),
            })?;
            if ended {
                let call = self.open.pop_front().map(Open::into_call);
                self.incomplete.extend(call.as_ref().map(|c| c.no));
                return Ok(call);
            }
            let event = self.decoder.stream.byte().map_err(|fault| EventFault {
                fault,
                call: None,
                context: "an event".into(),
            })?;
            match event {
                0x00 => {
                    let no = self.next_no;
                    self.enter(no).map_err(|fault| EventFault {
                        fault,
                        call: Some(no),
                        context: format!("the enter event of call {no} (from offset {start})"),
                    })?;
                }
                0x01 => {
                    if let Some(call) = self.leave(start)? {
                        return Ok(Some(call));
                    }
                }
                e => {
                    let fault = Fault::unknown(start, "event", e, "0x00 enter and 0x01 leave");
                    let call = Some(self.next_no);
                    return Err(EventFault {
                        fault,
                        call,
                        context: String::new(),
                    });
                }
            }
        }
    }

    /// An enter event (after its tag): the thread (version 4 on), the
    /// function signature and the details.
    fn enter(&mut self, no: u64) -> Result<(), Fault> {
        let thread = if self.decoder.version >= 4 {
            self.thread()?
        } else {
            0
        };
        let sig = self.decoder.function_sig()?;
        if self.api == Api::Unknown {
            self.api = Api::from_function(&sig.name);
        }
        let mut call = Open {
            no,
            thread,
            sig,
            args: Vec::new(),
            ret: None,
        };
        self.details(&mut call)?;
        self.next_no = no + 1;
        self.open.push_back(call);
        Ok(())
    }

    /// A leave event (after its tag): the call number and the details.
    /// Returns the completed call.
    fn leave(&mut self, start: u64) -> Result<Option<Call>, EventFault> {
        let at = self.decoder.stream.offset();
        let no = self.decoder.stream.uint().map_err(|fault| EventFault {
            fault,
            call: None,
            context: format!("the leave event at offset {start}"),
        })?;
        // The call left is almost always the one entered last.
        let Some(i) = self.open.iter().rposition(|c| c.no == no) else {
            let fault = Fault::corrupt(
                at,
                format!(
                    "a leave event at decompressed offset {start} is for call {no}, \
                     which is not open (entered and not yet left)"
                ),
            );
            return Err(EventFault {
                fault,
                call: Some(no),
                context: String::new(),
            });
        };
        let mut call = self.open.remove(i).expect("the position was just found");
        self.details(&mut call).map_err(|fault| EventFault {
            fault,
            call: Some(no),
            context: format!("the leave event of call {no} (from offset {start})"),
        })?;
        Ok(Some(call.into_call()))
    }

    fn thread(&mut self) -> Result<u32, Fault> {
        let at = self.decoder.stream.offset();
        let t = self.decoder.stream.uint()?;
        u32::try_from(t)
            .map_err(|_| Fault::corrupt(at, format!("thread number {t} does not fit 32 bits")))
    }

    /// Call details up to their terminator.
    fn details(&mut self, call: &mut Open) -> Result<(), Fault> {
        loop {
            let at = self.decoder.stream.offset();
            match self.decoder.stream.byte()? {
                0x00 => return Ok(()),
                0x01 => {
                    let index = self.decoder.stream.uint()?;
                    if index >= MAX_ARG_INDEX {
                        return Err(Fault::corrupt(
                            at,
                            format!(
                                "argument index {index} is out of range (below {MAX_ARG_INDEX})"
                            ),
                        ));
                    }
                    let value = self.decoder.value()?;
                    let i = index as usize;
                    if i >= call.args.len() {
                        call.args.resize(i + 1, Value::Null);
                    }
                    call.args[i] = value;
                }
                0x02 => call.ret = Some(self.decoder.value()?),
                0x03 => call.thread = self.thread()?,
                0x04 => self.decoder.skip_backtrace()?,
                // Flags (bit 0: a call apitrace made up, "fake"): read and
                // not kept.
                0x05 => {
                    self.decoder.stream.uint()?;
                }
                d => return Err(Fault::unknown(at, "call detail", d, "0x00 to 0x05")),
            }
        }
    }
}
