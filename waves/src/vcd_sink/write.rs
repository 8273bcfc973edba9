//! Writing the file: the header and hierarchy up to `$enddefinitions`,
//! the first cycle's full dump and each later cycle's changes.

use std::io::{self, Write};

use vcd::{IdCode, ReferenceIndex, SimulationCommand, TimescaleUnit, VarType};

use super::hierarchy::Event;
use super::sink::VcdSink;
use super::time::{time_unit_note, TimeAxis};

/// Text of the `$version` header.
pub const VERSION: &str = concat!("wasp ", env!("CARGO_PKG_VERSION"));

impl<W: Write> VcdSink<W> {
    /// Header and hierarchy, up to `$enddefinitions`.
    pub(super) fn write_header(&mut self) -> io::Result<()> {
        if self.axis == TimeAxis::RealTime && self.clock_mhz.is_none() {
            return Err(self.fail(
                io::ErrorKind::InvalidInput,
                "a real-time axis needs the clock frequency (with_clock_mhz)".to_owned(),
            ));
        }
        let note = time_unit_note(self.clock_mhz, self.axis);
        let unit = match self.axis {
            TimeAxis::Cycles => TimescaleUnit::NS,
            TimeAxis::RealTime => TimescaleUnit::PS,
        };
        let mut w = vcd::Writer::new(&mut self.out);
        if let Some(date) = &self.date {
            w.date(date)?;
        }
        w.version(VERSION)?;
        w.comment(&note)?;
        w.timescale(1, unit)?;
        w.add_module(&self.top)?;
        let mut index = 0;
        for event in &self.events {
            match event {
                Event::Push(name) => w.add_module(name)?,
                Event::Pop => w.upscope()?,
                Event::Signal => {
                    let info = &self.signals[index];
                    let range = info
                        .is_vector()
                        .then(|| ReferenceIndex::Range(info.width as i32 - 1, 0));
                    w.var_def(
                        VarType::Wire,
                        info.width,
                        IdCode::from(index as u64),
                        &info.name,
                        range,
                    )?;
                    index += 1;
                }
            }
        }
        w.upscope()?;
        w.enddefinitions()?;
        self.defined = true;
        Ok(())
    }

    /// The first cycle: every value under `$dumpvars`.
    pub(super) fn write_dumpvars(&mut self) -> io::Result<()> {
        let time = self.time_of(self.cycle);
        let mut w = vcd::Writer::new(&mut self.out);
        w.timestamp(time)?;
        w.begin(SimulationCommand::Dumpvars)?;
        for slot in &mut self.slots {
            slot.write_value(w.writer())?;
            slot.written = slot.value;
        }
        w.end()?;
        self.last_time = Some(time);
        Ok(())
    }

    /// A later cycle: the changed values, under a timestamp if any.
    pub(super) fn write_changes(&mut self) -> io::Result<()> {
        let mut stamped = false;
        let time = self.time_of(self.cycle);
        for slot in &mut self.slots {
            if slot.value != slot.written {
                if !stamped {
                    vcd::Writer::new(&mut self.out).timestamp(time)?;
                    stamped = true;
                }
                slot.write_value(&mut self.out)?;
                slot.written = slot.value;
            }
        }
        if stamped {
            self.last_time = Some(time);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vcd_sink::testkit::*;
    use crate::vcd_sink::TIME_UNIT_COMMENT;
    use vcd::{Command, ScopeItem, Value};

    #[test]
    fn header_defines_hierarchy_timescale_and_vars() {
        let bytes = write_toy();
        let mut parser = vcd::Parser::new(&bytes[..]);
        let header = parser.parse_header().unwrap();
        assert_eq!(header.timescale, Some((1, TimescaleUnit::NS)));
        assert_eq!(header.version.as_deref(), Some(VERSION));
        assert_eq!(header.date, None);
        assert!(header
            .items
            .iter()
            .any(|i| matches!(i, ScopeItem::Comment(c) if c == TIME_UNIT_COMMENT)));

        let mshrs = header.find_var(&["top", "core0", "free_mshrs"]).unwrap();
        assert_eq!(mshrs.size, 5);
        assert_eq!(mshrs.index, Some(ReferenceIndex::Range(4, 0)));
        let valid = header.find_var(&["top", "core0", "valid"]).unwrap();
        assert_eq!(valid.size, 1);
        assert_eq!(valid.index, None);
        let word = header.find_var(&["top", "core0", "sched", "word"]).unwrap();
        assert_eq!(word.size, 64);
        assert_eq!(word.index, Some(ReferenceIndex::Range(63, 0)));
        assert!(header.find_scope(&["top", "core0", "sched"]).is_some());

        let text = String::from_utf8(bytes).unwrap();
        assert!(
            text.contains("$var wire 5 ! free_mshrs [4:0] $end\n"),
            "{text}"
        );
        assert!(text.contains("$var wire 1 \" valid $end\n"), "{text}");
        assert!(text.contains("$scope module top $end\n$scope module core0 $end\n"));
    }

    #[test]
    fn exact_output() {
        let text = String::from_utf8(write_toy()).unwrap();
        let expected = format!(
            "$version\n    {VERSION}\n$end\n\
             $comment\n    one time unit = one clock cycle\n$end\n\
             $timescale 1 ns $end\n\
             $scope module top $end\n\
             $scope module core0 $end\n\
             $var wire 5 ! free_mshrs [4:0] $end\n\
             $var wire 1 \" valid $end\n\
             $scope module sched $end\n\
             $var wire 3 # warp [2:0] $end\n\
             $var wire 64 $ word [63:0] $end\n\
             $upscope $end\n\
             $upscope $end\n\
             $upscope $end\n\
             $enddefinitions $end\n\
             #0\n$dumpvars\nb00110 !\n0\"\nb000 #\nb{ones} $\n$end\n\
             #1\n1\"\n\
             #2\nb00101 !\nb111 #\n\
             #4\n0\"\n\
             #5\nb1{zeros} $\n\
             #6\n",
            ones = "1".repeat(64),
            zeros = "0".repeat(63),
        );
        assert_eq!(text, expected);
    }

    #[test]
    fn only_changes_after_first_cycle_msb_first() {
        let cmds = body(&write_toy());
        let mshrs: IdCode = "!".parse().unwrap();
        let valid: IdCode = "\"".parse().unwrap();
        let warp: IdCode = "#".parse().unwrap();
        let word: IdCode = "$".parse().unwrap();
        let expected = vec![
            Command::Timestamp(0),
            // 0b00110 in 5 bits, MSB first: 0,0,1,1,0
            Command::ChangeVector(mshrs, bits("00110")),
            Command::ChangeScalar(valid, Value::V0),
            Command::ChangeVector(warp, bits("000")),
            Command::ChangeVector(word, bits(&"1".repeat(64))),
            Command::Timestamp(1),
            Command::ChangeScalar(valid, Value::V1),
            Command::Timestamp(2),
            Command::ChangeVector(mshrs, bits("00101")),
            Command::ChangeVector(warp, bits("111")),
            // cycle 3: nothing changed, no timestamp
            Command::Timestamp(4),
            Command::ChangeScalar(valid, Value::V0),
            Command::Timestamp(5),
            Command::ChangeVector(word, bits(&format!("1{}", "0".repeat(63)))),
            Command::Timestamp(6),
        ];
        assert_eq!(cmds, expected);
    }

    #[test]
    fn deterministic() {
        assert_eq!(write_toy(), write_toy());
    }

    #[test]
    fn no_change_cycles_write_no_timestamp_and_final_is_written() {
        let mut sink = VcdSink::new(Vec::new(), "top");
        for cycle in 0..10 {
            sink.trace_cycle(cycle, &START).unwrap();
        }
        let cmds = body(&sink.finish(10).unwrap());
        let stamps: Vec<_> = cmds
            .iter()
            .filter_map(|c| match c {
                Command::Timestamp(t) => Some(*t),
                _ => None,
            })
            .collect();
        assert_eq!(stamps, [0, 10]);
    }

    #[test]
    fn date_is_opt_in() {
        let mut sink = VcdSink::new(Vec::new(), "top").with_date("today");
        sink.trace_cycle(0, &START).unwrap();
        let bytes = sink.finish(1).unwrap();
        let header = vcd::Parser::new(&bytes[..]).parse_header().unwrap();
        assert_eq!(header.date.as_deref(), Some("today"));
    }
}
