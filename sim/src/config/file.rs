//! Reading a configuration file: a whole machine, or the fields in which
//! it differs from a base machine.
//!
//! A file that sets every field of the machine (as the shipped ones do,
//! and as [`MachineConfig::to_toml`] writes them) is that machine. Any other file is a patch, read on top of a base: the
//! machine its top-level `extends` names, by default the paper's
//! (`configs/paper.toml`). `extends` takes a shipped machine by name
//! ([`SHIPPED`]: `paper`, `paper-width2`) or a file, relative to the file
//! that names it; that file may be a patch in turn. A patch's sections
//! merge key by key into the base's (a section the base lacks, such as
//! `[l0]` on `paper-width2`, must then be whole); its other values replace
//! the base's. Unknown keys are errors, and every error about a key of
//! the file names the file and the line that set it (`my.toml:12`).
//!
//! So `[l0]\nmshrs = 8` alone is the paper's machine with 8 L0 MSHRs. A
//! patch without `extends` has the paper's L0: a machine without one
//! extends `paper-width2`.

use super::{ConfigError, MachineConfig, SHIPPED};
use serde::de::{Deserializer, MapAccess, SeqAccess, Visitor};
use serde::Deserialize;
use std::collections::BTreeMap;
use std::fmt;
use std::path::{Path, PathBuf};
use toml::Spanned;

/// Files a chain of `extends` may hold (a longer one has a cycle).
const MAX_DEPTH: usize = 16;

/// Read the file at `path` as a machine; `depth` files extend it.
pub(super) fn load(path: &Path, depth: usize) -> Result<MachineConfig, ConfigError> {
    let source = path.display().to_string();
    let bytes = std::fs::read(path).map_err(|e| ConfigError {
        source: source.clone(),
        message: format!("cannot read: {e}"),
    })?;
    let text = std::str::from_utf8(&bytes).map_err(|e| {
        let at = e.valid_up_to();
        let (line, column) = line_and_column(&bytes, at);
        ConfigError {
            source: format!("{source}:{line}:{column}"),
            message: format!(
                "byte 0x{:02x} is not UTF-8 (line {line}, byte column {column}); a \
                 configuration is UTF-8 TOML text",
                bytes[at]
            ),
        }
    })?;
    read(text, &source, path.parent(), depth)
}

/// Read `text` (named `source`; its `extends` paths relative to `dir`, or
/// to the working directory) as a machine; `depth` files extend it.
pub(super) fn read(
    text: &str,
    source: &str,
    dir: Option<&Path>,
    depth: usize,
) -> Result<MachineConfig, ConfigError> {
    let mut file = ConfigFile::parse(text, source)?;
    let extends = match file.table.remove("extends") {
        None => None,
        Some(toml::Value::String(name)) => Some(name),
        Some(other) => {
            return Err(file.error(format!(
            "extends = {other}: expected the name of a shipped machine ({}) or a file, as a string",
            shipped_names()
        )))
        }
    };
    let whole = MachineConfig::deserialize(toml::Value::Table(file.table.clone()));
    let base = match (extends, whole) {
        (Some(name), _) => Some(base(&file, &name, dir, depth)?),
        (None, Ok(_)) => None,
        (None, Err(_)) => Some(MachineConfig::paper()),
    };
    let mut table = match base {
        Some(base) => match toml::Value::try_from(&base).expect("a machine serializes") {
            toml::Value::Table(t) => t,
            _ => unreachable!("a machine is a table"),
        },
        None => toml::Table::new(),
    };
    merge(&mut table, &file.table);
    let cfg = MachineConfig::deserialize(toml::Value::Table(table))
        .map_err(|e| file.deserialize_error(e))?;
    cfg.validate().map_err(|m| file.error(m))?;
    Ok(cfg)
}

/// The machine `name` (the value of `file`'s `extends`) names.
fn base(
    file: &ConfigFile,
    name: &str,
    dir: Option<&Path>,
    depth: usize,
) -> Result<MachineConfig, ConfigError> {
    if depth + 1 >= MAX_DEPTH {
        return Err(file.error(format!(
            "extends = \"{name}\": more than {MAX_DEPTH} files extend one another (a cycle?)"
        )));
    }
    if let Some((shipped, text)) = SHIPPED.iter().find(|(n, _)| *n == name) {
        return read(
            text,
            &format!("<embedded configs/{shipped}.toml>"),
            None,
            depth + 1,
        );
    }
    let path = match dir {
        Some(d) => d.join(name),
        None => PathBuf::from(name),
    };
    if !path.exists() {
        return Err(file.error(format!(
            "extends = \"{name}\": no shipped machine of that name ({}) and no file {}",
            shipped_names(),
            path.display()
        )));
    }
    load(&path, depth + 1)
}

fn shipped_names() -> String {
    let names: Vec<&str> = SHIPPED.iter().map(|(n, _)| *n).collect();
    names.join(", ")
}

/// Merge `patch` into `base`: tables key by key, other values replaced.
fn merge(base: &mut toml::Table, patch: &toml::Table) {
    for (key, value) in patch {
        match (base.get_mut(key), value) {
            (Some(toml::Value::Table(b)), toml::Value::Table(p)) => merge(b, p),
            _ => {
                base.insert(key.clone(), value.clone());
            }
        }
    }
}

/// The 1-based line and byte column of byte `at` of `bytes`.
fn line_and_column(bytes: &[u8], at: usize) -> (usize, usize) {
    let before = &bytes[..at];
    let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
    let start = before
        .iter()
        .rposition(|&b| b == b'\n')
        .map_or(0, |i| i + 1);
    (line, at - start + 1)
}

/// One parsed file.
#[derive(Debug)]
struct ConfigFile {
    /// The file's name (or `<embedded ...>`), for errors.
    source: String,
    /// Its table.
    table: toml::Table,
    /// The line of every key, by dotted path (`core.max_warps`; a section's
    /// own line is its header's).
    lines: BTreeMap<String, usize>,
}

impl ConfigFile {
    /// Parse TOML `text`; `source` names it in errors.
    fn parse(text: &str, source: &str) -> Result<Self, ConfigError> {
        let node: Node = toml::from_str(text).map_err(|e| ConfigError {
            source: source.to_string(),
            message: e.to_string().trim_end().to_string(),
        })?;
        let starts: Vec<usize> = std::iter::once(0)
            .chain(text.match_indices('\n').map(|(i, _)| i + 1))
            .collect();
        let line = |at: usize| starts.partition_point(|&s| s <= at);
        let mut lines = BTreeMap::new();
        let Node::Table(entries) = node else {
            unreachable!("a TOML document is a table")
        };
        let table = entries.into_table("", &line, &mut lines);
        Ok(ConfigFile {
            source: source.to_string(),
            table,
            lines,
        })
    }

    /// The error `message`, with this file as its source and, when the
    /// message names a key of the file, that key's line
    /// (`file.toml:12`). The key named first in the message counts, the
    /// longest when several start there.
    fn error(&self, message: String) -> ConfigError {
        let named = self
            .lines
            .iter()
            .filter_map(|(key, &line)| {
                Some((find_key(&message, key)?, usize::MAX - key.len(), line))
            })
            .min();
        ConfigError {
            source: match named {
                Some((_, _, line)) => format!("{}:{line}", self.source),
                None => self.source.clone(),
            },
            message,
        }
    }

    /// The error of deserializing the file's table: serde names the place
    /// last (`...\nin `scheduler.policy``); the message names it first
    /// (`scheduler.policy: ...`), and an unknown field by its own path.
    fn deserialize_error(&self, e: toml::de::Error) -> ConfigError {
        let text = e.to_string().trim_end().to_string();
        let (what, place) = match text.rsplit_once("\nin `") {
            Some((what, place)) => (what.to_string(), place.trim_end_matches('`').to_string()),
            None => (text, String::new()),
        };
        let unknown = what
            .strip_prefix("unknown field `")
            .and_then(|r| r.split_once('`'))
            .map(|(key, _)| key);
        let place = match (unknown, place.as_str()) {
            (Some(key), "") => key.to_string(),
            (Some(key), section) => format!("{section}.{key}"),
            (None, place) => place.to_string(),
        };
        if place.is_empty() {
            self.error(what)
        } else {
            self.error(format!("{place}: {what}"))
        }
    }
}

/// Where `key` appears in `message` as a whole dotted name (not inside a
/// longer one), if it does.
fn find_key(message: &str, key: &str) -> Option<usize> {
    let word = |c: char| c.is_ascii_alphanumeric() || c == '_' || c == '.';
    message.match_indices(key).map(|(i, _)| i).find(|&i| {
        let before = message[..i].chars().next_back();
        let after = message[i + key.len()..].chars().next();
        !before.is_some_and(word) && !after.is_some_and(|c| word(c) && c != '.')
    })
}

/// A TOML value with the spans of its keys.
enum Node {
    Table(Entries),
    Value(toml::Value),
}

/// A table's keys and values, in file order, with their spans.
struct Entries(Vec<(Spanned<String>, Node)>);

impl Entries {
    /// The plain table, recording in `lines` the line of every key under
    /// `prefix`.
    fn into_table(
        self,
        prefix: &str,
        line: &dyn Fn(usize) -> usize,
        lines: &mut BTreeMap<String, usize>,
    ) -> toml::Table {
        let mut table = toml::Table::new();
        for (key, node) in self.0 {
            let path = if prefix.is_empty() {
                key.get_ref().clone()
            } else {
                format!("{prefix}.{}", key.get_ref())
            };
            lines.insert(path.clone(), line(key.span().start));
            let value = match node {
                Node::Table(t) => toml::Value::Table(t.into_table(&path, line, lines)),
                Node::Value(v) => v,
            };
            table.insert(key.into_inner(), value);
        }
        table
    }
}

impl<'de> Deserialize<'de> for Node {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(NodeVisitor)
    }
}

struct NodeVisitor;

impl<'de> Visitor<'de> for NodeVisitor {
    type Value = Node;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a TOML value")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Node, A::Error> {
        let mut entries = Vec::new();
        while let Some(key) = map.next_key::<Spanned<String>>()? {
            entries.push((key, map.next_value::<Node>()?));
        }
        Ok(Node::Table(Entries(entries)))
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Node, A::Error> {
        let mut items = Vec::new();
        while let Some(v) = seq.next_element::<toml::Value>()? {
            items.push(v);
        }
        Ok(Node::Value(toml::Value::Array(items)))
    }

    fn visit_str<E>(self, v: &str) -> Result<Node, E> {
        Ok(Node::Value(toml::Value::String(v.to_string())))
    }

    fn visit_string<E>(self, v: String) -> Result<Node, E> {
        Ok(Node::Value(toml::Value::String(v)))
    }

    fn visit_i64<E>(self, v: i64) -> Result<Node, E> {
        Ok(Node::Value(toml::Value::Integer(v)))
    }

    fn visit_u64<E: serde::de::Error>(self, v: u64) -> Result<Node, E> {
        i64::try_from(v)
            .map(|v| Node::Value(toml::Value::Integer(v)))
            .map_err(|_| E::custom(format!("{v} is too large for a TOML integer")))
    }

    fn visit_f64<E>(self, v: f64) -> Result<Node, E> {
        Ok(Node::Value(toml::Value::Float(v)))
    }

    fn visit_bool<E>(self, v: bool) -> Result<Node, E> {
        Ok(Node::Value(toml::Value::Boolean(v)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_and_columns_count_from_one() {
        let b = b"ab\ncd\n\nxyz";
        assert_eq!(line_and_column(b, 0), (1, 1));
        assert_eq!(line_and_column(b, 1), (1, 2));
        assert_eq!(line_and_column(b, 3), (2, 1));
        assert_eq!(line_and_column(b, 6), (3, 1));
        assert_eq!(line_and_column(b, 9), (4, 3));
    }

    const TEXT: &str = "name = \"x\"\n\n[core]\nmax_warps = 64\nalu_latency = 4\n[l0]\nmshrs = 8\n";

    #[test]
    fn every_key_has_its_line() {
        let f = ConfigFile::parse(TEXT, "t.toml").unwrap();
        let lines: Vec<(&str, usize)> = f.lines.iter().map(|(k, &l)| (k.as_str(), l)).collect();
        assert_eq!(
            lines,
            [
                ("core", 3),
                ("core.alu_latency", 5),
                ("core.max_warps", 4),
                ("l0", 6),
                ("l0.mshrs", 7),
                ("name", 1)
            ]
        );
        assert_eq!(f.table["core"]["max_warps"].as_integer(), Some(64));
    }

    #[test]
    fn errors_name_the_line_of_the_key_they_name_first() {
        let f = ConfigFile::parse(TEXT, "t.toml").unwrap();
        let e = f.error("core.max_warps = 0: must be in 1..=128".into());
        assert_eq!(
            (e.source.as_str(), e.message.as_str()),
            ("t.toml:4", "core.max_warps = 0: must be in 1..=128")
        );
        // The section when no key of it is named; no line when nothing of
        // the file is.
        assert_eq!(f.error("l0: 3 ways".into()).source, "t.toml:6");
        assert_eq!(f.error("l0.mshrsx = 1".into()).source, "t.toml:6");
        assert_eq!(f.error("gpu.cores = 0".into()).source, "t.toml");
        assert_eq!(f.error("score.max_warps".into()).source, "t.toml");
    }

    #[test]
    fn syntax_errors_keep_toml_s_line() {
        let e = ConfigFile::parse("[core\nx = 1", "bad.toml").unwrap_err();
        assert_eq!(e.source, "bad.toml");
        assert!(e.message.contains("line 1"), "{e}");
    }

    /// A scratch folder for files that extend one another.
    fn folder(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("wasp-config-{name}-{}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn a_partial_file_patches_the_papers_machine() {
        let c = MachineConfig::parse("[l0]\nmshrs = 8\n", "p.toml").unwrap();
        let mut want = MachineConfig::paper();
        want.l0.as_mut().unwrap().mshrs = 8;
        assert_eq!(c, want);
        // Several sections, and a value of the top level.
        let c = MachineConfig::parse(
            "name = \"mine\"\n[core]\nalu_latency = 7\n[scheduler]\npolicy = \"baseline\"\n",
            "p.toml",
        )
        .unwrap();
        assert_eq!(
            (
                c.name.as_str(),
                c.core.alu_latency,
                c.scheduler.policy.to_string()
            ),
            ("mine", 7, "baseline".to_string())
        );
        assert_eq!(
            (c.core.max_warps, c.l1),
            (64, want.l1),
            "the rest is the paper's"
        );
    }

    #[test]
    fn whole_files_are_their_machine() {
        // The width-2 file has no L0: read whole, not onto the paper's.
        let w2 = MachineConfig::parse(super::super::PAPER_WIDTH2_TOML, "w2.toml").unwrap();
        assert!(w2.l0.is_none());
        assert_eq!(w2, MachineConfig::paper_width2());
        let p = MachineConfig::paper();
        assert_eq!(MachineConfig::parse(&p.to_toml(), "again.toml").unwrap(), p);
        let mut no_l0 = p.clone();
        no_l0.l0 = None;
        no_l0.scheduler.policy = wasp_rtl::policy::PolicySpec::Baseline;
        let c = MachineConfig::parse(&no_l0.to_toml(), "no-l0.toml").unwrap();
        assert_eq!(c, no_l0, "a whole file without [l0] has none");
    }

    #[test]
    fn extends_names_a_shipped_machine() {
        let c = MachineConfig::parse("extends = \"paper-width2\"\n[l1]\nmshrs = 8\n", "x").unwrap();
        let mut want = MachineConfig::paper_width2();
        want.l1.mshrs = 8;
        assert_eq!(c, want);
        let c = MachineConfig::parse("extends = \"paper\"\n", "x").unwrap();
        assert_eq!(c, MachineConfig::paper());
        // A section the base lacks must be whole.
        let e = MachineConfig::parse("extends = \"paper-width2\"\n\n[l0]\nmshrs = 8\n", "x.toml")
            .unwrap_err();
        assert_eq!(e.source, "x.toml:3");
        assert!(
            e.message.starts_with("l0: missing field `size_bytes`"),
            "{e}"
        );
    }

    #[test]
    fn extends_names_a_file_relative_to_the_one_that_names_it() {
        let d = folder("chain");
        std::fs::create_dir_all(d.join("sub")).unwrap();
        std::fs::write(
            d.join("sub/base.toml"),
            "extends = \"paper-width2\"\n[l1]\nmshrs = 12\n",
        )
        .unwrap();
        std::fs::write(
            d.join("top.toml"),
            "extends = \"sub/base.toml\"\n[core]\nmax_warps = 40\n",
        )
        .unwrap();
        let c = MachineConfig::load(&d.join("top.toml")).unwrap();
        let mut want = MachineConfig::paper_width2();
        want.l1.mshrs = 12;
        want.core.max_warps = 40;
        assert_eq!(c, want);
        // The base's own errors name the base.
        std::fs::write(d.join("sub/base.toml"), "[l1]\nmshrs = 0\n").unwrap();
        let e = MachineConfig::load(&d.join("top.toml")).unwrap_err();
        assert_eq!(e.source, format!("{}:2", d.join("sub/base.toml").display()));
        assert!(e.message.contains("l1.mshrs = 0"), "{e}");
        // A cycle is refused.
        std::fs::write(d.join("sub/base.toml"), "extends = \"../top.toml\"\n").unwrap();
        let e = MachineConfig::load(&d.join("top.toml")).unwrap_err();
        assert!(
            e.message.contains("more than 16 files extend one another"),
            "{e}"
        );
        std::fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    fn bad_extends_and_unknown_keys_name_the_line() {
        let e = MachineConfig::parse("\nextends = \"paper-width3\"\n", "x.toml").unwrap_err();
        assert_eq!(e.source, "x.toml:2");
        assert!(
            e.message
                .contains("no shipped machine of that name (paper, paper-width2)"),
            "{e}"
        );
        let e = MachineConfig::parse("extends = 2\n", "x.toml").unwrap_err();
        assert!(e.message.contains("as a string"), "{e}");
        let e = MachineConfig::parse("[l0]\nmshrs = 8\nmshr = 9\n", "x.toml").unwrap_err();
        assert_eq!(e.source, "x.toml:3");
        assert!(
            e.message.starts_with("l0.mshr: unknown field `mshr`"),
            "{e}"
        );
        let e = MachineConfig::parse("[nope]\nx = 1\n", "x.toml").unwrap_err();
        assert_eq!(e.source, "x.toml:1");
        assert!(e.message.contains("unknown field `nope`"), "{e}");
        // Values are checked after the merge, naming the line that set them.
        let e = MachineConfig::parse("[core]\n\nmax_warps = 0\n", "x.toml").unwrap_err();
        assert_eq!(e.source, "x.toml:3");
        assert!(
            e.message
                .starts_with("core.max_warps = 0: must be in 1..=128"),
            "{e}"
        );
        let e = MachineConfig::parse("[l0]\nmshrs = 32\n", "x.toml").unwrap_err();
        assert_eq!(e.source, "x.toml:2");
        assert!(e.message.contains("5-bit free-MSHR register"), "{e}");
    }
}
