//! The bound on every number of a trace: read at the bound, refused just
//! above it on every reading path.

use crate::{Instr, Trace, MAX_ALU_RUN, MAX_QUAD_INSTRS, MAX_REJECTED_RUN, MAX_TEX_BLOCKS};

/// A version-4 trace of one 64-pixel tile holding `body` (its lines).
fn one_tile(body: &str) -> String {
    format!("wasp-trace 4\nworkload w\nframe 64 64 tile 64\ntile 0 0\n{body}end\n")
}

#[test]
fn every_number_of_a_trace_is_bounded() {
    // At each bound the trace is read; just above it the reader names the
    // file and line, the token and the allowed range, on the plain and on
    // the multi-threaded path alike.
    let alu_max = format!("q 0 0 a{MAX_ALU_RUN}\n");
    let alu_over = format!("q 0 0 a{}\n", MAX_ALU_RUN + 1);
    let z_max = format!("q 0 0 a1\nz {MAX_REJECTED_RUN}\n");
    let z_over = format!("z {}\n", MAX_REJECTED_RUN + 1);
    let blocks = |n: usize| {
        (1..=n)
            .map(|b| format!("{b:x}"))
            .collect::<Vec<_>>()
            .join(",")
    };
    let tex_max = format!("q 0 0 t{}\n", blocks(MAX_TEX_BLOCKS));
    let tex_over = format!("q 0 0 T{}\n", blocks(MAX_TEX_BLOCKS + 1));
    for ok in [&alu_max, &z_max, &tex_max] {
        let text = one_tile(ok);
        Trace::parse(&text, "b.trace").unwrap_or_else(|e| panic!("{ok}: {e}"));
    }
    // A program of exactly the bound: 15 full ALU runs, a texture
    // instruction after each, and a last run to fill it up.
    let runs = MAX_QUAD_INSTRS / MAX_ALU_RUN - 1;
    let full = (0..runs)
        .map(|_| format!("a{MAX_ALU_RUN} t1"))
        .collect::<Vec<_>>()
        .join(" ");
    let last = MAX_QUAD_INSTRS - runs * (MAX_ALU_RUN + 1);
    let at_bound = format!("q 0 0 {full} a{last}");
    // One texture instruction more; or one ALU instruction more, found
    // in the middle of the line.
    let prog_over = format!("{at_bound} t2\n");
    let prog_over_alu = format!("q 0 0 a1 t2 {full} a{last}\n");
    let t = Trace::parse(&one_tile(&format!("{at_bound}\n")), "b.trace").unwrap();
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
    let cases: [(&str, String); 5] = [
        (
            &alu_over,
            format!(
                "ALU run `{}` out of range (expected at most {MAX_ALU_RUN})",
                MAX_ALU_RUN + 1
            ),
        ),
        (
            &z_over,
            format!(
                "rejected quads `{}` out of range (expected at most {MAX_REJECTED_RUN})",
                MAX_REJECTED_RUN + 1
            ),
        ),
        (
            &tex_over,
            format!(
                "texture instruction with {} blocks (expected at most {MAX_TEX_BLOCKS})",
                MAX_TEX_BLOCKS + 1
            ),
        ),
        (
            &prog_over,
            format!(
                "quad program of {} instructions (expected 1 to {MAX_QUAD_INSTRS}",
                MAX_QUAD_INSTRS + 1
            ),
        ),
        (
            &prog_over_alu,
            format!(
                "quad program of {} instructions (expected 1 to {MAX_QUAD_INSTRS}",
                MAX_QUAD_INSTRS + 2
            ),
        ),
    ];
    for (body, want) in cases {
        let text = one_tile(body);
        for (threads, min) in [(1, usize::MAX), (3, 0)] {
            let e = Trace::parse_with(&text, "b.trace", threads, min)
                .unwrap_err()
                .to_string();
            assert!(e.starts_with("b.trace:5: "), "{e}");
            assert!(e.contains(&want), "{e}\nwanted {want}");
        }
    }
}
