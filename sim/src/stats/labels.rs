//! The descriptive fields of a run's statistics that no configuration
//! enum names alone: the main-memory model with its timing
//! ([`DramModelLabel`], `"fixed: row hit 30 / row miss 60 cycles"`) and
//! the priority subset with whether the policy uses it ([`SubsetLabel`],
//! `"mesh4 (unused by the baseline)"`). Each is written in the JSON as
//! that text and read back from it.

use crate::mem::{DramConfig, DramModel};
use std::fmt;
use std::str::FromStr;
use wasp_rtl::subset::SubsetSpec;

/// Serde through a label's text: `TryFrom<String>` by its `FromStr`,
/// `Into<String>` by its `Display`.
macro_rules! through_text {
    ($($t:ty),*) => {$(
        impl TryFrom<String> for $t {
            type Error = String;
            fn try_from(s: String) -> Result<Self, String> {
                s.parse()
            }
        }

        impl From<$t> for String {
            fn from(l: $t) -> String {
                l.to_string()
            }
        }
    )*};
}

through_text!(DramModelLabel, SubsetLabel);

/// The main-memory model and the timing that sets its speed, as the
/// statistics name it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(try_from = "String", into = "String")]
pub enum DramModelLabel {
    /// The fixed-latency model.
    Fixed {
        /// `dram.row_hit_latency`.
        row_hit_latency: u32,
        /// `dram.row_miss_latency`.
        row_miss_latency: u32,
    },
    /// The banked model.
    Banked {
        /// `dram.channels`.
        channels: u32,
        /// `dram.banks` (per channel).
        banks: u32,
        /// `dram.t_burst`: cycles a line holds the data bus.
        t_burst: u32,
    },
}

impl DramModelLabel {
    /// The label of `dram`.
    pub fn of(dram: &DramConfig) -> Self {
        match dram.model {
            DramModel::Banked => DramModelLabel::Banked {
                channels: dram.channels,
                banks: dram.banks,
                t_burst: dram.t_burst,
            },
            DramModel::Fixed => DramModelLabel::Fixed {
                row_hit_latency: dram.row_hit_latency,
                row_miss_latency: dram.row_miss_latency,
            },
        }
    }

    /// The model.
    pub fn model(self) -> DramModel {
        match self {
            DramModelLabel::Fixed { .. } => DramModel::Fixed,
            DramModelLabel::Banked { .. } => DramModel::Banked,
        }
    }
}

impl fmt::Display for DramModelLabel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            DramModelLabel::Banked {
                channels,
                banks,
                t_burst,
            } => write!(
                f,
                "banked: {channels} channels x {banks} banks / {t_burst} cycles a line"
            ),
            DramModelLabel::Fixed {
                row_hit_latency,
                row_miss_latency,
            } => write!(
                f,
                "fixed: row hit {row_hit_latency} / row miss {row_miss_latency} cycles"
            ),
        }
    }
}

impl FromStr for DramModelLabel {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        let bad = || {
            format!(
                "dram_model {s:?}: expected \"fixed: row hit H / row miss M cycles\" or \
                 \"banked: C channels x B banks / T cycles a line\""
            )
        };
        let num = |t: &str| t.parse::<u32>().map_err(|_| bad());
        let words: Vec<&str> = s.split(' ').collect();
        match words.as_slice() {
            ["fixed:", "row", "hit", h, "/", "row", "miss", m, "cycles"] => {
                Ok(DramModelLabel::Fixed {
                    row_hit_latency: num(h)?,
                    row_miss_latency: num(m)?,
                })
            }
            ["banked:", c, "channels", "x", b, "banks", "/", t, "cycles", "a", "line"] => {
                Ok(DramModelLabel::Banked {
                    channels: num(c)?,
                    banks: num(b)?,
                    t_burst: num(t)?,
                })
            }
            _ => Err(bad()),
        }
    }
}

/// The priority subset and whether the run's policy launches priority
/// warps at all (the baseline does not).
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(try_from = "String", into = "String")]
pub struct SubsetLabel {
    /// The subset (`scheduler.subset`).
    pub spec: SubsetSpec,
    /// Whether the policy uses it (every policy but the baseline).
    pub used: bool,
}

/// What follows the subset's name when the policy does not use it.
const UNUSED: &str = " (unused by the baseline)";

impl fmt::Display for SubsetLabel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.spec)?;
        if !self.used {
            f.write_str(UNUSED)?;
        }
        Ok(())
    }
}

impl FromStr for SubsetLabel {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        let (name, used) = match s.strip_suffix(UNUSED) {
            Some(name) => (name, false),
            None => (s, true),
        };
        Ok(SubsetLabel {
            spec: name.parse()?,
            used,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dram_labels_read_back_what_they_write() {
        let mut d = DramConfig::default();
        for model in [DramModel::Fixed, DramModel::Banked] {
            d.model = model;
            let l = DramModelLabel::of(&d);
            assert_eq!(l.model(), model);
            assert_eq!(l.to_string().parse::<DramModelLabel>(), Ok(l));
        }
        assert_eq!(
            "fixed: row hit 30 / row miss 60 cycles".parse(),
            Ok(DramModelLabel::Fixed {
                row_hit_latency: 30,
                row_miss_latency: 60
            })
        );
        let e = "fixed: row hit x / row miss 60 cycles"
            .parse::<DramModelLabel>()
            .unwrap_err();
        assert!(e.contains("expected"), "{e}");
        assert!("banked".parse::<DramModelLabel>().is_err());
    }

    #[test]
    fn subset_labels_read_back_what_they_write() {
        for used in [true, false] {
            let l = SubsetLabel {
                spec: SubsetSpec::Random(7),
                used,
            };
            assert_eq!(l.to_string().parse::<SubsetLabel>(), Ok(l.clone()));
        }
        assert_eq!(
            SubsetLabel {
                spec: SubsetSpec::Mesh(4),
                used: false
            }
            .to_string(),
            "mesh4 (unused by the baseline)"
        );
        assert!("mesh3".parse::<SubsetLabel>().is_err());
    }
}
