//! The README's numbers against the documents they come from: every
//! figure the README's "Results" and "A first experiment" state is read
//! back from docs/results.md (its generated headline table and sentences)
//! and docs/reproduce.md (its measured "Time" table), so the README cannot
//! drift from them.

fn doc(path: &str) -> String {
    let text = std::fs::read_to_string(format!("{}/{path}", env!("CARGO_MANIFEST_DIR")))
        .unwrap_or_else(|e| panic!("{path}: {e}"));
    // One space between words, so that a phrase may be wrapped anywhere.
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// The token right after `phrase` in `text` (up to a space), trimmed of
/// punctuation.
fn after<'a>(text: &'a str, phrase: &str) -> &'a str {
    let i = text
        .find(phrase)
        .unwrap_or_else(|| panic!("`{phrase}` not found"))
        + phrase.len();
    text[i..]
        .split(' ')
        .next()
        .unwrap()
        .trim_end_matches([',', ';', ')', '.', '('])
}

/// The cells of the row whose first cell is `first` in a Markdown
/// table of `text`.
fn row(text: &str, first: &str) -> Vec<String> {
    let start = text
        .find(&format!("| {first} |"))
        .unwrap_or_else(|| panic!("row `{first}` not found"));
    let line = &text[start..];
    let end = line
        .find(" | |")
        .or_else(|| line.find("| |"))
        .unwrap_or(line.len());
    line[..end]
        .split('|')
        .map(|c| c.trim().to_string())
        .filter(|c| !c.is_empty())
        .collect()
}

/// `x` (e.g. "10.4" or "-11.7%") rounded to whole percent, sign dropped.
fn whole(x: &str) -> String {
    let v: f64 = x.trim_matches(['%', '+', '-']).parse().unwrap();
    format!("{:.0}", v)
}

#[test]
fn the_results_summary_is_the_headline_table() {
    let readme = doc("README.md");
    let results = doc("docs/results.md");
    // | WaSP speedup | paper | games | 3D | 2D | procedural | per-core ...
    let wasp = row(&results, "WaSP speedup");
    let (paper, d3, d2, proc_) = (&wasp[1], &wasp[3], &wasp[4], &wasp[5]);
    assert_eq!(after(&readme, "WaSP gains "), d2, "2D");
    assert_eq!(after(&readme, "on the 2D games and "), proc_, "procedural");
    assert_eq!(after(&readme, "on the procedural scenes but "), d3, "3D");
    assert_eq!(
        after(&readme, "on the 3D games (the paper: "),
        paper,
        "paper"
    );
    let ideal3 = after(&results, "ideal memory makes the baseline ");
    let ideal2 = after(&results, "faster on 3D scenes and ");
    assert_eq!(
        after(&readme, "ideal memory itself gains only "),
        format!("{}%", whole(ideal3))
    );
    assert_eq!(
        after(&readme, &format!("gains only {}% (", whole(ideal3))),
        format!("{}%", whole(ideal2))
    );
    // The latency change: the smallest and largest group's, rounded.
    let lat = row(&results, "Memory latency change (WaSP)");
    let groups: Vec<f64> = lat[3..6]
        .iter()
        .map(|c| c.trim_matches(['%', '+', '-']).parse().unwrap())
        .collect();
    let lo = groups.iter().cloned().fold(f64::INFINITY, f64::min);
    let hi = groups.iter().cloned().fold(0.0, f64::max);
    assert_eq!(
        after(&readme, "latency per warp falls "),
        format!("{lo:.0}-{hi:.0}%")
    );
    assert_eq!(
        after(&readme, &format!("falls {lo:.0}-{hi:.0}% (the paper: ")),
        format!("{}%", whole(&lat[1]))
    );
}

#[test]
fn the_first_experiments_times_are_the_measured_ones() {
    let readme = doc("README.md");
    let repro = doc("docs/reproduce.md");
    let quick = row(&repro, "`reproduce --quick` (quick map included)");
    // | run | tasks | simulations run | CPU time | wall time | faster |
    assert!(
        readme.contains(&format!("({} on two cores once the game data", quick[4])),
        "README's quick-look time is not {}",
        quick[4]
    );
    let full = row(
        &repro,
        "`reproduce` (the paper's study and the map on 13 scenes)",
    );
    let minutes = {
        let w: Vec<&str> = full[4].split(' ').collect();
        let (m, s): (f64, f64) = (w[0].parse().unwrap(), w[2].parse().unwrap());
        format!("{:.0} min", m + s / 60.0)
    };
    assert!(
        readme.contains(&format!(
            "({} simulations, {minutes} on two cores)",
            full[2]
        )),
        "README's full-run figures are not {} simulations, {minutes}",
        full[2]
    );
    assert!(readme.contains("the whole map on 13 of them"));
}
