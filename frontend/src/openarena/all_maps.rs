//! Every map of the fetched game data loads (ignored unless asked for).

use super::*;
use crate::def::Game;

/// Every map of the fetched packages with `spawn:0`: reports each and
/// fails on any load error.
#[test]
#[ignore = "needs fetched game data: wasp scenes fetch openarena"]
fn every_map_loads() {
    let Some(root) = super::tests::real_root() else {
        return;
    };
    let mut fails = Vec::new();
    let all = maps(&root).unwrap();
    assert!(all.len() >= 40, "{all:?}");
    for m in &all {
        let d = SceneDef {
            name: m.clone(),
            ..crate::def::test_def(Game::Openarena, m, "spawn:0", 1960, 768)
        };
        let t = std::time::Instant::now();
        match load(&root, &d) {
            Ok(s) => {
                super::tests::check_real(&s, 500);
                eprintln!(
                    "OK {m}: {} {:.2?}",
                    s.source.split("GPL; ").nth(1).unwrap_or(""),
                    t.elapsed()
                );
            }
            Err(e) => {
                eprintln!("FAIL {m}: {e}");
                fails.push(format!("{m}: {e}"));
            }
        }
    }
    eprintln!("{} maps, {} failures", all.len(), fails.len());
    assert!(fails.is_empty(), "{fails:#?}");
}
