//! A configuration file as text: its TOML table, and the line of every key
//! in it, so that an error about a field (an unknown key, a value of the
//! wrong type or out of range) names the line that set it.

use super::ConfigError;
use serde::de::{Deserializer, MapAccess, SeqAccess, Visitor};
use serde::Deserialize;
use std::collections::BTreeMap;
use std::fmt;
use toml::Spanned;

/// One parsed file.
#[derive(Debug)]
pub(super) struct ConfigFile {
    /// The file's name (or `<embedded ...>`), for errors.
    pub(super) source: String,
    /// Its table.
    pub(super) table: toml::Table,
    /// The line of every key, by dotted path (`core.max_warps`; a section's
    /// own line is its header's).
    lines: BTreeMap<String, usize>,
}

impl ConfigFile {
    /// Parse TOML `text`; `source` names it in errors.
    pub(super) fn parse(text: &str, source: &str) -> Result<Self, ConfigError> {
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
    pub(super) fn error(&self, message: String) -> ConfigError {
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
    pub(super) fn deserialize_error(&self, e: toml::de::Error) -> ConfigError {
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
}
