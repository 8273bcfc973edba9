//! The bound on every number of a trace: read at the bound, refused just
//! above it on every reading path.

use crate::{Instr, Trace, MAX_ALU_RUN, MAX_QUAD_INSTRS, MAX_REJECTED_RUN, MAX_TEX_BLOCKS};

/// A version-4 trace of one 64-pixel tile holding `body` (its lines).
fn one_tile(body: &str) -> String {
    format!("wasp-trace 4\nworkload w\nframe 64 64 tile 64\ntile 0 0\n{body}end\n")
}

/// Block numbers 1 to `n` in hex, joined by commas.
fn blocks(n: usize) -> String {
    (1..=n)
        .map(|b| format!("{b:x}"))
        .collect::<Vec<_>>()
        .join(",")
}

/// A quad program of exactly the bound, as (its full ALU runs, each
/// followed by a texture instruction; its last ALU run): 15 full runs and
/// a last run to fill it up.
fn program_at_bound() -> (String, u32) {
    let runs = MAX_QUAD_INSTRS / MAX_ALU_RUN - 1;
    let full = (0..runs)
        .map(|_| format!("a{MAX_ALU_RUN} t1"))
        .collect::<Vec<_>>()
        .join(" ");
    (full, MAX_QUAD_INSTRS - runs * (MAX_ALU_RUN + 1))
}

#[test]
fn every_number_of_a_trace_is_read_at_its_bound() {
    let alu_max = format!("q 0 0 a{MAX_ALU_RUN}\n");
    let z_max = format!("q 0 0 a1\nz {MAX_REJECTED_RUN}\n");
    let tex_max = format!("q 0 0 t{}\n", blocks(MAX_TEX_BLOCKS));
    for ok in [&alu_max, &z_max, &tex_max] {
        let text = one_tile(ok);
        Trace::parse(&text, "b.trace").unwrap_or_else(|e| panic!("{ok}: {e}"));
    }
    let (full, last) = program_at_bound();
    let t = Trace::parse(&one_tile(&format!("q 0 0 {full} a{last}\n")), "b.trace").unwrap();
    let instrs: u64 = t.tiles()[0]
        .quads()
        .map(|q| {
            q.instrs()
                .map(|i| match i {
                    Instr::Alu(n) => u64::from(n),
                    _ => 1,
                })
                .sum::<u64>()
        })
        .sum();
    assert_eq!(instrs, u64::from(MAX_QUAD_INSTRS));
}

#[test]
fn every_number_of_a_trace_is_refused_just_above_its_bound() {
    // Just above each bound the reader names the file and line, the token
    // and the allowed range, on the plain and on the multi-threaded path
    // alike.
    let (full, last) = program_at_bound();
    // The program at the bound and one texture instruction more; or one
    // ALU instruction more, found in the middle of the line.
    let prog_over = format!("q 0 0 {full} a{last} t2\n");
    let prog_over_alu = format!("q 0 0 a1 t2 {full} a{last}\n");
    let cases: [(String, String); 5] = [
        (
            format!("q 0 0 a{}\n", MAX_ALU_RUN + 1),
            format!(
                "ALU run `{}` out of range (expected at most {MAX_ALU_RUN})",
                MAX_ALU_RUN + 1
            ),
        ),
        (
            format!("z {}\n", MAX_REJECTED_RUN + 1),
            format!(
                "rejected quads `{}` out of range (expected at most {MAX_REJECTED_RUN})",
                MAX_REJECTED_RUN + 1
            ),
        ),
        (
            format!("q 0 0 T{}\n", blocks(MAX_TEX_BLOCKS + 1)),
            format!(
                "texture instruction with {} blocks (expected at most {MAX_TEX_BLOCKS})",
                MAX_TEX_BLOCKS + 1
            ),
        ),
        (
            prog_over,
            format!(
                "quad program of {} instructions (expected 1 to {MAX_QUAD_INSTRS}",
                MAX_QUAD_INSTRS + 1
            ),
        ),
        (
            prog_over_alu,
            format!(
                "quad program of {} instructions (expected 1 to {MAX_QUAD_INSTRS}",
                MAX_QUAD_INSTRS + 2
            ),
        ),
    ];
    for (body, want) in cases {
        let text = one_tile(&body);
        for (threads, min) in [(1, usize::MAX), (3, 0)] {
            let e = Trace::parse_with(&text, "b.trace", threads, min)
                .unwrap_err()
                .to_string();
            assert!(e.starts_with("b.trace:5: "), "{e}");
            assert!(e.contains(&want), "{e}\nwanted {want}");
        }
    }
}
