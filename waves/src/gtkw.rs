//! GTKWave save files (`.gtkw`) that preselect signals.
//!
//! GTKWave opens a dump file with no signal shown; a save file lists the
//! traces to show, their display format, comment lines and groups, and the
//! initial view. Open both with `gtkwave waves.vcd waves.gtkw` (or
//! `gtkwave -a waves.gtkw waves.vcd`).
//!
//! ```
//! use wasp_waves::gtkw::{Format, GtkwSave};
//!
//! let save = GtkwSave::new("waves.vcd")
//!     .zoom_to_fit(100)
//!     .signal("top.clk_en", 1, Format::Binary)
//!     .comment_group("Scheduler")
//!     .signal("top.core0.free_mshrs", 5, Format::Decimal);
//! let mut text = Vec::new();
//! save.write_to(&mut text)?;
//! # Ok::<(), std::io::Error>(())
//! ```
//!
//! # File format
//!
//! A save file is line based. `[name] value` lines set the view
//! (`[dumpfile]`, `[timestart]`, `[size]`, `[sst_width]`, ...); `[*]` lines
//! are comments. A `*zoom marker` line sets the zoom: GTKWave shows
//! `2^-zoom` time units per 200 pixels. An `@flags` line sets the display
//! flags, in hexadecimal, of the traces that follow; the bits are GTKWave's
//! `TR_*` trace flags (`analyzer.h`):
//!
//! | flag | bit | used for |
//! | --- | --- | --- |
//! | `TR_HEX` | `0x2` | [`Format::Hex`] |
//! | `TR_DEC` | `0x4` | [`Format::Decimal`] |
//! | `TR_BIN` | `0x8` | [`Format::Binary`], one-bit signals |
//! | `TR_RJUSTIFY` | `0x20` | every signal (values right-justified) |
//! | `TR_BLANK` | `0x200` | comment lines and group markers |
//! | `TR_SIGNED` | `0x400` | [`Format::SignedDecimal`] |
//! | `TR_CLOSED` | `0x400000` | a group shown collapsed |
//! | `TR_GRP_BEGIN` | `0x800000` | start of a group |
//! | `TR_GRP_END` | `0x1000000` | end of a group |
//!
//! so `@22` is hexadecimal, `@24` decimal, `@28` binary, `@200` a comment.
//! A trace line names a signal by its dotted full name; a vector's name ends
//! with its range as the VCD declares it (`top.core0.free_mshrs[4:0]`, which
//! GTKWave 3.3 needs to find a vector), a scalar has no brackets. A `-text`
//! line under `@200` is a comment line; under `@800200` / `@1000200` it opens
//! / closes a group.
//!
//! The output is deterministic: no date, no absolute path unless given.

use std::io::{self, Write};

use crate::vcd_sink::SignalInfo;

/// GTKWave trace flags (`TR_*` in GTKWave's `analyzer.h`).
mod flags {
    pub const HEX: u64 = 1 << 1;
    pub const DEC: u64 = 1 << 2;
    pub const BIN: u64 = 1 << 3;
    pub const RJUSTIFY: u64 = 1 << 5;
    pub const BLANK: u64 = 1 << 9;
    pub const SIGNED: u64 = 1 << 10;
    pub const CLOSED: u64 = 1 << 22;
    pub const GRP_BEGIN: u64 = 1 << 23;
    pub const GRP_END: u64 = 1 << 24;
}

/// How GTKWave displays a vector's value. One-bit signals are always drawn
/// as a waveform, with [`Format::Binary`] flags whatever is asked.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Format {
    /// Hexadecimal (GTKWave's default).
    #[default]
    Hex,
    /// Unsigned decimal.
    Decimal,
    /// Two's complement decimal.
    SignedDecimal,
    /// Binary.
    Binary,
}

impl Format {
    /// The `@` flags of a signal shown in this format.
    fn flags(self) -> u64 {
        flags::RJUSTIFY
            | match self {
                Format::Hex => flags::HEX,
                Format::Decimal => flags::DEC,
                Format::SignedDecimal => flags::DEC | flags::SIGNED,
                Format::Binary => flags::BIN,
            }
    }
}

/// One line of the trace list.
#[derive(Debug, Clone, PartialEq)]
enum Item {
    Signal {
        name: String,
        width: u32,
        format: Format,
    },
    Comment(String),
    GroupBegin {
        name: String,
        closed: bool,
    },
    GroupEnd,
}

/// The initial zoom.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Zoom {
    /// No zoom line: GTKWave picks (it fits dumps of at most 400 time units
    /// to the window, and zooms fully in on longer ones).
    Auto,
    /// Fit `timestart..=last` to the wave pane.
    Fit { last: u64 },
    /// An explicit GTKWave zoom level.
    Level(f64),
}

/// Default main window size, pixels.
const DEFAULT_SIZE: (u32, u32) = (1400, 700);
/// Default width of the signal search tree pane, pixels.
const DEFAULT_SST_WIDTH: u32 = 220;
/// Default width of the signal name pane, pixels.
const DEFAULT_SIGNALS_WIDTH: u32 = 280;
/// Pixels of the window width that are neither pane (borders, pane handles,
/// scroll bar), used to estimate the wave pane width for
/// [`GtkwSave::zoom_to_fit`]. Overestimating only zooms out a little.
const CHROME_WIDTH: u32 = 100;

/// A GTKWave save file, built up then written with
/// [`write_to`](GtkwSave::write_to).
#[derive(Debug, Clone, PartialEq)]
pub struct GtkwSave {
    dumpfile: String,
    items: Vec<Item>,
    timestart: u64,
    zoom: Zoom,
    size: (u32, u32),
    sst_width: u32,
    signals_width: u32,
    /// Header comment lines (`[*] text`), e.g. what a time unit is.
    notes: Vec<String>,
}

impl GtkwSave {
    /// A save file for the dump file at `dumpfile` (written as given; GTKWave
    /// resolves a relative path against its working directory).
    pub fn new(dumpfile: impl Into<String>) -> Self {
        GtkwSave {
            dumpfile: dumpfile.into(),
            items: Vec::new(),
            timestart: 0,
            zoom: Zoom::Auto,
            size: DEFAULT_SIZE,
            sst_width: DEFAULT_SST_WIDTH,
            signals_width: DEFAULT_SIGNALS_WIDTH,
            notes: Vec::new(),
        }
    }

    /// A `[*] text` comment line in the file's header, after the version
    /// line; GTKWave ignores it. Used to say what a time unit is
    /// ([`time_unit_note`](crate::vcd_sink::time_unit_note)), since GTKWave
    /// labels the axis with the VCD's physical unit.
    pub fn note(mut self, text: impl Into<String>) -> Self {
        self.notes.push(text.into());
        self
    }

    /// First cycle shown at the left edge (default 0). Times in a save file
    /// are VCD time units: cycles on the
    /// [cycle axis](crate::vcd_sink::TimeAxis::Cycles), picoseconds on the
    /// real-time one.
    pub fn timestart(mut self, cycle: u64) -> Self {
        self.timestart = cycle;
        self
    }

    /// Zoom so that cycles `timestart..=last_cycle` fill the wave pane.
    ///
    /// A save file cannot ask GTKWave to "zoom to fit", so the zoom level is
    /// computed from the window and pane sizes this file sets, the way
    /// GTKWave's own *Zoom Best Fit* does. Pass the last cycle of the dump
    /// (the `final_cycle` given to
    /// [`VcdSink::finish`](crate::vcd_sink::VcdSink::finish)).
    pub fn zoom_to_fit(mut self, last_cycle: u64) -> Self {
        self.zoom = Zoom::Fit { last: last_cycle };
        self
    }

    /// An explicit GTKWave zoom level: `2^-level` cycles per 200 pixels, so 0
    /// is the closest zoom (200 pixels a cycle) and each step of -1 halves
    /// the magnification.
    pub fn zoom(mut self, level: f64) -> Self {
        self.zoom = Zoom::Level(level);
        self
    }

    /// Main window size in pixels (default 1400 x 700).
    pub fn window_size(mut self, width: u32, height: u32) -> Self {
        self.size = (width, height);
        self
    }

    /// Width in pixels of the pane listing the shown signal names (default
    /// 280).
    pub fn signals_width(mut self, pixels: u32) -> Self {
        self.signals_width = pixels;
        self
    }

    /// Adds a signal by dotted full name (`top.core0.free_mshrs`) and width;
    /// vectors get their `[msb:0]` range appended.
    pub fn signal(mut self, full_name: impl Into<String>, width: u32, format: Format) -> Self {
        self.items.push(Item::Signal {
            name: full_name.into(),
            width,
            format,
        });
        self
    }

    /// Adds a signal of a [`VcdSink`](crate::vcd_sink::VcdSink).
    pub fn traced(self, info: &SignalInfo, format: Format) -> Self {
        self.signal(info.full_name(), info.width, format)
    }

    /// Adds a comment line, e.g. a heading above a set of signals.
    pub fn comment_group(mut self, text: impl Into<String>) -> Self {
        self.items.push(Item::Comment(text.into()));
        self
    }

    /// Opens a named group, which GTKWave can fold; close it with
    /// [`end_group`](Self::end_group). `closed` shows it folded.
    pub fn begin_group(mut self, name: impl Into<String>, closed: bool) -> Self {
        self.items.push(Item::GroupBegin {
            name: name.into(),
            closed,
        });
        self
    }

    /// Closes the innermost open group.
    pub fn end_group(mut self) -> Self {
        self.items.push(Item::GroupEnd);
        self
    }

    /// The zoom level written, if any.
    fn zoom_level(&self) -> Option<f64> {
        match self.zoom {
            Zoom::Auto => None,
            Zoom::Level(level) => Some(level),
            Zoom::Fit { last } => {
                let span = last.saturating_sub(self.timestart) + 1;
                let wave_width = self
                    .size
                    .0
                    .saturating_sub(self.sst_width + self.signals_width + CHROME_WIDTH)
                    .max(100);
                // GTKWave: 2^-zoom time units per 200 pixels.
                let level = -(span as f64 * 200.0 / f64::from(wave_width)).log2();
                Some(level.min(0.0))
            }
        }
    }

    /// Checks names and nesting before anything is written.
    fn validate(&self) -> io::Result<()> {
        fn bad(message: String) -> io::Error {
            io::Error::new(io::ErrorKind::InvalidInput, message)
        }
        if let Some(note) = self.notes.iter().find(|n| n.contains(['\n', '\r'])) {
            return Err(bad(format!("note {note:?} contains a newline")));
        }
        if self.dumpfile.contains(['\n', '\r', '"']) {
            return Err(bad(format!(
                "dump file path {:?} contains a newline or a double quote",
                self.dumpfile
            )));
        }
        let mut depth = 0usize;
        for item in &self.items {
            match item {
                Item::Signal { name, width, .. } => {
                    if name.is_empty() || name.contains(char::is_whitespace) {
                        return Err(bad(format!(
                            "signal name {name:?} is empty or contains whitespace"
                        )));
                    }
                    if *width == 0 {
                        return Err(bad(format!("signal `{name}` has width 0")));
                    }
                }
                Item::Comment(text) | Item::GroupBegin { name: text, .. } => {
                    if text.contains(['\n', '\r']) {
                        return Err(bad(format!("comment or group {text:?} contains a newline")));
                    }
                    if matches!(item, Item::GroupBegin { .. }) {
                        depth += 1;
                    }
                }
                Item::GroupEnd => {
                    depth = depth
                        .checked_sub(1)
                        .ok_or_else(|| bad("end_group without begin_group".to_owned()))?;
                }
            }
        }
        if depth != 0 {
            return Err(bad(format!("{depth} group(s) not closed with end_group")));
        }
        Ok(())
    }

    /// Writes the save file.
    ///
    /// # Errors
    ///
    /// [`io::ErrorKind::InvalidInput`] if a name contains whitespace or a
    /// newline, a signal has width 0, or groups are unbalanced (nothing is
    /// written then); any error of `out`.
    pub fn write_to(&self, mut out: impl Write) -> io::Result<()> {
        self.validate()?;
        writeln!(out, "[*]")?;
        writeln!(out, "[*] {} GTKWave save file", crate::vcd_sink::VERSION)?;
        for note in &self.notes {
            writeln!(out, "[*] {note}")?;
        }
        writeln!(out, "[*]")?;
        writeln!(out, "[dumpfile] \"{}\"", self.dumpfile)?;
        writeln!(out, "[timestart] {}", self.timestart)?;
        writeln!(out, "[size] {} {}", self.size.0, self.size.1)?;
        writeln!(out, "[pos] -1 -1")?;
        if let Some(level) = self.zoom_level() {
            // Zoom, then the primary marker (-1: none).
            writeln!(out, "*{level:.6} -1")?;
        }
        writeln!(out, "[sst_width] {}", self.sst_width)?;
        writeln!(out, "[signals_width] {}", self.signals_width)?;
        writeln!(out, "[sst_expanded] 1")?;

        // Flags persist until the next `@` line; write one only on change.
        let mut current = None;
        let mut set_flags = |out: &mut dyn Write, flags: u64| -> io::Result<()> {
            if current != Some(flags) {
                writeln!(out, "@{flags:x}")?;
                current = Some(flags);
            }
            Ok(())
        };
        let mut groups = Vec::new();
        for item in &self.items {
            match item {
                Item::Signal {
                    name,
                    width,
                    format,
                } => {
                    if *width > 1 {
                        set_flags(&mut out, format.flags())?;
                        writeln!(out, "{name}[{}:0]", width - 1)?;
                    } else {
                        set_flags(&mut out, Format::Binary.flags())?;
                        writeln!(out, "{name}")?;
                    }
                }
                Item::Comment(text) => {
                    set_flags(&mut out, flags::BLANK)?;
                    writeln!(out, "-{text}")?;
                }
                Item::GroupBegin { name, closed } => {
                    let closed = if *closed { flags::CLOSED } else { 0 };
                    set_flags(&mut out, flags::BLANK | flags::GRP_BEGIN | closed)?;
                    writeln!(out, "-{name}")?;
                    groups.push(name.as_str());
                }
                Item::GroupEnd => {
                    set_flags(&mut out, flags::BLANK | flags::GRP_END)?;
                    writeln!(out, "-{}", groups.pop().unwrap_or_default())?;
                }
            }
        }
        out.flush()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vcd_sink::VERSION;

    fn text(save: &GtkwSave) -> String {
        let mut out = Vec::new();
        save.write_to(&mut out).unwrap();
        String::from_utf8(out).unwrap()
    }

    #[test]
    fn exact_content() {
        let save = GtkwSave::new("run/waves.vcd")
            .zoom(-3.0)
            .signal("top.clk_en", 1, Format::Hex)
            .comment_group("Scheduler")
            .signal("top.core0.free_mshrs", 5, Format::Decimal)
            .signal("top.core0.pc", 32, Format::Hex)
            .signal("top.core0.credit", 8, Format::Hex)
            .signal("top.core0.mask", 4, Format::Binary)
            .signal("top.core0.delta", 6, Format::SignedDecimal)
            .begin_group("Memory", true)
            .signal("top.mem.busy", 1, Format::Binary)
            .end_group();
        let expected = format!(
            "[*]\n\
             [*] {VERSION} GTKWave save file\n\
             [*]\n\
             [dumpfile] \"run/waves.vcd\"\n\
             [timestart] 0\n\
             [size] 1400 700\n\
             [pos] -1 -1\n\
             *-3.000000 -1\n\
             [sst_width] 220\n\
             [signals_width] 280\n\
             [sst_expanded] 1\n\
             @28\n\
             top.clk_en\n\
             @200\n\
             -Scheduler\n\
             @24\n\
             top.core0.free_mshrs[4:0]\n\
             @22\n\
             top.core0.pc[31:0]\n\
             top.core0.credit[7:0]\n\
             @28\n\
             top.core0.mask[3:0]\n\
             @424\n\
             top.core0.delta[5:0]\n\
             @c00200\n\
             -Memory\n\
             @28\n\
             top.mem.busy\n\
             @1000200\n\
             -Memory\n"
        );
        assert_eq!(text(&save), expected);
    }

    #[test]
    fn auto_zoom_writes_no_zoom_line() {
        let t = text(&GtkwSave::new("w.vcd").signal("top.a", 1, Format::Binary));
        assert!(!t.lines().any(|l| l.starts_with('*')), "{t}");
    }

    #[test]
    fn zoom_to_fit_matches_gtkwave_best_fit() {
        // Wave pane: 1400 - 220 - 280 - 100 = 800 pixels for 101 cycles.
        let save = GtkwSave::new("w.vcd").zoom_to_fit(100);
        let level = save.zoom_level().unwrap();
        let cycles_per_200px = (-level).exp2();
        assert!((cycles_per_200px - 101.0 * 200.0 / 800.0).abs() < 1e-9);
        assert!(text(&save).contains(&format!("*{level:.6} -1\n")));

        // A span shorter than the pane is capped at the closest zoom.
        assert_eq!(
            GtkwSave::new("w.vcd").zoom_to_fit(1).zoom_level(),
            Some(0.0)
        );
        // timestart narrows the span.
        let late = GtkwSave::new("w.vcd").timestart(50).zoom_to_fit(100);
        assert!(late.zoom_level().unwrap() > level);
        assert!(text(&late).contains("[timestart] 50\n"));
    }

    #[test]
    fn traced_uses_signal_info() {
        let info = SignalInfo {
            path: vec!["top".into(), "core0".into()],
            name: "free_mshrs".into(),
            width: 5,
        };
        let t = text(&GtkwSave::new("w.vcd").traced(&info, Format::Decimal));
        assert!(t.ends_with("@24\ntop.core0.free_mshrs[4:0]\n"), "{t}");
    }

    #[test]
    fn invalid_input_is_rejected_before_writing() {
        let cases = [
            GtkwSave::new("w.vcd").signal("top.a b", 1, Format::Hex),
            GtkwSave::new("w.vcd").signal("top.a", 0, Format::Hex),
            GtkwSave::new("w.vcd").comment_group("two\nlines"),
            GtkwSave::new("w\".vcd"),
            GtkwSave::new("w.vcd").begin_group("g", false),
            GtkwSave::new("w.vcd").end_group(),
        ];
        for save in cases {
            let mut out = Vec::new();
            let err = save.write_to(&mut out).unwrap_err();
            assert_eq!(err.kind(), io::ErrorKind::InvalidInput, "{save:?}");
            assert!(out.is_empty());
        }
    }

    #[test]
    fn notes_follow_the_version_line() {
        let save = GtkwSave::new("w.vcd")
            .note("one time unit = one GPU cycle at 600 MHz (1.667 ns)")
            .signal("top.a", 1, Format::Binary);
        let t = text(&save);
        assert!(
            t.starts_with(&format!(
                "[*]\n[*] {VERSION} GTKWave save file\n\
                 [*] one time unit = one GPU cycle at 600 MHz (1.667 ns)\n[*]\n[dumpfile]"
            )),
            "{t}"
        );
        let mut out = Vec::new();
        let err = GtkwSave::new("w.vcd")
            .note("two\nlines")
            .write_to(&mut out)
            .unwrap_err();
        assert_eq!(err.kind(), io::ErrorKind::InvalidInput);
        assert!(out.is_empty());
    }
}
