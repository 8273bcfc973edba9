//! Example charts to look at: `cargo test --bin wasp charts::examples --
//! --ignored` writes them to `wasp-chart-examples` in the temp directory.

use super::*;

const SCENES: [&str; 16] = [
    "sponza-atrium",
    "bistro-exterior-night",
    "san-miguel-courtyard",
    "crytek-sponza-lion",
    "amazon-lumberyard-bistro",
    "sun-temple",
    "emerald-square-city",
    "zero-day",
    "suntemple-interior-dusk",
    "fireplace-room",
    "living-room-2",
    "hairball",
    "powerplant-section-a",
    "rungholt",
    "lost-empire-minecraft",
    "vokselia-spawn",
];

fn dir() -> std::path::PathBuf {
    let dir = std::env::temp_dir().join("wasp-chart-examples");
    std::fs::create_dir_all(&dir).expect("examples dir");
    dir
}

fn wave(i: usize, k: usize) -> f64 {
    let x = (i * 7 + k * 3) % 11;
    0.006 * x as f64 - 0.02 + 0.01 * k as f64
}

#[test]
#[ignore = "writes example pictures to look at"]
fn examples() {
    let dir = dir();
    let mut categories: Vec<String> = SCENES.iter().map(|s| s.to_string()).collect();
    categories.push("mean 3D".into());
    categories.push("mean all".into());
    let series: Vec<Series> = ["WaSP", "Fullpriority"]
        .iter()
        .enumerate()
        .map(|(k, name)| {
            let values: Vec<f64> = (0..18).map(|i| wave(i, k)).collect();
            Series::full(*name, &values)
        })
        .collect();
    let bars = BarChart {
        subtitle: "shared-tile machine, 16 scenes".into(),
        series,
        paper: vec![
            PaperMark::all(Some(0), 0.039, "paper 3.9%"),
            PaperMark::all(Some(1), 0.012, "paper 1.2%"),
            PaperMark::at(Some(0), 16, 0.035, "paper 3.5%"),
            PaperMark::at(None, 17, 0.03, "paper 3.0%"),
        ],
        percent: true,
        reference: Some(0.0),
        separators: vec![16],
        highlight: vec![16, 17],
        ..BarChart::new(
            "Speedup over the baseline scheduler",
            "speedup",
            categories.clone(),
        )
    };
    draw_bars(&bars, &dir.join("bars.png")).expect("bars");
    draw_bars(&bars, &dir.join("bars.svg")).expect("bars svg");

    // Many series, 25 categories.
    let mut many = categories;
    many.extend((0..7).map(|i| format!("extra-scene-{i}")));
    let series: Vec<Series> = (0..5)
        .map(|k| {
            let values: Vec<f64> = (0..25).map(|i| 1.0 + wave(i, k) * 4.0).collect();
            Series::full(format!("policy {k}"), &values)
        })
        .collect();
    let ratios = BarChart {
        series,
        reference: Some(1.0),
        paper: vec![PaperMark::all(None, 1.1, "paper 1.10")],
        ..BarChart::new("L1 misses relative to the baseline", "ratio", many)
    };
    draw_bars(&ratios, &dir.join("bars-many.png")).expect("many bars");

    let x = vec![28.0, 32.0, 40.0, 48.0, 64.0, 96.0];
    let lines = LineChart {
        subtitle: "per-core-tile machine, mean of 16 scenes".into(),
        x_ticks: Some(x.iter().map(|v| format!("{v}")).collect()),
        series: vec![
            Series::full("baseline", &[0.0, 0.0, 0.0, 0.0, 0.0, 0.0]),
            Series::new(
                "WaSP",
                vec![
                    Some(0.021),
                    Some(0.039),
                    None,
                    Some(0.031),
                    Some(0.024),
                    Some(0.018),
                ],
            ),
            Series::full("Fullpriority", &[-0.02, 0.004, 0.011, 0.009, 0.006, 0.004]),
        ],
        paper: vec![
            PaperMark::at(Some(1), 1, 0.039, "paper 3.9%"),
            PaperMark::at(Some(2), 1, 0.001, "paper 0.1%"),
            PaperMark::all(None, 0.03, "paper mean 3.0%"),
        ],
        percent: true,
        reference: Some(0.0),
        ..LineChart::new(
            "Speedup by MSHR count",
            "MSHRs per core",
            "speedup over baseline",
            x,
        )
    };
    draw_lines(&lines, &dir.join("lines.png")).expect("lines");
    draw_lines(&lines, &dir.join("lines.svg")).expect("lines svg");
}

#[test]
#[ignore = "writes example pictures to look at"]
fn small_examples() {
    let dir = dir();
    let mut one = BarChart::new(
        "A single scene with a rather long title that keeps going",
        "speedup",
        vec!["amazon-lumberyard-bistro".into()],
    );
    one.series = vec![
        Series::full("WaSP", &[-0.021]),
        Series::full("Fullpriority", &[0.004]),
    ];
    one.paper = vec![PaperMark::at(Some(0), 0, 0.01, "paper 1.0%")];
    one.percent = true;
    one.reference = Some(0.0);
    draw_bars(&one, &dir.join("bars-one.png")).expect("one bar");
    let mut point = LineChart::new("One point", "MSHRs", "IPC", vec![32.0]);
    point.series = vec![Series::full("WaSP", &[0.7])];
    point.paper = vec![PaperMark::at(None, 0, 0.72, "paper 0.72")];
    draw_lines(&point, &dir.join("lines-one.png")).expect("one point");
}
