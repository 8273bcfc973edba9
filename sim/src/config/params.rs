//! The machine's parameters as facts: every field of every section with
//! its path, type, value, declared range and description, as `section!`
//! declares them ([`crate::param`]), and the Markdown table of the paper's
//! machine that docs/machine.md shows between its `params` markers (a test
//! fails when the two differ; `WASP_ACCEPT_GOLDEN=1 cargo test -p wasp-sim
//! config::params` rewrites the doc's table).

use super::MachineConfig;
use crate::param::Param;

/// The marker line before the generated table in docs/machine.md.
pub const TABLE_BEGIN: &str = "<!-- params: generated from section! by `WASP_ACCEPT_GOLDEN=1 cargo test -p wasp-sim config::params`; do not edit -->";
/// The marker line after it.
pub const TABLE_END: &str = "<!-- params: end -->";

impl MachineConfig {
    /// Every field of every section, in the order of `configs/paper.toml`,
    /// with this machine's values (the `[l0]` fields only when it has an
    /// L0). For [`MachineConfig::paper`] the values are the defaults.
    pub fn params(&self) -> Vec<Param> {
        let mut all = self.gpu.params("gpu");
        all.extend(self.raster.params("raster"));
        all.extend(self.core.params("core"));
        all.extend(self.scheduler.params("scheduler"));
        if let Some(l0) = &self.l0 {
            all.extend(l0.params("l0"));
        }
        all.extend(self.l1.params("l1"));
        all.extend(self.l2.params("l2"));
        all.extend(self.dram.params("dram"));
        all.extend(self.memory.params("memory"));
        all.extend(self.prefetch.params("prefetch"));
        all.extend(self.energy.params("energy"));
        all.extend(self.sim.params("sim"));
        all
    }
}

/// The Markdown table of `params` (field, type, default, range,
/// description), one row a field. The description is the first sentence
/// of the doc comment; a field described as an earlier one with the same
/// key (`l1.ways` after `l0.ways`) points at it.
pub fn markdown_table(params: &[Param]) -> String {
    let mut out = String::from("| field | type | default | range | description |\n");
    out.push_str("|---|---|---|---|---|\n");
    for (i, p) in params.iter().enumerate() {
        let key = p.path.split_once('.').map_or("", |(_, k)| k);
        let same = params[..i]
            .iter()
            .find(|q| q.doc == p.doc && q.path.ends_with(&format!(".{key}")));
        let description = match same {
            Some(q) => format!("as `{}`", q.path),
            None => first_sentence(&plain(p.doc)),
        };
        out.push_str(&format!(
            "| `{}` | `{}` | `{}` | {} | {} |\n",
            p.path,
            p.ty,
            p.value,
            cell(&range_text(p)),
            cell(&description)
        ));
    }
    out
}

/// The range column: `lo..=hi` with its note, `any` for an unbounded
/// number, nothing for a value of another kind (its description names the
/// forms).
fn range_text(p: &Param) -> String {
    match &p.range {
        Some(r) if p.ty == "f64" => format!("{}..={}{}, finite", r.lo, r.hi, r.note),
        Some(r) if r.generic => format!("{}..={}{}", r.lo, r.hi, r.note),
        Some(r) => format!("{}..={}, {}", r.lo, r.hi, r.note),
        None if matches!(p.ty, "u32" | "u64" | "f64") => "any".into(),
        None => String::new(),
    }
}

/// `text` safe in a table cell.
fn cell(text: &str) -> String {
    text.replace('|', "\\|")
}

/// A doc comment as one line of Markdown without rustdoc's links:
/// ``[`X`](path)`` and ``[`X`]`` become `` `X` ``, `[text](url)` `text`.
fn plain(doc: &str) -> String {
    let text = doc.split_whitespace().collect::<Vec<_>>().join(" ");
    let mut out = String::new();
    let mut chars = text.chars().peekable();
    let mut code = false;
    while let Some(c) = chars.next() {
        match c {
            '`' => {
                code = !code;
                out.push(c);
            }
            '[' | ']' if !code => {
                if c == ']' && chars.peek() == Some(&'(') {
                    let mut depth = 0;
                    for d in chars.by_ref() {
                        depth += match d {
                            '(' => 1,
                            ')' => -1,
                            _ => 0,
                        };
                        if depth == 0 {
                            break;
                        }
                    }
                }
            }
            _ => out.push(c),
        }
    }
    out
}

/// The text up to its first full stop outside code and parentheses.
fn first_sentence(text: &str) -> String {
    let (mut code, mut depth) = (false, 0i32);
    for (i, c) in text.char_indices() {
        match c {
            '`' => code = !code,
            '(' if !code => depth += 1,
            ')' if !code => depth -= 1,
            '.' if !code && depth == 0 && text[i + 1..].starts_with(' ') => {
                return text[..=i].to_string();
            }
            _ => {}
        }
    }
    text.to_string()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::PAPER_TOML;

    const MACHINE_MD: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/machine.md");

    #[test]
    fn docs_machine_md_shows_the_current_parameter_table() {
        let doc = std::fs::read_to_string(MACHINE_MD).unwrap();
        let a = doc.find(TABLE_BEGIN).expect("the begin marker") + TABLE_BEGIN.len() + 1;
        let b = a + doc[a..].find(TABLE_END).expect("the end marker");
        let table = markdown_table(&MachineConfig::paper().params());
        if std::env::var_os("WASP_ACCEPT_GOLDEN").is_some() {
            std::fs::write(MACHINE_MD, format!("{}{table}{}", &doc[..a], &doc[b..])).unwrap();
        } else {
            assert!(
                doc[a..b] == table,
                "docs/machine.md's parameter table is stale: rewrite it with \
                 WASP_ACCEPT_GOLDEN=1 cargo test -p wasp-sim config::params"
            );
        }
    }

    #[test]
    fn paper_toml_sets_every_parameter_once_within_its_range() {
        let file: toml::Table = toml::from_str(PAPER_TOML).unwrap();
        let mut keys = Vec::new();
        for (section, table) in &file {
            if let Some(table) = table.as_table() {
                keys.extend(table.iter().map(|(k, v)| (format!("{section}.{k}"), v)));
            }
        }
        let params = MachineConfig::paper().params();
        assert_eq!(keys.len(), params.len());
        for (path, v) in keys {
            let p = params.iter().find(|p| p.path == path);
            let p = p.unwrap_or_else(|| panic!("{path} is not a parameter"));
            assert_eq!(v, &p.value, "{path} is written as it reads back");
            if let Some(r) = &p.range {
                let x = v.as_float().or(v.as_integer().map(|i| i as f64)).unwrap();
                let (lo, hi): (f64, f64) = (r.lo.parse().unwrap(), r.hi.parse().unwrap());
                assert!((lo..=hi).contains(&x), "{path} = {v} outside {lo}..={hi}");
            }
        }
    }

    #[test]
    fn a_key_with_a_declared_default_defaults_to_the_papers_value() {
        // Keys a whole file may leave out (added after files existed
        // without them): their serde default is the file's value.
        let file: toml::Table = toml::from_str(PAPER_TOML).unwrap();
        let mut defaulted = Vec::new();
        for p in MachineConfig::paper().params() {
            let (section, key) = p.path.split_once('.').unwrap();
            let mut without = file.clone();
            without[section].as_table_mut().unwrap().remove(key);
            let text = toml::to_string(&without).unwrap();
            if let Ok(m) = toml::from_str::<MachineConfig>(&text) {
                assert_eq!(m, MachineConfig::paper(), "{} defaults elsewhere", p.path);
                defaulted.push(p.path);
            }
        }
        let mut without = file.clone();
        without.remove("prefetch");
        let m: MachineConfig = toml::from_str(&toml::to_string(&without).unwrap()).unwrap();
        assert_eq!(m, MachineConfig::paper(), "a file without [prefetch]");
        assert_eq!(
            defaulted,
            [
                "raster.rejected_per_slot",
                "core.issue",
                "memory.texture_cache"
            ]
        );
    }

    #[test]
    fn descriptions_are_plain_first_sentences() {
        let doc = "Launch policy: `wasp[:t]` (see\n[`PolicySpec`]; checked by\n[`validate`](super::X::validate)). More.\n";
        assert_eq!(
            first_sentence(&plain(doc)),
            "Launch policy: `wasp[:t]` (see `PolicySpec`; checked by `validate`)."
        );
        assert_eq!(cell("`a|b`"), "`a\\|b`");
    }
}
