//! The statistics as CSV: one flat `key,value` field per statistic, and
//! several runs under one header.

use super::RunStats;

impl RunStats {
    /// Flat `key,value` rows of the CSV, values unquoted (nested names
    /// joined with `.`; a list of numbers, such as a histogram, is one field
    /// of values joined by `;`, a list of records or lists is numbered:
    /// `priority_lead.histogram.3.count`, `occupancy.per_core_histogram.2`).
    /// The per-tile records are left out: they are in the JSON.
    pub fn to_csv_rows(&self) -> Vec<(String, String)> {
        let mut v = serde_json::to_value(self).expect("stats serialize");
        if let Some(m) = v.as_object_mut() {
            m.remove("per_tile");
        }
        let mut rows = Vec::new();
        flatten("", &v, &mut rows);
        rows
    }

    /// CSV with a header line and one line of values (several runs can be
    /// joined under one header with [`csv_table`]).
    pub fn to_csv(&self) -> String {
        csv_table(std::slice::from_ref(self))
    }
}

/// Flatten a JSON value into `key,value` CSV fields (unquoted: the
/// writer quotes them, [`csv_text`]) under `prefix`: nested
/// names joined with `.`, a list of plain values one field joined by `;`, a
/// list of records or lists numbered (the rows of [`RunStats::to_csv_rows`]).
pub fn flatten(prefix: &str, v: &serde_json::Value, out: &mut Vec<(String, String)>) {
    match v {
        serde_json::Value::Object(m) => {
            for (k, x) in m {
                let key = if prefix.is_empty() {
                    k.clone()
                } else {
                    format!("{prefix}.{k}")
                };
                flatten(&key, x, out);
            }
        }
        serde_json::Value::Null => out.push((prefix.to_string(), String::new())),
        serde_json::Value::String(s) => out.push((prefix.to_string(), s.clone())),
        serde_json::Value::Array(items)
            if items.iter().all(|x| !x.is_object() && !x.is_array()) =>
        {
            let joined: Vec<String> = items.iter().map(|x| x.to_string()).collect();
            out.push((prefix.to_string(), joined.join(";")));
        }
        serde_json::Value::Array(items) => {
            for (i, x) in items.iter().enumerate() {
                flatten(&format!("{prefix}.{i}"), x, out);
            }
        }
        other => out.push((prefix.to_string(), other.to_string())),
    }
}

/// Several runs as one CSV table: the header holds the first run's fields,
/// then those of later runs that it lacks (such as `issue`, which only a
/// run off the default order has), in order of appearance; a run without
/// a field leaves it empty.
pub fn csv_table(runs: &[RunStats]) -> String {
    csv_text(csv_records(runs))
}

/// The records of [`csv_table`]: the header, then one record a run.
pub fn csv_records(runs: &[RunStats]) -> Vec<Vec<String>> {
    let all: Vec<Vec<(String, String)>> = runs.iter().map(RunStats::to_csv_rows).collect();
    let mut header: Vec<String> = Vec::new();
    for rows in &all {
        for (k, _) in rows {
            if !header.contains(k) {
                header.push(k.clone());
            }
        }
    }
    if all.is_empty() {
        return Vec::new();
    }
    let mut out = vec![header.clone()];
    for rows in &all {
        out.push(
            header
                .iter()
                .map(|k| {
                    rows.iter()
                        .find(|(rk, _)| rk == k)
                        .map(|(_, v)| v.clone())
                        .unwrap_or_default()
                })
                .collect(),
        );
    }
    out
}

/// Records as CSV text, written by the `csv` crate: a field is quoted only
/// where it must be (it holds a comma, a quote or a line break), each
/// record ends in `\n`, and records may differ in length.
pub fn csv_text<R, F>(records: impl IntoIterator<Item = R>) -> String
where
    R: IntoIterator<Item = F>,
    F: AsRef<[u8]>,
{
    let mut w = csv::WriterBuilder::new()
        .flexible(true)
        .from_writer(Vec::new());
    for r in records {
        w.write_record(r).expect("CSV into memory: no I/O error");
    }
    let bytes = w.into_inner().expect("CSV into memory: no I/O error");
    String::from_utf8(bytes).expect("CSV of UTF-8 fields is UTF-8")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fields_are_quoted_only_where_they_must_be() {
        let t = csv_text([vec!["a", "b,c", "d\"e", "f\ng", "", " x"], vec!["1", ""]]);
        assert_eq!(t, "a,\"b,c\",\"d\"\"e\",\"f\ng\",, x\n1,\n");
        assert_eq!(csv_text(Vec::<Vec<&str>>::new()), "");
    }

    #[test]
    fn runs_share_one_header_and_leave_missing_fields_empty() {
        use crate::synth::{generate, GenParams};
        let run = |seed: u64| {
            let t = generate(&GenParams {
                frame_w: 64,
                frame_h: 32,
                seed,
                ..GenParams::default()
            })
            .unwrap();
            let cfg = crate::config::MachineConfig::paper();
            crate::run::simulate(&cfg, &t, &Default::default(), &mut |_, _| {}).unwrap()
        };
        let (a, b) = (run(1), run(2));
        let recs = csv_records(&[a.clone(), b.clone()]);
        assert_eq!(recs.len(), 3);
        let col = recs[0].iter().position(|k| k == "cycles").expect("cycles");
        assert_eq!(recs[1][col], a.cycles.to_string());
        assert_eq!(recs[2][col], b.cycles.to_string());
        assert_eq!(a.to_csv(), csv_table(std::slice::from_ref(&a)));
        assert!(a.to_csv().starts_with(&recs[0].join(",")));
        assert!(csv_records(&[]).is_empty());
    }
}
