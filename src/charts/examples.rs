//! Example charts to look at: `cargo test --bin wasp charts::examples --
//! --ignored` writes one of each kind to `wasp-chart-examples` in the temp
//! directory.

use super::heatmap::tests::mshrs_by_warps;
use super::tornado::tests::gains;
use super::xy::tests::area;
use super::*;

#[test]
#[ignore = "writes example pictures to look at"]
fn examples() {
    let dir = std::env::temp_dir().join("wasp-chart-examples");
    std::fs::create_dir_all(&dir).expect("examples dir");
    let wave =
        |i: usize, k: usize| Some(0.006 * ((i * 7 + k * 3) % 11) as f64 - 0.02 + 0.01 * k as f64);
    let mut categories: Vec<String> = (0..9).map(|i| format!("scene-{i}-of-the-suite")).collect();
    categories.extend(["mean 3D", "mean 2D", "mean games"].map(String::from));
    let group = |label: &str, categories| CategoryGroup {
        label: label.into(),
        categories,
    };
    let series = |k: usize, key, name: &str, n: usize| Series {
        key,
        name: name.into(),
        values: (0..n).map(|i| wave(i, k)).collect(),
    };
    let mark = |series, category, value, label: &str| PaperMark {
        series,
        category,
        value,
        label: label.into(),
    };
    let bars = BarChart {
        title: "Speedup over the baseline scheduler".into(),
        subtitle: "shared-tile machine, 9 scenes".into(),
        y_label: "speedup".into(),
        categories,
        series: vec![
            series(0, Key::FullPriority, "fullpriority", 12),
            series(1, Key::Wasp, "wasp:0:3", 12),
        ],
        paper: vec![
            mark(Some(1), None, 0.039, "paper 3.9%"),
            mark(None, Some(11), 0.03, "paper 3.0%"),
        ],
        percent: true,
        reference: Some(0.0),
        separators: vec![5, 9],
        highlight: vec![9, 10, 11],
        groups: vec![group("3D", 0..5), group("2D", 5..9), group("means", 9..12)],
    };
    let lines = LineChart {
        title: "Sensitivity at width 4".into(),
        x_label: "warp slots per core".into(),
        y_label: "speedup".into(),
        x: vec![0.0, 1.0, 2.0, 3.0, 4.0],
        x_ticks: Some(["32", "48", "64", "96", "128"].map(String::from).to_vec()),
        series: vec![
            series(0, Key::Baseline, "baseline", 5),
            series(1, Key::Wasp, "wasp:0:3", 5),
        ],
        paper: vec![mark(Some(1), Some(1), 0.02, "paper: WaSP@48 +2%")],
        percent: true,
        reference: Some(0.0),
        ..LineChart::default()
    };
    for ext in ["png", "svg"] {
        let path = |name: &str| dir.join(format!("{name}.{ext}"));
        draw_bars(&bars, &path("bars")).expect("bars");
        draw_lines(&lines, &path("lines")).expect("lines");
        draw_xy(&area(), &path("xy")).expect("xy");
        draw_tornado(&gains(), &path("tornado")).expect("tornado");
        draw_heatmap(&mshrs_by_warps(), &path("heatmap")).expect("heat map");
    }
}
