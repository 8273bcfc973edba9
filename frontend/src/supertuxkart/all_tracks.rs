//! Every track of the fetched game data loads (ignored unless asked
//! for).

use super::*;
use crate::def::Game;

/// Every track of the fetched package with `start:0`: reports each
/// and fails on any load error.
#[test]
#[ignore = "needs fetched game data: wasp scenes fetch supertuxkart"]
fn every_track_loads() {
    let Some(root) = super::tests::real_root() else {
        return;
    };
    let mut fails = Vec::new();
    for m in &tracks(&root).unwrap() {
        let d = SceneDef {
            name: m.clone(),
            ..crate::def::test_def(Game::Supertuxkart, m, "start:0", 1960, 768)
        };
        let t = std::time::Instant::now();
        match load(&root, &d) {
            Ok(s) => {
                // Cutscene cameras look at their stage from outside it.
                let track_xml =
                    std::fs::read_to_string(root.join("tracks").join(m).join("track.xml"))
                        .unwrap_or_default();
                let cutscene = track_xml.contains("cutscene");
                super::tests::check_real(&s, 1_000, !cutscene);
                eprintln!(
                    "OK {m}: {} meshes {} {:?}",
                    s.meshes.len(),
                    s.source.split("SA; ").nth(1).unwrap_or(""),
                    t.elapsed()
                );
            }
            Err(e) => {
                eprintln!("FAIL {m}: {e}");
                fails.push(format!("{m}: {e}"));
            }
        }
    }
    eprintln!("{} failures: {fails:?}", fails.len());
    assert!(fails.is_empty(), "{fails:#?}");
}
