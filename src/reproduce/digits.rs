//! Numbers printed side by side without hiding their order: a set of
//! changes (fractions) prints with one decimal of a percent, and with more
//! (up to three) where one decimal would print two different values the
//! same or reverse their order; values still equal at three decimals print
//! as tied. Only the report's comparisons use it, so the rest of the report
//! keeps its one decimal.

/// Most decimals of a percent printed.
const MAX_DECIMALS: usize = 3;

/// `v` (a fraction) as a signed percent with `d` decimals.
fn signed(v: f64, d: usize) -> String {
    format!("{:+.*}%", d, 100.0 * v)
}

/// Whether `d` decimals print every pair of `values` in their true order:
/// different values differently, the larger above.
fn keeps_order(values: &[f64], d: usize) -> bool {
    let scale = 10f64.powi(d as i32 + 2);
    let round = |v: f64| (v * scale).round();
    values.iter().enumerate().all(|(i, &a)| {
        values[i + 1..].iter().all(|&b| {
            if a == b {
                return true;
            }
            let (ra, rb) = (round(a), round(b));
            (a < b && ra < rb) || (a > b && ra > rb)
        })
    })
}

/// The fewest decimals (1 to 3) that keep the order of `values`.
pub fn decimals(values: &[f64]) -> usize {
    (1..=MAX_DECIMALS)
        .find(|&d| keeps_order(values, d))
        .unwrap_or(MAX_DECIMALS)
}

/// The values (fractions; `None` prints `-`) as signed percents, with as
/// many decimals as keep their order ([`decimals`]); a value that prints
/// the same as a different one at three decimals says `(tied)`.
pub fn distinct_pcts(values: &[Option<f64>]) -> Vec<String> {
    let known: Vec<f64> = values.iter().flatten().copied().collect();
    let d = decimals(&known);
    values
        .iter()
        .map(|v| match v {
            None => "-".into(),
            Some(x) => {
                let text = signed(*x, d);
                let tied = known.iter().any(|&y| y != *x && signed(y, d) == text);
                if tied {
                    format!("{text} (tied)")
                } else {
                    text
                }
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_decimal_unless_it_would_hide_the_order() {
        // Apart at one decimal: one decimal.
        assert_eq!(
            distinct_pcts(&[Some(0.021), Some(-0.001)]),
            ["+2.1%", "-0.1%"]
        );
        // 0.84% and 0.76% both print +0.8% at one decimal.
        assert_eq!(
            distinct_pcts(&[Some(0.0084), Some(0.0076), None]),
            ["+0.84%", "+0.76%", "-"]
        );
        // Equal values print equal; no tie is claimed between them.
        assert_eq!(distinct_pcts(&[Some(0.01), Some(0.01)]), ["+1.0%", "+1.0%"]);
        // Different beyond three decimals: tied.
        let t = distinct_pcts(&[Some(0.012_340_1), Some(0.012_340_2)]);
        assert_eq!(t, ["+1.234% (tied)", "+1.234% (tied)"]);
    }

    #[test]
    fn rounding_never_reverses_an_order() {
        // 0.0149 rounds to 1.5 and 0.0151 to 1.5: two decimals.
        assert_eq!(decimals(&[0.0149, 0.0151]), 2);
        assert_eq!(decimals(&[0.0149, 0.0251]), 1);
    }
}
