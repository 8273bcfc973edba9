//! Runs the tasks of a study in parallel: each scene is rendered once per
//! draw order and tile size, and its trace shared by every task on it
//! (load once, run many), finished
//! points are stored as they end and skipped on the next run, progress is
//! shown, and the run ends with its wall time and points per second.
//!
//! Tasks are ordered by scene, and the workers take them in that order, so
//! at most about one scene per worker is held in memory; a scene's frame
//! is dropped as soon as its last task ends.

use super::cache::{Cache, PointRecord};
use super::point::{binary_id, hash_parts, point_key, scene_identity, Point, Resolver};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::collections::{BTreeMap, HashMap};
use std::io::IsTerminal;
use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Instant;
use wasp_frontend::characterize::{characterize, Characterization};
use wasp_frontend::def::{self, Route, SceneDef};
use wasp_frontend::raster::{rasterize_timed, DrawOrder, Frame, RasterOptions};
use wasp_frontend::texture::FormatChoice;
use wasp_frontend::{fetch, load};
use wasp_sim::config::{MachineConfig, TextureCache};
use wasp_sim::run::{simulate, simulate_timeline, RunOptions};

/// One piece of work on a scene.
#[derive(Clone, Debug, PartialEq)]
pub enum Task {
    /// Simulate a point and store its statistics.
    Run(Point),
    /// Characterise the scene (Table I figures, footprint ratio of every
    /// subset) at the tile size of the base configuration `config`.
    Characterize {
        /// Scene name.
        scene: String,
        /// Base configuration name (its `gpu.tile_size` is the tile).
        config: String,
        /// The textures' format (`None`: the scene definition's); a
        /// characterisation in a named format goes to
        /// [`Outcome::scenes_as`].
        format: Option<FormatChoice>,
    },
    /// Draw the timeline of cycles `from..=to` of a point to `out` (.png
    /// or .svg); skipped if `out` exists and `out.key` names the point's
    /// key.
    Timeline {
        /// The run.
        point: Point,
        /// First cycle.
        from: u64,
        /// Last cycle.
        to: u64,
        /// The picture.
        out: PathBuf,
    },
}

impl Task {
    fn scene(&self) -> &str {
        match self {
            Task::Run(p) | Task::Timeline { point: p, .. } => &p.scene,
            Task::Characterize { scene, .. } => scene,
        }
    }
}

/// How to run.
#[derive(Clone, Debug)]
pub struct RunnerOptions {
    /// Simulations at once.
    pub jobs: usize,
    /// No progress output.
    pub quiet: bool,
    /// Fetch a game's data when a scene needs it and it is missing (else:
    /// an error naming `wasp scenes fetch`).
    pub fetch: bool,
    /// The progress bar's label.
    pub label: String,
    /// Scene definitions known before the scenes folder is searched (e.g.
    /// files named on the command line); tasks name them by `name`.
    pub scenes: Vec<SceneDef>,
}

/// What a study's run produced.
#[derive(Debug, Default)]
pub struct Outcome {
    /// Every point's result (cached or run).
    pub points: HashMap<Point, PointRecord>,
    /// Every characterised scene (in its definition's texture format).
    pub scenes: BTreeMap<String, Characterization>,
    /// Every scene characterised with its textures in a named format
    /// (`Task::Characterize` with a `format`).
    pub scenes_as: BTreeMap<(String, FormatChoice), Characterization>,
    /// Tasks that failed, with why.
    pub failures: Vec<String>,
    /// Tasks run now.
    pub ran: usize,
    /// Tasks whose result was stored already.
    pub cached: usize,
    /// Tasks on the same machine as an earlier task of the run (sharing its
    /// result).
    pub same: usize,
    /// Wall seconds.
    pub seconds: f64,
    /// Points on the same machine as an earlier point of the run, with the
    /// key whose result they take when the run is over.
    sharing: Vec<(Point, String)>,
}

impl Outcome {
    /// The result of `p`, if it ran.
    pub fn get(&self, p: &Point) -> Option<&PointRecord> {
        self.points.get(p)
    }

    /// Keep characterisation `c` of a task characterising in `format`.
    fn put_scene(&mut self, format: Option<FormatChoice>, c: Characterization) {
        match format {
            Some(f) => self.scenes_as.insert((c.scene.clone(), f), c),
            None => self.scenes.insert(c.scene.clone(), c),
        };
    }

    /// The closing line: tasks, wall time and points per second.
    pub fn summary(&self) -> String {
        let rate = if self.seconds > 0.0 {
            self.ran as f64 / self.seconds
        } else {
            0.0
        };
        format!(
            "{} tasks ({} run, {} already done{}{}) in {:.1} s wall, {:.2} tasks/s",
            self.ran + self.cached + self.same,
            self.ran,
            self.cached,
            if self.same == 0 {
                String::new()
            } else {
                format!(", {} the same as another", self.same)
            },
            if self.failures.is_empty() {
                String::new()
            } else {
                format!(", {} failed", self.failures.len())
            },
            self.seconds,
            rate
        )
    }
}

/// A task ready to run: its key, effective configuration and the scene
/// as it renders it (its draw order applied).
pub(super) struct Ready {
    task: Task,
    key: String,
    cfg: MachineConfig,
    def: SceneDef,
}

/// The scene a group of tasks shares.
struct Group {
    def: SceneDef,
    tile: u32,
    /// The trace lists decoded texture lines (`memory.texture_cache =
    /// "decompressed"`).
    decoded: bool,
    frame: Mutex<Option<Result<Arc<Frame>, String>>>,
    remaining: AtomicUsize,
}

/// Scene definitions by name, read once.
#[derive(Default)]
pub struct Scenes {
    defs: HashMap<String, SceneDef>,
}

impl Scenes {
    /// A lookup that knows `defs` before the scenes folder.
    pub fn with(defs: &[SceneDef]) -> Scenes {
        Scenes {
            defs: defs.iter().map(|d| (d.name.clone(), d.clone())).collect(),
        }
    }

    /// The definition of `name` (`wasp scenes list`).
    pub fn def(&mut self, name: &str) -> Result<&SceneDef, String> {
        if !self.defs.contains_key(name) {
            let d = def::lookup(name).map_err(|e| e.to_string())?;
            self.defs.insert(name.to_string(), d);
        }
        Ok(&self.defs[name])
    }
}

/// Run `tasks` with the results stored in `cache`.
pub fn run(tasks: &[Task], cache: &Cache, opts: &RunnerOptions) -> Result<Outcome, String> {
    let start = Instant::now();
    let mut scenes = Scenes::with(&opts.scenes);
    // The games' data first: a scene's identity (and so every key) holds
    // the versions of the packages its data came from, known once fetched;
    // likewise an engine scene's capture.
    fetch_games(tasks, &mut scenes, opts)?;
    let uncaptured = capture_engines(tasks, &mut scenes, opts)?;
    let (mut out, mut todo) = resolve(tasks, cache, &mut scenes, &uncaptured)?;
    if !opts.quiet {
        // The counts the progress and the closing line use, tied together.
        eprintln!(
            "wasp: {}: {} tasks: {} to run, {} already done, {} the same as another",
            opts.label,
            tasks.len(),
            todo.len(),
            out.cached,
            out.same
        );
    }
    // Group by scene, draw order, texture format, tile size and the
    // lines the trace lists, in scene order.
    let group_key = |r: &Ready| {
        (
            r.def.name.clone(),
            r.def.draw_order,
            r.def.texture_format,
            r.cfg.gpu.tile_size,
            decoded_lines(&r.cfg),
        )
    };
    todo.sort_by_key(group_key);
    let (groups, group_of) = group_by_scene(&todo);
    let results = execute(&todo, &groups, &group_of, cache, opts);
    for (i, r) in results {
        match r {
            Ok(Done::Point(rec)) => {
                if let Task::Run(p) = &todo[i].task {
                    out.points.insert(p.clone(), *rec);
                }
            }
            Ok(Done::Scene(c)) => {
                if let Task::Characterize { format, .. } = &todo[i].task {
                    out.put_scene(*format, *c);
                }
            }
            Ok(Done::Drawn) => {}
            Err(e) => out
                .failures
                .push(format!("{}: {e}", describe(&todo[i].task))),
        }
        out.ran += 1;
    }
    share_results(&mut out);
    out.seconds = start.elapsed().as_secs_f64();
    Ok(out)
}

/// Fetch the data of every game the tasks' scenes need and the cache
/// lacks (or, without `opts.fetch`, name the command that fetches it).
fn fetch_games(tasks: &[Task], scenes: &mut Scenes, opts: &RunnerOptions) -> Result<(), String> {
    let mut games = Vec::new();
    for t in tasks {
        let d = scenes.def(t.scene())?;
        // An engine scene's frame comes from its capture, not the data.
        if d.route == Route::Loader {
            games.push(d.game);
        }
    }
    games.sort_by_key(|g| g.name());
    games.dedup();
    games.retain(|g| !fetch::is_fetched(*g));
    if let Some(g) = games.first().filter(|_| !opts.fetch) {
        return Err(format!(
            "the {} data is not fetched: run `wasp scenes fetch {}`",
            g.name(),
            g.name()
        ));
    }
    crate::game_data::fetch_missing(&games, opts.quiet)
        .map_err(|e| format!("{e} (its scenes need it; name the other scenes to leave them out)"))
}

/// The capture of every engine scene the tasks name, made now where the
/// scene cache lacks it (unless `opts.fetch` is off): the scenes that have
/// none, with why. Their tasks fail; the others run.
pub(super) fn capture_engines(
    tasks: &[Task],
    scenes: &mut Scenes,
    opts: &RunnerOptions,
) -> Result<HashMap<String, String>, String> {
    let mut why = HashMap::new();
    let mut seen = std::collections::HashSet::new();
    for t in tasks {
        if !seen.insert(t.scene().to_string()) {
            continue;
        }
        let d = scenes.def(t.scene())?;
        if d.route == Route::Engine {
            if let Err(e) = crate::engine_frame::capture(d, opts.fetch, opts.quiet) {
                why.insert(d.name.clone(), e);
            }
        }
    }
    Ok(why)
}

/// Resolve every task to its key, effective configuration and scene as it
/// renders it (bad scenes and overrides fail here, before any run) and
/// take the stored results: the outcome so far and the tasks left to run.
/// A task on a scene of `uncaptured` (an engine scene without a capture)
/// fails with its reason.
pub(super) fn resolve(
    tasks: &[Task],
    cache: &Cache,
    scenes: &mut Scenes,
    uncaptured: &HashMap<String, String>,
) -> Result<(Outcome, Vec<Ready>), String> {
    let mut out = Outcome::default();
    let mut resolver = Resolver::default();
    let mut ids: HashMap<(String, DrawOrder, FormatChoice), String> = HashMap::new();
    let mut todo: Vec<Ready> = Vec::new();
    let mut seen: std::collections::HashSet<String> = std::collections::HashSet::new();
    for t in tasks {
        if let Some(e) = uncaptured.get(t.scene()) {
            out.failures.push(format!("{}: {e}", describe(t)));
            continue;
        }
        let d = scenes.def(t.scene())?.clone();
        let d = match t {
            Task::Run(p) | Task::Timeline { point: p, .. } => p.scene_def(&d),
            Task::Characterize { format, .. } => SceneDef {
                texture_format: format.unwrap_or(d.texture_format),
                ..d
            },
        };
        let id = ids
            .entry((d.name.clone(), d.draw_order, d.texture_format))
            .or_insert_with(|| scene_identity(&d))
            .clone();
        let (key, cfg) = task_key(t, &d, &id, &mut resolver)?;
        // A task on the same machine as an earlier one (the same key and
        // kind) shares its result; a characterisation in a named format
        // runs apart from the scene's own (the same work when the scene's
        // format is that one), so that each finds its place in the outcome.
        let id = match t {
            Task::Timeline { out, .. } => format!("timeline {key} {}", out.display()),
            Task::Run(_) => format!("run {key}"),
            Task::Characterize { format, .. } => format!("scene {key} {format:?}"),
        };
        if !seen.insert(id) {
            out.same += 1;
            if let Task::Run(p) = t {
                // Filled in from the first one's result at the end.
                out.sharing.push((p.clone(), key.clone()));
            }
            continue;
        }
        if take_stored(t, &key, cache, &mut out) {
            out.cached += 1;
        } else {
            todo.push(Ready {
                task: t.clone(),
                key,
                cfg,
                def: d,
            });
        }
    }
    Ok((out, todo))
}

/// The cache key and effective configuration of a task on the scene `d`
/// of identity `id`.
fn task_key(
    t: &Task,
    d: &SceneDef,
    id: &str,
    resolver: &mut Resolver,
) -> Result<(String, MachineConfig), String> {
    match t {
        Task::Run(p) | Task::Timeline { point: p, .. } => {
            let cfg = resolver
                .config(p)
                .map_err(|e| format!("{}: {e}", p.describe()))?;
            Ok((point_key(binary_id(), id, &cfg), cfg))
        }
        Task::Characterize { config, .. } => {
            let cfg = resolver
                .config(&Point::new(&d.name, config, &[]))
                .map_err(|e| format!("{config}: {e}"))?;
            let tile = cfg.gpu.tile_size.to_string();
            let key = hash_parts(&[
                b"wasp-scene-1",
                binary_id().as_bytes(),
                id.as_bytes(),
                tile.as_bytes(),
            ]);
            Ok((key, cfg))
        }
    }
}

/// Put the stored result of `t` (key `key`) into `out`; whether there was
/// one.
fn take_stored(t: &Task, key: &str, cache: &Cache, out: &mut Outcome) -> bool {
    match t {
        Task::Run(p) => match cache.load_point(&p.scene, key) {
            Some(r) => {
                out.points.insert(p.clone(), r);
                true
            }
            None => false,
        },
        Task::Characterize { scene, format, .. } => match cache.load_scene(scene, key) {
            Some(c) => {
                out.put_scene(*format, c);
                true
            }
            None => false,
        },
        Task::Timeline { out: path, .. } => {
            path.is_file() && std::fs::read_to_string(key_file(path)).is_ok_and(|k| k.trim() == key)
        }
    }
}

/// Whether a machine's trace lists decoded texture lines: its texture
/// caches hold decompressed texels.
fn decoded_lines(cfg: &MachineConfig) -> bool {
    cfg.memory.texture_cache == TextureCache::Decompressed
}

/// The tasks (sorted by scene, draw order, texture format, tile size and
/// the lines the trace lists) grouped by them:
/// the groups and each task's group.
fn group_by_scene(todo: &[Ready]) -> (Vec<Group>, Vec<usize>) {
    let mut groups: Vec<Group> = Vec::new();
    let mut group_of = Vec::with_capacity(todo.len());
    for r in todo {
        let tile = r.cfg.gpu.tile_size;
        let decoded = decoded_lines(&r.cfg);
        let same = groups.last().is_some_and(|g| {
            g.def.name == r.def.name
                && g.def.draw_order == r.def.draw_order
                && g.def.texture_format == r.def.texture_format
                && g.tile == tile
                && g.decoded == decoded
        });
        if !same {
            groups.push(Group {
                def: r.def.clone(),
                tile,
                decoded,
                frame: Mutex::new(None),
                remaining: AtomicUsize::new(0),
            });
        }
        let g = groups.len() - 1;
        groups[g].remaining.fetch_add(1, Ordering::Relaxed);
        group_of.push(g);
    }
    (groups, group_of)
}

/// Run the tasks on `opts.jobs` workers, each scene rendered once for its
/// group; every task's result by index, in task order.
fn execute(
    todo: &[Ready],
    groups: &[Group],
    group_of: &[usize],
    cache: &Cache,
    opts: &RunnerOptions,
) -> Vec<(usize, Result<Done, String>)> {
    let pb = progress(opts, todo.len());
    let done = Mutex::new(0usize);
    let results = crate::pool::run_indexed(todo.len(), opts.jobs, |i| {
        let g = &groups[group_of[i]];
        pb.set_message(g.def.name.clone());
        let frame = frame_of(g);
        let r = frame.and_then(|f| perform(&todo[i], &f, cache));
        if g.remaining.fetch_sub(1, Ordering::AcqRel) == 1 {
            *g.frame.lock().expect("lock") = None;
        }
        let mut d = done.lock().expect("lock");
        *d += 1;
        pb.set_position(*d as u64);
        pb.tick_line(*d, todo.len());
        r
    });
    pb.finish();
    results.into_iter().enumerate().collect()
}

/// Fill in the points that named a machine another point ran under
/// another name (and drop those whose twin failed).
fn share_results(out: &mut Outcome) {
    let by_key: HashMap<String, PointRecord> = out
        .points
        .values()
        .map(|r| (r.key.clone(), r.clone()))
        .collect();
    for (p, key) in std::mem::take(&mut out.sharing) {
        if out.points.contains_key(&p) {
            continue;
        }
        if let Some(x) = by_key.get(&key) {
            let r = PointRecord {
                point: p.clone(),
                ..x.clone()
            };
            out.points.insert(p, r);
        }
    }
}

fn describe(t: &Task) -> String {
    match t {
        Task::Run(p) => p.describe(),
        Task::Characterize {
            scene,
            config,
            format,
        } => match format {
            Some(f) => format!("characterising {scene} ({config}, textures {f})"),
            None => format!("characterising {scene} ({config})"),
        },
        Task::Timeline { point, out, .. } => {
            format!("timeline {} of {}", out.display(), point.describe())
        }
    }
}

/// `PICTURE.key` beside a timeline picture: the key of the run it shows,
/// so that a picture of another build or machine is drawn again.
fn key_file(picture: &std::path::Path) -> PathBuf {
    let mut s = picture.as_os_str().to_owned();
    s.push(".key");
    PathBuf::from(s)
}

/// What a task produced.
enum Done {
    Point(Box<PointRecord>),
    Scene(Box<Characterization>),
    Drawn,
}

/// The group's frame, rendered by the first worker that needs it.
fn frame_of(g: &Group) -> Result<Arc<Frame>, String> {
    let mut slot = g.frame.lock().expect("lock");
    if slot.is_none() {
        *slot = Some(render(&g.def, g.tile, g.decoded).map(Arc::new));
    }
    slot.as_ref().expect("set").clone()
}

/// The scene's frame as `wasp render SCENE --trace-out` makes it, in the
/// definition's draw order and texture format, listing decoded texture
/// lines when `decoded` (`--texture-cache decompressed`; the trace does
/// not depend on the colour pass, which is skipped).
///
/// An engine-route scene's frame is its capture's last complete frame,
/// imported as `wasp import-gl` imports it ([`crate::engine_frame`]).
pub fn render(d: &SceneDef, tile: u32, decoded: bool) -> Result<Frame, String> {
    let opts = RasterOptions {
        tile,
        colour: false,
        threads: 1,
        draw_order: d.draw_order,
        texture_format: d.texture_format,
        decoded_lines: decoded,
        ..RasterOptions::default()
    };
    if d.route == Route::Engine {
        return crate::engine_frame::frame(d, &opts).map(|(f, _)| f);
    }
    let scene = load::load_scene(d).map_err(|e| e.to_string())?;
    rasterize_timed(&scene, d.width, d.height, &opts)
        .map(|(f, _)| f)
        .map_err(|e| e.to_string())
}

fn perform(r: &Ready, frame: &Frame, cache: &Cache) -> Result<Done, String> {
    match &r.task {
        Task::Run(p) => {
            let stats = simulate(&r.cfg, &frame.trace, &RunOptions::default(), &mut |_, _| {})
                .map_err(|e| e.to_string())?;
            let rec = PointRecord::new(r.key.clone(), p.clone(), &stats);
            cache.store_point(&rec)?;
            Ok(Done::Point(Box::new(rec)))
        }
        Task::Characterize { scene, .. } => {
            let c = characterize(scene, frame, 0.0);
            cache.store_scene(&r.key, &c)?;
            Ok(Done::Scene(Box::new(c)))
        }
        Task::Timeline { from, to, out, .. } => {
            let opts = RunOptions {
                timeline: Some((*from, *to)),
                ..RunOptions::default()
            };
            let (_, tl) = simulate_timeline(&r.cfg, &frame.trace, &opts, &mut |_, _| {})
                .map_err(|e| e.to_string())?;
            crate::timeline_plot::draw(&tl, out)?;
            super::cache::write_atomic(&key_file(out), &format!("{}\n", r.key))?;
            Ok(Done::Drawn)
        }
    }
}

/// Progress: a bar on a terminal; otherwise a line at every tenth.
struct Progress {
    bar: ProgressBar,
    lines: bool,
    label: String,
    start: Instant,
}

impl Progress {
    fn set_message(&self, m: String) {
        self.bar.set_message(m);
    }
    fn set_position(&self, n: u64) {
        self.bar.set_position(n);
    }
    fn tick_line(&self, done: usize, total: usize) {
        if self.lines && (done * 10 / total) != ((done - 1) * 10 / total) {
            eprintln!(
                "wasp: {}: {done}/{total} tasks to run, {:.0} s",
                self.label,
                self.start.elapsed().as_secs_f64()
            );
        }
    }
    fn finish(&self) {
        self.bar.finish_and_clear();
    }
}

fn progress(opts: &RunnerOptions, total: usize) -> Progress {
    let tty = std::io::stderr().is_terminal();
    let bar = if opts.quiet || !tty || total == 0 {
        ProgressBar::hidden()
    } else {
        let pb = ProgressBar::with_draw_target(Some(total as u64), ProgressDrawTarget::stderr());
        pb.set_style(
            ProgressStyle::with_template(
                "{prefix:>12} [{bar:40}] {pos}/{len} tasks to run {elapsed_precise} eta {eta} {msg}",
            )
            .expect("valid template")
            .progress_chars("=> "),
        );
        pb.set_prefix(opts.label.clone());
        pb.enable_steady_tick(std::time::Duration::from_millis(250));
        pb
    };
    Progress {
        bar,
        lines: !opts.quiet && !tty && total > 0,
        label: opts.label.clone(),
        start: Instant::now(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A cache in `dir` and runner options for a 256x128 procedural plane
    /// named `test-small-plane`.
    fn small_plane(dir: &std::path::Path) -> (Cache, SceneDef, RunnerOptions) {
        let cache = Cache::open(dir).unwrap();
        let mut plane = def::lookup("procedural-plane").unwrap();
        plane.name = "test-small-plane".into();
        (plane.width, plane.height) = (256, 128);
        let opts = RunnerOptions {
            jobs: 2,
            quiet: true,
            fetch: false,
            label: "test".into(),
            scenes: vec![plane.clone()],
        };
        (cache, plane, opts)
    }

    #[test]
    fn a_point_runs_on_the_scene_rendered_in_its_draw_order() {
        let dir = std::env::temp_dir().join(format!("wasp-runner-order-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let (cache, plane, opts) = small_plane(&dir);
        let loaded = Point::new("test-small-plane", "paper", &[]);
        let sorted = loaded.drawn(DrawOrder::FrontToBackObject);
        let same = loaded.drawn(DrawOrder::AsLoaded);
        let tasks = [
            Task::Run(loaded.clone()),
            Task::Run(sorted.clone()),
            Task::Run(same.clone()),
        ];
        let out = run(&tasks, &cache, &opts).unwrap();
        assert!(out.failures.is_empty(), "{:?}", out.failures);
        assert_eq!((out.ran, out.same), (2, 1));
        let (a, b, c) = (
            &out.points[&loaded],
            &out.points[&sorted],
            &out.points[&same],
        );
        assert_ne!(a.key, b.key);
        assert_eq!(a.key, c.key, "the scene's own order is the same scene");
        // The sorted trace shades fewer warps (the ground is drawn after
        // the blocks on it): the run saw another trace.
        let warps = |r: &PointRecord| r.stats.warps as f64;
        assert!(warps(b) < warps(a), "{} vs {}", warps(b), warps(a));
        // Its frame is the one `render` makes in that order.
        let f = render(&sorted.scene_def(&plane), 64, false).unwrap();
        assert_eq!(f.stats.draw_order, DrawOrder::FrontToBackObject);
        assert_eq!(f.trace.quad_count() as f64, warps(b));
        // Stored under its key: a second run takes both from the folder.
        let again = run(&tasks, &cache, &opts).unwrap();
        assert_eq!((again.ran, again.cached), (0, 2));
        assert_eq!(again.points[&sorted], *b);
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_decompressed_texture_cache_runs_on_the_decoded_lines() {
        let dir = std::env::temp_dir().join(format!("wasp-runner-texcache-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let (cache, _, opts) = small_plane(&dir);
        // The scene's own format is the etc2 rule.
        let etc2 = Point::new("test-small-plane", "paper", &[]);
        let rgba8 = etc2.stored(FormatChoice::Rgba8);
        let decoded = etc2.set(
            "memory.texture_cache",
            &wasp_sim::config::TextureCache::Decompressed,
        );
        let tasks = [
            Task::Run(rgba8.clone()),
            Task::Run(etc2.clone()),
            Task::Run(decoded.clone()),
        ];
        let out = run(&tasks, &cache, &opts).unwrap();
        assert!(out.failures.is_empty(), "{:?}", out.failures);
        assert_eq!(out.ran, 3);
        let get = |p: &Point| &out.points[p].stats;
        // The L1s see the RGBA8 lines; the DRAM sees the compressed ones.
        assert_eq!(get(&decoded).cf, get(&rgba8).cf);
        assert_eq!(get(&decoded).warps, get(&rgba8).warps);
        assert!(get(&etc2).cf < get(&rgba8).cf);
        assert!(get(&decoded).dram.requests < get(&rgba8).dram.requests);
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn an_engine_scene_without_a_capture_fails_its_tasks_alone() {
        let dir = std::env::temp_dir().join(format!("wasp-runner-engine-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let (cache, _, mut opts) = small_plane(&dir);
        let mut engine = def::lookup("oa-dm1-spawn0-engine").unwrap();
        engine.name = format!("test-uncaptured-{}-engine", std::process::id());
        opts.scenes.push(engine.clone());
        let plane = Point::new("test-small-plane", "paper", &[]);
        let tasks = [
            Task::Characterize {
                scene: engine.name.clone(),
                config: "paper".into(),
                format: None,
            },
            Task::Run(Point::new(&engine.name, "paper", &[])),
            Task::Run(plane.clone()),
        ];
        // No capture and no capturing (`fetch` off): the engine scene's two
        // tasks fail, naming the command; the loader scene's point runs.
        let out = run(&tasks, &cache, &opts).unwrap();
        assert_eq!(out.failures.len(), 2, "{:?}", out.failures);
        for f in &out.failures {
            assert!(f.contains(&engine.name), "{f}");
            assert!(f.contains("wasp scenes capture"), "{f}");
        }
        assert!(out.points.contains_key(&plane));
        assert!(out.scenes.is_empty());
        let _ = std::fs::remove_dir_all(&dir);
    }
}
