//! The driveline (`quads.xml`, `graph.xml`): the main line from the start,
//! and points along it for the `driveline:F` camera.

use super::*;

/// A driveline quad: p0 p1 is the entry edge, p3 p2 the exit edge.
pub(super) type Quad = [Vec3; 4];

pub(super) fn parse_quads(text: &str, file: &Path) -> Result<Vec<Quad>, SceneError> {
    let doc = parse_xml(text, file)?;
    let mut quads: Vec<Quad> = Vec::new();
    for q in doc.descendants().filter(|n| n.has_tag_name("quad")) {
        let mut pts = [[0.0f32; 3]; 4];
        for (k, p) in pts.iter_mut().enumerate() {
            let attr = format!("p{k}");
            let at = q.range().start as u64;
            let s = q
                .attribute(attr.as_str())
                .ok_or_else(|| SceneError::at(file, at, format!("<quad> without {attr}")))?;
            *p = if let Some((qi, pi)) = s.split_once(':') {
                let (qi, pi) = (qi.trim().parse::<usize>(), pi.trim().parse::<usize>());
                match (qi, pi) {
                    (Ok(qi), Ok(pi)) if qi < quads.len() && pi < 4 => quads[qi][pi],
                    _ => {
                        return Err(SceneError::at(
                            file,
                            at,
                            format!("<quad> {attr}=\"{s}\": bad reference to an earlier quad"),
                        ))
                    }
                }
            } else {
                vec3_attr(q, &attr, file)?.unwrap_or_default()
            };
        }
        quads.push(pts);
    }
    Ok(quads)
}

/// Successor lists of the drive graph (nodes = quads, in order).
pub(super) fn parse_graph(
    text: &str,
    file: &Path,
    n: usize,
) -> Result<Vec<Vec<usize>>, SceneError> {
    let doc = parse_xml(text, file)?;
    let mut succ = vec![Vec::new(); n];
    let mut edge = |a: usize, b: usize, at: usize| -> Result<(), SceneError> {
        if a >= n || b >= n {
            return Err(SceneError::at(
                file,
                at as u64,
                format!("edge {a} -> {b}: node out of range ({n} quads)"),
            ));
        }
        succ[a].push(b);
        Ok(())
    };
    for e in doc.root_element().children().filter(|c| c.is_element()) {
        let at = e.range().start;
        let from = f32_attr(e, "from", file)?.map(|v| v as usize);
        let to = f32_attr(e, "to", file)?.map(|v| v as usize);
        let (Some(from), Some(to)) = (from, to) else {
            continue;
        };
        match tag(e) {
            "edge" => edge(from, to, at)?,
            "edge-line" | "edge-loop" => {
                for i in from..to.min(n) {
                    edge(i, i + 1, at)?;
                }
                if tag(e) == "edge-loop" {
                    edge(to, from, at)?;
                }
            }
            _ => {}
        }
    }
    Ok(succ)
}

/// The main driveline from node 0 following first successors, as
/// (centre of entry edge, centre of exit edge) segments.
pub(super) fn main_line(quads: &[Quad], succ: &[Vec<usize>]) -> Vec<(Vec3, Vec3)> {
    let mut seen = vec![false; quads.len()];
    let mut out = Vec::new();
    let mut node = 0usize;
    while node < quads.len() && !seen[node] {
        seen[node] = true;
        let q = &quads[node];
        out.push((scale(add(q[0], q[1]), 0.5), scale(add(q[2], q[3]), 0.5)));
        match succ.get(node).and_then(|s| s.first()) {
            Some(&s) => node = s,
            None => break,
        }
    }
    out
}

/// The point at `dist` along the line (may be negative: before the start,
/// measured backwards from the line's end, the loop closing on the start)
/// and the direction of travel there.
pub(super) fn along(line: &[(Vec3, Vec3)], dist: f32) -> (Vec3, Vec3) {
    let total: f32 = line.iter().map(|(a, b)| len(sub(*b, *a))).sum();
    let mut d = if total > 0.0 {
        dist.rem_euclid(total)
    } else {
        0.0
    };
    for (a, b) in line {
        let l = len(sub(*b, *a));
        if d <= l {
            let dir = normalize(sub(*b, *a));
            return (add(*a, scale(dir, d)), dir);
        }
        d -= l;
    }
    let (a, b) = line[line.len() - 1];
    (b, normalize(sub(b, a)))
}

pub(super) fn line_length(line: &[(Vec3, Vec3)]) -> f32 {
    line.iter().map(|(a, b)| len(sub(*b, *a))).sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn driveline_quads_and_graph() {
        let q = r#"<quads><quad p0="0 0 0" p1="2 0 0" p2="2 0 10" p3="0 0 10"/>
            <quad p0="0:3" p1="0:2" p2="2 0 20" p3="0 0 20"/></quads>"#;
        let quads = parse_quads(q, Path::new("quads.xml")).unwrap();
        assert_eq!(quads[1][0], [0.0, 0.0, 10.0]);
        assert_eq!(quads[1][1], [2.0, 0.0, 10.0]);
        let g =
            r#"<graph><node-list from-quad="0" to-quad="1"/><edge-loop from="0" to="1"/></graph>"#;
        let succ = parse_graph(g, Path::new("graph.xml"), 2).unwrap();
        assert_eq!(succ, vec![vec![1], vec![0]]);
        let line = main_line(&quads, &succ);
        assert_eq!(line.len(), 2);
        assert_eq!(line_length(&line), 20.0);
        let (p, d) = along(&line, 15.0);
        assert_eq!((p, d), ([1.0, 0.0, 15.0], [0.0, 0.0, 1.0]));
        // Behind the start: wraps onto the end of the loop.
        let (p, _) = along(&line, -2.0);
        assert_eq!(p, [1.0, 0.0, 18.0]);
        let bad = r#"<quads><quad p0="5:3" p1="0 0 0" p2="0 0 0" p3="0 0 0"/></quads>"#;
        let e = parse_quads(bad, Path::new("quads.xml")).unwrap_err();
        assert_eq!(e.offset, Some(7));
        let e = parse_graph(
            "<graph><edge from=\"0\" to=\"7\"/></graph>",
            Path::new("g.xml"),
            2,
        )
        .unwrap_err();
        assert!(e.message.contains("out of range"));
        let e = parse_quads("<quads><quad", Path::new("q.xml")).unwrap_err();
        assert!(e.offset.is_some() && e.message.contains("XML"), "{e}");
    }
}
