//! The time axis of a VCD: one unit per cycle or real time in picoseconds,
//! the clock period, and the sentence that states what a unit is.

/// Text of the `$comment` header that states the time unit when the clock
/// frequency is not given.
pub const TIME_UNIT_COMMENT: &str = "one time unit = one clock cycle";

/// How VCD time relates to clock cycles (see the [time unit](super#time)).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum TimeAxis {
    /// One time unit per cycle (`$timescale 1 ns`, read as cycles).
    #[default]
    Cycles,
    /// Picoseconds (`$timescale 1 ps`): cycle × the clock period.
    RealTime,
}

/// The clock period in whole picoseconds (rounded), at least 1.
pub fn period_ps(clock_mhz: u32) -> u64 {
    let mhz = u64::from(clock_mhz.max(1));
    ((1_000_000 + mhz / 2) / mhz).max(1)
}

/// The sentence that states what a VCD time unit is: the `$comment` of a
/// [`VcdSink`](super::VcdSink) and a comment line of its GTKWave save file.
///
/// ```
/// use wasp_waves::vcd_sink::{time_unit_note, TimeAxis};
///
/// assert_eq!(
///     time_unit_note(Some(600), TimeAxis::Cycles),
///     "one time unit = one GPU cycle at 600 MHz (1.667 ns)"
/// );
/// assert_eq!(
///     time_unit_note(Some(600), TimeAxis::RealTime),
///     "time unit = 1 ps; one GPU cycle at 600 MHz = 1667 ps: cycle N is at time N x 1667"
/// );
/// ```
pub fn time_unit_note(clock_mhz: Option<u32>, axis: TimeAxis) -> String {
    match (clock_mhz, axis) {
        (None, _) => TIME_UNIT_COMMENT.to_owned(),
        (Some(mhz), TimeAxis::Cycles) => format!(
            "one time unit = one GPU cycle at {mhz} MHz ({:.3} ns)",
            1000.0 / f64::from(mhz.max(1))
        ),
        (Some(mhz), TimeAxis::RealTime) => {
            let ps = period_ps(mhz);
            format!(
                "time unit = 1 ps; one GPU cycle at {mhz} MHz = {ps} ps: \
                 cycle N is at time N x {ps}"
            )
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vcd_sink::testkit::*;
    use crate::vcd_sink::{readback, VcdSink};
    use std::io;
    use vcd::{Command, TimescaleUnit};

    #[test]
    fn period_is_rounded_to_whole_picoseconds() {
        assert_eq!(period_ps(600), 1667);
        assert_eq!(period_ps(1000), 1000);
        assert_eq!(period_ps(1), 1_000_000);
        assert_eq!(period_ps(10_000), 100);
        assert_eq!(period_ps(0), 1_000_000);
    }

    #[test]
    fn clock_names_the_cycle_in_the_comment_and_keeps_cycle_times() {
        let plain = write_toy();
        let bytes = write_toy_with(|s| s.with_clock_mhz(600));
        assert_eq!(
            header_comments(&bytes),
            ["one time unit = one GPU cycle at 600 MHz (1.667 ns)"]
        );
        let header = vcd::Parser::new(&bytes[..]).parse_header().unwrap();
        assert_eq!(header.timescale, Some((1, TimescaleUnit::NS)));
        assert_eq!(timestamps(&bytes), timestamps(&plain));
        assert_eq!(timestamps(&bytes), [0, 1, 2, 4, 5, 6]);
        assert_eq!(body(&bytes), body(&plain));
    }

    #[test]
    fn real_time_axis_writes_picoseconds() {
        let plain = write_toy();
        let bytes = write_toy_with(|s| s.with_time_axis(TimeAxis::RealTime).with_clock_mhz(600));
        let header = vcd::Parser::new(&bytes[..]).parse_header().unwrap();
        assert_eq!(header.timescale, Some((1, TimescaleUnit::PS)));
        assert_eq!(
            header_comments(&bytes),
            ["time unit = 1 ps; one GPU cycle at 600 MHz = 1667 ps: cycle N is at time N x 1667"]
        );
        let want: Vec<u64> = [0, 1, 2, 4, 5, 6].iter().map(|c| c * 1667).collect();
        assert_eq!(timestamps(&bytes), want);
        // The same changes, only the timestamps differ.
        let strip = |b: &[u8]| -> Vec<Command> {
            body(b)
                .into_iter()
                .filter(|c| !matches!(c, Command::Timestamp(_)))
                .collect()
        };
        assert_eq!(strip(&bytes), strip(&plain));
        let waves = readback::values_by_cycle(&bytes).unwrap();
        assert_eq!(waves.value_at("top.core0.sched.warp", 2 * 1667), Some(7));
        assert_eq!(
            waves.value_at("top.core0.sched.warp", 2 * 1667 - 1),
            Some(0)
        );
        assert_eq!(waves.end_time(), Some(6 * 1667));
    }

    #[test]
    fn real_time_needs_a_clock_and_a_clock_must_tick() {
        let mut sink = VcdSink::new(Vec::new(), "top").with_time_axis(TimeAxis::RealTime);
        expect_error(
            sink.trace_cycle(0, &START),
            io::ErrorKind::InvalidInput,
            "clock frequency",
        );
        let mut sink = VcdSink::new(Vec::new(), "top").with_clock_mhz(0);
        expect_error(
            sink.trace_cycle(0, &START),
            io::ErrorKind::InvalidInput,
            "0 MHz",
        );
    }
}
