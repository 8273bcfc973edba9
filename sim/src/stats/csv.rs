//! The statistics as CSV: one flat `key,value` field per statistic, and
//! several runs under one header.

use super::RunStats;

impl RunStats {
    /// Flat `key,value` CSV rows (nested names joined with `.`; a list of
    /// numbers, such as a histogram, is one field of values joined by `;`,
    /// a list of records or lists is numbered:
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

/// Flatten a JSON value into `key,value` CSV fields under `prefix`: nested
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
        serde_json::Value::String(s) => out.push((prefix.to_string(), csv_field(s))),
        serde_json::Value::Array(items)
            if items.iter().all(|x| !x.is_object() && !x.is_array()) =>
        {
            let joined: Vec<String> = items.iter().map(|x| x.to_string()).collect();
            out.push((prefix.to_string(), csv_field(&joined.join(";"))));
        }
        serde_json::Value::Array(items) => {
            for (i, x) in items.iter().enumerate() {
                flatten(&format!("{prefix}.{i}"), x, out);
            }
        }
        other => out.push((prefix.to_string(), other.to_string())),
    }
}

fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// Several runs as one CSV table: the header holds the first run's fields,
/// then those of later runs that it lacks (such as `issue`, which only a
/// run off the default order has), in order of appearance; a run without
/// a field leaves it empty.
pub fn csv_table(runs: &[RunStats]) -> String {
    let mut s = String::new();
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
        return s;
    }
    s.push_str(&header.join(","));
    s.push('\n');
    for rows in &all {
        let vals: Vec<String> = header
            .iter()
            .map(|k| {
                rows.iter()
                    .find(|(rk, _)| rk == k)
                    .map(|(_, v)| v.clone())
                    .unwrap_or_default()
            })
            .collect();
        s.push_str(&vals.join(","));
        s.push('\n');
    }
    s
}
