//! The results of a study on disk: one JSON file per finished point (and
//! per characterised scene), written atomically, so that a killed run
//! loses only the points it was running and the next run skips the rest.
//!
//! Layout under the study's folder:
//!
//! - `points/SCENE.KEY.json`: a [`PointRecord`] (the point, its key and the
//!   run's statistics without the per-tile records);
//! - `scenes/SCENE.KEY.json`: a scene's [`Characterization`].

use super::point::Point;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use wasp_frontend::characterize::Characterization;
use wasp_sim::stats::RunStats;

/// The result of one point.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PointRecord {
    /// The cache key ([`super::point::point_key`]).
    pub key: String,
    /// The point.
    pub point: Point,
    /// The `wasp` binary that ran it ([`super::point::binary_id`]).
    #[serde(default)]
    pub binary: String,
    /// The run's statistics (`wasp run --json`) as the file holds them:
    /// without `per_tile` (empty here) and the input queue (0 here), which
    /// the file leaves out.
    #[serde(serialize_with = "serialize_stored")]
    pub stats: RunStats,
}

impl PointRecord {
    /// The record of `point` run to `stats`.
    pub fn new(key: String, point: Point, stats: &RunStats) -> PointRecord {
        PointRecord {
            key,
            point,
            binary: super::point::binary_id().to_string(),
            stats: RunStats {
                per_tile: Vec::new(),
                input_queue: 0,
                ..stats.clone()
            },
        }
    }

    /// Simulated cycles.
    pub fn cycles(&self) -> f64 {
        self.stats.cycles as f64
    }

    /// The statistics as the record's file writes them: the JSON of
    /// `wasp run --json`, its keys in alphabetical order, without
    /// `per_tile`. For output only (results files, CSV columns).
    pub fn stats_json(&self) -> serde_json::Value {
        stored_json(&self.stats)
    }

    /// The statistics flattened to `wasp run --csv`'s column names and
    /// values, in the order of [`stats_json`](Self::stats_json).
    pub fn flat_stats(&self) -> Vec<(String, String)> {
        let mut v = Vec::new();
        wasp_sim::stats::flatten("", &self.stats_json(), &mut v);
        v
    }
}

/// `stats` as a stored record holds it (see [`PointRecord::stats_json`]).
fn stored_json(stats: &RunStats) -> serde_json::Value {
    let mut v = serde_json::to_value(stats).expect("statistics serialize");
    if let Some(m) = v.as_object_mut() {
        m.remove("per_tile");
    }
    v
}

fn serialize_stored<S: serde::Serializer>(stats: &RunStats, ser: S) -> Result<S::Ok, S::Error> {
    stored_json(stats).serialize(ser)
}

/// A study's folder of finished points and characterised scenes.
#[derive(Clone, Debug)]
pub struct Cache {
    dir: PathBuf,
}

impl Cache {
    /// Open (creating) the folder `dir`.
    pub fn open(dir: &Path) -> Result<Cache, String> {
        for sub in ["points", "scenes"] {
            let d = dir.join(sub);
            std::fs::create_dir_all(&d)
                .map_err(|e| format!("cannot create {}: {e}", d.display()))?;
        }
        Ok(Cache {
            dir: dir.to_path_buf(),
        })
    }

    /// The folder `dir` read as it is, creating nothing (a folder that
    /// does not exist holds no results): for counting without a run.
    pub fn read_only(dir: &Path) -> Cache {
        Cache {
            dir: dir.to_path_buf(),
        }
    }

    fn point_path(&self, scene: &str, key: &str) -> PathBuf {
        self.dir.join("points").join(format!("{scene}.{key}.json"))
    }

    fn scene_path(&self, scene: &str, key: &str) -> PathBuf {
        self.dir.join("scenes").join(format!("{scene}.{key}.json"))
    }

    /// The stored result of the point with `key`, if any. A file that does
    /// not parse (not written by this program: writes are atomic) counts as
    /// absent and is run again.
    pub fn load_point(&self, scene: &str, key: &str) -> Option<PointRecord> {
        let text = std::fs::read_to_string(self.point_path(scene, key)).ok()?;
        let r: PointRecord = serde_json::from_str(&text).ok()?;
        (r.key == key).then_some(r)
    }

    /// Store a point's result.
    pub fn store_point(&self, r: &PointRecord) -> Result<(), String> {
        let text = serde_json::to_string_pretty(r).expect("records serialize") + "\n";
        write_atomic(&self.point_path(&r.point.scene, &r.key), &text)
    }

    /// The stored characterisation of a scene with `key`, if any.
    pub fn load_scene(&self, scene: &str, key: &str) -> Option<Characterization> {
        let text = std::fs::read_to_string(self.scene_path(scene, key)).ok()?;
        serde_json::from_str(&text).ok()
    }

    /// Store a scene's characterisation.
    pub fn store_scene(&self, key: &str, c: &Characterization) -> Result<(), String> {
        let text = serde_json::to_string_pretty(c).expect("characterisations serialize") + "\n";
        write_atomic(&self.scene_path(&c.scene, key), &text)
    }
}

/// Every point record in the `points/` folders of `dirs` (each a study
/// folder or a `points/` folder itself), sorted by scene and key; files
/// that are not records are named in the error.
pub fn read_points(dirs: &[PathBuf]) -> Result<Vec<PointRecord>, String> {
    let mut out = Vec::new();
    for d in dirs {
        let pd = if d.join("points").is_dir() {
            d.join("points")
        } else {
            d.clone()
        };
        let rd =
            std::fs::read_dir(&pd).map_err(|e| format!("cannot list {}: {e}", pd.display()))?;
        let mut files: Vec<PathBuf> = rd
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.extension().is_some_and(|x| x == "json"))
            .collect();
        files.sort();
        for f in files {
            let text = std::fs::read_to_string(&f)
                .map_err(|e| format!("cannot read {}: {e}", f.display()))?;
            let r: PointRecord = serde_json::from_str(&text)
                .map_err(|e| format!("{}: not a point record: {e}", f.display()))?;
            out.push(r);
        }
    }
    out.sort_by(|a, b| (&a.point.scene, &a.key).cmp(&(&b.point.scene, &b.key)));
    Ok(out)
}

/// Write `text` to `path` through a temporary file in the same folder and
/// a rename, so that a reader never sees half a file.
pub fn write_atomic(path: &Path, text: &str) -> Result<(), String> {
    crate::output::write_atomic(path, text.as_bytes())
        .map_err(|e| format!("cannot write {}: {e}", path.display()))
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use std::sync::OnceLock;

    /// The statistics of the tiny trace on the shipped machine (run once),
    /// for tests that need a whole [`RunStats`] to change a few fields of.
    pub(crate) fn sample_stats() -> RunStats {
        static STATS: OnceLock<RunStats> = OnceLock::new();
        STATS
            .get_or_init(|| {
                let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/traces/tiny.trace");
                let trace = wasp_sim::trace::Trace::read(path).unwrap();
                let mut cfg = wasp_sim::config::MachineConfig::paper();
                cfg.gpu.tile_size = trace.header().tile;
                let opts = wasp_sim::run::RunOptions::default();
                wasp_sim::run::simulate(&cfg, &trace, &opts, &mut |_, _| {}).unwrap()
            })
            .clone()
    }

    /// [`sample_stats`] as a record holds them, with `cycles`.
    pub(crate) fn stats_of(cycles: u64) -> RunStats {
        let s = PointRecord::new(
            String::new(),
            Point::new("s", "paper", &[]),
            &sample_stats(),
        )
        .stats;
        RunStats { cycles, ..s }
    }

    fn temp(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("wasp-cache-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        d
    }

    #[test]
    fn points_round_trip_and_foreign_files_count_as_absent() {
        let d = temp("round");
        let c = Cache::open(&d).unwrap();
        let r = PointRecord {
            key: "00000000000000aa".into(),
            point: Point::new(
                "sc",
                "paper",
                &[wasp_sim::config::Override::new("l0.mshrs", &8)],
            ),
            binary: "b".into(),
            stats: stats_of(1234),
        };
        assert_eq!(c.load_point("sc", &r.key), None);
        c.store_point(&r).unwrap();
        let back = c.load_point("sc", &r.key).unwrap();
        assert_eq!(back, r);
        assert_eq!(back.cycles(), 1234.0);
        // The file holds the statistics without the tiles, keys sorted.
        let text = std::fs::read_to_string(c.point_path("sc", &r.key)).unwrap();
        assert!(!text.contains("per_tile"));
        let at = |k: &str| text.find(&format!("\"{k}\": ")).unwrap();
        assert!(at("avg_warps_per_core") < at("cycles") && at("cycles") < at("workload"));
        // So does a record made from a run's statistics.
        let full = sample_stats();
        assert!(!full.per_tile.is_empty());
        let made = PointRecord::new(r.key.clone(), r.point.clone(), &full);
        assert!(made.stats.per_tile.is_empty());
        assert_eq!(made.stats_json(), stored_json(&full));
        // A truncated file (as from another program) is not a result.
        std::fs::write(c.point_path("sc", &r.key), "{\"key\":").unwrap();
        assert_eq!(c.load_point("sc", &r.key), None);
        let e = read_points(std::slice::from_ref(&d)).unwrap_err();
        assert!(e.contains("not a point record"), "{e}");
        let _ = std::fs::remove_dir_all(&d);
    }

    #[test]
    fn a_stored_record_reads_back_and_writes_the_same_file() {
        // A record the build before typed statistics wrote (with a
        // prefetcher, a texture format and a subset the baseline leaves
        // unused).
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/tests/golden/text/point-record.json"
        );
        let text = std::fs::read_to_string(path).unwrap();
        let r: PointRecord = serde_json::from_str(&text).unwrap();
        assert!(r.stats.prefetch.is_some() && !r.stats.subset.subset.used);
        assert_eq!(serde_json::to_string_pretty(&r).unwrap() + "\n", text);
    }

    #[test]
    fn read_points_takes_study_folders_and_points_folders() {
        let d = temp("read");
        let c = Cache::open(&d).unwrap();
        for (scene, key) in [("b", "02"), ("a", "01")] {
            c.store_point(&PointRecord {
                key: key.into(),
                point: Point::new(scene, "paper", &[]),
                binary: "b".into(),
                stats: stats_of(1),
            })
            .unwrap();
        }
        let all = read_points(std::slice::from_ref(&d)).unwrap();
        assert_eq!(
            all.iter()
                .map(|r| r.point.scene.as_str())
                .collect::<Vec<_>>(),
            ["a", "b"]
        );
        assert_eq!(read_points(&[d.join("points")]).unwrap(), all);
        let _ = std::fs::remove_dir_all(&d);
    }
}
