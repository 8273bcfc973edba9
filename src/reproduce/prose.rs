//! The words of REPORT.md's comparisons, chosen from the numbers: which of
//! two values is larger (within a stated tolerance), whether ours agree
//! with the paper's, and how numbers print (changes with their sign,
//! shares without).
//!
//! It depends on no other module of the report: the figures, the tables
//! and the map's sections print their numbers with it.
//!
//! Every sentence of the report that compares two numbers takes its verb
//! from here, so that it says what the data shows, and where the data
//! disagrees with the paper it says so, whichever way a run comes out.

/// How one value stands against another.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Relation {
    /// Larger by more than the tolerance.
    Above,
    /// Smaller by more than the tolerance.
    Below,
    /// Within the tolerance.
    Same,
}

/// Tolerance of changes and speedups (fractions): half a percentage point.
pub const CHANGE_TOL: f64 = 0.005;

/// Tolerance of shares of time (fractions): half a percentage point.
pub const SHARE_TOL: f64 = 0.005;

/// How `a` stands against `b`, within `tol`.
pub fn relation(a: f64, b: f64, tol: f64) -> Relation {
    if a > b + tol {
        Relation::Above
    } else if a < b - tol {
        Relation::Below
    } else {
        Relation::Same
    }
}

/// A change or speedup as text, with its sign (`+3.9%`; `-` for none),
/// as the figures print them.
pub fn pct(v: Option<f64>) -> String {
    v.map_or("-".into(), |x| format!("{:+.1}%", 100.0 * x))
}

/// A share (of time, of launches) as text, without a sign (`6.3%`).
pub fn share(v: Option<f64>) -> String {
    v.map_or("-".into(), |x| format!("{:.1}%", 100.0 * x))
}

/// A share as a whole percent without a sign (`6%`), as the map's tables
/// print them.
pub fn whole_share(v: Option<f64>) -> String {
    v.map_or("-".into(), |x| format!("{:.0}%", 100.0 * x))
}

/// A plain number with one decimal (`-` for none).
pub fn num(v: Option<f64>) -> String {
    v.map_or("-".into(), |x| format!("{x:.1}"))
}

/// How a mean speedup stands against the paper's `paper` (a positive
/// gain): "slows ... down" when ours is negative, else above, below or
/// about the paper's.
pub fn speedup_against_paper(ours: f64, paper: f64) -> String {
    let p = pct(Some(paper));
    if ours < -CHANGE_TOL {
        return format!("a slowdown, where the paper measures a gain of {p}");
    }
    match relation(ours, paper, CHANGE_TOL) {
        Relation::Above => format!("above the paper's {p}"),
        Relation::Below => format!("below the paper's {p}"),
        Relation::Same => format!("about the paper's {p}"),
    }
}

/// A change against the paper's `paper` change of the same statistic:
/// whether it goes the paper's way ("falls, as in the paper (-9.0%)"),
/// the other way, or barely moves.
pub fn change_against_paper(what: &str, ours: f64, paper: f64, tol: f64) -> String {
    let p = pct(Some(paper));
    let o = pct(Some(ours));
    let moved = |v: f64| match relation(v, 0.0, tol) {
        Relation::Above => "rises",
        Relation::Below => "falls",
        Relation::Same => "barely changes",
    };
    let (m, pm) = (moved(ours), moved(paper));
    if m == pm {
        format!("{what} {m} ({o}), as in the paper ({p})")
    } else {
        format!("{what} {m} ({o}), where the paper's {pm} ({p})")
    }
}

/// "ahead of" or "behind" for a lead in positions (positive: ahead).
pub fn ahead_or_behind(lead: f64) -> &'static str {
    if lead >= 0.0 {
        "ahead of"
    } else {
        "behind"
    }
}

/// A lead in positions as "N positions ahead of" / "N positions behind".
pub fn lead_text(lead: Option<f64>) -> String {
    match lead {
        Some(v) => format!("{:.1} positions {}", v.abs(), ahead_or_behind(v)),
        None => "- positions ahead of".into(),
    }
}

/// "faster" / "slower" by a speedup's sign, with its magnitude
/// ("4.0% faster").
pub fn faster_or_slower(speedup: Option<f64>) -> String {
    match speedup {
        Some(v) if v < 0.0 => format!("{:.1}% slower", -100.0 * v),
        Some(v) => format!("{:.1}% faster", 100.0 * v),
        None => "- faster".into(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn relations_respect_the_tolerance() {
        assert_eq!(relation(0.10, 0.05, 0.005), Relation::Above);
        assert_eq!(relation(0.05, 0.10, 0.005), Relation::Below);
        assert_eq!(relation(0.052, 0.05, 0.005), Relation::Same);
    }

    #[test]
    fn numbers_print_changes_with_a_sign_and_shares_without() {
        assert_eq!(pct(Some(0.063)), "+6.3%");
        assert_eq!(share(Some(0.063)), "6.3%");
        assert_eq!(pct(None), "-");
        assert_eq!(lead_text(Some(-2.25)), "2.2 positions behind");
        assert_eq!(lead_text(Some(3.0)), "3.0 positions ahead of");
        assert_eq!(faster_or_slower(Some(-0.04)), "4.0% slower");
    }

    #[test]
    fn the_paper_is_named_where_the_data_disagrees() {
        assert_eq!(
            speedup_against_paper(-0.02, 0.039),
            "a slowdown, where the paper measures a gain of +3.9%"
        );
        assert_eq!(
            speedup_against_paper(0.01, 0.039),
            "below the paper's +3.9%"
        );
        assert_eq!(
            change_against_paper("latency", 0.03, -0.09, CHANGE_TOL),
            "latency rises (+3.0%), where the paper's falls (-9.0%)"
        );
        assert_eq!(
            change_against_paper("latency", -0.05, -0.09, CHANGE_TOL),
            "latency falls (-5.0%), as in the paper (-9.0%)"
        );
    }
}
