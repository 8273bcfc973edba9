//! `wasp compare --variant NAME:KEY=VALUE[,KEY=VALUE...]`: machine
//! variants beside the machine as configured, so that rivals that are
//! machine options (a prefetcher, ideal memory) and launch policies stand in
//! one table of speedups against one reference row.

use crate::cli_error::CliError;
use serde::Serialize;
use std::fmt::Write as _;
use wasp_sim::config::{MachineConfig, Override};
use wasp_sim::stats::{csv_records, csv_text, RunStats};

/// One `--variant`: a name and the overrides it applies on top of the
/// machine as configured.
#[derive(Clone, Debug, PartialEq)]
pub struct Variant {
    /// The name its rows carry (`raster` in `raster/baseline`).
    pub name: String,
    /// Its overrides, in order.
    pub sets: Vec<Override>,
}

impl std::str::FromStr for Variant {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        let (name, sets) = s.split_once(':').ok_or_else(|| {
            format!(
                "`{s}`: expected NAME:KEY=VALUE[,KEY=VALUE...], e.g. \
                 raster:prefetch.kind=raster"
            )
        })?;
        let name = name.trim();
        if name.is_empty()
            || !name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_')
        {
            return Err(format!(
                "`{s}`: the name `{name}` must be letters, digits, `-` or `_`"
            ));
        }
        let sets = sets
            .split(',')
            .map(|x| {
                x.trim().parse().map_err(|_| {
                    format!(
                        "`{s}`: `{}` is not KEY=VALUE (e.g. prefetch.kind=raster)",
                        x.trim()
                    )
                })
            })
            .collect::<Result<Vec<Override>, String>>()?;
        Ok(Variant {
            name: name.to_string(),
            sets,
        })
    }
}

/// The machine of each variant: `base` with its overrides, named with them.
/// Names must be unique.
pub fn machines(
    base: &MachineConfig,
    variants: &[Variant],
) -> Result<Vec<(Variant, MachineConfig)>, CliError> {
    let mut out: Vec<(Variant, MachineConfig)> = Vec::new();
    for v in variants {
        if out.iter().any(|(o, _)| o.name == v.name) {
            return Err(CliError::usage(format!(
                "--variant {}: two variants of that name; give each its own",
                v.name
            )));
        }
        let mut cfg = base
            .with_overrides(&v.sets)
            .map_err(|e| CliError::usage(format!("--variant {}: {e}", v.name)))?;
        cfg.name = cfg.named_with(&v.sets);
        out.push((v.clone(), cfg));
    }
    Ok(out)
}

/// One row of a comparison with variants.
#[derive(Serialize)]
pub struct Row<'a> {
    /// `POLICY` on the machine as configured, `NAME/POLICY` on a variant.
    pub row: &'a str,
    /// The variant's name (`null` on the machine as configured).
    pub variant: Option<&'a str>,
    /// The reference row of the speedup.
    pub reference: &'a str,
    /// `reference cycles / cycles - 1`, in percent.
    pub speedup_percent: f64,
    /// The run's statistics.
    pub stats: &'a RunStats,
}

/// Speedup of `r` against `base`, in percent.
pub fn speedup(base: &RunStats, r: &RunStats) -> f64 {
    100.0 * (base.cycles as f64 / r.cycles as f64 - 1.0)
}

/// The rows as JSON: an array of [`Row`].
pub fn json(rows: &[Row]) -> Result<String, CliError> {
    serde_json::to_string_pretty(rows)
        .map(|t| t + "\n")
        .map_err(|e| CliError::failed(format!("encoding JSON: {e}")))
}

/// The rows as CSV: `row`, `variant`, `reference`, `speedup_percent`, then
/// every statistic's column as in `wasp compare --csv`.
pub fn csv(rows: &[Row]) -> String {
    let runs: Vec<RunStats> = rows.iter().map(|r| r.stats.clone()).collect();
    let table = csv_records(&runs);
    let lead = ["row", "variant", "reference", "speedup_percent"].map(String::from);
    let records = table.into_iter().enumerate().map(|(i, fields)| {
        let first = match i {
            0 => lead.clone(),
            _ => {
                let r = &rows[i - 1];
                [
                    r.row.to_string(),
                    r.variant.unwrap_or("").to_string(),
                    r.reference.to_string(),
                    format!("{:.4}", r.speedup_percent),
                ]
            }
        };
        first.into_iter().chain(fields).collect::<Vec<String>>()
    });
    csv_text(records)
}

/// The lines naming each variant's machine, for the table's header.
pub fn header(machines: &[(Variant, MachineConfig)]) -> String {
    let mut s = String::new();
    for (v, cfg) in machines {
        let _ = writeln!(s, "variant {}: machine {}", v.name, cfg.name);
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn variants_parse_and_refuse_bad_forms() {
        let v: Variant = "raster:prefetch.kind=raster, l0.mshrs=8".parse().unwrap();
        assert_eq!(v.name, "raster");
        let texts: Vec<String> = v.sets.iter().map(Override::to_string).collect();
        assert_eq!(texts, ["prefetch.kind=raster", "l0.mshrs=8"]);
        assert!("raster"
            .parse::<Variant>()
            .unwrap_err()
            .contains("NAME:KEY"));
        assert!("a b:x=1"
            .parse::<Variant>()
            .unwrap_err()
            .contains("letters"));
        assert!("r:x".parse::<Variant>().unwrap_err().contains("KEY=VALUE"));
    }

    #[test]
    fn each_variant_is_named_and_checked() {
        let base = MachineConfig::paper();
        let vs: Vec<Variant> = vec!["p:prefetch.kind=raster".parse().unwrap()];
        let m = machines(&base, &vs).unwrap();
        assert_eq!(m[0].1.name, "paper-width4-64warps + prefetch.kind=raster");
        let twice = vec![vs[0].clone(), vs[0].clone()];
        assert!(machines(&base, &twice).is_err());
        let bad = vec!["q:l0.mshrs=0".parse().unwrap()];
        let e = machines(&base, &bad).unwrap_err().to_string();
        assert!(e.starts_with("--variant q: "), "{e}");
    }
}
