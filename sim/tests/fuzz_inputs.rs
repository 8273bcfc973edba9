//! A standing fuzz suite over the two inputs a user hands the model: the
//! machine configuration (`MachineConfig::parse`) and the trace
//! (`Trace::parse_bytes`). Each target mutates valid inputs (byte flips,
//! insertions and deletions; random values in random fields or tokens;
//! random keys and lines) and asserts that every input gives `Ok` or an
//! `Err` with a message, never a panic; a configuration that parses builds
//! the GPU and its memory system and runs a tiny trace for a few thousand
//! cycles, and a trace that parses is written and read back unchanged and
//! runs a few thousand cycles on the paper's machine. Every mutated trace is
//! also read in four pieces by the multi-threaded reader, which must give
//! the one-thread reader's trace or error.
//!
//! The case budget is fixed (`CASES` in release, `DEBUG_CASES` in a debug
//! build, so `cargo test` in CI stays fast) and the random seed too, so a
//! run is reproducible. `WASP_FUZZ_CASES=N` sets the cases of each target
//! and `WASP_FUZZ_SEED=S` the seed, for longer campaigns:
//!
//! ```text
//! WASP_FUZZ_CASES=200000 WASP_FUZZ_SEED=7 cargo test --release -p wasp-sim --test fuzz_inputs -- --nocapture
//! ```

use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestCaseError, TestRng, TestRunner};
use std::path::PathBuf;
use wasp_sim::config::MachineConfig;
use wasp_sim::gpu::Gpu;
use wasp_sim::synth::{generate, GenParams};
use wasp_sim::trace::Trace;

/// Cases per target in a release build.
const CASES: u32 = 2000;
/// Cases per target in a debug build (`cargo test` without `--release`).
const DEBUG_CASES: u32 = 1000;
/// Cycles a configuration or trace that parses is run for.
const RUN_CYCLES: u64 = 3000;

fn cases() -> u32 {
    match std::env::var("WASP_FUZZ_CASES") {
        Ok(v) => v
            .parse()
            .unwrap_or_else(|_| panic!("WASP_FUZZ_CASES={v:?} (expected a whole number)")),
        Err(_) if cfg!(debug_assertions) => DEBUG_CASES,
        Err(_) => CASES,
    }
}

fn runner() -> TestRunner {
    let seed: u64 = match std::env::var("WASP_FUZZ_SEED") {
        Ok(v) => v
            .parse()
            .unwrap_or_else(|_| panic!("WASP_FUZZ_SEED={v:?} (expected a whole number)")),
        Err(_) => 0,
    };
    let mut bytes = [0u8; 32];
    bytes[..8].copy_from_slice(&seed.to_le_bytes());
    TestRunner::new_with_rng(
        Config {
            cases: cases(),
            failure_persistence: None,
            ..Config::default()
        },
        TestRng::from_seed(RngAlgorithm::ChaCha, &bytes),
    )
}

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// Numbers at the edges of the ranges the inputs use.
const EDGES: &[i64] = &[
    0,
    1,
    -1,
    2,
    3,
    7,
    8,
    31,
    32,
    63,
    64,
    65,
    255,
    256,
    511,
    512,
    513,
    1023,
    1024,
    1025,
    4095,
    4096,
    4097,
    65535,
    65536,
    65537,
    4_194_304,
    4_194_305,
    i32::MAX as i64,
    1 << 31,
    u32::MAX as i64,
    1 << 32,
    1 << 40,
    i64::MAX,
    i64::MIN,
];

/// One mutation: what, and three random numbers it picks with.
type Mutation = (u8, u64, u64, i64);

fn mutations() -> impl Strategy<Value = Vec<Mutation>> {
    proptest::collection::vec(
        (any::<u8>(), any::<u64>(), any::<u64>(), any::<i64>()),
        1..5,
    )
}

/// A number: mostly an edge, sometimes small, sometimes anything.
fn number(a: u64, v: i64) -> i64 {
    match a % 4 {
        0 | 1 => EDGES[(v.unsigned_abs() % EDGES.len() as u64) as usize],
        2 => v % 100,
        _ => v,
    }
}

fn byte_mutation(bytes: &mut Vec<u8>, kind: u8, a: u64, b: u64) {
    let n = bytes.len() as u64;
    match kind % 3 {
        0 if n > 0 => bytes[(a % n) as usize] ^= 1 << (b % 8),
        1 => {
            let pool = b"0123456789-+.=[]\"\n #,x_aqtTz\t\r\x00\xff";
            bytes.insert(
                (a % (n + 1)) as usize,
                pool[(b % pool.len() as u64) as usize],
            );
        }
        _ if n > 0 => {
            let at = (a % n) as usize;
            let len = (b % 8 + 1) as usize;
            bytes.drain(at..(at + len).min(bytes.len()));
        }
        _ => {}
    }
}

// ---------------------------------------------------------------- configs

/// The paths of the leaves and of the tables of a TOML document.
fn paths(
    t: &toml::Table,
    at: &mut Vec<String>,
    leaves: &mut Vec<Vec<String>>,
    tables: &mut Vec<Vec<String>>,
) {
    tables.push(at.clone());
    for (k, v) in t {
        at.push(k.clone());
        match v {
            toml::Value::Table(sub) => paths(sub, at, leaves, tables),
            _ => leaves.push(at.clone()),
        }
        at.pop();
    }
}

fn table_at<'a>(t: &'a mut toml::Table, path: &[String]) -> &'a mut toml::Table {
    let mut t = t;
    for k in path {
        t = match t.get_mut(k) {
            Some(toml::Value::Table(sub)) => sub,
            _ => unreachable!("a table path"),
        };
    }
    t
}

/// A random value for a leaf that held `old`.
fn value_for(old: &toml::Value, a: u64, b: u64, v: i64) -> toml::Value {
    let floats = [
        0.0,
        -0.0,
        1e-12,
        0.5,
        1.0,
        1.5,
        1e9,
        1e300,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NAN,
        -1.0,
    ];
    match (a / 4) % 8 {
        // A value of the same type.
        0..=4 => match old {
            toml::Value::Integer(_) => toml::Value::Integer(number(a, v)),
            toml::Value::Float(f) => match b % 3 {
                0 => toml::Value::Float(floats[(v.unsigned_abs() % floats.len() as u64) as usize]),
                1 => toml::Value::Float(f * (v % 1000) as f64 / 10.0),
                _ => toml::Value::Float(number(a, v) as f64),
            },
            toml::Value::Boolean(x) => toml::Value::Boolean(!x),
            toml::Value::String(s) => {
                let tails = [
                    ":0",
                    ":1",
                    ":3",
                    ":99999999999",
                    ":-1",
                    ":",
                    "",
                    "x",
                    ",",
                    ":0.5",
                    ":65",
                ];
                let mut s = s.clone();
                match b % 3 {
                    0 => s.truncate((v.unsigned_abs() % (s.len() as u64 + 1)) as usize),
                    1 => {
                        if let Some(c) = s.find(':') {
                            s.truncate(c);
                        }
                        s.push_str(tails[(v.unsigned_abs() % tails.len() as u64) as usize]);
                    }
                    _ => s.push_str(tails[(v.unsigned_abs() % tails.len() as u64) as usize]),
                }
                toml::Value::String(s)
            }
            toml::Value::Array(xs) => {
                let mut xs = xs.clone();
                if !xs.is_empty() && b.is_multiple_of(2) {
                    xs.remove((v.unsigned_abs() % xs.len() as u64) as usize);
                } else if let Some(x) = xs.first().cloned() {
                    xs.push(value_for(&x, a / 32, b / 2, v));
                }
                toml::Value::Array(xs)
            }
            other => other.clone(),
        },
        // A value of another type.
        5 => toml::Value::String(format!("{}", number(a, v))),
        6 => toml::Value::Float(number(a, v) as f64 + 0.5),
        _ => match b % 3 {
            0 => toml::Value::Boolean(v % 2 == 0),
            1 => toml::Value::Integer(number(a, v)),
            _ => toml::Value::Array(vec![]),
        },
    }
}

fn config_mutation(doc: &mut toml::Table, (kind, a, b, v): Mutation) {
    let (mut leaves, mut tables) = (Vec::new(), Vec::new());
    paths(doc, &mut Vec::new(), &mut leaves, &mut tables);
    match kind % 8 {
        // A random value in a random field (mostly numbers).
        0..=4 if !leaves.is_empty() => {
            let path = &leaves[(a % leaves.len() as u64) as usize];
            let (key, table) = path.split_last().expect("a leaf has a key");
            let t = table_at(doc, table);
            let new = value_for(&t[key], b, a, v);
            t.insert(key.clone(), new);
        }
        // A random key.
        5 => {
            let table = tables[(a % tables.len() as u64) as usize].clone();
            let names = [
                "x", "cores", "size", "ways", "policy", "banks", "latency", "mem", "l2",
            ];
            let name = names[(b % names.len() as u64) as usize].to_string();
            let t = table_at(doc, &table);
            let new = match v % 3 {
                0 => toml::Value::Table(toml::Table::new()),
                _ => toml::Value::Integer(number(b, v)),
            };
            t.insert(name, new);
        }
        // A key removed.
        6 if !leaves.is_empty() => {
            let path = &leaves[(a % leaves.len() as u64) as usize];
            let (key, table) = path.split_last().expect("a leaf has a key");
            table_at(doc, table).remove(key);
        }
        // A table removed.
        _ if tables.len() > 1 => {
            let path = &tables[1 + (a % (tables.len() as u64 - 1)) as usize];
            let (key, table) = path.split_last().expect("not the root");
            table_at(doc, table).remove(key);
        }
        _ => {}
    }
}

/// A small trace of 64-pixel tiles: the paper machine's tile size.
fn small_trace(seed: u64) -> Trace {
    generate(&GenParams {
        frame_w: 128,
        frame_h: 64,
        coverage: 0.5,
        seed,
        ..GenParams::default()
    })
    .expect("small synthetic trace")
}

/// Builds the GPU (its memory system included) for `cfg` and `trace` and
/// runs it for at most [`RUN_CYCLES`] cycles; errors are fine, panics not.
fn run_briefly(cfg: &MachineConfig, trace: &Trace) -> Result<(), String> {
    let mut gpu = Gpu::new(cfg, trace).map_err(|e| e.to_string())?;
    while !gpu.done() && gpu.cycle() < RUN_CYCLES {
        gpu.step().map_err(|e| e.to_string())?;
    }
    Ok(())
}

#[test]
fn mutated_configs_parse_or_fail_cleanly() {
    let text = std::fs::read_to_string(repo().join("configs/paper.toml")).unwrap();
    let doc: toml::Table = toml::from_str(&text).unwrap();
    let trace = small_trace(3);
    // Half the cases mutate the text's bytes, half the document's values.
    let strategy = (any::<bool>(), mutations());
    let stats = std::cell::Cell::new([0usize; 4]);
    let count = |i: usize| {
        let mut s = stats.get();
        s[i] += 1;
        stats.set(s);
    };
    let result = runner().run(&strategy, |(bytes, muts)| {
        let mutated = if bytes {
            let mut b = text.clone().into_bytes();
            for &(kind, a, bb, _) in &muts {
                byte_mutation(&mut b, kind, a, bb);
            }
            String::from_utf8_lossy(&b).into_owned()
        } else {
            let mut d = doc.clone();
            for &m in &muts {
                config_mutation(&mut d, m);
            }
            toml::to_string(&d).unwrap()
        };
        count(0);
        match MachineConfig::parse(&mutated, "fuzz.toml") {
            Ok(cfg) => {
                count(1);
                if run_briefly(&cfg, &trace).is_err() {
                    count(3);
                }
            }
            Err(e) => {
                count(2);
                let m = e.to_string();
                prop_assert!(
                    m.starts_with("fuzz.toml") && m.len() > "fuzz.toml: ".len(),
                    "{m}"
                );
            }
        }
        Ok(())
    });
    let [n, ok, refused, run_err] = stats.get();
    eprintln!(
        "fuzz: config {n} cases, {ok} parsed ({run_err} of them refused by the GPU build or \
         run), {refused} refused"
    );
    if let Err(e) = result {
        panic!("{e}");
    }
    assert!(ok > 0 && refused > 0, "the mutations reach both outcomes");
}

// ----------------------------------------------------------------- traces

fn trace_seeds() -> Vec<String> {
    let mut seeds: Vec<String> = ["tiny", "overdraw", "synthetic-small"]
        .iter()
        .map(|n| std::fs::read_to_string(repo().join(format!("tests/traces/{n}.trace"))).unwrap())
        .collect();
    seeds.push(small_trace(1).to_text());
    seeds.push(
        "wasp-trace 4\n# note\nworkload hand\nframe 100 64 tile 64\ntile 0 0\nz 3\n\
         q 0 0 a3 t1a40,1a41 a2 T1a40,1b20\nq 1 0 a5\nz 12\nq 0 0 a2 t2b00\nz 3\nend\n\
         tile 1 0\nq 0 0 T1a48 a4\nend\n"
            .to_string(),
    );
    seeds
}

const LINES: &[&str] = &[
    "z 5",
    "end",
    "tile 0 0",
    "tile 1 0",
    "q 0 0 a1",
    "q 31 31 t1 a2",
    "wasp-trace 4",
    "frame 64 64 tile 64",
    "workload w",
    "# c",
    "",
    "q 0 0 T1,2,3",
];

fn trace_mutation(text: &str, (kind, a, b, v): Mutation) -> String {
    match kind % 6 {
        // Bytes.
        0 | 1 => {
            let mut bytes = text.as_bytes().to_vec();
            byte_mutation(&mut bytes, kind / 6, a, b);
            String::from_utf8_lossy(&bytes).into_owned()
        }
        // A number in a token replaced.
        2 | 3 => {
            let spans: Vec<(usize, usize)> = {
                let bs = text.as_bytes();
                let mut out = Vec::new();
                let mut i = 0;
                while i < bs.len() {
                    if bs[i].is_ascii_hexdigit() {
                        let j = (i..bs.len())
                            .find(|&j| !bs[j].is_ascii_hexdigit())
                            .unwrap_or(bs.len());
                        out.push((i, j));
                        i = j;
                    } else {
                        i += 1;
                    }
                }
                out
            };
            if spans.is_empty() {
                return text.to_string();
            }
            let (i, j) = spans[(a % spans.len() as u64) as usize];
            let n = number(b, v);
            let new = if b.is_multiple_of(5) {
                format!("{:x}", n.unsigned_abs())
            } else {
                n.to_string()
            };
            format!("{}{}{}", &text[..i], new, &text[j..])
        }
        // A line inserted, deleted or repeated.
        _ => {
            let mut lines: Vec<&str> = text.split('\n').collect();
            let at = (a % lines.len() as u64) as usize;
            match b % 3 {
                0 => lines.insert(at, LINES[(v.unsigned_abs() % LINES.len() as u64) as usize]),
                1 => {
                    lines.remove(at);
                }
                _ => lines.insert(at, lines[at]),
            }
            lines.join("\n")
        }
    }
}

#[test]
fn mutated_traces_parse_or_fail_cleanly() {
    let seeds = trace_seeds();
    let cfg = MachineConfig::paper();
    let strategy = (0..seeds.len(), mutations());
    let stats = std::cell::Cell::new([0usize; 4]);
    let count = |i: usize| {
        let mut s = stats.get();
        s[i] += 1;
        stats.set(s);
    };
    let result = runner().run(&strategy, |(seed, muts)| {
        let mut text = seeds[seed].clone();
        for &m in &muts {
            text = trace_mutation(&text, m);
        }
        count(0);
        // The multi-threaded reader agrees with the one-thread reader on
        // every input, valid or not.
        if let Ok(utf8) = std::str::from_utf8(text.as_bytes()) {
            let one = Trace::parse_pieces(utf8, "fuzz.trace", 1);
            let four = Trace::parse_pieces(utf8, "fuzz.trace", 4);
            prop_assert_eq!(
                one.as_ref().map_err(|e| e.to_string()),
                four.as_ref().map_err(|e| e.to_string())
            );
        }
        match Trace::parse_bytes(text.as_bytes(), "fuzz.trace") {
            Ok(t) => {
                count(1);
                let back = Trace::parse(&t.to_text(), "back.trace").map_err(|e| {
                    TestCaseError::fail(format!("written trace not read back: {e}"))
                })?;
                prop_assert_eq!(&back, &t);
                if t.header().tile == cfg.gpu.tile_size {
                    count(3);
                    run_briefly(&cfg, &t).map_err(TestCaseError::fail)?;
                }
            }
            Err(e) => {
                count(2);
                let m = e.to_string();
                prop_assert!(
                    m.starts_with("fuzz.trace:") && m.len() > "fuzz.trace:1: ".len(),
                    "{m}"
                );
            }
        }
        Ok(())
    });
    let [n, ok, refused, ran] = stats.get();
    eprintln!("fuzz: trace {n} cases, {ok} parsed ({ran} of them run), {refused} refused");
    if let Err(e) = result {
        panic!("{e}");
    }
    assert!(ok > 0 && refused > 0, "the mutations reach both outcomes");
}
