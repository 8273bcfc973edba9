//! Property suites over whole traces: exact round trips, and arbitrary or
//! mutated input that never panics and reads alike in pieces.

use crate::memo::Memo;
use crate::testkit::*;
use crate::Trace;
use proptest::prelude::*;

/// Mutations of a valid trace text: some keep it valid, most break it.
fn mutate(text: &str, ops: &[(u8, usize, usize, String)]) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    for (kind, a, b, s) in ops {
        if lines.is_empty() {
            break;
        }
        let i = a % lines.len();
        let j = b % lines.len();
        match kind % 8 {
            0 => {
                lines.remove(i);
            }
            1 => {
                let l = lines[i].clone();
                lines.insert(j, l);
            }
            2 => lines.swap(i, j),
            3 => lines.insert(i, s.clone()),
            4 => {
                let l = &mut lines[i];
                let mut cut = (*b).min(l.len());
                while !l.is_char_boundary(cut) {
                    cut -= 1;
                }
                l.insert_str(cut, s);
            }
            5 => {
                let l = &mut lines[i];
                let mut cut = (*b).min(l.len());
                while !l.is_char_boundary(cut) {
                    cut -= 1;
                }
                l.truncate(cut);
            }
            6 => {
                // Change one digit.
                let l = &mut lines[i];
                if let Some(p) = l
                    .char_indices()
                    .filter(|(_, c)| c.is_ascii_digit())
                    .map(|(p, _)| p)
                    .nth(*b % 4)
                {
                    l.replace_range(p..p + 1, &((b % 10).to_string()));
                }
            }
            _ => lines[i] = lines[i].replace(' ', s),
        }
    }
    lines.join("\n")
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    #[test]
    fn round_trip_is_exact(t in arb_trace()) {
        let text = t.to_text();
        let back = Trace::parse(&text, "rt").unwrap();
        prop_assert_eq!(&back, &t);
        prop_assert_eq!(back.to_text(), text);
    }

    #[test]
    fn scanline_traces_read_the_same_as_version_1(t in arb_trace_v(true)) {
        let text = t.to_text().replacen("wasp-trace 4\n", "wasp-trace 1\n", 1);
        prop_assert_eq!(Trace::parse(&text, "v1").unwrap(), t);
    }

    #[test]
    fn random_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..400)) {
        let _ = Trace::parse_bytes(&bytes, "r");
        let mut prefixed = HEAD.as_bytes().to_vec();
        prefixed.extend_from_slice(&bytes);
        let _ = Trace::parse_bytes(&prefixed, "r");
        let mut prefixed = HEAD3.as_bytes().to_vec();
        prefixed.extend_from_slice(&bytes);
        let _ = Trace::parse_bytes(&prefixed, "r");
    }

    #[test]
    fn random_token_soup_never_panics(
        toks in proptest::collection::vec(prop_oneof![
            Just("tile".to_string()), Just("q".to_string()), Just("end".to_string()),
            Just("workload".to_string()), Just("frame".to_string()), Just("\n".to_string()),
            Just("#".to_string()), Just("a1".to_string()), Just("a0".to_string()),
            Just("t1,2".to_string()), Just("tffffffffffffffff".to_string()),
            Just("4294967296".to_string()), Just("t".to_string()), Just(",".to_string()),
            Just("z".to_string()), Just("\nz".to_string()), Just("2147483648".to_string()),
            (0u32..40).prop_map(|n| n.to_string()), "[ -~]{0,4}",
        ], 0..80),
        v3 in any::<bool>(),
    ) {
        let head = if v3 { HEAD3 } else { HEAD };
        let text = format!("{head}{}", toks.join(" "));
        if let Ok(t) = Trace::parse(&text, "soup") {
            prop_assert_eq!(Trace::parse(&t.to_text(), "soup2").unwrap(), t);
        }
    }

    #[test]
    fn mutated_traces_never_panic(
        t in arb_trace(),
        ops in proptest::collection::vec((any::<u8>(), any::<usize>(), 0usize..40, "[ -~\t\r]{0,6}"), 1..6),
    ) {
        let text = mutate(&t.to_text(), &ops);
        match Trace::parse(&text, "m") {
            Ok(t2) => prop_assert_eq!(Trace::parse(&t2.to_text(), "m2").unwrap(), t2),
            Err(e) => {
                let msg = e.to_string();
                prop_assert!(msg.starts_with("m:"), "{}", msg);
                prop_assert!(msg.contains("(expected "), "{}", msg);
            }
        }
    }

    #[test]
    fn reading_in_pieces_is_reading_on_one_thread(
        t in arb_trace(),
        pieces in 2usize..6,
        ops in proptest::collection::vec((any::<u8>(), any::<usize>(), 0usize..40, "[ -~\t\r]{0,6}"), 0..4),
    ) {
        let text = if ops.is_empty() { t.to_text() } else { mutate(&t.to_text(), &ops) };
        let one = Trace::parse_with(&text, "m", 1, usize::MAX);
        prop_assert_eq!(Trace::parse_with(&text, "m", pieces, 0), one);
    }

    #[test]
    fn one_tile_traces_appended_give_the_trace_back(t in arb_trace()) {
        // What the front end does: each tile built alone, then appended.
        let mut b = Trace::builder(t.header().clone()).unwrap();
        for tile in t.tiles() {
            let part = Trace {
                header: t.header().clone(),
                tiles: vec![tile.clone()],
                frame_starts: vec![0],
                stats: Memo::default(),
            };
            let part = Trace::parse(&part.to_text(), "part").unwrap();
            b.append(part).unwrap();
        }
        let back = b.finish().unwrap();
        prop_assert_eq!(back.rejected_count(), t.rejected_count());
        prop_assert_eq!(&back, &t);
    }
}
